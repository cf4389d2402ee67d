"""Figure: contact area against load and the coefficient kappa (results/area_load.nc, results/surfaces/)."""

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402

from contactlib.studies import PERSSON_KAPPA, PUBLISHED_KAPPA_RANGE  # noqa: E402

sm = snakemake  # noqa: F821
sys.stderr = open(sm.log[0], "w")
ds = xr.open_dataset(sm.input.data).where(lambda d: d.status == 0)
fig, axes = plt.subplots(1, 3, figsize=(14, 4.2), layout="constrained")
p = ds.reduced_pressure
for i, hurst in enumerate(ds.hurst.values):
    for j, n in enumerate(ds.n.values):
        a = ds.contact_area.sel(hurst=hurst, n=n)
        axes[0].errorbar(p, a.mean("seed"), a.std("seed"), color=f"C{i}", ls=("--", "-")[j % 2], marker="o",
                         ms=3, label=f"H={hurst:g}, n={n}")
        k = ds.kappa.sel(hurst=hurst, n=n)
        axes[1].errorbar(hurst + 0.02 * (j - 0.5), k.mean(), k.std(), color=f"C{i}", marker="os"[j % 2],
                         capsize=3, label=f"H={hurst:g}, n={n}")
axes[0].plot(p, PERSSON_KAPPA * p, "k:", label="Persson sqrt(8/pi)")
axes[0].set(xlabel=f"{p.long_name} [{p.units}]", ylabel=f"{ds.contact_area.long_name} [1]",
            title="area against load (mean +- std over seeds)")
axes[1].axhline(PERSSON_KAPPA, color="k", ls=":", label="Persson sqrt(8/pi)")
axes[1].axhspan(*PUBLISHED_KAPPA_RANGE, color="0.85", label="published simulations")
axes[1].set(xlabel=f"{ds.hurst.long_name} [1]", ylabel=f"{ds.kappa.long_name} [1]",
            title="kappa: mean +- std over seeds and loads")
surf = xr.open_dataset(sm.input.surfaces).height
h = surf.isel(hurst=len(surf.hurst) // 2, seed=0)
h.plot.imshow(ax=axes[2], x="x", y="y", cmap="viridis", cbar_kwargs={"label": f"{surf.long_name} [{surf.units}]"})
axes[2].set(title=f"surface H={float(h.hurst):g}, seed 0, n={surf.sizes['x']}", aspect="equal")
for ax in axes[:2]:
    ax.legend(fontsize=7)
fig.suptitle(f"{ds.attrs['title']} ({ds.attrs['scale']} scale)", fontsize=9)
fig.savefig(sm.output[0], dpi=120)
print(ds.kappa.mean("seed").mean("reduced_pressure").to_pandas(), file=sys.stderr)
print(f"kappa overall: {float(ds.kappa.mean()):.3f} +- {float(ds.kappa.std()):.3f}", file=sys.stderr)
