"""The checks of every entry point's input: heights to an array on a grid, the window's periodicity, loads,
tolerances, friction and sliding velocity. Each refuses bad input with a ``ValueError`` naming the parameter,
before anything is built."""

from __future__ import annotations

import math
import numbers

import numpy as np
import xarray as xr

from .grid import Grid

# The one validation path: every entry point (solve, solve_tolerances, solve_transient, solve_reciprocating,
# adhesion_curve, two_scale.solve, the surfaces, the materials, Layer, Adhesion) checks its numbers, whole numbers,
# arrays and times through the functions below, so a wrong type or shape is refused naming the parameter.
# (materials and bodies import these: this module imports them only inside the functions that need them.)


def _kind(value) -> str:
    """The type of a refused value, for a message (``None`` as itself)."""
    return "None" if value is None else type(value).__name__


def _short(value, limit: int = 60) -> str:
    text = repr(value)
    return text if len(text) <= limit else text[: limit - 3] + "..."


def _described(value) -> str:
    """A refused value with its type, for a message: ``str '1e7'``, ``None``."""
    return "None" if value is None else f"{_kind(value)} {_short(value)}"


def _bounds(lower, upper, lower_open: bool, upper_open: bool) -> str:
    """`` > 0``, `` in (0, 1]``, ...: the range of :func:`number` in words ("" without bounds)."""
    if lower is not None and upper is not None:
        return f" in {'(' if lower_open else '['}{lower:g}, {upper:g}{')' if upper_open else ']'}"
    if lower is not None:
        return f" {'>' if lower_open else '>='} {lower:g}"
    if upper is not None:
        return f" {'<' if upper_open else '<='} {upper:g}"
    return ""


def number(name: str, value, *, lower: float | None = None, upper: float | None = None, lower_open: bool = False,
           upper_open: bool = False, finite: bool = True) -> float:
    """``value`` as a float: a real number (a Python or numpy scalar, or a 0-d array) within the bounds.

    Raises ``ValueError`` naming ``name``: a wrong type (a string, a bool, None, a complex number, a sequence: the
    type is named, as ``E must be a number > 0, got str '1e7'``), a NaN or infinity (unless ``finite=False``), or a
    value outside ``[lower, upper]`` (open ends where ``lower_open`` / ``upper_open``).
    """
    raw = value[()] if isinstance(value, np.ndarray) and value.ndim == 0 else value
    if isinstance(raw, (bool, np.bool_)) or not isinstance(raw, numbers.Real):
        raise ValueError(f"{name} must be a number{_bounds(lower, upper, lower_open, upper_open)}, got "
                         f"{_described(value)}")
    x = float(raw)
    if math.isnan(x) and not finite:
        return x
    outside = ((finite and not math.isfinite(x)) or math.isnan(x)
               or (lower is not None and (x < lower or (lower_open and x == lower)))
               or (upper is not None and (x > upper or (upper_open and x == upper))))
    if outside:
        what = "a finite number" if finite else "a number"
        raise ValueError(f"{name} must be {what}{_bounds(lower, upper, lower_open, upper_open)}, got {value!r}")
    return x


def real_values(values, name: str) -> np.ndarray:
    """``values`` as a float array, refused by ``name`` when they are not an array of real numbers: a string, None,
    a ragged nested list, non-numeric entries, or complex values (numpy would drop the imaginary part with a
    warning: a field's FFT passed for the field itself)."""
    if values is None or isinstance(values, (str, bytes)):
        raise ValueError(f"{name} must be an array of numbers, got {_described(values)}")
    try:
        raw = values if isinstance(values, np.ndarray) else np.asarray(values)
    except (ValueError, TypeError):  # numpy: "inhomogeneous shape"
        raise ValueError(f"{name} must be a rectangular array of numbers: its rows differ in length (a ragged "
                         "nested list)") from None
    if np.iscomplexobj(raw):
        raise ValueError(f"{name} must be real, got complex values (dtype {raw.dtype})")
    if raw.dtype.kind not in "biuf":
        try:  # an object array of numbers converts; strings, dates and others do not
            converted = np.asarray(raw, dtype=float) if raw.dtype.kind == "O" else None
        except (ValueError, TypeError):
            converted = None
        if converted is None:
            raise ValueError(f"{name} must be an array of numbers, got dtype {raw.dtype} ({_short(values)})")
        return converted
    return np.asarray(raw, dtype=float)


