"""The elastic half-space's compliance on slabs: the distributed :class:`contactlib.model.operators.Compliance`.

Kernels are pure functions of the wavevectors, so each rank evaluates them on its own spectral columns:
periodic, the continuous multiplier ``2 / (E* |q|)`` (:func:`contactlib.kernels.elastic.halfspace_spectral_multiplier`);
non-periodic, the transform of the collocated point-load influence coefficients on the doubled box
(:func:`contactlib.kernels.elastic.halfspace_point_influence`), each rank computing its rows of them. The
multipliers carry the ``1 / N`` of the unnormalised inverse transform, as the serial ones do, and the loop's
transforms (:class:`DistributedTransforms`) do what the serial :class:`contactlib.model.operators.IterationTransforms`
do, with every sum over the spectrum reduced over the ranks.
"""

from __future__ import annotations

import numba
import numpy as np

from ..kernels.elastic import love_rectangle
from .fft import SlabFFT


@numba.njit(cache=True, nogil=True, boundscheck=False)
def _weighted_power(spectrum, multiplier, weights, scale_after):
    """``sum w_j |S_ij|^2 M_ij`` over a spectral slab; with ``scale_after``, then ``S *= M`` in place."""
    total = 0.0
    for i in range(spectrum.shape[0]):
        for j in range(spectrum.shape[1]):
            s = spectrum[i, j]
            m = multiplier[i, j]
            total += weights[0, j] * (s.real * s.real + s.imag * s.imag) * m
            if scale_after:
                spectrum[i, j] = s * m
    return total


@numba.njit(cache=True, nogil=True, boundscheck=False)
def _scale(spectrum, multiplier):
    """``S *= M`` in place."""
    for i in range(spectrum.shape[0]):
        for j in range(spectrum.shape[1]):
            spectrum[i, j] = spectrum[i, j] * multiplier[i, j]


@numba.njit(cache=True, nogil=True, boundscheck=False)
def _subtract_scaled(field, offset, offset_scale):
    """``field -= offset_scale * offset`` in place (2D, possibly strided views)."""
    for i in range(field.shape[0]):
        for j in range(field.shape[1]):
            field[i, j] -= offset_scale * offset[i, j]


