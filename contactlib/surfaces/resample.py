"""Resample a periodic surface on another grid through its trigonometric (Fourier) interpolant."""

from __future__ import annotations

import numpy as np
import scipy.signal
import xarray as xr

from ..core.grid import Grid
from ..core.labels import attrs_for


def resample(heights: xr.DataArray, n: int) -> xr.DataArray:
    """The band-limited periodic surface of ``heights`` sampled on ``n`` points per side.

    Every Fourier mode of ``heights`` below the new Nyquist wavenumber is kept with its amplitude
    and phase (refining: the spectrum is zero-padded, so the old nodes keep their values exactly;
    coarsening: the spectrum is truncated). So ``resample(h, 4 * n)`` is the *same* continuous
    surface as ``h`` on a 4x finer grid, which :func:`self_affine` with the same seed is not (its
    white noise is drawn on the grid it is asked for).

    Parameters
    ----------
    heights : xarray.DataArray
        Periodic surface with ``x`` (and ``y``) coordinates starting at 0 (as the generators give).
    n : int
        Points per side of the new grid.


    Returns
    -------
    xarray.DataArray
        The same surface on ``n`` points per side, with the attributes of ``heights``.


    Raises
    ------
    ValueError
        When ``heights`` is not a DataArray with its coordinates, or ``n`` is not an integer >= 2.

    Examples
    --------
    >>> import contactlib
    >>> h = contactlib.surfaces.self_affine(32, hurst=0.8, q_roll=2, q_cutoff=8, rms_slope=0.1, seed=1)
    >>> fine = contactlib.surfaces.resample(h, 128)
    >>> bool(abs(fine.values[::4, ::4] - h.values).max() < 1e-12 * float(abs(h).max()))
    True
    """
    if not isinstance(heights, xr.DataArray):
        raise ValueError(f"heights must be a DataArray with its coordinates (as the generators give), got "
                         f"{type(heights).__name__}")
    if isinstance(n, bool) or not np.isfinite(n) or int(n) != n or n < 2:
        raise ValueError(f"n must be an integer >= 2, got {n!r}")
    n = int(n)
    values = np.asarray(heights.values, dtype=float)
    for axis in range(values.ndim):
        values = scipy.signal.resample(values, n, axis=axis)  # Fourier method, Nyquist term split/merged
    lengths = tuple(float(heights[d][1] - heights[d][0]) * heights.sizes[d] for d in heights.dims)
    grid = Grid((n,) * values.ndim, lengths)
    unit = heights.attrs.get("units", "m")
    coords = {d: (d, c, attrs_for(d, length=unit)) for d, c in zip(heights.dims, grid.coordinates())}
    attrs = dict(heights.attrs)
    attrs["resampled_from"] = int(heights.sizes[heights.dims[0]])
    return xr.DataArray(values, dims=heights.dims, coords=coords, name=heights.name, attrs=attrs)
