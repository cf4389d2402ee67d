"""Steady sliding on a linearly viscoelastic body: the elastic kernels times a speed-dependent compliance.

A rigid surface moving at velocity ``V`` over the body is steady in its own frame. A surface mode
``exp(i q . x)`` of that frame is, at a material point ``X = x + V t`` of the body,
``exp(i q . X) exp(-i (q . V) t)``: the material oscillates at the angular frequency
``omega(q) = -q . V`` (:func:`sliding_frequency`). With a constant Poisson ratio every Green's function
of the body is the elastic one at unit modulus times the creep compliance, so each Fourier multiplier
of the elastic body at modulus ``E0`` is multiplied by (seed 2, eqs 23 and 25)::

    factor(q) = E0 / E*(omega(q)) = E0 / conj(E*(q . V)),

with ``E*`` the material's complex modulus (:meth:`contactlib.Viscoelastic.complex_modulus`). Its real
part is even in ``q``: the symmetric, positive-definite part of the normal operator; its imaginary part
is odd: a skew part, which the coupled solver takes as it takes friction's
(:mod:`contactlib.solvers.coupled`). Sign check: a point ahead of the slider (it arrives from
``+V``) has not been loaded yet, so there the body is glassy; behind it the material is still
recovering. The pressure leans to the leading edge and the contact patches shrink at the trailing edge
(tests/test_viscoelastic.py).

The ``q = 0`` mode does not move: it is relaxed (``factor = 1``).
"""

from __future__ import annotations

import numpy as np

from ..grid import Grid


def sliding_frequency(grid: Grid, velocity) -> np.ndarray:
    """``omega(q) = -q . V`` [rad/time] on the grid's rfft layout: the angular frequency (for a time
    dependence ``exp(i omega t)``) at which the body's material sees the surface mode ``q`` when the
    rigid surface slides at ``velocity`` [length/time] (1D: ``(Vx,)``)."""
    q = grid.wavevectors()
    return -sum(qi * float(vi) for qi, vi in zip(q, velocity))


def sliding_factor(material, velocity, *q) -> np.ndarray:
    """``E0 / E*(-q . V)`` at the wavevector components ``q`` [1/length] (arrays), complex: the pointwise
    factor of :func:`steady_sliding_factor` (Love's aliased images take it at each image)."""
    return material.E0 / material.complex_modulus(-sum(qi * float(vi) for qi, vi in zip(q, velocity)))


def steady_sliding_factor(grid: Grid, material, velocity) -> np.ndarray:
    """``E0 / E*(omega(q))`` on the rfft layout [1], complex: the factor of every elastic multiplier at
    the relaxed modulus ``E0`` (module docstring). 1 at ``q = 0`` and at zero speed.

    The modes that are their own mirror image (every index 0 or Nyquist) keep the real part: a real
    transform cannot carry an imaginary multiplier there (the inverse rfft drops it).
    """
    return real_where_self_conjugate(grid, material.E0 / material.complex_modulus(sliding_frequency(grid, velocity)))


def real_where_self_conjugate(grid: Grid, multiplier: np.ndarray) -> np.ndarray:
    """``multiplier`` with its real part kept on the modes that are their own mirror image (in place)."""
    mask = _self_conjugate(grid)
    multiplier[mask] = multiplier[mask].real
    return multiplier


def _self_conjugate(grid: Grid) -> np.ndarray:
    """Mask of the rfft layout's modes equal to their own mirror image."""
    masks = []
    for axis, n in enumerate(grid.shape):
        size = grid.spectral_shape()[axis]
        index = np.arange(size)
        mask = (index == 0) | ((n % 2 == 0) & (index == n // 2))
        masks.append(mask.reshape([-1 if a == axis else 1 for a in range(grid.dim)]))
    out = masks[0]
    for m in masks[1:]:
        out = out & m
    return np.broadcast_to(out, grid.spectral_shape())


def modulus_deviation(grid: Grid, material, velocity, reference: float) -> float:
    """``max |E*(q . V) - reference| / reference`` over the grid's non-zero wavevectors [1]: how far the
    scene is from an elastic body of modulus ``reference`` (the reduction rule of
    :func:`contactlib.bodies.body_model` compares the complex modulus, not its magnitude: the loss
    modulus, which makes the friction, moves at first order in ``q V``)."""
    return modulus_deviations(grid, material, velocity, (reference,))[0]


def modulus_deviations(grid: Grid, material, velocity, references) -> tuple[float, ...]:
    """:func:`modulus_deviation` from each of ``references`` [pressure], the complex modulus evaluated once
    (it is most of the cost: one per speed of a sweep instead of two)."""
    omega = sliding_frequency(grid, velocity)
    nonzero = grid.wavenumber() > 0
    if not nonzero.any():
        return tuple(0.0 for _ in references)
    modulus = material.complex_modulus(omega[nonzero])
    return tuple(float(np.abs(modulus - reference).max() / reference) for reference in references)
