"""Anderson mixing of a fixed point ``x = T(x)`` of fields: the one mixer of the iterative solvers.

Type II (Walker & Ni, SIAM J. Numer. Anal. 49, 1715-1735, 2011): with the residual ``f = T(x) - x`` and the
differences of the last ``memory`` images ``dT`` and residuals ``dF``, the weights ``gamma`` minimise
``|f_k - dF gamma|`` and the next iterate is

    x_{k+1} = x_k + beta f_k - sum_j gamma_j (dx_j + beta df_j)
            = T_k + (beta - 1) f_k - sum_j gamma_j (dT_j + (beta - 1) df_j),

``beta = 1`` giving ``T_k - dT gamma`` (GMRES on a linear map; ``beta`` relaxes the step). ``gamma`` solves the
normal equations with a relative ridge, ``(G + ridge tr(G) I) gamma = dF^T f_k``, ``G = dF^T dF`` updated by one
row a call (a least-squares solve of the tall ``dF`` costs more than an inner contact solve on 512^2). A zero or
non-finite ``tr(G)`` (an iterate that stands still, a NaN) gives the plain step and a fresh memory.

Its users: the fixed point on the skew part (:mod:`.coupled`: the ``W`` image of the pressure carried along, so
mixing needs no application of ``W``), Douglas-Rachford splitting (:mod:`.splitting`: with the safeguard of
:meth:`Anderson.retreat`) and the frozen-traction cohesive rounds (:mod:`.cohesive`: clipped to the law's
tractions, relaxed, and fused). The fused mixer keeps its history in ring buffers swept by numba (one sweep
records a round, one mixes it: numpy's passes and BLAS dot products cost as much a round as an FFT pair at
256^2); the unfused one keeps the image differences and takes its inner products with numpy's own loop
(:func:`.state.dot`). The two orders of summation, and the SVD (fused) or LU solve of ``gamma``, give the same
iterates to round-off; each solver keeps the one it was tuned and validated with.
"""

from __future__ import annotations

import numpy as np

from ..core._numba import jit as _jit
from .state import dot


def mixing_coefficients(gram: np.ndarray, rhs: np.ndarray, ridge: float, *,
                        least_squares: bool = False) -> np.ndarray | None:
    """Anderson mixing's coefficients: ``(G + ridge tr(G) I)^-1 rhs`` for the Gram matrix ``G`` of the residual
    differences (the relative ridge keeps the normal equations solvable when differences become parallel), by LU or
    (``least_squares``) by SVD; None where the differences are degenerate (a zero or non-finite trace: the iterate
    stands still, or a singular system), where the mixer takes the plain step and starts its memory again."""
    scale = float(np.trace(gram))
    if not (np.isfinite(scale) and scale > 0):
        return None
    regularised = gram + ridge * scale * np.eye(len(rhs))
    try:
        if least_squares:
            return np.linalg.lstsq(regularised, rhs, rcond=None)[0]
        return np.linalg.solve(regularised, rhs)
    except np.linalg.LinAlgError:
        return None


