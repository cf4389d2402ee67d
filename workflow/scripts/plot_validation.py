"""Figure: Hertz sphere and Westergaard wavy contact, numerical against analytic (results/validation.nc)."""

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402

from contactlib.reference import westergaard  # noqa: E402

sm = snakemake  # noqa: F821
sys.stderr = open(sm.log[0], "w")
ds = xr.open_dataset(sm.input.data).where(lambda d: d.status == 0)
fig, axes = plt.subplots(1, 3, figsize=(13, 4), layout="constrained")
c = ds.contact_fraction
for n in ds.n.values:
    d = ds.sel(n=n)
    axes[0].plot(c, d.hertz_contact_radius / d.hertz_contact_radius_exact, "o-", label=f"a, n={n}")
    axes[0].plot(c, d.hertz_peak_pressure / d.hertz_peak_pressure_exact, "s--", label=f"p0, n={n}")
    p_ratio = np.sin(np.pi * d.westergaard_contact_fraction_exact / 2) ** 2
    axes[1].plot(p_ratio, d.westergaard_contact_fraction, "o", label=f"n={n}")
axes[0].axhline(1.0, color="k", lw=0.8)
axes[0].set(xlabel=f"{c.long_name} [{c.units}]", ylabel="numerical / analytic [1]",
            title="Hertz sphere, non-periodic")
p = np.linspace(0, 1, 200)
axes[1].plot(p, westergaard.contact_fraction(p, amplitude=1.0, wavelength=1.0, E_star=1 / np.pi), "k-",
             label="Westergaard (analytic)")
axes[1].set(xlabel="mean pressure / p* [1]", ylabel=f"{ds.westergaard_contact_fraction.long_name} [1]",
            title="Westergaard 1D partial contact")
err = ds.westergaard_pressure_error
for cf in c.values:
    axes[2].loglog(ds.n, err.sel(contact_fraction=cf), "o-", label=f"{c.name}={cf:g}")
axes[2].set_xticks(ds.n.values, [str(n) for n in ds.n.values], minor=False)
axes[2].xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
axes[2].set(xlabel=f"{ds.n.long_name} [1]", ylabel=f"{err.long_name} [{err.units}]",
            title="Westergaard pressure, refinement")
for ax in axes:
    ax.legend(fontsize=7)
fig.suptitle(f"{ds.attrs['title']} ({ds.attrs['scale']} scale)", fontsize=9)
fig.savefig(sm.output[0], dpi=120)
