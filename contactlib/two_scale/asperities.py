"""The asperity table of the two-scale method: centres, radii and summit heights, validated.

The method assumes separate spherical contacts (seed paper 1, eqs. 1-3): every asperity is a
spherical cap ``z_k - R_k + sqrt(R_k^2 - r^2)`` over its own footprint disc on a flat base at 0, and
no two footprints overlap. :func:`asperity_table` reads the table from the DataArray of
:func:`contactlib.surfaces.spheres` (which carries it in ``attrs``) or from an ``xarray.Dataset`` on an
``asperity`` dimension, and refuses what breaks that assumption, naming the parameter.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import xarray as xr

from ..core._numba import jit
from ..core.grid import Grid
from ..core.inputs import in_solver_axes, real_values, solver_values

NEIGHBOUR_SPACINGS = 2.5
"""The Ewald sum's real-space reach in mean spacings ``L / sqrt(N)`` (:data:`.interaction.EWALD_NEIGHBOURS`):
the widest neighbour query of a solve, done once (:meth:`AsperityTable.neighbour_pairs`)."""


@dataclass(frozen=True)
class AsperityTable:
    """Spherical asperities on a flat base, in a square window.

    Attributes
    ----------
    centers : ndarray, shape (N, 2)
        Summit positions in the plane [length], inside ``[0, length)`` for a periodic window.
    radius : ndarray, shape (N,)
        Sphere radii ``R_k`` [length], > 0.
    summit_height : ndarray, shape (N,)
        Summit heights ``z_k`` above the base [length], ``0 < z_k <= R_k``.
    length : float
        Window size [length] (square window).
    periodic : bool
        Whether the window repeats (interaction summed over periodic images).
    heights : ndarray or None
        The heights on a grid when the input carried one (DataArray), for the micro scale.
    grid : Grid or None
        That grid.
    footprint : ndarray or None
        Footprint radii [length] of asperities that are not spherical caps (a tabulated law's support);
        None: the spherical caps' own.
    highest : float or None
        ``heights.max()`` when known [length].
    """

    centers: np.ndarray
    radius: np.ndarray
    summit_height: np.ndarray
    length: float
    periodic: bool
    heights: np.ndarray | None = None
    grid: Grid | None = None
    footprint: np.ndarray | None = None
    highest: float | None = None

    @property
    def count(self) -> int:
        return int(self.radius.size)

    @property
    def footprint_radius(self) -> np.ndarray:
        """Radius of each cap's intersection with the base [length]: ``sqrt(z (2R - z))`` (or the
        :attr:`footprint` given)."""
        if self.footprint is not None:
            return self.footprint
        z, R = self.summit_height, self.radius
        return np.sqrt(z * (2 * R - z))

    @property
    def neighbour_reach(self) -> float:
        """The Ewald sum's real-space reach [length]: :data:`NEIGHBOUR_SPACINGS` mean spacings, below half the
        window (one image per pair at most)."""
        return min(NEIGHBOUR_SPACINGS * (self.length / math.sqrt(self.count)), 0.45 * self.length)

    def neighbour_pairs(self, distance: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Pairs ``(k, l)``, ``k < l``, of summits closer than ``distance`` (nearest periodic image),
        and their distances [length]. The widest query is kept on the table and the narrower ones are
        read from it: the overlap check and the Ewald sum's neighbours then cost one k-d tree query."""
        cached = self.__dict__.get("_pairs")
        if cached is None or cached[0] < distance * (1 - 1e-12):  # a reach computed otherwise: rounding
            # the validation's query asks for at least the Ewald sum's neighbours, which come next
            reach = max(distance, self.neighbour_reach)
            k, l, r = cell_pairs(self.centers, self.length, reach, self.periodic)
            cached = (reach, k, l, r)
            self.__dict__["_pairs"] = cached  # a cache, not a field: the dataclass stays frozen
        reach, k, l, r = cached
        if distance >= reach * (1 - 1e-12):
            return k, l, r
        keep = r <= distance
        return k[keep], l[keep], r[keep]

    def distance(self, k: np.ndarray, l: np.ndarray) -> np.ndarray:
        """In-plane distance between summits ``k`` and ``l`` (nearest periodic image) [length]."""
        d = self.centers[k] - self.centers[l]
        if self.periodic:
            d -= self.length * np.rint(d / self.length)
        return np.sqrt(np.sum(d**2, axis=-1))


