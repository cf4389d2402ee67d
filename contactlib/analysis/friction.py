"""Friction of a sliding rough contact: the interlocking part from the pressure's asymmetry."""

from __future__ import annotations

import numpy as np

from ..core.inputs import solver_values


def directional_slope(field: np.ndarray, *, lengths, direction: float = 0.0, periodic: bool = True) -> np.ndarray:
    """``d field / ds`` along ``s = (cos direction, sin direction)`` (1D: ``d/dx``) [field/length]:
    spectral for a periodic field, second-order central differences otherwise (exact on parabolas).

    Parameters
    ----------
    field : xarray.DataArray or ndarray
        1D or 2D field: a DataArray's x and y read by name, an ndarray indexed ``[ix, iy]``.
    lengths : sequence of float
        Window size per axis [length].
    direction : float
        Direction ``s`` [rad] (ignored in 1D).
    periodic : bool
        Spectral derivative (periodic) or central differences.

    Returns
    -------
    ndarray
        The slope field [field units / length].

    Raises
    ------
    ValueError
        Naming ``lengths`` when not finite and > 0.
    """
    field = solver_values(field, "field")
    window = np.broadcast_to(np.asarray(lengths, dtype=float), (field.ndim,))
    if not np.all(np.isfinite(window) & (window > 0)):
        raise ValueError(f"lengths must be finite and > 0, got {lengths!r}")
    spacing = [length / n for n, length in zip(field.shape, window)]
    if periodic:
        spectrum = np.fft.rfftn(field)
        axes = []
        for axis, (n, d) in enumerate(zip(field.shape, spacing)):
            last = axis == field.ndim - 1
            q = 2 * np.pi * (np.fft.rfftfreq(n, d) if last else np.fft.fftfreq(n, d))
            if n % 2 == 0:
                q[n // 2] = 0.0  # the Nyquist mode has no sign: its derivative is not representable
            axes.append(q.reshape([-1 if a == axis else 1 for a in range(field.ndim)]))
        grads = [np.fft.irfftn(1j * q * spectrum, s=field.shape, axes=range(field.ndim)) for q in axes]
    else:
        grads = np.gradient(field, *spacing) if field.ndim > 1 else [np.gradient(field, spacing[0])]
    if field.ndim == 1:
        return grads[0] * np.cos(direction)
    return grads[0] * np.cos(direction) + grads[1] * np.sin(direction)


def interlocking_friction(pressure, surface, *, lengths, direction: float = 0.0, periodic: bool = True,
                          slopes: SlopeCache | None = None) -> float:
    """Interlocking friction coefficient ``mu_a`` [1] of a rigid surface sliding along ``direction``.

    ``mu_a = -(1 / (A p_m)) * integral of p du_z/ds`` over the contact (seed 2, section 4.3), with
    ``u_z`` the normal displacement positive into the body, ``s`` the direction in which the rigid
    surface moves, ``A`` the nominal area and ``p_m`` the mean pressure. The body pushes on the rigid
    surface along its deformed normal; ``-p du_z/ds`` is that force's component against the motion,
    so ``mu_a > 0`` when the pressure sits on slopes facing the motion (it resists sliding) and
    ``mu_a < 0`` when it helps. Example: a cylinder ``h = -x^2/(2R)`` gives ``mu_a = x_c / R`` with ``x_c``
    the pressure's centroid, positive when the pressure leans to the leading side.

    ``surface`` is the body's deformed surface, ``u_z`` (``solve(...).displacement``, as :func:`contactlib.solve`
    reports ``mu_a``), or the rigid heights, equal to it on the contact up to a constant. From ``u_z`` the estimate
    is the discrete operator's own: ``sum p D u_z = p^T D M p`` with ``D`` the derivative (spectral, odd, so
    antisymmetric; central differences off a periodic window) and ``M`` the body's operator. Its symmetric part (an
    elastic body's whole operator) commutes with ``D`` and drops out exactly, so a decoupled elastic contact
    (frictionless, or ``nu = 0.5`` on a half-space) carries no tangential force to round-off, and on a steady
    viscoelastic slide ``mu_a p_m |V|`` is the power the operator dissipates
    (:func:`contactlib.analysis.traction_power`, equal to round-off). From the rigid heights the derivative misses
    that identity by its discretisation error (1e-5 to 1e-4 on a rough elastic contact, 4-15 % of a viscoelastic
    slide's dissipated power at 4 points per shortest wavelength); where the contact is resolved both agree.

    Parameters
    ----------
    pressure : xarray.DataArray or ndarray
        Pressure field [pressure]: a DataArray's x and y read by name, an ndarray indexed ``[ix, iy]``.
    surface : xarray.DataArray or ndarray
        The deformed surface's normal displacement ``u_z`` [length] (positive into the body), on the same grid
        (read as ``pressure``).
    lengths : sequence of float
        Window size per axis [length].
    direction : float
        Direction of the rigid surface's motion [rad].
    periodic : bool
        Spectral slopes (periodic) or central differences.
    slopes : SlopeCache, optional
        Keeps the surface's slope for the next call with the same surface (a speed sweep).

    Returns
    -------
    float
        ``mu_a`` [1]; 0 where the mean pressure is 0.

    Raises
    ------
    ValueError
        Naming ``lengths`` when not finite and > 0.
    """
    p = solver_values(pressure, "pressure")
    total = float(p.sum())
    if total <= 0:
        return 0.0
    if slopes is None:
        slope = directional_slope(surface, lengths=lengths, direction=direction, periodic=periodic)
    else:
        slope = slopes.slope(surface, lengths=lengths, direction=direction, periodic=periodic)
    return -float(np.sum(p * slope)) / total


class SlopeCache:
    """The last surface's :func:`directional_slope`, kept for the next :func:`interlocking_friction` with the same
    surface (a study that labels many pressures with one rigid surface): pass one as ``slopes=``. The hit is checked
    on the values, not the object, so a caller that edits its array in place gets a fresh slope; the slope is
    read-only while kept, and lives as long as its holder."""

    def __init__(self):
        self.kept: tuple | None = None  # (heights copy, key, slope)

    def slope(self, heights, *, lengths, direction: float, periodic: bool) -> np.ndarray:
        """:func:`directional_slope` of ``heights``, the kept one where the values, window, direction and periodicity
        are the same."""
        heights = solver_values(heights, "heights")
        key = (tuple(np.broadcast_to(np.asarray(lengths, dtype=float), (heights.ndim,))), float(direction),
               bool(periodic))
        if self.kept is not None:
            stored, stored_key, slope = self.kept
            if stored_key == key and stored.shape == heights.shape and np.array_equal(stored, heights):
                return slope
        slope = directional_slope(heights, lengths=lengths, direction=direction, periodic=periodic)
        slope.flags.writeable = False
        self.kept = (heights.copy(), key, slope)
        return slope
