"""Fused element-wise passes of the Polonsky-Keer iteration (numba, single-threaded).

Each function is one sweep over the grid doing what would take numpy 4-8 passes and
temporaries; with two FFT pairs per iteration, memory passes otherwise dominate the cost
(measured in benchmarks/). Arrays are 2D (profiles are viewed as ``(1, n)``) and may be
strided views into the FFT work buffers.
"""

from __future__ import annotations

import numba
import numpy as np

_jit = numba.njit(cache=True, nogil=True, fastmath=False, boundscheck=False)


@_jit
def scale_and_load(p, factor, dest):
    """``p *= factor``; ``dest[...] = p`` (pressure into the FFT input block)."""
    for i in range(p.shape[0]):
        for j in range(p.shape[1]):
            v = p[i, j] * factor
            p[i, j] = v
            dest[i, j] = v


@_jit
def gap_and_contact_mean(u, hp, p, g):
    """``g = u - hp``; returns (number of points with p > 0, sum of g over them)."""
    n_c = 0
    s = 0.0
    for i in range(u.shape[0]):
        for j in range(u.shape[1]):
            v = u[i, j] - hp[i, j]
            g[i, j] = v
            if p[i, j] > 0.0:
                n_c += 1
                s += v
    return n_c, s


@_jit
def shift_and_measure(g, p, approach, masked, write_masked):
    """``g -= approach``; if ``write_masked``, ``masked = g`` on the contact set and 0 elsewhere.

    Returns (sum p|g|, sum max(-g, 0) off contact, sum over contact of g^2, sum p)."""
    comp = 0.0
    pen = 0.0
    G = 0.0
    psum = 0.0
    for i in range(g.shape[0]):
        for j in range(g.shape[1]):
            v = g[i, j] - approach
            g[i, j] = v
            pv = p[i, j]
            if pv > 0.0:
                G += v * v
                psum += pv
                comp += pv * abs(v)
                if write_masked:
                    masked[i, j] = v
            else:
                if v < 0.0:
                    pen -= v
                if write_masked:
                    masked[i, j] = 0.0
    return comp, pen, G, psum


@_jit
def conjugate_direction(z, shift, g, p, beta, t, dest):
    """``t = (z - shift + beta t)`` on the contact set, 0 elsewhere; ``dest[...] = t`` (``dest`` may
    be ``z``: each element is read before it is written); returns (sum t, sum g t)."""
    st = 0.0
    gt = 0.0
    for i in range(g.shape[0]):
        for j in range(g.shape[1]):
            if p[i, j] > 0.0:
                v = z[i, j] - shift + beta * t[i, j]
                st += v
                gt += g[i, j] * v
            else:
                v = 0.0
            t[i, j] = v
            dest[i, j] = v
    return st, gt


@_jit
def contact_sums(r, t, p):
    """Returns (sum of r over the contact set, sum r t)."""
    sr = 0.0
    rt = 0.0
    for i in range(r.shape[0]):
        for j in range(r.shape[1]):
            if p[i, j] > 0.0:
                sr += r[i, j]
                rt += r[i, j] * t[i, j]
    return sr, rt


@_jit
def step_project_reenter(p, t, g, tau):
    """``p -= tau t``, project on ``p >= 0``, re-enter interpenetrating points with ``p = -tau g``.

    Returns (sum p, number of re-entered points)."""
    psum = 0.0
    n_ol = 0
    for i in range(p.shape[0]):
        for j in range(p.shape[1]):
            v = p[i, j] - tau * t[i, j]
            if v <= 0.0:
                v = 0.0
                if g[i, j] < 0.0:
                    v = -tau * g[i, j]
                    n_ol += 1
            p[i, j] = v
            psum += v
    return psum, n_ol


def as2d(a: np.ndarray) -> np.ndarray:
    return a.reshape(1, -1) if a.ndim == 1 else a
