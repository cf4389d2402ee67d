"""Apply a compliance kernel: pressure field -> surface displacement.

A :class:`Compliance` wraps one kernel on one grid. Periodic problems multiply the rfft of
the pressure by a Fourier multiplier; non-periodic problems embed the pressure in a doubled,
zero-padded box and convolve with real-space influence coefficients, which is the exact
linear (aperiodic) convolution. Solvers only see ``apply(pressure) -> displacement``.
"""

from __future__ import annotations

from functools import lru_cache

import numba
import numpy as np

from ..core import fft
from ..core._numba import column_sums, jit, parallel_jit, parallel_sweeps, row_blocks, serialised
from ..core.grid import Grid
from ..kernels import elastic

KERNELS = ("spectral", "love")


@jit
def _weighted_power_sum(spectrum, multiplier, even):
    """``sum_q w |S(q)|^2 M(q)`` over an rfft half-spectrum (2D view), ``w = 2`` but for the first
    column and, for an even last axis, the last one (they have no mirror image)."""
    last = spectrum.shape[1] - 1
    total = 0.0
    edges = 0.0
    for i in range(spectrum.shape[0]):
        for j in range(spectrum.shape[1]):  # branch-free inner loop: it vectorises
            s = spectrum[i, j]
            total += (s.real * s.real + s.imag * s.imag) * multiplier[i, j]
        s = spectrum[i, 0]
        edges += (s.real * s.real + s.imag * s.imag) * multiplier[i, 0]
        if even and last > 0:
            s = spectrum[i, last]
            edges += (s.real * s.real + s.imag * s.imag) * multiplier[i, last]
    return 2.0 * total - edges


@numba.njit(cache=True, nogil=True, boundscheck=False)
def _scale_spectrum(spectrum, multiplier):
    """``spectrum *= multiplier`` in place (2D views): one pass, where numpy's complex-by-real
    in-place multiply takes 1.3-3x longer (benchmarks/bench_iteration.py); same bits."""
    for i in range(spectrum.shape[0]):
        for j in range(spectrum.shape[1]):
            spectrum[i, j] = spectrum[i, j] * multiplier[i, j]


@parallel_jit
def _threaded_weighted_power_sum(spectrum, multiplier, even):
    blocks, size = row_blocks(spectrum.shape[0], spectrum.shape[1])
    part = np.empty((blocks, 1))
    for b in numba.prange(blocks):
        r = slice(b * size, min((b + 1) * size, spectrum.shape[0]))
        part[b, 0] = _weighted_power_sum(spectrum[r], multiplier[r], even)
    return column_sums(part)[0]


@numba.njit(cache=True, nogil=True, boundscheck=False, parallel=True)
def _threaded_scale_spectrum(spectrum, multiplier):
    blocks, size = row_blocks(spectrum.shape[0], spectrum.shape[1])
    for b in numba.prange(blocks):
        r = slice(b * size, min((b + 1) * size, spectrum.shape[0]))
        _scale_spectrum(spectrum[r], multiplier[r])


@numba.njit(cache=True, nogil=True, boundscheck=False)
def affine_spectrum(spectrum, multiplier, offset, offset_scale):
    """``spectrum = spectrum * multiplier - offset_scale * offset`` in place (2D views), one pass."""
    for i in range(spectrum.shape[0]):
        for j in range(spectrum.shape[1]):
            spectrum[i, j] = spectrum[i, j] * multiplier[i, j] - offset_scale * offset[i, j]


@jit
def scale_and_power_sum(spectrum, multiplier, even):
    """:func:`_weighted_power_sum` of ``spectrum``, then ``spectrum *= multiplier``: one pass."""
    last = spectrum.shape[1] - 1
    total = 0.0
    edges = 0.0
    for i in range(spectrum.shape[0]):
        s = spectrum[i, 0]  # the unmirrored columns, before the row is scaled
        edges += (s.real * s.real + s.imag * s.imag) * multiplier[i, 0]
        if even and last > 0:
            s = spectrum[i, last]
            edges += (s.real * s.real + s.imag * s.imag) * multiplier[i, last]
        for j in range(spectrum.shape[1]):
            s = spectrum[i, j]
            m = multiplier[i, j]
            total += (s.real * s.real + s.imag * s.imag) * m
            spectrum[i, j] = s * m
    return 2.0 * total - edges