def _heights_of(asperities: xr.DataArray) -> tuple[np.ndarray, Grid, float]:
    """The heights of a 2D DataArray, their grid and the highest [length], as :func:`contactlib.core.inputs.grid_of`
    reads them (window length = coordinate step x points), with its checks: finiteness and the highest (kept for
    the approach) in one pass rather than a mask, and the coordinates from their indexes rather than as
    DataArrays (0.6 -> 0.2 ms on 700^2)."""
    values = np.ascontiguousarray(real_values(asperities.values, "asperities"))
    lengths = []
    for d, size in zip(asperities.dims, values.shape):
        if d not in asperities.coords:
            raise ValueError(f"asperities: dimension {d!r} has no coordinate")
        index = asperities.xindexes.get(d)  # an indexed coordinate: two values, not the whole index converted
        c = index.index if index is not None and hasattr(index, "index") else asperities.coords.variables[d].values
        if size < 2:
            raise ValueError(f"asperities: grid smaller than 2 points along {d!r}")
        lengths.append(float(c[1] - c[0]) * size)
    highest, finite = _highest_and_finite(values.reshape(-1))
    if not finite:
        raise ValueError("asperities: the heights contain NaN or infinite values")
    return values, Grid(values.shape, tuple(lengths)), highest


@jit
def _highest_and_finite(values):
    """The largest value and whether all are finite, in one pass over the grid: numpy's ``max`` and ``min`` read it
    twice, 3.9 MB each at 700^2. From memory (the heights out of cache, as after a full solve) 0.19 against 0.30 ms;
    in cache 0.17 against 0.10 ms. Four lanes, so the compares pipeline; ``v * 0`` is NaN exactly for a NaN or an
    infinity, and then so is the sum."""
    n = values.size
    h0 = h1 = h2 = h3 = -np.inf
    s0 = s1 = s2 = s3 = 0.0
    i = 0
    while i + 4 <= n:
        a, b, c, d = values[i], values[i + 1], values[i + 2], values[i + 3]
        h0, h1, h2, h3 = max(h0, a), max(h1, b), max(h2, c), max(h3, d)
        s0 += a * 0.0
        s1 += b * 0.0
        s2 += c * 0.0
        s3 += d * 0.0
        i += 4
    while i < n:
        h0 = max(h0, values[i])
        s0 += values[i] * 0.0
        i += 1
    return max(max(h0, h1), max(h2, h3)), (s0 + s1) + (s2 + s3) == 0.0


def _column(source, names: tuple[str, ...], label: str) -> np.ndarray:
    for name in names:
        if name in source:
            return np.atleast_1d(np.asarray(source[name], dtype=float)).ravel()
    raise ValueError(f"asperities: no {label!r} in the asperity table (looked for {', '.join(names)})")


