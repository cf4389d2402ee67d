"""Compiled passes over the micro scale's window stacks (:mod:`.micro`): numba, serial.

A stack holds one ``w x w`` window per asperity, ``(N, w, w)``, its node ``(k, i, j)`` at the grid's row
``rows[k, i]`` and column ``cols[k, j]`` (wrapped on a periodic grid), and whether that node lies in the
asperity's footprint (``masks``). Between its two full-grid convolutions and its local solves, a two-scale
solve gathers, scatters and reduces these stacks about twenty times; as numpy expressions (fancy indexing,
``np.where`` temporaries, masked reductions) that bookkeeping took about 20 ms of a 50 ms solve at 10^3
asperities on 700^2 nodes, several times the arithmetic. Each function here is one pass. They are bound by
memory traffic (the grid fields and the stacks come from memory, not cache): the two ``(N, w)`` index arrays
instead of one flat index per node (``(N, w, w)`` int64, as large as a stack) took 3-5 % off the whole solve.
Sums run in a fixed order, so a solve returns the same bits every time.
"""

from __future__ import annotations

import math

import numpy as np

from ..core._numba import jit


@jit
def window_nodes(centers, h, n, window, periodic, length, footprint, rows, cols, masks, r2):
    """Fill ``rows``, ``cols`` ``(N, w)`` and ``masks``, ``r2`` ``(N, w, w)``: each window centred on the grid node
    nearest its summit (``centers`` [length], ``h`` the spacing, ``n`` nodes a side), wrapped if ``periodic``
    (window ``length``), else shifted inside the grid; the squared distances [length^2] from the summit (nearest
    image) and the nodes inside the ``footprint`` radius."""
    half = window // 2
    ox = np.empty(window)
    oy = np.empty(window)
    for k in range(centers.shape[0]):
        sx = int(np.rint(centers[k, 0] / h)) - half
        sy = int(np.rint(centers[k, 1] / h)) - half
        if not periodic:
            sx = min(max(sx, 0), n - window)
            sy = min(max(sy, 0), n - window)
        for i in range(window):
            ox[i] = (sx + i) * h - centers[k, 0]
            oy[i] = (sy + i) * h - centers[k, 1]
            rows[k, i] = sx + i
            cols[k, i] = sy + i
            if periodic:
                ox[i] = (ox[i] + length / 2) % length - length / 2
                oy[i] = (oy[i] + length / 2) % length - length / 2
                rows[k, i] = rows[k, i] % n
                cols[k, i] = cols[k, i] % n
        reach = footprint[k] * footprint[k]
        for i in range(window):
            for j in range(window):
                d = ox[i] * ox[i] + oy[j] * oy[j]
                r2[k, i, j] = d
                masks[k, i, j] = d < reach


@jit
def footprint_edges(masks, edge, border):
    """``edge``: the nodes next to a node off the footprint (4-neighbours in the window); ``border``: the
    window border's nodes that are not on ``edge``."""
    m, w, _ = masks.shape
    for k in range(m):
        for i in range(w):
            for j in range(w):
                near = (i > 0 and not masks[k, i - 1, j]) or (i < w - 1 and not masks[k, i + 1, j]) or \
                       (j > 0 and not masks[k, i, j - 1]) or (j < w - 1 and not masks[k, i, j + 1])
                edge[k, i, j] = near
                border[k, i, j] = (i == 0 or i == w - 1 or j == 0 or j == w - 1) and not near


@jit
def hertz_stack(force, radius, r2, node_area, masks, masked, out):
    """``out`` ``(N, w, w)``: Hertz's pressure ``sqrt(1 - r^2/a^2)`` of each loaded asperity scaled so that its
    nodes carry ``force`` [force] at ``node_area`` [length^2]; zero where ``masked`` and off ``masks``."""
    m, w, _ = r2.shape
    for k in range(m):
        if not force[k] > 0:
            out[k] = 0.0
            continue
        a2 = radius[k] * radius[k]
        total = 0.0
        for i in range(w):
            for j in range(w):
                v = 1.0 - r2[k, i, j] / a2
                v = math.sqrt(v) if v > 0.0 else 0.0
                out[k, i, j] = v
                total += v
        total *= node_area
        factor = force[k] / total if total > 0 else 0.0
        for i in range(w):
            for j in range(w):
                out[k, i, j] *= factor if (masks[k, i, j] or not masked) else 0.0


