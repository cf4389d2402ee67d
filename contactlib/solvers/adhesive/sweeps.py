"""Fused element-wise passes of the frozen-traction cohesive iteration (numba, serial).

Each round of :class:`contactlib.solvers.adhesive.cohesive_frozen.FrozenTraction` evaluates the cohesive law at the new
gap, the residual of the state, and an Anderson mixing step: in numpy some thirty passes over the grid
and their temporaries, which cost as much per round as one or two Polonsky-Keer iterations (256^2). Here
they are three sweeps: :func:`law_residual` and the fused :class:`.anderson.Anderson`'s two. Arrays are flat and
contiguous, except in :func:`frozen_state` and :func:`move_heights`, the two sweeps of a round inside a running
Polonsky-Keer solve (:mod:`.cohesive_rounds`), which read and write its buffers as 2D (maybe strided) views.
"""

from __future__ import annotations

import math

from ...core._numba import jit as _jit

MAUGIS, EXPONENTIAL = 0, 1
"""Codes of the cohesive laws (:class:`contactlib.Adhesion`'s ``model``) in the sweeps."""


@_jit
def law_residual(p, g, model, sigma0, range_, ramp, c, image):
    """``image`` = the adhesive traction ``a(g)`` of the law (:meth:`contactlib.Adhesion.traction`,
    Maugis' step as its ramp of half-width ``ramp * range_``); returns ``(sum |phi|, sum max(-g, 0),
    sum |p_r| |g|, sum |p_r|, sum |p|, the points within the range)`` with ``phi = c g`` where the repulsive
    part ``p_r = p - a(g)`` exceeds ``c g``, else ``p_r``."""
    phi_sum = 0.0
    overlap = 0.0
    comp = 0.0
    weight = 0.0
    traction = 0.0
    interacting = 0
    for i in range(p.size):
        gi = g[i]
        gp = max(gi, 0.0)
        if model == MAUGIS:
            share = ((1.0 + ramp) * range_ - gp) / (2.0 * ramp * range_)
            a = -sigma0 * min(max(share, 0.0), 1.0)
        else:
            a = -sigma0 * math.exp(-gp / range_)
        image[i] = a
        repulsive = p[i] - a
        cg = c * gi
        phi_sum += abs(cg) if repulsive > cg else abs(repulsive)
        overlap += max(-gi, 0.0)
        comp += abs(repulsive) * abs(gi)
        weight += abs(repulsive)
        traction += abs(p[i])
        if gi <= range_:
            interacting += 1
    return phi_sum, overlap, comp, weight, traction, interacting


@_jit
def frozen_state(q, factor, w, approach, a, total, gap):
    """The state of a round inside the Polonsky-Keer solve (2D arrays, ``q`` and ``w`` maybe strided views of its
    buffers): ``total = factor q + a`` (the traction) and ``gap = factor w - approach``."""
    for i in range(q.shape[0]):
        for j in range(q.shape[1]):
            total[i, j] = factor * q[i, j] + a[i, j]
            gap[i, j] = factor * w[i, j] - approach


@_jit
def move_heights(w, hp, u, factor, new_factor):
    """Lower the heights ``hp`` by ``u`` (2D arrays) and move ``w = K q - hp / factor`` to the lowered heights and
    ``new_factor``: ``w += hp (1 / factor - 1 / new_factor) + u / new_factor``, ``hp -= u``."""
    shift = 1.0 / factor - 1.0 / new_factor
    inverse = 1.0 / new_factor
    for i in range(w.shape[0]):
        for j in range(w.shape[1]):
            w[i, j] += hp[i, j] * shift + u[i, j] * inverse
            hp[i, j] -= u[i, j]