def asperity_table(asperities, *, length: float | None = None, periodic: bool | None = None,
                   footprint_radius: float | None = None) -> AsperityTable:
    """Read and validate the asperity table.

    Parameters
    ----------
    asperities : xarray.DataArray or xarray.Dataset
        The heights from :func:`contactlib.surfaces.spheres` (the table in ``attrs``, the window from
        the coordinates), or a Dataset with ``center_x``, ``center_y``, ``radius``, ``summit_height`` on
        an ``asperity`` dimension [length] and the window length in ``attrs['length']`` or ``length``.
    length : float, optional
        Window size [length]; required for a Dataset without ``attrs['length']``.
    periodic : bool, optional
        Default: the input's ``attrs['periodic']``, else True.
    footprint_radius : float, optional
        Asperities that are not spherical caps (a tabulated law's shape): their common footprint radius
        [length]; ``radius`` is then not used (any positive value) and ``summit_height`` only needs to be
        positive.


    Returns
    -------
    AsperityTable
        The validated table.

    Raises
    ------
    ValueError
        Naming the parameter: missing columns, NaN or infinite positions, ``radius <= 0``,
        ``summit_height`` outside ``(0, radius]``, centres outside a non-periodic window, overlapping
        asperities (footprint discs that intersect: the caps would not be separate spheres).
    """
    heights = grid = highest = None
    if isinstance(asperities, xr.DataArray):
        if asperities.ndim != 2:
            raise ValueError(f"asperities: the two-scale method needs a 2D surface, got {asperities.ndim}D")
        values, grid, highest = _heights_of(in_solver_axes(asperities))  # by name: [ix, iy]
        if abs(grid.lengths[0] - grid.lengths[1]) > 1e-12 * grid.lengths[0] or grid.shape[0] != grid.shape[1]:
            raise ValueError(f"asperities: the window must be square with a square grid, got {grid.shape} "
                             f"points over {grid.lengths}")
        heights, window = values, grid.lengths[0]
        if length is not None and abs(float(length) - window) > 1e-9 * window:
            raise ValueError(f"length {length!r} differs from the DataArray's window {window!r}")
        source = asperities.attrs
        x = _column(source, ("asperity_center_x",), "asperity_center_x")
        y = _column(source, ("asperity_center_y",), "asperity_center_y")
        radius = _column(source, ("asperity_radius",), "asperity_radius")
        summit = _column(source, ("asperity_summit_height",), "asperity_summit_height")
    elif isinstance(asperities, xr.Dataset):
        if "asperity" not in asperities.dims:
            raise ValueError("asperities: the Dataset needs an 'asperity' dimension")
        window = length if length is not None else asperities.attrs.get("length")
        if window is None:
            raise ValueError("length: give the window size (length=...) or attrs['length'] on the Dataset")
        source = {k: asperities[k].values for k in asperities.variables}
        x = _column(source, ("center_x",), "center_x")
        y = _column(source, ("center_y",), "center_y")
        radius = _column(source, ("radius",), "radius")
        summit = _column(source, ("summit_height",), "summit_height")
    else:
        raise ValueError("asperities must be the DataArray of contactlib.surfaces.spheres or an xarray.Dataset "
                         f"with an 'asperity' dimension, got {type(asperities).__name__}")
    window = float(window)
    if not np.isfinite(window) or window <= 0:
        raise ValueError(f"length must be finite and > 0, got {window!r}")
    if periodic is None:
        periodic = bool(asperities.attrs.get("periodic", True))
    n = radius.size
    for name, column in (("center_x", x), ("center_y", y), ("summit_height", summit)):
        if column.size != n:
            raise ValueError(f"asperities: {name} has {column.size} entries, radius {n}")
    if n == 0:
        raise ValueError("asperities: the table is empty")
    centers = np.empty((n, 2))
    if not _valid_columns(x, y, radius, summit, footprint_radius is None, float(window), bool(periodic), centers):
        _refuse_columns(x, y, radius, summit, footprint_radius, window, periodic)
    footprint = None
    if footprint_radius is not None:
        if not (np.isfinite(footprint_radius) and footprint_radius > 0):
            raise ValueError(f"footprint_radius must be finite and > 0, got {footprint_radius!r}")
        footprint = np.full(n, float(footprint_radius))
    if highest is not None and highest > float(summit.max()) * (1 + 1e-9):
        # the macro scale reads the table, the micro scale the heights: edited heights would be two surfaces
        raise ValueError(f"asperities: the heights rise to {highest:.6g}, above the table's highest summit "
                         f"{float(summit.max()):.6g}: the heights were changed after the table was made (make a new "
                         "field)")
    table = AsperityTable(centers, radius, summit, window, bool(periodic), heights, grid, footprint, highest)
    check_separate(table)
    return table


@jit
def _valid_columns(x, y, radius, summit, caps, window, periodic, centers):
    """Whether the columns pass :func:`_refuse_columns`' checks, in one pass that also fills the centres (wrapped
    into the window when periodic): numpy's masks, stacking and modulo took 0.1 ms at 10^3 asperities."""
    for k in range(x.size):
        r, z = radius[k], summit[k]
        if not (math.isfinite(x[k]) and math.isfinite(y[k]) and math.isfinite(r) and r > 0 and math.isfinite(z)
                and z > 0 and (z <= r or not caps)):
            return False
        if periodic:
            centers[k, 0], centers[k, 1] = x[k] % window, y[k] % window
        elif x[k] < 0 or x[k] > window or y[k] < 0 or y[k] > window:
            return False
        else:
            centers[k, 0], centers[k, 1] = x[k], y[k]
    return True