class Anderson:
    """Anderson type-II mixing of a fixed point of fields (module docstring).

    Parameters
    ----------
    memory : int
        Differences kept (0: the plain, relaxed and clipped, step).
    beta : float
        Mixing parameter: 1 the unit step ``T_k - dT gamma``.
    bounds : (float, float), optional
        ``(lower, upper)``: every iterate is clipped into them (a mixed iterate can leave a set that ``T`` keeps).
    ridge : float
        Relative ridge of the normal equations.
    fused : bool
        Numba sweeps over ring buffers, for a mixer called once per round of a solver on a large grid; it needs the
        iterate ``x`` at each call and carries no other fields.

    Notes
    -----
    A call (:meth:`next`, or ``mixer(x, image)``) records the differences from the last call and returns the next
    iterate. Fields may have any shape; the ones carried along (:meth:`next`'s ``carried``: images of the ``T``'s
    under a linear map, with ``beta = 1`` and no bounds) are mixed with the same weights and come back after it.
    """

    def __init__(self, memory: int, *, beta: float = 1.0, bounds: tuple[float, float] | None = None,
                 ridge: float = 1e-10, fused: bool = False):
        if int(memory) != memory or memory < 0:
            raise ValueError(f"memory must be a non-negative integer, got {memory!r}")
        if not (np.isfinite(beta) and beta > 0):
            raise ValueError(f"beta must be positive and finite, got {beta!r}")
        if not (np.isfinite(ridge) and ridge >= 0):
            raise ValueError(f"ridge must be non-negative and finite, got {ridge!r}")
        if bounds is not None and not float(bounds[0]) <= float(bounds[1]):
            raise ValueError(f"bounds must be (lower, upper) with lower <= upper, got {bounds!r}")
        self.memory, self.beta, self.ridge, self.fused = int(memory), float(beta), float(ridge), bool(fused)
        self.bounds = None if bounds is None else (float(bounds[0]), float(bounds[1]))
        self.rings = None  # fused: (dx, df, last_x, last_f, gram, rhs), allocated at the first call
        self.reset()

    def reset(self):
        """Forget every difference, the last iterate and the safeguard's state."""
        self.last = None  # unfused: (T, f, *carried) of the last call
        self.diffs: list[tuple[np.ndarray, ...]] = []  # unfused: (dT, dF, *d carried), oldest first
        self.gram = np.zeros((0, 0))
        self.rounds = 0  # fused: calls recorded since the reset (the ring's row is the last one mod memory)
        self._plain, self._last_norm = None, np.inf

    @property
    def active(self) -> bool:
        """Whether the next call can mix (differences are stored)."""
        return bool(self.diffs) if not self.fused else min(self.rounds, self.memory) > 0

    def retreat(self, f: np.ndarray) -> np.ndarray | None:
        """The safeguard of Zhang, O'Donoghue & Boyd (SIAM J. Optim. 30, 2020), called with the residual ``f`` of the
        iterate the last call returned: where that was a mixed iterate and ``|f|`` rose above the residual before
        it, the plain step of the last call, to take instead (the memory is cleared); else None (``|f|`` noted)."""
        if self.fused:
            raise ValueError("the safeguard is the unfused mixer's (the fused one keeps no plain step)")
        norm = float(np.sqrt(dot(f, f)))
        if self.active and norm > self._last_norm and self._plain is not None:
            plain = self._plain
            self.reset()
            return plain
        self._last_norm = norm
        return None

    def __call__(self, x: np.ndarray, image: np.ndarray) -> np.ndarray:
        """The next iterate from ``x`` and ``T(x)`` (``image``)."""
        return self.next(image, x=x)

    def next(self, image: np.ndarray, f: np.ndarray | None = None, *carried: np.ndarray,
             x: np.ndarray | None = None):
        """The next iterate from the image ``T(x)`` and the residual ``f = T(x) - x`` (or the iterate ``x``, from which
        ``f`` is formed; the fused mixer needs ``x``).

        Returns
        -------
        ndarray, or tuple of ndarray
            The next iterate; with ``carried`` fields (images under a linear map ``L`` of the ``T``'s), the tuple of
            it and of ``L`` of it.
        """
        if self.fused:
            if carried or x is None:
                raise ValueError("the fused mixer needs the iterate x and carries no other fields")
            return self._fused_next(x, image)
        if carried and (self.beta != 1.0 or self.bounds is not None):  # L of a relaxed or clipped step is not known
            raise ValueError("carried fields need beta = 1 and no bounds")
        if f is None:
            if x is None:
                raise ValueError("give the residual f or the iterate x")
            f = image - x
        if self.last is not None and self.memory > 0:
            last_image, last_f, *last_carried = self.last
            df = f - last_f
            if len(self.diffs) == self.memory:
                self.diffs.pop(0)
                self.gram = self.gram[1:, 1:]
            row = np.array([dot(d[1], df) for d in self.diffs] + [dot(df, df)])
            m = len(self.diffs) + 1
            gram = np.empty((m, m))
            gram[:-1, :-1], gram[-1, :], gram[:, -1] = self.gram, row, row
            self.gram = gram
            self.diffs.append((image - last_image, df, *(c - c0 for c, c0 in zip(carried, last_carried))))
        self.last = (image, f, *carried)
        relax = self.beta - 1.0
        step = image if relax == 0.0 else image + relax * f  # the plain step (the caller's image where beta = 1)
        self._plain = step if self.bounds is None else np.clip(step, *self.bounds)
        outs = [step.copy(), *(c.copy() for c in carried)]
        if self.diffs:
            gamma = mixing_coefficients(self.gram, np.array([dot(d[1], f) for d in self.diffs]), self.ridge)
            if gamma is None:  # degenerate differences: the plain step, and a fresh memory from this call
                self.diffs, self.gram = [], np.zeros((0, 0))
            else:
                for g, (d_image, d_f, *d_carried) in zip(gamma, self.diffs):
                    outs[0] -= g * (d_image if relax == 0.0 else d_image + relax * d_f)
                    for out, d in zip(outs[1:], d_carried):
                        out -= g * d
        if self.bounds is not None:
            np.clip(outs[0], *self.bounds, out=outs[0])
        return outs[0] if not carried else tuple(outs)

    def _fused_next(self, x: np.ndarray, image: np.ndarray) -> np.ndarray:
        shape = x.shape
        x, image = np.ascontiguousarray(x).ravel(), np.ascontiguousarray(image).ravel()
        depth = max(self.memory, 1)
        if self.rings is None or self.rings[2].size != x.size:
            self.rings = (np.zeros((depth, x.size)), np.zeros((depth, x.size)), np.zeros(x.size), np.zeros(x.size),
                          np.zeros((depth, depth)), np.zeros(depth))
        dx, df, last_x, last_f, gram, rhs = self.rings
        m = min(self.rounds, self.memory)
        row = (self.rounds - 1) % depth if m else -1
        anderson_record(x, image, last_x, last_f, dx, df, row, m, gram, rhs)
        self.rounds += 1
        lower, upper = self.bounds if self.bounds is not None else (-np.inf, np.inf)
        gamma = None if m == 0 else mixing_coefficients(gram[:m, :m], rhs[:m], self.ridge, least_squares=True)
        if gamma is None:
            if m:  # degenerate differences: a fresh memory from this call
                self.rounds = 1
            return np.clip(x + self.beta * (image - x), lower, upper).reshape(shape)
        out = np.empty_like(x)
        anderson_mix(x, image, dx, df, gamma, m, self.beta, lower, upper, out)
        return out.reshape(shape)


