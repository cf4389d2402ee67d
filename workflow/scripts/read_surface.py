"""Read one measured topography file (contactlib.surfaces.read) into results/surfaces/{study}/{surface}.nc."""

import json
import sys

from contactlib import surfaces

from contactlib.pipeline import sweep

sm = snakemake  # noqa: F821 (injected by Snakemake)
sys.stderr = open(sm.log[0], "w")
entry = dict(sm.params.surface)
options = {k: entry[k] for k in ("length", "unit", "periodic", "detrend", "fill", "format") if k in entry}
height = surfaces.read(sm.input[0], **options)
ds = height.to_dataset()
ds.attrs.update(sweep.provenance({"title": f"Measured surface {entry['name']!r}", "source": "contactlib.surfaces.read",
                                  "config": json.dumps(entry, sort_keys=True)}))
sweep.write_netcdf(ds, sm.output[0])
print(f"wrote {sm.output[0]}: {dict(ds.sizes)} from {sm.input[0]} (sha256 {height.attrs['source_sha256']})",
      file=sys.stderr)