@parallel_jit
def _threaded_scale_and_power_sum(spectrum, multiplier, even):
    blocks, size = row_blocks(spectrum.shape[0], spectrum.shape[1])
    part = np.empty((blocks, 1))
    for b in numba.prange(blocks):
        r = slice(b * size, min((b + 1) * size, spectrum.shape[0]))
        part[b, 0] = scale_and_power_sum(spectrum[r], multiplier[r], even)
    return column_sums(part)[0]


@numba.njit(cache=True, nogil=True, boundscheck=False, parallel=True)
def _threaded_affine_spectrum(spectrum, multiplier, offset, offset_scale):
    blocks, size = row_blocks(spectrum.shape[0], spectrum.shape[1])
    for b in numba.prange(blocks):
        r = slice(b * size, min((b + 1) * size, spectrum.shape[0]))
        affine_spectrum(spectrum[r], multiplier[r], offset[r], offset_scale)


# each pass over a half-spectrum, serial and threaded (one launch at a time: contactlib.core._numba.LAUNCH_LOCK)
_SPECTRUM_PASSES = {serial: serialised(threaded) for serial, threaded in (
    (_weighted_power_sum, _threaded_weighted_power_sum), (_scale_spectrum, _threaded_scale_spectrum),
    (affine_spectrum, _threaded_affine_spectrum), (scale_and_power_sum, _threaded_scale_and_power_sum))}


def spectrum_pass(serial, spectrum: np.ndarray):
    """``serial``, or its threaded version where the solvers' sweeps would thread (:mod:`contactlib.core._numba`)."""
    threaded = parallel_sweeps(spectrum.shape[0], 2 * spectrum.size)  # a half-spectrum: about the grid's size
    return _SPECTRUM_PASSES[serial] if threaded else serial


def weighted_power_sum(spectrum: np.ndarray, multiplier: np.ndarray, even: bool) -> float:
    """:func:`_weighted_power_sum`, threaded like the solvers' sweeps (:mod:`contactlib.core._numba`)."""
    return spectrum_pass(_weighted_power_sum, spectrum)(spectrum, multiplier, even)


def scale_spectrum(spectrum: np.ndarray, multiplier: np.ndarray) -> None:
    """:func:`_scale_spectrum`, threaded like the solvers' sweeps (the same bits either way)."""
    spectrum_pass(_scale_spectrum, spectrum)(spectrum, multiplier)


def _rows(a: np.ndarray) -> np.ndarray:
    """A 2D view (a profile's half-spectrum as one row) for the numba passes."""
    return a.reshape(-1, a.shape[-1])


