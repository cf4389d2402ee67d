"""Measured topographies in: :func:`read` a surface file into the labelled ``height`` DataArray of the generators."""

from __future__ import annotations

import hashlib
import math
import warnings
from pathlib import Path

import numpy as np
import xarray as xr

from ..core.grid import Grid
from ..core.labels import attrs_for, field_dims, field_values
from . import preparation, readers

# attrs that describe one reading; a file written from an earlier reading carries them, and they are renewed
PROVENANCE = ("source_file", "source_sha256", "source_format", "source_reader", "height_unit", "length",
               "length_from", "periodic", "detrend", "detrend_offset", "detrend_slope_x", "detrend_slope_y", "fill",
               "filled_points")


def read(path, *, length=None, unit: str | None = None, periodic: bool | None = None, detrend: str = "plane",
         fill: str | None = None, format: str | None = None) -> xr.DataArray:
    """Read a topography file into a labelled ``height`` DataArray [m], as the generators return.

    Parameters
    ----------
    path : str or path-like
        The file. Formats: contactlib's NetCDF (``contactlib surface``), ``.npy``, a plain-text height
        matrix (one row per y, one column per x: the Contact Mechanics Challenge's "matrix form"), and
        plain-text ``x y z`` columns on a uniform grid (``x z`` for a profile; any text file of 2 or 3
        columns is read so). With ``contactlib[topography]`` installed, every format SurfaceTopography
        reads (AFM, profilometer and interferometer files, ISO 25178 SDF, X3P, MATLAB, HDF5, ...). A
        profile (line scan) gives a 1D DataArray along ``x``.
    length : float or sequence of float, optional
        Window size [unit], one value for every axis or one per axis. Required when the file does not
        carry its size; if it does, ``length`` must agree with it (nothing is guessed or overridden).
    unit : str, optional
        Length unit of the heights and of ``length`` (m, mm, um or µm, nm, pm, Å). Required when the
        file does not state it; if it does, it must agree.
    periodic : bool, optional
        Whether the window is one period of a periodic surface. Default: what the file says (a
        contactlib NetCDF, some SurfaceTopography formats), otherwise False: a measurement is solved
        non-periodic (zero-padded) unless the caller says otherwise. Recorded in ``attrs['periodic']``
        (0 or 1), which :func:`contactlib.solve` honours when not given ``periodic``.
    detrend : {"plane", "line", "mean", "none"}
        Subtract the least-squares plane (``line`` for a profile; ``plane`` on a profile removes the
        line), the mean, or nothing. The trend is fitted to the finite heights before filling.
        Recorded with the removed offset [m] and slopes [1]. A plane removed from a periodic surface
        breaks its periodicity, so that combination warns: use ``mean`` there.
    fill : {None, "interpolate", "mean"}
        Missing points (NaN) are refused, with their count, unless filled: ``mean`` of the finite
        heights, or ``interpolate`` (piecewise-linear over a Delaunay triangulation of the finite
        points bordering the holes, nearest finite height outside their hull; linear along a profile).
    format : str, optional
        Force a format: ``netcdf``, ``npy``, ``matrix``, ``xyz``, or a SurfaceTopography format id
        (``x3p``, ``sdf``, ``di``, ...). Default: from the extension (and a text file's column count).

    Returns
    -------
    xarray.DataArray
        ``height`` [m] with dims ``("y", "x")`` or ``("x",)`` (a ``.npy`` array is indexed ``[ix, iy]``, a
        text matrix has one row per y, a NetCDF ``height`` is read by its dims' names), coordinates [m] (``i * length / n``, or
        the file's own uniform positions), and attrs: ``source_file`` (name), ``source_sha256``,
        ``source_format``, ``source_reader``, ``height_unit`` (the file's), ``length`` [m] per axis,
        ``length_from`` (file or argument), ``periodic``, ``detrend`` (+ what it removed), ``fill``,
        ``filled_points``. The same file and arguments give the same array, bit for bit; heights in
        metres are not rescaled, so a surface written by contactlib reads back bit-identical with
        ``detrend="none"``.

    Raises
    ------
    FileNotFoundError, ValueError
        A missing file; an unknown format (the message lists the native formats and says that
        ``contactlib[topography]`` adds more); ragged rows; a non-uniform grid or one that does not
        fill a rectangle; a missing size or unit; NaN heights without ``fill``. Each names the file.

    Examples
    --------
    >>> import contactlib  # doctest: +SKIP
    >>> h = contactlib.surfaces.read("surface.2048x2048.ASCII.dat", length=0.1, unit="mm", periodic=True,
    ...                              detrend="mean")                                   # doctest: +SKIP
    """
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"{path}: no such file")
    raw = readers.read_raw(path, format)
    values = raw.heights
    if values.ndim not in (1, 2) or min(values.shape) < 2:
        raise ValueError(f"{path}: heights of shape {values.shape}; need a profile or a map of at least 2 points "
                         "per axis")
    unit = resolve_unit(path, raw.unit, unit)
    lengths, length_from = resolve_lengths(path, raw.lengths, length, values.ndim, unit)
    if np.isinf(values).any():
        raise ValueError(f"{path}: {int(np.isinf(values).sum())} heights are infinite")
    missing = int(np.isnan(values).sum())
    if missing and fill is None:
        raise ValueError(f"{path}: {missing} of {values.size} heights are missing (NaN); pass fill='interpolate' "
                         "or fill='mean' to fill them")
    if missing == values.size:
        raise ValueError(f"{path}: every height is missing (NaN)")
    values = preparation.to_metres(values, unit)
    lengths = tuple(float(preparation.to_metres(v, unit)) for v in lengths)
    grid = Grid(values.shape, lengths)
    coords = grid.coordinates() if raw.coords is None else tuple(preparation.to_metres(c, unit) for c in raw.coords)
    periodic = bool(raw.periodic) if periodic is None and raw.periodic is not None else bool(periodic)
    if periodic and detrend in ("plane", "line"):
        warnings.warn(f"{path}: detrend={detrend!r} on a periodic surface makes it non-periodic (the plane steps "
                      "at the window edge); detrend='mean' keeps it periodic", UserWarning, stacklevel=2)
    values, trend = preparation.remove_trend(values, detrend, grid.spacing)
    if fill is not None:
        values, filled = preparation.fill_missing(values, fill)
    else:
        filled = 0

    dims = ("x", "y")[: values.ndim]
    attrs = {k: v for k, v in raw.attrs.items() if k not in PROVENANCE}
    attrs.update(attrs_for("height"))
    attrs.update(source_file=path.name, source_sha256=file_sha256(path), source_format=raw.format,
                 source_reader=raw.reader, height_unit=unit, length=list(lengths), length_from=length_from,
                 periodic=int(periodic), **trend, fill=fill or "none", filled_points=filled)
    return xr.DataArray(field_values(dims, values), dims=field_dims(dims), name="height", attrs=attrs,
                        coords={d: (d, c, attrs_for(d)) for d, c in zip(dims, coords)})


