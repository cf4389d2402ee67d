"""Figure: anisotropy of the rigid surface against that of the contact pressure (results/anisotropy.nc)."""

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402

sm = snakemake  # noqa: F821
sys.stderr = open(sm.log[0], "w")
ds = xr.open_dataset(sm.input.data).where(lambda d: d.status == 0)
fig, axes = plt.subplots(1, 3, figsize=(14, 4.2), layout="constrained")
sg, pg = ds.surface_gamma, ds.pressure_gamma
axes[0].errorbar(sg.mean("seed"), pg.mean("seed"), pg.std("seed"), xerr=sg.std("seed"), fmt="o", capsize=3,
                 label="mean +- std over seeds")
axes[0].plot([0, 1], [0, 1], "k:", label="equal anisotropy")
axes[0].set(xlabel=f"{sg.long_name} [1]", ylabel=f"{pg.long_name} [1]", xlim=(0, 1.05), ylim=(0, 1.05))
aniso = ds.sel(anisotropy=ds.anisotropy[ds.anisotropy < 0.95])  # theta_d is undefined for an isotropic surface
for name, marker in (("surface_theta_d", "o"), ("pressure_theta_d", "s")):
    v = aniso[name]
    axes[1].errorbar(aniso.anisotropy, np.degrees(v.mean("seed")), np.degrees(v.std("seed")), fmt=marker,
                     capsize=3, label=v.long_name)
axes[1].set(xlabel=f"{ds.anisotropy.long_name} [1]", ylabel="theta_d [deg]", title="principal direction")
field = ds["pressure"] if "pressure" in ds else xr.open_dataset(sm.input.surfaces).height
f = field.isel(anisotropy=0, seed=0)  # the most anisotropic surface (coordinates sorted ascending)
f.plot.imshow(ax=axes[2], x="x", y="y", cmap="magma", cbar_kwargs={"label": f"{field.long_name} [{field.units}]"})
axes[2].set(title=f"{field.name}, gamma={float(f.anisotropy):g}, seed 0", aspect="equal")
for ax in axes[:2]:
    ax.legend(fontsize=7)
fig.suptitle(f"{ds.attrs['title']} ({ds.attrs['scale']} scale)", fontsize=9)
fig.savefig(sm.output[0], dpi=120)
