"""The linear solve on a fixed contact set for a non-symmetric periodic compliance: preconditioned GMRES.

A body whose compliance is a complex Fourier multiplier ``M(q) = K(q) + i W(q)`` (``K > 0`` even, ``W`` odd:
Coulomb friction's normal-tangential coupling, the loss part of a viscoelastic body in steady sliding) gives
on a contact set ``A``, under load control, the equality problem

    (M p)_A = h_A + d,   p = 0 off A,   sum p = P,

with the approach ``d`` its multiplier. On the fields centred on ``A`` the operator ``C M_AA C`` (``C`` the
centring) has a positive definite symmetric part, so GMRES converges on it without breakdown. It is
right-preconditioned by the exact Fourier inverse ``1 / M(q)`` restricted to ``A`` and centred, as the
symmetric constrained CG is by ``1 / K(q)`` (Vollebregt, J. Comput. Phys. 257, 2014): restriction leaves the
preconditioned operator close to the identity away from the set's edges, whatever ``|W| / K``, where the fixed
point on the skew part (:mod:`.coupled`) contracts only by ``max |W| / K``. Each iteration is two FFT pairs
(the operator and the preconditioner) and a Gram-Schmidt sweep over the Krylov basis.

:class:`ComplexCompliance` is the operator and the set solve that the semismooth Newton loop
(:func:`.semismooth.solve_semismooth`, its ``set_solver``) takes: the primal-dual active-set method around it
needs nothing else.
"""

from __future__ import annotations

import numpy as np

from ..core import fft
from . import krylov_sweeps as sweeps
from .recycle import RecycledSpace
from .state import dot

RESTART = 30
"""Krylov vectors kept before GMRES restarts (one field on the contact set each)."""

FORCING = 0.3
"""Each set's GMRES stops once it has cut its initial residual by this factor (or reached the absolute
tolerance the Newton loop asks): an inexact Newton step. The contact set settles in a few more updates than
with exact solves (12-16 instead of 7-9 on 512^2) but each costs 4-5 iterations instead of 9-15: 44 instead
of 79 in all on a confined layer (q0 h = 1, mu = 1, 50 % contact), 81 instead of 100 viscoelastic."""

START_TOL = 1e-3
"""A cold solve starts from the symmetric part's constrained CG stopped at this residual (10-32 iterations on
512^2 rough surfaces): its contact set is close to the answer's. The Newton loop's own cold start (the highest
5 % of the points) took 1.2-1.6x the GMRES iterations there; a start at 0.1 is as good on rough surfaces but,
on a smooth indenter in a wide window (the residual is relative to the rms height of the whole window), leaves
a contact set 40 times too wide, which the Newton loop shrinks by a few points a step."""

SETTLED = 0.01
"""A set that differs from the last one's by at most this fraction of its points is solved to the absolute
tolerance the Newton loop asks, without :data:`FORCING`: near the answer the set moves by a few points and
the loose solves only crawled (a factor 3-4 in the residual per set update; 6-8 updates for a warm start
already within 1e-4 of the answer)."""

STALL_SETS = 20
"""The Newton loop stops (not converged) when its best residual has not fallen by 10 % over this many set
updates: on a loss-dominated viscoelastic body (``max |Im M| / Re M`` = 16) the sets cycle and the residual
grows, where Douglas-Rachford (:mod:`.splitting`) converges."""


TRY_ITERATIONS = 400
"""A first try on a loss-dominated body (:data:`.splitting.SPLIT_ABOVE`), before Douglas-Rachford: the GMRES
iterations it may use in all (the symmetric start included). Where the loop converges there (E_inf/E0 = 1000,
zeta = V tau q0 = 1e-4 .. 1e-2, 64^2-512^2 at 10 % and 60 % contact) it took 60-245; where it fails the sets
grow and, unbounded, their GMRES stagnated (1982 and 7937 iterations on two sets of a 128^2 surface). Failed
tries stopped after 78-271 (by :data:`TRY_GROWTH`), or this budget, where Douglas-Rachford then takes 500-2800
iterations of similar cost."""

TRY_GROWTH = 10.0
"""The first try stops once its residual exceeds this factor times its first set's: there the loop diverges
(the contact set floods, the residual grows by 1.5-5 per update, from 2-7e-2 to 1e2-1e7 on cold 128^2-512^2
starts). Converging loops stayed below 2x their first residual; a factor of their best would not do: near the
answer a set change lifts the residual 100x above a best reached on the previous set."""

TRY_SET_ITERATIONS = 100
"""The first try's GMRES iterations on one contact set (converging tries used at most 30): a stagnating set
solve hands back to the Newton loop, whose monitor then sees the residual."""