def _refuse_columns(x, y, radius, summit, footprint_radius, window, periodic) -> None:
    """Raise the error naming the column that :func:`_valid_columns` found wrong."""
    for name, column in (("center_x", x), ("center_y", y)):
        bad = np.flatnonzero(~np.isfinite(column))
        if bad.size:
            raise ValueError(f"{name}: NaN or infinite position of asperity {bad.tolist()[:5]}")
    bad = np.flatnonzero(~(np.isfinite(radius) & (radius > 0)))
    if bad.size:
        raise ValueError(f"radius must be finite and > 0: asperity {bad.tolist()[:5]} has {radius[bad][:5].tolist()}")
    cap = summit <= radius if footprint_radius is None else True
    bad = np.flatnonzero(~(np.isfinite(summit) & (summit > 0) & cap))
    if bad.size:
        raise ValueError(f"summit_height must lie in (0, radius] (a cap above the base): asperity "
                         f"{bad.tolist()[:5]} has {summit[bad][:5].tolist()}")
    centers = np.stack([x, y], axis=1)
    if not periodic and (np.any(centers < 0) or np.any(centers > window)):
        raise ValueError("center_x, center_y: a non-periodic window holds its asperities inside [0, length]")
    raise RuntimeError("asperities: the table's check and its error messages disagree")  # not reached


def check_separate(table: AsperityTable) -> None:
    """Refuse footprints that intersect: the method needs each cap to be its own sphere."""
    footprint = table.footprint_radius
    k, l, r = table.neighbour_pairs(2 * float(footprint.max()))
    overlap = r < footprint[k] + footprint[l]
    if np.any(overlap):
        i = int(np.flatnonzero(overlap)[0])
        raise ValueError(
            f"asperities overlap: asperity {k[i]} and {l[i]} are {r[i]:.4g} apart but their footprints have radii "
            f"{footprint[k[i]]:.4g} and {footprint[l[i]]:.4g} ({int(overlap.sum())} overlapping pairs); the two-scale "
            "method assumes separate spherical caps (place them further apart or lower the summits)")


def asperity_forces(pressure: np.ndarray, table: AsperityTable) -> np.ndarray:
    """Force on each asperity from a pressure field on the table's grid (e.g. :func:`contactlib.solve`'s):
    the pressure summed over its footprint times the node area [force]. With separate footprints every
    loaded node belongs to one asperity at most.

    Parameters
    ----------
    pressure : xarray.DataArray or ndarray
        Pressure field on the table's grid [pressure]: a DataArray's x and y read by name, an ndarray indexed
        ``[ix, iy]``.
    table : AsperityTable
        The asperities, with their grid.

    Returns
    -------
    ndarray
        Force on each asperity [force].

    Raises
    ------
    ValueError
        When the table has no grid, or ``pressure`` is not on it.
    """
    if table.grid is None:
        raise ValueError("asperities: the table has no grid to read a pressure field on")
    pressure = solver_values(pressure, "pressure")  # a DataArray's x and y by name: [ix, iy], as the table's grid
    if pressure.shape != table.grid.shape:
        raise ValueError(f"pressure has shape {pressure.shape}, the grid {table.grid.shape}")
    n, step = table.grid.shape[0], table.grid.spacing[0]
    x = np.arange(n) * step
    out = np.zeros(table.count)
    for k, (c, reach) in enumerate(zip(table.centers, table.footprint_radius)):
        half = int(np.ceil(reach / step)) + 1
        idx = [np.arange(n) if 2 * half + 1 >= n else (int(np.rint(c[a] / step)) + np.arange(-half, half + 1)) % n
               for a in range(2)]
        d = [x[i] - c[a] for a, i in enumerate(idx)]
        if table.periodic:
            d = [(v + table.length / 2) % table.length - table.length / 2 for v in d]
        inside = d[0][:, None] ** 2 + d[1][None, :] ** 2 < reach**2
        out[k] = float(np.sum(pressure[np.ix_(*idx)] * inside)) * step * step
    return out


