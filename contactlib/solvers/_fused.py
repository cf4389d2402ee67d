"""Fused element-wise passes of the Polonsky-Keer iteration (numba, single-threaded).

Each function is one sweep over the grid doing what would take numpy 4-8 passes and
temporaries; the sweeps are memory-bound and, beside two or three FFT pairs per iteration,
would otherwise dominate its cost (measured in benchmarks/). Arrays are 2D (profiles are
viewed as ``(1, n)``) and may be strided views into the FFT work buffers.
"""

from __future__ import annotations

import numba
import numpy as np

# reassociation lets the reductions vectorise; no finite-math assumptions (NaN must propagate)
_jit = numba.njit(cache=True, nogil=True, fastmath={"reassoc", "contract", "nsz"}, boundscheck=False)

# The contact set ``p > 0`` is patchy on rough surfaces, so the sweeps select with arithmetic
# rather than branches: mispredicted branches made the projection step cost up to one FFT pair.


@_jit
def gap_and_contact_mean(u, factor, hp, p, g):
    """``g = factor u - hp``; returns (number of points with p > 0, sum of g over them)."""
    n_c = 0
    s = 0.0
    for i in range(u.shape[0]):
        for j in range(u.shape[1]):
            v = factor * u[i, j] - hp[i, j]
            g[i, j] = v
            c = p[i, j] > 0.0
            n_c += 1 if c else 0
            s += v if c else 0.0
    return n_c, s


@_jit
def measure(g, p, factor, approach, masked, write_masked):
    """Contact measures of the gap ``g - approach`` (``g`` is left unshifted) and pressure
    ``factor p``; if ``write_masked``, ``masked`` = the gap on the contact set and 0 elsewhere.

    Returns (sum p|gap|, sum max(-gap, 0) off contact, sum over contact of gap^2, sum p)."""
    comp = 0.0
    pen = 0.0
    G = 0.0
    psum = 0.0
    for i in range(g.shape[0]):
        for j in range(g.shape[1]):
            v = g[i, j] - approach
            pv = factor * p[i, j]
            m = 1.0 if pv > 0.0 else 0.0
            w = m * v
            G += w * v
            psum += pv
            comp += pv * abs(v)
            pen += (1.0 - m) * max(-v, 0.0)
            if write_masked:
                masked[i, j] = w
    return comp, pen, G, psum


@_jit
def conjugate_direction(z, shift, g, approach, p, beta, t, dest):
    """``t = (z - shift + beta t)`` on the contact set, 0 elsewhere; ``dest[...] = t`` (``dest`` may
    be ``z``: each element is read before it is written); returns (sum t, sum (g - approach) t)."""
    st = 0.0
    gt = 0.0
    for i in range(g.shape[0]):
        for j in range(g.shape[1]):
            if p[i, j] > 0.0:
                v = z[i, j] - shift + beta * t[i, j]
                st += v
                gt += (g[i, j] - approach) * v
            else:
                v = 0.0
            t[i, j] = v
            dest[i, j] = v
    return st, gt


@_jit
def contact_sums(r, t, offset, p):
    """Returns (sum of r over the contact set, sum over it of r (t - offset))."""
    sr = 0.0
    rt = 0.0
    for i in range(r.shape[0]):
        for j in range(r.shape[1]):
            v = r[i, j] if p[i, j] > 0.0 else 0.0
            sr += v
            rt += v * (t[i, j] - offset)
    return sr, rt


@_jit
def step_project_reenter(p, factor, t, g, approach, tau, tau_reenter, dest):
    """``p = factor p - tau t``, projected on ``p >= 0``, points where the gap ``g - approach`` is
    negative re-entered with ``p = -tau_reenter gap``; ``dest[...] = p``. Returns (sum p, number of
    re-entered points, sum of ``t`` over the new contact set)."""
    psum = 0.0
    n_ol = 0
    t_kept = 0.0
    for i in range(p.shape[0]):
        for j in range(p.shape[1]):
            tv = t[i, j]
            v = factor * p[i, j] - tau * tv
            gv = g[i, j] - approach
            reenter = v <= 0.0 and gv < 0.0
            v = -tau_reenter * gv if reenter else max(v, 0.0)
            n_ol += 1 if reenter else 0
            t_kept += tv if v > 0.0 else 0.0
            p[i, j] = v
            dest[i, j] = v
            psum += v
    return psum, n_ol, t_kept


def as2d(a: np.ndarray) -> np.ndarray:
    return a.reshape(1, -1) if a.ndim == 1 else a
