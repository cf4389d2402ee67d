"""The one spatial and spectral grid vocabulary.

A :class:`Grid` is a periodic box of ``shape`` points over ``lengths`` (1D or 2D).
Wavevectors follow numpy's ``rfftfreq`` layout on the last axis, so every
Fourier-space kernel in :mod:`contactlib.kernels` is a function of the arrays
returned by :meth:`Grid.wavevectors`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Grid:
    """Regular periodic grid.

    Parameters
    ----------
    shape : tuple of int
        Points per axis, ``(n,)`` for a profile or ``(nx, ny)`` for a surface.
    lengths : tuple of float
        Physical size of the box along each axis [length].
    """

    shape: tuple[int, ...]
    lengths: tuple[float, ...]

    def __post_init__(self):
        if len(self.shape) not in (1, 2) or len(self.shape) != len(self.lengths):
            raise ValueError(f"shape {self.shape} and lengths {self.lengths} must both be 1D or 2D")
        for n in self.shape:
            if int(n) < 2:
                raise ValueError(f"grid shape {self.shape}: need at least 2 points per axis")
        for length in self.lengths:
            if not np.isfinite(length) or length <= 0:
                raise ValueError(f"length must be finite and > 0, got {self.lengths}")

    @property
    def dim(self) -> int:
        return len(self.shape)

    @property
    def spacing(self) -> tuple[float, ...]:
        """Grid spacing per axis [length]."""
        return tuple(length / n for n, length in zip(self.shape, self.lengths))

    @property
    def size(self) -> int:
        return int(np.prod(self.shape))

    @property
    def element_area(self) -> float:
        """Area (2D) or width (1D) of one boundary element [length^dim]."""
        return float(np.prod(self.spacing))

    def coordinates(self) -> tuple[np.ndarray, ...]:
        """Cell-centre-free node coordinates ``i * dx`` per axis [length]."""
        return tuple(np.arange(n) * d for n, d in zip(self.shape, self.spacing))

    def wavevectors(self) -> tuple[np.ndarray, ...]:
        """Angular wavevector components on the rfft layout [1/length].

        Returns broadcastable arrays: ``(qx,)`` in 1D, ``(qx[:, None], qy[None, :])`` in 2D,
        where the last axis holds the non-negative half (``rfftfreq``).
        """
        d = self.spacing
        if self.dim == 1:
            return (2 * np.pi * np.fft.rfftfreq(self.shape[0], d[0]),)
        qx = 2 * np.pi * np.fft.fftfreq(self.shape[0], d[0])
        qy = 2 * np.pi * np.fft.rfftfreq(self.shape[1], d[1])
        return qx[:, None], qy[None, :]

    def wavenumber(self) -> np.ndarray:
        """Modulus ``|q|`` on the rfft layout [1/length]."""
        q = self.wavevectors()
        return np.sqrt(sum(c**2 for c in q)) if self.dim == 2 else np.abs(q[0])

    def spectral_shape(self) -> tuple[int, ...]:
        """Shape of an rfft of a field on this grid."""
        return self.shape[:-1] + (self.shape[-1] // 2 + 1,)

    def padded(self) -> "Grid":
        """The doubled grid used to embed a non-periodic problem (zero padding)."""
        return Grid(tuple(2 * n for n in self.shape), tuple(2 * length for length in self.lengths))
