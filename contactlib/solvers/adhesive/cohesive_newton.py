"""The semi-smooth Newton (primal-dual active set) solve of cohesive contact at one range: the second
method of :mod:`.cohesive`, which also lends the first its residual (:meth:`CohesiveNewton.residual_of`)."""

from __future__ import annotations

import numpy as np

from ...model.operators import Compliance
from ..krylov import gmres
from ..state import height_scale

C_SCALE = 1.0
"""The complementarity constant ``c`` in units of an element's stiffness ``pi E* / (2 dx)`` (0.1-10 gave
the same iteration counts on the Maugis sphere)."""

BACKTRACK = 6
"""Halvings of a Newton step that would multiply the residual by more than :data:`GROWTH`."""

GROWTH = 2.0

NEAR = 1e-4
"""Backtracking acts only below this residual: far from the answer the first Newton steps must be free
to move the contact a long way (a cold start at small range failed with it on)."""

STALL = 12
"""Newton iterations without halving the best residual that count as a stall."""

DIVERGED = 1e6
"""A residual this many times the start's (or not finite) ends the solve as diverged: a wild first step on a cold
start (a Maugis sphere at tol 1e-3: approach -3e21 after three steps) otherwise spent :data:`STALL` Newton steps of
up to :data:`GMRES_ITERATIONS` each on a state with no contact left (6.5 s against 0.05 s for the continuation in
the range that then converged). Converging solves met at most 430x their start's residual (at their third step).
An unconverged solve returns its best state: the continuation's next stage started from a diverged one's last (at
residual 1e23) and stalled there for 13 steps a stage (an ``adhesion_curve`` on a rough 64^2 surface with a Maugis
law: 0.05-3.3 s over tol 1e-4..1e-10, 0.8 s at the default 1e-6; now 0.2-0.4 s)."""

LAW_WEIGHT = 1e-3
"""Weight of :meth:`CohesiveNewton.law_term` in the residual: at the default ``tol`` 1e-6 the tractions may miss the law
by 0.1 % of those present, at ``tol`` 1e-8 by 1e-5. On spheres with resolved process zones the other terms had let
states through that missed it by up to 2.1e-3, one of them 2.7 % off the converged force (exponential law, 128^2
over one radius); it now stops within 0.2 %. The adhesion tests take 24.8 s instead of 22.7."""

GMRES_RESTART = 40
"""Krylov vectors a Newton step's GMRES keeps before it restarts, at least (:func:`restart_for`)."""

GMRES_BASIS = 2**25
"""Bound on the values a Newton step's Krylov basis holds (256 MiB): up to :data:`LONG_RESTART` vectors where the grid
allows it. Issue 38's Maugis sphere at lambda 10 on 512^2 (its last range stage, 30-60 GMRES iterations a step):
586 GMRES iterations and 24.7 s at 40 vectors, 314 and 18.0 s at 120."""

LONG_RESTART = 120
"""The most Krylov vectors a step keeps (:data:`GMRES_BASIS`)."""

FORCING = 1e-2
"""Relative tolerance of each Newton step's GMRES (the inexact Newton forcing term): a step need only cut the
residual's linear model a hundredfold, since the next step measures the true residual again. The parent solved each
step to ``min(1e-4, 0.1 r)`` (``r`` the scale-free residual, so 1e-7 near the answer): issue 38's Maugis spheres on
256^2 at lambda 3.5-10 took 1.2-2x as long with it (the whole solve, one process each)."""


