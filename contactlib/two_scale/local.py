"""The micro scale's local problems, all windows at once: one stacked convolution per step for every
asperity, and Polonsky & Keer's constrained conjugate gradients vectorised over the stack.

Every window has the same size and spacing, hence the same zero-padded half-space kernel (the
multiplier of :class:`contactlib.model.operators.Compliance` with ``periodic=False`` on the window's grid):
the stack of ``M`` windows is convolved by one batched real FFT of shape ``(M, 2w, 2w)``, or, for windows
of at most :data:`DENSE_WINDOW` nodes a side, by one product with the kernel's dense ``w^2 x w^2`` matrix
(built once from the FFT; 9x faster at 16 nodes). Solving the
windows one by one cost a Python call, two small FFTs and a few fused sweeps per iteration and window;
on 10^3 asperities that overhead, not the arithmetic, was a third of the two-scale time.

The iteration is :func:`contactlib.solvers.solve_polonsky_keer`'s under displacement control without the
preconditioner (Polonsky & Keer 1999: CG on the contact set, projection on ``p >= 0``, re-entry of
interpenetrating points with a restart of the conjugacy), with its residual
(:func:`contactlib.solvers.contact_residual`) per window. A window leaves the stack once its residual is
at most ``tol``, so the work follows each window's own iterations. Between the two batched products of an
iteration, the rest (gap, residual, direction; step, projection, re-entry) is two compiled passes over the
stack: as a dozen numpy expressions it cost more than the products (10^3 windows of 14^2 nodes, single
precision, 4 iterations: 13.8 -> 8.3 ms a solve, the same iterates to 1e-15 in double precision).
"""

from __future__ import annotations

import copy
import math

import numpy as np
import scipy.fft as sfft

from ..core.grid import Grid
from ..core._numba import jit
from ..model.operators import Compliance


BLOCK = 1024
"""Windows per batched FFT: bounds the padded spectra's memory (10^4 windows of 44^2 would take 160 MB)."""
COMPACT = 0.25
"""The stack drops its done windows once they are this fraction of it; until then they stay, frozen (a
copy of the stack's arrays costs about one product: at 10^3 windows, most finish within a few
iterations of each other)."""
DENSE_WINDOW = 32
"""Windows of at most this many nodes per side apply the compliance as a dense ``w^2 x w^2`` matrix (one
matrix product for the whole stack, 8 MB at 32): at 16 nodes it is 9x faster than the batched FFT of the
zero-padded windows, and the product's cost grows like ``w^4`` against the FFT's ``w^2 log w``."""


