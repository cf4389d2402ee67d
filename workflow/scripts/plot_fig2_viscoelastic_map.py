"""Figure: pressure map of an isotropic rough surface sliding on a viscoelastic half-space, with a zoom on
one patch, beside the same surface at rest (seed 2 Fig. 2; results/fig2_viscoelastic_map.nc)."""

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import xarray as xr  # noqa: E402

sm = snakemake  # noqa: F821
sys.stderr = open(sm.log[0], "w")
ds = xr.open_dataset(sm.input.data).isel(seed=0)
p, rest = ds.pressure / 1e3, ds.pressure_at_rest / 1e3
fig, axes = plt.subplots(1, 3, figsize=(15, 4.8), layout="constrained")
vmax = float(p.quantile(0.995))
for ax, field, title in ((axes[0], rest, f"at rest (relaxed): contact {float(ds.contact_area_at_rest):.3f}"),
                         (axes[1], p, f"sliding along +x: contact {float(ds.contact_area):.3f}, "
                                      f"mu_a = {float(ds.friction_coefficient_interlocking):.4f}")):
    field.plot.imshow(ax=ax, x="x", y="y", cmap="magma", vmin=0, vmax=vmax, cbar_kwargs={"label": "pressure [kPa]"})
    ax.set_title(title, fontsize=9)
    ax.set_aspect("equal")
# zoom on the patch around the largest pressure of the sliding map
peak = p.argmax(dim=("x", "y"))  # by name: the fields are on (y, x)
i, j = int(peak["x"]), int(peak["y"])
half = max(6, p.sizes["x"] // 16)
window = p.isel(x=slice(max(0, i - half), i + half), y=slice(max(0, j - half), j + half))
window.plot.imshow(ax=axes[2], x="x", y="y", cmap="magma", vmin=0, vmax=vmax, cbar_kwargs={"label": "pressure [kPa]"})
rest_window = rest.isel(x=slice(max(0, i - half), i + half), y=slice(max(0, j - half), j + half))
axes[2].contour(rest_window.x, rest_window.y, (rest_window > 0).transpose("y", "x").astype(float), levels=[0.5],
                colors="c", linewidths=1)  # matplotlib's Z: one row per y
axes[2].annotate("", xy=(0.95, 0.05), xytext=(0.75, 0.05), xycoords="axes fraction",
                 arrowprops={"arrowstyle": "->", "color": "w"})
axes[2].set_title("zoom: sliding patch; cyan: outline at rest; arrow: V", fontsize=9)
axes[2].set_aspect("equal")
fig.suptitle(f"{ds.attrs['title']}\n({ds.attrs['scale']} scale, {p.sizes['x']}^2, V tau / lambda = "
             f"{float(ds.speed_ratio) if 'speed_ratio' in ds else 0.13:g})", fontsize=9)
fig.savefig(sm.output[0], dpi=120)
print(f"contact area sliding {float(ds.contact_area):.4f}, at rest {float(ds.contact_area_at_rest):.4f}, "
      f"mu_a {float(ds.friction_coefficient_interlocking):.5f}, status {int(ds.status)}", file=sys.stderr)
