"""Deterministic geometries: wavy profiles and surfaces, paraboloids, spherical asperity fields."""

from __future__ import annotations

import math
import numbers

import numpy as np
import xarray as xr

from .._version import __version__
from ..core.grid import Grid
from ..core.inputs import check_whole, number, real_values
from ..core.labels import attrs_for, field_dims, field_values


def _as_dataarray(values, grid: Grid, length_unit: str, **attrs) -> xr.DataArray:
    dims = ("x", "y")[: grid.dim]
    coords = {d: (d, c, attrs_for(d, length=length_unit)) for d, c in zip(dims, grid.coordinates())}
    a = attrs_for("height", length=length_unit)
    a.update(attrs, contactlib_version=__version__)
    return xr.DataArray(field_values(dims, values), dims=field_dims(dims), coords=coords, name="height", attrs=a)


def _grid(n, length, dim) -> Grid:
    if isinstance(dim, bool) or dim not in (1, 2):
        raise ValueError(f"dim must be 1 or 2, got {dim!r}")
    n = check_whole(n, "n", 2)
    return Grid((n,) * dim, (number("length", length, lower=0.0, lower_open=True),) * dim)


def _per_asperity(name: str, value, k: int) -> np.ndarray:
    """One finite value [length] per asperity from one number or ``k`` of them, refused by ``name``."""
    values = real_values(value, name)
    try:
        values = np.broadcast_to(values, (k,))
    except ValueError:
        raise ValueError(f"{name} must be one value or one per asperity ({k}), got shape {values.shape}") from None
    if not np.all(np.isfinite(values)):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return values


def wavy(n: int, *, length: float = 1.0, amplitude: float, wavelengths: int = 1, dim: int = 1,
         length_unit: str = "m") -> xr.DataArray:
    """``amplitude cos(q x)`` (1D) or the egg-box ``amplitude cos(q x) cos(q y)`` (2D), with
    ``q = 2 pi wavelengths / length``; a crest sits at the origin.

    Parameters
    ----------
    n : int
        Points per side (``n x n`` in 2D, ``n`` in 1D), at least 2.
    length : float
        Window size [length].
    amplitude : float
        Amplitude [length].
    wavelengths : int
        Whole wavelengths over the window, in ``[1, n/2]``.
    dim : {1, 2}
        A profile (1D) or a surface (2D).
    length_unit : str
        udunits string written to the ``units`` attributes of the heights and coordinates.

    Returns
    -------
    xarray.DataArray
        ``height`` [length] on ``("y", "x")`` (2D) or ``("x",)`` (1D), coordinates from 0, with ``units`` and
        ``long_name``.

    Raises
    ------
    ValueError
        Naming ``n``, ``dim`` or ``wavelengths`` out of range.

    Examples
    --------
    >>> import contactlib
    >>> h = contactlib.surfaces.wavy(8, amplitude=0.01)
    >>> float(h[0])
    0.01
    """
    amplitude = number("amplitude", amplitude, lower=0.0, lower_open=True)
    grid = _grid(n, length, dim)
    length = grid.lengths[0]
    # a whole number of waves, resolved: the window stays periodic and the wave is not aliased
    if isinstance(wavelengths, bool) or not isinstance(wavelengths, numbers.Real) or not math.isfinite(wavelengths) \
            or int(wavelengths) != wavelengths \
            or not 1 <= wavelengths <= int(n) // 2:
        raise ValueError(f"wavelengths must be a whole number in [1, n/2 = {int(n) // 2}], got {wavelengths!r}")
    q = 2 * np.pi * wavelengths / length
    xs = grid.coordinates()
    h = amplitude * np.cos(q * xs[0])
    if dim == 2:
        h = h[:, None] * np.cos(q * xs[1])[None, :]
    return _as_dataarray(h, grid, length_unit, generator="contactlib.surfaces.wavy", periodic=1, amplitude=amplitude,
                         wavelength=length / wavelengths)


