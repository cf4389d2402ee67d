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
from scipy.spatial import cKDTree

from ..contact import grid_of
from ..grid import Grid

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
    """

    centers: np.ndarray
    radius: np.ndarray
    summit_height: np.ndarray
    length: float
    periodic: bool
    heights: np.ndarray | None = None
    grid: Grid | None = None
    footprint: np.ndarray | None = None

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

    def neighbour_pairs(self, distance: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Pairs ``(k, l)``, ``k < l``, of summits closer than ``distance`` (nearest periodic image),
        and their distances [length]. The widest query is kept on the table and the narrower ones are
        read from it: the overlap check and the Ewald sum's neighbours then cost one k-d tree query."""
        cached = self.__dict__.get("_pairs")
        if cached is None or cached[0] < distance:
            # the validation's query asks for at least the Ewald sum's neighbours, which come next
            reach = max(distance, NEIGHBOUR_SPACINGS * (self.length / math.sqrt(self.count)))  # as the Ewald cutoff
            tree = cKDTree(self.centers, boxsize=self.length if self.periodic else None)
            pairs = tree.query_pairs(reach, output_type="ndarray")
            if pairs.size == 0:
                k = l = np.zeros(0, np.int64)
                r = np.zeros(0)
            else:
                k, l = pairs[:, 0].astype(np.int64), pairs[:, 1].astype(np.int64)
                r = self.distance(k, l)
            cached = (reach, k, l, r)
            self.__dict__["_pairs"] = cached  # a cache, not a field: the dataclass stays frozen
        reach, k, l, r = cached
        if distance >= reach:
            return k, l, r
        keep = r <= distance
        return k[keep], l[keep], r[keep]

    def distance(self, k: np.ndarray, l: np.ndarray) -> np.ndarray:
        """In-plane distance between summits ``k`` and ``l`` (nearest periodic image) [length]."""
        d = self.centers[k] - self.centers[l]
        if self.periodic:
            d -= self.length * np.rint(d / self.length)
        return np.sqrt(np.sum(d**2, axis=-1))


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

    Raises
    ------
    ValueError
        Naming the parameter: missing columns, NaN or infinite positions, ``radius <= 0``,
        ``summit_height`` outside ``(0, radius]``, centres outside a non-periodic window, overlapping
        asperities (footprint discs that intersect: the caps would not be separate spheres).
    """
    heights = grid = None
    if isinstance(asperities, xr.DataArray):
        if asperities.ndim != 2:
            raise ValueError(f"asperities: the two-scale method needs a 2D surface, got {asperities.ndim}D")
        values, grid, _, _ = grid_of(asperities)
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
    if periodic:
        centers = centers % window
    elif np.any(centers < 0) or np.any(centers > window):
        raise ValueError("center_x, center_y: a non-periodic window holds its asperities inside [0, length]")
    footprint = None
    if footprint_radius is not None:
        if not (np.isfinite(footprint_radius) and footprint_radius > 0):
            raise ValueError(f"footprint_radius must be finite and > 0, got {footprint_radius!r}")
        footprint = np.full(n, float(footprint_radius))
    table = AsperityTable(centers, radius, summit, window, bool(periodic), heights, grid, footprint)
    check_separate(table)
    return table


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
    loaded node belongs to one asperity at most."""
    if table.grid is None:
        raise ValueError("asperities: the table has no grid to read a pressure field on")
    pressure = np.asarray(pressure, dtype=float)
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
