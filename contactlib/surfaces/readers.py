"""Topography file formats: raw heights and what the file says about their size, unit and periodicity.

Native formats (no extra dependency): contactlib's NetCDF, ``.npy``, a plain-text height matrix and
plain-text ``x y z`` (or ``x z``) columns on a uniform grid. Every other format goes through
SurfaceTopography's readers (``pip install contactlib[topography]``), imported only when such a
file is read.

Axis convention: heights come out as ``values[i, j] = h(x_i, y_j)``, x along the first axis, as in
contactlib and in SurfaceTopography (whose ``heights()[i, j]`` is the height at ``(i sx/nx, j sy/ny)``).
A text matrix holds one row per y and one column per x (the Contact Mechanics Challenge's "matrix
form" and SurfaceTopography's ``to_matrix`` layout), so it is transposed on reading.
"""

from __future__ import annotations

import dataclasses
import re
from pathlib import Path

import numpy as np

NATIVE_FORMATS = {
    "netcdf": "NetCDF with a 'height' variable, as written by `contactlib surface` (.nc)",
    "npy": "NumPy array (.npy), x along the first axis",
    "matrix": "plain-text height matrix, one row per y, one column per x (.txt, .dat, .asc, .csv)",
    "xyz": "plain-text columns x y z on a uniform grid, or x z for a profile (.xyz; any text file of 2 or 3 columns)",
}
"""The formats contactlib reads itself, by name (the ``format=`` of :func:`contactlib.surfaces.read`)."""

_EXTENSIONS = {".nc": "netcdf", ".nc4": "netcdf", ".cdf": "netcdf", ".npy": "npy", ".txt": "text", ".dat": "text",
               ".asc": "text", ".csv": "text", ".xyz": "text"}
_TOPOGRAPHY_EXTRA = ("pip install 'contactlib[topography]' adds the 42 formats of SurfaceTopography (Bruker/DI, "
                     "Zygo, Keyence, Sensofar, ISO 25178 SDF, X3P, Gwyddion, MATLAB, HDF5, ...)")
_PERIODIC_GENERATORS = ("contactlib.surfaces.self_affine", "contactlib.surfaces.wavy", "contactlib.surfaces.spheres")
# SurfaceTopography's text-matrix header: '# Width: 1.0 m', '# Height: 0.5 m', '# Value units: m'
_HEADER = re.compile(r"^#\s*(Width|Height|Value units)\s*:\s*(\S+)\s*(\S*)\s*$")


@dataclasses.dataclass
class RawTopography:
    """Heights as stored (file unit, NaN where missing) and the metadata the file carries (None: absent)."""

    heights: np.ndarray
    format: str
    reader: str = "contactlib"
    lengths: tuple[float, ...] | None = None  # window size per axis [file unit]
    unit: str | None = None  # of heights and lengths
    coords: tuple[np.ndarray, ...] | None = None  # node positions per axis [file unit], if stored
    periodic: bool | None = None
    attrs: dict = dataclasses.field(default_factory=dict)  # other attributes worth keeping


def unknown_format_message(path, detail: str = "") -> str:
    native = "; ".join(f"{k}: {v}" for k, v in NATIVE_FORMATS.items())
    installed = " (installed here: it could not read this file either)" if _has_surfacetopography() else ""
    return f"{path}: unknown topography format{detail}. contactlib reads {native}. {_TOPOGRAPHY_EXTRA}{installed}."


def read_raw(path: Path, format: str | None = None) -> RawTopography:
    """Read ``path`` in ``format`` (default: from the extension, then the column count of a text file)."""
    kind = format if format is not None else _EXTENSIONS.get(path.suffix.lower())
    if kind == "netcdf":
        raw = _read_netcdf(path, explicit=format is not None)
        return raw if raw is not None else _read_surfacetopography(path, None)
    if kind == "npy":
        return _read_npy(path)
    if kind in ("text", "matrix", "xyz"):
        return _read_text(path, kind)
    if kind is None and format is None:
        return _read_surfacetopography(path, None)
    return _read_surfacetopography(path, kind)


