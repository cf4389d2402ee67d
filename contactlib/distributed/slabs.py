"""The slab decomposition of a grid over MPI ranks: contiguous blocks of rows (or columns).

Rank ``r`` of ``P`` holds ``n // P`` rows, plus one for the first ``n % P`` ranks, so any ``n >= P``
(odd, prime, not a multiple of ``P``) is split with at most one row of imbalance. The same split
serves the rows of a real field and the columns of its half-spectrum (:mod:`.fft`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Slabs:
    """``n`` indices split into ``size`` contiguous blocks.

    Parameters
    ----------
    n : int
        Number of rows (or spectral columns) to split.
    size : int
        Number of ranks.
    """

    n: int
    size: int

    def __post_init__(self):
        if self.size < 1:
            raise ValueError(f"size (number of ranks) must be >= 1, got {self.size}")
        if self.n < self.size:
            raise ValueError(f"n={self.n} rows cannot be split over {self.size} ranks: need at least one row a rank")

    @property
    def counts(self) -> np.ndarray:
        """Rows held by each rank."""
        base, extra = divmod(self.n, self.size)
        return np.array([base + (r < extra) for r in range(self.size)], dtype=np.int64)

    @property
    def starts(self) -> np.ndarray:
        """First row of each rank."""
        return np.concatenate(([0], np.cumsum(self.counts)[:-1])).astype(np.int64)

    def bounds(self, rank: int) -> tuple[int, int]:
        """``(start, stop)`` of ``rank``'s rows."""
        if not 0 <= rank < self.size:
            raise ValueError(f"rank must be in [0, {self.size}), got {rank}")
        start = int(self.starts[rank])
        return start, start + int(self.counts[rank])

    def slice(self, rank: int) -> slice:
        return slice(*self.bounds(rank))


def slab_of(field: np.ndarray, comm) -> np.ndarray:
    """This rank's rows of a whole ``field`` (a copy): for tests and small inputs, not for large grids."""
    return np.ascontiguousarray(field[Slabs(field.shape[0], comm.Get_size()).slice(comm.Get_rank())])


def gather_field(local: np.ndarray, comm, root: int = 0) -> np.ndarray | None:
    """The whole field on ``root`` from every rank's rows (None elsewhere): for tests and small grids."""
    parts = comm.gather(np.ascontiguousarray(local), root=root)
    return None if parts is None else np.concatenate(parts, axis=0)
