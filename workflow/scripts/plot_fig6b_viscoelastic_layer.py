"""Figure: mu_a / g against zeta = V tau q0 on a thin confined viscoelastic layer, with and without Coulomb
friction (seed 2 Fig. 6b; results/fig6b_viscoelastic_layer.nc)."""

import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import xarray as xr  # noqa: E402
from seed_bands import band  # noqa: E402

sm = snakemake  # noqa: F821
sys.stderr = open(sm.log[0], "w")
ds = xr.open_dataset(sm.input.data).where(lambda d: d.status == 0)
fig, axes = plt.subplots(1, 2, figsize=(12, 4.5), layout="constrained")
for ax, v in zip(axes, (ds.interlocking_over_slope, ds.contact_area)):
    for mu in ds.friction.values:
        band(ax, ds.zeta, v.sel(friction=mu), label=f"mu_c = {mu:g}")
    ax.set(xscale="log", xlabel=f"{ds.zeta.long_name} [1]", ylabel=f"{v.long_name} [{v.units}]")
    ax.legend(fontsize=8)
axes[0].set_title("(b) with coupling mu_a stays > 0 at both ends")
constants = json.loads(ds.attrs["config"])["study"]["constants"]
fig.suptitle(f"{ds.attrs['title']}\n({ds.attrs['scale']} scale, n = {constants['n']}, q0 h = "
             f"{constants['scaled_layer_thickness']:g}, E_inf/E0 = {constants['glassy_ratio']:g}, "
             f"{ds.sizes['seed']} seeds)", fontsize=9)
fig.savefig(sm.output[0], dpi=120)
print(ds.interlocking_over_slope.mean("seed").to_pandas().to_string(float_format="%.4f"), file=sys.stderr)
print(f"failed points: {int((xr.open_dataset(sm.input.data).status != 0).sum())}", file=sys.stderr)