class WindowStack:
    """Zero-padded half-space compliance of ``w x w`` windows of spacing ``h``, applied to a stack.

    Parameters
    ----------
    window : int
        Nodes per side.
    spacing : float
        Node spacing [length].
    E_star : float
        Contact modulus [pressure].
    single : bool
        Apply the dense matrix in single precision (float32 products, float64 results): twice as fast,
        with a rounding of about 1e-6 of the displacement, for local tolerances far above it.
    """

    def __init__(self, window: int, spacing: float, E_star: float, *, single: bool = False):
        self.window = int(window)
        grid = Grid((self.window, self.window), (self.window * spacing, self.window * spacing))
        self.operator = Compliance(grid, E_star=E_star, periodic=False)
        self.work_shape = self.operator.work_shape
        # Compliance folds the inverse transform's 1/N into its multiplier; scipy's irfft2 divides by N again
        self._multiplier = np.asarray(self.operator.multiplier) * float(np.prod(self.work_shape))
        self.self_compliance = self.operator.self_compliance()
        self._dense = None
        if self.window <= DENSE_WINDOW:  # the response of every node to a unit pressure on each: one FFT
            dense = self.operator.matrix(np.arange(self.window * self.window))
            self._dense = np.ascontiguousarray(dense, dtype=np.float32 if single else float)
        self.dtype = np.dtype(np.float32 if single and self._dense is not None else float)
        """The precision :func:`solve_stack` iterates in."""
        self._buffers = (np.empty((0, 0), np.float32),) * 2  # single precision's input and output, kept:
        # a fresh float32 array for each product made it slower than the float64 one (measured at 10^3 windows)

    def with_own_scratch(self) -> "WindowStack":
        """A shallow copy sharing the kernel and dense matrix, with scratch buffers of its own: a kept
        operator can then serve solves in several threads."""
        other = copy.copy(self)
        other._buffers = (np.empty((0, 0), np.float32),) * 2
        return other

    def __call__(self, pressure: np.ndarray) -> np.ndarray:
        """Displacement [length] on each window of the stack ``(M, w, w)`` of pressures [pressure]."""
        if self._dense is not None:  # symmetric: row or column stacking alike
            m = pressure.shape[0]
            flat = pressure.reshape(m, -1)
            if self._dense.dtype == flat.dtype:
                return (flat @ self._dense).reshape(pressure.shape)
            if self._buffers[0].shape[0] < m:
                self._buffers = tuple(np.empty((m, flat.shape[1]), np.float32) for _ in range(2))
            source, target = (b[:m] for b in self._buffers)
            np.copyto(source, flat, casting="same_kind")
            np.matmul(source, self._dense, out=target)
            return target.astype(float).reshape(pressure.shape)
        return self._convolve(pressure)

    def _convolve(self, pressure: np.ndarray) -> np.ndarray:
        """:meth:`__call__` by batched zero-padded FFTs."""
        out = np.empty_like(pressure)
        for start in range(0, pressure.shape[0], BLOCK):  # in blocks: the padded spectra of 10^4 windows
            block = slice(start, start + BLOCK)
            spectrum = sfft.rfft2(pressure[block], s=self.work_shape)
            spectrum *= self._multiplier
            out[block] = sfft.irfft2(spectrum, s=self.work_shape)[:, : self.window, : self.window]
        return out


def solve_stack(stack: WindowStack, interference: np.ndarray, *, tol: float, max_iter: int,
                initial_pressure: np.ndarray | None = None, scale: np.ndarray | None = None,
                initial_displacement: np.ndarray | None = None):
    """Frictionless contact of every window of the stack at a fixed rigid approach.

    Parameters
    ----------
    stack : WindowStack
    interference : ndarray, shape (M, w, w)
        Rigid interference ``s`` [length]: the gap is ``K p - s``; positive where the rigid surface would
        enter the body.
    tol : float
        Target of each window's :func:`contactlib.solvers.contact_residual`.
    max_iter : int
        Iterations at most per window.
    initial_pressure : ndarray, optional
        Warm start [pressure]; default ``max(s, 0)`` over the window's own compliance.
    scale : ndarray, shape (M,), optional
        Each window's height scale of the residual [length] (default: rms of ``s``).
    initial_displacement : ndarray, optional
        ``K`` applied to ``initial_pressure`` [length], if the caller has it (saves a product).

    Returns
    -------
    pressure, displacement : ndarray, shape (M, w, w)
        [pressure], ``K p`` [length].
    iterations : ndarray of int, shape (M,)
    residual : ndarray, shape (M,)
    """
    shape = np.shape(interference)
    m = shape[0]
    # every window as a row of w^2 nodes, in the stack's precision (single: half the memory traffic of
    # every pass, no casts around the products); the passes between the products are compiled, one a side
    s = np.asarray(interference).reshape(m, -1).astype(stack.dtype, copy=False)
    if scale is None:
        scale = np.empty(m)
        _window_rms(s, scale)
    scale = np.where(scale > 0, scale, 1.0)
    pressure, displacement = np.empty((m, s.shape[1])), np.empty((m, s.shape[1]))
    p = np.maximum(s, 0.0) / stack.dtype.type(stack.self_compliance) if initial_pressure is None else \
        np.maximum(np.asarray(initial_pressure, dtype=stack.dtype).reshape(m, -1), 0.0)
    iterations, residual = np.zeros(m, dtype=np.int64), np.full(m, np.inf)
    live = np.arange(m)  # windows still on the stack, and their state below
    frozen = np.zeros(m, dtype=bool)  # on the stack but done: answer recorded, held still (tau = 0)
    t = np.zeros_like(p)
    g = np.empty(p.shape)
    G_old = np.ones(m)
    restart = np.ones(m, dtype=bool)
    known = None if initial_displacement is None else np.asarray(initial_displacement).reshape(m, -1)
    for it in range(max_iter + 1):
        u = known if it == 0 and known is not None else stack(p.reshape(-1, *shape[1:])).reshape(p.shape)
        held = _measure_and_direct(u, s, p, g, t, scale, G_old, restart, frozen, live, float(tol), it,
                                   it == max_iter, pressure, displacement, iterations, residual)
        if held == frozen.size:
            break
        if held >= COMPACT * frozen.size:  # copying the stack costs a product
            keep = np.flatnonzero(~frozen)
            live, p, g, t, s, scale = live[keep], p[keep], g[keep], t[keep], s[keep], scale[keep]
            G_old, restart, frozen = G_old[keep], restart[keep], frozen[keep]
        kt = stack(t.reshape(-1, *shape[1:])).reshape(t.shape)
        _step_project_reenter(kt, g, p, t, frozen, restart, 1.0 / stack.self_compliance)
    return pressure.reshape(shape), displacement.reshape(shape), iterations, residual


