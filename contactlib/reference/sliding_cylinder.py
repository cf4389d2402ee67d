"""Rigid cylinder sliding with Coulomb friction on an elastic half-space (plane strain).

K. L. Johnson, *Contact Mechanics* (1985), section 7.2: the pressure has exponents ``1/2 -+ gamma``
at the two edges. Everything is per unit width; numbers are unit-free (any consistent units).

Conventions (fixed)
-------------------
* ``x`` along the surface, origin at the cylinder axis (profile height ``x^2 / (2R)``). The cylinder
  moves in ``+x`` relative to the body: the leading edge is at larger ``x``.
* Pressure ``p >= 0`` compressive; the body's surface carries ``tau = +mu p`` in ``+x``.
* ``u_z`` is positive INTO the body (Johnson eqs 2.19b, 2.20b)::

      u_z(x) = -(2/(pi E*)) int p(s) ln|x-s| ds + k int tau(s) sgn(x-s) ds + const,
      E* = E/(1-nu^2),  k = (1-2nu)(1+nu)/(2E),

  so a tangential load in ``+x`` pushes the surface ahead of it into the body.
* In contact ``du_z/dx = -x/R``; ``beta = (1-2nu)/(2(1-nu))`` (so that ``2k = pi beta * 2/(pi E*)``).

Derivation
----------
Differentiating ``u_z`` and using ``tau = mu p``, the contact condition is the singular integral
equation (Carleman type) ::

      mu beta p(x) + (1/pi) PV int p(s)/(s - x) ds = -E* x / (2R)     on  -b1 < x < b2.

With ``Phi(z) = (1/(2 pi i)) int p(s)/(s - z) ds`` it becomes the Hilbert problem
``Phi+ = G Phi- + f``, ``G = (mu beta - i)/(mu beta + i) = -exp(2 pi i gamma)`` with ::

      tan(pi gamma) = +mu beta        (gamma >= 0 for mu >= 0, nu <= 1/2; |gamma| < 1/2).

The solution bounded (zero) at both edges is ``Phi = C [X(z) - z]`` with
``X = (z + b1)^(1/2-gamma) (z - b2)^(1/2+gamma)``; decay of ``Phi`` at infinity requires the constant
term of ``X`` to vanish, ``(1/2-gamma) b1 = (1/2+gamma) b2``, and ``C = -i E*/(4R)``. Hence ::

      p(x) = (E* cos(pi gamma) / (2R)) (x + b1)^(1/2-gamma) (b2 - x)^(1/2+gamma),
      P    = pi E* a^2 (1 - 4 gamma^2) / (4R)   =>   a = sqrt(4PR / (pi E* (1 - 4 gamma^2))),
      b1 = (1 + 2 gamma) a  (trailing),   b2 = (1 - 2 gamma) a  (leading),   e = (b2 - b1)/2 = -2 gamma a,

      pressure centroid  x_bar = int x p dx / P = -8 gamma a / 3,   peak pressure at x = -4 gamma a.

Signs: for ``mu > 0`` and ``nu < 1/2`` the friction pushes the surface behind the cylinder up (out of the
body) and ahead of it down, so the contact and the pressure shift toward the TRAILING edge
(``e < 0``, ``x_bar < 0``) and the interlocking friction ``mu_a = x_bar / R`` is NEGATIVE (the
inclined pressure aids sliding). At ``mu = 0`` or ``nu = 1/2``, ``gamma = 0``: Hertz's line contact.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class SlidingContact:
    """Contact of the sliding cylinder (all lengths in the cylinder's frame, axis at ``x = 0``).

    Attributes
    ----------
    a : float
        Half-width of the contact [length].
    e : float
        Offset of the contact centre from the cylinder axis, positive toward the leading edge (+x) [length].
    x_trailing, x_leading : float
        Edges of the contact, ``e - a`` and ``e + a`` [length].
    gamma : float
        Edge exponent, ``tan(pi gamma) = mu beta`` [-].
    pressure_centroid : float
        ``int x p(x) dx / P = -8 gamma a / 3`` [length].
    """

    a: float
    e: float
    x_trailing: float
    x_leading: float
    gamma: float
    pressure_centroid: float


def _check(P, R, E, nu):
    if not (P > 0 and R > 0 and E > 0):
        raise ValueError("P, R and E must be positive")
    if not -1.0 < nu <= 0.5:
        raise ValueError("nu must lie in (-1, 0.5]")


def exponent(mu: float, nu: float) -> float:
    """Edge exponent gamma of the pressure, from ``tan(pi gamma) = +mu beta``.

    Parameters
    ----------
    mu : float
        Coulomb friction coefficient [-] (``mu > 0``: friction drags the body surface in +x).
    nu : float
        Poisson ratio of the half-space [-], ``-1 < nu <= 0.5``.

    Returns
    -------
    float
        ``gamma = arctan(mu beta) / pi`` with ``beta = (1 - 2 nu) / (2 (1 - nu))`` [-]; ``|gamma| < 1/2``.
        The pressure goes as ``(x - x_trailing)^(1/2 - gamma)`` and ``(x_leading - x)^(1/2 + gamma)``.
    """
    beta = (1.0 - 2.0 * nu) / (2.0 * (1.0 - nu))
    return float(np.arctan(mu * beta) / np.pi)


def contact(P: float, R: float, E: float, nu: float, mu: float) -> SlidingContact:
    """Contact half-width, offset, edges and pressure centroid.

    Parameters
    ----------
    P : float
        Normal load per unit width [force/length].
    R : float
        Cylinder radius [length].
    E : float
        Young's modulus of the half-space [pressure].
    nu : float
        Poisson ratio [-].
    mu : float
        Coulomb friction coefficient [-].

    Returns
    -------
    SlidingContact
        ``a = sqrt(4 P R / (pi E* (1 - 4 gamma^2)))``, ``e = -2 gamma a``,
        ``x_trailing = -(1 + 2 gamma) a``, ``x_leading = (1 - 2 gamma) a``,
        ``pressure_centroid = -8 gamma a / 3``.
    """
    _check(P, R, E, nu)
    E_star = E / (1.0 - nu**2)
    g = exponent(mu, nu)
    a = float(np.sqrt(4.0 * P * R / (np.pi * E_star * (1.0 - 4.0 * g * g))))
    e = -2.0 * g * a
    return SlidingContact(a=a, e=e, x_trailing=e - a, x_leading=e + a, gamma=g,
                          pressure_centroid=-8.0 * g * a / 3.0)


def pressure(x, P: float, R: float, E: float, nu: float, mu: float):
    """Pressure field [pressure] at positions ``x`` [length] (cylinder frame), zero outside the contact.

    ``p(x) = (E* cos(pi gamma) / (2R)) (x - x_trailing)^(1/2 - gamma) (x_leading - x)^(1/2 + gamma)``,
    written as ``2 P cos(pi gamma) / (pi a^2 (1 - 4 gamma^2)) * (...)`` (same thing, since
    ``E*/R = 4P / (pi a^2 (1 - 4 gamma^2))``). Parameters as in :func:`contact`.


    Parameters
    ----------
    x : array_like
        Positions in the cylinder's frame [length].
    P : float
        Normal load per unit width [force/length].
    R : float
        Cylinder radius [length].
    E : float
        Young's modulus of the half-space [pressure].
    nu : float
        Poisson ratio [-].
    mu : float
        Coulomb friction coefficient [-].

    Returns
    -------
    numpy.ndarray
        Array of the shape of ``x``.
    """
    c = contact(P, R, E, nu, mu)
    g, a = c.gamma, c.a
    x = np.asarray(x, dtype=float)
    lead = np.clip(c.x_leading - x, 0.0, None)
    trail = np.clip(x - c.x_trailing, 0.0, None)
    amp = 2.0 * P * np.cos(np.pi * g) / (np.pi * a * a * (1.0 - 4.0 * g * g))
    return amp * trail ** (0.5 - g) * lead ** (0.5 + g)


def interlocking_friction(P: float, R: float, E: float, nu: float, mu: float) -> float:
    """Interlocking (ploughing) friction coefficient of the inclined pressure [-].

    ``mu_a = -(1/P) int p du_z/dx dx = (1/(P R)) int x p dx = pressure_centroid / R = -8 gamma a / (3R)``:
    the horizontal force the pressure exerts against the cylinder's motion, per unit load. Positive would
    resist sliding; here it is ``<= 0`` for ``mu >= 0``, ``nu <= 1/2`` (pressure sits on the trailing side).
    Parameters as in :func:`contact`.

    Parameters
    ----------
    P : float
        Normal load per unit width [force/length].
    R : float
        Cylinder radius [length].
    E : float
        Young's modulus of the half-space [pressure].
    nu : float
        Poisson ratio [-].
    mu : float
        Coulomb friction coefficient [-].

    Returns
    -------
    float
        mu_a [1], <= 0 for mu >= 0 and nu <= 1/2.
    """
    return contact(P, R, E, nu, mu).pressure_centroid / R
