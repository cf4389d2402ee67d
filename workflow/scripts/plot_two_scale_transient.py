"""Figure: creep of an asperity field by the two-scale method's time stepping, its macro step and the full
transient solver (results/two_scale_transient.nc)."""

import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import xarray as xr  # noqa: E402

sm = snakemake  # noqa: F821
sys.stderr = open(sm.log[0], "w")
raw = xr.open_dataset(sm.input.data)
ds = raw.where(lambda d: d.status == 0).mean("seed")
constants = json.loads(ds.attrs["config"])["study"]["constants"]
methods = {"full": ("full transient solver", "k"), "two_scale": ("two-scale", "tab:blue"),
           "macro": ("macro step", "tab:red")}
styles = dict(zip(ds["count"].values, ("-", "--", ":", "-.", (0, (1, 3)), (0, (5, 1)))))
fig, axes = plt.subplots(1, 3, figsize=(15, 4.5), layout="constrained")
for coverage in ds.coverage.values:
    for ratio in ds.glassy_ratio.values:
        point = ds.sel(coverage=coverage, glassy_ratio=ratio)
        for count in ds["count"].values:
            one = point.sel(count=count)
            start = one.reference_creep_penetration.isel(time=0)
            axes[0].plot(one.time, one.reference_creep_penetration / start, ls=styles[count], color="gray", lw=2.5,
                         alpha=0.5)
            for name, (label, colour) in methods.items():
                if name != "full":
                    axes[0].plot(one.time, one[f"{name}_creep_penetration"] / start, ls=styles[count], color=colour,
                                 lw=1)
                axes[1].semilogy(one.time, one[f"{name}_creep_force_error"], ls=styles[count], color=colour,
                                 label=f"{label}, N = {count}, coverage {coverage:g}, E_inf/E0 = {ratio:g}")
        for name, (label, colour) in methods.items():
            axes[2].loglog(point["count"], point[f"{name}_creep_time"], "o-", color=colour,
                           label=f"{label}, coverage {coverage:g}, E_inf/E0 = {ratio:g}")
axes[0].set(xlabel="time since the step [s]", ylabel="penetration / reference penetration at t = 0 [1]",
            title="creep: approach (grey: reference; blue: two-scale; red: macro)")
axes[1].axhline(1e-2, color="gray", lw=0.8, ls=":")
axes[1].set(xlabel="time since the step [s]", ylabel="largest asperity-force error / largest force [1]",
            title="per-step force error against the reference")
axes[1].legend(fontsize=6)
axes[2].set(xlabel=f"{ds['count'].long_name} [1]", ylabel="wall time of the whole history [s]",
            title="wall time (one run each after a warm-up)")
axes[2].legend(fontsize=7)
fig.suptitle(f"{ds.attrs['title']}\n({ds.attrs['scale']} scale, {constants['nodes_per_radius']:g} nodes per contact "
             f"radius, tau = {constants['tau']:g} s, {raw.sizes['seed']} seeds)", fontsize=9)
fig.savefig(sm.output[0], dpi=120)
print(ds[["two_scale_creep_speedup", "macro_creep_speedup"]].to_dataframe().to_string(float_format="%.3g"),
      file=sys.stderr)
print(f"failed points: {int((raw.status != 0).sum())}", file=sys.stderr)