def resolve_unit(path: Path, file_unit: str | None, unit: str | None) -> str:
    if file_unit is None and unit is None:
        raise ValueError(f"{path}: the file does not state its length unit; pass unit= (m, mm, um, nm, ...)")
    if file_unit is not None and unit is not None and _canonical(unit) != _canonical(file_unit):
        raise ValueError(f"{path}: the file states its unit as {file_unit!r}, not {unit!r}; leave unit= out")
    chosen = unit if file_unit is None else file_unit
    if chosen not in preparation.METRES_PER:
        raise ValueError(f"{path}: unknown length unit {chosen!r}; known: {', '.join(preparation.METRES_PER)}")
    return chosen


def _canonical(unit: str) -> str:
    return {"µm": "um", "μm": "um", "micron": "um", "Å": "angstrom"}.get(unit, unit)


def resolve_lengths(path: Path, file_lengths, length, ndim: int, unit: str) -> tuple[tuple[float, ...], str]:
    if length is None:
        if file_lengths is None:
            raise ValueError(f"{path}: the file does not carry its physical size; pass length= (in {unit}, one "
                             "value or one per axis)")
        return tuple(file_lengths), "file"
    given = np.atleast_1d(np.asarray(length, dtype=float))
    if given.size not in (1, ndim):
        raise ValueError(f"{path}: length= needs 1 or {ndim} values for a {ndim}D topography, got {given.size}")
    given = tuple(float(v) for v in np.broadcast_to(given, (ndim,)))
    if not all(math.isfinite(v) and v > 0 for v in given):
        raise ValueError(f"{path}: length must be finite and > 0, got {length!r}")
    if file_lengths is not None:
        if not np.allclose(given, file_lengths, rtol=1e-9, atol=0):
            raise ValueError(f"{path}: the file carries its size {tuple(file_lengths)} {unit}, not {given}; leave "
                             "length= out")
        return tuple(file_lengths), "file"
    return given, "argument"


def file_sha256(path: Path) -> str:
    digest = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()
