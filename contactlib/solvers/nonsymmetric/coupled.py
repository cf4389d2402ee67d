"""Contact with a non-symmetric compliance ``K + W``: symmetric part ``K`` definite, skew part ``W``.

Coulomb friction ``mu p`` along the sliding direction adds to the normal displacement ``W p``, the
normal-tangential block of the Green's tensor: odd in ``q``, antisymmetric in real space
(:class:`contactlib.model.operators.Coupling`). A viscoelastic kernel in steady sliding has the same
structure (its loss part is odd in ``q . V``). The complementarity problem

    p >= 0,   g = (K + W) p - h - d >= 0,   p g = 0

has a unique solution whenever ``K`` is positive definite, however large ``W``.

It is solved as a fixed point on the skew part, accelerated: for a given pressure ``x`` the
symmetric problem with the heights ``h - W x`` is today's constrained CG (the fast frictionless
loop, unchanged: :func:`.ccg.solve_polonsky_keer` or, for periodic displacement control,
:func:`.dual.solve_periodic_displacement`), whose answer ``y = F(x)`` is the next iterate. In the
``K``-norm the map contracts by ``rho = max_q |W(q)| / K(q)`` (a symmetric LCP's solution is a
``K``-projection: non-expansive), which is at most ``mu (1 - 2 nu) / (2 (1 - nu)) <= 1/2`` on a
half-space but reaches ``1.5 mu / (q h)`` on a thin incompressible confined layer, where the plain
fixed point diverges. On a fixed contact set the map is linear with an imaginary spectrum
(``K^-1 W`` is similar to a skew matrix), so Anderson mixing (Walker & Ni, SIAM J. Numer. Anal. 49,
2011: GMRES on the fixed point) converges where plain or damped iteration cannot: its few slow
directions are the long waves where ``rho > 1``. Where ``rho`` is large (above
:data:`contactlib.model.bodies.SHIFT_ABOVE`) the body model splits differently: ``K + |W|`` (still a
symmetric definite multiplier) is the inner operator and ``W - |W|`` the outer part. At full contact
the eigenvalues of the outer map, ``(i w - |w|) / (k + |w|)``, then stay in the disc of radius
``sqrt(2)`` with real part <= 0 however large ``|w| / k``, instead of ``i w / k`` on the imaginary axis:
Anderson converges where it stalled with the plain split (q0 h = 0.1, mu = 1). Each inner solve is warm-started from the last one,
with a tolerance tightening with the outer residual, so late inner solves take a few iterations.

The residual is :func:`.contact_residual` of the true gap ``(K + W) y - h - d`` (one application of
``W`` per outer iteration), so ``tol`` means what it means for every solver.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from ..anderson import Anderson
from ..state import ContactState, contact_residual, height_scale

ANDERSON_MEMORY = 8
"""Past iterates kept by the Anderson mixing (each three fields: pressure, residual, ``W`` pressure)."""

ANDERSON_RIDGE = 1e-12
"""Relative ridge of the mixing's normal equations (:class:`.anderson.Anderson`)."""

MAX_OUTER = 300
"""Outer iterations before the solve is returned as not converged."""

STALL_OUTER = 30
"""Outer iterations without a 10 % drop of the best residual before the solve stops as not converged."""

INNER_TOL_FACTOR = 0.05
"""Inner solves stop at this fraction of the last outer residual (and at ``tol / 4`` at the latest):
inexact early solves, exact enough late ones."""


def solve_coupled(
    inner: Callable[..., ContactState],
    coupling: Callable[[np.ndarray], np.ndarray],
    heights: np.ndarray,
    *,
    mean_pressure: float | None = None,
    penetration: float | None = None,
    tol: float = 1e-8,
    max_iter: int = 10_000,
    initial_pressure: np.ndarray | None = None,
    memory: int = ANDERSON_MEMORY,
    max_outer: int = MAX_OUTER,
) -> ContactState:
    """Pressure under ``heights`` [length] on a body with compliance ``K + W``.

    Parameters
    ----------
    inner : callable
        ``inner(heights, mean_pressure=, penetration=, tol=, max_iter=, initial_pressure=)``: the symmetric
        contact solver of ``K`` (returns a :class:`ContactState`; penetration from first contact).
    coupling : callable
        ``coupling(pressure) -> W pressure`` [length]: the skew part.
    mean_pressure, penetration : float
        Exactly one, as for :func:`.ccg.solve_polonsky_keer`.
    tol : float
        Target of the residual of the coupled problem.
    max_iter : int
        Bound on the inner iterations of each inner solve; the outer loop stops at ``max_outer``.
    initial_pressure : ndarray, optional
        Warm start.

    Returns
    -------
    ContactState
        ``iterations`` counts inner iterations over all outer ones, ``outer_iterations`` the inner
        solves; ``converged`` is False (with the residual reached) when ``max_outer`` passes or the
        outer residual stalls.
    """
    load_control = mean_pressure is not None
    scale = height_scale(heights)
    top = float(heights.max())
    x = np.zeros_like(heights) if initial_pressure is None else np.maximum(initial_pressure, 0.0)
    Wx = coupling(x)
    warm = None if initial_pressure is None else x
    mixer = Anderson(memory, ridge=ANDERSON_RIDGE)  # unit step: the next input y_k - dY gamma, W y with it
    total, residual, best, best_k = 0, np.inf, np.inf, 0
    inner_tol = max(tol, 1e-4) if initial_pressure is None else tol
    state = None
    for k in range(1, max_outer + 1):
        effective = heights - Wx
        shift = float(effective.max()) - top  # the inner solver measures its approach from its own top
        inner_state = inner(effective, mean_pressure=mean_pressure,
                            penetration=None if load_control else penetration + shift,
                            tol=inner_tol, max_iter=max_iter, initial_pressure=warm)
        total += inner_state.iterations
        y = inner_state.pressure
        Wy = coupling(y)
        gap = inner_state.gap + (Wy - Wx)
        residual = contact_residual(y, gap, scale)
        state = ContactState(
            pressure=y, gap=gap, displacement=inner_state.displacement + Wy,
            penetration=inner_state.penetration - shift, mean_pressure=inner_state.mean_pressure,
            iterations=total, residual=residual, converged=bool(residual <= tol and inner_state.converged),
            solver=f"coupled-anderson({inner_state.solver})", outer_iterations=k)
        if state.converged:
            return state
        if residual < 0.9 * best:
            best, best_k = residual, k
        elif k - best_k >= STALL_OUTER:  # no progress: round-off floor of the inner solver, or a stall
            break
        x, Wx = mixer.next(y, y - x, Wy)
        warm = y
        inner_tol = max(tol / 4, min(inner_tol, INNER_TOL_FACTOR * residual))
    return state
