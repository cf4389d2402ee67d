"""Steady viscoelastic sliding of a periodic profile, in real space: the second route to the spectral kernel.

Seed 2, eq 25 (its normal-normal entry): in steady sliding at speed ``V`` the displacement at ``x`` due
to a unit load at the origin of the slider's frame is ::

    G_V(x) = J(0+) G1(x) + int_0^inf G1(x + V t) dJ/dt dt,

the material point now at ``x`` having been at ``x + V t`` a time ``t`` ago (the slider moves in ``+x``
relative to the body), ``G1`` the elastic Green's function at unit modulus and ``J`` the creep function
(:meth:`contactlib.Viscoelastic.creep`). Here ``G1`` is the periodic response at the nodes to a uniform
pressure on one element (Love's element, the ``kernel="love"`` discretisation of :func:`contactlib.solve`)
in closed form with Clausen's function (:func:`clausen2`), and the time integral is a Gauss-Legendre
quadrature over panels between element edges, one period of ``x + V t`` at a time (the
exponentials of the creep rate sum the periods as a geometric series). Nothing comes from a Fourier
multiplier: the dense, non-symmetric influence matrix built from ``G_V`` is solved by the seed's
active-set method (:func:`contactlib.solvers.solve_active_set`).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.special import bernoulli, factorial

from ..solvers import ContactState, solve_active_set

_TERMS = 30
_B = np.abs(bernoulli(2 * _TERMS)[2::2])  # |B_2|, |B_4|, ...
_K = np.arange(1, _TERMS + 1)
_COEFFICIENTS = _B / (2 * _K * (2 * _K + 1) * factorial(2 * _K))


def clausen2(theta):
    """Clausen's function ``Cl2(theta) = -int_0^theta ln|2 sin(t/2)| dt = sum_k sin(k theta)/k^2``.

    Reduced to ``[-pi, pi]`` (odd, ``2 pi``-periodic), then its series
    ``theta - theta ln|theta| + sum_k |B_2k| theta^(2k+1) / (2k (2k+1) (2k)!)`` (converges for
    ``|theta| < 2 pi``; 30 terms reach round-off at ``pi``).

    Parameters
    ----------
    theta : float or array_like
        Angle [rad].

    Returns
    -------
    ndarray
        Cl2(theta).
    """
    t = np.asarray(theta, dtype=float)
    t = t - 2 * np.pi * np.round(t / (2 * np.pi))
    a = np.abs(t)
    with np.errstate(divide="ignore", invalid="ignore"):
        log_term = np.where(a > 0, a * np.log(a), 0.0)
    t2 = t * t
    series = np.zeros_like(t)
    for c in _COEFFICIENTS[::-1]:  # Horner in theta^2
        series = series * t2 + c
    return np.sign(t) * (a - log_term) + series * t2 * t


def element_influence(x, *, length: float, n: int, nu: float) -> np.ndarray:
    """Periodic normal displacement at ``x`` [length] (any positions) due to a unit uniform pressure on the
    element ``|x| < dx/2`` (``dx = length/n``) of a half-space of unit Young's modulus, zero-mean
    [length/pressure]: ``-(2 (1 - nu^2)/pi) int ln|2 sin(pi (x - s)/length)| ds``.

    Parameters
    ----------
    x : array_like
        Positions [length].
    length : float
        Period of the profile [length].
    n : int
        Number of elements over the period.
    nu : float
        Poisson ratio.

    Returns
    -------
    ndarray
        The displacement at ``x`` [length/pressure].
    """
    dx = length / n
    x = np.asarray(x, dtype=float)
    a, b = 2 * np.pi * (x - dx / 2) / length, 2 * np.pi * (x + dx / 2) / length
    return -(2 * (1 - nu**2) / np.pi) * (length / (2 * np.pi)) * (clausen2(a) - clausen2(b))


def steady_sliding_influence(n: int, *, length: float, material, velocity: float, order: int = 12) -> np.ndarray:
    """``G_V`` at the node offsets ``0, dx, ..., (n-1) dx`` [length/pressure] (module docstring).

    ``order`` Gauss-Legendre points per panel; panels run between element edges, and where the creep's
    decay length ``V lambda_j`` is shorter than an element the first panels are split geometrically.

    Parameters
    ----------
    n : int
        Number of elements.
    length : float
        Period [length].
    material : contactlib.Viscoelastic
        The body.
    velocity : float
        Sliding velocity [length/time].
    order : int
        Gauss-Legendre points per panel.

    Returns
    -------
    ndarray
        ``G_V`` at the ``n`` node offsets [length/pressure].
    """
    dx = length / n
    offsets = np.arange(n) * dx
    speed = abs(float(velocity))
    if speed == 0:
        return float(material.creep(1e300)) * element_influence(offsets, length=length, n=n, nu=material.nu)
    sign = 1.0 if velocity > 0 else -1.0
    glassy = float(material.creep(0.0))
    out = glassy * element_influence(offsets, length=length, n=n, nu=material.nu)
    nodes, weights = np.polynomial.legendre.leggauss(order)
    times, amplitudes = material.retardation()
    for lam, D in zip(times, amplitudes):
        decay = speed * lam  # [length]: the creep rate decays as exp(-sigma / decay) along sigma = V t
        edges = np.concatenate([[0.0], dx / 2 + dx * np.arange(n), [length]])
        if decay < dx:  # resolve the fast exponential inside the first element
            fine = decay * np.geomspace(1e-3, 40, 40)
            edges = np.unique(np.concatenate([edges, fine[fine < length]]))
        lo, hi = edges[:-1], edges[1:]
        sigma = (0.5 * (hi - lo)[:, None] * nodes + 0.5 * (hi + lo)[:, None]).ravel()
        w = (0.5 * (hi - lo)[:, None] * weights).ravel()
        rate = D / decay * np.exp(-sigma / decay) * w
        periods = 1.0 / -math.expm1(-length / decay)
        for i, x in enumerate(offsets):
            out[i] += periods * np.dot(rate, element_influence(x + sign * sigma, length=length, n=n,
                                                               nu=material.nu))
    return out


class CirculantOperator:
    """A dense periodic influence matrix ``A[i, j] = influence[(i - j) mod n]`` applied by matrix
    products (no FFT): the operator interface :func:`contactlib.solvers.solve_active_set` takes.

    Parameters
    ----------
    influence : ndarray
        First column of the circulant matrix.
    """

    periodic = True

    def __init__(self, influence: np.ndarray):
        n = influence.size
        self.influence = np.asarray(influence, dtype=float)
        self._index = (np.arange(n)[:, None] - np.arange(n)[None, :]) % n
        self._dense = self.influence[self._index]

    def matrix(self, flat_indices) -> np.ndarray:
        idx = np.asarray(flat_indices)
        return self._dense[np.ix_(idx, idx)]

    def __call__(self, pressure: np.ndarray) -> np.ndarray:
        return self._dense @ pressure


def solve_profile(heights, *, length: float, material, velocity: float, mean_pressure: float,
                  tol: float = 1e-10) -> ContactState:
    """The contact of a periodic profile ``heights`` [length] sliding at ``velocity`` [length/time] on a
    ``material`` half-space under ``mean_pressure`` [pressure], by this module's route: real-space
    ``G_V`` and the active-set method.

    Parameters
    ----------
    heights : ndarray
        Profile heights [length], periodic.
    length : float
        Period [length].
    material : contactlib.Viscoelastic
        The body.
    velocity : float
        Sliding velocity [length/time].
    mean_pressure : float
        Mean pressure [pressure].
    tol : float
        Tolerance of the active-set solve.

    Returns
    -------
    contactlib.solvers.ContactState
        The solved state.
    """
    heights = np.asarray(heights, dtype=float)
    operator = CirculantOperator(steady_sliding_influence(heights.size, length=length, material=material,
                                                          velocity=velocity))
    return solve_active_set(operator, heights, mean_pressure=mean_pressure, tol=tol)
