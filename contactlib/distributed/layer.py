"""An elastic layer on the slabs' spectral columns: the normal compliance that the serial
:func:`contactlib.model.bodies.body_model` builds for a periodic, frictionless layer, and its reduction to the
half-space.

The layer's compliance is a Fourier multiplier (:func:`contactlib.kernels.layer.layer_factors` times the half-space's
``2 / (E* |q|)``, the uniform mode :func:`contactlib.kernels.layer.zero_mode_compliance`), so each rank evaluates it on
its own columns. As in the serial library, a layer within :data:`contactlib.model.bodies.REDUCTION_FRACTION` ``tol`` of the
half-space on every wavevector of the grid is solved as the half-space (keeping a confined layer's uniform
compression); the maximum deviation is reduced over the ranks.
"""

from __future__ import annotations

import numpy as np

from ..model.bodies import REDUCTION_FRACTION, Layer
from ..kernels.layer import layer_factors, zero_mode_compliance


def layer_transfer(comm, q: np.ndarray, *, E: float, nu: float, layer: Layer, tol: float,
                   column_start: int) -> tuple[np.ndarray, str]:
    """The normal compliance [length/pressure] on this rank's spectral columns (``q``: their wavenumbers, all rows)
    and the serial model's description (``attrs['model']``)."""
    from mpi4py import MPI  # the distributed path only

    if not 0 <= nu <= 0.5:
        raise ValueError(f"nu: a layer needs 0 <= nu <= 0.5, got {nu!r}")
    positive = q > 0
    unit = np.zeros_like(q)
    unit[positive] = 2 * (1 - nu**2) / (E * q[positive])
    X = np.where(positive, q * layer.thickness, 1.0)
    full = unit * layer_factors(X, nu, layer.base)["normal"]
    local = float(np.abs(full[positive] / unit[positive] - 1).max()) if positive.any() else 0.0
    deviation = comm.allreduce(local, op=MPI.MAX)
    zero = zero_mode_compliance(layer.thickness, E, nu, layer.base)["normal"]
    if deviation > REDUCTION_FRACTION * tol:
        transfer, note = full, f"{layer.base} layer, h = {layer.thickness:g}"
    else:
        transfer = unit
        note = (f"half-space (the {layer.base} layer of h = {layer.thickness:g} is within {deviation:.1e} of it, "
                f"<= {REDUCTION_FRACTION} tol, on this grid)")
    if column_start == 0:
        transfer[0, 0] = zero if transfer is full or zero > 0 else 0.0
    return transfer, note
