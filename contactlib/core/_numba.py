"""numba compilation of the element-wise sweeps, and their threaded versions.

A sweep is first written serially, over a whole 2D array. Its threaded version (``_threaded_*``)
cuts the rows into blocks fixed by the array's shape (:func:`row_blocks`), runs the serial sweep
on each block in a ``numba.prange`` loop, and adds the blocks' sums in block order. No sum depends
on which thread computed it, so a threaded sweep returns the same bits on 2 threads or 16; they
differ from the serial sweep's in round-off, as FFTW's threaded transforms do from its serial ones.
:func:`parallel_sweeps` says when to thread, from the thread setting of :mod:`contactlib.core.fft`.
"""

from __future__ import annotations

import functools
import os
import threading

import numba
import numpy as np

from . import fft

# numba's default OpenMP layer and the OpenMP runtime bundled with pyFFTW's FFTW keep two pools of
# spinning threads: on 2 cores, FFTW and the sweeps on 2 threads each ran 512^2 iterations 7x slower
# than on 1 thread (43 against 6 ms). The workqueue layer's threads sleep between launches: 4.3 ms.
# It takes one launch at a time, hence :data:`LAUNCH_LOCK`. A layer the user names is kept.
if "NUMBA_THREADING_LAYER" not in os.environ:
    numba.config.THREADING_LAYER = "workqueue"

LAUNCH_LOCK = threading.Lock()
"""Held while a threaded sweep runs: the workqueue layer aborts on concurrent launches (a dask worker
with several threads)."""


def serialised(sweep):
    """``sweep``, called under :data:`LAUNCH_LOCK`."""
    @functools.wraps(sweep)
    def call(*args):
        with LAUNCH_LOCK:
            return sweep(*args)
    return call

# reassociation lets the reductions vectorise; no finite-math assumptions (NaN must propagate)
FASTMATH = {"reassoc", "contract", "nsz"}
jit = numba.njit(cache=True, nogil=True, fastmath=FASTMATH, boundscheck=False)
parallel_jit = numba.njit(cache=True, nogil=True, fastmath=FASTMATH, boundscheck=False, parallel=True)
vector_jit = numba.njit(cache=True, nogil=True, fastmath=FASTMATH, boundscheck=False, error_model="numpy")
""":data:`jit` for element-wise loops that divide: numba's default checks every float division for a zero divisor
(Python's ZeroDivisionError), which keeps such a loop from vectorising; here a division by zero gives an infinity
or a NaN, as numpy's does (the 9 300 Ewald pair weights of 10^3 asperities: 98 -> 24 us)."""

PARALLEL_MIN_SIZE = 1 << 23
"""Smallest grid (points) swept on several threads. A workqueue launch wakes sleeping threads, which
costs about a quarter of a millisecond on this 2-vCPU VM, and FFTW's OpenMP threads are still
spinning on the other core when a sweep starts. Whole 1-thread-sweep against 2-thread-sweep solves,
FFTW on 2 threads (ms per iteration): 256^2 1.08 / 2.64, 512^2 4.5 / 5.6, 1024^2 20.2 / 22.7,
2048^2 118.6 / 126.7, 4096^2 671 / 623. So the sweeps thread from 4096^2 (8.4 million points) up."""

BLOCK_SIZE = 1 << 13
"""Points per row block of a threaded sweep (whole rows, at least one): enough that a block's
start-up is small beside its sweep, few enough blocks to share out evenly."""


def parallel_sweeps(rows: int, size: int) -> bool:
    """Whether sweeps over a grid of ``rows`` rows and ``size`` points run on several threads: the
    FFT thread setting is above 1, the grid is large enough and has rows for every thread. Sets
    numba's thread count (per calling thread) to match."""
    threads = fft.threads()
    if threads < 2 or size < PARALLEL_MIN_SIZE:
        return False
    threads = min(threads, numba.config.NUMBA_NUM_THREADS)
    if threads < 2 or rows < 2 * threads:
        return False
    if numba.get_num_threads() != threads:
        numba.set_num_threads(threads)
    return True


@numba.njit(cache=True, nogil=True)
def row_blocks(rows: int, columns: int) -> tuple[int, int]:
    """``(number of blocks, rows per block)`` of a threaded sweep over a ``rows x columns`` grid."""
    per_block = max(1, BLOCK_SIZE // max(columns, 1))
    return (rows + per_block - 1) // per_block, per_block


@numba.njit(cache=True, nogil=True)  # no fastmath: the block order of the sum is fixed
def column_sums(part: np.ndarray) -> np.ndarray:
    """Sums of each column of ``part``, adding the rows in order."""
    out = np.zeros(part.shape[1])
    for i in range(part.shape[0]):
        for k in range(part.shape[1]):
            out[k] += part[i, k]
    return out