@jit
def _window_rms(s, out):
    """``out[k]``: the rms of row ``k`` of ``s`` about its mean."""
    n = s.shape[1]
    for k in range(s.shape[0]):
        total = 0.0
        for i in range(n):
            total += s[k, i]
        mean = total / n
        var = 0.0
        for i in range(n):
            d = s[k, i] - mean
            var += d * d
        out[k] = math.sqrt(var / n)


@jit
def _measure_and_direct(u, s, p, g, t, scale, G_old, restart, frozen, live, tol, it, last, pressure, displacement,
                        iterations, residual):
    """One pass per window still moving: the gap ``g = u - s``, the window's residual (that of
    :func:`contactlib.solvers.contact_residual`); a window at ``tol`` (or at the last iteration) records its
    answer in row ``live[k]`` of ``pressure`` and ``displacement`` and is frozen; the others get their next
    conjugate direction ``t = g + beta t`` on the contact (0 off it). Returns the count of frozen windows."""
    m, n = p.shape
    held = 0
    for k in range(m):
        if frozen[k]:
            held += 1
            continue
        psum = 0.0
        comp = 0.0
        pen = 0.0
        G = 0.0
        for i in range(n):
            gi = u[k, i] - s[k, i]
            g[k, i] = gi
            pi = p[k, i]
            psum += pi
            comp += pi * abs(gi)
            pen += max(-gi, 0.0)
            G += gi * gi if pi > 0.0 else 0.0
        if psum > 0.0:
            r = (comp + psum * pen / n) / (psum * scale[k])
        else:
            r = pen / (n * scale[k])
        row = live[k]
        residual[row] = r
        iterations[row] = it
        if r <= tol or last:
            for i in range(n):
                pressure[row, i] = p[k, i]
                displacement[row, i] = u[k, i]
            frozen[k] = True
            held += 1
            continue
        beta = 0.0
        if not restart[k] and G_old[k] > 0.0:
            beta = G / G_old[k]
        G_old[k] = G
        for i in range(n):
            t[k, i] = beta * t[k, i] + g[k, i] if p[k, i] > 0.0 else 0.0
    return held


@jit
def _step_project_reenter(kt, g, p, t, frozen, restart, fallback):
    """Per window still moving: the step ``tau = <g, t>_contact / <t, K t>`` (``fallback``, the inverse
    self-compliance, if the curvature is not positive), ``p -= tau t`` projected on ``p >= 0``, and re-entry
    of the points off contact that interpenetrate with the pressure their overlap asks, ``-tau g``, which
    restarts the conjugacy."""
    m, n = p.shape
    for k in range(m):
        if frozen[k]:
            continue
        tkt = 0.0
        gt = 0.0
        for i in range(n):
            tkt += t[k, i] * kt[k, i]
            if p[k, i] > 0.0:
                gt += g[k, i] * t[k, i]
        tau = gt / tkt if tkt > 0.0 else fallback
        entered = False
        for i in range(n):
            if p[k, i] > 0.0:
                value = p[k, i] - tau * t[k, i]
                p[k, i] = value if value > 0.0 else 0.0
            elif g[k, i] < 0.0:
                p[k, i] = -tau * g[k, i]
                entered = True
        restart[k] = entered
