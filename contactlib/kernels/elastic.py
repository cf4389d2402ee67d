"""Frictionless elastic half-space: normal compliance of the surface.

All functions take the contact modulus ``E_star = E / (1 - nu**2)`` [pressure] and return
displacement per unit pressure [length/pressure] (2D) or per unit line pressure (1D, plane
strain, per unit width).

References: K. L. Johnson, *Contact Mechanics* (1985), eqs. (2.19), (3.25);
Love (1929) doi:10.1098/rsta.1929.0004; seed paper 2, eqs. (6)-(8).
"""

from __future__ import annotations

import numpy as np

from ..core.grid import Grid
from .nyquist import even_on_nyquist

#: image orders summed per axis by the periodic Love multiplier (alternating tail: error ~ M^-2)
LOVE_IMAGES_2D = 12
LOVE_IMAGES_1D = 256


def halfspace_spectral_multiplier(grid: Grid, E_star: float) -> np.ndarray:
    """Continuous multiplier ``2 / (E* |q|)`` on the rfft layout; zero at ``q = 0``.

    The ``q = 0`` term of a periodic half-space is infinite; setting it to zero defines the
    displacement as zero-mean, so penetrations are measured from the mean deformed plane.
    Exact for a single Fourier mode: the discretisation error is that of sampling.
    """
    q = grid.wavenumber()
    out = np.zeros_like(q)
    nz = q > 0
    out[nz] = 2.0 / (E_star * q[nz])
    return out


def _sinc(z: np.ndarray) -> np.ndarray:
    return np.sinc(z / np.pi)


def halfspace_love_multiplier(grid: Grid, E_star: float, *, images: int | None = None,
                              factor=None) -> np.ndarray:
    """Periodic Love kernel: uniform pressure on each element, displacement at element centres.

    Sampling the continuous response of piecewise-constant pressure aliases every wavevector
    ``k + m K`` (``K = 2 pi / dx``) onto ``k``:
    ``L(k) = sum_m 2 / (E* |k + m K|) * S(k + m K)`` with ``S`` the element's shape factor
    ``prod_i sinc(q_i dx_i / 2)``. This is the Fourier form of the image sum of seed 2 eqs. (7)-(8)
    (``l_ij - l_m``: the mean is the ``k = 0`` term, zero here). Pairs ``+m, -m`` alternate in
    sign, so truncating at ``|m_i| <= images`` converges fast.

    ``factor(*q)``, optional: a complex factor of the continuous kernel at each aliased wavevector
    ``k + m K`` (a viscoelastic body in steady sliding: each alias oscillates at its own frequency);
    the result is then complex.
    """
    M = images if images is not None else (LOVE_IMAGES_2D if grid.dim == 2 else LOVE_IMAGES_1D)
    orders = np.arange(-M, M + 1)
    out = _love_image_sum(grid.wavevectors(), grid.spacing, E_star, orders, factor)
    if factor is not None:  # odd through the factor: even on the Nyquist planes (the image set is not symmetric)
        out = even_on_nyquist(grid, lambda *q: _love_image_sum(q, grid.spacing, E_star, orders, factor), out)
    out[(0,) * grid.dim] = 0.0  # zero-mean displacement (the image terms vanish there up to rounding)
    return out


