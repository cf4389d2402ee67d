"""Distributed real-to-complex 2D FFT on slabs: the serial convention of :mod:`contactlib.core.fft` over MPI ranks.

A real field is split by rows (:class:`.slabs.Slabs`), its half-spectrum by columns. The forward transform is
pyFFTW's ``rfft`` along the contiguous axis of each rank's rows, a global transpose by ``MPI_Alltoallw`` on
subarray datatypes (each rank sends every other one the block of its rows in that rank's columns, without packing),
then the ``fft`` along the rows' axis of the rank's columns, in place. The inverse runs the same steps backwards.
Both are unnormalised, as the solvers' FFTW plans are: forward then inverse multiplies by the number of points,
which :func:`contactlib.core.fft.convolution_multiplier` folds into the kernels. Rank ``r``'s spectral slab is
``rfftn(field)[:, c0:c1]`` of the whole field, to FFTW's rounding.

A zero-padded (non-periodic) transform on the doubled ``(2 nx, 2 ny)`` box keeps only the field's ``nx``
rows in real space: the padding rows are zero going in and unwanted coming out, so they are neither stored
nor sent; the padding columns are local to each rank.
"""

from __future__ import annotations

import numpy as np
import pyfftw

from ..core import fft as serial_fft
from .slabs import Slabs