def _read_netcdf(path: Path, explicit: bool) -> RawTopography | None:
    import xarray as xr

    with xr.open_dataset(path) as ds:
        if "height" not in ds:
            if explicit:
                raise ValueError(f"{path}: NetCDF without a 'height' variable (has {sorted(ds.data_vars)})")
            return None  # another NetCDF layout: SurfaceTopography's, if installed
        height = ds["height"].load()
    if height.dims not in (("x",), ("x", "y"), ("y", "x")):
        raise ValueError(f"{path}: 'height' has dims {height.dims}; contactlib reads ('x',), ('y', 'x') or "
                         "('x', 'y')")
    height = height.transpose(*sorted(height.dims))  # by name: rows along x, as every reader gives them
    unit = height.attrs.get("units")
    coords = None
    if all(d in height.coords for d in height.dims):
        coords = tuple(np.asarray(height[d].values, dtype=float) for d in height.dims)
        for d in height.dims:
            if height[d].attrs.get("units", unit) != unit:
                raise ValueError(f"{path}: coordinate {d!r} is in {height[d].attrs.get('units')!r}, heights in "
                                 f"{unit!r}; contactlib reads files with one length unit")
        for d, c in zip(height.dims, coords):
            _check_uniform(c, d, path)
    periodic = height.attrs.get("periodic")
    if periodic is None and height.attrs.get("generator") in _PERIODIC_GENERATORS:
        periodic = True  # written before surfaces recorded it: these generators are periodic by construction
    keep = {k: v for k, v in height.attrs.items() if k not in ("units", "long_name", "periodic")}
    lengths = None if coords is None else tuple(float(c[1] - c[0]) * c.size for c in coords)
    return RawTopography(np.asarray(height.values, dtype=float), "netcdf", lengths=lengths, unit=unit,
                         coords=coords, periodic=None if periodic is None else bool(periodic), attrs=keep)


def _read_npy(path: Path) -> RawTopography:
    try:
        values = np.load(path, allow_pickle=False)
    except ValueError as err:
        raise ValueError(f"{path}: not a plain .npy array ({err})") from None
    if values.ndim not in (1, 2) or not np.issubdtype(values.dtype, np.number):
        raise ValueError(f"{path}: .npy holds a {values.ndim}D {values.dtype} array; need 1D or 2D numbers")
    return RawTopography(np.asarray(values, dtype=float), "npy")


def _read_text(path: Path, kind: str) -> RawTopography:
    header = {}
    with open(path, encoding="utf-8", errors="replace") as f:
        for line in f:
            if not line.startswith("#"):
                break
            match = _HEADER.match(line.strip())
            if match:
                header[match.group(1)] = (match.group(2), match.group(3) or None)
        first = line
    delimiter = "," if "," in first else None
    try:
        data = np.loadtxt(path, comments="#", delimiter=delimiter, ndmin=2, dtype=float, encoding="utf-8")
    except ValueError as err:
        text = str(err)
        if "number of columns changed" in text:
            raise ValueError(f"{path}: ragged rows in a text matrix: {text}") from None
        if kind != "text":
            raise ValueError(f"{path}: not a numeric text {kind}: {text}") from None
        if _has_surfacetopography():  # e.g. an instrument's ASCII export with a header of its own
            return _read_surfacetopography(path, None)
        raise ValueError(f"{path}: not a numeric text matrix ({text}). {_TOPOGRAPHY_EXTRA}") from None
    if data.size == 0:
        raise ValueError(f"{path}: no numbers in the file")
    columns = data.shape[1]
    if kind == "xyz" or (kind == "text" and columns in (2, 3) and data.shape[0] > columns):
        return _xyz_grid(data, path)
    values = data[0] if data.shape[0] == 1 else data[:, 0] if columns == 1 else data.T  # rows are y: transpose
    lengths, unit = None, None
    if "Width" in header:
        sizes = [header["Width"]] + ([header["Height"]] if values.ndim == 2 and "Height" in header else [])
        if len(sizes) == values.ndim:
            lengths = tuple(float(s[0]) for s in sizes)
            unit = sizes[0][1]
    if "Value units" in header:
        unit = header["Value units"][0]
    return RawTopography(values, "matrix", lengths=lengths, unit=unit)


