"""Height statistics of periodic fields: rms height, rms slope, PSD, Hurst exponent.

PSD convention: ``C(q) = (2 pi)^-dim * int <h(0) h(x)> exp(-i q.x) d^dim x``, so that
``<h^2> = int C(q) d^dim q``.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from ..core.grid import Grid
from ..core.inputs import check_whole, in_solver_axes, real_values, window_of
from ..core.labels import attrs_for


def values_and_grid(field, length=None) -> tuple[np.ndarray, Grid]:
    """The field's values (indexed ``[ix, iy]``: a DataArray's x and y read by name, a bare array as given) and
    grid, refused unless 1D or 2D, at least 2 points a side, finite, on a window of
    finite positive lengths."""
    if isinstance(field, xr.DataArray):
        field = in_solver_axes(field)  # x and y by name: [ix, iy], as a bare array
        values = real_values(field.values, "field")
        if length is None and values.ndim in (1, 2) and min(values.shape, default=0) >= 2:
            length = window_of(field)  # evenly spaced coordinates, as solve reads them
    else:
        values = real_values(field, "field")
        if length is None:  # no default window: a 1 m one gave micrometre surfaces a slope a million times too small
            raise ValueError(f"length: a field given as a bare array (shape {values.shape}) carries no window size: "
                             "pass length= (the window [length], one number or one per axis), or give a DataArray "
                             "whose coordinates carry it")
    check_field(values, "field")
    lengths = tuple(float(v) for v in np.broadcast_to(np.asarray(length, dtype=float), (values.ndim,)))
    if not all(np.isfinite(v) and v > 0 for v in lengths):
        raise ValueError(f"length must be finite and > 0, got {length!r}")
    return values, Grid(values.shape, lengths)


def check_field(values: np.ndarray, name: str) -> None:
    """Refuse a field an analysis cannot read: not 1D or 2D, fewer than 2 points a side, NaN or infinite values."""
    if values.ndim not in (1, 2) or min(values.shape, default=0) < 2:
        raise ValueError(f"{name} must be 1D or 2D with at least 2 points a side, got shape {values.shape}")
    if not np.all(np.isfinite(values)):
        raise ValueError(f"{name} contains NaN or infinite values")


def half_spectrum_weights(grid: Grid) -> np.ndarray:
    """Weights of an rfft half-spectrum in a sum over the full spectrum (2, but 1 for the columns
    without a mirror image)."""
    weight = np.full(grid.spectral_shape(), 2.0)
    weight[..., 0] = 1.0
    if grid.shape[-1] % 2 == 0:
        weight[..., -1] = 1.0
    return weight


def rms_height(field) -> float:
    """Root mean square of the field about its mean [field units].

    Parameters
    ----------
    field : xarray.DataArray or ndarray
        1D or 2D field.

    Returns
    -------
    float
        The rms about the mean [field units].

    Examples
    --------
    >>> import numpy as np
    >>> from contactlib import analysis
    >>> analysis.rms_height(np.array([1.0, -1.0, 1.0, -1.0]))
    1.0
    """
    values = real_values(field, "field")
    return float(np.sqrt(np.mean((values - values.mean()) ** 2)))


def rms_slope(field, *, length=None) -> float:
    """Root mean square gradient ``sqrt(<|grad h|^2>)``, computed spectrally (exact for a
    periodic band-limited field; the Nyquist mode is dropped as its derivative is undefined).

    Parameters
    ----------
    field : xarray.DataArray or ndarray
        1D or 2D periodic field with at least 2 points a side; a DataArray carries its window.
    length : float or tuple, optional
        Window size [length], required for a bare array.

    Returns
    -------
    float
        The rms slope [field units / length].

    Raises
    ------
    ValueError
        When the field is not 1D or 2D, holds NaN or infinite values, or a bare array comes without ``length``.
    """
    values, grid = values_and_grid(field, length)
    spec = np.fft.rfftn(values)
    q2 = grid.wavenumber() ** 2
    for axis, n in enumerate(grid.shape):
        if n % 2 == 0:  # the Nyquist plane has no well-defined derivative
            index = [slice(None)] * grid.dim
            index[axis] = n // 2
            q2[tuple(index)] = 0.0
    weight = np.full(spec.shape, 2.0)  # rfft: each stored mode stands for itself and its conjugate
    weight[..., 0] = 1.0
    if grid.shape[-1] % 2 == 0:
        weight[..., -1] = 1.0
    return float(np.sqrt(np.sum(weight * q2 * np.abs(spec) ** 2)) / grid.size)


def psd(field, *, length=None, bins: int | None = None) -> xr.DataArray:
    """Radially averaged PSD [length^4] in 2D (profile PSD [length^3] in 1D) against ``|q|``.

    Bins are one ``q0 = 2 pi / L`` wide (or ``bins`` log-spaced bins) up to Nyquist.

    Parameters
    ----------
    field : xarray.DataArray or ndarray
        1D or 2D periodic field with at least 2 points a side; a DataArray carries its window.
    length : float or tuple, optional
        Window size [length], required for a bare array.
    bins : int, optional
        Number of log-spaced bins (default: bins one ``q0`` wide).

    Returns
    -------
    xarray.DataArray
        ``psd`` (2D) or ``psd_1d`` on the ``wavenumber`` coordinate [rad/length], labelled.

    Raises
    ------
    ValueError
        When the field is not 1D or 2D, holds NaN or infinite values, or a bare array comes without ``length``.
    """
    if bins is not None:
        check_whole(bins, "bins")
    values, grid = values_and_grid(field, length)
    spec = np.abs(np.fft.rfftn(values - values.mean())) ** 2
    c = spec * grid.element_area**2 / ((2 * np.pi) ** grid.dim * float(np.prod(grid.lengths)))
    q = grid.wavenumber()
    q0 = 2 * np.pi / grid.lengths[0]
    qmax = np.pi / max(grid.spacing)
    edges = (np.geomspace(q0 / 2, qmax, bins + 1) if bins else np.arange(0.5, qmax / q0 + 1.0) * q0)
    idx = np.digitize(q.ravel(), edges) - 1
    ok = (idx >= 0) & (idx < len(edges) - 1)
    counts = np.bincount(idx[ok], minlength=len(edges) - 1)
    sums = np.bincount(idx[ok], weights=c.ravel()[ok], minlength=len(edges) - 1)
    qsum = np.bincount(idx[ok], weights=q.ravel()[ok], minlength=len(edges) - 1)
    keep = counts > 0
    centres = qsum[keep] / counts[keep]
    name = "psd" if grid.dim == 2 else "psd_1d"
    return xr.DataArray(sums[keep] / counts[keep], dims=("wavenumber",),
                        coords={"wavenumber": ("wavenumber", centres, attrs_for("wavenumber"))},
                        name="psd", attrs=attrs_for(name))


def fit_hurst(field, *, q_min: float, q_max: float, length=None) -> float:
    """Hurst exponent from a least-squares fit of ``log C`` against ``log q`` on ``[q_min, q_max]``
    (multiples of ``q0``): slope ``-(dim + 2H)``.

    Parameters
    ----------
    field : xarray.DataArray or ndarray
        1D or 2D periodic field with at least 2 points a side; a DataArray carries its window.
    q_min, q_max : float
        The fitted band, as multiples of ``q0 = 2 pi / L``.
    length : float or tuple, optional
        Window size [length], required for a bare array.

    Returns
    -------
    float
        The Hurst exponent H.

    Raises
    ------
    ValueError
        When the field is not 1D or 2D, holds NaN or infinite values, or a bare array comes without ``length``. Or ``q_min``, ``q_max`` out of order, or
        a band with too few spectrum bins.
    """
    if not (np.isfinite(q_min) and np.isfinite(q_max) and 0 < q_min < q_max):
        raise ValueError(f"need 0 < q_min < q_max (multiples of q0), got q_min={q_min!r}, q_max={q_max!r}")
    values, grid = values_and_grid(field, length)
    c = psd(values, length=grid.lengths)
    q0 = 2 * np.pi / grid.lengths[0]
    sel = (c.wavenumber >= q_min * q0) & (c.wavenumber <= q_max * q0) & (c > 0)
    if int(sel.sum()) < 2:
        raise ValueError(f"q_min, q_max: the band [{q_min}, {q_max}] q0 holds {int(sel.sum())} spectrum bin(s) with "
                         "power, 2 at least are needed for a fit")
    slope = np.polyfit(np.log(c.wavenumber[sel]), np.log(c[sel]), 1)[0]
    return float(-(slope + grid.dim) / 2)
