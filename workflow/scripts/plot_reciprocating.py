"""Figure: hysteresis loops (friction coefficient along +x against position) at three frequencies around the
maximum of the energy dissipated per cycle, and that energy against frequency (results/reciprocating.nc)."""

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
constants = json.loads(ds.attrs["config"])["study"]["constants"]
energy = ds.dissipated_energy_per_cycle.mean("seed")
peak = int(np.nanargmax(energy.values))
around = sorted({max(peak - 1, 0), peak, min(peak + 1, ds.sizes["frequency"] - 1)})
fig, axes = plt.subplots(1, 2, figsize=(12, 4.5), layout="constrained")
for k in around:
    f = float(ds.frequency[k])
    loop = ds.isel(frequency=k, seed=0)
    x = np.append(loop.loop_position.values, loop.loop_position.values[:1])  # close the loop
    mu = np.append(loop.loop_friction.values, loop.loop_friction.values[:1])
    axes[0].plot(x, mu, label=f"f tau = {f * constants['tau']:g}" + (" (maximum)" if k == peak else ""))
axes[0].set(xlabel="position X / A [1]", ylabel="friction coefficient along +x [1]",
            title="hysteresis loops (seed 0, last cycle)")
axes[0].axhline(0, color="0.7", lw=0.5)
axes[0].legend(fontsize=8)
std = ds.dissipated_energy_per_cycle.std("seed")
(line,) = axes[1].plot(ds.frequency, energy, marker="o", label="energy dissipated (internal variables)")
axes[1].fill_between(ds.frequency, energy - std, energy + std, color=line.get_color(), alpha=0.2, lw=0)
axes[1].plot(ds.frequency, ds.friction_work_per_cycle.mean("seed"), ls="--", marker="x",
             label="loop area (tangential force work)")
unsettled = ds.settled.min("seed") < 1
if bool(unsettled.any()):
    axes[1].plot(ds.frequency[unsettled], energy[unsettled], "rs", mfc="none", ms=10, label="not settled")
axes[1].set(xscale="log", yscale="log", xlabel="frequency f [1/s]", ylabel="energy per cycle per unit area [Pa m]",
            title="energy per cycle against frequency")
axes[1].legend(fontsize=8)
fig.suptitle(f"{ds.attrs['title']}\n({ds.attrs['scale']} scale, {constants['n']}^2, A = {constants['amplitude']:g} m, "
             f"p = {constants['reduced_pressure']:g} E0* g, E_inf/E0 = {constants['glassy_ratio']:g}, "
             f"{ds.sizes['seed']} seeds)", fontsize=9)
fig.savefig(sm.output[0], dpi=120)
print(energy.to_pandas().to_string(float_format="%.4g"), file=sys.stderr)
print(f"failed points: {int((xr.open_dataset(sm.input.data).status != 0).sum())}", file=sys.stderr)