def _xyz_grid(data: np.ndarray, path: Path) -> RawTopography:
    """Heights on the uniform grid spanned by the x (and y) columns; every grid node exactly once."""
    if data.shape[1] not in (2, 3):
        raise ValueError(f"{path}: {data.shape[1]} columns; an xyz file has x y z (surface) or x z (profile)")
    axes = [_grid_index(data[:, k], "xy"[k], path) for k in range(data.shape[1] - 1)]
    shape = tuple(n for _, n, _ in axes)
    flat = np.ravel_multi_index(tuple(index for index, _, _ in axes), shape)
    counts = np.bincount(flat, minlength=int(np.prod(shape)))
    missing, repeated = int(np.count_nonzero(counts == 0)), int(np.count_nonzero(counts > 1))
    if missing or repeated:
        raise ValueError(f"{path}: the {data.shape[0]} points of this {data.shape[1]}-column file do not fill the "
                         f"{' x '.join(map(str, shape))} grid their coordinates span ({missing} nodes missing, "
                         f"{repeated} given more than once); write missing heights as nan")
    values = np.empty(int(np.prod(shape)))
    values[flat] = data[:, -1]
    coords = tuple(origin + np.arange(n) * step for _, n, (origin, step) in axes)
    lengths = tuple(n * step for _, n, (_, step) in axes)
    return RawTopography(values.reshape(shape), "xyz", lengths=lengths, coords=coords)


def _grid_index(values: np.ndarray, name: str, path: Path):
    """Node index of each value on a uniform axis, the node count, and (origin, spacing)."""
    nodes = np.unique(values)
    span = nodes[-1] - nodes[0]
    nodes = nodes[np.concatenate([[True], np.diff(nodes) > 1e-9 * span])]  # printing noise is the same node
    if nodes.size < 2:
        raise ValueError(f"{path}: every point has the same {name}; need at least 2 nodes along {name}")
    _check_uniform(nodes, name, path)
    step = span / (nodes.size - 1)
    return np.rint((values - nodes[0]) / step).astype(np.int64), nodes.size, (float(nodes[0]), float(step))


def _check_uniform(nodes: np.ndarray, name: str, path: Path) -> None:
    steps = np.diff(nodes)
    if steps.min() <= 0 or steps.max() - steps.min() > 1e-6 * steps.mean():
        raise ValueError(f"{path}: the {name} positions are not a uniform grid (spacing from {steps.min():.6g} to "
                         f"{steps.max():.6g}); contactlib solves on uniform grids: resample the data first")


def _has_surfacetopography() -> bool:
    import importlib.util

    try:
        return importlib.util.find_spec("SurfaceTopography") is not None
    except ValueError:  # a test's sys.modules["SurfaceTopography"] = None
        return False


def _read_surfacetopography(path: Path, format: str | None) -> RawTopography:
    """Heights and metadata through SurfaceTopography (its axis convention is ours: x along the first axis)."""
    try:
        import SurfaceTopography
        from SurfaceTopography.IO import CannotDetectFileFormat, UnknownFileFormat, open_topography
    except ImportError:
        detail = f" {path.suffix!r}" if format is None else f" {format!r}"
        raise ValueError(unknown_format_message(path, detail)) from None
    try:
        reader = open_topography(str(path), format=format)
    except (CannotDetectFileFormat, UnknownFileFormat) as err:
        raise ValueError(unknown_format_message(path, f" ({type(err).__name__}: {err})")) from None
    with reader:
        channel = reader.default_channel
        sizes, unit = channel.physical_sizes, channel.unit
        dim = len(channel.nb_grid_pts)
        # sizes or unit absent from the file: placeholders, replaced by the caller's length and unit
        topography = reader.topography(physical_sizes=None if sizes is not None else (1.0,) * dim,
                                       unit=None if unit is not None else "m")
    if not topography.is_uniform:
        raise ValueError(f"{path}: a non-uniform line scan; contactlib solves on uniform grids: resample it first "
                         "(SurfaceTopography's to_uniform)")
    heights = np.ma.filled(np.ma.asarray(topography.heights(), dtype=float), np.nan)
    periodic = getattr(channel, "is_periodic", None)
    return RawTopography(heights, reader.format(), reader=f"SurfaceTopography {SurfaceTopography.__version__}",
                         lengths=None if sizes is None else tuple(float(s) for s in sizes), unit=unit,
                         periodic=None if periodic is None else bool(periodic))