def _love_image_sum(q, d, E_star: float, orders: np.ndarray, factor) -> np.ndarray:
    """The image sum of :func:`halfspace_love_multiplier` at the wavevector components ``q`` (broadcastable
    arrays) on a grid of spacing ``d``."""
    shape = np.broadcast_shapes(*(np.shape(c) for c in q))
    out = np.zeros(shape, dtype=float if factor is None else complex)
    if len(q) == 1:
        K = 2 * np.pi / d[0]
        for m in orders:
            qm = q[0] + m * K
            absq = np.abs(qm)
            with np.errstate(divide="ignore", invalid="ignore"):
                term = np.where(absq > 0, 2.0 / (E_star * absq) * _sinc(qm * d[0] / 2), 0.0)
            out += term if factor is None else term * factor(qm)
        return out
    Kx, Ky = 2 * np.pi / d[0], 2 * np.pi / d[1]
    for mx in orders:
        qx = q[0] + mx * Kx
        sx = _sinc(qx * d[0] / 2)
        for my in orders:
            qy = q[1] + my * Ky
            absq = np.sqrt(qx**2 + qy**2)
            with np.errstate(divide="ignore", invalid="ignore"):
                term = np.where(absq > 0, sx * _sinc(qy * d[1] / 2) * 2.0 / (E_star * absq), 0.0)
            out += term if factor is None else term * factor(qx, qy)
    return out


def padded_offsets(grid: Grid) -> tuple[np.ndarray, ...]:
    """Signed node offsets on the padded (2n) circular layout, per axis [length]."""
    out = []
    for n, d in zip(grid.shape, grid.spacing):
        i = np.arange(2 * n)
        out.append(np.where(i < n, i, i - 2 * n) * d)
    if grid.dim == 2:
        return out[0][:, None], out[1][None, :]
    return (out[0],)


def love_rectangle(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """``x asinh(y/|x|) + y asinh(x/|y|)``: Love's primitive with the ``x ln|x|`` parts cancelled."""
    with np.errstate(divide="ignore", invalid="ignore"):
        a = np.where(x != 0, x * np.arcsinh(y / np.abs(x)), 0.0)
        b = np.where(y != 0, y * np.arcsinh(x / np.abs(y)), 0.0)
    return a + b


def _xlogx(x: np.ndarray, scale: float) -> np.ndarray:
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(x != 0, x * np.log(np.abs(x) / scale), 0.0)


def halfspace_love_influence(grid: Grid, E_star: float) -> np.ndarray:
    """Non-periodic Love influence coefficients on the padded ``2n`` circular layout.

    2D: displacement at offset (x, y) from the centre of a uniformly loaded rectangle
    ``dx x dy`` (Johnson eq. 3.25). 1D (plane strain): strip of width ``dx``; the displacement
    of a half-plane is defined up to a constant, fixed here so that a line load gives zero
    displacement at distance ``L`` (the window length): ``u = -(2/(pi E*)) ln(r/L)`` per unit load.
    """
    off = padded_offsets(grid)
    if grid.dim == 2:
        x, y = off
        a, b = grid.spacing[0] / 2, grid.spacing[1] / 2
        u = (love_rectangle(x + a, y + b) - love_rectangle(x + a, y - b)
             - love_rectangle(x - a, y + b) + love_rectangle(x - a, y - b))
        return u / (np.pi * E_star)
    (x,) = off
    a = grid.spacing[0] / 2
    L = grid.lengths[0]
    return -2.0 / (np.pi * E_star) * (_xlogx(x + a, L) - _xlogx(x - a, L) - 2 * a)


def halfspace_point_influence(grid: Grid, E_star: float) -> np.ndarray:
    """Non-periodic collocated point-load coefficients on the padded layout.

    The real-space counterpart of the continuous multiplier: the element's load acts at its
    node (Boussinesq ``dA / (pi E* r)``, 1D ``-(2 dx / (pi E*)) ln(r / L)``); the singular self
    term is taken from the uniform element (Love), as for any collocation scheme.
    """
    love = halfspace_love_influence(grid, E_star)
    off = padded_offsets(grid)
    with np.errstate(divide="ignore"):
        if grid.dim == 2:
            r = np.sqrt(off[0] ** 2 + off[1] ** 2)
            u = grid.element_area / (np.pi * E_star * r)
        else:
            r = np.abs(off[0])
            u = -2.0 * grid.spacing[0] / (np.pi * E_star) * np.log(r / grid.lengths[0])
    origin = (0,) * grid.dim
    u[origin] = love[origin]
    return u
