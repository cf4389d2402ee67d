"""Constrained conjugate gradients for frictionless normal contact.

Polonsky & Keer (1999), doi:10.1016/S0043-1648(99)00113-1: conjugate gradients on the
current contact set, with projection onto ``p >= 0`` and re-entry of interpenetrating points
(which restarts the conjugacy). Load control fixes ``mean(p)`` and finds the rigid approach as
the mean gap offset over the contact set; displacement control fixes the approach.

Two convolutions per iteration (``K p`` and ``K t``). The loop works in place on preallocated
arrays and reduces with ``einsum`` (no BLAS threads competing with FFTW, no boolean fancy
indexing).
"""

from __future__ import annotations

from typing import Callable

import numpy as np

from .state import ContactState, contact_residual, height_scale


def _dot(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.einsum("i,i->", a.ravel(), b.ravel()))


def solve_polonsky_keer(
    apply_compliance: Callable[..., np.ndarray],
    heights: np.ndarray,
    *,
    mean_pressure: float | None = None,
    penetration: float | None = None,
    tol: float = 1e-8,
    max_iter: int = 10_000,
    initial_pressure: np.ndarray | None = None,
    self_compliance: float = 1.0,
) -> ContactState:
    """Solve for the contact pressure under load or displacement control.

    Parameters
    ----------
    apply_compliance : callable
        ``apply_compliance(pressure, out=...) -> displacement``, a linear symmetric operator.
    heights : ndarray
        Rigid surface heights [length]; higher points touch first.
    mean_pressure, penetration : float
        Exactly one: the mean pressure over the window [pressure], or the rigid approach from
        first contact of the highest point [length].
    tol : float
        Target of :func:`contact_residual`.
    initial_pressure : ndarray, optional
        Warm start (e.g. the previous point of a load path).
    self_compliance : float
        Displacement per unit pressure of one element; scales the displacement-control start.
    """
    load_control = mean_pressure is not None
    hp = heights - heights.max()  # <= 0; gap = u - hp - penetration
    scale = height_scale(heights)
    n = heights.size

    if load_control:
        p = np.full(heights.shape, float(mean_pressure)) if initial_pressure is None else initial_pressure.copy()
        p *= mean_pressure / p.mean() if p.mean() > 0 else 1.0
        if mean_pressure == 0:
            return _zero_state(heights, hp, penetration=0.0, scale=scale)
    else:
        interference = np.maximum(hp + penetration, 0.0)
        if not interference.any():
            return _zero_state(heights, hp, penetration=float(penetration), scale=scale)
        p = interference / self_compliance if initial_pressure is None else initial_pressure.copy()

    u = np.empty_like(p)
    g = np.empty_like(p)
    t = np.zeros_like(p)
    r = np.empty_like(p)
    mask = np.empty_like(p)
    G_old, restart = 1.0, True
    residual, approach = np.inf, float(penetration or 0.0)
    it = 0
    for it in range(max_iter + 1):
        apply_compliance(p, out=u)
        np.subtract(u, hp, out=g)
        np.greater(p, 0.0, out=mask, casting="unsafe")
        n_contact = mask.sum()
        if load_control:
            approach = _dot(g, mask) / n_contact
        g -= approach
        residual = contact_residual(p, g, scale)
        if residual <= tol or it == max_iter:
            break
        G = _dot(g * g, mask)
        beta = 0.0 if restart else G / G_old
        t *= beta
        t += g
        t *= mask
        G_old = G
        apply_compliance(t, out=r)
        if load_control:
            r -= _dot(r, mask) / n_contact
        denom = _dot(r, t)
        tau = _dot(g, t) / denom if denom > 0 else 1.0 / self_compliance
        p -= tau * t
        np.maximum(p, 0.0, out=p)
        # interpenetrating points without pressure re-enter the contact set
        overlap = (p == 0.0) & (g < 0.0)
        restart = bool(overlap.any())
        if restart:
            p -= tau * g * overlap
        if load_control:
            total = p.sum()
            if total <= 0:  # lost every point: restart from the highest point
                p[...] = np.where(hp == 0.0, 1.0, 0.0)
                total = p.sum()
            p *= mean_pressure * n / total

    return ContactState(
        pressure=p, gap=g, displacement=u, penetration=float(approach),
        mean_pressure=float(p.mean()), iterations=it, residual=float(residual),
        converged=bool(residual <= tol), solver="polonsky-keer",
    )


def _zero_state(heights: np.ndarray, hp: np.ndarray, *, penetration: float, scale: float) -> ContactState:
    p = np.zeros_like(heights)
    g = -hp - penetration
    return ContactState(
        pressure=p, gap=g, displacement=np.zeros_like(heights), penetration=penetration,
        mean_pressure=0.0, iterations=0, residual=contact_residual(p, g, scale), converged=True,
        solver="polonsky-keer",
    )