class IterationTransforms:
    """The transforms of one iterative solve on an operator's grid, on buffers of their own.

    ``with operator.iteration_transforms(offset) as transforms:`` lends this thread's buffers (kept
    for the next solve of the same grid). Three input fields live in them for the whole solve, as
    views of the grid's block: :attr:`pressure`, :attr:`residual` and :attr:`direction`. The
    transforms read them and never write over them, so a solver updates them in place and copies
    nothing into FFT buffers:

    * :meth:`displacement`: ``K pressure - offset_scale * offset`` (the offset's spectrum is kept, so
      subtracting it costs no pass in real space);
    * :meth:`precondition`: the approximate inverse of ``K`` (:attr:`Compliance.inverse_multiplier`)
      applied to :attr:`residual`, and ``<residual, P residual>`` by Parseval on the way;
    * :meth:`direction_energy`: ``<direction, K direction>`` by Parseval (a forward transform only).

    The results are views valid until the next call of the same method; :meth:`take` hands a field
    over at the end. The buffers are not reset between solves, except :attr:`direction`, which starts
    at zero (and, zero-padded, the inputs' padding).
    """

    def __init__(self, operator: Compliance, offset: np.ndarray | None = None):
        self.operator = operator
        outputs = {"displacement": None, "preconditioned": "residual" if operator.periodic else None}
        self._pool = fft.shared_spectrum(operator.work_shape, ("pressure", "residual", "direction"), outputs)
        self._offset_field = offset

    def __enter__(self) -> IterationTransforms:
        op = self.operator
        ws = self.workspace = self._pool.__enter__()
        if not op.periodic:  # the padding of the inputs must be zero; only their block is ever written
            for name in ("pressure", "residual", "direction"):
                ws.buffers[name].fill(0.0)
        self.pressure, self.residual, self.direction = (ws.buffers[k][op._block]
                                                        for k in ("pressure", "residual", "direction"))
        self._multiplier, self._inverse = _rows(op.multiplier), _rows(op.inverse_multiplier)
        self._even = op.work_shape[-1] % 2 == 0
        self.offset_spectrum = None
        if self._offset_field is not None:
            self.direction[...] = self._offset_field
            self.offset_spectrum = _rows(ws.forward("direction") / float(np.prod(op.work_shape)))
        self.direction.fill(0.0)
        return self

    def __exit__(self, *exc) -> None:
        self.offset_spectrum = None
        self._pool.__exit__(*exc)

    def take(self, name: str) -> np.ndarray:
        """The field in buffer ``name`` (``"pressure"``, ``"displacement"``, ``"residual"``...) as an array
        of the caller's, on the grid: periodic, the buffer itself, handed over without a copy (the pool
        gets a new one); zero-padded, a copy of the block. The offset's spectrum is dropped first: a
        solve takes its fields at the end, and its memory peaks there."""
        self.offset_spectrum = None
        if self.operator.periodic:
            return self.workspace.detach(name)
        return self.workspace.buffers[name][self.operator._block].copy()

    def displacement(self, offset_scale: float = 0.0) -> np.ndarray:
        """``K pressure - offset_scale * offset`` [length], a view of the block."""
        spectrum = _rows(self.workspace.forward("pressure"))
        if self.offset_spectrum is None or offset_scale == 0.0:
            spectrum_pass(_scale_spectrum, spectrum)(spectrum, self._multiplier)
        else:
            spectrum_pass(affine_spectrum, spectrum)(spectrum, self._multiplier, self.offset_spectrum, offset_scale)
        return self.workspace.inverse("displacement")[self.operator._block]

    def lower_offset(self, field: np.ndarray) -> np.ndarray:
        """Subtract ``K field`` from the offset in Fourier space and return ``K field`` [length] (a view of
        the block, valid until the next call): one FFT pair on buffers of its own. A solver whose heights
        move with a traction (the frozen-traction cohesive rounds, :mod:`contactlib.solvers.adhesive.cohesive_rounds`)
        moves them without a new set-up; on a zero-padded grid the offset is then right on the block only,
        which is all :meth:`displacement` returns."""
        op = self.operator
        plan = fft.get_fft(op.work_shape, slot="offset")
        if not op.periodic:
            plan.real.fill(0.0)
        plan.real[op._block] = field
        spectrum = _rows(plan.forward())
        spectrum_pass(_scale_spectrum, spectrum)(spectrum, self._multiplier)
        self.offset_spectrum -= spectrum  # the offset is kept as FFT(offset) / size: the multiplier has the 1 / size
        return plan.inverse()[op._block]

    def precondition(self) -> tuple[np.ndarray, float]:
        """``(P residual, <residual, P residual>)``: a view of the block, and the sum over the grid."""
        spectrum = _rows(self.workspace.forward("residual"))
        power = spectrum_pass(scale_and_power_sum, spectrum)(spectrum, self._inverse, self._even)
        return self.workspace.inverse("preconditioned")[self.operator._block], float(power)

    def direction_energy(self) -> float:
        """``<direction, K direction>`` [length * pressure, summed over elements]."""
        spectrum = _rows(self.workspace.forward("direction"))
        return float(weighted_power_sum(spectrum, self._multiplier, self._even))


@lru_cache(maxsize=8)
def _unit_multiplier(grid: Grid, kernel: str, periodic: bool) -> np.ndarray:
    """Normalised convolution multiplier for ``E* = 1``, cached: the Love image sums cost seconds
    at N = 1024 and a sweep solves the same grid many times."""
    if periodic:
        build = elastic.halfspace_spectral_multiplier if kernel == "spectral" else elastic.halfspace_love_multiplier
        transfer, shape = build(grid, 1.0), grid.shape
    else:
        build = elastic.halfspace_point_influence if kernel == "spectral" else elastic.halfspace_love_influence
        shape = grid.padded().shape
        transfer = fft.rfftn(build(grid, 1.0)).real  # symmetric kernel: real spectrum
    multiplier = fft.convolution_multiplier(transfer, shape)
    multiplier.flags.writeable = False
    return multiplier


PRECONDITION_SOFTENING = 2.0
"""Largest ratio of a layer's normal compliance to the half-space's (over ``q != 0``) that is still
preconditioned. A thin remote-pressure layer (a plate: compliance ~ 1/(q^4 h^3) at long waves) led the
preconditioned loop astray: on a 16384-point profile at 19 % contact it stalled at 29 % for q0 h = 1
(ratio 7.4) and took 3x longer than without at q0 h = 1.5 (ratio 2.9); unpreconditioned, both converge
(down to q0 h = 0.63 in 1D and 0.2 on 128^2). Below q0 h = 2.5 (ratio 1.3) preconditioning pays again."""


