"""Scenes and a peer cross-check shared by contactlib's tests and its benchmarks (the ``xarray.testing`` pattern).

A scene is a small function returning what a solve needs: the heights (a labelled ``DataArray`` from
:mod:`contactlib.surfaces`, which carries its window) and the keywords of :func:`contactlib.solve`. The test
suite asserts on them and ``benchmarks/`` times them, so a scene added here is both checked and measured.

* :data:`HARD_CASES`: scenes chosen to break solvers, each with a check of its answer
  (``tests/test_hard_cases.py``, ``benchmarks/bench_hard_cases.py``).
* :func:`adhesive_rough_scene`: a rough surface under an adhesive law, the scene of the tamaas cross-check
  (``tests/test_peer_tamaas_adhesion.py``, ``benchmarks/bench_adhesion.py``).
* :func:`solve_tamaas_adhesive`: that scene solved by tamaas 2.9 (an optional peer, imported on call).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Callable

import numpy as np
import xarray as xr

from . import surfaces
from .model.adhesion import Adhesion
from .reference import westergaard

__all__ = ["HARD_CASE_E", "HARD_CASE_NU", "HARD_CASES", "HardCase", "adhesive_rough_scene", "solve_tamaas_adhesive"]

HARD_CASE_E, HARD_CASE_NU = 1.0, 0.5
"""Young's modulus and Poisson ratio of every hard case."""
_E_STAR = HARD_CASE_E / (1 - HARD_CASE_NU**2)


@dataclass(frozen=True)
class HardCase:
    """One hard scene: ``surface()`` builds its heights, ``solve`` holds its keywords of :func:`contactlib.solve`
    (besides ``E``, ``nu``: :data:`HARD_CASE_E`, :data:`HARD_CASE_NU`), ``check(result)`` asserts its reference."""

    name: str
    surface: Callable[[], xr.DataArray]
    solve: dict
    check: Callable | None = None
    extra: dict = field(default_factory=dict)
    cross_check: bool = True  # re-solve under displacement control at the found penetration


def _rough(n, hurst=0.8, dim=2, q_roll=2, q_cutoff=None, seed=0, **kw):
    return lambda: surfaces.self_affine(n, hurst=hurst, q_roll=q_roll, q_cutoff=q_cutoff or n // 4, rms_slope=0.1,
                                        seed=seed, dim=dim, **kw)


def _spike():
    h = surfaces.self_affine(128, hurst=0.8, q_roll=2, q_cutoff=32, rms_height=1.0, seed=2).copy()
    h[{"x": 40, "y": 70}] = 100.0  # one spike a hundred rms heights tall (by name: the field is on (y, x))
    return h


def _check_single_point(out):
    assert 0 < int((out.pressure > 0).sum()) <= 3


def _check_spike_carries_load_alone(out):
    assert int((out.pressure > 0).sum()) == 1 and float(out.pressure.isel(x=40, y=70)) > 0


def _check_uniform(value):
    def check(out):
        np.testing.assert_allclose(out.pressure.values, value, rtol=1e-12)
        assert float(out.contact_area) == 1.0
    return check


def _check_fraction(lo, hi):
    def check(out):
        assert lo <= float(out.contact_area) <= hi
    return check


def _check_westergaard_threshold(out):
    exact = westergaard.full_contact_field(out.x.values, mean_pressure=float(out.mean_pressure), amplitude=0.01,
                                           wavelength=1.0, E_star=_E_STAR)
    np.testing.assert_allclose(out.pressure.values, exact, atol=1e-4 * float(out.mean_pressure))


_P_FULL = westergaard.full_contact_pressure(amplitude=0.01, wavelength=1.0, E_star=_E_STAR)

