"""Table: cheapest setting per target error and scene, and the convergence orders (results/speed_vs_error.nc)."""

import sys

import xarray as xr

from contactlib import analysis

sm = snakemake  # noqa: F821
sys.stderr = open(sm.log[0], "w")
ds = xr.open_dataset(sm.input.data)
rows = analysis.cheapest_settings(ds, sm.params.targets)
orders = analysis.convergence_orders(ds).to_dataframe().dropna().reset_index()
lines = [f"# {ds.attrs['title']}", "",
         f"{ds.attrs['scale']} scale, contactlib {ds.attrs['contactlib_version']} ({ds.attrs['git_revision']}), "
         f"{ds.attrs['date_created']}. Error = {ds.max_error.long_name}; time = {ds.solve_time.long_name}.", "",
         analysis.markdown_table(rows), "## Convergence orders (error = C resolution^-p, smallest tol)", "",
         "| scene | kernel | quantity | order p | constant C |", "|---|---|---|---|---|"]
lines += [f"| {r.scene} | {r.kernel} | {r.quantity} | {r.order:.2f} | {r.constant:.3g} |" for r in orders.itertuples()]
lines += ["", f"Tolerance gain max |error(tol) - error(min tol)| / tol = {analysis.tolerance_gain(ds):.3g}", ""]
with open(sm.output[0], "w") as f:
    f.write("\n".join(lines))
