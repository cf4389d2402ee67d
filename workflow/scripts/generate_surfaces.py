"""Write the seeded rough surfaces of one study to results/surfaces/{study}.nc."""

import json
import sys

from contactlib import studies

from contactlib.pipeline import sweep

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821 (snakemake object)
spec = snakemake.params.spec  # noqa: F821
ds = studies.study_surfaces(spec["name"], spec["constants"], spec["grid"])
ds.attrs.update(sweep.provenance({
    "title": f"Rough surfaces of the {spec['name']} study",
    "source": "contactlib.studies.study_surfaces",
    "config": json.dumps(spec, sort_keys=True),
}))
sweep.write_netcdf(ds, snakemake.output[0], sweep_dims=studies.STUDIES[spec["name"]]["surface_keys"])  # noqa: F821
print(f"wrote {snakemake.output[0]}: {dict(ds.sizes)}", file=sys.stderr)  # noqa: F821
