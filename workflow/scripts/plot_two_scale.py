"""Figure: speed against error of the two-scale method, its macro step and the full FFT solver
(results/two_scale.nc)."""

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import xarray as xr  # noqa: E402

sm = snakemake  # noqa: F821
sys.stderr = open(sm.log[0], "w")
ds = xr.open_dataset(sm.input.data).where(lambda d: d.status == 0).mean("seed")
methods = {"full": ("full FFT solver", "k"), "two_scale": ("two-scale", "tab:blue"), "macro": ("macro step", "tab:red")}
markers = dict(zip(ds.coverage.values, "os^vDP"))
fig, axes = plt.subplots(1, 3, figsize=(14, 4.2), layout="constrained")
for name, (label, colour) in methods.items():
    err, t = ds[f"{name}_asperity_force_error"], ds[f"{name}_time"]
    for coverage in ds.coverage.values:
        e, w = err.sel(coverage=coverage), t.sel(coverage=coverage)
        axes[0].loglog(e, w, markers[coverage], color=colour, alpha=0.8,
                       label=f"{label}, coverage {coverage:g}" if name != "full" or coverage == ds.coverage[0] else None)
        axes[1].loglog(ds["count"], w, markers[coverage] + "-", color=colour, alpha=0.8)
axes[0].axvline(1e-2, color="gray", lw=0.8, ls=":")
axes[0].set(xlabel="asperity force error (max over asperities / largest force) [1]", ylabel="wall time [s]",
            title="speed against error (one marker per field)")
axes[1].set(xlabel=f"{ds['count'].long_name} [1]", ylabel="wall time [s]", title="wall time (markers: coverage)")
for name, style in (("two_scale_speedup", "tab:blue"), ("macro_speedup", "tab:red")):
    for coverage in ds.coverage.values:
        axes[2].loglog(ds["count"], ds[name].sel(coverage=coverage), markers[coverage] + "-", color=style,
                       label=f"{ds[name].long_name}, coverage {coverage:g}")
axes[2].axhline(1.0, color="k", lw=0.8)
axes[2].set(xlabel=f"{ds['count'].long_name} [1]", ylabel="speed-up over the full solver [1]",
            title="speed-up (>1: faster than the full solver)")
axes[0].legend(fontsize=6)
axes[2].legend(fontsize=6)
fig.suptitle(f"{ds.attrs['title']} ({ds.attrs['scale']} scale)", fontsize=9)
fig.savefig(sm.output[0], dpi=120)
