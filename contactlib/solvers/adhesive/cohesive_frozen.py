"""The frozen-traction iteration of cohesive contact: the first method of :mod:`.cohesive` (its module docstring says
when each method runs), with the adhesive traction held fixed a round and the scene's own non-adhesive solver run on
the heights it shifts."""

from __future__ import annotations

import numpy as np

from . import sweeps
from ..anderson import Anderson
from ..symmetric.ccg import solve_polonsky_keer
from .cohesive_newton import CohesiveNewton
from .cohesive_rounds import Rounds

ANDERSON_DEPTH = 5
"""Rounds of the frozen-traction iteration that Anderson mixing combines (2-8 took the same rounds on the
benchmark scene; without mixing the Maugis law took 22 rounds instead of 14)."""

ANDERSON_BETA = 1.3
"""Mixing parameter of the Anderson step, ``x + beta f - sum gamma (dx + beta df)`` (``f = T(x) - x``): 1 is
the plain step. On the benchmark scene (``benchmarks/bench_adhesion.py``, iterations / rounds, exponential and
Maugis) 256^2: 0.5 45/15 and 57/19, 1 39/13 and 42/14, 1.3 36/12 and 39/13, 1.5 39/13 and 39/13, 2 42/14 and
36/12; 512^2: 1 45/15 both, 1.3 42/14 both."""

ANDERSON_RIDGE = 1e-14
"""Relative ridge of the mixing's normal equations (:class:`.anderson.Anderson`)."""

MAX_ROUNDS = 100
"""Bound on the rounds of the frozen-traction iteration before the Newton solve takes over."""

INNER_ITERATIONS = 3
"""CG iterations of the primal inner solve a round (256^2 rough scene: 2 took 36-40 iterations in 18-20
rounds, 3 took 39-42 in 13-14, uncapped 66-105 in 8-12; a round's restart costs about one iteration)."""

CONTINUED = True
"""Run the rounds inside one Polonsky-Keer solve that moves its heights (:mod:`.cohesive_rounds`) where the inner
solve is that one; False restarts it each round (the dual path and an unpreconditioned CG always do)."""

STALL_ROUNDS = 4
STALL_DROP = 0.25
"""The frozen-traction iteration counts as stalled when :data:`STALL_ROUNDS` rounds have not brought the residual
below ``STALL_DROP`` times its best before them (on 2D rough scenes under load it falls 2-3x a round; where it
falls 10 % a round, as on a 1D wavy profile with a 16-element process zone, Newton is faster)."""

FIRST_INNER_TOL = 1e-2
INNER_FRACTION = 0.1
INNER_FLOOR = 0.1
"""The inner solves' tolerance: :data:`FIRST_INNER_TOL` first, then this fraction of the outer residual,
never below ``INNER_FLOOR * tol``."""


