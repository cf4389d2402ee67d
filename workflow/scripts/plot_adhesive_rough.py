"""Figure: adhesive rough contact, area-load paths and pull-off against rms slope and work of adhesion
(results/adhesive_rough.nc)."""

import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import xarray as xr  # noqa: E402

sm = snakemake  # noqa: F821
sys.stderr = open(sm.log[0], "w")
raw = xr.open_dataset(sm.input.data)
ds = raw.where((raw.status == 0) & (raw.converged == 1))
p, a = ds.reduced_mean_pressure, ds.contact_area


def label(v):
    return f"{v.long_name} [{v.units}]"


fig, axes = plt.subplots(1, 2, figsize=(12, 4.5), layout="constrained")
colour = 0
for g in ds.rms_slope.values:
    for w in ds.work.values:
        for branch, style in (("loading", "-"), ("unloading", "--")):
            if branch in ds.branch.values:
                pm = p.sel(rms_slope=g, work=w, branch=branch).mean("seed")
                am = a.sel(rms_slope=g, work=w, branch=branch).mean("seed")
                axes[0].plot(pm, am, style, marker="o", ms=3, color=f"C{colour}",
                             label=f"g = {g:g}, w = {w:g}" if branch == "loading" else None)
        colour += 1
pull = ds.reduced_pull_off_pressure.max(["penetration_over_rms", "branch"])  # one value per path
for w in ds.work.values:
    sel = pull.sel(work=w)
    axes[1].errorbar(ds.rms_slope, sel.mean("seed"), yerr=sel.std("seed"), marker="o", capsize=3,
                     label=f"w = {w:g} Pa m")
axes[0].axvline(0.0, color="k", lw=0.6, ls=":")
axes[0].set(xlabel=label(p), ylabel=label(a), yscale="log", title="area against load (mean over seeds)")
axes[1].set(xlabel=label(ds.rms_slope), ylabel=label(ds.reduced_pull_off_pressure),
            title="pull-off (mean, std over seeds)")
for ax in axes:
    ax.legend(fontsize=7)
constants = json.loads(ds.attrs["config"])["study"]["constants"]
fig.suptitle(f"{ds.attrs['title']}\n({ds.attrs['scale']} scale, {constants['n']}^2, {ds.sizes['seed']} seeds; solid: "
             "loading, dashed: unloading)", fontsize=9)
fig.savefig(sm.output[0], dpi=120)
print(pull.mean("seed").to_pandas().to_string(float_format="%.4f"), file=sys.stderr)
print(f"failed or unconverged points: {int(((raw.status != 0) | (raw.converged != 1)).sum())}", file=sys.stderr)
