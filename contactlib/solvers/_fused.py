"""Fused element-wise passes of the Polonsky-Keer iteration (numba; serial or threaded).

Each function is one sweep over the grid doing what would take numpy 4-8 passes and
temporaries; the sweeps are memory-bound and, beside two or three FFT pairs per iteration,
would otherwise dominate its cost (measured in benchmarks/). Arrays are 2D (profiles are
viewed as ``(1, n)``) and may be strided views into the FFT work buffers. :func:`select` gives
the serial sweeps or their threaded versions (:mod:`contactlib._numba`).
"""

from __future__ import annotations

from typing import NamedTuple

import numba
import numpy as np

from .._numba import column_sums, parallel_jit, parallel_sweeps, row_blocks
from .._numba import jit as _jit

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


# Threaded versions: each runs its serial sweep on fixed row blocks and adds the blocks' sums in order.


@parallel_jit
def _threaded_gap_and_contact_mean(u, factor, hp, p, g):
    blocks, size = row_blocks(u.shape[0], u.shape[1])
    part = np.empty((blocks, 2))
    for b in numba.prange(blocks):
        r = slice(b * size, min((b + 1) * size, u.shape[0]))
        part[b, 0], part[b, 1] = gap_and_contact_mean(u[r], factor, hp[r], p[r], g[r])
    s = column_sums(part)
    return int(s[0]), s[1]


@parallel_jit
def _threaded_measure(g, p, factor, approach, masked, write_masked):
    blocks, size = row_blocks(g.shape[0], g.shape[1])
    part = np.empty((blocks, 4))
    for b in numba.prange(blocks):
        r = slice(b * size, min((b + 1) * size, g.shape[0]))
        out = masked[r] if write_masked else masked
        part[b, 0], part[b, 1], part[b, 2], part[b, 3] = measure(g[r], p[r], factor, approach, out, write_masked)
    s = column_sums(part)
    return s[0], s[1], s[2], s[3]


@parallel_jit
def _threaded_conjugate_direction(z, shift, g, approach, p, beta, t, dest):
    blocks, size = row_blocks(g.shape[0], g.shape[1])
    part = np.empty((blocks, 2))
    for b in numba.prange(blocks):
        r = slice(b * size, min((b + 1) * size, g.shape[0]))
        part[b, 0], part[b, 1] = conjugate_direction(z[r], shift, g[r], approach, p[r], beta, t[r], dest[r])
    s = column_sums(part)
    return s[0], s[1]


@parallel_jit
def _threaded_contact_sums(values, t, offset, p):
    blocks, size = row_blocks(values.shape[0], values.shape[1])
    part = np.empty((blocks, 2))
    for b in numba.prange(blocks):
        r = slice(b * size, min((b + 1) * size, values.shape[0]))
        part[b, 0], part[b, 1] = contact_sums(values[r], t[r], offset, p[r])
    s = column_sums(part)
    return s[0], s[1]


@parallel_jit
def _threaded_step_project_reenter(p, factor, t, g, approach, tau, tau_reenter, dest):
    blocks, size = row_blocks(p.shape[0], p.shape[1])
    part = np.empty((blocks, 3))
    for b in numba.prange(blocks):
        r = slice(b * size, min((b + 1) * size, p.shape[0]))
        part[b, 0], part[b, 1], part[b, 2] = step_project_reenter(p[r], factor, t[r], g[r], approach, tau,
                                                                  tau_reenter, dest[r])
    s = column_sums(part)
    return s[0], int(s[1]), s[2]


class Sweeps(NamedTuple):
    """One version (serial or threaded) of each sweep; the serial functions' docstrings say what they do."""

    gap_and_contact_mean: object
    measure: object
    conjugate_direction: object
    contact_sums: object
    step_project_reenter: object


SERIAL = Sweeps(gap_and_contact_mean, measure, conjugate_direction, contact_sums, step_project_reenter)
THREADED = Sweeps(_threaded_gap_and_contact_mean, _threaded_measure, _threaded_conjugate_direction,
                  _threaded_contact_sums, _threaded_step_project_reenter)


def select(shape: tuple[int, ...]) -> Sweeps:
    """The sweeps for 2D arrays of ``shape``: threaded when the FFTs are and the grid is large."""
    return THREADED if parallel_sweeps(shape[0], int(np.prod(shape))) else SERIAL


def as2d(a: np.ndarray) -> np.ndarray:
    return a.reshape(1, -1) if a.ndim == 1 else a
