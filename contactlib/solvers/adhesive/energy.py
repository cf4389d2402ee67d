"""The energy balance of the seed paper (eqs 9-11): the JKR limit without a range, on nested contact domains.

The contact domain ``Omega`` is where the gap closes; inside it the traction is whatever keeps it closed
(tensile at its edges), outside it vanishes. At fixed approach ``d`` the free energy ``F = U_el - w A``,
``U_el = 1/2 int_Omega p u dx`` (per unit width and period), is stationary over ``Omega`` (eq. 9), and
a stable state is a local minimum of it.

Here ``Omega`` is one interval of ``2 m + 1`` elements centred on the highest point of a profile
symmetric about it (a wavy profile, a cylinder): one contact per period; or, on a 2D surface of
revolution (a sphere), the disc of radius ``(m + 1/2) dx`` about its apex (the JKR sphere). For each ``m`` the closed
domain gives, with ``K`` the compliance matrix on it, ``p = K^-1 (d - h0)`` (``h0 = max h - h``) and

    U_m(d) = dx / 2 [d^2 1'K^-1 1 - 2 d 1'K^-1 h0 + h0'K^-1 h0],

so ``F_m(d) = U_m(d) - w (2 m + 1) dx`` is a quadratic in ``d`` for each ``m``. The energy release rate between
``m`` and ``m + 1`` is ``G = (U_{m+1} - U_m) / (A_{m+1} - A_m)`` and equilibrium ``G = w``.

How it is solved, exactly and without iteration: ``h0``, ``1`` and the domains are symmetric about the apex (the
reflection of a profile; the eight mirrors and quarter turns of a square grid about a sphere's apex, those the
window and the compliance share), so ``p`` is too, and ``K p = d - h0`` reduces to one unknown per orbit of
those symmetries: ``B = Q'KQ`` (``Q`` the elements-by-orbits indicator), about an eighth of the elements in 2D.
The Cholesky factor of ``B`` with its orbits in the order the domain grows holds every domain's factor as a
leading block, so one factorisation (``O(n^3 / 3)`` in the ``n`` orbits) and two triangular solves give all
``m``: the coefficients of the whole family are exact for the discrete problem. The whole window of a 128^2
sphere (12,000 elements, 1,600 orbits) takes about 0.1 s; of a 256^2 one (50,000, 6,400) a few seconds.
The family ends at the largest domain the window holds, or at :data:`MAX_UNKNOWNS` orbits: a state that needs
a larger one is refused, naming the limit (:attr:`EnergyFamily.limit`), never cut to the largest.

On a grid ``G`` of a growth step is never zero (a ring of elements at unequal distances cannot unload at once): a
``w`` below a step's least ``G`` (:meth:`EnergyFamily.least_release_rate`: 3.6e-7 to 1.9e-5 over the first 18
steps of a 40^2 sphere of radius 1, E* = 4/3, unit window) is not resolved there, and the edge moves where ``G`` is
least, the non-adhesive edge of discs. The curve ``G = w`` takes those points (so ``w -> 0`` has a curve, a
load-controlled state and a pull-off that tends to 0), and :func:`contactlib.problems.adhesive.energy_or_plain`
solves such a state without adhesion, saying so.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.linalg import cholesky, solve_triangular

from ...core._numba import jit
from .energy_orbits import orbit_compliance, symmetry_orbits

MAX_UNKNOWNS = 8192
"""Most unknowns (symmetry orbits of its elements) of the energy method's largest domain: their compliance
matrix is dense (8192^2 doubles, 0.5 GB) and factorised once (about 1.8e11 flops). The whole window of a 256^2
sphere is about 6,400 orbits, of a 1D profile of 16384 points 8,192. Before the reduction by symmetry the cap
was 4096 elements, and a larger contact was cut to it silently (issue 38)."""


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
    factor: np.ndarray
    """Lower Cholesky factor of the orbits' compliance matrix ``B = Q'KQ``, orbits in growth order."""
    orbit: np.ndarray
    """The orbit of each element of ``order`` (non-decreasing: an orbit's elements are contiguous)."""
    counts: np.ndarray
    """Elements per orbit."""
    h0: np.ndarray
    limit: str | None = None
    """What the largest domain is, where a state may need a larger one (the largest disc about the apex the
    window holds; :data:`MAX_UNKNOWNS`); None where the next state is the closed window (a profile's largest
    interval leaves out one element)."""

    @property
    def spacing(self) -> float:
        """The element's length [length] (1D), for half-widths."""
        return self.element

    @property
    def orbit_ends(self) -> np.ndarray:
        """Orbits in each domain."""
        return self.orbit[self.ends - 1] + 1

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

    def penetration_at(self, m: int, mean_pressure: float) -> float:
        """The approach at which domain ``m`` carries ``mean_pressure`` (the load is linear in ``d``)."""
        return float((self.size * mean_pressure + self.b[m]) / self.a[m])

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

    def open_threshold(self, work: float) -> float:
        """The approach (``<= 0``) below which domain 0 opens: the tensile root of ``F_0(d) = 0`` (the
        open state's free energy), 0 where ``F_0 > 0`` at every negative approach."""
        A, B, C = self.a[0], -2 * self.b[0], self.c[0] - 2 * work * self.ends[0]
        disc = B * B - 4 * A * C
        if disc < 0 or A <= 0:
            return 0.0
        return float(min((-B - math.sqrt(disc)) / (2 * A), 0.0))

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

    def resolved(self, work: float) -> np.ndarray:
        """For each ``m < M``, whether ``G = w`` has a root between domains ``m`` and ``m + 1``: ``w`` at least the
        step's least energy release rate :meth:`least_release_rate`. Where it has none the grid does not resolve
        ``w`` there: the edge moves where ``G`` is least (:meth:`growth_threshold`), whatever ``w`` is."""
        return np.isfinite(self.equilibrium_penetration(work))

    def least_release_rate(self) -> np.ndarray:
        """For each ``m < M``, the least ``G`` [energy/area] of the step from domain ``m`` to ``m + 1`` over the
        approach (at :meth:`growth_threshold`'s vertex). It is positive on a grid: a ring of elements at unequal
        distances cannot unload all at once, so a work of adhesion below it is not resolved (0 in the continuum)."""
        da, db, dc = np.diff(self.a), np.diff(self.b), np.diff(self.c)
        return np.maximum(dc - db * db / da, 0.0) / (2 * np.diff(self.ends))

    def adhesive_load(self, m: int, work: float) -> float:
        """An estimate [pressure] of what a work of adhesion ``w`` changes domain ``m``'s mean traction by: the
        shift of the growth threshold from the vertex that ``G = w`` makes where the least ``G`` is zero (the
        continuum), ``sqrt(2 w dn / da)``, times the load per approach; for the note of a state where the grid does
        not resolve ``w`` (:meth:`resolved`)."""
        k = min(max(int(m), 0), self.a.size - 2)
        da = float(self.a[k + 1] - self.a[k])
        shift = math.sqrt(2 * work * float(self.ends[k + 1] - self.ends[k]) / da) if da > 0 else math.inf
        return float(self.a[max(int(m), 0)]) * shift / self.size

    def open_point(self, work: float) -> tuple[float, float]:
        """The start of :meth:`equilibrium_curve`: the approach where domain 0 opens (:meth:`open_threshold`) and
        the mean of its traction there and the open state's (zero). At ``w = 0`` it is ``(0, 0)``: the first
        touch.

        One element pulled off alone is a flat punch, whose pull-off grows as ``sqrt(w)``: far above the sphere's
        ``3/2 pi w R`` (150 times at ``w`` 3e-5 of the first step's least ``G``), beyond even DMT's ``2 pi w R``. So
        where the grid does not resolve ``w`` at the first step (``w`` below its :meth:`least_release_rate`, the
        pull-off's contact under a spacing), the load is the first touch's at that least ``G``, scaled to ``w`` as
        the continuum's pull-off scales: ``w`` on a surface of revolution, ``w^(2/3)`` on a profile (Johnson's
        cylinder); 0.8 of JKR's on a 40^2 sphere at ``w`` 3e-5 of it."""
        least = float(self.least_release_rate()[0]) if self.a.size > 1 else 0.0
        if not 0 < work < least:
            d = self.open_threshold(work)
            return d, 0.5 * float(self.mean_pressure(0, d))
        disc = self.ends[1] - self.ends[0] > 2  # a first ring of more than two elements: a 2D grid
        d = self.open_threshold(least)
        load = 0.5 * float(self.mean_pressure(0, d)) * (work / least) ** (1.0 if disc else 2.0 / 3.0)
        return self.penetration_at(0, 2 * load), load

    def equilibrium_curve(self, work: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The equilibrium states between domains ``m`` and ``m + 1``: closed area (their mean), approach
        (:meth:`growth_threshold`: the tensile root of ``G = w``, or where the grid does not resolve ``w`` there,
        :meth:`resolved`, the vertex where ``G`` is least: the non-adhesive edge) and mean traction over the window
        (the mean of the two domains' at that approach: the edge lies between them).

        These points sample the continuous equilibrium curve ``G = w`` to second order in the spacing (the
        discrete branch, whose domain grows by whole elements, jumps from the one domain's traction to the
        other's at each point: a sawtooth about them). Joined by straight segments, and started at
        :meth:`open_point`, they are the curve that :meth:`pull_off` and :meth:`load_state` use. Before the
        vertex fallback, a small ``w`` (below the least ``G`` of the steps) left every point NaN: no load-controlled
        state and no pull-off as ``w -> 0`` (issue 38)."""
        d = self.growth_threshold(work)
        m = np.arange(d.size)
        area = 0.5 * (self.ends[:-1] + self.ends[1:]) * self.element
        pressure = 0.5 * (self.mean_pressure(m, d) + self.mean_pressure(m + 1, d))
        return area, d, pressure

    def _curve_from_open(self, work: float) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`equilibrium_curve`'s approaches and loads with :meth:`open_point` in front (index ``k + 1`` is
        the curve's point ``k``)."""
        _, d, P = self.equilibrium_curve(work)
        d0, P0 = self.open_point(work)
        return np.r_[d0, d], np.r_[P0, P]

    def pull_off(self, work: float) -> tuple[float, int]:
        """The pull-off of load control [pressure] and the point ``k`` of :meth:`equilibrium_curve` where it
        lies (``-1``: :meth:`open_point`, where the least load is the first touch: a work the grid does not
        resolve, or ``w = 0``): the least load of the curve's rising stretches (stable under load control: the
        load grows with the contact), at the start of one. ``(NaN, -2)`` where the curve nowhere rises (no
        stable partial contact, or the family ends before it does). A wavy profile's curve falls again toward
        full contact (Johnson's ``-alpha sqrt(tan)``): that stretch is unstable and not a pull-off.

        Its error against the continuous curve is second order in the spacing: at most ``(9/32) (dx / a_c)^2``
        of ``|P_c|`` for a JKR sphere (the curve's ``P'' = 4.5 |P_c| / a_c^2`` at ``a_c``), 0.1 % at 16
        spacings in ``a_c``; on a 128^2 sphere with 16 spacings in ``a_c`` it is 1.005 JKR's. Where ``a_c`` is
        below a spacing (``w -> 0``) it is the first touch's, which tends to 0 with ``w`` as JKR's does."""
        _, P = self._curve_from_open(work)
        lo, hi = P[:-1], P[1:]
        with np.errstate(invalid="ignore"):
            rising = np.flatnonzero(np.isfinite(lo) & np.isfinite(hi) & (hi > lo))
        if rising.size == 0:
            return math.nan, -2
        k = int(rising[np.argmin(lo[rising])])
        return float(P[k]), k - 1

    def pull_off_penetration(self, work: float) -> float:
        """The approach [length] of :meth:`equilibrium_curve` at its least load (:meth:`pull_off`): the jump
        out of contact under load control. The load is flat there and the approach steep (about ``0.07 dx``
        per spacing of radius on a JKR sphere), so the point is placed at the vertex of the parabola through
        the three points about the least (its load within a step's square of the least one's), and its approach
        interpolated there: the point itself was 16 % off JKR's on a 128^2 sphere (16 spacings in ``a_c``), the
        vertex 4 %. NaN where :meth:`pull_off` is."""
        d, P = self._curve_from_open(work)
        _, k = self.pull_off(work)
        k += 1  # on the curve from the open point
        if k < 0:
            return math.nan
        if k == 0 or k + 1 >= P.size or not (np.isfinite(P[k - 1]) and np.isfinite(d[k - 1])
                                             and np.isfinite(d[k + 1])):
            return float(d[k])
        curvature = P[k - 1] - 2 * P[k] + P[k + 1]
        shift = 0.5 * (P[k - 1] - P[k + 1]) / curvature if curvature > 0 else 0.0
        shift = float(np.clip(shift, -0.5, 0.5))
        side = k + 1 if shift > 0 else k - 1
        return float(d[k] + abs(shift) * (d[side] - d[k]))

    def load_state(self, mean_pressure: float, work: float, near: int | None = None) -> tuple[int, float] | None:
        """The state carrying ``mean_pressure`` under load control: ``(m, d)``, domain and approach, or None
        where none does (beyond the pull-off, or beyond the largest domain).

        On a segment of :meth:`equilibrium_curve` that rises with the contact (stable under load control),
        between its points ``k`` (the edge between domains ``k`` and ``k + 1``) and ``k + 1`` (between
        ``k + 1`` and ``k + 2``), the edge lies in domain ``k + 1``'s cell: the state is domain ``k + 1``
        at the approach that makes its load the one asked (the load is linear in ``d``). That approach lies
        between the two points' (``t_k <= d <= t_{k+1}``: domain ``k + 1`` carries less than the point's mean
        at ``t_k`` and more at ``t_{k+1}``), where domain ``k + 1`` is the stable one under penetration
        control too: an equilibrium of the discrete family, at the load asked exactly. The segment from
        :meth:`open_point` to point 0 is domain 0's. ``near``: the segment nearest that domain (a path's
        previous state); else that of largest contact."""
        _, P = self._curve_from_open(work)
        lo, hi = P[:-1], P[1:]
        with np.errstate(invalid="ignore"):
            rising = np.isfinite(lo) & np.isfinite(hi) & (hi > lo) & (lo <= mean_pressure) & (mean_pressure <= hi)
        segments = np.flatnonzero(rising)  # segment j: domain j (from the open point)
        if segments.size == 0:
            return None
        m = int(segments[-1] if near is None else segments[np.argmin(np.abs(segments - max(near, 0)))])
        return m, self.penetration_at(m, mean_pressure)

    def detachment_penetration(self, work: float, start: int | None = None) -> float:
        """The approach at which unloading under penetration control from domain ``start`` (default the
        largest) ends out of contact, however finely it is stepped: the edge retreats below each domain's
        shrink threshold (:meth:`growth_threshold`), and where the next one down is higher (the branch
        unstable under fixed grips) it runs through them to the open state (:meth:`open_threshold`)."""
        t = self.growth_threshold(work)
        shrink = np.concatenate([[self.open_threshold(work)], t])  # shrink[m]: domain m leaves below it
        m = self.a.size - 1 if start is None else int(start)
        d = math.inf
        while m >= 0:
            d = min(d, float(shrink[m]))
            m -= 1
            while m >= 0 and not shrink[m] < d:  # runs through every domain that cannot hold at d
                m -= 1
        return d

    def domain(self, m: int) -> np.ndarray:
        """Flat indices of the elements of domain ``m``."""
        return self.order[: self.ends[m]]

    def pressure(self, m: int, penetration: float) -> np.ndarray:
        """The traction field [pressure] of domain ``m`` at approach ``d`` (zero outside it), flat: the orbits'
        ``B_m X = Q'(d - h0)`` by the leading block of the factor, one value per orbit."""
        e = int(self.ends[m])
        k = int(self.orbit[e - 1]) + 1
        head = self.order[np.r_[0, np.flatnonzero(np.diff(self.orbit[:e])) + 1]]  # an element of each orbit
        values = _leading_block_solve(self.factor, k, self.counts[:k] * (penetration - self.h0[head]))
        p = np.zeros(self.size)
        p[self.order[:e]] = values[self.orbit[:e]]
        return p

    def beyond(self, m: int) -> bool:
        """Whether a state in domain ``m`` may need a larger domain than the family holds (its last, where
        :attr:`limit` says what ends it)."""
        return self.limit is not None and m >= self.a.size - 1

    def refusal(self, name: str, value: float) -> ValueError:
        """The error for a state beyond the family (:meth:`beyond`), naming ``name``, the limit and what to
        change (:attr:`limit`)."""
        return ValueError(f"{name} {value!r}: the contact would grow beyond the energy method's largest domain, "
                          f"{self.limit}")


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


@jit
def _leading_block_solve(L, k, rhs):
    """``(L_k L_k')^-1 rhs`` for the leading ``k x k`` block ``L_k`` of the lower factor ``L`` (rows contiguous),
    in place of ``rhs``: by rows forward, then by rows of ``L`` backward (no copy of the block)."""
    for i in range(k):
        s = rhs[i]
        for j in range(i):
            s -= L[i, j] * rhs[j]
        rhs[i] = s / L[i, i]
    for i in range(k - 1, -1, -1):
        x = rhs[i] / L[i, i]
        rhs[i] = x
        for j in range(i):
            rhs[j] -= L[i, j] * x
    return rhs


def energy_family(response: np.ndarray, heights: np.ndarray, spacing: tuple[float, ...], element: float,
                  order: np.ndarray, ends: np.ndarray, *, periodic: bool, limit: str | None) -> EnergyFamily:
    """The family of nested contact domains of a profile or axisymmetric surface (module docstring).

    Parameters
    ----------
    response : ndarray
        The displacement [length/pressure] on the work grid due to a unit pressure on the element at the
        origin (:meth:`contactlib.model.operators.Compliance.response`): the compliance between two elements is
        its value at their offset.
    heights : ndarray
        The surface [length].
    spacing : tuple of float
        Grid spacing per axis [length].
    element : float
        Element length (1D) or area (2D).
    order, ends : ndarray
        From :func:`growth_order`.
    periodic : bool
        Whether offsets wrap around the window.
    limit : str or None
        What ends ``order`` (:attr:`EnergyFamily.limit`); replaced by :data:`MAX_UNKNOWNS` where that cuts it.
    """
    shape = heights.shape
    h0 = (heights.max() - heights).ravel()
    ends = np.asarray(ends)
    order, orbit = symmetry_orbits(shape, spacing, np.asarray(order)[: ends[-1]], response, periodic=periodic)
    if np.any(orbit[ends[:-1]] == orbit[ends[:-1] - 1]):  # equal distances: never; the algebra needs it
        raise RuntimeError("energy_family: an orbit of symmetries straddles two nested domains")
    orbit_ends = orbit[ends - 1] + 1
    if orbit_ends[-1] > MAX_UNKNOWNS:
        keep = int(np.searchsorted(orbit_ends, MAX_UNKNOWNS, side="right"))
        if keep < 2:
            raise ValueError(f"adhesion model 'jkr': the energy method's smallest domains already exceed "
                             f"MAX_UNKNOWNS = {MAX_UNKNOWNS} unknowns")
        ends, orbit_ends = ends[:keep], orbit_ends[:keep]
        order, orbit = order[: ends[-1]], orbit[: ends[-1]]
        limit = (f"the energy method's cap of MAX_UNKNOWNS = {MAX_UNKNOWNS} distinct unknowns (a dense matrix); "
                 "use a coarser grid (fewer elements across the contact) or a cohesive model ('maugis')")
    n = int(orbit_ends[-1])
    starts = np.r_[0, np.flatnonzero(np.diff(orbit)) + 1]
    counts = np.diff(np.r_[starts, order.size]).astype(float)
    # B[o, o'] = n_o sum_{j in o'} K[rep_o, j]: the compliance is the same from every element of an orbit
    # the compliance at every offset between two elements (-(n - 1) .. n - 1 per axis), laid out so that an
    # offset's flat index is the difference of the two elements' flat indices on that layout
    span = tuple(2 * size - 1 for size in shape)
    table = response[np.ix_(*[np.arange(1 - size, size) % w for size, w in zip(shape, response.shape)])].ravel()
    index = np.ravel_multi_index(np.unravel_index(order, shape), span)
    heads = index[starts] + np.ravel_multi_index(tuple(size - 1 for size in shape), span)
    matrix = np.zeros((n, n))
    orbit_compliance(table, heads, index, orbit, np.r_[starts, order.size], counts, matrix)
    # the leading blocks of the Cholesky factor of B in growth order are the factors of every domain
    L = cholesky(matrix.T, lower=False, overwrite_a=True, check_finite=False).T
    H = h0[order[starts]]
    y = solve_triangular(L, counts, lower=True, check_finite=False)  # L^-1 Q'1
    z = solve_triangular(L, counts * H, lower=True, check_finite=False)  # L^-1 Q'h0
    last = orbit_ends - 1
    a, b, c = np.cumsum(y * y)[last], np.cumsum(y * z)[last], np.cumsum(z * z)[last]
    return EnergyFamily(a=a, b=b, c=c, element=float(element), size=heights.size, order=order, ends=ends,
                        factor=L, orbit=orbit, counts=counts, h0=h0, limit=limit)


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
