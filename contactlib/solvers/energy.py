"""The energy balance of the seed paper (eqs 9-11) for a 1D profile: the JKR limit without a range.

The contact domain ``Omega`` is where the gap closes; inside it the traction is whatever keeps it closed
(tensile at its edges), outside it vanishes. At fixed approach ``d`` the free energy ``F = U_el - w A``,
``U_el = 1/2 int_Omega p u dx`` (per unit width and period), is stationary over ``Omega`` (eq. 9), and
a stable state is a local minimum of it.

Here ``Omega`` is one interval of ``2 m + 1`` elements centred on the highest point of a profile
symmetric about it (a wavy profile, a cylinder): one contact per period. For each ``m`` the closed
domain gives, with ``K`` the compliance matrix on it, ``p = K^-1 (d - h0)`` (``h0 = max h - h``) and

    U_m(d) = dx / 2 [d^2 1'K^-1 1 - 2 d 1'K^-1 h0 + h0'K^-1 h0],

so ``F_m(d) = U_m(d) - w (2 m + 1) dx`` is a quadratic in ``d`` for each ``m``. The Cholesky factor of ``K`` with
its elements in the order the domain grows (the centre, then pairs left and right) holds every domain's
factor as a leading block, so one factorisation (``O(N^3 / 3)``) and two triangular solves give all ``m``: the coefficients of the whole family are exact for the
discrete problem, with no iteration. The energy release rate between ``m`` and ``m + 1`` is ``G =
(U_{m+1} - U_m) / (2 dx)`` and equilibrium ``G = w``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.linalg import solve_triangular

MAX_POINTS = 4096
"""Largest profile the energy method takes (a dense compliance matrix of ``N^2`` entries)."""


@dataclass(frozen=True)
class EnergyFamily:
    """The contact domains ``m = 0 .. M`` of a symmetric profile and their energy coefficients.

    ``U_m(d) = dx / 2 (a_m d^2 - 2 b_m d + c_m)``; the mean traction over the window is
    ``(s_m d - t_m) / N`` with ``s_m = 1'K^-1 1`` and ``t_m = 1'K^-1 h0``.
    """

    a: np.ndarray
    b: np.ndarray
    c: np.ndarray
    spacing: float
    size: int
    order: np.ndarray
    """Element indices in the order the domain grows: the centre, then pairs left/right."""
    matrix: np.ndarray
    h0: np.ndarray

    @property
    def half_widths(self) -> np.ndarray:
        """Contact half-width ``(m + 1/2) dx`` of each domain [length]."""
        return (np.arange(self.a.size) + 0.5) * self.spacing

    def elastic_energy(self, penetration) -> np.ndarray:
        """``U_m(d)`` for every ``m`` [energy per unit width]."""
        d = np.asarray(penetration, dtype=float)[..., None]
        return self.spacing / 2 * (self.a * d**2 - 2 * self.b * d + self.c)

    def free_energy(self, penetration, work: float) -> np.ndarray:
        """``F_m(d) = U_m(d) - w (2 m + 1) dx``."""
        return self.elastic_energy(penetration) - work * (2 * np.arange(self.a.size) + 1) * self.spacing

    def mean_pressure(self, m, penetration) -> np.ndarray:
        """Mean traction over the window [pressure] of domain ``m`` at approach ``d``."""
        m = np.asarray(m)
        return (self.a[m] * penetration - self.b[m]) / self.size

    def equilibrium_penetration(self, work: float) -> np.ndarray:
        """For each ``m < M``, the approach at which ``G = (U_{m+1} - U_m) / (2 dx) = w`` with a tensile
        edge (the root whose edge traction is negative: the JKR crack); NaN where none is."""
        da, db, dc = np.diff(self.a), np.diff(self.b), np.diff(self.c)
        # dx/2 (da d^2 - 2 db d + dc) = 2 w dx
        A, B, C = da, -2 * db, dc - 4 * work
        disc = B * B - 4 * A * C
        disc = np.where((disc < 0) & (disc > -1e-9 * B * B), 0.0, disc)  # w -> 0: a double root, round-off
        out = np.full(da.shape, np.nan)
        ok = (disc >= 0) & (A > 0)
        root = np.sqrt(np.where(ok, disc, 0.0))
        # the smaller root: the larger would press the edge (the compressive "crack" of negative K_I)
        out[ok] = (-B[ok] - root[ok]) / (2 * A[ok])
        return out

    def pressure(self, m: int, penetration: float) -> np.ndarray:
        """The traction field [pressure] of domain ``m`` at approach ``d`` (zero outside it)."""
        idx = self.order[: 2 * m + 1]
        K = self.matrix[np.ix_(idx, idx)]
        p = np.zeros(self.size)
        p[idx] = np.linalg.solve(K, penetration - self.h0[idx])
        return p


def energy_family(matrix: np.ndarray, heights: np.ndarray, spacing: float, *, max_half_width: int | None = None
                  ) -> EnergyFamily:
    """The family of symmetric contact domains of a 1D profile (module docstring).

    Parameters
    ----------
    matrix : ndarray
        The compliance matrix ``K[i, j]`` [length/pressure], displacement at ``i`` of a unit pressure on
        element ``j`` (:meth:`contactlib.operators.Compliance.matrix`).
    heights : ndarray
        The profile [length], symmetric about its highest point.
    spacing : float
        Element length [length].
    max_half_width : int, optional
        Largest ``m`` (default: the domain reaches the window less one element).
    """
    n = heights.size
    i0 = int(np.argmax(heights))
    h0 = heights.max() - heights
    largest = (n - 2) // 2 if max_half_width is None else int(max_half_width)
    order = [i0]
    for k in range(1, largest + 1):
        order += [(i0 - k) % n, (i0 + k) % n]
    order = np.array(order)
    # the leading blocks of the Cholesky factor of K in growth order are the factors of every domain
    L = np.linalg.cholesky(matrix[np.ix_(order, order)])
    y = solve_triangular(L, np.ones(order.size), lower=True, check_finite=False)  # L^-1 1
    z = solve_triangular(L, h0[order], lower=True, check_finite=False)  # L^-1 h0
    ends = 2 * np.arange(largest + 1) + 1
    a, b, c = np.cumsum(y * y)[ends - 1], np.cumsum(y * z)[ends - 1], np.cumsum(z * z)[ends - 1]
    return EnergyFamily(a=a, b=b, c=c, spacing=float(spacing), size=n, order=order, matrix=matrix, h0=h0)


def check_symmetric(heights: np.ndarray) -> None:
    """Refuse a profile that is not symmetric about its highest point (one contact per period)."""
    n = heights.size
    i0 = int(np.argmax(heights))
    k = np.arange(1, n // 2)
    left, right = heights[(i0 - k) % n], heights[(i0 + k) % n]
    scale = float(np.ptp(heights)) or 1.0
    if np.max(np.abs(left - right)) > 1e-9 * scale:
        raise ValueError("adhesion model 'jkr' (energy method) takes a 1D profile symmetric about its highest "
                         "point (one contact interval per period); use a cohesive model ('maugis' or "
                         "'exponential') for other surfaces")
