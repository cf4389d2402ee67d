"""A coarse space of long waves for contact on plate-like bodies: a two-level preconditioner.

A thin remote-pressure layer (free back face) is a plate at long waves: its compliance grows as
``1 / (q^4 h^3)`` instead of the half-space's ``2 / (E* q)``, 6000 times the half-space's at ``q h = 0.1``.
On a contact set ``A`` the operator ``K_AA`` then has a few huge eigenvalues, one per soft long wave,
which a Fourier preconditioner restricted to ``A`` cannot remove: restriction mixes the waves, and the
preconditioned operator keeps outliers of order ``(K(q) / K_hs(q)) f (1 - f)`` at contact fraction ``f``.

The remedy here is a balancing (BNN) two-level preconditioner (Mandel 1993; Tang, Nabben, Vuik & Erlangga,
J. Sci. Comput. 39, 2009) whose coarse space ``Z`` is the soft Fourier modes restricted to ``A`` and
centred on it (the load constraint): with ``E = Z^T K Z`` solved exactly,

    P r = (I - Z E^-1 Z^T K) M (I - K Z E^-1 Z^T) r + Z E^-1 Z^T r,

where ``M`` is the exact Fourier inverse of ``K`` restricted to ``A``. It is symmetric positive definite
on the centred fields of ``A``, and CG with it sees the soft waves solved exactly and the rest
preconditioned as on a half-space. Building it costs one FFT pair per coarse field (``K Z``) and
``m^2 |A|`` for ``E``, so it is rebuilt only when the contact set changes: the semismooth Newton solver
(:mod:`.semismooth`) holds the set fixed through each linear solve, and :func:`two_level` keeps the last few:
a frictional plate's outer loop starts each inner solve on the set the last one ended on (on a 128^2 plate at
q0 h = 0.1, mu = 1, 2 % contact: 18 builds instead of 34, 9.7 s instead of 12.5 s; frictionless 6.5 s, 12 builds).
"""

from __future__ import annotations

import numpy as np
import pyfftw
from scipy.linalg import cho_factor, cho_solve, lu_factor, lu_solve

from ...core import fft
from ..krylov import ComplexCompliance

COARSE_SOFTENING = 4.0
"""A Fourier mode joins the coarse space where the body is more than this many times softer than the
half-space of the same ``E*``. On a 16384-point profile at q0 h = 0.1 (36, 24 and 18 coarse fields at
2, 4 and 8) the CG iterations of a whole solve were 270-290, 340-420 and 450-540."""

MAX_COARSE = 256
"""At most this many coarse fields (the softest modes first): the build costs ``m`` FFT pairs and
``m^2 |A|`` operations per contact set (2D, q0 h = 0.1 at 4x: about 520 fields)."""

PLATE_SET_FLOOR = 1e-5
"""The loosest tolerance (relative, as ``tol``) that the semismooth loop's changed-set solves may stop at on a plate
(:func:`.semismooth.solve_semismooth`'s ``set_floor``). At ``tol`` 1e-3-1e-4 the floor had been ``tol / 2`` (GMRES)
or ``tol / 16`` (CG): loose solves left 0.2 % of the load as negative pressure, which on a plate displaces the
surface by several rms heights, so the sets cycled (a 4096-point profile at q0 h = 0.1, mu = 0.5: 20 set updates,
then the fixed point, 298-386 iterations; frictionless 139-274 CG iterations against 124-174 at tol 1e-8). At 1e-5
every scene measured converged in 4-9 sets with no more iterations than at tol 1e-8 (1e-4 did not; 1e-6 cost more)."""

_CHUNK = 32  # coarse fields transformed at once: bounds the memory to 32 grid-sized fields

RECENT_BUILDS = 4
"""Preconditioners kept for reuse (:func:`two_level`): a frictional plate's outer loop starts each inner solve
on the contact set the last one ended on."""



