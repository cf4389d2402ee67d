"""Figure: contact area against load of one measured surface (results/measured_area_load/{surface}.nc, its surface)."""

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import xarray as xr  # noqa: E402

from contactlib.studies import PERSSON_KAPPA, PUBLISHED_KAPPA_RANGE  # noqa: E402

sm = snakemake  # noqa: F821
sys.stderr = open(sm.log[0], "w")
ds = xr.open_dataset(sm.input.data)
ok = ds.where(ds.status == 0)
h = xr.open_dataset(sm.input.surface).height
fig, axes = plt.subplots(1, 2, figsize=(10, 4.2), layout="constrained")
p = ds.reduced_pressure
axes[0].plot(p, ok.contact_area, "o-", label="contactlib")
axes[0].plot(p, PERSSON_KAPPA * p, "k:", label="Persson sqrt(8/pi)")
for kappa in PUBLISHED_KAPPA_RANGE:
    axes[0].plot(p, kappa * p, color="0.7", lw=0.8)
axes[0].set(xlabel=f"{p.long_name} [{p.units}]", ylabel=f"{ds.contact_area.long_name} [1]",
            title=f"{int((ds.status != 0).sum())} failed points; grey: kappa 1.8 and 2.2")
axes[0].legend(fontsize=7)
if h.ndim == 2:
    h.plot.imshow(ax=axes[1], x="x", y="y", cmap="viridis", cbar_kwargs={"label": f"{h.long_name} [{h.units}]"})
    axes[1].set(aspect="equal")
else:
    h.plot(ax=axes[1])
axes[1].set(title=f"{h.source_file} ({h.source_format}, sha256 {h.source_sha256[:12]}), detrend {h.detrend}, "
                  f"fill {h.fill}, {'periodic' if h.periodic else 'non-periodic'}")
axes[1].title.set_fontsize(7)
fig.suptitle(f"{ds.attrs['title']} ({ds.attrs['scale']} scale)", fontsize=9)
fig.savefig(sm.output[0], dpi=120)
print(ds[["contact_area", "kappa", "status"]].to_dataframe(), file=sys.stderr)
