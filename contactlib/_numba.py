"""numba compilation of the element-wise sweeps: one flag set, and serial/parallel twins.

A sweep is written as a loop over grid rows (``numba.prange``) that stores each row's partial
sums in a ``(rows, k)`` array, reduced by :func:`column_sums` in row order. Compiled twice, it runs
serially or over threads; each row's sums do not depend on which thread computed them and the
final reduction is sequential, so both twins return the same bits whatever the thread count.
:func:`parallel_sweeps` picks the twin from the thread setting of :mod:`contactlib.fft`.
"""

from __future__ import annotations

import types

import numba
import numpy as np

from . import fft

# reassociation lets the row reductions vectorise; no finite-math assumptions (NaN must propagate)
FASTMATH = {"reassoc", "contract", "nsz"}
jit = numba.njit(cache=True, nogil=True, fastmath=FASTMATH, boundscheck=False)

PARALLEL_MIN_SIZE = 1 << 16
"""Smallest grid (points) swept on several threads: below it, starting the threads costs more than
the sweep (a 256^2 sweep streams a few MB, tens of microseconds)."""


def twins(driver, fastmath=FASTMATH):
    """``(serial, parallel)`` compilations of a row-loop ``driver``. The parallel one is compiled
    from a copy with its own qualified name: numba's on-disk cache keys on the name and signature,
    not on the ``parallel`` flag, so one name would load the other's machine code."""
    copy = types.FunctionType(driver.__code__, driver.__globals__, driver.__name__ + "_parallel",
                              driver.__defaults__, driver.__closure__)
    copy.__qualname__ = driver.__qualname__ + "_parallel"
    copy.__doc__ = driver.__doc__
    flags = dict(cache=True, nogil=True, fastmath=fastmath, boundscheck=False)
    return numba.njit(**flags)(driver), numba.njit(parallel=True, **flags)(copy)


def parallel_sweeps(rows: int, size: int) -> bool:
    """Whether sweeps over a grid of ``rows`` rows and ``size`` points run on several threads: the
    FFT thread setting is above 1, the grid is large enough and has rows for every thread. Sets
    numba's thread count (per calling thread) to match."""
    threads = min(fft.fft_options()["threads"], numba.config.NUMBA_NUM_THREADS)
    if threads < 2 or rows < 2 * threads or size < PARALLEL_MIN_SIZE:
        return False
    if numba.get_num_threads() != threads:
        numba.set_num_threads(threads)
    return True


@numba.njit(cache=True, nogil=True)  # no fastmath: the row order of the sum is fixed
def column_sums(part: np.ndarray) -> np.ndarray:
    """Sums of each column of ``part``, adding the rows in order."""
    out = np.zeros(part.shape[1])
    for i in range(part.shape[0]):
        for k in range(part.shape[1]):
            out[k] += part[i, k]
    return out