def time_values(values, name: str = "times") -> np.ndarray:
    """Instants [time] as a finite, strictly increasing 1D float array, refused by ``name``: a string or a single
    number (give a sequence: ``[t]``), a wrong shape, NaN, or a step that does not increase."""
    times = real_values(values, name)
    if times.ndim == 0:
        raise ValueError(f"{name} must be a 1D sequence of times [time], got the single number {float(times):g}: give "
                         f"[{float(times):g}]")
    if times.ndim != 1 or times.size < 1:
        raise ValueError(f"{name} must be a 1D sequence of at least one time, got shape {times.shape}")
    if not np.all(np.isfinite(times)):
        raise ValueError(f"{name} must be finite")
    if np.any(np.diff(times) <= 0):
        k = int(np.argmax(np.diff(times) <= 0))
        raise ValueError(f"{name} must increase strictly (every dt > 0): {name}[{k + 1}] = {float(times[k + 1])!r} "
                         f"after {name}[{k}] = {float(times[k])!r}")
    return times


def load_history(load, times: np.ndarray, name: str) -> np.ndarray:
    """A load [its unit] as one value per time of ``times`` (as :func:`time_values` gives them): a constant, a
    sequence of one value per time or a function of time; NaN, infinities and non-numbers refused naming ``name``
    (the time-stepping drivers' ``mean_pressure`` and ``penetration`` histories)."""
    if callable(load):
        values = real_values([number(f"{name}(t = {float(t):g})", load(t), finite=False) for t in times], name)
    else:
        values = real_values(load, name)
        if values.ndim == 0:
            values = np.full(times.shape, float(values))
        elif values.shape != times.shape:
            raise ValueError(f"{name} has {values.size} values for {times.size} times: give one per time")
    if not np.all(np.isfinite(values)):
        k = int(np.argmax(~np.isfinite(values)))
        raise ValueError(f"{name} history holds a non-finite value ({values[k]!r}) at times[{k}] = {times[k]!r}")
    return values


def in_solver_axes(field):
    """``field`` with its axes in the solvers' index order ``[ix, iy]``: a DataArray with both an ``"x"`` and a
    ``"y"`` dimension transposed by name to end in ``("x", "y")`` (the ``("y", "x")`` fields contactlib returns, and
    ``("x", "y")`` ones from older files, read the same); anything else unchanged (a bare array is already
    ``[ix, iy]``; a DataArray on other dims is read by position)."""
    if isinstance(field, xr.DataArray) and "x" in field.dims and "y" in field.dims:
        return field.transpose(..., "x", "y")
    return field


def solver_values(field, name: str) -> np.ndarray:
    """A field given to an entry point (``initial_pressure``, a pressure or gap to analyse) as a float array indexed
    ``[ix, iy]``: a DataArray on ``"x"`` and ``"y"`` by name (:func:`in_solver_axes`), a bare array as it is;
    refused by ``name`` as :func:`real_values` refuses."""
    field = in_solver_axes(field)
    return real_values(field.values if isinstance(field, xr.DataArray) else field, name)


