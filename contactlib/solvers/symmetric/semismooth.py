"""Contact on plate-like bodies, load or displacement control: semismooth Newton with a two-level CG.

A thin remote-pressure layer stalls the constrained CG of :mod:`.ccg` (see
:data:`contactlib.model.operators.PRECONDITION_SOFTENING`): its contact set changes at every step, so the
conjugacy that would absorb the plate's few huge eigenvalues is lost, and no Fourier preconditioner
restricted to the set removes them. This solver separates the two difficulties.

* Outside: the primal-dual active-set method (Hintermueller, Ito & Kunisch, SIAM J. Optim. 13, 2003),
  a semismooth Newton method for ``min(p, g) = 0``: solve the equality problem on the set ``A``
  (``g = 0`` on ``A``, ``p = 0`` off it, ``mean(p)`` fixed, the approach its multiplier), then take
  as the next set the points of positive pressure in ``A`` and the interpenetrating points outside.
  It stops when the residual is below ``tol`` and the pressure is non-negative (the set repeats, or only
  points to join remain: their interpenetration is in the residual), or its negative part, clipped, leaves
  a state whose own residual is below ``tol``.
* Inside: CG on the fixed set, on fields centred on ``A`` (the load), preconditioned by the two-level
  :class:`.coarse.TwoLevel` (the soft long waves solved exactly). Each solve is warm-started from the
  last pressure, and solved loosely while the set still moves.

Measured on a 16384-point profile at q0 h = 0.1 (nu = 0.3): 9-14 set updates and 270-420 CG iterations
in all from 2 % to 74 % contact, where Polonsky-Keer stalls at residuals of 2e-2 to 0.4.

Displacement control (``penetration`` fixed, the load free). A remote-pressure layer has a rigid-body mode,
so its displacements are zero-mean and the penetration is measured against the mean deformed plane, as on a
periodic half-space. On a set ``A`` that is not the whole grid the problem ``K_AA p = hp_A + d`` is still
well posed: ``K`` is positive semi-definite with only the constant in its null space, and a field that
vanishes off ``A`` is not constant, so ``K_AA`` is definite. It is solved through the load-controlled
system above, which is linear in the load ``T = sum p``: ``p = p_T + (T' - T) p_1``, approach ``a_T +
(T' - T) a_1``, with ``(p_1, a_1)`` the answer to a unit load and no heights, so ``T' = T + (d - a_T) /
a_1`` (``a_1 = 1 / (1^T K_AA^-1 1) > 0``: the Newton step of the joint problem in ``p`` and the load). Two
CG solves per set, each warm-started; at full contact ``a_1 = 0`` and the load is undetermined (refused
before, by :func:`contactlib.solve`). The dual iteration (:mod:`.dual`) stalled here beyond about 5 %
contact at q0 h = 0.1.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from .ccg import zero_state
from .coarse import soft_modes, two_level
from ..state import ContactState, dot, height_scale, residual_from_sums
from ..krylov_sweeps import newton_sweep

MAX_SETS = 200
"""Contact-set updates before the solve is returned as not converged."""

START_FRACTION = 0.05
"""A cold start's contact set: the highest points, this fraction of the grid."""

INNER_FORCING = 0.1
"""With a ``set_solver`` (:mod:`.krylov`), each set is solved to this fraction of the last set's outer residual
(Eisenstat-Walker), not to a tolerance fixed by the number of points that moved: near the answer a few points
still move and the fixed rule asked exact solves of sets about to change (20 of 85 GMRES iterations on one
512^2 viscoelastic speed). With :data:`.krylov.SETTLED` and a held set solved to ``tol / 16`` at once: 7 % fewer
GMRES iterations over a 30-speed sweep (1298 against 1401), 5 % on cold friction and viscoelastic solves, with
fewer set updates (5-10 against 9-14). On a 512^2 30-speed sweep (held sets and the floor at ``tol / 2``) 0.03,
0.2 and 0.3 took 1055, 1056 and 1061 GMRES iterations against 1050."""

