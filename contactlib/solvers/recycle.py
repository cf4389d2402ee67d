"""Krylov vectors carried from one GMRES set solve to the next: a low-rank correction of the preconditioner.

Each GMRES iteration of :meth:`.krylov.ComplexCompliance.solve_on_set` applies the preconditioned operator
``B = A P`` (``A`` the compliance on the contact set, centred; ``P`` the restricted ``1 / M(q)``) to a vector:
it gives a pair ``(x, z = A P x)`` for free. Kept pairs, orthonormalised so that ``Z^T Z = I`` (``X``
transformed alike), make the map

    Q u = u + (X - Z) Z^T u,   with   A P Q z = z   for ``z`` in the span of ``Z``,

and the next solve is right-preconditioned by ``P Q`` instead of ``P``: the directions its predecessors
found slow are solved in one step (a spectral preconditioner update in the manner of Carpentieri, Duff &
Giraud, Numer. Linear Algebra Appl. 10, 2003, built from the Arnoldi products already paid for rather than
from eigenvectors). It costs no operator application; the pairs of an earlier speed, or of a slightly
different contact set, are stale, so ``A P Q`` is only close to the identity there, but any fixed ``Q`` leaves
GMRES exact (the answer and its stopping test do not change, only the iterations).

Measured over 30 speeds zeta = V tau q0 1e-3..1e3 (E_inf/E0 = 10, 10 % contact, tol 1e-8, from
:func:`contactlib.predict_pressure`): 816 -> 738 GMRES iterations in all on 256^2, 1118 -> 1014 on 512^2; 13-14
-> 3 iterations per speed at the high-speed end, where the set and the operator settle, nothing in the
transition, where the set moves at every update. The time is not lower at 512^2 (CPU 10.2 s both ways in one
run, load 4.5): building ``Z`` (``SIZE^2 / 2`` inner products on the set at each solve) and applying ``Q``
(``2 SIZE`` per iteration) cost what the saved iterations did, so :func:`contactlib.solve_speeds` carries the
vectors only on request (a :class:`RecycledSpace` held by the path's prepared problem, passed to each
:class:`.krylov.ComplexCompliance` it builds). Where the set moves by more than :data:`MOVED` of its points the
pairs mislead (503 iterations on one speed of the transition when kept): they are dropped there.
"""

from __future__ import annotations

import numpy as np

from .state import dot

SIZE = 30
"""Pairs kept (the latest). On the 256^2 sweep walked from the last answer: 10 gave 853 iterations, 30 gave 801, 60
gave 802 (938 without); on 512^2 from the prediction, 10 and 16 gave 1062 and 1041 (1014 at 30, 1118 without), at
the same CPU time within the noise."""

MOVED = 0.01
"""A set that differs from the kept pairs' set by more than this fraction of its points drops them (256^2 sweep
from the last answer: 0.002 gave 815 iterations, 0.01 801, 0.05 831; keeping them at any move, 1449)."""

class RecycledSpace:
    """The kept pairs ``(x, z)`` (on the contact set :attr:`index`, the latest last) and the map ``Q`` they give.

    Parameters
    ----------
    size : int
        :data:`SIZE`.
    moved : float
        :data:`MOVED`.
    """

    def __init__(self, size: int = SIZE, moved: float = MOVED):
        if size < 1:
            raise ValueError(f"size must be >= 1, got {size}")
        self.size, self.moved = int(size), float(moved)
        self.index = None
        self.pairs: list[tuple[np.ndarray, np.ndarray]] = []
        self.uses = 0  # set solves that ran with a correction (for tests and benchmarks)

    def _follow(self, index: np.ndarray, points: int) -> None:
        """Move the pairs onto the set ``index`` (zero on new points), or drop them where it moved too much."""
        if self.index is not None and not (self.index.size == index.size and np.array_equal(self.index, index)):
            where = np.full(points, -1)
            where[self.index] = np.arange(self.index.size)
            where = where[index]
            inside = where >= 0
            kept = int(np.count_nonzero(inside))
            if (index.size - kept) + (self.index.size - kept) > self.moved * index.size:
                self.pairs = []
            else:
                source = where[inside]

                def move(a):
                    b = np.zeros(index.size)
                    b[inside] = a[source]
                    return b

                self.pairs = [(move(x), move(z)) for x, z in self.pairs]
        self.index = index

    def _basis(self) -> tuple[np.ndarray, np.ndarray]:
        """``(X, Z)`` as rows, ``Z`` orthonormal (modified Gram-Schmidt, the latest pair first; the same
        combinations on ``X``), a pair already in the span left out."""
        X, Z = [], []
        for x, z in reversed(self.pairs):
            x, z = x.copy(), z.copy()
            norm0 = np.sqrt(dot(z, z))
            for xk, zk in zip(X, Z):
                c = dot(z, zk)
                z -= c * zk
                x -= c * xk
            norm = np.sqrt(dot(z, z))
            if norm > 1e-6 * norm0:
                X.append(x / norm)
                Z.append(z / norm)
        return np.array(X), np.array(Z)

    def wrap(self, index: np.ndarray, points: int, operator, preconditioner):
        """``(operator, preconditioner)`` for a GMRES solve on ``index`` (of ``points`` in the grid): the
        preconditioner ``P Q`` (``Q`` from the kept pairs, fixed during the solve), both recording this solve's
        pairs for the next one."""
        self._follow(index, points)
        pending: list[np.ndarray] = []
        if self.pairs:
            X, Z = self._basis()
            D = X - Z
            self.uses += 1

            def corrected(v):
                x = v + np.einsum("i,ij->j", np.einsum("ij,j->i", Z, v), D)
                pending.append(x)
                return preconditioner(x)
        else:
            def corrected(v):
                pending.append(v.copy())
                return preconditioner(v)

        def recorded(v):
            w, side = operator(v)
            if pending:  # the image of the direction just preconditioned (not a restart's residual)
                self.pairs.append((pending.pop(), w.copy()))
                del self.pairs[:-self.size]
            return w, side

        return recorded, corrected
