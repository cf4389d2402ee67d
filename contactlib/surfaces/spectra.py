"""Power spectral densities of self-affine surfaces, as functions of the wavevector grid."""

from __future__ import annotations

import numpy as np

# A grid's wavenumbers q = 2 pi m / L are rounded, so a mode that lies on a band edge (k = q / q0 = 1, say) comes out
# an ulp or two either side of it, which side depending on L. Within EDGE_TOLERANCE (in units of q0) of an edge a mode
# counts as on it: rounding errors are ~1e-16 k, far below it for any grid, while a lattice mode off an integer edge
# e lies at least ~1 / (2 e) from it, far above it.
EDGE_TOLERANCE = 1e-9


def self_affine_psd(q, *, q0: float, hurst: float, q_low: float, q_roll: float, q_cutoff: float, dim: int = 2):
    """Unnormalised self-affine PSD (amplitude 1 on the plateau).

    ``C(q) = 1`` for ``q_low <= q/q0 < q_roll``, ``(q / (q_roll q0))^-(dim + 2 H)`` up to
    ``q_cutoff``, zero elsewhere (so the mean height is zero). ``q`` [1/length] may be an
    effective (stretched) wavenumber for anisotropic surfaces. A mode within ``EDGE_TOLERANCE``
    (1e-9 of ``q0``) of ``q_low`` or ``q_cutoff`` is in the band, so the rounding of ``q`` never
    moves a mode on an edge out of it, whatever the window length.

    Parameters
    ----------
    q : float or array_like
        Wavenumber [1/length] (or an effective, stretched one).
    q0 : float
        Fundamental wavenumber ``2 pi / length`` [1/length].
    hurst : float
        Hurst exponent H.
    q_low, q_roll, q_cutoff : float
        Band edges as multiples of ``q0``.
    dim : {1, 2}
        Dimension of the surface (the exponent is ``-(dim + 2 H)``).

    Returns
    -------
    ndarray
        ``C(q)``, 1 on the plateau.
    """
    k = np.asarray(q) / q0
    exponent = -(dim + 2.0 * hurst)
    with np.errstate(divide="ignore"):
        c = np.where(k < q_roll, 1.0, (k / q_roll) ** exponent)
    in_band = (k >= q_low - EDGE_TOLERANCE) & (k <= q_cutoff + EDGE_TOLERANCE) & (k > 0)
    return np.where(in_band, c, 0.0)


def stretched_wavenumber(qx, qy, *, anisotropy: float, angle: float):
    """``|A R q|``: the wavevector rotated by ``angle`` and its normal component stretched by
    ``anisotropy**-1/2``, so the slope tensor's eigenvalue ratio is ``anisotropy`` and its
    principal (steepest) direction is ``angle``."""
    q1 = qx * np.cos(angle) + qy * np.sin(angle)
    q2 = -qx * np.sin(angle) + qy * np.cos(angle)
    return np.sqrt(q1**2 + q2**2 / anisotropy)