class SlabFFT:
    """Planned distributed transforms of fields of ``shape`` rows over the ranks of ``comm``.

    Parameters
    ----------
    comm : mpi4py.MPI.Comm
    shape : tuple of int
        The field's global ``(nx, ny)``.
    padded : bool
        Transform on the zero-padded ``(2 nx, 2 ny)`` work box (non-periodic problems).
    inputs, outputs : tuple of str
        Named real buffers, each ``(rows, work columns)`` and zeroed: ``forward(name)`` transforms an input,
        ``inverse(name)`` writes an output. The field occupies the first ``ny`` columns (:meth:`field`).
    """

    def __init__(self, comm, shape: tuple[int, int], *, padded: bool = False, inputs=("field",), outputs=("field",),
                 effort: str | None = None):
        if len(shape) != 2:
            raise ValueError(f"shape must be 2D (nx, ny), got {shape}")
        self.comm, self.rank, self.size = comm, comm.Get_rank(), comm.Get_size()
        self.shape = tuple(int(n) for n in shape)
        self.padded = bool(padded)
        nx, ny = self.shape
        self.work_shape = (2 * nx, 2 * ny) if padded else (nx, ny)
        mx, my = self.work_shape
        self.spectral_columns = my // 2 + 1
        self.rows = Slabs(nx, self.size)
        self.columns = Slabs(self.spectral_columns, self.size)
        self.row_start, self.row_stop = self.rows.bounds(self.rank)
        self.column_start, self.column_stop = self.columns.bounds(self.rank)
        n_rows, n_cols = self.row_stop - self.row_start, self.column_stop - self.column_start
        effort = effort or serial_fft.fft_options()["effort"]
        serial_fft.load_wisdom_once()  # the serial plans' on-disk wisdom: FFTW_MEASURE is paid once per shape
        # row spectra (rfft along y) and this rank's spectral columns
        self._row_spectra = pyfftw.empty_aligned((n_rows, self.spectral_columns), dtype="complex128")
        self.spectrum = pyfftw.empty_aligned((mx, n_cols), dtype="complex128")
        self.buffers = {}
        for name in (*inputs, *outputs):
            if name not in self.buffers:
                self.buffers[name] = pyfftw.empty_aligned((n_rows, my), dtype="float64")
        first = self.buffers[(*inputs, *outputs)[0]]
        self._r2c = pyfftw.FFTW(first, self._row_spectra, axes=(1,), flags=(effort,), threads=1)
        self._c2r = pyfftw.FFTW(self._row_spectra, first, axes=(1,), direction="FFTW_BACKWARD",
                                flags=(effort, "FFTW_DESTROY_INPUT"), threads=1)
        self._col_forward = pyfftw.FFTW(self.spectrum, self.spectrum, axes=(0,), flags=(effort,), threads=1)
        self._col_backward = pyfftw.FFTW(self.spectrum, self.spectrum, axes=(0,), direction="FFTW_BACKWARD",
                                         flags=(effort,), threads=1)
        if effort != "FFTW_ESTIMATE":
            serial_fft.save_wisdom()
        for buffer in self.buffers.values():
            buffer.fill(0.0)
        self.spectrum.fill(0.0)
        # The transpose is one Alltoallw: to rank s go our rows of its columns, a subarray datatype of the row
        # spectra (no packing buffer); from rank r come its rows of our columns, a contiguous block of our spectral
        # columns at r's first row. The inverse swaps the two.
        from mpi4py import MPI  # the distributed path only

        item = MPI.C_DOUBLE_COMPLEX
        self._types = [item.Create_subarray([n_rows, self.spectral_columns], [n_rows, int(k)], [0, int(c)]).Commit()
                       for c, k in zip(self.columns.starts, self.columns.counts)]
        self._row_side = [self._row_spectra, [1] * self.size, [0] * self.size, self._types]
        self._column_side = [self.spectrum, [int(k) * n_cols for k in self.rows.counts],
                             [int(a) * n_cols * 16 for a in self.rows.starts], [item] * self.size]
        # bytes this rank sends to the others per transpose (its own block stays): the communication volume
        self.bytes_per_transpose = 16 * n_rows * (self.spectral_columns - n_cols)
        self.transposes = 0

    @property
    def local_shape(self) -> tuple[int, int]:
        """This rank's rows of the field: ``(rows, ny)``."""
        return (self.row_stop - self.row_start, self.shape[1])

    def field(self, name: str) -> np.ndarray:
        """Buffer ``name`` on the field's columns (a view; the padding columns stay zero for an input)."""
        return self.buffers[name][:, : self.shape[1]]

    def forward(self, name: str) -> np.ndarray:
        """Transform buffer ``name`` into :attr:`spectrum`: this rank's columns ``[column_start, column_stop)``
        of the work box's rfft layout, all ``mx`` rows (unnormalised)."""
        buffer = self.buffers[name]
        self._r2c.update_arrays(buffer, self._row_spectra)
        self._r2c.execute()
        if self.padded:
            self.spectrum[self.shape[0]:] = 0.0
        self.comm.Alltoallw(self._row_side, self._column_side)
        self.transposes += 1
        self._col_forward.execute()
        return self.spectrum

    def inverse(self, name: str) -> np.ndarray:
        """Transform :attr:`spectrum` (destroyed) back into buffer ``name`` (unnormalised); returns the view of
        the field's columns."""
        self._col_backward.execute()
        self.comm.Alltoallw(self._column_side, self._row_side)
        self.transposes += 1
        buffer = self.buffers[name]
        self._c2r.update_arrays(self._row_spectra, buffer)
        self._c2r.execute()
        return self.field(name)

    def wavevectors(self, lengths: tuple[float, float]) -> tuple[np.ndarray, np.ndarray]:
        """Angular wavevector components of this rank's spectral columns on the work box [1/length]:
        ``qx`` (``(mx, 1)``, all rows) and ``qy`` (``(1, columns)``), for the field's window ``lengths``."""
        dx, dy = (length / n for length, n in zip(lengths, self.shape))
        mx, my = self.work_shape
        qx = 2 * np.pi * np.fft.fftfreq(mx, dx)
        qy = 2 * np.pi * np.fft.rfftfreq(my, dy)[self.column_start: self.column_stop]
        return qx[:, None], qy[None, :]

    def parseval_weights(self) -> np.ndarray:
        """Weight of each local spectral column in a sum over the whole spectrum (``(1, columns)``): 2, but 1
        for the zero column and, for an even work width, the Nyquist column, which have no mirror image."""
        my = self.work_shape[1]
        index = np.arange(self.column_start, self.column_stop)
        weights = np.where((index == 0) | ((my % 2 == 0) & (index == my // 2)), 1.0, 2.0)
        return weights[None, :]


def rfft2(comm, local: np.ndarray, shape: tuple[int, int], *, padded: bool = False) -> np.ndarray:
    """This rank's spectral columns of ``numpy.fft.rfft2`` of the field whose rows this rank holds (a copy;
    zero-padded to ``(2 nx, 2 ny)`` if ``padded``). One-off transforms (set-up, tests)."""
    plan = SlabFFT(comm, shape, padded=padded, effort="FFTW_ESTIMATE")
    plan.field("field")[...] = local
    return plan.forward("field").copy()


def irfft2(comm, spectrum: np.ndarray, shape: tuple[int, int], *, padded: bool = False) -> np.ndarray:
    """This rank's rows of ``numpy.fft.irfft2`` (normalised) from its spectral columns: the inverse of
    :func:`rfft2` (the field's rows only, when ``padded``)."""
    plan = SlabFFT(comm, shape, padded=padded, effort="FFTW_ESTIMATE")
    plan.spectrum[...] = spectrum
    return plan.inverse("field").copy() / float(np.prod(plan.work_shape))


def rows_to_columns(comm, rows: np.ndarray, n_rows: int) -> np.ndarray:
    """The global transpose: from this rank's rows ``(local rows, columns)`` of an ``(n_rows, columns)`` array to
    its columns ``(n_rows, local columns)`` (:class:`.Slabs` splits of both), by one ``Alltoallv``."""
    size = comm.Get_size()
    row_split, column_split = Slabs(n_rows, size), Slabs(rows.shape[1], size)
    c0, c1 = column_split.bounds(comm.Get_rank())
    packed = np.concatenate([np.ascontiguousarray(rows[:, a: a + k]).ravel()
                             for a, k in zip(column_split.starts, column_split.counts)])
    out = np.empty((n_rows, c1 - c0), dtype=rows.dtype)
    comm.Alltoallv([packed, (rows.shape[0] * column_split.counts, rows.shape[0] * column_split.starts)],
                   [out, (row_split.counts * (c1 - c0), row_split.starts * (c1 - c0))])
    return out


def columns_to_rows(comm, columns: np.ndarray, n_columns: int) -> np.ndarray:
    """The inverse of :func:`rows_to_columns`: from this rank's columns ``(rows, local columns)`` of a
    ``(rows, n_columns)`` array to its rows ``(local rows, n_columns)``."""
    size = comm.Get_size()
    row_split, column_split = Slabs(columns.shape[0], size), Slabs(n_columns, size)
    r0, r1 = row_split.bounds(comm.Get_rank())
    width = columns.shape[1]
    received = np.empty((r1 - r0) * n_columns, dtype=columns.dtype)
    comm.Alltoallv([np.ascontiguousarray(columns), (row_split.counts * width, row_split.starts * width)],
                   [received, ((r1 - r0) * column_split.counts, (r1 - r0) * column_split.starts)])
    out = np.empty((r1 - r0, n_columns), dtype=columns.dtype)
    for a, k in zip(column_split.starts, column_split.counts):
        out[:, a: a + k] = received[(r1 - r0) * a: (r1 - r0) * (a + k)].reshape(r1 - r0, k)
    return out
