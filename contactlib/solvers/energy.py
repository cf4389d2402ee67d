"""The energy balance of the seed paper (eqs 9-11) for a 1D profile: the JKR limit without a range.

The contact domain ``Omega`` is where the gap closes; inside it the traction is whatever keeps it closed
(tensile at its edges), outside it vanishes. At fixed approach ``d`` the free energy ``F = U_el - w A``,
``U_el = 1/2 int_Omega p u dx`` (per unit width and period), is stationary over ``Omega`` (eq. 9), and
a stable state is a local minimum of it.

Here ``Omega`` is one interval of ``2 m + 1`` elements centred on the highest point of a profile
symmetric about it (a wavy profile, a cylinder): one contact per period; or, on a 2D surface of
revolution (a sphere), the disc of radius ``(m + 1/2) dx`` about its apex (the JKR sphere). For each ``m`` the closed
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
    """Nested contact domains ``m = 0 .. M`` grown about the highest point and their energy coefficients.

    Domain ``m`` is the first ``ends[m]`` elements of ``order``. ``U_m(d) = dA / 2 (a_m d^2 - 2 b_m d +
    c_m)`` with ``a_m = 1'K^-1 1``, ``b_m = 1'K^-1 h0``, ``c_m = h0'K^-1 h0`` on the domain, ``dA`` the
    element's length (1D) or area (2D); the mean traction over the window is ``(a_m d - b_m) / N``.
    """

    a: np.ndarray
    b: np.ndarray
    c: np.ndarray
    element: float
    size: int
    order: np.ndarray
    ends: np.ndarray
    matrix: np.ndarray
    """The compliance matrix among the elements of ``order``, in that order."""
    h0: np.ndarray

    @property
    def spacing(self) -> float:
        """The element's length [length] (1D), for half-widths."""
        return self.element

    def area(self, m) -> np.ndarray:
        """Closed area of domain ``m`` [length (1D) or length^2 (2D)]."""
        return self.ends[np.asarray(m)] * self.element

    def elastic_energy(self, penetration) -> np.ndarray:
        """``U_m(d)`` for every ``m`` [energy per unit width (1D) or energy (2D)]."""
        d = np.asarray(penetration, dtype=float)[..., None]
        return self.element / 2 * (self.a * d**2 - 2 * self.b * d + self.c)

    def free_energy(self, penetration, work: float) -> np.ndarray:
        """``F_m(d) = U_m(d) - w A_m``."""
        return self.elastic_energy(penetration) - work * self.ends * self.element

    def mean_pressure(self, m, penetration) -> np.ndarray:
        """Mean traction over the window [pressure] of domain ``m`` at approach ``d``."""
        m = np.asarray(m)
        return (self.a[m] * penetration - self.b[m]) / self.size

    def equilibrium_penetration(self, work: float) -> np.ndarray:
        """For each ``m < M``, the approach at which ``G = (U_{m+1} - U_m) / (A_{m+1} - A_m) = w`` with a
        tensile edge (the root whose edge traction is negative: the JKR crack); NaN where none is."""
        da, db, dc = np.diff(self.a), np.diff(self.b), np.diff(self.c)
        A, B, C = da, -2 * db, dc - 2 * work * np.diff(self.ends)
        disc = B * B - 4 * A * C
        disc = np.where((disc < 0) & (disc > -1e-9 * B * B), 0.0, disc)  # w -> 0: a double root, round-off
        out = np.full(da.shape, np.nan)
        ok = (disc >= 0) & (A > 0)
        root = np.sqrt(np.where(ok, disc, 0.0))
        # the smaller root: the larger would press the edge (the compressive "crack" of negative K_I)
        out[ok] = (-B[ok] - root[ok]) / (2 * A[ok])
        return out

    def growth_threshold(self, work: float) -> np.ndarray:
        """For each ``m < M``, the approach above which domain ``m`` grows into ``m + 1`` (below it, ``m + 1``
        shrinks into ``m``): the tensile-edge root of ``G = w`` (:meth:`equilibrium_penetration`), or, where
        ``G > w`` at every approach, the approach of the traction-free edge (``G`` least).

        Comparing free energies alone is not enough: above the compressive root ``G`` exceeds ``w`` again,
        so ``F`` falls toward smaller domains, which interpenetrate outside (a large approach step from a
        small domain, or a stiff thin layer, would descend into them). The edge moves out wherever it is
        not tensile enough to hold, whatever ``F`` says there.
        """
        d = self.equilibrium_penetration(work)
        da, db = np.diff(self.a), np.diff(self.b)
        vertex = np.where(da > 0, db / np.where(da > 0, da, 1.0), np.nan)
        return np.where(np.isfinite(d), d, vertex)

    def descend(self, m: int, penetration: float, work: float) -> int:
        """The domain reached from domain ``m`` (``-1``: open) at approach ``penetration``, moving its edge
        one element at a time by :meth:`growth_threshold`; the open state and domain 0 by their free
        energies (without a range nothing pulls open surfaces together: open stays open at ``d < 0``)."""
        d = float(penetration)
        if m < 0:
            if d < 0:
                return -1
            m = 0
        t = self.growth_threshold(work)
        last = self.a.size - 1
        while m < last and not (d <= t[m]):  # NaN threshold (A <= 0, never here): grow
            m += 1
        while m > 0 and d < t[m - 1]:
            m -= 1
        if m == 0 and d < 0 and float(self.free_energy(d, work)[0]) > 0.0:
            return -1
        return m

    def stable_domains(self, penetration: float, work: float) -> np.ndarray:
        """The domains (``-1``: open) that :meth:`descend` does not leave at ``penetration``."""
        d = float(penetration)
        t = self.growth_threshold(work)
        m = np.arange(self.a.size)
        lower = np.concatenate([[-np.inf], t])  # shrink below
        upper = np.concatenate([t, [np.inf]])  # grow above
        stable = (d >= lower) & (d <= upper)
        if d < 0:
            stable[0] &= float(self.free_energy(d, work)[0]) <= 0.0
            return np.concatenate([[-1], m[stable]])
        return m[stable]

    def equilibrium_curve(self, work: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The equilibrium states between domains ``m`` and ``m + 1``: closed area (their mean), approach
        (:meth:`equilibrium_penetration`) and mean traction over the window (the mean of the two domains'
        at that approach: the edge lies between them). NaN where no tensile-edge root exists."""
        d = self.equilibrium_penetration(work)
        m = np.arange(d.size)
        area = 0.5 * (self.ends[:-1] + self.ends[1:]) * self.element
        pressure = 0.5 * (self.mean_pressure(m, d) + self.mean_pressure(m + 1, d))
        return area, d, pressure

    def domain(self, m: int) -> np.ndarray:
        """Flat indices of the elements of domain ``m``."""
        return self.order[: self.ends[m]]

    def pressure(self, m: int, penetration: float) -> np.ndarray:
        """The traction field [pressure] of domain ``m`` at approach ``d`` (zero outside it), flat."""
        e = int(self.ends[m])
        p = np.zeros(self.size)
        p[self.order[:e]] = np.linalg.solve(self.matrix[:e, :e], penetration - self.h0[self.order[:e]])
        return p

    def displacement(self, pressure: np.ndarray) -> np.ndarray:
        """``K p`` on the elements the family holds (flat; the others are not needed and left 0)."""
        u = np.zeros(self.size)
        u[self.order] = self.matrix @ pressure[self.order]
        return u


def growth_order(heights: np.ndarray, spacing: tuple[float, ...], *, periodic: bool,
                 max_radius: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Elements in the order the domain grows about the highest point, and the nested domains' sizes.

    1D: the centre, then pairs left and right (``2 m + 1`` elements). 2D: by distance from the apex, the
    domains the discs of radius ``(m + 1/2) dx`` (periodic distance where ``periodic``).
    """
    n = heights.size
    apex = np.unravel_index(int(np.argmax(heights)), heights.shape)
    if heights.ndim == 1:
        i0 = apex[0]
        largest = (n - 2) // 2
        if max_radius is not None:
            largest = min(largest, int(max_radius / spacing[0]))
        order = [i0]
        for k in range(1, largest + 1):
            order += [(i0 - k) % n, (i0 + k) % n]
        return np.array(order), 2 * np.arange(largest + 1) + 1
    offsets = []
    for axis, (size, dx) in enumerate(zip(heights.shape, spacing)):
        k = np.arange(size) - apex[axis]
        if periodic:
            k = (k + size // 2) % size - size // 2
        offsets.append(k * dx)
    dist = np.sqrt(offsets[0][:, None] ** 2 + offsets[1][None, :] ** 2).ravel()
    dx = max(spacing)
    limit = (min(heights.shape) // 2 - 1) * dx if max_radius is None else max_radius
    order = np.argsort(dist, kind="stable")
    order = order[dist[order] <= limit]
    radii = (np.arange(int(limit / dx)) + 0.5) * dx
    ends = np.searchsorted(dist[order], radii, side="right")
    return order, ends[ends > 0]


def energy_family(matrix: np.ndarray, heights: np.ndarray, element: float, order: np.ndarray,
                  ends: np.ndarray) -> EnergyFamily:
    """The family of nested contact domains of a profile or axisymmetric surface (module docstring).

    Parameters
    ----------
    matrix : ndarray
        The compliance matrix [length/pressure] among the elements ``order``, in that order: the
        displacement at one of a unit pressure on another (:meth:`contactlib.operators.Compliance.matrix`).
    heights : ndarray
        The surface [length].
    element : float
        Element length (1D) or area (2D).
    order, ends : ndarray
        From :func:`growth_order`.
    """
    h0 = (heights.max() - heights).ravel()
    # the leading blocks of the Cholesky factor of K in growth order are the factors of every domain
    L = np.linalg.cholesky(matrix)
    y = solve_triangular(L, np.ones(order.size), lower=True, check_finite=False)  # L^-1 1
    z = solve_triangular(L, h0[order], lower=True, check_finite=False)  # L^-1 h0
    a, b, c = np.cumsum(y * y)[ends - 1], np.cumsum(y * z)[ends - 1], np.cumsum(z * z)[ends - 1]
    return EnergyFamily(a=a, b=b, c=c, element=float(element), size=heights.size, order=order,
                        ends=np.asarray(ends), matrix=matrix, h0=h0)


def check_symmetric(heights: np.ndarray, spacing: tuple[float, ...]) -> None:
    """Refuse a surface that is not symmetric about its highest point: a profile symmetric about it (one
    contact interval per period) or a surface of revolution about it (one disc)."""
    scale = float(np.ptp(heights)) or 1.0
    apex = np.unravel_index(int(np.argmax(heights)), heights.shape)
    if heights.ndim == 1:
        n = heights.size
        k = np.arange(1, n // 2)
        left, right = heights[(apex[0] - k) % n], heights[(apex[0] + k) % n]
        bad = np.max(np.abs(left - right)) > 1e-9 * scale
    else:  # a surface of revolution: equal heights at equal distances from the apex (the discs' premise)
        r = min(min(apex[0], heights.shape[0] - 1 - apex[0]), min(apex[1], heights.shape[1] - 1 - apex[1]))
        block = heights[apex[0] - r: apex[0] + r + 1, apex[1] - r: apex[1] + r + 1]
        k = np.arange(-r, r + 1)
        dist2 = (k[:, None] ** 2 + k[None, :] ** 2).ravel()
        values = block.ravel()
        order = np.argsort(dist2, kind="stable")
        d2, v = dist2[order], values[order]
        starts = np.flatnonzero(np.r_[True, np.diff(d2) > 0])
        spread = np.maximum.reduceat(v, starts) - np.minimum.reduceat(v, starts)
        bad = r < 1 or float(spread.max()) > 1e-9 * scale
    if bad:
        raise ValueError("adhesion model 'jkr' (energy method) takes a surface symmetric about its highest "
                         "point: a profile (one contact interval per period) or a surface of revolution (one "
                         "disc); use a cohesive model ('maugis' or 'exponential') for other surfaces")