def paraboloid(n: int, *, length: float = 1.0, radius: float, dim: int = 2, length_unit: str = "m") -> xr.DataArray:
    """Sphere (2D) or cylinder (1D) tip ``-r^2 / (2 radius)`` centred in the window, apex at 0.

    Parameters
    ----------
    n : int
        Points per side (``n x n`` in 2D, ``n`` in 1D), at least 2.
    length : float
        Window size [length].
    radius : float
        Radius of curvature at the apex [length].
    dim : {1, 2}
        A profile (1D) or a surface (2D).
    length_unit : str
        udunits string written to the ``units`` attributes of the heights and coordinates.

    Returns
    -------
    xarray.DataArray
        ``height`` [length] on ``("y", "x")`` (2D) or ``("x",)`` (1D), coordinates from 0, with ``units`` and
        ``long_name``.

    Raises
    ------
    ValueError
        Naming ``n`` or ``dim`` out of range.

    Examples
    --------
    >>> import contactlib
    >>> h = contactlib.surfaces.paraboloid(64, length=1.0, radius=1.0)
    >>> float(h.sel(y=0.5).idxmax())  # the apex is at the window's centre
    0.5
    """
    radius = number("radius", radius, lower=0.0, lower_open=True)
    grid = _grid(n, length, dim)
    length = grid.lengths[0]
    xs = [c - length / 2 for c in grid.coordinates()]
    r2 = xs[0] ** 2 if dim == 1 else xs[0][:, None] ** 2 + xs[1][None, :] ** 2
    return _as_dataarray(-r2 / (2 * radius), grid, length_unit, generator="contactlib.surfaces.paraboloid",
                         radius=radius)


SUMMIT_FRACTION = 0.1
"""Default summit height of :func:`spheres`, as a fraction of each asperity's radius: a cap a tenth of its sphere's
radius high, whose footprint on the base has a radius of 0.44 of the sphere's."""