def cell_pairs(centers: np.ndarray, length: float, reach: float, periodic: bool) -> tuple[np.ndarray, np.ndarray,
                                                                                        np.ndarray]:
    """Pairs ``(k, l)``, ``k < l``, of points of the window ``[0, length]^2`` at most ``reach`` apart (nearest
    periodic image when ``periodic``), and their distances [length], by a cell list: cells at least ``reach``
    wide, each cell against itself and four of its neighbours (each pair of cells once), in a numba kernel that
    walks the points sorted by cell (each cell's coordinates contiguous, no index per candidate). At 10^3
    points and 9 300 pairs about 0.1 ms, where a k-d tree query and the distances of its pairs took 1.2 ms.
    The pairs come grouped by cell."""
    centers = np.ascontiguousarray(centers, dtype=float)
    # cells at least reach wide, and about as many as points at most (a short reach: no cells^2 blow-up)
    cells = max(min(int(length / reach), int(math.sqrt(len(centers))) + 1), 1) if reach > 0 else 1
    if periodic and cells < 3:
        cells = 1  # fewer than three cells a side: the neighbouring cells would wrap onto the same ones
    index = np.minimum((centers * (cells / length)).astype(np.int64), cells - 1)
    cell = index[:, 0] * cells + index[:, 1]
    order = np.argsort(cell, kind="stable")
    start = np.searchsorted(cell[order], np.arange(cells * cells + 1))
    xy = np.ascontiguousarray(centers[order].T)
    # room for the pairs of a uniform field within reach and a third more; a clustered field with more is walked
    # again with room for all (the candidates' bound, 3x the pairs at 10^3 points, put each array above glibc's
    # mmap threshold: fresh pages on every call)
    n = len(centers)
    room = int(min(1.35 * 0.5 * n * n * math.pi * reach * reach / (length * length), 0.5 * n * n)) + 64
    while True:
        k, l, r = np.empty(room, np.int64), np.empty(room, np.int64), np.empty(room)
        count = _cell_pairs(xy, order, start, cells, float(length), float(reach), bool(periodic), k, l, r)
        if count <= room:
            return k[:count], l[:count], r[:count]
        room = count


_FORWARD = np.array([[0, 0], [0, 1], [1, -1], [1, 0], [1, 1]])
"""A cell and the four neighbours ahead of it: with the other four's own, every pair of the 3 x 3 block once."""


@jit
def _neighbour_cell(a, b, f, cells, length, periodic):
    """Cell ``f`` of :data:`_FORWARD` from cell ``(a, b)``: its flat index (-1 outside a non-periodic window) and
    the shift of its image across the window's edge."""
    a, b = a + _FORWARD[f, 0], b + _FORWARD[f, 1]
    sx = sy = 0.0
    if periodic:
        if a < 0 or a >= cells:
            sx = length if a >= cells else -length
            a %= cells
        if b < 0 or b >= cells:
            sy = length if b >= cells else -length
            b %= cells
    elif a < 0 or a >= cells or b < 0 or b >= cells:
        return -1, sx, sy
    return a * cells + b, sx, sy


@jit
def _cell_pairs(xy, order, start, cells, length, reach, periodic, k_out, l_out, r_out):
    """The pairs of :func:`cell_pairs` from the coordinates sorted by cell ``xy`` (2, N) (point ``order[t]`` at
    ``xy[:, t]``; cell ``c``'s points at ``start[c]`` to ``start[c + 1]``), written to ``k_out``, ``l_out``, ``r_out``
    as far as they have room; returns how many there are."""
    reach2 = reach * reach
    blocks = 1 if cells == 1 else 5
    wrap = periodic and cells == 1  # one cell: the nearest image pair by pair
    room = k_out.size
    x, y = xy[0], xy[1]
    count = 0
    for a in range(cells):
        for b in range(cells):
            first, last = start[a * cells + b], start[a * cells + b + 1]
            for f in range(blocks):
                c, sx, sy = _neighbour_cell(a, b, f, cells, length, periodic)
                if c < 0:
                    continue
                for s in range(first, last):
                    xi, yi = x[s] - sx, y[s] - sy
                    for t in range(s + 1 if f == 0 else start[c], start[c + 1]):  # the own cell: each pair once
                        dx, dy = x[t] - xi, y[t] - yi
                        if wrap:
                            dx -= length * np.rint(dx / length)
                            dy -= length * np.rint(dy / length)
                        d2 = dx * dx + dy * dy
                        if d2 <= reach2:
                            if count < room:
                                i, j = order[s], order[t]
                                k_out[count], l_out[count] = min(i, j), max(i, j)
                                r_out[count] = math.sqrt(d2)
                            count += 1
    return count
