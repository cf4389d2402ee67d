"""Figure: interlocking friction mu_a / (mu_c g) against load for several Poisson ratios on a thin
confined layer, seed 2 Fig. 6a (results/fig6a_interlocking.nc)."""

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
p = ds.scaled_pressure


def label(v):
    return f"{v.long_name} [{v.units}]"


fig, axes = plt.subplots(1, 2, figsize=(12, 4.5), layout="constrained")
for ax, v in zip(axes, (ds.interlocking_ratio, ds.contact_area)):
    for nu in ds.nu.values:
        band(ax, p, v.sel(nu=nu), label=f"nu = {nu:g}")
    ax.set(xscale="log", xlabel=label(p), ylabel=label(v))
    ax.legend(fontsize=7)
axes[0].axhline(0.0, color="k", lw=0.8, ls=":")
axes[0].set_title("(a) > 0: the pressure's asymmetry resists sliding")
axes[1].set_title("contact area with friction")
constants = json.loads(ds.attrs["config"])["study"]["constants"]
fig.suptitle(f"{ds.attrs['title']}\n({ds.attrs['scale']} scale, n = {constants['n']}, "
             f"q0 h = {constants['scaled_layer_thickness']:g}, mu_c = {constants['friction']:g}, "
             f"{ds.sizes['seed']} seeds; mean and std over seeds)", fontsize=9)
fig.savefig(sm.output[0], dpi=120)
print("mu_a / (mu_c g), mean over seeds:", file=sys.stderr)
print(ds.interlocking_ratio.mean("seed").to_pandas().to_string(float_format="%+.4f"), file=sys.stderr)
print(f"failed points: {int((xr.open_dataset(sm.input.data).status != 0).sum())}", file=sys.stderr)