def grid_of(heights, length=None) -> tuple[np.ndarray, Grid, tuple[str, ...], dict]:
    """Heights array, grid, dim names and coords of a DataArray or ndarray input: the one way every entry point
    reads heights.

    A DataArray (as :mod:`contactlib.surfaces` makes them) carries its window: coordinate step times points
    (``length`` may repeat it). Its axes are read by name: a surface on ``("y", "x")`` (as contactlib makes them)
    and one on ``("x", "y")`` give the same array (:func:`in_solver_axes`); other dims are read by position.
    A bare array (ndarray, nested list) is indexed ``[ix, iy]`` (rows along x, as tamaas and ContactMechanics
    index theirs; ``surface.transpose("x", "y").values`` is that array of a DataArray surface), and has no window,
    so ``length`` [length] is required: there is no default window (a 1 m one made micrometre heights come back in
    full contact).

    Returns the array ``[ix, iy]``, its grid, the solver's dim names (``("x", "y")``, ``("x",)`` or a DataArray's
    own) and the coordinates.

    Raises ``ValueError`` naming ``heights`` (not an array of real numbers, ragged, complex, not 1D or 2D, fewer
    than 2 points, NaN) or ``length`` (missing for a bare array, not a positive number per axis, contradicting the
    coordinates).
    """
    if isinstance(heights, xr.DataArray):
        heights = in_solver_axes(heights)
        values = real_values(heights.values, "heights")
        dims = tuple(heights.dims)
        window = window_of(heights) if all(d in heights.coords for d in dims) else None
        if length is None:
            if window is None:
                missing = next(d for d in dims if d not in heights.coords)
                raise ValueError(f"heights: dimension {missing!r} has no coordinate; pass length=")
            lengths = window
        else:
            lengths = lengths_of(length, values.ndim)
            if window is not None and any(abs(a - b) > 1e-9 * b for a, b in zip(lengths, window)):
                raise ValueError(f"length {length!r} differs from the heights' window {window} (coordinate step "
                                 "times points): omit length, or give the heights as an ndarray")
        coords = {d: heights[d] for d in dims if d in heights.coords}
    else:
        values = real_values(heights, "heights")
        if values.ndim not in (1, 2):
            raise ValueError(f"heights must be 1D or 2D, got {values.ndim} dimensions")
        if length is None:
            raise ValueError(f"length: heights given as a bare array ({_kind(heights)} of shape {values.shape}) carry "
                             "no window size: pass length= (the window [length], one number or one per axis), or "
                             "give a DataArray from contactlib.surfaces, whose coordinates carry it")
        dims = ("x", "y")[: values.ndim]
        lengths = lengths_of(length, values.ndim)
        coords = {}
    if values.ndim not in (1, 2):
        raise ValueError(f"heights must be 1D or 2D, got {values.ndim} dimensions")
    if min(values.shape) < 2:
        raise ValueError(f"heights: grid smaller than 2 points, shape {values.shape}")
    if not np.all(np.isfinite(values)):
        raise ValueError("heights contain NaN or infinite values")
    grid = Grid(values.shape, lengths)
    if not coords:
        coords = {d: (d, c) for d, c in zip(dims, grid.coordinates())}
    return np.ascontiguousarray(values), grid, dims, coords


def window_of(heights: xr.DataArray) -> tuple[float, ...]:
    """The window lengths of a DataArray's coordinates (step times points), refused unless each coordinate is
    finite, increasing and evenly spaced (the FFT grid's)."""
    lengths = []
    for d in heights.dims:
        raw = np.asarray(heights[d].values)
        c = raw.astype(float)
        if c.size < 2:
            raise ValueError(f"heights: grid smaller than 2 points along {d!r}")
        steps = np.diff(c)
        # evenly spaced to 1e-6 of a step, or to the coordinates' own rounding (float32 data: 6e-8 of their size)
        eps = np.finfo(raw.dtype).eps if np.issubdtype(raw.dtype, np.floating) else 0.0
        slack = max(1e-6 * abs(float(steps[0])), 8 * eps * float(np.max(np.abs(c))))
        if not (np.all(np.isfinite(steps)) and steps[0] > 0 and np.max(np.abs(steps - steps[0])) <= slack):
            raise ValueError(f"heights: coordinate {d!r} must be finite, increasing and evenly spaced (the FFT "
                             f"grid's): its steps differ from the first by up to "
                             f"{float(np.max(np.abs(steps - steps[0])) / abs(steps[0])):.3g} of it")
        # float64 coordinates as before (step times points); rounded ones by their mean step
        step = float(steps[0]) if eps <= np.finfo(float).eps else float(c[-1] - c[0]) / (c.size - 1)
        lengths.append(step * c.size)
    return tuple(lengths)


def periodic_of(heights, periodic: bool | None) -> bool:
    """``periodic`` if given, else what a DataArray's ``attrs['periodic']`` says (a measured surface from
    :func:`contactlib.surfaces.read` is non-periodic unless its file or reader said so), else True."""
    if periodic is not None:
        if not isinstance(periodic, (bool, np.bool_, numbers.Real)) or periodic not in (0, 1):  # "no" was True
            raise ValueError(f"periodic must be True, False or None (from the heights), got {_described(periodic)}")
        return bool(periodic)
    if isinstance(heights, xr.DataArray) and "periodic" in heights.attrs:
        return bool(heights.attrs["periodic"])
    return True


def lengths_of(length, ndim: int) -> tuple[float, ...]:
    """The window [length] along each of ``ndim`` axes: one number, or one per axis, each finite and > 0."""
    if isinstance(length, (str, bytes, bool, np.bool_)) or length is None:
        raise ValueError(f"length must be a number or one per axis ({ndim}), finite and > 0, got "
                         f"{_described(length)}")
    try:
        lengths = tuple(float(v) for v in np.broadcast_to(np.asarray(length, dtype=float), (ndim,)))
    except (TypeError, ValueError):
        raise ValueError(f"length must be a number or one per axis ({ndim}), finite and > 0, got {length!r}") from None
    for v in lengths:
        if not math.isfinite(v) or v <= 0:
            raise ValueError(f"length must be finite and > 0, got {length!r}")
    return lengths


