"""Figure: contact area with Coulomb friction over without on a thin confined layer, seed 2 Fig. 5
(results/fig5_friction_area.nc)."""

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
panels = sm.params.panels
ratio, a0, p, t = ds.area_ratio, ds.frictionless_contact_area, ds.scaled_pressure, ds.scaled_layer_thickness


def label(v):
    return f"{v.long_name} [{v.units}]"


thin = ratio.sel(scaled_layer_thickness=panels["scaled_layer_thickness"], method="nearest")
k = thin.sizes["scaled_layer_thickness"]  # panels: one (a) per thickness, (b), then a0
cols = (k + 3) // 2
fig, axes = plt.subplots(2, cols, figsize=(5.5 * cols, 8.5), layout="constrained", squeeze=False)
axes = axes.flat
for ax, h in zip(axes, thin.scaled_layer_thickness.values):
    for mu in ds.friction.values:
        band(ax, p, thin.sel(friction=mu, scaled_layer_thickness=h), label=f"mu_c = {mu:g}")
    ax.set(title=f"(a) against the load, q0 h = {h:g}", xlabel=label(p))
for mu in panels["friction"]:
    for load in panels["scaled_pressure"]:
        v = ratio.sel(friction=mu, scaled_pressure=load, method="nearest")
        band(axes[k], t, v, label=f"mu_c = {float(v.friction):g}, p~ = {float(v.scaled_pressure):g}")
axes[k].set(title="(b) against the layer thickness", xlabel=label(t))
for ax in axes[: k + 1]:
    ax.axhline(1.0, color="k", lw=0.8, ls=":")
    ax.set(xscale="log", ylabel=label(ratio))
for h in t.values:  # a0 does not depend on mu_c: every friction value solved it alike
    band(axes[k + 1], p, a0.sel(scaled_layer_thickness=h).isel(friction=0), label=f"q0 h = {h:g}")
axes[k + 1].set(xscale="log", xlabel=label(p), ylabel=label(a0), title="frictionless contact area")
for i, ax in enumerate(axes):
    ax.legend(fontsize=7) if i < k + 2 else ax.set_axis_off()
constants = json.loads(ds.attrs["config"])["study"]["constants"]
fig.suptitle(f"{ds.attrs['title']}\n({ds.attrs['scale']} scale, n = {constants['n']}, {ds.sizes['seed']} seeds; "
             "lines: mean over seeds, bands: one standard deviation)", fontsize=9)
fig.savefig(sm.output[0], dpi=120)
top = ratio.sel(friction=ds.friction.max())
print(f"a/a0 at mu_c = {float(ds.friction.max()):g}, mean and std over seeds:", file=sys.stderr)
print(top.mean("seed").to_pandas().to_string(float_format="%.4f"), file=sys.stderr)
print(top.std("seed").to_pandas().to_string(float_format="%.4f"), file=sys.stderr)
print(f"failed points: {int((xr.open_dataset(sm.input.data).status != 0).sum())}", file=sys.stderr)
