"""Point functions of the parametric studies: pure functions of one grid point, returning scalars.

Each ``*_point`` takes the swept parameters and the study's constants as keywords (bind the
constants with ``functools.partial``) and calls only the public API. :data:`STUDIES` maps a study
name to its point function, the FFT shapes it plans, and the labels of its outputs.
"""

from __future__ import annotations

import inspect
import itertools
import math

import numpy as np
import xarray as xr

from . import analysis, surfaces
from .contact import solve
from .materials import contact_modulus
from .reference import hertz, westergaard
from .sweep import SWEEP_VARIABLES

PERSSON_KAPPA = math.sqrt(8 / math.pi)
"""Persson's small-load proportionality coefficient sqrt(8/pi) of A/A0 against p/(E* rms_slope)."""
PUBLISHED_KAPPA_RANGE = (1.8, 2.2)
"""Range of kappa from published numerical simulations (Hyun et al. 2004; Campana & Muser 2007; Putignano et al. 2012)."""

STUDY_VARIABLES: dict[str, dict[str, str]] = {
    "contact_fraction": {"units": "1", "long_name": "target contact size (Hertz: 4a/L, Westergaard: 2a/wavelength)"},
    "hertz_contact_radius": {"units": "m", "long_name": "Hertz sphere contact radius, numerical"},
    "hertz_contact_radius_exact": {"units": "m", "long_name": "Hertz sphere contact radius, analytic"},
    "hertz_penetration": {"units": "m", "long_name": "Hertz sphere approach, numerical"},
    "hertz_penetration_exact": {"units": "m", "long_name": "Hertz sphere approach, analytic"},
    "hertz_peak_pressure": {"units": "Pa", "long_name": "Hertz sphere peak pressure, numerical"},
    "hertz_peak_pressure_exact": {"units": "Pa", "long_name": "Hertz sphere peak pressure, analytic"},
    "westergaard_contact_fraction": {"units": "1", "long_name": "Westergaard 1D contact fraction, numerical"},
    "westergaard_contact_fraction_exact": {"units": "1", "long_name": "Westergaard 1D contact fraction, analytic"},
    "westergaard_pressure_error": {"units": "1", "long_name": "Westergaard rms pressure error / peak pressure"},
    "hurst": {"units": "1", "long_name": "Hurst exponent"},
    "reduced_pressure": {"units": "1", "long_name": "mean pressure / (E* rms slope)"},
    "contact_area": {"units": "1", "long_name": "contact area fraction"},
    "mean_pressure": {"units": "Pa", "long_name": "mean contact pressure over the window"},
    "penetration": {"units": "m", "long_name": "rigid approach from first contact"},
    "iterations": {"units": "1", "long_name": "solver iterations"},
    "rms_slope": {"units": "1", "long_name": "rms slope of the discretised surface"},
    "kappa": {"units": "1", "long_name": "area-load coefficient A/A0 / (p/(E* rms slope))"},
    "anisotropy": {"units": "1", "long_name": "target anisotropy ratio gamma of the surface"},
    "surface_gamma": {"units": "1", "long_name": "anisotropy ratio gamma of the rigid surface"},
    "surface_theta_d": {"units": "rad", "long_name": "principal direction theta_d of the rigid surface"},
    "pressure_gamma": {"units": "1", "long_name": "anisotropy ratio gamma of the contact pressure"},
    "pressure_theta_d": {"units": "rad", "long_name": "principal direction theta_d of the contact pressure"},
    "pressure": {"units": "Pa", "long_name": "contact pressure (compressive positive)"},
    "x": {"units": "m", "long_name": "position along x"},
    "y": {"units": "m", "long_name": "position along y"},
}
for _field in ("surface", "pressure"):
    for _ij in ("xx", "xy", "yy"):
        STUDY_VARIABLES[f"{_field}_m_{_ij}"] = {
            "units": "1" if _field == "surface" else "Pa2 m-2",
            "long_name": f"anisotropy tensor component M_{_ij} of the {'rigid surface' if _field == 'surface' else 'contact pressure'}",
        }


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


def rough_surface(*, n: int, hurst: float, seed: int, q_low: float, q_roll: float, q_cutoff: float,
                  rms_slope: float, anisotropy: float = 1.0, angle: float = 0.0):
    """The seeded self-affine surface of a study point (also written by the workflow's surfaces rule)."""
    return surfaces.self_affine(n, length=1.0, hurst=hurst, q_low=q_low, q_roll=q_roll, q_cutoff=q_cutoff,
                                rms_slope=rms_slope, seed=seed, anisotropy=anisotropy, angle=angle)