class Stall:
    """The Newton loop's monitor (:func:`.semismooth.solve_semismooth`): counts the set updates (:attr:`sets`)
    and stops the loop on a stall (:data:`STALL_SETS`), a residual that is not finite, or one above ``growth``
    times the first set's (a first try: :data:`TRY_GROWTH`; :attr:`diverged` says so)."""

    def __init__(self, patience: int = STALL_SETS, growth: float = np.inf):
        self.patience, self.growth, self.sets, self.best, self.best_set = patience, growth, 0, np.inf, 0
        self.first, self.diverged = None, False

    def __call__(self, k: int, residual: float, snapshot) -> bool:
        self.sets = k
        if self.first is None:
            self.first = residual
        if residual < 0.9 * self.best:
            self.best, self.best_set = residual, k
        self.diverged = not np.isfinite(residual) or residual > self.growth * self.first
        return self.diverged or k - self.best_set >= self.patience


class ComplexCompliance:
    """A periodic compliance given by its complex multiplier, with the GMRES solve on a contact set.

    Parameters
    ----------
    multiplier : ndarray, complex
        ``M(q)`` [length/pressure] on the rfft layout of ``grid``, in the convention
        ``displacement = irfftn(M rfftn(p))`` (:func:`.splitting.fourier_multiplier`), ``Re M > 0`` at ``q != 0``.
    grid : Grid
    relative : float
        :data:`FORCING`.
    cap : int, optional
        GMRES iterations allowed on one set, whatever the Newton loop's budget (a first try:
        :data:`TRY_SET_ITERATIONS`); the set solve then returns its iterate, unconverged.
    space : contactlib.solvers.recycle.RecycledSpace, optional
        Krylov vectors carried from set solve to set solve, across the solves of a path of speeds.
    """

    def __init__(self, multiplier: np.ndarray, grid, relative: float = FORCING, cap: int | None = None,
                 space: RecycledSpace | None = None):
        self.grid, self.relative, self.cap = grid, relative, cap
        self.shape = tuple(grid.shape)
        count = float(np.prod(self.shape))
        # the plan's inverse transform is unnormalised: fold the 1/N into both multipliers (one division each:
        # masked assignments cost 2 ms a speed at 512^2)
        self.forward = multiplier / count
        self.inverse = np.divide(1.0 / count, multiplier, out=np.zeros_like(multiplier), where=multiplier != 0)
        self.inverse.flat[0] = 0.0  # load control fixes the mean: the preconditioner acts on centred fields
        self._plan = fft.get_fft(self.shape, slot="krylov")
        self._last = np.zeros(int(count), dtype=bool)  # the last call's contact set
        self._workspace = np.empty(0)  # GMRES's basis and directions, grown to the largest set so far
        self.space = space  # Krylov vectors carried across solves (:mod:`.recycle`), or None

    def _convolve(self, multiplier: np.ndarray, index: np.ndarray | None, values: np.ndarray) -> np.ndarray:
        """``M values`` of a field that is ``values`` on ``index`` (None: everywhere) and 0 elsewhere."""
        real = self._plan.real
        if index is None:
            real[...] = values.reshape(self.shape)
        else:
            sweeps.scatter(real.reshape(-1), index, values)
        spectrum = self._plan.forward()
        spectrum *= multiplier
        return self._plan.inverse()

    def _on_set(self, multiplier: np.ndarray, index: np.ndarray, values: np.ndarray) -> tuple[np.ndarray, float]:
        """``(M values)`` on ``index``, centred (a new array), and the mean removed."""
        out = np.empty(index.size)
        mean = sweeps.gather_centred(self._convolve(multiplier, index, values).reshape(-1), index, out)
        return out, mean

    def __call__(self, pressure: np.ndarray) -> np.ndarray:
        """Displacement [length] under ``pressure`` [pressure] (a new array)."""
        return self._convolve(self.forward, None, pressure).copy()

    def preconditioner_for(self, index: np.ndarray):
        """The right preconditioner of the set solve on ``index``: ``1 / M(q)`` restricted to the set and centred
        (a field on the set to a new one)."""

        def preconditioner(v):
            return self._on_set(self.inverse, index, v)[0]

        return preconditioner

    def solve_on_set(self, hp: np.ndarray, index: np.ndarray, start: np.ndarray, total: float, tol: float,
                     max_iter: int, image: np.ndarray | None = None) -> tuple[np.ndarray, float, int]:
        """``(p on the set, approach, iterations)``: GMRES for ``M_AA p = hp_A + approach``, ``sum p = total``,
        from ``start`` (moved to the load), until the rms of the centred gap on the set is at most ``tol``
        [length] (or :data:`FORCING` times its initial value while the set still moves, :data:`SETTLED`). ``hp``
        [length] is the flat height field measured down from its top (``<= 0``). ``image`` [length], when given:
        ``M start`` on the set, already known (a held set, whose ``start`` carries the load: the Newton loop's last
        convolution), which saves the first application (not counted)."""
        n_a = index.size
        start = np.where(np.isfinite(start), start, 0.0)
        p = start + (total - start.sum()) / n_a
        kept = int(np.count_nonzero(self._last[index]))
        moved = (n_a - kept) + (int(np.count_nonzero(self._last)) - kept)
        self._last.fill(False)
        self._last[index] = True
        relative = 0.0 if moved <= SETTLED * n_a else self.relative

        def operator(v):  # centred on the set; the mean is the approach's share
            return self._on_set(self.forward, index, v)

        preconditioner = self.preconditioner_for(index)
        heights = hp[index]
        b = heights - heights.mean()
        if self.cap is not None:
            max_iter = min(max_iter, self.cap)
        if image is not None:
            operator = _known_first(operator, image)
        if self.space is not None:
            operator, preconditioner = self.space.wrap(index, self._last.size, operator, preconditioner)
        if self._workspace.size < (2 * RESTART + 1) * n_a:
            self._workspace = np.empty((2 * RESTART + 1) * n_a)
        p, used, mean = gmres(operator, preconditioner, b, p, tol * np.sqrt(n_a), max_iter, relative=relative,
                              workspace=self._workspace)
        return p, float(mean - heights.mean()), used - (image is not None)


