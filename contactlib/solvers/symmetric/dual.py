"""Periodic displacement control, solved as its dual: the gap as unknown.

A periodic compliance ignores the mean pressure, so under displacement control (no load to
centre the search direction on) the preconditioned Polonsky-Keer iteration meets a direction of
zero curvature and overshoots (see :mod:`.ccg`). Exchanging the roles of pressure and gap gives a
problem with the structure of load control:

* unknown: the gap ``g >= 0``, whose mean is fixed by the approach, since a periodic displacement
  has zero mean: ``mean(g) = mean(max h - h) - penetration``;
* its "gap": the pressure ``p = S (g + h - max h) + mean(p) >= 0``, with ``S`` the stiffness (the
  compliance's exact inverse, mean mode 0, :class:`contactlib.model.operators.Stiffness`) and the mean
  pressure as the multiplier of the mean-gap constraint (the approach of load control);
* ``p g = 0``.

So the load-controlled loop of :func:`.ccg.solve_polonsky_keer` solves it unchanged on ``S``,
preconditioned with the compliance itself. The loop's own (dual) residual is only a screen: the
solve stops when the primal answer (pressure zero off contact, its own displacement ``K p``) has a
:func:`.contact_residual` below ``tol`` as well, so ``tol`` means what it means for every solver.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable

import numpy as np

from ...model.operators import Compliance, Stiffness
from .ccg import zero_state, solve_polonsky_keer
from ..state import ContactState, contact_residual, height_scale


def solve_periodic_displacement(
    operator: Compliance,
    heights: np.ndarray,
    *,
    penetration: float,
    tol: float = 1e-8,
    max_iter: int = 10_000,
    initial_pressure: np.ndarray | None = None,
    monitor: Callable[[int, float, Callable[[], ContactState]], None] | None = None,
    verify_below: float | None = None,
) -> ContactState:
    """Pressure under a periodic surface pressed by ``penetration`` [length] (from first contact).

    Same arguments and answer as :func:`.solve_polonsky_keer` under displacement control, for a
    periodic ``operator``. ``verify_below`` (default ``tol``): the dual residual below which the
    primal residual is evaluated (one convolution); :func:`contactlib.solve_tolerances` sets it to
    its loosest tolerance so that every tolerance stops where its own solve would.
    """
    if not operator.periodic:
        raise ValueError("solve_periodic_displacement: the operator must be periodic")
    hp = heights - heights.max()
    if not np.any(hp + penetration > 0):
        return zero_state(heights, penetration=float(penetration))
    mean_gap = float(-np.mean(hp) - penetration)
    if mean_gap <= 0:
        raise ValueError(f"penetration {penetration!r} reaches full contact (mean gap {mean_gap:.3e} <= 0): a "
                         "periodic surface cannot be pressed further by displacement; give mean_pressure")
    scale = height_scale(heights)
    stiffness = Stiffness(operator)
    stiffness.load()[...] = heights
    dual_heights = -stiffness.convolve().copy()  # -S h: the pressure that flattens the surface, negated
    cache: dict[int, ContactState] = {}

    def primal(dual: ContactState) -> ContactState:
        """The answer a dual iterate stands for; the dual iterate's gap field is the pressure."""
        if dual.iterations not in cache:
            cache.clear()
            pressure = np.where(dual.pressure > 0, 0.0, np.maximum(dual.gap, 0.0))
            displacement = operator.apply_aside(pressure)
            gap = displacement - hp - penetration
            residual = contact_residual(pressure, gap, scale)
            cache[dual.iterations] = ContactState(
                pressure=pressure, gap=gap, displacement=displacement, penetration=float(penetration),
                mean_pressure=float(pressure.mean()), iterations=dual.iterations, residual=residual,
                converged=bool(residual <= tol), solver="polonsky-keer-dual")
        return cache[dual.iterations]

    initial = None
    if initial_pressure is not None:
        initial = np.maximum(operator.apply_aside(np.maximum(initial_pressure, 0.0)) - hp - penetration, 0.0)
    watch = None if monitor is None else (lambda it, residual, snapshot: monitor(it, residual, lambda: primal(snapshot())))
    # restarts on every re-entry: the dual's "contact set" is the open gap, nearly the whole surface at
    # low contact, so the primal's fraction rule would hardly ever restart (97-266 iterations against
    # 14-23 on 256^2-1024^2 at 0.2-0.4 % contact)
    dual = solve_polonsky_keer(stiffness, dual_heights, mean_pressure=mean_gap, tol=tol, max_iter=max_iter,
                               initial_pressure=initial, monitor=watch, verify=lambda s: primal(s).residual,
                               verify_below=verify_below, restart_fraction=0.0)
    answer = primal(dual)
    # the loop stops on max(dual, primal) residual: report the primal one, with the loop's verdict
    return dataclasses.replace(answer, converged=bool(dual.residual <= tol and answer.residual <= tol))
