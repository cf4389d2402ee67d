"""Fused element-wise passes of the Polonsky-Keer iteration (numba; serial or over threads).

Each sweep is one pass over the grid doing what would take numpy 4-8 passes and temporaries; the
sweeps are memory-bound and, beside two or three FFT pairs per iteration, would otherwise
dominate its cost (measured in benchmarks/). Arrays are 2D (profiles are viewed as ``(1, n)``)
and may be strided views into the FFT work buffers. Every sweep works row by row and returns its
sums as an array, reduced in row order, so that the serial and the threaded compilations
(:func:`select`) give the same bits (:mod:`contactlib._numba`).
"""

from __future__ import annotations

from typing import NamedTuple

import numba
import numpy as np

from .._numba import column_sums, jit, parallel_sweeps, twins

# The contact set ``p > 0`` is patchy on rough surfaces, so the rows select with arithmetic
# rather than branches: mispredicted branches made the projection step cost up to one FFT pair.


@jit
def _gap_row(u, factor, hp, p, g):
    n_c = 0
    s = 0.0
    for j in range(u.shape[0]):
        v = factor * u[j] - hp[j]
        g[j] = v
        c = p[j] > 0.0
        n_c += 1 if c else 0
        s += v if c else 0.0
    return float(n_c), s


def _gap_and_contact_mean(u, factor, hp, p, g):
    """``g = factor u - hp``; returns [number of points with p > 0, sum of g over them]."""
    part = np.empty((u.shape[0], 2))
    for i in numba.prange(u.shape[0]):
        part[i, 0], part[i, 1] = _gap_row(u[i], factor, hp[i], p[i], g[i])
    return column_sums(part)


@jit
def _measure_row(g, p, factor, approach, masked, write_masked):
    comp = 0.0
    pen = 0.0
    G = 0.0
    psum = 0.0
    for j in range(g.shape[0]):
        v = g[j] - approach
        pv = factor * p[j]
        m = 1.0 if pv > 0.0 else 0.0
        w = m * v
        G += w * v
        psum += pv
        comp += pv * abs(v)
        pen += (1.0 - m) * max(-v, 0.0)
        if write_masked:
            masked[j] = w
    return comp, pen, G, psum


def _measure(g, p, factor, approach, masked, write_masked):
    """Contact measures of the gap ``g - approach`` (``g`` is left unshifted) and pressure
    ``factor p``; if ``write_masked``, ``masked`` = the gap on the contact set and 0 elsewhere
    (``masked`` is not touched otherwise and may be any 2D array).

    Returns [sum p|gap|, sum max(-gap, 0) off contact, sum over contact of gap^2, sum p]."""
    part = np.empty((g.shape[0], 4))
    for i in numba.prange(g.shape[0]):
        row = masked[i] if write_masked else masked[0]
        part[i, 0], part[i, 1], part[i, 2], part[i, 3] = _measure_row(g[i], p[i], factor, approach, row,
                                                                     write_masked)
    return column_sums(part)


@jit
def _direction_row(z, shift, g, approach, p, beta, t, dest):
    st = 0.0
    gt = 0.0
    for j in range(g.shape[0]):
        if p[j] > 0.0:
            v = z[j] - shift + beta * t[j]
            st += v
            gt += (g[j] - approach) * v
        else:
            v = 0.0
        t[j] = v
        dest[j] = v
    return st, gt


def _conjugate_direction(z, shift, g, approach, p, beta, t, dest):
    """``t = (z - shift + beta t)`` on the contact set, 0 elsewhere; ``dest[...] = t`` (``dest`` may
    be ``z``: each element is read before it is written); returns [sum t, sum (g - approach) t]."""
    part = np.empty((g.shape[0], 2))
    for i in numba.prange(g.shape[0]):
        part[i, 0], part[i, 1] = _direction_row(z[i], shift, g[i], approach, p[i], beta, t[i], dest[i])
    return column_sums(part)


@jit
def _contact_sums_row(r, t, offset, p):
    sr = 0.0
    rt = 0.0
    for j in range(r.shape[0]):
        v = r[j] if p[j] > 0.0 else 0.0
        sr += v
        rt += v * (t[j] - offset)
    return sr, rt


def _contact_sums(r, t, offset, p):
    """Returns [sum of r over the contact set, sum over it of r (t - offset)]."""
    part = np.empty((r.shape[0], 2))
    for i in numba.prange(r.shape[0]):
        part[i, 0], part[i, 1] = _contact_sums_row(r[i], t[i], offset, p[i])
    return column_sums(part)


@jit
def _step_row(p, factor, t, g, approach, tau, tau_reenter, dest):
    psum = 0.0
    n_ol = 0
    t_kept = 0.0
    for j in range(p.shape[0]):
        tv = t[j]
        v = factor * p[j] - tau * tv
        gv = g[j] - approach
        reenter = v <= 0.0 and gv < 0.0
        v = -tau_reenter * gv if reenter else max(v, 0.0)
        n_ol += 1 if reenter else 0
        t_kept += tv if v > 0.0 else 0.0
        p[j] = v
        dest[j] = v
        psum += v
    return psum, float(n_ol), t_kept


def _step_project_reenter(p, factor, t, g, approach, tau, tau_reenter, dest):
    """``p = factor p - tau t``, projected on ``p >= 0``, points where the gap ``g - approach`` is
    negative re-entered with ``p = -tau_reenter gap``; ``dest[...] = p``. Returns [sum p, number of
    re-entered points, sum of ``t`` over the new contact set]."""
    part = np.empty((p.shape[0], 3))
    for i in numba.prange(p.shape[0]):
        part[i, 0], part[i, 1], part[i, 2] = _step_row(p[i], factor, t[i], g[i], approach, tau, tau_reenter,
                                                       dest[i])
    return column_sums(part)


class Sweeps(NamedTuple):
    """One compilation (serial or threaded) of each sweep; see the functions' docstrings."""

    gap_and_contact_mean: object
    measure: object
    conjugate_direction: object
    contact_sums: object
    step_project_reenter: object


_DRIVERS = (_gap_and_contact_mean, _measure, _conjugate_direction, _contact_sums, _step_project_reenter)
_SERIAL, _PARALLEL = (Sweeps(*c) for c in zip(*(twins(d) for d in _DRIVERS)))


def select(shape: tuple[int, ...]) -> Sweeps:
    """The sweeps for 2D arrays of ``shape``: threaded when the FFTs are (same results either way)."""
    return _PARALLEL if parallel_sweeps(shape[0], int(np.prod(shape))) else _SERIAL


def as2d(a: np.ndarray) -> np.ndarray:
    return a.reshape(1, -1) if a.ndim == 1 else a