def soft_modes(grid, transfer: np.ndarray, E_star: float, *, softening: float = COARSE_SOFTENING,
               max_fields: int = MAX_COARSE) -> np.ndarray:
    """Integer wavevectors ``(m, dim)`` and kinds (0 cosine, 1 sine) of the real coarse fields: the modes
    ``q != 0`` where ``transfer`` [length/pressure] exceeds ``softening`` times ``2 / (E* |q|)``."""
    q = grid.wavenumber()
    ratio = np.zeros_like(q)
    nonzero = q > 0
    ratio[nonzero] = transfer[nonzero] * E_star * q[nonzero] / 2
    fields = []
    for index in np.argwhere(ratio > softening):
        k = [int(index[0])] if grid.dim == 1 else [int(index[0]) - (grid.shape[0] if index[0] > grid.shape[0] // 2
                                                                       else 0), int(index[1])]
        if grid.dim == 2 and k[1] == 0 and k[0] < 0:
            continue  # the mirror image of a mode kept
        nyquist = all(2 * abs(c) in (0, n) for c, n in zip(k, grid.shape))  # sin vanishes on the grid
        for kind in (0,) if nyquist else (0, 1):
            fields.append((ratio[tuple(index)], k, kind))
    fields.sort(key=lambda f: -f[0])
    fields = fields[:max_fields]
    if not fields:
        return np.zeros((0, grid.dim + 1), dtype=int)
    return np.array([k + [kind] for _, k, kind in fields], dtype=int)


def two_level(operator, modes: np.ndarray, active: np.ndarray) -> "TwoLevel":
    """:class:`TwoLevel` of ``operator`` on ``active``, reused when one of the last :data:`RECENT_BUILDS` was
    built for the same operator object, modes and set (a build costs one FFT pair per coarse field)."""
    # kept on the operator, so the builds (m x |A| fields each) go with the scene, not with the process
    recent = operator.__dict__.setdefault("_two_level_builds", [])  # (modes, active, TwoLevel), latest last
    for k, entry in enumerate(recent):
        if np.array_equal(entry[0], modes) and np.array_equal(entry[1], active):
            recent.append(recent.pop(k))
            return entry[2]
    built = TwoLevel(operator, modes, active)
    recent.append((modes, active.copy(), built))
    del recent[:-RECENT_BUILDS]
    return built


class TwoLevel:
    """The balancing preconditioner of a compliance ``operator`` on the contact set ``active`` (flat
    indices), for fields that are centred on it (load control).

    ``apply(r)`` takes and returns values on ``active`` only.
    """

    def __init__(self, operator, modes: np.ndarray, active: np.ndarray):
        shape = operator.grid.shape
        self.operator, self.active, self.shape = operator, active, shape
        Z = _coarse_fields(modes, active, shape)
        multiplier = operator.multiplier * float(np.prod(operator.work_shape))  # the unnormalised transfer
        KZ, = _responses(Z, active, shape, (multiplier,))
        KZ -= KZ.mean(axis=1, keepdims=True)
        E = Z @ KZ.T
        E = (E + E.T) / 2
        # a sparse contact set cannot carry every wave (fewer points than fields): E is then singular
        # along combinations that vanish on the set, which the ridge leaves harmless (Z^T c = 0 there)
        if E.size and not np.trace(E) > 0:  # a one-point set: every centred field vanishes on it, no coarse space
            Z, KZ, E = Z[:0], KZ[:0], E[:0, :0]
        if E.size:
            E[np.diag_indices_from(E)] += 1e-12 * np.trace(E) / len(E)
            self.factor = cho_factor(E, check_finite=False)
        self.Z, self.KZ = Z, KZ

    def _coarse(self, c: np.ndarray) -> np.ndarray:
        return cho_solve(self.factor, c, check_finite=False)

    def _fine(self, r: np.ndarray) -> np.ndarray:
        """``M r``: the Fourier inverse of ``K`` restricted to the set, centred."""
        op = self.operator
        field = op.load()
        field.fill(0.0)
        field.reshape(-1)[self.active] = r
        z = op.convolve(inverse=True).reshape(-1)[self.active]
        return z - z.mean()

    def apply(self, r: np.ndarray) -> np.ndarray:
        if not self.Z.shape[0]:
            return self._fine(r)
        c = self._coarse(self.Z @ r)
        y = self._fine(r - self.KZ.T @ c)
        return y - self.Z.T @ self._coarse(self.KZ @ y) + self.Z.T @ c


