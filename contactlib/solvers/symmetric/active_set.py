"""The seed paper's active-set scheme, for small grids and as an independent cross-check.

Seed 2, section 2: fix the penetration, take the bearing area (points of interpenetration) as
the trial contact set, solve ``L_cc p_c = interference_c`` on that set only with Gauss-Seidel,
delete points of negative pressure, add points that interpenetrate, repeat until the set is
stable. Load control wraps it in a bracketed root search on the penetration.
"""

from __future__ import annotations

import numpy as np
from scipy.linalg import lu_factor, lu_solve, solve_triangular
from scipy.optimize import brentq

from ..state import ContactState, contact_residual, height_scale

MAX_POINTS = 8192


def _gauss_seidel(A: np.ndarray, b: np.ndarray, x: np.ndarray, *, rtol: float = 1e-14, max_sweeps: int = 5_000):
    """Gauss-Seidel sweeps ``(D + L) x_new = b - U x`` as triangular solves (A symmetric positive definite)."""
    lower = np.tril(A)
    upper = np.triu(A, 1)
    bnorm = np.linalg.norm(b) or 1.0
    for _ in range(max_sweeps):
        x = solve_triangular(lower, b - upper @ x, lower=True, check_finite=False)
        if np.linalg.norm(A @ x - b) <= rtol * bnorm:
            break
    return x


def _solve_fixed_penetration(operator, hp, penetration, scale, max_sets):
    flat_hp = hp.ravel()
    active = np.flatnonzero(flat_hp + penetration > 0)
    p = np.zeros(hp.size)
    n_sets, settled = 0, False
    for n_sets in range(1, max_sets + 1):
        if operator.periodic and active.size == hp.size:
            raise ValueError("method='active-set': full contact in a periodic window (load undetermined); use method='cg'")
        if active.size == 0:
            p[:] = 0.0
            settled = True
            break
        A = operator.matrix(active)
        x0 = p[active]
        p[:] = 0.0
        if np.array_equal(A, A.T):
            p[active] = _gauss_seidel(A, flat_hp[active] + penetration, x0)
        else:  # a sliding viscoelastic body: Gauss-Seidel needs symmetry, LU does not
            p[active] = lu_solve(lu_factor(A, check_finite=False), flat_hp[active] + penetration,
                                 check_finite=False)
        gap = (operator(p.reshape(hp.shape)) - hp - penetration).ravel()
        keep = active[p[active] > 0]
        outside = np.ones(hp.size, dtype=bool)
        outside[active] = False
        enter = np.flatnonzero((gap < -1e-14 * scale) & outside)
        new_active = np.union1d(keep, enter)
        if np.array_equal(new_active, active):
            settled = True
            break
        p[np.setdiff1d(active, keep)] = 0.0
        active = new_active
    p = np.maximum(p, 0.0).reshape(hp.shape)
    u = operator(p)
    gap = u - hp - penetration
    return p, u, gap, n_sets, settled


def solve_active_set(
    operator,
    heights: np.ndarray,
    *,
    mean_pressure: float | None = None,
    penetration: float | None = None,
    tol: float = 1e-8,
    max_iter: int = 200,
) -> ContactState:
    """Active-set + Gauss-Seidel solve (``operator`` is a :class:`~contactlib.model.operators.Compliance`, or any
    object with ``periodic``, ``matrix(indices)`` and ``__call__(pressure)``; a non-symmetric matrix is
    solved by LU instead of Gauss-Seidel).

    ``max_iter`` bounds the number of contact-set updates per penetration. Grids above
    ``MAX_POINTS`` elements are refused: the method builds dense matrices.

    Converged only if the last contact set repeated and, under load control, the mean pressure is the
    load: the residual is the larger of the contact residual and the load's relative error. (On a strongly
    non-symmetric matrix the set can cycle, and the mean pressure then jumps with the penetration: the root
    search closes on a jump, not a root, e.g. 0.004 for a load of 0.5 at E_inf/E0 = 1000, V tau q0 = 1e-3.)
    """
    if heights.size > MAX_POINTS:
        raise ValueError(f"method='active-set' builds dense matrices: grid of {heights.size} points exceeds {MAX_POINTS}")
    hp = heights - heights.max()
    scale = height_scale(heights)
    total_sets = 0
    settled = True

    def at(delta):
        nonlocal total_sets, settled
        p, u, g, n, settled = _solve_fixed_penetration(operator, hp, delta, scale, max_iter)
        total_sets += n
        return p, u, g

    if mean_pressure is None:
        delta = float(penetration)
    else:
        def excess(delta):
            return float(at(delta)[0].mean()) - mean_pressure
        # bracket from below: near full contact the dense systems become slow and ill-conditioned
        limit = float(-hp.mean()) * (1 - 1e-9) if operator.periodic else np.inf
        lo, hi = 0.0, min(0.25 * scale, limit)
        for _ in range(64):
            if excess(hi) >= 0:
                break
            if hi >= limit:
                raise ValueError("method='active-set': mean_pressure at or beyond full contact; use method='cg'")
            lo, hi = hi, min(1.5 * hi, limit)
        delta = brentq(excess, lo, hi, xtol=1e-15 * max(hi, 1e-300), rtol=4 * np.finfo(float).eps, maxiter=200)
    p, u, g = at(delta)
    residual = contact_residual(p, g, scale)
    if mean_pressure is not None and mean_pressure > 0:
        residual = max(residual, abs(float(p.mean()) - mean_pressure) / mean_pressure)
    return ContactState(
        pressure=p, gap=g, displacement=u, penetration=float(delta), mean_pressure=float(p.mean()),
        iterations=total_sets, residual=residual, converged=bool(settled and residual <= tol), solver="active-set",
    )