def check_below_full_contact(penetration: float, heights: np.ndarray, name: str = "penetration",
                             remedy: str = "give mean_pressure instead") -> None:
    """Refuse a ``penetration`` [length] that closes every gap of ``heights`` [length] on a body whose displacements
    are zero-mean (a periodic half-space or plate: the approach is against the mean deformed plane, so full contact
    comes at ``max - mean`` height): the load is then undetermined (:func:`contactlib.solve`,
    :func:`contactlib.adhesion_curve`)."""
    closed = float(heights.max() - heights.mean())
    if penetration >= closed:
        raise ValueError(f"{name} {float(penetration)!r} reaches full contact (max - mean height = {closed:.6g}); in a "
                         f"periodic window the load is then undetermined: {remedy}")


def check_tolerance(value, name: str) -> None:
    """A relative tolerance: a number in (0, 1) (at 1 or more the initial guess already meets it)."""
    if isinstance(value, bool) or not (isinstance(value, numbers.Real) and math.isfinite(value) and 0 < value < 1):
        shown = repr(value) if isinstance(value, numbers.Real) and not isinstance(value, bool) else _described(value)
        raise ValueError(f"{name} must be a number in (0, 1), got {shown}")


def check_whole(value, name: str, minimum: int = 1) -> int:
    """``value`` as an int: a whole number >= ``minimum`` (a float such as 64.0 passes; 2.5, NaN, infinity, a bool or a
    string are refused with a ValueError naming ``name``, and the type where it is not a number)."""
    raw = value[()] if isinstance(value, np.ndarray) and value.ndim == 0 else value
    if isinstance(raw, (bool, np.bool_)) or not isinstance(raw, numbers.Real):
        raise ValueError(f"{name} must be a whole number >= {minimum}, got {_described(value)}")
    if not math.isfinite(raw) or int(raw) != raw or raw < minimum:
        raise ValueError(f"{name} must be a whole number >= {minimum}, got {value!r}")
    return int(raw)


def check_iterations(value, name: str = "max_iter") -> None:
    """An iteration bound: a whole number >= 1."""
    check_whole(value, name, 1)


def check_loads(mean_pressure, penetration) -> None:
    if (mean_pressure is None) == (penetration is None):
        raise ValueError("give exactly one of mean_pressure or penetration")
    if mean_pressure is not None:
        number("mean_pressure", mean_pressure, lower=0.0)
    if penetration is not None:
        number("penetration", penetration)


EDGE_RTOL = 1e-12
"""Compression on the window's edge below this fraction of the largest ``|pressure|`` is round-off, not
contact: a converged cohesive state (256^2 JKR sphere, tol 1e-6) kept +5e-56 on an edge whose true
traction is zero, 1e-54 of its peak adhesive stress, and was refused as a contact cut by the window."""


EDGE_TENSION = 0.5
"""Adhesive tension on a non-periodic window's edge above this fraction of the law's peak stress: the cohesive zone
itself reaches the edge (a Maugis law's stress is the peak all across it; an exponential law's is above half of it
within 0.69 ranges of gap), so the window cuts off adhesion that acts beyond it: refused, as compression there is.
An exponential law's weaker tail at the edge is left to the user's window."""


def _edges(pressure: np.ndarray) -> list[np.ndarray]:
    """The window's edge rows and columns (the two ends of a profile)."""
    return [np.take(pressure, i, axis=a) for a in range(pressure.ndim) for i in (0, -1)]


def round_off_floor(pressure: np.ndarray) -> float:
    """:data:`EDGE_RTOL` times the largest ``|pressure|``: below it an edge value is round-off [pressure]."""
    return EDGE_RTOL * float(np.max(np.abs(pressure), initial=0.0))


def edge_tension(pressure: np.ndarray, floor: float) -> bool:
    """Whether a non-periodic adhesive state's edge carries tension above ``floor`` [pressure]
    (:data:`EDGE_TENSION` of a cohesive law's peak stress)."""
    return any(np.any(e < -floor) for e in _edges(pressure))


def touches_edge(pressure: np.ndarray) -> bool:
    """Whether a non-periodic footprint reaches the window's edge: compression there above
    :data:`EDGE_RTOL` times the largest ``|pressure|`` (the adhesive tension included) [dimensionless test]."""
    floor = round_off_floor(pressure)
    return any(np.any(e > floor) for e in _edges(pressure))
