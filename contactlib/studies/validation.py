"""The ``validation`` study: a Hertz sphere and a Westergaard 1D wavy contact against their analytic
solutions, over grid size and target contact size."""

from __future__ import annotations

import math

import numpy as np

from .. import surfaces
from ..problems.contact import solve
from ..model.materials import contact_modulus
from ..reference import hertz, westergaard

VARIABLES: dict[str, dict[str, str]] = {
    "hertz_contact_radius": {"units": "m", "long_name": "Hertz sphere contact radius, numerical"},
    "hertz_contact_radius_exact": {"units": "m", "long_name": "Hertz sphere contact radius, analytic"},
    "hertz_penetration": {"units": "m", "long_name": "Hertz sphere approach, numerical"},
    "hertz_penetration_exact": {"units": "m", "long_name": "Hertz sphere approach, analytic"},
    "hertz_peak_pressure": {"units": "Pa", "long_name": "Hertz sphere peak pressure, numerical"},
    "hertz_peak_pressure_exact": {"units": "Pa", "long_name": "Hertz sphere peak pressure, analytic"},
    "westergaard_contact_fraction": {"units": "1", "long_name": "Westergaard 1D contact fraction, numerical"},
    "westergaard_contact_fraction_exact": {"units": "1", "long_name": "Westergaard 1D contact fraction, analytic"},
    "westergaard_pressure_error": {"units": "1", "long_name": "Westergaard rms pressure error / peak pressure"},
}
"""Labels of the study's own names (the shared ones are in :data:`contactlib.studies._common.COMMON_VARIABLES`)."""


def validation_point(*, n: int, contact_fraction: float, radius: float, amplitude: float, E: float, nu: float,
                     tol: float, max_iter: int, kernel: str) -> dict:
    """Hertz sphere (non-periodic, load control) and Westergaard 1D wavy contact at one resolution.

    ``contact_fraction`` sets the target: Hertz contact radius ``a = contact_fraction * L / 4`` (L = 1),
    Westergaard contact fraction ``2a/wavelength = contact_fraction``.
    """
    E_star = contact_modulus(E, nu)
    a_exact = contact_fraction / 4.0
    load = 4.0 * E_star * a_exact**3 / (3.0 * radius)
    sphere = surfaces.paraboloid(n, length=1.0, radius=radius)
    out = solve(sphere, E=E, nu=nu, mean_pressure=load, periodic=False, tol=tol, max_iter=max_iter, kernel=kernel)
    p_mean = float(westergaard.mean_pressure(contact_fraction, amplitude=amplitude, wavelength=1.0, E_star=E_star))
    profile = surfaces.wavy(n, length=1.0, amplitude=amplitude, dim=1)
    wave = solve(profile, E=E, nu=nu, mean_pressure=p_mean, tol=tol, max_iter=max_iter, kernel=kernel)
    exact = westergaard.partial_contact_pressure(wave.x.values, mean_pressure=p_mean, amplitude=amplitude,
                                                 wavelength=1.0, E_star=E_star)
    return {
        "hertz_contact_radius": math.sqrt(float(out.contact_area) / math.pi),
        "hertz_contact_radius_exact": a_exact,
        "hertz_penetration": float(out.penetration),
        "hertz_penetration_exact": hertz.sphere_penetration(load, radius=radius, E_star=E_star),
        "hertz_peak_pressure": float(out.pressure.max()),
        "hertz_peak_pressure_exact": 3.0 * load / (2.0 * math.pi * a_exact**2),
        "westergaard_contact_fraction": float(wave.contact_area),
        "westergaard_contact_fraction_exact": float(contact_fraction),
        "westergaard_pressure_error": float(np.sqrt(np.mean((wave.pressure.values - exact) ** 2)) / exact.max()),
        "iterations": float(out.iterations),
        "residual": max(float(out.residual), float(wave.residual)),
    }


def validation_shapes(grid: dict, constants: dict) -> list[tuple[int, ...]]:
    """FFT shapes of the validation study: the zero-padded Hertz grid and the 1D profile, per ``n``."""
    return [s for n in grid["n"] for s in ((2 * n, 2 * n), (n,))]


STUDY = {"point": validation_point, "fft_shapes": validation_shapes}
"""This study's entry of :data:`contactlib.studies.STUDIES`."""
