"""What a measured topography needs before a solve: length units, detrending and missing points."""

from __future__ import annotations

import numpy as np

METRES_PER = {"m": 1.0, "mm": 1e-3, "um": 1e-6, "µm": 1e-6, "μm": 1e-6, "micron": 1e-6, "nm": 1e-9, "pm": 1e-12,
              "Å": 1e-10, "angstrom": 1e-10, "km": 1e3}
"""Length units a file or the caller may state (SurfaceTopography reports m, mm, µm, nm, pm, Å, km)."""
# divide by these exact integers rather than multiply by inexact 1e-6 etc.: one correctly rounded operation
_PER_METRE = {"m": 1, "mm": 10**3, "um": 10**6, "µm": 10**6, "μm": 10**6, "micron": 10**6, "nm": 10**9,
              "pm": 10**12, "Å": 10**10, "angstrom": 10**10}

DETREND_MODES = ("none", "mean", "plane", "line")
FILL_MODES = ("interpolate", "mean")


def to_metres(values, unit: str):
    """``values`` [unit] in metres; ``m`` returns them unchanged (bit for bit)."""
    if unit not in METRES_PER:
        raise ValueError(f"unknown length unit {unit!r}; known: {', '.join(METRES_PER)}")
    if unit == "m":
        return values
    if unit in _PER_METRE:
        return np.asarray(values, dtype=float) / _PER_METRE[unit]
    return np.asarray(values, dtype=float) * METRES_PER[unit]


def remove_trend(heights: np.ndarray, mode: str, spacing: tuple[float, ...]) -> tuple[np.ndarray, dict]:
    """Subtract the mean, or the least-squares plane (a line for a profile), fitted to the finite heights.

    Returns the heights and what was removed, as attrs: ``detrend`` (the mode applied: ``plane``
    becomes ``line`` on a profile), ``detrend_offset`` [length] (the trend at the window's centre)
    and ``detrend_slope_x``/``_y`` [1] (its gradient). Missing points (NaN) stay missing.
    """
    if mode not in DETREND_MODES:
        raise ValueError(f"detrend must be one of {DETREND_MODES}, got {mode!r}")
    if mode == "line" and heights.ndim == 2:
        raise ValueError("detrend='line' is for profiles; use 'plane' for a 2D topography")
    if mode == "none":
        return heights, {"detrend": "none"}
    valid = np.isfinite(heights)
    if mode == "mean":
        offset = float(heights[valid].mean())
        return heights - offset, {"detrend": "mean", "detrend_offset": offset}
    # centred node indices make the normal equations well conditioned
    axes = [np.arange(n) - (n - 1) / 2 for n in heights.shape]
    columns = [np.ones(heights.shape)] + [np.broadcast_to(a.reshape((-1,) + (1,) * (heights.ndim - 1 - k)),
                                                         heights.shape) for k, a in enumerate(axes)]
    design = np.stack([c[valid] for c in columns], axis=1)
    normal = design.T @ design
    if np.linalg.matrix_rank(normal) < normal.shape[0]:  # e.g. the finite points on one line of a map
        raise ValueError(f"detrend={mode!r}: the {int(valid.sum())} finite heights do not determine a "
                         f"{'plane' if heights.ndim == 2 else 'line'} (too few, or all on one line); use "
                         "detrend='mean'")
    coefficients = np.linalg.solve(normal, design.T @ heights[valid])
    trend = sum(c * column for c, column in zip(coefficients, columns))
    record = {"detrend": "plane" if heights.ndim == 2 else "line", "detrend_offset": float(coefficients[0])}
    for name, c, d in zip("xy", coefficients[1:], spacing):
        record[f"detrend_slope_{name}"] = float(c / d)
    return heights - trend, record


def fill_missing(heights: np.ndarray, mode: str) -> tuple[np.ndarray, int]:
    """Replace NaN heights: ``mean`` of the finite heights, or ``interpolate`` (linear, see below).

    ``interpolate``: in 2D, each missing node takes the piecewise-linear interpolant (Delaunay
    triangulation, ``scipy.interpolate.griddata``, in grid-index space) of the finite nodes bordering
    the missing regions; nodes outside their convex hull (a missing edge or corner) take the nearest
    finite node's height. A profile is interpolated linearly between its nearest finite neighbours
    and extended flat past its ends. Returns the heights and the number of nodes filled.
    """
    if mode not in FILL_MODES:
        raise ValueError(f"fill must be one of {FILL_MODES} or None, got {mode!r}")
    missing = np.isnan(heights)
    count = int(missing.sum())
    if count == 0:
        return heights, 0
    out = heights.copy()
    if mode == "mean":
        out[missing] = heights[~missing].mean()
    elif heights.ndim == 1:
        index = np.arange(heights.size)
        out[missing] = np.interp(index[missing], index[~missing], heights[~missing])
    else:
        out[missing] = _interpolate_2d(heights, missing)
    return out, count


def _interpolate_2d(heights: np.ndarray, missing: np.ndarray) -> np.ndarray:
    from scipy import interpolate, ndimage

    border = ndimage.binary_dilation(missing, structure=np.ones((3, 3), bool)) & ~missing
    known, values, targets = np.argwhere(border), heights[border], np.argwhere(missing)
    try:
        filled = interpolate.griddata(known, values, targets, method="linear")
    except Exception:  # border nodes on one line (Qhull cannot triangulate): nearest only
        filled = np.full(len(targets), np.nan)
    outside = np.isnan(filled)
    if outside.any():
        filled[outside] = interpolate.griddata(known, values, targets[outside], method="nearest")
    return filled