def spheres(n: int, *, length: float = 1.0, radius, summit_height=None, centers=None, count: int | None = None,
            lattice: int | None = None, height_std: float = 0.0, seed: int = 0, dim: int = 2,
            length_unit: str = "m") -> xr.DataArray:
    """Periodic field of spherical asperities on a flat base.

    Either a square ``lattice`` of ``lattice x lattice`` asperities, ``count`` asperities at
    uniformly random positions, or explicit ``centers`` (array ``(k, dim)`` [length]).
    Summit heights [length] are ``summit_height`` (one value or one per asperity; default None: 0 with scatter,
    about which the summits scatter as before, and :data:`SUMMIT_FRACTION` of each asperity's radius without, where
    0 left no cap above the base) plus Gaussian scatter of std ``height_std``;
    ``radius`` may be one value or one per asperity. Each cap is the exact sphere
    ``z_k - R_k + sqrt(R_k^2 - r^2)`` (nearest periodic image), truncated at the base 0.

    The returned DataArray carries its asperity table in ``attrs`` (1D arrays, one entry per
    asperity): ``asperity_center_x``, ``asperity_center_y`` [length] (2D only), ``asperity_radius``
    [length] and ``asperity_summit_height`` [length], so the same object feeds :func:`contactlib.solve`
    and :func:`contactlib.two_scale.solve`.


    Parameters
    ----------
    n : int
        Points per side (``n x n`` in 2D, ``n`` in 1D), at least 2.
    length : float
        Window size [length].
    radius : float or array_like
        Sphere radius [length], one value or one per asperity.
    summit_height : float or array_like, optional
        Summit heights above the base [length] before the scatter (see above).
    centers : array_like, optional
        Explicit centres, shape ``(k, dim)`` [length].
    count : int, optional
        Number of asperities at uniformly random positions.
    lattice : int, optional
        Asperities per side of a square lattice.
    height_std : float
        Standard deviation of the summits' Gaussian scatter [length].
    seed : int
        Seed of ``numpy.random.default_rng`` for the positions and the scatter.
    dim : {1, 2}
        A profile (1D) or a surface (2D).
    length_unit : str
        udunits string written to the ``units`` attributes of the heights and coordinates.


    Returns
    -------
    xarray.DataArray
        ``height`` [length] on ``("y", "x")`` (2D) or ``("x",)`` (1D), coordinates from 0, with ``units`` and
        ``long_name``. Its ``attrs`` hold the asperity table.

    Raises
    ------
    ValueError
        Naming the parameter: a wrong type or shape, a value out of range, no asperity above the base, or a
        summit above its sphere's radius.
    """
    grid = _grid(n, length, dim)
    length = grid.lengths[0]
    rng = np.random.default_rng(seed)
    if sum(v is not None for v in (centers, count, lattice)) != 1:
        raise ValueError("give exactly one of centers, count or lattice")
    for name, value in (("lattice", lattice), ("count", count)):
        if value is not None:
            check_whole(value, name)
    height_std = number("height_std", height_std, lower=0.0)
    if lattice is not None:
        pos = (np.arange(lattice) + 0.5) * length / lattice
        mesh = np.meshgrid(*([pos] * dim), indexing="ij")
        centers = np.stack([m.ravel() for m in mesh], axis=1)
    elif count is not None:
        centers = rng.uniform(0, length, size=(int(count), dim))
    centers = np.atleast_2d(real_values(centers, "centers"))
    if centers.ndim != 2 or centers.shape[1] != dim or not np.all(np.isfinite(centers)):
        raise ValueError(f"centers must be finite, one row of {dim} coordinate(s) per asperity, got shape "
                         f"{centers.shape}")
    k = centers.shape[0]
    radii = _per_asperity("radius", radius, k)
    if not np.all(radii > 0):
        raise ValueError("radius must be finite and > 0")
    if summit_height is None:  # scattered summits about the base, as before; without scatter, caps of a tenth R
        summits = np.zeros(k) if height_std > 0 else SUMMIT_FRACTION * radii
    else:
        summits = _per_asperity("summit_height", summit_height, k)
    tops = summits + height_std * rng.standard_normal(k)
    if not np.any(tops > 0):
        raise ValueError(f"summit_height: no asperity rises above the base (summits {np.max(tops):.4g} at the "
                         "highest); the surface would be flat")
    if np.any(tops > radii):
        raise ValueError("summit_height must not exceed radius: a cap higher than its sphere's radius is more than "
                         "a hemisphere (a cliff on the grid)")
    xs = grid.coordinates()
    h = np.zeros(grid.shape)
    for c, R, z in zip(centers, radii, tops):
        if not z > 0:
            continue  # a cap at or below the base leaves it unchanged
        # only the footprint (radius sqrt(z (2R - z)) or R) can rise above the base: compute the cap on its
        # bounding box of nodes (the same values as on the whole grid, in far fewer operations)
        reach = np.sqrt(z * (2 * R - z)) if z < R else R
        box = []
        for axis, x in enumerate(xs):
            n_axis, step = grid.shape[axis], grid.spacing[axis]
            half = int(np.ceil(reach / step)) + 1
            if 2 * half + 1 >= n_axis:
                box.append(np.arange(n_axis))
            else:
                box.append((int(np.rint(c[axis] / step)) + np.arange(-half, half + 1)) % n_axis)
        d2 = np.zeros(tuple(len(b) for b in box))
        for axis, (x, b) in enumerate(zip(xs, box)):
            dx = (x[b] - c[axis] + length / 2) % length - length / 2
            d2 = d2 + (dx[:, None] ** 2 if (dim == 2 and axis == 0) else dx[None, :] ** 2 if dim == 2 else dx**2)
        cap = np.where(d2 < R**2, z - R + np.sqrt(np.clip(R**2 - d2, 0, None)), -np.inf)
        block = np.ix_(*box)
        h[block] = np.maximum(h[block], cap)
    table = {f"asperity_center_{axis}": np.array(centers[:, i]) for i, axis in enumerate("xy"[:dim])}
    table.update(asperity_radius=np.array(radii, dtype=float), asperity_summit_height=np.array(tops, dtype=float))
    return _as_dataarray(h, grid, length_unit, generator="contactlib.surfaces.spheres", periodic=1, asperities=k,
                         seed=seed, **table)