HELD_FRACTION = 0.5
"""With a ``set_solver``, a held set (no point changes but the residual above ``tol``) is solved at once to this
fraction of ``tol`` in the rms of its gap on the set [in units of the rms height]. The outer residual that follows
was 0.4-0.5 times that rms (the pressure-weighted mean of ``|gap|``, 19 held sets of a 512^2 30-speed sweep), so
half of ``tol`` lands it at about ``tol / 4``; ``tol / 16`` cost 56 more GMRES iterations over that sweep (1118
against 1062) for no closer answer to a ``tol = 1e-10`` reference. A held set that still misses ``tol`` is solved
again ten times tighter."""

FLOOR_FRACTION = 0.5
"""With a ``set_solver``, the tightest tolerance a changed set is solved to, as a fraction of ``tol`` (as
:data:`HELD_FRACTION`): the set solve after the last change often ends the loop, and a tighter floor only pushed
the final residual further below ``tol`` (1050 against 1062 GMRES iterations on that sweep, the same distance to
the reference: 5.7e-7 rms in the pressure relative to its rms, at ``tol = 1e-8``)."""


def solve_semismooth(
    operator,
    heights: np.ndarray,
    *,
    mean_pressure: float | None = None,
    penetration: float | None = None,
    tol: float = 1e-8,
    max_iter: int = 10_000,
    initial_pressure: np.ndarray | None = None,
    monitor: Callable[[int, float, Callable[[], ContactState]], bool | None] | None = None,
    set_solver: Callable | None = None,
    name: str = "semismooth-newton",
    set_floor: float | None = None,
) -> ContactState:
    """Pressure under ``heights`` [length] at ``mean_pressure`` [pressure] or ``penetration`` [length, from
    first contact, against the mean deformed plane] on a periodic ``operator`` (exactly one of the two).

    Same arguments and answer as :func:`.ccg.solve_polonsky_keer`; ``max_iter`` bounds the CG iterations over
    all sets, ``iterations`` counts them, ``monitor`` is called once per set update (a true return stops the
    loop there, e.g. on a stall). ``set_floor``: the loosest that the tightest tolerance of a changed set's solve
    may be, relative as ``tol`` (a plate: :data:`.coarse.PLATE_SET_FLOOR`). ``set_solver(hp, index, start, total,
    tol, max_iter[, image]) -> (p on
    the set, approach, iterations)`` (``image``, when given: the displacement of ``start`` on the set, already
    known) replaces the two-level CG on each set (a non-symmetric ``operator``:
    :meth:`.krylov.ComplexCompliance.solve_on_set`; load control only); ``name`` is the solver name reported.
    """
    load_control = mean_pressure is not None
    if load_control == (penetration is not None):
        raise ValueError("solve_semismooth: give exactly one of mean_pressure and penetration")
    if set_solver is not None and not load_control:
        raise ValueError("solve_semismooth: a set_solver works under load control only (give mean_pressure)")
    shape, n = heights.shape, heights.size
    hp = (heights - heights.max()).reshape(-1)
    scale = height_scale(heights)
    if not load_control and not np.any(hp + penetration > 0):
        return zero_state(heights, penetration=float(penetration))
    total = n * float(mean_pressure) if load_control else None
    modes = None if set_solver is not None else soft_modes(
        operator.grid, operator.multiplier * float(np.prod(operator.work_shape)), operator.E_star)
    if initial_pressure is not None and np.any(initial_pressure > 0):
        p = np.maximum(np.asarray(initial_pressure, dtype=float).reshape(-1), 0.0)
        active = p > 0
        if not load_control:
            total = float(p.sum())
    else:
        p = np.zeros(n)
        # cold: the highest points (load control), the bearing area (displacement control)
        active = hp >= np.quantile(hp, 1 - START_FRACTION) if load_control else hp + penetration > 0
    unit, unit_approach = np.zeros(n), None  # displacement control: the answer to a unit load on the set
    iterations, residual, inner_tol = 0, np.inf, 1e-3
    seen: set[bytes] = set()
    # a set solver's tightest changed-set tolerance (tol / 16 once the sets cycle); the CG set solves' is tol / 16
    floor = FLOOR_FRACTION * tol if set_solver is not None else tol / 16
    floor = floor if set_floor is None else min(floor, set_floor)
    state = None
    image = None  # M p of the last set's answer, when the set holds: the next set solve's start, known
    for k in range(1, MAX_SETS + 1):
        index = np.flatnonzero(active)
        budget = max_iter - iterations
        if set_solver is not None:
            p_a, approach, used = set_solver(hp, index, p[index], total, inner_tol * scale, budget,
                                             **({"image": image[index]} if image is not None else {}))
        else:
            preconditioner = two_level(operator, modes, index)
            if total is None:  # a cold start: the load of the bearing area's rigid punch is found below
                total = 0.0
            p_a, approach, used = _solve_on_set(operator, preconditioner, hp, index, p[index], total,
                                                inner_tol * scale, budget)
        if not load_control:
            p_a, approach, total, unit_approach, more = _fix_approach(
                operator, preconditioner, index, unit, unit_approach, p_a, approach, total, float(penetration),
                inner_tol * scale, budget - used)
            used += more
        iterations += used
        p = np.zeros(n)
        p[index] = p_a
        displacement = np.ascontiguousarray(operator(p.reshape(shape)).reshape(-1), dtype=float)
        gap, positive, following = np.empty(n), np.empty(n), np.empty(n, dtype=bool)
        sums = newton_sweep(p, active, displacement, hp, float(approach), gap, positive, following)
        residual = residual_from_sums(sums[1], sums[2], sums[0], n, scale)
        changed = int(sums[3])
        # converged: the residual within tol, and the pressure its own displacement's (no point of the set below
        # zero). Points still to join then only interpenetrate by what the residual counts, as a Polonsky-Keer
        # answer may; waiting for them to join made a set pair cycle with the residual 40x below tol.
        own = changed == 0 or float(p_a.min()) >= 0.0
        state = ContactState(pressure=positive.reshape(shape), gap=gap.reshape(shape),
                             displacement=displacement.reshape(shape), penetration=float(approach),
                             mean_pressure=float(positive.mean()), iterations=iterations, residual=residual,
                             converged=bool(own and residual <= tol), solver=name)
        # only negative pressures left: clipped, is it an answer? (not on a plate: clipping even 1e-6 of the load
        # displaces it by more than tol, so the check was an operator application a set for nothing)
        if not state.converged and residual <= tol and set_floor is None:
            state = _clipped(operator, positive, hp, float(approach), total if load_control else None, shape, scale,
                             tol, iterations, name) or state
        stop = monitor is not None and monitor(k, residual, lambda s=state: s)
        # a held set restarts from this p: its image is known (for a changed set, leaving the dropped points'
        # share out cost more set updates than the application it saved: 190 against 154 on a 30-speed sweep)
        image = displacement if set_solver is not None and changed == 0 else None
        if state.converged or iterations >= max_iter or stop:
            return state
        if changed == 0:  # the set holds: solve it tighter (a set solver: to the end at once)
            if set_solver is None:
                inner_tol = max(tol / 16, inner_tol / 100)
            else:
                inner_tol = HELD_FRACTION * tol if inner_tol > HELD_FRACTION * tol else inner_tol / 10
            continue
        key = following.tobytes()
        if key in seen:  # a cycle of sets: tighter solves break ties made by round-off
            floor = tol / 16 if set_floor is None else min(tol / 16, set_floor)
            inner_tol = max(tol / 16, inner_tol / 10)
        seen.add(key)
        active = following
        if not active.any():  # cannot happen with a positive load; keep the highest point
            active = hp == 0.0
        if not load_control and active.all():
            raise ValueError(f"penetration {penetration!r} reaches full contact on this body: the load is then "
                             "undetermined; give mean_pressure instead")
        if set_solver is not None:  # inexact Newton: the set solves follow the outer residual
            inner_tol = max(floor, min(inner_tol, INNER_FORCING * residual))
        else:
            inner_tol = min(inner_tol, max(floor, 1e-3 * changed / n))
    return state


