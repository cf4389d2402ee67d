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
(:mod:`contactlib.solvers.nonsymmetric.coupled`). Sign check: a point ahead of the slider (it arrives from
``+V``) has not been loaded yet, so there the body is glassy; behind it the material is still
recovering. The pressure leans to the leading edge and the contact patches shrink at the trailing edge
(tests/test_viscoelastic.py).

The ``q = 0`` mode does not move: it is relaxed (``factor = 1``).
"""

from __future__ import annotations

import itertools
from functools import partial

import numba
import numpy as np

from ..core.grid import Grid
from .nyquist import even_on_nyquist


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

    Its imaginary part is odd in ``q``: on the Nyquist planes it is the mean over the signs of the Nyquist
    components (:func:`.nyquist.even_on_nyquist`), so that a mirrored scene gives the mirrored answer. On the
    modes that are their own mirror image (every index 0 or Nyquist) that mean is real, as a real transform
    needs (the inverse rfft drops an imaginary part there).
    """
    return sliding_factor_and_deviations(grid, material, velocity, ())[0]


def sliding_factor_and_deviations(grid: Grid, material, velocity, references) -> tuple[np.ndarray, tuple]:
    """``(steady_sliding_factor, modulus_deviations)`` from one evaluation of the complex modulus: a compiled
    pass over the grid (:func:`_modulus_pass`) instead of about fifteen numpy ones, two of them over the
    complex modulus. ``references`` [pressure] as :func:`modulus_deviations`."""
    omega = np.ascontiguousarray(sliding_frequency(grid, velocity), dtype=float).reshape(-1)
    factor = np.empty(omega.size, dtype=complex)
    moduli = np.array([E for E, _ in material.prony], dtype=float)
    taus = np.array([tau for _, tau in material.prony], dtype=float)
    refs = np.array(references, dtype=float)
    deviations = _modulus_pass(omega, float(material.E0), moduli, taus, refs, factor)
    factor = even_on_nyquist(grid, partial(sliding_factor, material, velocity), factor.reshape(grid.spectral_shape()))
    factor = real_where_self_conjugate(grid, factor)  # the mean is real there, to round-off: exactly so
    return factor, tuple(float(d) for d in deviations)


@numba.njit(cache=True, nogil=True, boundscheck=False)
def _modulus_pass(omega, E0, moduli, taus, references, factor):
    """``factor = E0 / E*(omega)`` (a Prony series: ``E* = E0 + sum_k E_k i omega tau_k / (1 + i omega tau_k)``),
    and ``max |E* - r| / r`` over every entry but the first (``q = 0`` in the rfft layout) for each reference
    ``r``, in one pass with the real and imaginary parts kept apart."""
    deviations = np.zeros(references.size)
    for i in range(omega.size):
        re = E0
        im = 0.0
        for k in range(moduli.size):
            x = omega[i] * taus[k]
            if abs(x) <= 1.0:
                d = moduli[k] / (1.0 + x * x)
                re += d * x * x
                im += d * x
            else:  # in 1/x: x * x overflowed past omega tau 1e154, and 0 * inf made the modulus NaN
                re += moduli[k] / (1.0 + 1.0 / (x * x))
                im += moduli[k] / (x + 1.0 / x)
        norm = re * re + im * im
        factor[i] = complex(E0 * re / norm, -E0 * im / norm)
        if i > 0:
            for j in range(references.size):
                dev = np.sqrt((re - references[j]) ** 2 + im * im) / references[j]
                if dev > deviations[j]:
                    deviations[j] = dev
    return deviations


def real_where_self_conjugate(grid: Grid, multiplier: np.ndarray) -> np.ndarray:
    """``multiplier`` with its real part kept on the modes that are their own mirror image (in place)."""
    for index in _self_conjugate(grid):
        multiplier[index] = multiplier[index].real
    return multiplier


def _self_conjugate(grid: Grid) -> list[tuple[int, ...]]:
    """The rfft layout's modes equal to their own mirror image (every index 0 or Nyquist): at most ``2^dim``."""
    per_axis = [(0,) if n % 2 else (0, n // 2) for n in grid.shape]
    return list(itertools.product(*per_axis))


def modulus_deviation(grid: Grid, material, velocity, reference: float) -> float:
    """``max |E*(q . V) - reference| / reference`` over the grid's non-zero wavevectors [1]: how far the
    scene is from an elastic body of modulus ``reference`` (the reduction rule of
    :func:`contactlib.model.bodies.body_model` compares the complex modulus, not its magnitude: the loss
    modulus, which makes the friction, moves at first order in ``q V``)."""
    return modulus_deviations(grid, material, velocity, (reference,))[0]


def modulus_deviations(grid: Grid, material, velocity, references) -> tuple[float, ...]:
    """:func:`modulus_deviation` from each of ``references`` [pressure], the complex modulus evaluated once
    (it is most of the cost: one per speed of a sweep instead of two)."""
    return sliding_factor_and_deviations(grid, material, velocity, references)[1]
