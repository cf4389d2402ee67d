"""Figure: hysteretic friction coefficient and contact area of a 2D rough surface against zeta = V tau q0,
for two E_inf / E0 (results/friction_speed.nc)."""

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
for ax, v in zip(axes, (ds.friction_coefficient_interlocking, ds.contact_area)):
    for ratio in ds.glassy_ratio.values:
        band(ax, ds.zeta, v.sel(glassy_ratio=ratio), label=f"E_inf / E0 = {ratio:g}")
    ax.set(xscale="log", xlabel=f"{ds.zeta.long_name} [1]", ylabel=f"{v.long_name} [{v.units}]")
    ax.legend(fontsize=8)
axes[0].set_title("hysteretic friction: the bell over speed")
axes[1].set(yscale="log", title="contact area: relaxed (slow) to glassy (fast)")
constants = json.loads(ds.attrs["config"])["study"]["constants"]
fig.suptitle(f"{ds.attrs['title']}\n({ds.attrs['scale']} scale, {constants['n']}^2, p = "
             f"{constants['reduced_pressure']:g} E0* g, {ds.sizes['seed']} seeds)", fontsize=9)
fig.savefig(sm.output[0], dpi=120)
print(ds.friction_coefficient_interlocking.mean("seed").to_pandas().to_string(float_format="%.4f"), file=sys.stderr)
print(f"failed points: {int((xr.open_dataset(sm.input.data).status != 0).sum())}", file=sys.stderr)
