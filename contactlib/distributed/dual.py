"""Periodic displacement control on slabs, solved as its dual (the gap as unknown):
:mod:`contactlib.solvers.symmetric.dual`.

The periodic compliance ignores the mean pressure, so the preconditioned primal iteration cannot run under
displacement control; as in the serial library the load-controlled loop (:func:`.ccg.solve_polonsky_keer`)
solves the dual problem on the stiffness, and stops when the primal answer's residual is below ``tol`` too.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from ..solvers.state import residual_from_sums
from .ccg import LocalState, zero_state, global_height_scale, global_max, solve_polonsky_keer
from .operator import DistributedCompliance, apply, stiffness_of


def solve_periodic_displacement(op: DistributedCompliance, heights: np.ndarray, *, penetration: float,
                                tol: float = 1e-8, max_iter: int = 10_000, progress=None,
                                row_start: int = 0) -> LocalState:
    """This rank's rows of the pressure under a periodic surface pressed by ``penetration`` [length]."""
    n = op.shape[0] * op.shape[1]
    hmax = global_max(op.comm, heights.max())
    hp = heights - hmax
    scale = global_height_scale(op, heights)
    if not op.allsum(float(np.any(hp + penetration > 0)))[0]:
        return zero_state(op, hp, scale, float(penetration), row_start)
    mean_gap = float(-op.allsum(float(np.sum(hp)))[0] / n - penetration)
    if mean_gap <= 0:
        raise ValueError(f"penetration {penetration!r} reaches full contact (mean gap {mean_gap:.3e} <= 0): a "
                         "periodic surface cannot be pressed further by displacement; give mean_pressure")
    stiffness = stiffness_of(op)
    dual_heights = -apply(op, heights, stiffness.multiplier)  # -S h
    cache: dict[int, LocalState] = {}

    def primal(dual: LocalState) -> LocalState:
        if dual.iterations not in cache:
            cache.clear()
            pressure = np.where(dual.pressure > 0, 0.0, np.maximum(dual.gap, 0.0))
            displacement = apply(op, pressure)
            gap = displacement - hp - penetration
            comp, pen, psum, n_contact = op.allsum(float(np.sum(pressure * np.abs(gap))),
                                                   float(np.sum(np.maximum(-gap, 0.0))), float(pressure.sum()),
                                                   float(np.count_nonzero(pressure > 0)))
            residual = residual_from_sums(comp, pen, psum, n, scale)
            cache[dual.iterations] = LocalState(
                pressure=pressure, gap=gap, displacement=displacement, penetration=float(penetration),
                mean_pressure=float(psum) / n, contact_area=float(n_contact) / n, iterations=dual.iterations,
                residual=residual, converged=bool(residual <= tol), solver="polonsky-keer-dual", row_start=row_start,
                shape=op.shape)
        return cache[dual.iterations]

    dual = solve_polonsky_keer(stiffness, dual_heights, mean_pressure=mean_gap, tol=tol, max_iter=max_iter,
                               restart_fraction=0.0, verify=lambda s: primal(s).residual, progress=progress,
                               overwrite_heights=True,
                               row_start=row_start)
    answer = primal(dual)
    return dataclasses.replace(answer, converged=bool(dual.residual <= tol and answer.residual <= tol))