def area_load_point(*, hurst: float, n: int, seed: int, reduced_pressure: float, q_low: float, q_roll: float,
                    q_cutoff: float, rms_slope: float, E: float, nu: float, tol: float, max_iter: int,
                    kernel: str, initial_pressure=None) -> dict:
    """Contact area at mean pressure ``reduced_pressure * E* * rms_slope`` (measured slope of the grid).

    ``initial_pressure`` warm-starts the solver (the ``_warm_start`` output of a lower load on the same surface).
    """
    h = rough_surface(n=n, hurst=hurst, seed=seed, q_low=q_low, q_roll=q_roll, q_cutoff=q_cutoff,
                      rms_slope=rms_slope)
    slope = analysis.rms_slope(h)
    E_star = contact_modulus(E, nu)
    out = solve(h, E=E, nu=nu, mean_pressure=reduced_pressure * E_star * slope, tol=tol, max_iter=max_iter,
                kernel=kernel, initial_pressure=initial_pressure)
    area = float(out.contact_area)
    return {"contact_area": area, "mean_pressure": float(out.mean_pressure), "penetration": float(out.penetration),
            "iterations": float(out.iterations), "residual": float(out.residual), "rms_slope": slope,
            "kappa": area / reduced_pressure, "_warm_start": out.pressure.values}


def anisotropy_point(*, anisotropy: float, seed: int, n: int, hurst: float, angle: float, reduced_pressure: float,
                     q_low: float, q_roll: float, q_cutoff: float, rms_slope: float, zeta1: float, zeta2: float,
                     E: float, nu: float, tol: float, max_iter: int, kernel: str, save_fields: bool = False) -> dict:
    """Anisotropy (gamma, theta_d, M) of a rigid anisotropic surface and of its contact pressure."""
    h = rough_surface(n=n, hurst=hurst, seed=seed, q_low=q_low, q_roll=q_roll, q_cutoff=q_cutoff,
                      rms_slope=rms_slope, anisotropy=anisotropy, angle=angle)
    slope = analysis.rms_slope(h)
    E_star = contact_modulus(E, nu)
    out = solve(h, E=E, nu=nu, mean_pressure=reduced_pressure * E_star * slope, tol=tol, max_iter=max_iter,
                kernel=kernel)
    result = {"contact_area": float(out.contact_area), "mean_pressure": float(out.mean_pressure),
              "iterations": float(out.iterations), "residual": float(out.residual)}
    for name, field in (("surface", h), ("pressure", out.pressure)):
        t = analysis.anisotropy_tensor(field, zeta1, zeta2)
        m = t.M.values
        result.update({f"{name}_gamma": float(t.gamma), f"{name}_theta_d": float(t.theta_d),
                       f"{name}_m_xx": float(m[0, 0]), f"{name}_m_xy": float(m[0, 1]), f"{name}_m_yy": float(m[1, 1])})
    if save_fields:
        p = out.pressure.reset_coords(drop=True)
        p.attrs = {}
        result["pressure"] = p
    return result


STUDIES = {
    "validation": {"point": validation_point,
                   "fft_shapes": lambda grid, c: [s for n in grid["n"] for s in ((2 * n, 2 * n), (n,))]},
    "area_load": {"point": area_load_point, "fft_shapes": lambda grid, c: [(n, n) for n in grid["n"]],
                  "path_dim": "reduced_pressure"},
    "anisotropy": {"point": anisotropy_point, "fft_shapes": lambda grid, c: [(c["n"], c["n"])]},
}
STUDIES["area_load"]["surface_keys"] = ("hurst", "seed")
STUDIES["anisotropy"]["surface_keys"] = ("anisotropy", "seed")


def study_surfaces(name: str, constants: dict, grid: dict) -> xr.Dataset:
    """The seeded surfaces of a study (at its smallest resolution) as one labelled Dataset.

    Dims are the study's surface parameters (e.g. ``hurst``, ``seed``) then ``x``, ``y``; the
    points regenerate the same surfaces bit for bit from these parameters.
    """
    keys = STUDIES[name]["surface_keys"]
    n = min(grid["n"]) if "n" in grid else constants["n"]
    accepted = set(inspect.signature(rough_surface).parameters)
    fixed = {k: v for k, v in constants.items() if k in accepted and k not in keys}
    values = [sorted(grid[k]) for k in keys]
    rows = []
    for combo in itertools.product(*values):
        rows.append(rough_surface(**{**fixed, "n": n, **dict(zip(keys, combo))}))
    first = rows[0]
    stacked = np.stack([r.values for r in rows]).reshape(tuple(len(v) for v in values) + first.shape)
    table = {**SWEEP_VARIABLES, **STUDY_VARIABLES}
    coords = {k: (k, np.asarray(v), dict(table[k])) for k, v in zip(keys, values)}
    coords.update({d: first[d] for d in first.dims})
    height = xr.DataArray(stacked, dims=keys + first.dims, coords=coords,
                          attrs={"units": "m", "long_name": "rigid surface height"})
    ds = xr.Dataset({"height": height})
    ds.attrs.update({k: v for k, v in fixed.items()})
    ds.attrs["n"] = n
    return ds
