"""Energy of steady viscoelastic sliding: the power the body dissipates.

In the frame of the rigid surface the fields are steady, so at a material point ``du/dt = -V . grad u``
and the power the surface tractions put into the body, per unit area, is
``P = mean(t . (-V . grad u))``. In Fourier space, with ``u(q) = M(q) t(q)`` and
``M = (elastic tensor at E0) x E0 / E*(-q . V)`` (:mod:`contactlib.kernels.viscoelastic`)::

    P = sum_q (q . V) Im[t(q)^H M(q) t(q)] / n^2,

and for a normal load alone, written with the displacement spectrum and the loss modulus
``E''`` [pressure] instead of the pressure (:func:`dissipated_power`)::

    P = sum_q (q . V) E''(q . V) |u(q)|^2 / C1(q) / n^2,

``C1`` the elastic normal compliance at unit modulus. In steady state all of it is dissipated
(nothing is stored over a period), so it equals the friction force times the speed: the energy balance
that tests/test_viscoelastic.py checks against the interlocking friction.
"""

from __future__ import annotations

import numpy as np
import scipy.fft

from ..core.grid import Grid
from ..kernels.nyquist import even_on_nyquist, nyquist_planes, wavevector_along
from ..kernels.tensor import surface_green_tensor
from .statistics import half_spectrum_weights, values_and_grid


def _along(grid: Grid, velocity) -> np.ndarray:
    """``q . V`` [rad/time] on the rfft layout, even on the Nyquist planes (:mod:`contactlib.kernels.nyquist`): the
    rate ``-V . grad`` of a steady field, whose multiplier is odd, as the body's operator takes it."""
    return wavevector_along(grid, velocity)


def dissipated_power(displacement, *, material, sliding_velocity, length=None, layer=None) -> float:
    """Power dissipated per unit area [pressure length/time] by a body under a steady sliding normal
    load, from its normal surface ``displacement`` [length] and the material's loss modulus (module
    docstring). Frictionless: a Coulomb traction adds its own work (the solver's
    ``dissipated_power`` includes it).

    Parameters
    ----------
    displacement : DataArray or ndarray
        Normal surface displacement, periodic, positive into the body (``solve(...).displacement``).
    material : contactlib.Viscoelastic or contactlib.Elastic
    sliding_velocity : sequence of float
        Velocity of the rigid surface relative to the body [length/time], one component per axis.
    length : float or tuple, optional
        Window size for an ndarray.
    layer : contactlib.Layer, optional
        The layer the displacement is on (its normal compliance replaces the half-space's).

    Returns
    -------
    float
        The dissipated power per unit area [pressure length/time].

    Raises
    ------
    ValueError
        Naming ``material`` (not a material) or ``sliding_velocity`` (not one finite component per axis).
    """
    if not (hasattr(material, "complex_modulus") and hasattr(material, "nu")):
        raise ValueError(f"material must be a contactlib.Viscoelastic or contactlib.Elastic, got {material!r}")
    values, grid = values_and_grid(displacement, length)
    velocity = np.asarray(sliding_velocity, dtype=float).ravel()
    if velocity.shape != (grid.dim,) or not np.all(np.isfinite(velocity)):
        raise ValueError(f"sliding_velocity must be {grid.dim} finite component(s), got {sliding_velocity!r}")
    along = _along(grid, velocity)
    unit = surface_green_tensor(grid, 1.0, material.nu, *((layer.thickness, layer.base) if layer else ()))
    nonzero = grid.wavenumber() > 0
    loss = np.zeros(grid.spectral_shape())
    loss[nonzero] = _body_modulus(grid, material, velocity)[nonzero].imag / unit.normal[nonzero]
    power = np.abs(np.fft.rfftn(values)) ** 2 * half_spectrum_weights(grid)
    return float(np.sum(power * along * loss) / grid.size**2)


def _body_modulus(grid: Grid, material, velocity) -> np.ndarray:
    """``E*(q . V)`` [pressure] on the rfft layout as the body's operator holds it: on the Nyquist planes its
    compliance ``1 / E*`` is the mean over the signs of the Nyquist components (as
    :func:`contactlib.kernels.viscoelastic.steady_sliding_factor` takes the factor ``E0 / conj E*``)."""
    def modulus(*q):
        return material.complex_modulus(sum(qi * float(v) for qi, v in zip(q, velocity)))

    values = modulus(*grid.wavevectors())
    planes = nyquist_planes(grid)
    compliance = even_on_nyquist(grid, lambda *q: 1.0 / modulus(*q), np.zeros(values.shape, dtype=complex))
    values[planes] = 1.0 / compliance[planes]
    return values


def traction_power(grid: Grid, pressure: np.ndarray, tensor, sliding_velocity, *, friction: float = 0.0,
                   direction: float = 0.0) -> float:
    """``sum_q (q.V) Im[t^H M t] / n^2`` [pressure length/time]: the power per unit area of the traction
    ``t = (mu p s, p)`` on a body whose (complex) Green's tensor is ``tensor`` (module docstring).

    With ``t`` along ``s`` the normal-tangential terms cancel in ``t^H M t``, leaving
    ``|p|^2 (Czz + mu^2 (Cxx (n . s)^2 + Canti (t . s)^2))`` with ``n = q/|q|``, ``t`` across it.

    Parameters
    ----------
    grid : contactlib.Grid
        The periodic grid.
    pressure : ndarray
        Normal pressure [pressure].
    tensor : contactlib.kernels.tensor.GreenTensor
        The body's (complex) surface Green's tensor.
    sliding_velocity : sequence of float
        Velocity of the rigid surface [length/time].
    friction : float
        Coulomb coefficient ``mu``.
    direction : float
        Sliding direction [rad].

    Returns
    -------
    float
        The power per unit area [pressure length/time].
    """
    spectrum = scipy.fft.rfftn(pressure)  # numpy's transform, 3x faster (1 ms at 512^2): once per labelled solve
    form = tensor.normal
    if friction > 0:
        k = grid.wavenumber()
        safe = np.where(k > 0, k, 1.0)
        if grid.dim == 1:
            form = form + friction**2 * tensor.inplane
        else:
            qx, qy = grid.wavevectors()
            along = (qx * np.cos(direction) + qy * np.sin(direction)) / safe
            form = form + friction**2 * (tensor.inplane * along**2 + tensor.antiplane * (1 - along**2))
    power = np.abs(spectrum) ** 2 * half_spectrum_weights(grid)
    return float(np.sum(power * _along(grid, sliding_velocity) * np.imag(form)) / grid.size**2)
