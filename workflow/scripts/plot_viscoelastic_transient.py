"""Figure: creep under a step load (contact area, penetration) and relaxation at a step penetration (mean
pressure, contact area) of a 2D rough contact, for several E_inf / E0, with the elastic E0 and E_inf levels
(results/viscoelastic_transient.nc)."""

import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402
from seed_bands import band  # noqa: E402

sm = snakemake  # noqa: F821
sys.stderr = open(sm.log[0], "w")
ds = xr.open_dataset(sm.input.data).where(lambda d: d.status == 0)
constants = json.loads(ds.attrs["config"])["study"]["constants"]
t = ds.time.where(ds.time > 0, drop=True)  # log axis: t = 0 (the glassy response) is the first marker
fig, axes = plt.subplots(1, 3, figsize=(15, 4.5), layout="constrained")
panels = ((axes[0], ds.creep_contact_area, ds.relaxed_contact_area, ds.glassy_contact_area),
          (axes[1], ds.creep_penetration, ds.relaxed_penetration, ds.glassy_penetration),
          (axes[2], ds.relaxation_mean_pressure / ds.step_mean_pressure, None, None))
for ax, v, relaxed, glassy in panels:
    for ratio in ds.glassy_ratio.values:
        line = band(ax, t, v.sel(glassy_ratio=ratio).sel(time=t), ms=2, label=f"E_inf / E0 = {ratio:g}")
        if relaxed is not None:
            for level, style in ((relaxed, "--"), (glassy, ":")):
                ax.axhline(float(level.sel(glassy_ratio=ratio).mean("seed")), color=line.get_color(), ls=style, lw=1)
        else:
            # the standard linear solid's E(t) / E0: the exact answer while the contact stays put
            ax.plot(t, 1 + (ratio - 1) * np.exp(-t / constants["tau"]), color=line.get_color(), ls="--", lw=1)
    ax.set(xscale="log", xlabel="time since the step [s]")
    ax.legend(fontsize=8)
axes[0].set(ylabel="contact area fraction [1]", title="creep: contact area (dashed E0, dotted E_inf)")
axes[1].set(ylabel="penetration [m]", title="creep: penetration (dashed E0, dotted E_inf)")
axes[2].set(yscale="log", ylabel="mean pressure / step load [1]",
            title="relaxation: p(t) and E(t) / E0 (dashed)")
fig.suptitle(f"{ds.attrs['title']}\n({ds.attrs['scale']} scale, {constants['n']}^2, p = "
             f"{constants['reduced_pressure']:g} E0* g, tau = {constants['tau']:g} s, {ds.sizes['seed']} seeds)",
             fontsize=9)
fig.savefig(sm.output[0], dpi=120)
print(ds.creep_contact_area.mean("seed").isel(time=[0, -1]).to_pandas().to_string(float_format="%.4f"), file=sys.stderr)
print(f"failed points: {int((xr.open_dataset(sm.input.data).status != 0).sum())}", file=sys.stderr)