@jit
def gather(field, rows, cols, out):
    """``out[k, i, j] = field[rows[k, i], cols[k, j]]`` (``field`` 2D)."""
    m, w, _ = out.shape
    for k in range(m):
        for i in range(w):
            line = field[rows[k, i]]
            for j in range(w):
                out[k, i, j] = line[cols[k, j]]


@jit
def scatter_footprints(values, masks, rows, cols, field):
    """``field`` = ``values`` on the footprints' nodes, 0 elsewhere (``field`` 2D; the footprints are
    disjoint, so every node is written once at most)."""
    field[:] = 0.0
    m, w, _ = values.shape
    for k in range(m):
        for i in range(w):
            line = field[rows[k, i]]
            for j in range(w):
                if masks[k, i, j]:
                    line[cols[k, j]] = values[k, i, j]


@jit
def local_heights(heights, displacement, rows, cols, own_displacement, masks, out, top, low):
    """The heights each window's local solve sees, ``heights - (u_all - K_w p_k)`` (``displacement`` the
    whole grid's, 2D), into ``out``; their highest (``top``) and lowest (``low``) on the footprint
    (-inf and inf for an empty one)."""
    m, w, _ = heights.shape
    for k in range(m):
        high, deep = -np.inf, np.inf
        for i in range(w):
            line = displacement[rows[k, i]]
            for j in range(w):
                v = heights[k, i, j] - (line[cols[k, j]] - own_displacement[k, i, j])
                out[k, i, j] = v
                if masks[k, i, j]:
                    high = max(high, v)
                    deep = min(deep, v)
        top[k] = high
        low[k] = deep


@jit
def interference(local, masks, which, top, low, body_level, out, scale):
    """The rigid interference of the windows ``which`` (``out[i]`` for window ``which[i]``): the local heights
    above ``body_level`` on the footprint, and off it the footprint's lowest point lowered by the
    footprint's height range (no contact there); ``scale[i]``: its rms about its mean [length]."""
    _, w, _ = local.shape
    count = w * w
    for i in range(which.size):
        k = which[i]
        lowered = low[k] - (top[k] - low[k]) - body_level
        total = 0.0
        for a in range(w):
            for b in range(w):
                v = local[k, a, b] - body_level if masks[k, a, b] else lowered
                out[i, a, b] = v
                total += v
        mean = total / count
        var = 0.0
        for a in range(w):
            for b in range(w):
                d = out[i, a, b] - mean
                var += d * d
        scale[i] = math.sqrt(var / count)


@jit
def rescale(patches, solved, factor, own):
    """Scale each window's new pressure ``patches`` and its displacement ``solved`` by ``factor`` (the coarse
    correction) in place; returns ``(|patches|^2, |patches - own|^2)`` after it."""
    m, w, _ = patches.shape
    norm = 0.0
    difference = 0.0
    for k in range(m):
        f = factor[k]
        for i in range(w):
            for j in range(w):
                p = patches[k, i, j] * f
                patches[k, i, j] = p
                solved[k, i, j] *= f
                norm += p * p
                d = p - own[k, i, j]
                difference += d * d
    return norm, difference


@jit
def gap_field(displacement, level, heights, gap, kept):
    """``gap = displacement + level - heights`` and ``kept`` = a copy of ``displacement`` (the FFT buffer's
    view), in one pass; returns how many nodes have a negative gap, and the sums of the heights and of
    their squares (the residual's height scale, without another pass over the grid)."""
    below = 0
    total = 0.0
    squares = 0.0
    rows, cols = gap.shape
    for i in range(rows):
        for j in range(cols):
            u = displacement[i, j]
            h = heights[i, j]
            kept[i, j] = u
            g = u + level - h
            gap[i, j] = g
            below += g < 0.0
            total += h
            squares += h * h
    return below, total, squares


@jit
def footprint_sums(pressure, gap, rows, cols, masks):
    """Over the footprints' nodes: ``(sum p, sum p |g|, sum max(-g, 0), nodes with g < 0)``, the pressure
    from its stack ``(N, w, w)``, the gap from the grid (2D)."""
    m, w, _ = pressure.shape
    total = comp = pen = 0.0
    below = 0
    for k in range(m):
        for i in range(w):
            line = gap[rows[k, i]]
            for j in range(w):
                if masks[k, i, j]:
                    g = line[cols[k, j]]
                    p = pressure[k, i, j]
                    total += p
                    comp += p * abs(g)
                    if g < 0.0:
                        pen -= g
                        below += 1
    return total, comp, pen, below
