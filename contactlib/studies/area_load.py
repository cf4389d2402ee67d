"""The ``area_load`` study: contact area against load of seeded self-affine surfaces, each load path
walked with warm starts (Hyun et al. 2004; Persson 2001)."""

from __future__ import annotations

import math

from .. import analysis
from ..problems.contact import solve
from ..model.materials import contact_modulus
from ._common import rough_surface

PERSSON_KAPPA = math.sqrt(8 / math.pi)
"""Persson's small-load proportionality coefficient sqrt(8/pi) of A/A0 against p/(E* rms_slope)."""
PUBLISHED_KAPPA_RANGE = (1.8, 2.2)
"""Range of kappa from published numerical simulations (Hyun et al. 2004; Campana & Muser 2007; Putignano et al. 2012)."""

VARIABLES: dict[str, dict[str, str]] = {
    "penetration": {"units": "m", "long_name": "rigid approach from first contact"},
    "kappa": {"units": "1", "long_name": "area-load coefficient A/A0 / (p/(E* rms slope))"},
}
"""Labels of the study's own names (the shared ones are in :data:`contactlib.studies._common.COMMON_VARIABLES`)."""


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
            "kappa": area / reduced_pressure, "_warm_start": out.pressure}


def area_load_shapes(grid: dict, constants: dict) -> list[tuple[int, ...]]:
    """FFT shapes of the area_load study: one periodic grid per ``n``."""
    return [(n, n) for n in grid["n"]]


STUDY = {"point": area_load_point, "fft_shapes": area_load_shapes, "path_dim": "reduced_pressure",
         "surface_keys": ("hurst", "seed")}
"""This study's entry of :data:`contactlib.studies.STUDIES`."""