def _softening(grid: Grid, transfer: np.ndarray, E_star: float) -> float:
    """``max transfer(q) / (2 / (E* |q|))`` over ``q != 0``."""
    q = grid.wavenumber()
    nonzero = q > 0
    return float(np.max(transfer[nonzero] * E_star * q[nonzero] / 2)) if nonzero.any() else 1.0


class Compliance:
    """Normal compliance of an elastic half-space or layer on ``grid``.

    Parameters
    ----------
    grid : Grid
    E_star : float
        Contact modulus ``E / (1 - nu**2)`` [pressure].
    kernel : {"spectral", "love"}
        ``spectral``: continuous multiplier ``2/(E*|q|)`` (non-periodic: collocated point loads);
        ``love``: uniform pressure on each element (Love), summed over periodic images.
    periodic : bool
    transfer : ndarray, optional
        A spectral normal compliance of another body on the rfft layout of the work grid [length/pressure]
        (:attr:`contactlib.kernels.SurfaceGreenTensor.normal`, a layer's), in place of the half-space's:
        real, even, positive for ``q != 0``; its ``q = 0`` entry may be positive (a confined layer's
        uniaxial compliance: the operator is then :attr:`definite`) or 0 (zero-mean displacements).
        Non-periodic: sampled on the doubled window (:meth:`Grid.padded`), whose images the caller has
        checked are out of reach (a confined layer's influence dies out over a few thicknesses).
    """

    def __init__(self, grid: Grid, *, E_star: float, kernel: str = "spectral", periodic: bool = True,
                 transfer: np.ndarray | None = None):
        if kernel not in KERNELS:
            raise ValueError(f"kernel must be one of {KERNELS}, got {kernel!r}")
        self.grid, self.E_star, self.kernel, self.periodic = grid, float(E_star), kernel, bool(periodic)
        work_grid = grid if self.periodic else grid.padded()
        self.work_shape = work_grid.shape
        self._transfer = transfer
        if transfer is None:
            self.multiplier = _unit_multiplier(grid, kernel, self.periodic) / self.E_star
        else:
            if kernel != "spectral":
                raise ValueError("a layer's compliance is a spectral kernel (kernel='spectral')")
            expected = work_grid.wavenumber().shape
            if transfer.shape != expected:
                raise ValueError(f"transfer has shape {transfer.shape}, the work grid's rfft layout {expected}")
            self.multiplier = fft.convolution_multiplier(transfer, self.work_shape)
        self._block = tuple(slice(0, n) for n in grid.shape)
        self._inverse = None
        self._softest = None  # set with _inverse
        self.preconditionable = transfer is None or \
            _softening(work_grid, transfer, self.E_star) <= PRECONDITION_SOFTENING

    preconditionable: bool
    """Whether the constrained CG preconditions with :attr:`inverse_multiplier`: not for a body more than
    :data:`PRECONDITION_SOFTENING` times softer than the half-space at some wavevector (a thin
    remote-pressure layer, a plate)."""

    @property
    def transfer(self) -> np.ndarray | None:
        """The ``transfer`` given (a layer's spectral compliance on the work grid), None for the half-space's."""
        return self._transfer

    @property
    def definite(self) -> bool:
        """Whether the compliance fixes the mean displacement: zero-padded, or a periodic body whose
        ``q = 0`` mode has a finite stiffness (a compressible confined layer). A periodic half-space
        does not: its displacements are zero-mean and a penetration is measured from their mean."""
        return not self.periodic or float(self.multiplier.flat[0]) > 0

    @property
    def inverse_multiplier(self) -> np.ndarray:
        """The preconditioner: the continuous half-space stiffness ``E*|q|/2`` on the work grid (or the
        exact inverse of a layer's ``transfer``), normalised; a zero mode without stiffness takes the
        lowest non-zero wavenumber's value so it stays definite."""
        if self._inverse is None:
            if self._transfer is None:
                q = Grid(self.work_shape, self.grid.lengths if self.periodic else self.grid.padded().lengths).wavenumber()
                lowest = float(q.flat[1]) if q.size > 1 else 1.0
                q.flat[0] = lowest
                stiffness = self.E_star * q / 2
                self._softest = self.E_star * lowest / 2
            else:
                stiffness = np.zeros_like(self._transfer)
                np.divide(1.0, self._transfer, out=stiffness, where=self._transfer > 0)
                self._softest = float(stiffness.flat[1:].min())
                if stiffness.flat[0] == 0:
                    stiffness.flat[0] = stiffness.flat[1]
            self._inverse = fft.convolution_multiplier(stiffness, self.work_shape)
        return self._inverse

    def reentry_scale(self) -> float:
        """The preconditioner's softest stiffness [pressure/length]: ``E* q1 / 2`` at the lowest non-zero
        wavenumber ``q1`` of the work grid for a half-space (its longest wave, and its zero mode), the
        smallest over ``q != 0`` for a layer. The preconditioned solver re-enters a point at this
        stiffness times its overlap."""
        self.inverse_multiplier  # builds it once: the preconditioned solve needs it anyway
        return self._softest

    def load(self) -> np.ndarray:
        """Writable view where the next input field goes (padding already zeroed)."""
        plan = fft.get_fft(self.work_shape)
        if not self.periodic:  # zero the padding only: the block may hold the caller's input
            n0 = self.grid.shape[0]
            plan.real[n0:].fill(0.0)
            if self.grid.dim == 2:
                plan.real[:n0, self.grid.shape[1]:].fill(0.0)
        return plan.real[self._block]

    def convolve(self, *, inverse: bool = False) -> np.ndarray:
        """Convolve what :meth:`load` received; returns a view of the displacement (valid until
        the next call on this shape in this thread). ``inverse=True`` applies the approximate
        inverse (:attr:`inverse_multiplier`) instead: a preconditioner."""
        return self._convolve(fft.get_fft(self.work_shape), self.inverse_multiplier if inverse else self.multiplier)

    def apply_aside(self, field: np.ndarray) -> np.ndarray:
        """Convolve ``field`` on FFT buffers of its own (a new array): safe in the middle of a solve
        whose iterate sits in the work buffers of :meth:`load`."""
        plan = fft.get_fft(self.work_shape, slot="aside")
        plan.real.fill(0.0)
        plan.real[self._block] = field
        return self._convolve(plan, self.multiplier).copy()

    def _convolve(self, plan: fft.RealFFT, multiplier: np.ndarray) -> np.ndarray:
        """Forward transform of ``plan.real``, times ``multiplier``, back: a view of the block."""
        spectrum = plan.forward()
        scale_spectrum(spectrum.reshape(-1, spectrum.shape[-1]), multiplier.reshape(-1, multiplier.shape[-1]))
        return plan.inverse()[self._block]

    def iteration_transforms(self, offset: np.ndarray | None = None) -> IterationTransforms:
        """The transforms of an iterative solve, with their own buffers (:class:`IterationTransforms`);
        ``offset`` [length] on the grid is subtracted from the displacement in Fourier space."""
        return IterationTransforms(self, offset)

    def quadratic_form(self) -> float:
        """``<t, K t>`` [length * pressure, summed over elements] for the field ``t`` written to
        :meth:`load`: by Parseval, from the forward transform alone (half the cost of a convolution)."""
        plan = fft.get_fft(self.work_shape)
        spectrum = plan.forward()
        return float(weighted_power_sum(spectrum.reshape(-1, spectrum.shape[-1]),
                                        self.multiplier.reshape(-1, self.multiplier.shape[-1]),
                                        self.work_shape[-1] % 2 == 0))

    def __call__(self, pressure: np.ndarray, out: np.ndarray | None = None) -> np.ndarray:
        """Displacement [length] due to ``pressure`` [pressure]; writes into ``out`` if given."""
        self.load()[...] = pressure
        result = self.convolve()
        if out is None:
            return result.copy()
        out[...] = result
        return out

    def response(self) -> np.ndarray:
        """Displacement field on the work grid due to unit pressure on the element at the origin."""
        unit = np.zeros(self.work_shape)
        unit[(0,) * self.grid.dim] = 1.0
        return fft.irfftn(fft.rfftn(unit) * self.multiplier * np.prod(self.work_shape), self.work_shape)

    def self_compliance(self) -> float:
        """Displacement of an element under its own unit pressure [length/pressure]:
        the inverse transform at the origin, i.e. the Hermitian-weighted sum of the multiplier."""
        weight = np.full(self.multiplier.shape, 2.0)
        weight[..., 0] = 1.0
        if self.work_shape[-1] % 2 == 0:
            weight[..., -1] = 1.0
        return float(np.sum(weight * self.multiplier))

    def matrix(self, flat_indices: np.ndarray) -> np.ndarray:
        """Dense influence matrix restricted to the given (flattened) elements: for small grids."""
        resp = self.response()
        idx = np.unravel_index(np.asarray(flat_indices), self.grid.shape)
        diff = tuple((a[:, None] - a[None, :]) % n for a, n in zip(idx, self.work_shape))
        return resp[diff]