class FrozenTraction:
    """The cohesive contact as a sequence of non-adhesive ones: with the adhesive traction ``a`` frozen, the
    total traction is ``p = a + q``, ``q >= 0`` the repulsive part, and the gap ``K q + (K a + h0 - d)``: the
    scene's own constrained solver (Polonsky-Keer, or its dual) on the heights ``h - K a`` under the load
    ``P - mean(a)``. The law then gives the next traction ``a(g)``; Anderson mixing (Walker & Ni, SIAM J.
    Numer. Anal. 49, 1715-1735, 2011) of the last :data:`ANDERSON_DEPTH` rounds makes that fixed point
    converge where plain substitution oscillates (its gain ``|a'| K`` is of order 1 across the process
    zone, which is what sets the zone's length). Each inner solve is warm-started from the last ``q``,
    stopped at a tolerance that follows the outer residual down and, on the primal path, after
    :data:`INNER_ITERATIONS` iterations. The residual is that of :class:`.cohesive_newton.CohesiveNewton` with the mean
    interpenetration, on the state ``(a + q, g)`` the inner solve returns."""

    def __init__(self, operator, heights, adhesion, mean_pressure, penetration, tol, solve_repulsive,
                 stall_rounds=None):
        self.op, self.law, self.tol, self.solve = operator, adhesion, tol, solve_repulsive
        self.stall_rounds = STALL_ROUNDS if stall_rounds is None else int(stall_rounds)
        self.heights, self.load, self.penetration = heights, mean_pressure, penetration
        self.measure = CohesiveNewton(operator, heights, adhesion, mean_pressure, penetration, tol, 1)
        # the primal solver keeps its progress from a warm start, so a few iterations a round suffice; the dual
        # one (periodic displacement control) restarts from the gap of the pressure and needs its full solve
        dual = not operator.definite and mean_pressure is None
        full = dual or not operator.preconditionable  # an unpreconditioned CG (plate-like layer) crawls too
        self.cap = {} if INNER_ITERATIONS is None or full else {"max_iter": INNER_ITERATIONS}
        # where the inner solve is the preconditioned Polonsky-Keer one (what constrained_solve runs there), the
        # rounds go on inside one solve of it instead of restarting it (.cohesive_rounds)
        self.continued = CONTINUED and not full and INNER_ITERATIONS is not None

    def __call__(self, p, delta):
        law, heights = self.law, self.heights
        if p is None:  # cold: no adhesive traction yet, the inner solver's own start
            a, q = np.zeros_like(heights), None
        else:
            if delta is None:  # a warm start without its approach: the one that closes the smallest gap
                delta = float(np.min(self.op(p) + self.measure.h0))
            a = law.traction(self.op(p) + self.measure.h0 - delta)
            q = np.maximum(p - a, 0.0)
        # the traction stays within the law's, [-sigma_0, 0]; a round on a large grid wants the fused sweeps
        self.mix = Anderson(ANDERSON_DEPTH, beta=ANDERSON_BETA, bounds=(-law.peak_stress, 0.0), ridge=ANDERSON_RIDGE,
                            fused=True)
        self.image = np.empty_like(heights)  # the law's traction at the last gap
        self.inner_tol, self.history, self.rounds, self.residual = FIRST_INNER_TOL, [], 0, np.inf
        result = self._continued(a, q) if self.continued else self._restarted(a, q)
        if result is None:
            return None
        p, delta, g, iterations = result
        # the last sweep left the law's traction at g in image: the repulsive part without another evaluation
        p_r = p - self.image
        closed = np.where(p_r > self.measure.c * g, p_r, 0.0)
        return p, delta, g, closed, iterations, self.rounds, self.residual, self.residual <= self.tol

    def judge(self, p, g) -> bool:
        """One round's verdict on the state ``(p, g)``: its residual (:attr:`residual`, the law's traction at
        ``g`` in :attr:`image`), and whether to go on (not converged, not stalled, rounds left); if so the
        next inner tolerance (:attr:`inner_tol`)."""
        self.rounds += 1
        residual = self.residual = self._residual(p, g, self.image)
        if residual <= self.tol or not np.isfinite(residual) or self.rounds >= MAX_ROUNDS:
            return False
        history = self.history
        history.append(residual)
        stall = self.stall_rounds
        if len(history) > stall and min(history[-stall:]) > STALL_DROP * min(history[:-stall]):
            return False  # too slow (a contact edge that moves a few elements a round): Newton takes over
        self.inner_tol = max(min(self.inner_tol, INNER_FRACTION * residual), INNER_FLOOR * self.tol)
        return True

    def _continued(self, a, q):
        """The rounds inside one Polonsky-Keer solve (:mod:`.cohesive_rounds`): ``(p, delta, g, iterations)``,
        or None where the adhesive traction alone would carry the load."""
        shifted = self.heights - self.op(a) if q is not None else self.heights
        lift = float(shifted.max()) - float(self.heights.max())  # the solve's approach counts from there
        load = None
        if self.load is not None:
            load = self.load - float(a.mean())
            if load <= 0.0:
                return None
        rounds = Rounds(self, a, load, INNER_ITERATIONS)
        state = solve_polonsky_keer(self.op, shifted, mean_pressure=load,
                                    penetration=None if load is not None else self.penetration + lift,
                                    tol=0.0, max_iter=MAX_ROUNDS * (INNER_ITERATIONS + 1), initial_pressure=q,
                                    rounds=rounds)
        if rounds.unloaded:
            return None
        # the solve stopped where judge did, before any move: its state is the one judged (a, not yet mixed)
        return state.pressure + rounds.a, state.penetration - lift, state.gap, state.iterations

    def _restarted(self, a, q):
        """A new inner solve each round (the dual path, an unpreconditioned CG): ``(p, delta, g, iterations)``,
        or None where the adhesive traction alone would carry the load."""
        heights, top, iterations = self.heights, float(self.heights.max()), 0
        shifted = np.empty_like(heights)  # h - K a, rewritten each round (the inner solve keeps no reference)
        while True:
            self.op(a, out=shifted)
            np.subtract(heights, shifted, out=shifted)
            lift = float(shifted.max()) - top  # the approach is counted from the highest shifted point
            if self.load is not None:
                load = self.load - float(a.mean())
                if load <= 0.0:  # the adhesive traction alone carries the load: no repulsive contact left
                    return None
                inner = self.solve(shifted, mean_pressure=load, penetration=None, tol=self.inner_tol,
                                   initial_pressure=q, **self.cap)
            else:
                inner = self.solve(shifted, mean_pressure=None, penetration=self.penetration + lift,
                                   tol=self.inner_tol, initial_pressure=q, **self.cap)
            iterations += inner.iterations
            q, g, delta = inner.pressure, inner.gap, inner.penetration - lift
            p = q + a
            if not self.judge(p, g):
                return p, delta, g, iterations
            a = self.mix(a, self.image)

    def _residual(self, p, g, image):
        """:meth:`.cohesive_newton.CohesiveNewton.residual_of` (mean interpenetration) in one sweep, writing the law's
        traction at the gap ``g`` into ``image``."""
        m, law = self.measure, self.law
        code = sweeps.MAUGIS if law.model == "maugis" else sweeps.EXPONENTIAL
        phi_sum, overlap, comp, weight, traction, interacting = sweeps.law_residual(
            np.ascontiguousarray(p).ravel(), np.ascontiguousarray(g).ravel(), code, law.peak_stress, law.range,
            law.ramp, m.c, image.reshape(-1))
        residual = max(phi_sum / m.c, overlap, m.complementarity(comp, weight)) / (p.size * m.hs)
        residual = max(residual, m.law_term(phi_sum, traction, interacting))
        if m.control:
            residual = max(residual, abs(float(p.mean()) - m.load) / m.pscale)
        return residual