class DistributedCompliance:
    """Normal compliance of an elastic half-space, its fields split by rows over ``comm``.

    Parameters
    ----------
    comm : mpi4py.MPI.Comm
    shape : tuple of int
        Global ``(nx, ny)``.
    lengths : tuple of float
        Window ``(Lx, Ly)`` [length].
    E_star : float
        Contact modulus [pressure].
    periodic : bool
        Periodic window, or an isolated one (zero-padded transform on the doubled box).
    """

    def __init__(self, comm, shape, lengths, *, E_star: float, periodic: bool = True, layer=None,
                 E: float | None = None, nu: float | None = None, tol: float = 1e-8):
        self.comm, self.shape, self.lengths = comm, tuple(shape), tuple(float(v) for v in lengths)
        self.E_star, self.periodic = float(E_star), bool(periodic)
        if layer is not None and not self.periodic:
            raise ValueError("layer: a distributed layer is periodic (periodic=True); solve a non-periodic one "
                             "serially")
        # periodic, the preconditioned residual overwrites the spent residual's buffer (as in the serial transforms)
        self.plan = SlabFFT(comm, self.shape, padded=not self.periodic,
                            inputs=("pressure", "residual", "direction"), outputs=("displacement", "preconditioned"))
        if self.periodic:
            self.plan.buffers["preconditioned"] = self.plan.buffers["residual"]
        self.work_shape = self.plan.work_shape
        self.count = float(np.prod(self.work_shape))
        self.weights = self.plan.parseval_weights()
        qx, qy = self.plan.wavevectors(self.lengths)
        q = np.sqrt(qx**2 + qy**2)
        lowest = 2 * np.pi / (self.work_shape[1] * self.lengths[1] / self.shape[1])
        self.model = "half-space"
        if layer is not None:
            from .layer import layer_transfer

            transfer, self.model = layer_transfer(comm, q, E=E, nu=nu, layer=layer, tol=tol,
                                                  column_start=self.plan.column_start)
            self._set_transfer(transfer, q)
            return
        if self.periodic:
            transfer = np.zeros_like(q)
            np.divide(2.0, self.E_star * q, out=transfer, where=q > 0)
        else:
            transfer = self._point_influence_spectrum()
        self.multiplier = np.ascontiguousarray(transfer / self.count)
        # the preconditioner: the continuous stiffness E*|q|/2, its zero mode given the lowest wavenumber's value
        q[q == 0] = lowest
        self.inverse_multiplier = np.ascontiguousarray(self.E_star * q / 2 / self.count)
        self._softest = self.E_star * lowest / 2
        self.definite = not self.periodic

    def _set_transfer(self, transfer: np.ndarray, q: np.ndarray) -> None:
        """A spectral compliance other than the half-space's (a layer's): preconditioned by its exact inverse, its
        zero mode, if without stiffness, given the ``(0, 1)`` mode's, as the serial operator does; refused where
        the serial solver would leave the CG (a plate-like layer:
        :data:`contactlib.model.operators.PRECONDITION_SOFTENING`)."""
        from mpi4py import MPI  # the distributed path only

        from ..model.operators import PRECONDITION_SOFTENING

        nonzero = q > 0
        local = float(np.max(transfer[nonzero] * self.E_star * q[nonzero] / 2)) if nonzero.any() else 0.0
        if self.comm.allreduce(local, op=MPI.MAX) > PRECONDITION_SOFTENING:
            raise ValueError("layer: a plate-like layer (softer than the half-space by more than "
                             f"{PRECONDITION_SOFTENING}x at some wavevector) needs the serial semismooth solver; "
                             "run it without MPI")
        self.multiplier = np.ascontiguousarray(transfer / self.count)
        stiffness = np.zeros_like(transfer)
        np.divide(1.0, transfer, out=stiffness, where=transfer > 0)
        owner = self.plan.column_start == 0
        first = float(self.allsum(float(stiffness[0, 1]) if self.plan.column_start <= 1 < self.plan.column_stop
                                  else 0.0)[0])
        softest = stiffness[nonzero].min() if nonzero.any() else np.inf
        self._softest = float(self.comm.allreduce(float(softest), op=MPI.MIN))
        zero_mode = float(self.allsum(float(transfer[0, 0]) if owner else 0.0)[0])
        if owner and stiffness[0, 0] == 0:
            stiffness[0, 0] = first
        self.inverse_multiplier = np.ascontiguousarray(stiffness / self.count)
        self.definite = zero_mode > 0

    def _point_influence_spectrum(self) -> np.ndarray:
        """The spectrum of the collocated point-load coefficients on the doubled box, from this rank's rows of
        both halves: the lower half's rows ``nx + i`` enter with the phase ``(-1)^kx`` of their shift by ``nx``."""
        plan = SlabFFT(self.comm, self.shape, padded=True, effort="FFTW_ESTIMATE")
        nx, ny = self.shape
        dx, dy = (length / n for length, n in zip(self.lengths, self.shape))
        j = np.arange(2 * ny)
        y = np.where(j < ny, j, j - 2 * ny) * dy
        a, b = dx / 2, dy / 2
        zero = np.zeros(1)
        self_term = float((love_rectangle(zero + a, zero + b) - love_rectangle(zero + a, zero - b)
                           - love_rectangle(zero - a, zero + b) + love_rectangle(zero - a, zero - b))[0]
                          / (np.pi * self.E_star))
        spectra = []
        for offset in (0, nx):
            i = np.arange(plan.row_start, plan.row_stop) + offset
            x = np.where(i < nx, i, i - 2 * nx) * dx
            r = np.sqrt(x[:, None] ** 2 + y[None, :] ** 2)
            with np.errstate(divide="ignore"):
                u = dx * dy / (np.pi * self.E_star * r)
            u[r == 0] = self_term
            plan.buffers["field"][...] = u
            spectra.append(plan.forward("field").real.copy())
        sign = np.where(np.arange(2 * nx) % 2 == 0, 1.0, -1.0)[:, None]
        return spectra[0] + sign * spectra[1]

    def allsum(self, *values: float) -> np.ndarray:
        """The sums over the ranks of local sums, in one reduction."""
        local = np.array(values, dtype=float)
        total = np.empty_like(local)
        self.comm.Allreduce(local, total)
        return total

    def self_compliance(self) -> float:
        """Displacement of an element under its own unit pressure: the Hermitian-weighted sum of the multiplier."""
        return float(self.allsum(float(np.sum(self.weights * self.multiplier)))[0])

    def reentry_scale(self) -> float:
        """The preconditioner's softest stiffness ``E* q1 / 2`` [pressure/length] (see the serial operator)."""
        return self._softest

    def iteration_transforms(self, offset_local: np.ndarray) -> "DistributedTransforms":
        return DistributedTransforms(self, offset_local)


