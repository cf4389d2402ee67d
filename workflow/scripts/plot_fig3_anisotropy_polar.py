"""Figure: polar plots of m2(theta) of the rigid surface and mu2(theta) of the deformed surface sliding on a
viscoelastic half-space, over seeds (seed 2 Fig. 3; results/fig3_anisotropy_polar.nc)."""

import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402

sm = snakemake  # noqa: F821
sys.stderr = open(sm.log[0], "w")
ds = xr.open_dataset(sm.input.data).where(lambda d: d.status == 0)
theta = np.linspace(0, 2 * np.pi, 361)
fig, axes = plt.subplots(1, 2, figsize=(11, 5.2), subplot_kw={"projection": "polar"}, layout="constrained")
for ax, name, symbol in ((axes[0], "surface", "m2"), (axes[1], "displacement", "mu2")):
    for seed in ds.seed.values:
        d = ds.sel(seed=seed)
        xx, xy, yy = float(d[f"{name}_m_xx"]), float(d[f"{name}_m_xy"]), float(d[f"{name}_m_yy"])
        curve = xx * np.cos(theta) ** 2 + 2 * xy * np.sin(theta) * np.cos(theta) + yy * np.sin(theta) ** 2
        ax.plot(theta, curve / curve.max(), lw=1, label=f"seed {seed}")
    g, t = ds[f"{name}_gamma"], ds[f"{name}_theta_d"]
    ax.set_title(f"{symbol}(theta) / max, {ds[f'{name}_gamma'].long_name.split(' of the ')[1]}\n"
                 f"gamma = {float(g.mean()):.3f} +- {float(g.std()):.3f}, theta_d = "
                 f"{float(np.degrees(t.mean())):.1f} +- {float(np.degrees(t.std())):.1f} deg", fontsize=9)
axes[1].legend(fontsize=7, loc="lower right")
constants = json.loads(ds.attrs["config"])["study"]["constants"]
fig.suptitle(f"{ds.attrs['title']}\n({ds.attrs['scale']} scale, n = {constants['n']}, band "
             f"{constants['zeta1']} q0 < |q| < {constants['zeta2']} q0, sliding along +x (theta = 0); "
             f"seed 2 reports gamma_d = 0.37, theta_d = pi/2)", fontsize=9)
fig.savefig(sm.output[0], dpi=120)
for name in ("surface", "displacement"):
    print(f"{name}: gamma {ds[f'{name}_gamma'].values}, theta_d {ds[f'{name}_theta_d'].values}", file=sys.stderr)