def _clipped(operator, positive, hp, approach, total, shape, scale, tol, iterations, name) -> ContactState | None:
    """The state of a set solve's pressure without its negative part (scaled back to the load ``total`` under load
    control; None: displacement control), with its own displacement, gap and residual, if that residual is within
    ``tol`` (else None). One operator application, where the next set's solve costs at least two and the set
    update's own: near the answer a few points of slightly negative pressure (1e-7-1e-4 of the load) kept the loop
    going for 2-5 more set updates with the residual already below ``tol``."""
    p = positive if total is None else positive * (total / float(positive.sum()))
    displacement = np.ascontiguousarray(operator(p.reshape(shape)).reshape(-1), dtype=float)
    n = p.size
    gap, clipped, following = np.empty(n), np.empty(n), np.empty(n, dtype=bool)
    sums = newton_sweep(p, p > 0, displacement, hp, approach, gap, clipped, following)
    residual = residual_from_sums(sums[1], sums[2], sums[0], n, scale)
    if not residual <= tol:
        return None
    return ContactState(pressure=clipped.reshape(shape), gap=gap.reshape(shape),
                        displacement=displacement.reshape(shape), penetration=approach,
                        mean_pressure=float(clipped.mean()), iterations=iterations, residual=residual, converged=True,
                        solver=name)