@_jit
def anderson_record(x, image, last_x, last_f, dx, df, row, m, gram, rhs):
    """With ``f = image - x``: the differences ``dx[row] = x - last_x`` and ``df[row] = f - last_f`` (if
    ``row >= 0``), then ``last_x = x``, ``last_f = f``; the Gram row ``gram[row, k] = df[row] . df[k]``
    and ``rhs[k] = df[k] . f`` for ``k < m``. One sweep writes, then one contiguous pass per stored row."""
    for i in range(x.size):
        f = image[i] - x[i]
        if row >= 0:
            dx[row, i] = x[i] - last_x[i]
            df[row, i] = f - last_f[i]
        last_x[i] = x[i]
        last_f[i] = f
    for k in range(m):
        dk = df[k]
        s_f = 0.0
        s_row = 0.0
        for i in range(x.size):
            s_f += dk[i] * last_f[i]
            s_row += dk[i] * df[row, i]
        rhs[k] = s_f
        if row >= 0:
            gram[row, k] = s_row
            gram[k, row] = s_row


@_jit
def anderson_mix(x, image, dx, df, gamma, m, beta, lower, upper, out):
    """``out = x + beta f - sum_k gamma_k (dx[k] + beta df[k])``, ``f = image - x`` (``beta = 1``: ``image -
    sum_k gamma_k (dx[k] + df[k])``), clipped to ``[lower, upper]``: one contiguous pass per stored row."""
    for i in range(x.size):
        out[i] = x[i] + beta * (image[i] - x[i])
    for k in range(m):
        gk = gamma[k]
        for i in range(x.size):
            out[i] -= gk * (dx[k, i] + beta * df[k, i])
    for i in range(x.size):
        out[i] = min(max(out[i], lower), upper)
