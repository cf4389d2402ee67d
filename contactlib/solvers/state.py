"""The state every normal-contact solver returns, and the one residual they all report."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class ContactState:
    """Solution of a normal contact problem on a grid (no units attached).

    ``gap = displacement + (max(heights) - heights) - penetration`` holds pointwise.
    """

    pressure: np.ndarray
    gap: np.ndarray
    displacement: np.ndarray
    penetration: float
    mean_pressure: float
    iterations: int
    residual: float
    converged: bool
    solver: str
    outer_iterations: int = 0
    """Inner solves of a coupled (frictional) solve; 0 for the frictionless solvers."""


def height_scale(heights: np.ndarray) -> float:
    """Roughness scale used to make the residual dimensionless: rms of heights about the mean."""
    s = float(np.sqrt(np.mean((heights - heights.mean()) ** 2)))
    return s if s > 0 else 1.0


def contact_residual(pressure: np.ndarray, gap: np.ndarray, scale: float) -> float:
    """Scale-free error in the contact conditions.

    ``R = [mean(p |g|) + mean(p) mean(max(-g, 0))] / (mean(p) * h_rms)``: the complementarity
    error (gap where pressure acts) plus the interpenetration, both relative to the mean pressure
    and the rms roughness. ``p >= 0`` is enforced exactly by every solver. ``R = 0`` for a state
    without pressure.
    """
    pbar = float(np.mean(pressure))
    if pbar <= 0:
        return float(np.mean(np.maximum(-gap, 0.0)) / scale)
    comp = float(np.einsum("i,i->", pressure.ravel(), np.abs(gap).ravel())) / pressure.size
    pen = float(np.mean(np.maximum(-gap, 0.0)))
    return (comp + pbar * pen) / (pbar * scale)


def residual_from_sums(comp: float, pen: float, psum: float, n: int, scale: float) -> float:
    """:func:`contact_residual` from its sums over the ``n`` grid points: ``comp = sum(p |g|)``, ``pen =
    sum(max(-g, 0))``, ``psum = sum(p)`` (a solver's fused sweep gives them in one pass)."""
    return (comp + psum * pen / n) / (psum * scale) if psum > 0 else pen / (n * scale)


def dot(a: np.ndarray, b: np.ndarray) -> float:
    """``sum(a * b)`` of two real fields, without BLAS. OpenBLAS threads a dot product of a 128^2 field,
    and next to FFTW's spinning threads or a second process that took 23 ms against 5 us single-threaded
    (2 cores): every inner product of the solvers' loops goes through numpy's own loop instead."""
    return float(np.einsum("i,i->", a.ravel(), b.ravel()))

