"""Figure: error against wall time (Pareto front) and against resolution, per scene (results/speed_vs_error.nc)."""

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402

from contactlib import analysis  # noqa: E402

sm = snakemake  # noqa: F821
sys.stderr = open(sm.log[0], "w")
ds = xr.open_dataset(sm.input.data)
ok = ds.where(ds.status == 0)
orders = analysis.convergence_orders(ds)
scenes = ds.scene.values
fig, axes = plt.subplots(2, len(scenes), figsize=(4.2 * len(scenes), 8), layout="constrained", squeeze=False)
marks = dict(zip(orders.quantity.values, "osD^"))
floor = 1e-16  # round-off: exact scenes (spectral kernel on one mode) are drawn on it
for ax, ax2, scene in zip(axes[0], axes[1], scenes):
    d = ok.sel(scene=scene)
    t, e = d.solve_time.values, np.maximum(d.max_error.values, floor)
    for k, kernel in enumerate(ds.kernel.values):
        sel = d.sel(kernel=kernel)
        ax.loglog(sel.solve_time.values.ravel(), np.maximum(sel.max_error.values.ravel(), floor), "o", ms=3,
                  color=f"C{k}", alpha=0.6, label=kernel)
    front = analysis.pareto_front(t, e)
    order = np.argsort(t[front])
    ax.loglog(t[front][order], e[front][order], "k.-", lw=1, ms=6, label="Pareto front")
    ax.set(xlabel=f"{ds.solve_time.long_name} [{ds.solve_time.units}]", ylabel=f"{ds.max_error.long_name} [1]",
           title=str(scene))
    ax.yaxis.label.set_size(7)
    best = d.sel(tol=ds.tol.min())
    for k, kernel in enumerate(ds.kernel.values):
        for q in orders.quantity.values:
            err = best[q].sel(kernel=kernel)
            if np.isnan(err).all():
                continue
            p = float(orders.order.sel(scene=scene, kernel=kernel, quantity=q))
            ax2.loglog(best.resolution.sel(kernel=kernel), np.maximum(err, floor), marker=marks[q], color=f"C{k}",
                       ms=4, ls="-" if kernel == "spectral" else "--",
                       label=f"{q.removesuffix('_error')}, {kernel}: order {p:.2f}" if np.isfinite(p)
                       else f"{q.removesuffix('_error')}, {kernel}: round-off")
    ax2.set(xlabel=f"{ds.resolution.long_name.split(' (')[0]} [1]", ylabel="relative error [1]",
            title=f"{scene}, tol = {float(ds.tol.min()):.0e}")
    ax2.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    for a in (ax, ax2):
        a.legend(fontsize=6)
fig.suptitle(f"{ds.attrs['title']} ({ds.attrs['scale']} scale; wall times noisy, shared machine). Bottom: "
             "per contact radius (hertz), half-width (westergaard_1d), wavelength (wavy_2d), "
             "shortest wavelength (rough)",
             fontsize=8)
fig.savefig(sm.output[0], dpi=120)
print(orders.order.to_dataframe().dropna().to_string(), file=sys.stderr)