class Stiffness(Compliance):
    """Normal stiffness of a periodic elastic half-space: surface displacement -> pressure.

    The exact inverse of a periodic :class:`Compliance` on every non-zero wavevector, and 0 on the
    mean, which a periodic surface's displacement does not fix. It is the operator of the dual
    contact problem (the gap as unknown, :mod:`contactlib.solvers.symmetric.dual`), whose preconditioner
    (:attr:`inverse_multiplier`) is the compliance itself, its zero mode given its longest wave's
    value as the compliance's preconditioner does.
    """

    def __init__(self, compliance: Compliance):
        if not compliance.periodic:
            raise ValueError("Stiffness: the compliance must be periodic (a zero-padded one has no exact inverse)")
        self.grid, self.E_star, self.kernel, self.periodic = compliance.grid, compliance.E_star, compliance.kernel, True
        self.work_shape, self._block = compliance.work_shape, compliance._block
        self._transfer = None
        count = float(np.prod(self.work_shape))
        transfer = compliance.multiplier * count
        stiffness = np.zeros_like(transfer)
        np.divide(1.0, transfer, out=stiffness, where=transfer > 0)
        self.multiplier = fft.convolution_multiplier(stiffness, self.work_shape)
        inverse = compliance.multiplier.copy()
        inverse.flat[0] = inverse.flat[1]  # grids have at least 2 points a side
        self._inverse = inverse
        self._softest = float(inverse.min()) * count
        self.preconditionable = True

    def reentry_scale(self) -> float:
        """The smallest compliance [length/pressure] (the shortest wave's): re-entry in the dual
        problem turns a tensile pressure into a gap, and the gentlest such conversion keeps it stable
        (the longest wave's, 1e3 times larger on 256^2, made the iteration diverge)."""
        return self._softest


