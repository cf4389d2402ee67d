"""Fused element-wise passes of the Polonsky-Keer iteration (numba; serial or threaded).

Each function is one sweep over the grid doing what would take numpy 4-8 passes and
temporaries; the sweeps are memory-bound and, beside two or three FFT pairs per iteration,
would otherwise dominate its cost (measured in benchmarks/). Arrays are 2D (profiles are
viewed as ``(1, n)``) and may be strided views into the FFT work buffers. :func:`select` gives
the serial sweeps or their threaded versions (:mod:`contactlib.core._numba`).
"""

from __future__ import annotations

from typing import NamedTuple

import numba
import numpy as np

from ...core._numba import column_sums, parallel_jit, parallel_sweeps, row_blocks, serialised
from ...core._numba import jit as _jit

# The contact set is patchy on rough surfaces, so the sweeps select with arithmetic rather than
# branches where they can: mispredicted branches made the projection step cost up to one FFT pair.
# It is kept as a byte mask ``contact`` (``p > 0``), an eighth of the pressure's memory traffic for
# the sweeps that need only the set. The gap is ``factor * w - approach``, with ``w`` the
# transforms' output ``K p - hp / factor``: no sweep writes a gap field.


@_jit
def contact_sum(values, contact):
    """Sum of ``values`` over the contact set."""
    s = 0.0
    for i in range(values.shape[0]):
        for j in range(values.shape[1]):
            s += values[i, j] if contact[i, j] else 0.0
    return s


@_jit
def measure(w, factor, approach, p, masked, write_masked):
    """Contact measures of the gap ``factor w - approach`` and the pressure ``factor p``; if
    ``write_masked``, ``masked`` = the gap on the contact set and 0 elsewhere.

    Returns (sum p|gap|, sum max(-gap, 0) off contact, sum over contact of gap^2, sum p)."""
    comp = 0.0
    pen = 0.0
    G = 0.0
    psum = 0.0
    for i in range(w.shape[0]):
        for j in range(w.shape[1]):
            v = factor * w[i, j] - approach
            pv = factor * p[i, j]
            m = 1.0 if pv > 0.0 else 0.0
            x = m * v
            G += x * v
            psum += pv
            comp += pv * abs(v)
            pen += (1.0 - m) * max(-v, 0.0)
            if write_masked:
                masked[i, j] = x
    return comp, pen, G, psum


@_jit
def conjugate_direction(z, z_scale, shift, w, factor, approach, contact, beta, t):
    """``t = z_scale z - shift + beta t`` on the contact set, 0 elsewhere, in place; returns (sum t,
    sum of gap t), the gap being ``factor w - approach``."""
    st = 0.0
    gt = 0.0
    for i in range(w.shape[0]):
        for j in range(w.shape[1]):
            if contact[i, j]:
                v = z_scale * z[i, j] - shift + beta * t[i, j]
                st += v
                gt += (factor * w[i, j] - approach) * v
            else:
                v = 0.0
            t[i, j] = v
    return st, gt


@_jit
def step_project_reenter(p, factor, t, w, approach, tau, tau_reenter, contact):
    """``p = factor p - tau t``, projected on ``p >= 0``, points where the gap ``factor w - approach``
    is negative re-entered with ``p = -tau_reenter gap``; ``contact`` = ``p > 0``. Returns (sum p,
    number of re-entered points, sum of ``t`` over the new contact set, number of contact points)."""
    psum = 0.0
    n_ol = 0
    n_c = 0
    t_kept = 0.0
    for i in range(p.shape[0]):
        for j in range(p.shape[1]):
            tv = t[i, j]
            v = factor * p[i, j] - tau * tv
            gv = factor * w[i, j] - approach
            reenter = v <= 0.0 and gv < 0.0
            v = -tau_reenter * gv if reenter else max(v, 0.0)
            c = v > 0.0
            n_ol += 1 if reenter else 0
            n_c += 1 if c else 0
            t_kept += tv if c else 0.0
            p[i, j] = v
            contact[i, j] = c
            psum += v
    return psum, n_ol, t_kept, n_c


# Threaded versions: each runs its serial sweep on fixed row blocks and adds the blocks' sums in order.


@parallel_jit
def _threaded_contact_sum(values, contact):
    blocks, size = row_blocks(values.shape[0], values.shape[1])
    part = np.empty((blocks, 1))
    for b in numba.prange(blocks):
        r = slice(b * size, min((b + 1) * size, values.shape[0]))
        part[b, 0] = contact_sum(values[r], contact[r])
    return column_sums(part)[0]


@parallel_jit
def _threaded_measure(w, factor, approach, p, masked, write_masked):
    blocks, size = row_blocks(w.shape[0], w.shape[1])
    part = np.empty((blocks, 4))
    for b in numba.prange(blocks):
        r = slice(b * size, min((b + 1) * size, w.shape[0]))
        out = masked[r] if write_masked else masked
        part[b, 0], part[b, 1], part[b, 2], part[b, 3] = measure(w[r], factor, approach, p[r], out, write_masked)
    s = column_sums(part)
    return s[0], s[1], s[2], s[3]


@parallel_jit
def _threaded_conjugate_direction(z, z_scale, shift, w, factor, approach, contact, beta, t):
    blocks, size = row_blocks(w.shape[0], w.shape[1])
    part = np.empty((blocks, 2))
    for b in numba.prange(blocks):
        r = slice(b * size, min((b + 1) * size, w.shape[0]))
        part[b, 0], part[b, 1] = conjugate_direction(z[r], z_scale, shift, w[r], factor, approach, contact[r],
                                                     beta, t[r])
    s = column_sums(part)
    return s[0], s[1]


@parallel_jit
def _threaded_step_project_reenter(p, factor, t, w, approach, tau, tau_reenter, contact):
    blocks, size = row_blocks(p.shape[0], p.shape[1])
    part = np.empty((blocks, 4))
    for b in numba.prange(blocks):
        r = slice(b * size, min((b + 1) * size, p.shape[0]))
        part[b, 0], part[b, 1], part[b, 2], part[b, 3] = step_project_reenter(p[r], factor, t[r], w[r], approach,
                                                                              tau, tau_reenter, contact[r])
    s = column_sums(part)
    return s[0], int(s[1]), s[2], int(s[3])


class Sweeps(NamedTuple):
    """One version (serial or threaded) of each sweep; the serial functions' docstrings say what they do."""

    contact_sum: object
    measure: object
    conjugate_direction: object
    step_project_reenter: object


SERIAL = Sweeps(contact_sum, measure, conjugate_direction, step_project_reenter)
THREADED = Sweeps(*(serialised(sweep) for sweep in (_threaded_contact_sum, _threaded_measure,
                                                     _threaded_conjugate_direction, _threaded_step_project_reenter)))


def select(shape: tuple[int, ...]) -> Sweeps:
    """The sweeps for 2D arrays of ``shape``: threaded when the FFTs are and the grid is large."""
    return THREADED if parallel_sweeps(shape[0], int(np.prod(shape))) else SERIAL


def as2d(a: np.ndarray) -> np.ndarray:
    return a.reshape(1, -1) if a.ndim == 1 else a