_batches: dict = {}  # (shape, threads) -> _Batch; one per grid shape, each _CHUNK grid-sized fields (x 3 buffers)


class _Batch:
    """FFTW transforms of :data:`_CHUNK` real fields at once (the coarse fields' responses): at 128^2, 8 times
    faster than numpy's, 1.5 times at 512^2. ``forward`` maps ``real`` to ``spectrum``; ``inverse`` maps ``work``
    to ``real``, unnormalised (destroys ``work``)."""

    def __init__(self, shape):
        spectral = tuple(shape[:-1]) + (shape[-1] // 2 + 1,)
        self.real = pyfftw.empty_aligned((_CHUNK,) + tuple(shape), dtype="float64")
        self.spectrum = pyfftw.empty_aligned((_CHUNK,) + spectral, dtype="complex128")
        self.work = pyfftw.empty_aligned((_CHUNK,) + spectral, dtype="complex128")
        axes, threads = tuple(range(1, len(shape) + 1)), fft.threads()
        self.forward = pyfftw.FFTW(self.real, self.spectrum, axes=axes, flags=("FFTW_ESTIMATE",),
                                   threads=threads).execute
        self.inverse = pyfftw.FFTW(self.work, self.real, axes=axes, direction="FFTW_BACKWARD",
                                   flags=("FFTW_ESTIMATE", "FFTW_DESTROY_INPUT"), threads=threads).execute

    @classmethod
    def of(cls, shape) -> "_Batch":
        key = (tuple(shape), fft.threads())
        if key not in _batches:
            _batches.clear()  # one shape at a time: a 512^2 batch holds 200 MB
            _batches[key] = cls(shape)
        return _batches[key]


def _responses(Z: np.ndarray, active: np.ndarray, shape, multipliers) -> list[np.ndarray]:
    """``[(irfftn(m rfftn(Z)))_A for m in multipliers]``: each coarse field's response on ``active`` under each
    multiplier [on the rfft layout, normalised: ``displacement = irfftn(m rfftn(p))``]."""
    batch = _Batch.of(shape)
    scaled = [m / float(np.prod(shape)) for m in multipliers]  # FFTW's inverse is unnormalised
    out = [np.empty_like(Z) for _ in multipliers]
    flat = batch.real.reshape(_CHUNK, -1)
    for start in range(0, Z.shape[0], _CHUNK):
        rows = min(_CHUNK, Z.shape[0] - start)
        flat.fill(0.0)
        flat[:rows, active] = Z[start:start + rows]
        batch.forward()
        for response, m in zip(out, scaled):
            np.multiply(batch.spectrum, m, out=batch.work)
            batch.inverse()
            response[start:start + rows] = flat[:rows, active]
    return out


def _coarse_fields(modes: np.ndarray, active: np.ndarray, shape) -> np.ndarray:
    """The coarse fields ``(m, |A|)``: the modes' cosines and sines on ``active`` (flat indices), centred on it."""
    if not modes.shape[0]:
        return np.zeros((0, active.size))
    coords = np.unravel_index(active, shape)
    phase = 2 * np.pi * sum(np.outer(modes[:, d], coords[d] / shape[d]) for d in range(len(shape)))
    Z = np.where(modes[:, -1:] == 0, np.cos(phase), np.sin(phase))
    return Z - Z.mean(axis=1, keepdims=True)


class ComplexTwoLevel:
    """The balancing preconditioner of :class:`TwoLevel` for a non-symmetric compliance ``A = K + W`` given by its
    complex multiplier ``M(q)`` (:mod:`.krylov`), on the contact set ``active``, for fields centred on it:

        P r = (I - Z E^-1 Z^T A) F (I - A Z E^-1 Z^T) r + Z E^-1 Z^T r,   E = Z^T A Z,

    with ``F`` the Fourier inverse ``1 / M(q)`` restricted to the set (``fine``). ``A P`` is the identity on the
    span of ``A Z`` and the deflated ``(I - A Q) A F (I - A Q)`` on a complement: the soft long waves, where
    ``F`` fails on a plate, are solved exactly. ``E``'s symmetric part is ``Z^T K Z`` (positive semi-definite),
    so its LU needs no pivoting beyond LAPACK's. Building costs one forward and two inverse FFTs per coarse
    field (``A Z`` and ``A^T Z``, the multipliers ``M`` and ``conj M``).

    Parameters
    ----------
    multiplier : ndarray, complex
        ``M(q)`` [length/pressure] on the rfft layout, ``displacement = irfftn(M rfftn(p))``.
    modes : ndarray
        :func:`soft_modes` of the symmetric part.
    active : ndarray
        Flat indices of the contact set.
    fine : callable
        ``F``: a centred field on the set to a new one.
    """

    def __init__(self, multiplier: np.ndarray, modes: np.ndarray, active: np.ndarray, shape, fine):
        self.active, self.fine = active, fine
        Z = _coarse_fields(modes, active, shape)
        AZ, ATZ = _responses(Z, active, shape, (multiplier, np.conj(multiplier)))  # A^T: conj M
        AZ -= AZ.mean(axis=1, keepdims=True)
        ATZ -= ATZ.mean(axis=1, keepdims=True)
        self.Z, self.AZ, self.ATZ = Z, AZ, ATZ
        if Z.shape[0]:
            E = Z @ AZ.T
            # a sparse set cannot carry every wave: the ridge keeps E regular along combinations vanishing on it
            E[np.diag_indices_from(E)] += 1e-12 * np.trace(E) / len(E)
            self.factor = lu_factor(E, check_finite=False)

    def apply(self, r: np.ndarray) -> np.ndarray:
        if not self.Z.shape[0]:
            return self.fine(r)
        c = lu_solve(self.factor, self.Z @ r, check_finite=False)
        y = self.fine(r - self.AZ.T @ c)
        # Z^T A y = (A^T Z)^T y: the transpose's fields, E^T's solve is not needed (E^-1 acts on Z^T A y)
        return y - self.Z.T @ lu_solve(self.factor, self.ATZ @ y, check_finite=False) + self.Z.T @ c


class PlateCompliance(ComplexCompliance):
    """:class:`.krylov.ComplexCompliance` of a plate-like body (a thin remote-pressure layer with friction): its
    set solves' GMRES is right-preconditioned by :class:`ComplexTwoLevel`, the soft long waves ``modes``
    (:func:`soft_modes` of the symmetric part) solved exactly, so the semismooth Newton loop runs on the complex
    multiplier directly, with no fixed point on the skew part around it (:mod:`.coupled`).

    Parameters
    ----------
    multiplier, grid
        As :class:`.krylov.ComplexCompliance`.
    modes : ndarray
        The coarse modes.
    relative : float
        Each set's GMRES stops at this fraction of its initial residual (or the Newton loop's tolerance): 0,
        every set solved to the tolerance. With loose solves (:data:`.krylov.FORCING` 0.3, and still at 0.05)
        the set updates diverged on a 2^14-point plate (residual 0.06, 0.8, 17, 306, ...): one GMRES step cuts
        the residual by solving the soft waves, which dominate it, and leaves the short waves of the pressure,
        whose signs pick the next set, unsolved.
    space : contactlib.solvers.recycle.RecycledSpace, optional
        As :class:`.krylov.ComplexCompliance`.
    """

    def __init__(self, multiplier: np.ndarray, grid, modes: np.ndarray, relative: float = 0.0, space=None):
        super().__init__(multiplier, grid, relative=relative, space=space)
        self.multiplier, self.modes = multiplier, modes
        self._built = None  # the last set's preconditioner: a held set is solved again, tighter

    def preconditioner_for(self, index: np.ndarray):
        if self._built is None or not np.array_equal(self._built.active, index):
            self._built = ComplexTwoLevel(self.multiplier, self.modes, index.copy(), self.shape,
                                          super().preconditioner_for(index))
        return self._built.apply
