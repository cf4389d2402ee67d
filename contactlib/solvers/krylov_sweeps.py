"""Fused passes of the GMRES set solve (:mod:`.krylov`): numba, serial, flat contiguous arrays.

On a 2^14-point profile a GMRES iteration's two FFT pairs cost about 0.1 ms each, and in numpy its
Gram-Schmidt sweep, the scatter to and gather from the contact set, the centring and the bookkeeping cost
as much again (0.8 ms an iteration against 0.3 ms of transforms). Here each of those is one compiled pass.
Sums run in a fixed order (one thread), so a solve returns the same bits every time.
"""

from __future__ import annotations

import math

import numba

from ..core._numba import jit as _jit


@_jit
def scatter(field, index, values):
    """``field`` = ``values`` on ``index``, 0 elsewhere (``field`` flat, ``index`` increasing)."""
    field[:] = 0.0
    for j in range(index.size):
        field[index[j]] = values[j]


@_jit
def gather_centred(field, index, out):
    """``out`` = ``field`` on ``index``, centred; returns the mean removed."""
    total = 0.0
    for j in range(index.size):
        v = field[index[j]]
        out[j] = v
        total += v
    mean = total / index.size
    for j in range(index.size):
        out[j] -= mean
    return mean


@_jit
def orthogonalise(basis, k, w, column):
    """Modified Gram-Schmidt of ``w`` (in place) against ``basis[0..k]``, the coefficients into
    ``column[0..k]``; returns the norm of what is left. Each vector's update and the next one's inner
    product share one pass (the product reads the updated ``w``, as modified Gram-Schmidt asks)."""
    n = w.size
    h = 0.0
    b = basis[0]
    for i in range(n):
        h += w[i] * b[i]
    for j in range(k + 1):
        column[j] = h
        b = basis[j]
        if j < k:
            c = basis[j + 1]
            nxt = 0.0
            for i in range(n):
                wi = w[i] - h * b[i]
                w[i] = wi
                nxt += wi * c[i]
            h = nxt
        else:
            for i in range(n):
                w[i] -= h * b[i]
    s = 0.0
    for i in range(n):
        s += w[i] * w[i]
    return math.sqrt(s)


@_jit
def scale_into(out, w, factor):
    """``out = factor * w``."""
    for i in range(w.size):
        out[i] = factor * w[i]


@_jit
def combine(x, directions, y, size):
    """``x += sum_j y[j] directions[j]`` over ``j < size`` (in place)."""
    for j in range(size):
        d = directions[j]
        yj = y[j]
        for i in range(x.size):
            x[i] += yj * d[i]


@_jit
def rotate(H, rotations, g, k):
    """Apply the ``k`` Givens rotations so far to column ``k`` of the Hessenberg matrix ``H``, then the new one
    that zeroes ``H[k + 1, k]`` (stored in ``rotations[k]``), to ``g`` too. Returns ``|g[k + 1]|``, the
    residual norm."""
    for j in range(k):
        c = rotations[j, 0]
        s = rotations[j, 1]
        a = H[j, k]
        b = H[j + 1, k]
        H[j, k] = c * a + s * b
        H[j + 1, k] = -s * a + c * b
    d = math.hypot(H[k, k], H[k + 1, k])
    if d > 0:
        c = H[k, k] / d
        s = H[k + 1, k] / d
    else:
        c = 1.0
        s = 0.0
    rotations[k, 0] = c
    rotations[k, 1] = s
    H[k, k] = d
    H[k + 1, k] = 0.0
    g[k + 1] = -s * g[k]
    g[k] = c * g[k]
    return abs(g[k + 1])


# no fastmath: the gap is a difference of near-equals, and reassociated it moves by eps |heights|
@numba.njit(cache=True, nogil=True, boundscheck=False)
def newton_sweep(p, active, displacement, hp, approach, gap, positive, following):
    """One pass of a Newton contact-set update (:func:`.semismooth.solve_semismooth`) instead of about ten
    numpy ones: ``gap = displacement - hp - approach``, ``positive = max(p, 0)``, the next set ``following``
    (held points stay while they carry pressure, others join where they interpenetrate). Returns
    ``(sum positive, sum positive |gap|, sum max(-gap, 0), points whose membership changes)``."""
    total = 0.0
    comp = 0.0
    pen = 0.0
    changed = 0
    for i in range(p.size):
        g = displacement[i] - hp[i] - approach
        gap[i] = g
        v = p[i] if p[i] > 0.0 else 0.0
        positive[i] = v
        total += v
        comp += v * abs(g)
        if g < 0.0:
            pen -= g
        f = p[i] > 0.0 if active[i] else g < 0.0
        following[i] = f
        if f != active[i]:
            changed += 1
    return total, comp, pen, changed