def restart_for(points: int) -> int:
    """The GMRES restart length of a grid of ``points``: :data:`LONG_RESTART` within :data:`GMRES_BASIS`, else no
    fewer than :data:`GMRES_RESTART`."""
    return max(GMRES_RESTART, min(LONG_RESTART, GMRES_BASIS // points))

GMRES_ITERATIONS = 20 * (GMRES_RESTART + 1)
"""Operator applications a Newton step's GMRES may use (twenty restart cycles)."""


class CohesiveNewton:
    """One semi-smooth Newton solve of the cohesive contact at one range, of at most ``max_iter`` steps and
    ``krylov`` GMRES iterations (None: :data:`GMRES_ITERATIONS` a step, no bound on their sum), each step's GMRES to
    the relative residual ``forcing``. With ``first_krylov`` the solve ends, no step taken, where the first step's
    GMRES does not reach ``forcing`` within that many iterations: a start too far from the answer for a short try."""

    def __init__(self, operator, heights, adhesion, mean_pressure, penetration, tol, max_iter, krylov=None,
                 forcing=FORCING, first_krylov=None):
        self.op, self.law, self.tol, self.max_iter = operator, adhesion, tol, int(max_iter)
        self.forcing = float(forcing)
        self.krylov, self.first_krylov = krylov, first_krylov
        self.shape, self.n = heights.shape, heights.size
        self.h0 = heights.max() - heights
        self.load = mean_pressure
        self.control = mean_pressure is not None
        self.sigma0 = adhesion.peak_stress
        # an element's stiffness: the compliance at the shortest wave, 2 / (E* q_max)
        self.c = C_SCALE * operator.E_star * np.pi / (2 * min(operator.grid.spacing))
        self.hs = height_scale(heights)
        self.pscale = self.sigma0 + (abs(mean_pressure) if self.control else 0.0)
        # the contact rows' preconditioner: a zero-padded half-space's stiffness is nearly its periodic twin's on the
        # window, at a quarter of the transform (issue 38's spheres on 256^2: the same GMRES iterations, 25 % less
        # time); a layer keeps its own
        self.preconditioner = operator
        if not operator.periodic and operator.transfer is None:
            self.preconditioner = Compliance(operator.grid, E_star=operator.E_star, kernel=operator.kernel)

    def _evaluate(self, p, delta):
        return self.residual_of(p, self.op(p) + self.h0 - delta)

    def residual_of(self, p, g, largest=True):
        """``(g, p_r, active, phi, residual)`` of the traction ``p`` and its gap ``g``; the interpenetration
        term is the largest (``largest``) or the mean one."""
        p_r = p - self.law.traction(g)
        active = p_r > self.c * g
        phi = np.where(active, self.c * g, p_r)
        overlap = np.maximum(-g, 0.0)
        overlap = float(np.max(overlap)) if largest else float(np.mean(overlap))
        weights = np.abs(p_r)
        complementarity = self.complementarity(float(np.sum(weights * np.abs(g))), float(weights.sum())) / self.n
        phi_sum = float(np.sum(np.abs(phi)))
        residual = max(phi_sum / (self.n * self.c), overlap, complementarity) / self.hs
        residual = max(residual, self.law_term(phi_sum, float(np.sum(np.abs(p))),
                                               int(np.count_nonzero(g <= self.law.range))))
        if self.control:
            residual = max(residual, abs(float(p.mean()) - self.load) / self.pscale)
        return g, p_r, active, phi, residual

    def law_term(self, phi_sum: float, traction: float, interacting: int) -> float:
        """The residual's term for the law itself: ``sum |phi|`` over the tractions present (``sum |p|``, floored at
        ``sigma_0`` on every point within the range), times :data:`LAW_WEIGHT`. The other terms are means over the
        window relative to its rms height, which a small contact in a wide window dilutes: a sphere on 512^2 over 4
        radii (a process zone of 4.4 elements) came back converged at tol 1e-6 with no adhesive traction at all
        (force 0 against -4.3e-4 on a window of one radius, 21 points closed against 277)."""
        return LAW_WEIGHT * phi_sum / max(traction, self.sigma0 * max(interacting, 1))

    def complementarity(self, comp: float, weight: float) -> float:
        """``n`` times the repulsive-traction-weighted mean gap [length] from ``comp = sum |p_r| |g|`` and ``weight =
        sum |p_r|``, the weights floored at ``n (sigma_0 + |P|)``: the non-adhesive solvers' complementarity term.
        ``|phi| / c`` alone measures a traction error by the displacement it would cause on one element, which
        let through, at tol 1e-3, a state with no contact whose open points carried compressive traction (a
        rough 64^2 surface: every gap above 6 ranges, 13 % contact in the answer)."""
        return comp / max(weight, self.n * self.pscale) * self.n

    def _stiffness(self, field):
        self.preconditioner.load()[...] = field
        return self.preconditioner.convolve(inverse=True).copy()

    def __call__(self, p, delta):
        n, shape, c = self.n, self.shape, self.c
        g, p_r, active, phi, residual = self._evaluate(p, delta)
        best, best_it, krylov, it = residual, 0, 0, 0
        bound = DIVERGED * residual
        lowest = (residual, p, delta, (g, p_r, active, phi, residual))  # an unconverged solve returns its best state
        for it in range(1, self.max_iter + 1):
            if residual <= self.tol:
                it -= 1
                break
            budget = GMRES_ITERATIONS if self.krylov is None else min(GMRES_ITERATIONS, self.krylov - krylov)
            first = it == 1 and self.first_krylov is not None
            if first:
                budget = min(budget, self.first_krylov)
            if it - best_it > STALL or not residual < bound or budget <= 0:
                it -= 1  # no step taken in this pass
                break
            on = active.astype(float)
            off = 1.0 - on
            slope = self.law.traction_slope(g)

            def matvec(v):
                dp = v[:n].reshape(shape)
                dg = self.op(dp) - (v[n] if self.control else 0.0)
                rows = (on * c * dg + off * (dp - slope * dg)).ravel()
                return np.concatenate([rows, [c * dp.mean()]]) if self.control else rows

            def precondition(v):
                r = v[:n].reshape(shape)
                z = (off * r + on * self._stiffness(on * r) / c).ravel()
                return np.concatenate([z, [v[n] / c]]) if self.control else z

            rhs = -phi.ravel()
            if self.control:
                rhs = np.concatenate([rhs, [-c * (float(p.mean()) - self.load)]])
            # the set solvers' GMRES (:func:`.krylov.gmres`), from zero, to a relative residual
            step, used, _ = gmres(lambda v: (matvec(v), 0.0), precondition, rhs, np.zeros_like(rhs), 0.0,
                                  budget, restart=restart_for(n), relative=self.forcing)
            krylov += used
            if first and used >= budget:  # the first system stagnates: this start is too far for a short try
                it -= 1
                break
            # near the answer a step that multiplies the residual is cut back (halved up to BACKTRACK times): the
            # answer an active-set flip at the contact edge can throw a full step far off
            for halving in range(BACKTRACK + 1):
                trial_p = p + step[:n].reshape(shape)
                trial_d = delta + (float(step[n]) if self.control else 0.0)
                trial = self._evaluate(trial_p, trial_d)
                if trial[-1] <= GROWTH * residual or residual > NEAR:
                    break
                step = 0.5 * step
            if residual <= NEAR and trial[-1] > GROWTH * residual:
                # no halving helps: near the answer the step is no descent (the active set flips at the contact
                # edge), and taking it threw issue 38's lambda-5 sphere on 512^2 from 1.7e-5 to 0.75 in 7 steps.
                # The solve stops here, and its best state goes to the frozen traction (.cohesive)
                it -= 1
                break
            p, delta = trial_p, trial_d
            g, p_r, active, phi, residual = trial
            if residual < 0.5 * best:
                best, best_it = residual, it
            if residual < lowest[0]:
                lowest = (residual, p, delta, trial)
        if residual > self.tol and lowest[0] < residual:  # a diverged or stalled solve: the continuation that
            p, delta, (g, p_r, active, phi, residual) = lowest[1:]  # follows starts from its best state, not 1e23
        # the open rows hold the law's (tensile) traction only to the Krylov tolerance: on a non-periodic window
        # the far edge kept 1e-93 to 1e-80 of compression, read as contact cut by the window. Open rows in
        # compression get the law's traction, and the state is measured again (kept unless it is worse)
        polished = np.where(active | (p <= 0.0), p, self.law.traction(g))
        trial = self._evaluate(polished, delta)
        if trial[-1] <= max(residual, self.tol):
            p, (g, p_r, active, phi, residual) = polished, trial
        converged = residual <= self.tol
        return p, delta, g, np.where(active, p_r, 0.0), it, krylov, residual, converged