class DistributedTransforms:
    """The transforms of one solve: :class:`contactlib.model.operators.IterationTransforms` on slabs.

    :attr:`pressure`, :attr:`residual` and :attr:`direction` are this rank's rows in the transforms' input
    buffers. The offset (the heights below their maximum) is subtracted from the displacement in real space, one
    pass over the rows, where the serial transforms keep its spectrum: a field less per rank, the memory that
    decides how large a grid fits (the results agree to round-off).
    """

    def __init__(self, operator: DistributedCompliance, offset_local: np.ndarray):
        self.op = operator
        plan = operator.plan
        for name in ("pressure", "residual", "direction"):
            plan.buffers[name].fill(0.0)
        self.pressure, self.residual, self.direction = (plan.field(k) for k in ("pressure", "residual", "direction"))
        self._offset = offset_local

    def displacement(self, offset_scale: float = 0.0) -> np.ndarray:
        """``K pressure - offset_scale * offset`` on this rank's rows (a view)."""
        _scale(self.op.plan.forward("pressure"), self.op.multiplier)
        out = self.op.plan.inverse("displacement")
        if offset_scale != 0.0:
            _subtract_scaled(out, self._offset, float(offset_scale))
        return out

    def precondition(self) -> tuple[np.ndarray, float]:
        """``(P residual, <residual, P residual>)``: this rank's rows, and the sum over the whole grid."""
        spectrum = self.op.plan.forward("residual")
        power = _weighted_power(spectrum, self.op.inverse_multiplier, self.op.weights, True)
        return self.op.plan.inverse("preconditioned"), float(self.op.allsum(power)[0])

    def direction_energy(self) -> float:
        """``<direction, K direction>`` over the whole grid, by Parseval."""
        spectrum = self.op.plan.forward("direction")
        return float(self.op.allsum(_weighted_power(spectrum, self.op.multiplier, self.op.weights, False))[0])


def apply(op: DistributedCompliance, field: np.ndarray, multiplier: np.ndarray | None = None) -> np.ndarray:
    """``K field`` on this rank's rows (a new array), on transform buffers of their own: safe in the middle of
    a solve. ``multiplier``: another Fourier multiplier on the same grid (normalised), in place of ``K``'s."""
    plan = getattr(op, "_aside", None)
    if plan is None:
        plan = op._aside = SlabFFT(op.comm, op.shape, padded=not op.periodic)
    plan.buffers["field"].fill(0.0)
    plan.field("field")[...] = field
    _scale(plan.forward("field"), op.multiplier if multiplier is None else multiplier)
    return plan.inverse("field").copy()


def stiffness_of(op: DistributedCompliance) -> DistributedCompliance:
    """The periodic stiffness, the compliance's exact inverse on ``q != 0`` and 0 on the mean, preconditioned by
    the compliance itself, its zero mode given its longest wave's value: :class:`contactlib.model.operators.Stiffness`
    on slabs, the operator of the dual problem (:mod:`.dual`)."""
    if not op.periodic:
        raise ValueError("stiffness_of: the compliance must be periodic")
    new = DistributedCompliance.__new__(DistributedCompliance)
    new.comm, new.shape, new.lengths, new.E_star, new.periodic = op.comm, op.shape, op.lengths, op.E_star, True
    new.plan = SlabFFT(op.comm, op.shape, padded=False, inputs=("pressure", "residual", "direction"),
                       outputs=("displacement", "preconditioned"))
    new.plan.buffers["preconditioned"] = new.plan.buffers["residual"]
    new.work_shape, new.count, new.weights, new.definite = op.work_shape, op.count, op.weights, False
    transfer = op.multiplier * op.count
    stiffness = np.zeros_like(transfer)
    np.divide(1.0, transfer, out=stiffness, where=transfer > 0)
    new.multiplier = np.ascontiguousarray(stiffness / op.count)
    inverse = op.multiplier.copy()
    # the serial operator's inverse.flat[1]: the multiplier at (kx, ky) = (0, 1), held by the rank of column 1
    has_one = op.plan.column_start <= 1 < op.plan.column_stop
    first = float(op.allsum(float(op.multiplier[0, 1 - op.plan.column_start]) if has_one else 0.0)[0])
    if op.plan.column_start == 0:
        inverse[0, 0] = first
    new.inverse_multiplier = inverse
    from mpi4py import MPI  # the distributed path only

    new._softest = float(op.comm.allreduce(float(inverse.min()), op=MPI.MIN)) * op.count
    return new