def _known_first(operator, image: np.ndarray):
    """``operator`` whose first call returns the centred ``image`` (the operator's value there, already known)
    and its mean instead of applying it: the set solve's start when the Newton loop has just computed it."""
    calls = []

    def first_known(v):
        if calls:
            return operator(v)
        calls.append(True)
        mean = float(image.mean())
        return image - mean, mean

    return first_known


def gmres(operator, preconditioner, b: np.ndarray, x: np.ndarray, tol: float, max_iter: int,
          restart: int = RESTART, relative: float = 0.0, workspace: np.ndarray | None = None
          ) -> tuple[np.ndarray, int, float]:
    """``(x, operator applications, side)``: right-preconditioned restarted GMRES (modified Gram-Schmidt, Givens
    rotations) for ``A x = b`` from ``x`` (updated in place), until ``|b - A x|_2 <= max(tol, relative |b - A x0|)``
    or ``max_iter`` applications. ``operator(v) -> (A v, s(v))`` with ``s`` a linear functional evaluated on the
    way (here the mean that centring removes): ``side`` is ``s(x)``, by linearity, without another application.
    ``preconditioner`` maps a 1-D field to a new one. The residual is GMRES's own estimate (exact in exact
    arithmetic); a restart starts from the true residual. The sweeps over the fields are compiled
    (:mod:`._krylov_sweeps`): on small sets numpy's per-call overhead cost as much as the transforms.
    From ``x = 0`` the first residual is ``b`` itself (no application). ``workspace``: a flat buffer of at least
    ``(2 restart + 1) b.size`` values for the Krylov basis and its preconditioned directions, kept by the caller
    across solves (fresh pages cost more to write than the sweeps that fill them)."""
    if x.any():
        r, side = operator(x)
        r = b - r
        it = 1
    else:  # from zero (a cohesive Newton step): the residual is b, no application
        r, side, it = b.copy(), 0.0, 0
    beta = np.sqrt(dot(r, r))
    tol = max(tol, relative * beta)
    column = np.empty(restart + 1)
    while beta > tol and it < max_iter:
        m = min(restart, max_iter - it)
        if workspace is None or workspace.size < (2 * m + 1) * r.size:
            workspace = np.empty((2 * m + 1) * r.size)
        basis = workspace[:(m + 1) * r.size].reshape(m + 1, r.size)
        directions = workspace[(m + 1) * r.size:(2 * m + 1) * r.size].reshape(m, r.size)
        sides = np.empty(m)
        H = np.zeros((m + 1, m))
        rotations = np.zeros((m, 2))
        g = np.zeros(m + 1)
        g[0] = beta
        sweeps.scale_into(basis[0], r, 1.0 / beta)
        k = 0
        for k in range(m):
            directions[k] = preconditioner(basis[k])
            w, sides[k] = operator(directions[k])
            it += 1
            norm = sweeps.orthogonalise(basis, k, w, column)
            H[:k + 1, k] = column[:k + 1]
            H[k + 1, k] = norm
            if norm > 0:
                sweeps.scale_into(basis[k + 1], w, 1.0 / norm)
            if sweeps.rotate(H, rotations, g, k) <= tol or H[k, k] == 0:
                break
        size = k + 1
        y = _upper_solve(H[:size, :size], g[:size])
        sweeps.combine(x, directions, y, size)
        side += float(y @ sides[:size])
        beta = abs(g[size])
        if H[k, k] == 0:  # the Krylov space is exhausted (happy breakdown or a singular system)
            break
        if beta > tol and it < max_iter:  # restart from the true residual
            r, side = operator(x)
            r = b - r
            it += 1
            beta = np.sqrt(dot(r, r))
    return x, it, side


def _upper_solve(R: np.ndarray, g: np.ndarray) -> np.ndarray:
    """Back substitution with an upper triangular ``R`` (small), skipping zero pivots."""
    y = np.zeros_like(g)
    for i in range(len(g) - 1, -1, -1):
        if R[i, i] != 0:
            y[i] = (g[i] - R[i, i + 1:] @ y[i + 1:]) / R[i, i]
    return y