class Coupling:
    """The normal displacement due to a Coulomb traction ``mu p`` along a sliding direction: ``W p``.

    ``W`` is the normal-tangential block of the surface Green's tensor times ``mu``: odd in ``q``,
    so antisymmetric in real space (the skew part of the frictional normal operator ``K + W``).
    Where coupling is strong the body model passes ``W - |W|`` instead (its ``|W|`` moved into the
    symmetric compliance: :data:`contactlib.model.bodies.SHIFT_ABOVE`).
    Periodic: the complex multiplier ``-i mu c (q . s)/|q|``
    (:meth:`contactlib.kernels.SurfaceGreenTensor.coupling_multiplier`); non-periodic: the half-space's
    real-space influence coefficients on the zero-padded box
    (:func:`contactlib.kernels.halfspace_coupling_influence`). Applied once per outer iteration of
    :func:`contactlib.solvers.solve_coupled`, on FFT buffers of its own.
    """

    def __init__(self, grid: Grid, *, periodic: bool, friction: float, transfer: np.ndarray | None = None,
                 influence: np.ndarray | None = None):
        self.grid, self.periodic = grid, bool(periodic)
        self.work_shape = grid.shape if periodic else grid.padded().shape
        self._block = tuple(slice(0, n) for n in grid.shape)
        # a spectral kernel on the work grid (non-periodic: a layer's, on the doubled window), kept for a padded
        # layer's model to reuse; else the odd real-space influence's (an imaginary spectrum), not kept
        self.transfer = None if transfer is None else np.asarray(transfer)
        spectrum = self.transfer if transfer is not None else fft.rfftn(influence)
        self.multiplier = np.ascontiguousarray(friction * spectrum / float(np.prod(self.work_shape)),
                                               dtype="complex128")

    def __call__(self, pressure: np.ndarray) -> np.ndarray:
        """``W pressure`` [length] (a new array)."""
        plan = fft.get_fft(self.work_shape, slot="coupling")
        plan.real.fill(0.0)
        plan.real[self._block] = pressure
        spectrum = plan.forward()
        spectrum *= self.multiplier
        return plan.inverse()[self._block].copy()