def _fix_approach(operator, preconditioner, index, unit, unit_approach, p_a, approach, total, penetration, tol,
                  max_iter):
    """Displacement control on a set: move the load ``total`` so the approach is ``penetration``.

    ``(p_a, approach)`` solve the set at load ``total``; ``unit`` (full field, updated in place) and
    ``unit_approach`` are the last answer to a unit load (its warm start, and the scale ``a_1`` of its
    tolerance; None at first, then the upper bound ``mean(K 1_A) / |A|`` stands in). The unit solve's error
    enters times the load change ``|penetration - approach| / a_1``, so its tolerance is ``tol`` over that
    change (and at most ``1e-3 a_1``). Returns ``(p_a, penetration, total, a_1, CG iterations)``."""
    warm = unit_approach is not None
    if not warm:
        field = np.zeros(unit.size)
        field[index] = 1.0 / index.size
        unit_approach = float(operator(field.reshape(operator.grid.shape)).reshape(-1)[index].mean())
    zero = np.zeros(unit.size)
    miss = max(abs(penetration - approach), 1e-300)
    used = 0
    for _ in range(3):  # a stale scale can make the tolerance too loose: solve again, warm
        unit_tol = min(tol * unit_approach / miss, 1e-3 * unit_approach)
        start = unit[index] if warm else np.full(index.size, 1.0 / index.size)
        u_a, a1, more = _solve_on_set(operator, preconditioner, zero, index, start, 1.0, unit_tol, max_iter - used)
        used += more
        if not a1 > 0:
            raise ValueError(f"penetration control: the contact set of {index.size} points takes no load (unit-load "
                             f"approach {a1:.3e}); give mean_pressure instead")
        unit[:] = 0.0
        unit[index] = u_a
        warm, stale, unit_approach = True, unit_approach, a1
        if a1 >= 0.5 * stale:
            break
    step = (penetration - approach) / a1
    return p_a + step * u_a, penetration, total + step, a1, used


def _solve_on_set(operator, preconditioner, hp, index, start, total, tol, max_iter):
    """``(p on the set, approach, iterations)``: CG for ``K_AA p = hp_A + approach``, ``sum p = total``,
    stopping when the centred gap on the set is at most ``tol`` [length] everywhere."""
    shape = operator.grid.shape
    n_a = index.size
    start = np.where(np.isfinite(start), start, 0.0)
    p = start + (total - start.sum()) / n_a

    def K(field):
        full = np.zeros(int(np.prod(shape)))
        full[index] = field
        return operator(full.reshape(shape)).reshape(-1)[index]

    g = K(p) - hp[index]
    r = -(g - g.mean())
    z = preconditioner.apply(r)
    t, rz = z.copy(), dot(r, z)
    it = 0
    while np.abs(r).max() > tol and it < max_iter:
        Kt = K(t)
        Kt -= Kt.mean()
        tKt = dot(t, Kt)
        if tKt <= 0:
            break
        alpha = rz / tKt
        p += alpha * t
        r -= alpha * Kt
        z = preconditioner.apply(r)
        rz, previous = dot(r, z), rz
        t = z + (rz / previous) * t
        it += 1
    g = K(p) - hp[index]  # the true gap: no drift of the updated residual
    return p, float(g.mean()), it + 2
