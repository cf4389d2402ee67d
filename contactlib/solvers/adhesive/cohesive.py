"""Cohesive-zone adhesion: the contact conditions with the adhesive traction as a term.

The total traction is ``p = p_r + a(g)``: a repulsive part ``p_r >= 0``, zero where the gap ``g = K p +
max h - h - d`` is open, and the adhesive traction ``a(g) = -sigma(g) <= 0`` of the cohesive law
(:class:`contactlib.Adhesion`). The conditions ``p_r >= 0, g >= 0, p_r g = 0`` are the complementarity
function ``phi = min(p_r, c g) = 0`` (``c`` an element stiffness, so both parts are pressures).

Two methods, tried in this order:

1. **Frozen traction** (:class:`.cohesive_frozen.FrozenTraction`). With ``a`` held fixed the problem is
   non-adhesive:
   ``q = p - a >= 0`` on the heights ``h - K a`` under the load ``P - mean(a)`` (or at the same approach),
   which the scene's own constrained solver (Polonsky-Keer, or its dual under periodic displacement
   control) solves, on any body it handles. The law then gives the next ``a = a(g)``; Anderson mixing
   accelerates that fixed point, and each round runs only :data:`.cohesive_frozen.INNER_ITERATIONS` warm-started
   CG iterations (a full inner solve on the dual path and on a plate-like remote-pressure layer, whose CG
   is not preconditioned). Where the inner solver is the preconditioned Polonsky-Keer one the rounds run
   inside one solve of it whose heights move (:mod:`.cohesive_rounds`: a round costs one FFT pair beside
   its CG iterations, no set-up), so a solve costs about twice the non-adhesive one on a 2D rough surface
   (``benchmarks/bench_adhesion.py``). A cold start is the first
   round itself (``a = 0``). Where the fixed point converges slowly (its gain ``|a'| K`` over the
   process zone is near 1 on a single smooth contact with a resolved zone: the JKR sphere, a 1D wavy
   profile), it stops after :data:`.cohesive_frozen.STALL_ROUNDS` rounds without a :data:`.cohesive_frozen.STALL_DROP`
   fall, and starts again by continuation in the range (:data:`FROZEN_RANGES`: a Maugis sphere at large lambda, whose
   contact edge then creeps an element every few rounds, is reached from the same sphere at a smaller lambda).
2. **Semi-smooth Newton** (primal-dual active set, :class:`.cohesive_newton.CohesiveNewton`): on the active
   set ``C = {p_r > c g}`` the row is ``g = 0`` (contact), elsewhere ``p = a(g)`` (the law), linearised
   with ``a'(g)``. Each Newton system goes to GMRES with the body's operator and, on the contact rows, the Fourier
   preconditioner the constrained CG uses (``operator.inverse_multiplier``). Load control adds the
   approach as unknown and ``mean(p) = P``. It starts from the non-adhesive state of the scene (or the
   warm start). The Maugis step is a narrow ramp (:data:`contactlib.model.adhesion.MAUGIS_RAMP`), so Newton
   sees its edge move. A strong or short-ranged law makes the first Newton steps wild (the active set
   swings by thousands of points on a rough surface); when a solve stalls it is restarted by
   continuation in the range (:data:`RANGES`, from its own start), and if that stalls too, from the
   non-adhesive state by continuation in the work of adhesion (``w / 16`` first, doubled after each
   converged stage, bisected back after a failed one: :func:`_continuation`). All Newton solves of one solve
   share one bound on their GMRES iterations (:data:`NEWTON_WORK`), so that a failure comes back in about a minute,
   not many. A warm start is a state on the branch a path follows: one that already holds comes back as it is, and
   one whose continuation in the range is lost at a stage stops there (:data:`LOST_STAGE`), unconverged, for the
   path's own fallbacks (:func:`contactlib.adhesion_curve`: midpoints, then the cold and open starts).

A Maugis step along a penetration path (a warm start given with its approach) is first tried by Newton at the law
itself, briefly (:data:`SHORT_KRYLOV`): from the last state when loading, from the frozen traction's first attempt
when unloading; only where that try fails does the step go the way above (and not at all in a narrow zone whose law
may yet be widened, where it failed). On issue 38's sphere on 512^2 a converging try costs 2-4 s against about 7 s
for the continuation in the range it replaces. A cold Maugis solve tries it before the frozen-traction continuation's
last stage.

A Maugis law whose process zone the grid does not resolve is solved as :mod:`.cohesive_law` regularises it (its ramp
widened, its zone floored at :data:`.cohesive_law.ZONE_FLOOR` elements). There, and wherever the zone spans fewer
than :data:`NARROW_ZONE` elements, the frozen traction's contact edge creeps an element in 40-100 rounds, and Newton
at the law itself stalls: after the first frozen-traction attempt the solve goes straight to Newton's continuation
in the range, from that attempt's best state. Newton moves the contact edge where the rounds creep, but near the
answer its steps can flip the edge's active set back and forth (no halving then helps); it stops there, and the
frozen traction, whose rounds do not flip, finishes from its best state. Which of two nearby answers the last stage
reaches turns on how inexact its steps are, so it is tried at two GMRES forcings (:data:`LAST_STAGE_FORCINGS`).
Issue 38's sphere, non-periodic, lambda 3.5-10: 5.2-5.8x the plain solve on 256^2 against 18-29x before these
changes; 8.6-9.5x on 512^2 (the grid's law: :data:`.cohesive_law.RAMP_GAIN`; at lambda 3.5, a resolved zone, the
frozen traction's continuation finished by a short Newton try, :data:`SHORT_KRYLOV`; ``benchmarks/bench_maugis.py``).

A solve that does not meet ``tol`` comes back ``converged=False``. The residual is scale-free: the mean
``|phi| / c``, the interpenetration and the repulsive traction's weighted mean gap (``sum |p_r| |g| / sum |p_r|``,
the weights floored at ``sigma_0 + |P|`` a point) over the rms height, the load error over ``sigma_0 + |P|``, and
the law's own error over the tractions present (:meth:`.cohesive_newton.CohesiveNewton.law_term`), which the
window's size and roughness do not dilute.
The third is the non-adhesive solvers' complementarity term: ``|phi| / c`` alone weighs a traction error by what it
would displace one element, and let a state with no contact through at tol 1e-3.
The interpenetration is the mean one for the frozen traction, as for the non-adhesive solvers (whose
answers at ``tol`` 1e-8 leave a largest interpenetration of a few 1e-8 of the rms height), and the
largest one for Newton, whose inexact steps can leave a few points far off with a small mean (a 1D
profile of 8192 points stopped 9 elements short of the contact width on the mean).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from ...model.adhesion import process_zone_length
from .cohesive_frozen import MAX_ROUNDS, STALL_ROUNDS, FrozenTraction
from .cohesive_law import grid_law
from .cohesive_newton import FORCING, GMRES_ITERATIONS, CohesiveNewton
from ..state import ContactState

MAX_NEWTON = 60
"""Default bound on the Newton iterations of one solve (one range)."""

NEWTON_WORK = 2**28
"""Bound on the GMRES iterations of every Newton solve of one cohesive solve together (its continuations'
included), times the points of the grid (4096 iterations at 256^2, 16,384 at 128^2; the adhesion tests use at most
8000 on 64^2). A non-periodic Maugis sphere at lambda 5 on 256^2 (1.7 elements across the process zone) raised
after 246 s and 28,400 GMRES iterations without it; with it, after 40 s, its frozen-traction continuation included
(0.74 s for the non-adhesive solve, loaded 2-core machine)."""

NEWTON_KRYLOV_FLOOR = 2 * GMRES_ITERATIONS
"""The least GMRES iterations that bound gives a solve, whatever its grid (two Newton steps' worth; the adhesion
tests' 512^2 Newton solve takes 87). Issue 38's Maugis sphere at lambda 5 on 512^2 (3.4 elements across the zone)
raised after 482 s with twice this floor on the loaded machine (three solves at once): most of it in Newton."""

NARROW_ZONE = 4.0
"""A Maugis process zone ``pi E* w / (4 sigma_0^2)`` narrower than this many spacings is solved from the first
frozen-traction attempt straight through Newton's continuation in the range (:data:`RANGES`), without the
frozen-traction continuation or Newton at the law itself first: on issue 38's sphere (non-periodic, 256^2 over a
quarter of its radius, approach 0.002) at lambda 3.5-10 (3.5-1.7 spacings, the zone floored below 1.7) that took
6.4-7.9x the plain solve against 18-29x (``benchmarks/bench_maugis.py``)."""

RANGES = (8.0, 4.0, 2.0, 1.0)
"""Range multipliers of the first continuation a stalled solve restarts with (from its own start)."""

LAST_STAGE_FORCINGS = (5e-2, FORCING)
"""The GMRES forcing terms (:data:`.cohesive_newton.FORCING`) of the tries at the range's last stage, the law itself,
each from the stage before and finished by the frozen traction where Newton stops near the answer. That stage is
where a narrow zone's contact edge moves its last rings: at ``FORCING`` its first step's GMRES stagnated (204
iterations of 273 on issue 38's sphere at lambda 10 on 512^2), and which of two nearby answers Newton's next steps
reach turns on how inexact that step is, for every forcing tried (0.01-0.1; chaotic in the scene). A second try
with another forcing then lands where the first did not: issue 38's sphere on 384^2 at lambda 5 (approach 0.002) and
10 (approach 0.001) raised after 35 s at ``FORCING`` alone, and converge now in 3-4 s; over 17 scenes (256^2 to
512^2, lambda 3.5-10, approaches 0.001 and 0.002) every one converges, 6-17x the plain solve, 9x the median
(``benchmarks/bench_maugis.py``)."""

SHORT_KRYLOV = 150
"""GMRES iterations of a short try at the law itself (Newton, from a state near the answer). Two places: a Maugis step
along a penetration path, from the last state when loading (the contact grows) and from the frozen traction's first
attempt when unloading (from the last state itself the first system of an unloading step did not converge); and a
cold Maugis solve's frozen-traction continuation, before its last stage, from the stage before. Those that fail are cut
here or by :data:`SHORT_FIRST_KRYLOV`, and the solve goes on as before. On issue 38's sphere on 512^2 the converging
path tries took 63-137 (9-17 Newton steps, 2-4 s, against about 7 s for the continuation in the range), and the cold
solve at lambda 3.5 took 52 (5 steps, 1.2 s; the last frozen stage there took 50-100 rounds, 4-11 s). Paths of 13
states (``benchmarks/bench_maugis.py --path 7``, ``benchmarks/RESULTS.md`` "After 8b9df0c"): 70 s at lambda 3.5 against
113 s, 86 s at lambda 7 against 98 s, 133 s at lambda 10 against 107 s (that path's first and last states, where the
law jumps in, go the long way either way; the machine was slower in this run: the plain solve 0.87 s against 0.68 s);
the single solve at lambda 3.5: 6.5 s against 10 s. With the first state of the lambda-10 path unloaded in one step
(:func:`contactlib.adhesion_curve`, "After 17cf38f"): every single solve on 512^2 8.6-9.5x, every path 8.0-9.6x per
state."""

SHORT_FIRST_KRYLOV = 40
"""GMRES iterations of a short try's first Newton step: where its system does not converge within them the start is
too far for a short try (on issue 38's sphere on 512^2 the tries that converged took 6-31 there, those that failed
stagnated to 200)."""

SHORT_FINISH = 1e-4
"""A short try that stops above ``tol`` but within this residual is finished by the frozen traction
(:func:`solve_cohesive`'s ``finished``): on issue 38's sphere at lambda 10 on 512^2 two loading tries stopped at 1.4e-5
and 2e-5, a step took 5-9 s more without the finish. At 1e-3 the finishes that failed cost 100 rounds (14 s); with a
stall bound of 12 or 20 rounds on them, finishes that converge in 26-41 rounds were cut (the lambda-10 path: 146-150 s
against 120-128 s)."""

LOST_STAGE = 1e-4
"""A warm-started solve whose continuation in the range leaves an intermediate stage above this residual stops there,
unconverged. On issue 38's sphere on 512^2 the parent's paths at lambda 7 and 10 (13 states each) had 5 warm steps
whose stages missed by 1.1e-6 to 6.9e-5, and every one then converged; the 3 whose stages missed by 2.7e-3 to 7.3e-2
all failed, after 46-108 s of the later stages (a sphere snapping in from its open state: the path then reached the
state through midpoints). Such a step now fails in 2-5 s."""

FIRST_FRACTION = 1.0 / 16
"""The fraction of the work of adhesion a stalled solve's continuation starts from."""

STAGES = 16
"""Bound on the Newton solves of that continuation."""

FROZEN_RANGES = (2.0, np.sqrt(2.0), 1.0)
"""Range multipliers of the frozen-traction continuation a stalled frozen traction restarts with, before Newton
(:func:`_frozen_continuation`). A non-periodic Maugis sphere at lambda 3.58 (256^2 over a quarter of its radius,
3.4 elements across the process zone, the approach 0.002 R): the frozen traction stalled after 11 rounds and
Newton then failed after 137 s (14,500 GMRES iterations); through this continuation it converges cold in 36, 6
and 22 rounds, 4.3 s against 1.0 s for the non-adhesive solve (loaded 2-core machine), to residual 1.2e-7."""

FROZEN_LOOSE_TOL = 1e-4
"""The tolerance of the continuation's intermediate stages: only a start for the next."""

FROZEN_STALL_ROUNDS = MAX_ROUNDS
""":data:`.cohesive_frozen.STALL_ROUNDS` of the continuation's stages, whose only bound is
:data:`.cohesive_frozen.MAX_ROUNDS`: there the contact edge moves an element every few rounds, with the residual flat
between (a Maugis sphere at lambda 1.8, 4 elements across the zone at lambda 3.6: 42 rounds from 3e-2 to 1e-5, flat over
4-7 rounds at a time)."""

FROZEN_FINAL_STALL_ROUNDS = STALL_ROUNDS
""":data:`.cohesive_frozen.STALL_ROUNDS` of the continuation's last stage where the grid's law is regularised (a process
zone of fewer than about 2 elements, :mod:`.cohesive_law`): there its contact edge creeps an element in 40-100 rounds
(issue 38's sphere on 256^2 at lambda 5: from 26,909 to 27,713 closed points in 100 rounds), and Newton, started from
the stage's best state, converges in 5-13 steps (3.5-4.3 s CPU on 256^2 at lambda 3.5-10 against 6.3-7.2 s with
:data:`FROZEN_STALL_ROUNDS`)."""

def solve_cohesive(
    operator,
    heights: np.ndarray,
    *,
    adhesion,
    mean_pressure: float | None = None,
    penetration: float | None = None,
    tol: float = 1e-8,
    max_iter: int = MAX_NEWTON,
    initial_pressure: np.ndarray | None = None,
    initial_penetration: float | None = None,
    solve_repulsive: Callable[..., ContactState] | None = None,
    report: dict | None = None,
) -> tuple[ContactState, np.ndarray]:
    """Adhesive contact of a rigid surface with a cohesive law.

    Parameters
    ----------
    operator : Compliance
        The body's normal compliance.
    heights : ndarray
        Rigid surface heights [length]; higher points touch first.
    adhesion : contactlib.Adhesion
        A cohesive law (``"maugis"`` or ``"exponential"``).
    mean_pressure, penetration : float
        Exactly one: the applied mean traction [pressure], adhesive part included (may be negative),
        or the approach from first contact of the highest point [length] (may be negative).
    tol : float
        Target of the scale-free residual (module docstring).
    max_iter : int
        Bound on the Newton iterations per range.
    initial_pressure, initial_penetration : optional
        Warm start: the total traction [pressure] (and, load control, the approach) of a neighbouring
        state, e.g. the previous point of a path (module docstring: one that holds is returned as it is).
    solve_repulsive : callable, optional
        ``solve_repulsive(heights, mean_pressure=, penetration=, tol=, max_iter=, initial_pressure=)``: the
        scene's non-adhesive constrained solver, for a cold start.
    report : dict, optional
        Receives ``"law"``: the law solved (:class:`.cohesive_law.GridLaw`; its ramp may have been widened on the
        way, :meth:`~.cohesive_law.GridLaw.widened`).

    Returns
    -------
    (ContactState, ndarray)
        The state (``pressure`` the total traction; frozen traction: ``iterations`` the inner CG iterations,
        ``outer_iterations`` the rounds; Newton: ``iterations`` the Newton steps, ``outer_iterations`` the
        GMRES iterations, both over every Newton solve, the continuations' failed stages included; Newton finished
        by the frozen traction (``"cohesive-newton+frozen-traction"``): Newton's counts; ``solver`` names the
        method) and the repulsive part ``p_r`` [pressure].
    """
    load_control = mean_pressure is not None
    adhesion = grid_law(adhesion, operator)  # Maugis' law as the grid resolves it (.cohesive_law)
    p = None if initial_pressure is None else np.array(initial_pressure, dtype=float)
    delta = initial_penetration if load_control else penetration
    result = None
    # a narrow Maugis zone: from the first frozen-traction attempt straight to Newton's continuation in the range
    narrow = adhesion.model == "maugis" and (process_zone_length(adhesion, operator.E_star)
                                             < NARROW_ZONE * max(operator.grid.spacing))
    # a Maugis step along a penetration path (a warm start with its approach): +1 loading, -1 unloading, else 0. Not
    # in a narrow zone whose law may yet be widened (.cohesive_law.GridLaw.widened): the try at the law as asked failed
    # on every step of issue 38's sphere on 256^2 at lambda 3.5 (gain 0.51), a path of 18 s against 11 s
    path_step = 0.0
    if (adhesion.model == "maugis" and p is not None and not load_control and initial_penetration is not None
            and not (narrow and adhesion.widened() is not None)):
        path_step = float(np.sign(penetration - initial_penetration))
    method = "cohesive-frozen-traction"
    spent = [0, 0]  # Newton steps and GMRES iterations of every Newton solve: the failed ones' are reported too

    krylov_budget = max(NEWTON_WORK // heights.size, NEWTON_KRYLOV_FLOOR)

    def newton(law, p, delta, forcing=FORCING, steps=max_iter, krylov=None, first_krylov=None):
        # every Newton solve draws on one bound of GMRES iterations
        left = krylov_budget - spent[1]
        solved = CohesiveNewton(operator, heights, law, mean_pressure, penetration, tol, steps,
                                krylov=left if krylov is None else min(krylov, left), forcing=forcing,
                                first_krylov=first_krylov)(p, delta)
        spent[0], spent[1] = spent[0] + solved[4], spent[1] + solved[5]
        return solved

    def finished(result):
        """``result``, or where Newton stopped near the answer (its steps flipping the contact edge's active set) the
        frozen traction's, whose rounds do not flip, from Newton's best state (issue 38's sphere at lambda 5 on 512^2:
        11 rounds from 1.7e-5)."""
        nonlocal method
        if result[-1] or solve_repulsive is None or not np.isfinite(result[6]):
            return result
        finish = FrozenTraction(operator, heights, adhesion, mean_pressure, penetration, tol, solve_repulsive,
                                 stall_rounds=FROZEN_STALL_ROUNDS)(result[0], result[1])
        if finish is None or not finish[-1]:
            return result
        method = "cohesive-newton+frozen-traction"
        return (*finish[:4], result[4], result[5], *finish[6:])

    def short_try(p, delta):
        """A short try at the law itself (:data:`SHORT_KRYLOV`), finished by the frozen traction from
        within :data:`SHORT_FINISH`; None where it does not converge."""
        nonlocal method
        solved = newton(adhesion, p, delta, krylov=SHORT_KRYLOV, first_krylov=SHORT_FIRST_KRYLOV)
        if not solved[-1] and solved[6] <= SHORT_FINISH:
            solved = finished(solved)
        if not solved[-1]:
            return None
        if method == "cohesive-frozen-traction":
            method = "cohesive-newton"
        return solved

    if path_step > 0.0:  # loading: Newton at the law straight from the last state
        result = short_try(p, delta)
    if result is None and solve_repulsive is not None:
        # cold, its first round is the non-adhesive solve, to a loose tolerance
        result = FrozenTraction(operator, heights, adhesion, mean_pressure, penetration, tol,
                                 solve_repulsive)(p, delta)
        if path_step < 0.0 and result is not None and not result[-1] and np.isfinite(result[6]):
            # unloading: Newton at the law from the frozen traction's first attempt
            result = short_try(result[0], result[1]) or result
        if result is not None and not result[-1] and np.isfinite(result[6]) and not narrow:
            result = _frozen_continuation(operator, heights, adhesion, mean_pressure, penetration, tol,
                                          solve_repulsive, p, delta, result,
                                          short_try if adhesion.model == "maugis" and p is None else None)
    if result is None or not result[-1]:  # the frozen-traction iteration stalled: semi-smooth Newton
        method = "cohesive-newton"
        wider = adhesion.widened()
        if wider is not None:  # a ramp whose points cycle (gain above RAMP_GAIN): from here on, the wider one
            adhesion = wider
        if adhesion.regularised and result is not None and np.isfinite(result[6]):
            p, delta = result[0], result[1]  # an unresolved zone: the frozen traction's best state, near the answer
        elif p is None:
            p, delta = _cold_start(operator, heights, adhesion, mean_pressure, penetration, solve_repulsive)
        if delta is None:
            delta = 0.0
        if not narrow:
            result = newton(adhesion, p, delta)
        elif initial_pressure is not None:
            # a narrow zone's warm start is measured at the law, no step taken: one that holds already (a path's open
            # state out of the law's reach) is the answer, which the continuation's wider ranges would pull into
            # contact
            result = newton(adhesion, p, delta, steps=0)
    if result is None or not result[-1]:  # stalled: continuation in the range (8, 4, 2, 1 times), stage to stage
        start, (p_c, d_c) = result, (p, delta)
        for factor in RANGES[:-1]:
            result = newton(adhesion.replace(range=adhesion.range * factor), p_c, d_c)
            if initial_pressure is not None and not result[-1] and result[6] > LOST_STAGE:
                result = start  # a warm start lost at a stage: the path's own fallbacks are cheaper (LOST_STAGE)
                break
            p_c, d_c = result[0], result[1]
        else:
            for forcing in LAST_STAGE_FORCINGS:  # the law itself: each try from the last stage, finished if need be
                result = finished(newton(adhesion, p_c, d_c, forcing))
                if result[-1]:
                    break
    if not result[-1] and initial_pressure is None:
        # still stalled: continuation in the work of adhesion from the cold start. Not from a warm start: a path
        # (contactlib.adhesion_curve) tries the cold start itself next, and ran this continuation twice a failed step
        result = _continuation(newton, adhesion,
                               *_cold_start(operator, heights, adhesion, mean_pressure, penetration, solve_repulsive))
    p, delta, g, p_r, iterations, krylov, residual, converged = result
    if report is not None:
        report["law"] = adhesion
    if method.startswith("cohesive-newton"):  # the frozen traction's finishing rounds are not counted
        iterations, krylov = spent
    displacement = g - (heights.max() - heights) + delta
    state = ContactState(pressure=p, gap=g, displacement=displacement, penetration=float(delta),
                         mean_pressure=float(p.mean()), iterations=iterations, residual=float(residual),
                         converged=bool(converged), solver=f"{method} ({adhesion.model})",
                         outer_iterations=krylov)
    return state, p_r


def _frozen_continuation(operator, heights, adhesion, mean_pressure, penetration, tol, solve_repulsive, p, delta,
                         stalled, short_try):
    """The frozen traction along the ranges :data:`FROZEN_RANGES` (times the law's), from ``(p, delta)``, each stage
    warm-started from the last one's state, the intermediate ones to :data:`FROZEN_LOOSE_TOL` and every stage given
    :data:`FROZEN_STALL_ROUNDS` before its stall check. A longer range is a smaller Maugis parameter (the same work,
    a lower peak stress): a longer process zone, which the fixed point resolves in few rounds, and a start for the
    next stage whose contact edge is already within an element or two of its place. Before the last stage (the law
    itself), ``short_try(p, delta)`` (Newton at the law, :data:`SHORT_KRYLOV`; None: none) from the stage before:
    where its answer converges it is returned. A cold Maugis solve only: from a warm start on a rough 64^2 surface
    (exponential law) Newton left the branch the path was on (the unloading state came back with the loading state's
    contact, 0.236 against 0.245), and a path's Maugis steps have their own try first. Else the last stage's result
    (its ``iterations`` and rounds those of every stage), or ``stalled`` (the first attempt's) where a stage unloads
    the contact or none gets closer than it."""
    iterations, rounds, result = stalled[4], stalled[5], None
    for factor in FROZEN_RANGES:
        last = factor == FROZEN_RANGES[-1]
        law = adhesion if last else adhesion.replace(range=adhesion.range * factor)
        if last and result is not None and short_try is not None:
            # the last stage's edge creeps an element every few rounds (issue 38's sphere on 512^2 at lambda 3.5:
            # 50-100 rounds, 4-11 s), where Newton from the stage before converged in 5 steps (1.2 s)
            tried = short_try(p, delta)
            if tried is not None:
                return tried
        stage = FrozenTraction(operator, heights, law, mean_pressure, penetration,
                                tol if last else max(tol, FROZEN_LOOSE_TOL), solve_repulsive,
                                stall_rounds=FROZEN_FINAL_STALL_ROUNDS if last and adhesion.regularised
                                else FROZEN_STALL_ROUNDS)(p, delta)
        if stage is None or not np.isfinite(stage[6]):
            return stalled
        iterations, rounds = iterations + stage[4], rounds + stage[5]
        p, delta, result = stage[0], stage[1], stage
    if result is None or result[6] > stalled[6]:
        return stalled
    return (*result[:4], iterations, rounds, *result[6:])


def _continuation(newton, adhesion, p, delta):
    """Newton (``newton(law, p, delta)``) along ``w -> f w``, ``f`` from :data:`FIRST_FRACTION` to 1: doubled after a
    converged stage, moved halfway back towards the last converged one after a failed stage (at most
    :data:`STAGES`)."""
    done, f = 0.0, FIRST_FRACTION
    for _ in range(STAGES):
        trial = newton(adhesion.replace(work=adhesion.work * f), p, delta)
        if trial[-1]:
            p, delta, done = trial[0], trial[1], f
            if f == 1.0:
                return trial
            f = min(1.0, 2.0 * f)
        else:
            f = 0.5 * (done + f)
    # the stages ran out short of w: a last try at w itself from the nearest converged stage. Never the stage's own
    # state, whose law is not the user's: a rough 64^2 state of the quick workflow came back converged at 0.97 w
    # (its open points 2.5 % short of the law's tension), and from that start w converged in 21 steps
    return newton(adhesion, p, delta)


def _cold_start(operator, heights, adhesion, mean_pressure, penetration, solve_repulsive):
    """The non-adhesive state at the same approach (or at the load, if compressive): contact first."""
    if solve_repulsive is None:
        return np.zeros_like(heights), (penetration if penetration is not None else 0.0)
    if penetration is not None:
        state = solve_repulsive(heights, mean_pressure=None, penetration=float(penetration))
        return state.pressure, penetration
    load = max(float(mean_pressure), 0.0)
    if load == 0.0:  # under tension: start from the contact of the adhesive stress itself
        load = adhesion.peak_stress * 1e-3
    state = solve_repulsive(heights, mean_pressure=load, penetration=None)
    return state.pressure, state.penetration
