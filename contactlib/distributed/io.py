"""Surfaces read and results written by slab, as the NetCDF files of the serial command line.

Reading: each rank reads its rows of x of the ``height`` variable with netCDF4's slicing (HDF5 reads only those
chunks), never the whole field. A rank's slab is rows of x in memory (``[ix, iy]``, as the solvers index), and the
files hold 2D fields on ``("y", "x")`` as every contactlib file does (``("x", "y")`` files of older versions are read
too), so a rank reads and writes a column block of the file's variable: netCDF4's hyperslabs take either.

Writing: one NetCDF file that the serial tools open, written in rank order. The netCDF4 wheels from PyPI are
not parallel-HDF5 builds (``netCDF4.__has_parallel4_support__`` is 0), so ranks cannot write one file at once;
gathering the fields on one rank would need the whole grid's memory there, which is what distributing avoids.
So rank 0 writes the header (the field variables, defined but unwritten, then the coordinates, scalars and
attributes through xarray, with the serial file's encodings), and each rank in turn opens the file and writes its
rows. The cost is the file's I/O, serialised; every rank holds only its slab. The file is written under a
temporary name and moved into place at the end, as the serial command does.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import xarray as xr

from ..core.labels import SOLVER_AXES, attrs_for, field_dims, field_values
from ..surfaces.measured import PROVENANCE, resolve_lengths, resolve_unit, file_sha256
from ..surfaces.preparation import to_metres
from .slabs import Slabs


def read_slab(comm, path, *, length=None, unit: str | None = None, periodic: bool | None = None) -> xr.DataArray:
    """This rank's rows of :func:`contactlib.surfaces.read` of a contactlib NetCDF surface with ``detrend="none"``
    and no ``fill`` (what ``contactlib solve`` does with a ``.nc`` file): the same values (bit for bit), coordinates
    and attributes. Other formats, detrending and filling need the whole surface: refused (ValueError)."""
    import netCDF4

    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"{path}: no such file")
    with netCDF4.Dataset(path) as nc:
        if "height" not in nc.variables:
            raise ValueError(f"{path}: a distributed solve reads contactlib NetCDF surfaces (a 'height' variable)")
        var = nc["height"]
        if var.dimensions not in (("y", "x"), ("x", "y")):
            raise ValueError(f"{path}: 'height' has dims {var.dimensions}; a distributed solve reads ('y', 'x') "
                             "or ('x', 'y')")
        var.set_auto_mask(False)
        rows_along_x = var.dimensions == ("x", "y")
        nx, ny = var.shape if rows_along_x else var.shape[::-1]
        start, stop = Slabs(nx, comm.Get_size()).bounds(comm.Get_rank())
        raw = np.asarray(var[start:stop, :] if rows_along_x else var[:, start:stop].T, dtype=float)  # [ix, iy]
        file_attrs = {k: var.getncattr(k) for k in var.ncattrs() if k != "_FillValue"}
        coords = tuple(np.asarray(nc[d][:], dtype=float) if d in nc.variables else None for d in ("x", "y"))
    file_unit = file_attrs.get("units")
    unit = resolve_unit(path, file_unit, unit)
    file_lengths = None if any(c is None for c in coords) else tuple(float(c[1] - c[0]) * c.size for c in coords)
    lengths, length_from = resolve_lengths(path, file_lengths, length, 2, unit)
    if not comm.allreduce(bool(np.all(np.isfinite(raw)))):
        raise ValueError(f"{path}: heights missing (NaN) or infinite; fill them with the serial "
                         "`contactlib surface --from FILE --fill ...` first")
    values = to_metres(raw, unit)
    lengths = tuple(float(to_metres(v, unit)) for v in lengths)
    if coords[0] is None:
        coords = tuple(np.arange(n) * (L / n) for n, L in zip((nx, ny), lengths))
    else:
        coords = tuple(to_metres(c, unit) for c in coords)
    file_periodic = file_attrs.get("periodic")
    if file_periodic is None and file_attrs.get("generator") == "contactlib.surfaces.self_affine":
        file_periodic = True
    periodic = bool(file_periodic) if periodic is None and file_periodic is not None else bool(periodic)
    attrs = {k: v for k, v in file_attrs.items() if k not in ("units", "long_name", "periodic") + PROVENANCE}
    attrs.update(attrs_for("height"))
    digest = file_sha256(path) if comm.Get_rank() == 0 else None
    attrs.update(source_file=path.name, source_sha256=comm.bcast(digest), source_format="netcdf",
                 source_reader="contactlib", height_unit=unit, length=list(lengths), length_from=length_from,
                 periodic=int(periodic), detrend="none", fill="none", filled_points=0)
    return xr.DataArray(field_values(SOLVER_AXES, values), dims=field_dims(SOLVER_AXES), name="height", attrs=attrs,
                        coords={"x": ("x", coords[0][start:stop], attrs_for("x")),
                                "y": ("y", coords[1], attrs_for("y"))})


def write_slabs(comm, path, *, shape: tuple[int, int], fields: dict, header: xr.Dataset) -> None:
    """Write one NetCDF file: ``header`` (coordinates ``x``, ``y`` of the whole grid, scalars, attributes) by rank
    0, then ``fields`` (name: ``(rows of x of this rank, indexed [ix, iy], attrs)``) by every rank in turn, each
    at its block of columns of the file's ``("y", "x")`` variables. ``shape`` is ``(nx, ny)``."""
    import netCDF4

    rank, size = comm.Get_rank(), comm.Get_size()
    tmp = comm.bcast(f"{path}.tmp{os.getpid()}" if rank == 0 else None)
    if rank == 0:
        with netCDF4.Dataset(tmp, "w", format="NETCDF4") as nc:
            nc.createDimension("x", shape[0])
            nc.createDimension("y", shape[1])
            for name, (_, attrs) in fields.items():  # defined first: the serial files list the fields first
                var = nc.createVariable(name, "f8", field_dims(SOLVER_AXES), fill_value=np.nan)
                var.setncatts(attrs)
        header.to_netcdf(tmp, mode="a")
    start, _ = Slabs(shape[0], size).bounds(rank)
    for turn in range(size):
        comm.Barrier()
        if turn == rank:
            with netCDF4.Dataset(tmp, "a") as nc:
                for name, (values, _) in fields.items():
                    nc[name][:, start: start + values.shape[0]] = field_values(SOLVER_AXES, values)
    comm.Barrier()
    if rank == 0:
        os.replace(tmp, path)  # never leave a partial file under the final name
    comm.Barrier()


def coordinate_header(shape, lengths, *, length_unit: str = "m") -> dict:
    """The ``x``, ``y`` coordinates of the whole grid (two 1D arrays: small)."""
    return {d: (d, np.arange(n) * (L / n), attrs_for(d, length=length_unit))
            for d, n, L in zip(("x", "y"), shape, lengths)}
