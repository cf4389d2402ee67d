"""Anisotropy tensor of a field over a wavenumber band (seed 2, eqs. 26-27).

``M_ij = int_{zeta1 q0 < |q| < zeta2 q0} q_i q_j C(q) d^2q = <d_i u d_j u>`` of the band-passed
field; ``mu2(theta) = e(theta) . M . e(theta)`` is the mean square slope of a cut along theta,
``gamma = lambda_min / lambda_max`` and ``theta_d`` the direction maximising ``mu2``.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from ..core.inputs import check_whole
from .statistics import half_spectrum_weights, values_and_grid


def anisotropy_tensor(field, zeta1: float, zeta2: float, *, length=None, n_theta: int = 181) -> xr.Dataset:
    """Anisotropy tensor of a 2D periodic field (surface heights, displacement or pressure).

    Parameters
    ----------
    field : DataArray or ndarray (2D)
        A DataArray's x and y read by name; an ndarray indexed ``[ix, iy]``.
    zeta1, zeta2 : float
        Band edges as multiples of ``q0 = 2 pi / Lx``, ``zeta1 < zeta2``.

    length : float, optional
        Window size along x [length], required for a bare array.
    n_theta : int
        Number of angles in ``[0, pi)`` at which ``mu2(theta)`` is sampled.

    Returns
    -------
    Dataset with ``M`` (dims ``i``, ``j``), ``mu2`` (dim ``theta``), ``gamma``, ``theta_d`` [rad, in [0, pi)].

    Raises
    ------
    ValueError
        For a field that is not 2D, band edges out of order or with no wavevector of the grid, or ``n_theta`` < 2.
    """
    values, grid = values_and_grid(field, length)
    if grid.dim != 2:
        raise ValueError("anisotropy_tensor needs a 2D field")
    if not (np.isfinite(zeta2) and 0 <= zeta1 < zeta2):
        raise ValueError(f"need 0 <= zeta1 < zeta2, finite, got {zeta1}, {zeta2}")
    check_whole(n_theta, "n_theta", 2)
    q0 = 2 * np.pi / grid.lengths[0]
    qx, qy = grid.wavevectors()
    q = np.hypot(qx, qy)
    band = (q > zeta1 * q0) & (q < zeta2 * q0)
    if not band.any():  # no mode: M = 0, gamma NaN and a theta_d read off a zero matrix
        raise ValueError(f"zeta1, zeta2: the band ({zeta1}, {zeta2}) q0 holds no wavevector of the grid (its modes "
                         f"lie on multiples of q0 up to {float(q.max() / q0):.4g} q0)")
    power = np.abs(np.fft.rfftn(values)) ** 2 * band
    power *= half_spectrum_weights(grid) / grid.size**2
    qx_b = np.broadcast_to(qx, q.shape)
    qy_b = np.broadcast_to(qy, q.shape)
    m = np.array([[np.sum(power * qx_b * qx_b), np.sum(power * qx_b * qy_b)],
                  [np.sum(power * qx_b * qy_b), np.sum(power * qy_b * qy_b)]])
    evals, evecs = np.linalg.eigh(m)
    lead = evecs[:, 1]
    theta_d = float(np.arctan2(lead[1], lead[0]) % np.pi)
    theta = np.linspace(0, np.pi, n_theta)
    mu2 = m[0, 0] * np.cos(theta) ** 2 + 2 * m[0, 1] * np.sin(theta) * np.cos(theta) + m[1, 1] * np.sin(theta) ** 2
    gamma = float(evals[0] / evals[1]) if evals[1] > 0 else np.nan
    return xr.Dataset(
        {
            "M": (("i", "j"), m, {"units": "1", "long_name": "anisotropy tensor (mean slope products)"}),
            "mu2": (("theta",), mu2, {"units": "1", "long_name": "mean square slope along theta"}),
            "gamma": ((), gamma, {"units": "1", "long_name": "anisotropy ratio lambda_min/lambda_max"}),
            "theta_d": ((), theta_d, {"units": "rad", "long_name": "principal anisotropy direction"}),
        },
        coords={"theta": ("theta", theta, {"units": "rad", "long_name": "cut direction"}),
                "i": ("i", ["x", "y"]), "j": ("j", ["x", "y"])},
        attrs={"zeta1": zeta1, "zeta2": zeta2},
    )