HARD_CASES = [
    HardCase("single touching point", _rough(256), {"mean_pressure": 1e-9}, _check_single_point),
    # 0.2 is just below the full-contact load (~0.224) of this surface: 99.9 % contact
    HardCase("near full contact", _rough(128), {"mean_pressure": 0.2}, _check_fraction(0.99, 0.9999)),
    HardCase("Hurst 0.3", _rough(256, hurst=0.3), {"mean_pressure": 0.01}, _check_fraction(0.02, 0.5)),
    HardCase("Hurst 0.95", _rough(256, hurst=0.95), {"mean_pressure": 0.01}, _check_fraction(0.02, 0.5)),
    HardCase("1000 scales in 1D at 65536 points", _rough(65536, dim=1, q_roll=1, q_cutoff=1000, hurst=0.8),
             {"mean_pressure": 0.01}, _check_fraction(0.01, 0.5)),
    HardCase("perfectly flat", lambda: surfaces.self_affine(64, hurst=0.8, q_roll=2, q_cutoff=16, rms_height=1.0,
                                                            seed=0) * 0.0,
             {"mean_pressure": 0.3}, _check_uniform(0.3), cross_check=False),  # no penetration fixes its load
    HardCase("one tall spike", _spike, {"mean_pressure": 1e-6}, _check_spike_carries_load_alone),
    HardCase("load exactly at full contact", lambda: surfaces.wavy(512, amplitude=0.01),
             {"mean_pressure": _P_FULL, "tol": 1e-10}, _check_westergaard_threshold,
             cross_check=False),  # a periodic penetration at full contact does not fix the load: refused
    HardCase("odd grid 101 x 99", lambda: surfaces.self_affine(
        101, hurst=0.7, q_roll=2, q_cutoff=25, rms_slope=0.1, seed=1).isel(y=slice(0, 99)),
        {"mean_pressure": 0.02}, _check_fraction(0.05, 0.6)),
    HardCase("non-power-of-two 96 x 96, Love kernel", _rough(96), {"mean_pressure": 0.02, "kernel": "love"},
             _check_fraction(0.05, 0.6)),
    HardCase("anisotropic gamma 0.1", _rough(128, anisotropy=0.1, angle=0.3), {"mean_pressure": 0.02},
             _check_fraction(0.05, 0.6)),
]
"""Scenes chosen to break solvers; to add a case, append a :class:`HardCase`."""


def adhesive_rough_scene(n: int = 256, *, model: str = "exponential") -> tuple[xr.DataArray, dict]:
    """A periodic self-affine surface under an adhesive law: the heights and the keywords of :func:`contactlib.solve`.

    Hurst 0.8, rolloff at 4 and cutoff at 32 wavelengths, rms slope 0.1 on the unit window of ``n x n``;
    ``E = 1``, ``nu = 0``, mean pressure 0.01, work 1e-5, range 1e-3: the process zone is 5 elements at
    ``n = 256`` and the law's strength ``sigma_0`` about the load.

    Parameters
    ----------
    n : int
        Nodes per side.
    model : {"exponential", "maugis"}
        The cohesive law of :class:`contactlib.Adhesion`.

    Returns
    -------
    heights : xarray.DataArray
    kwargs : dict
        ``E``, ``nu``, ``mean_pressure`` and ``adhesion``.
    """
    heights = surfaces.self_affine(n, hurst=0.8, q_roll=4, q_cutoff=32, rms_slope=0.1, seed=1)
    return heights, {"E": 1.0, "nu": 0.0, "mean_pressure": 0.01,
                     "adhesion": Adhesion(work=1e-5, range=1e-3, model=model)}


def solve_tamaas_adhesive(heights: np.ndarray, *, E: float, nu: float, work: float, range_: float, model: str,
                          mean_pressure: float, tol: float) -> dict:
    """The adhesive scene on tamaas 2.9: its Polonsky-Keer-Rey solver in gap mode under a mean pressure, with
    ``ExponentialAdhesionFunctional`` or ``MaugisAdhesionFunctional``, on the periodic unit square.

    Mapping (measured, ``../shared/peers/NOTES.md``): tamaas' ``model.E`` / ``model.nu`` are Young's modulus and
    Poisson ratio; its gap is ``displacement - heights``, up to a constant; contact is counted by the gap (its
    traction keeps round-off positives off contact): ``gap - min(gap) <= 1e-7 rms height``. Its functional's
    parameters are ``rho`` (the range) and ``surface_energy`` (the work of adhesion).

    Returns
    -------
    dict
        ``contact_area`` (fraction), ``mean_gap`` [length], ``mean_pressure`` and ``wall_time`` [s] of its solve.
    """
    import tamaas as tm

    tm.set_log_level(tm.LogLevel.error)
    m = tm.ModelFactory.createModel(tm.model_type.basic_2d, [1.0, 1.0], list(heights.shape))
    m.E, m.nu = E, nu
    h = np.ascontiguousarray(heights, dtype=float)
    solver = tm.PolonskyKeerRey(m, h, tol, tm.PolonskyKeerRey.gap, tm.PolonskyKeerRey.pressure)
    functional = (tm.MaugisAdhesionFunctional if model == "maugis" else tm.ExponentialAdhesionFunctional)(h)
    functional.parameters = {"rho": range_, "surface_energy": work}
    solver.addFunctionalTerm(functional)
    start = time.perf_counter()
    solver.solve(mean_pressure)
    wall = time.perf_counter() - start
    gap = np.array(m.displacement) - h
    gap -= gap.min()
    return {"contact_area": float(np.mean(gap <= 1e-7 * h.std())), "mean_gap": float(gap.mean()),
            "mean_pressure": float(np.array(m.traction).mean()), "wall_time": wall}
