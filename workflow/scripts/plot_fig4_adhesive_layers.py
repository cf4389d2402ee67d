"""Figure: seed 1 Fig. 4, adhesive wavy profile on confined and remote-pressure layers
(results/fig4_adhesive_layers.nc)."""

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import xarray as xr  # noqa: E402

sm = snakemake  # noqa: F821
sys.stderr = open(sm.log[0], "w")
ds = xr.open_dataset(sm.input.data).where(lambda d: d.status == 0)
d, p = ds.scaled_penetration, ds.scaled_mean_pressure


def label(v):
    return f"{v.long_name} [{v.units}]"


fig, axes = plt.subplots(1, ds.sizes["layer_base"], figsize=(12, 4.5), layout="constrained", squeeze=False)
for ax, base in zip(axes[0], ds.layer_base.values):
    for t in ds.scaled_layer_thickness.values:
        sel = p.sel(layer_base=base, scaled_layer_thickness=t)
        (line,) = ax.plot(d, sel.sel(branch="loading"), lw=1.2, label=f"q0 h = {t:g}")
        if "unloading" in ds.branch.values:
            ax.plot(d, sel.sel(branch="unloading"), lw=1.2, ls="--", color=line.get_color())
        one = ds.sel(layer_base=base, scaled_layer_thickness=t).max(["scaled_penetration", "branch"])
        pull, at = float(one.scaled_load_pull_off_pressure), float(one.scaled_load_pull_off_penetration)
        ax.plot([at], [pull], "o", color=line.get_color(), ms=5)
        print(f"{base} q0 h = {t:g}: load-control pull-off {pull:+.4f} at {at:+.2f}, most tensile "
              f"{float(one.scaled_pull_off_pressure):+.4f}, jump to full contact {int(one.jump_to_full_contact)}",
              file=sys.stderr)
    ax.axhline(0.0, color="k", lw=0.6, ls=":")
    ax.set(xlabel=label(d), ylabel=label(p), title=f"({'ab'[list(ds.layer_base.values).index(base)]}) {base}")
    ax.legend(fontsize=7)
fig.suptitle(f"{ds.attrs['title']} ({ds.attrs['scale']} scale)\nsolid: loading, dashed: unloading, "
             "dots: pull-off under load control (none: beyond the path)", fontsize=9)
fig.savefig(sm.output[0], dpi=120)
