"""The adhesive scene on tamaas 2.9 (its Polonsky-Keer-Rey solver in gap mode under a mean pressure, with
``ExponentialAdhesionFunctional`` or ``MaugisAdhesionFunctional``), for tests and benchmarks.

Mapping (measured, ``../shared/peers/NOTES.md``): tamaas' ``model.E`` / ``model.nu`` are Young's modulus and
Poisson ratio; its gap is ``displacement - heights``, up to a constant; contact is counted by the gap (its
traction keeps round-off positives off contact): ``gap - min(gap) <= 1e-7 rms height``. Its functional
parameters are ``rho`` (the range) and ``surface_energy`` (the work of adhesion ``w``).
"""

from __future__ import annotations

import time

import numpy as np


def solve_tamaas(heights: np.ndarray, *, E: float, nu: float, work: float, range_: float, model: str,
                 mean_pressure: float, tol: float) -> dict:
    """Contact area fraction, mean gap [length], mean traction and wall time [s] of tamaas' solve."""
    import tamaas as tm

    tm.set_log_level(tm.LogLevel.error)
    n = heights.shape
    m = tm.ModelFactory.createModel(tm.model_type.basic_2d, [1.0, 1.0], list(n))
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
