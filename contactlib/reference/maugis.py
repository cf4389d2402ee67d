"""The Maugis-Dugdale sphere: Maugis, J. Colloid Interface Sci. 150, 243-269 (1992), doi:10.1016/0021-9797(92)90285-T.

A rigid sphere (paraboloid of radius ``R``) on an elastic half-space of contact modulus ``E_star = E / (1 - nu^2)``,
``K = 4 E* / 3``, with a Dugdale (constant) adhesive stress ``sigma_0`` over a gap of ``w / sigma_0``; eqs. (6.17),
(6.19), (6.21) in the dimensionless variables ``A = a (K / (pi w R^2))^(1/3)``, ``P = P / (pi w R)``,
``D = d (K^2 / (pi^2 w^2 R))^(1/3)``, ``lambda = 2 sigma_0 (R / (pi w K^2))^(1/3)``, ``m = c / a`` (``c`` the outer
radius of the Dugdale zone). Its limits, JKR (``lambda -> infinity``) and the extrapolation to it, are in
:mod:`contactlib.reference.adhesive`.
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import brentq


def maugis_parameter(*, radius: float, E_star: float, work: float, peak_stress: float) -> float:
    """``lambda = 2 sigma_0 (R / (pi w K^2))^(1/3)``.

    Parameters
    ----------
    radius : float
        Sphere radius R [length].
    E_star : float
        Contact modulus E* = E / (1 - nu^2) [pressure].
    work : float
        Work of adhesion w [pressure length].
    peak_stress : float
        The Dugdale stress sigma_0 [pressure].

    Returns
    -------
    float
        The Maugis parameter lambda (K = 4 E* / 3) [1].
    """
    K = 4 * E_star / 3
    return float(2 * peak_stress * (radius / (np.pi * work * K**2)) ** (1 / 3))


def maugis_zone_ratio(A: float, lam: float) -> float:
    """``m = c / a`` solving Maugis' eq. (6.21) at dimensionless contact radius ``A`` and ``lambda``.

    Parameters
    ----------
    A : float
        Dimensionless contact radius a (K / (pi w R^2))^(1/3).
    lam : float
        Maugis parameter lambda.

    Returns
    -------
    float
        The ratio m = c / a of the cohesive zone's outer radius to the contact radius.

    Raises
    ------
    ValueError
        When no root m > 1 is bracketed.
    """
    def f(m):
        s = np.sqrt(m * m - 1)
        t = np.arctan(s)
        return (lam * A**2 / 2 * (s + (m * m - 2) * t) + 4 * lam**2 * A / 3 * (s * t - m + 1)) - 1

    hi = 2.0
    while f(hi) < 0:
        hi *= 2
        if hi > 1e8:
            raise ValueError("maugis_zone_ratio: no zone found")
    return brentq(f, 1.0, hi, xtol=1e-14, rtol=1e-13)


def maugis_load_penetration(A, lam: float) -> tuple[np.ndarray, np.ndarray]:
    """Dimensionless load ``P / (pi w R)`` and approach ``D`` of the Maugis-Dugdale sphere at dimensionless
    contact radii ``A`` (eqs. 6.17, 6.19).

    Parameters
    ----------
    A : float or array_like
        Dimensionless contact radii.
    lam : float
        Maugis parameter lambda.

    Returns
    -------
    P : ndarray
        Dimensionless load P / (pi w R).
    D : ndarray
        Dimensionless approach.
    """
    A = np.atleast_1d(np.asarray(A, dtype=float))
    P, D = np.empty_like(A), np.empty_like(A)
    for i, a in enumerate(A):
        m = maugis_zone_ratio(a, lam)
        s = np.sqrt(m * m - 1)
        P[i] = a**3 - lam * a**2 * (s + m * m * np.arctan(s))
        D[i] = a**2 - 4 / 3 * lam * a * s
    return P, D


def maugis_load(contact_radius, *, radius: float, E_star: float, work: float, peak_stress: float):
    """Maugis-Dugdale load [force] at contact radius ``a`` [length] (the repulsive contact, inside the zone).

    Parameters
    ----------
    contact_radius : float or array_like
        Contact radius a [length].
    radius : float
        Sphere radius R [length].
    E_star : float
        Contact modulus E* = E / (1 - nu^2) [pressure].
    work : float
        Work of adhesion w [pressure length].
    peak_stress : float
        The Dugdale stress sigma_0 [pressure].

    Returns
    -------
    float or ndarray
        The load [force].
    """
    K = 4 * E_star / 3
    lam = maugis_parameter(radius=radius, E_star=E_star, work=work, peak_stress=peak_stress)
    A = np.asarray(contact_radius, dtype=float) * (K / (np.pi * work * radius**2)) ** (1 / 3)
    return maugis_load_penetration(A, lam)[0] * np.pi * work * radius


def maugis_at_penetration(penetration: float, *, lam: float, radius: float, E_star: float,
                          work: float) -> tuple[float, float]:
    """The Maugis-Dugdale sphere's load [force] and contact radius [length] at the approach ``penetration`` [length],
    on the branch of the largest contact (the root of the approach of eq. 6.19 for dimensionless radii in 0.3-6).

    Parameters
    ----------
    penetration : float
        The approach d [length], positive into the body.
    lam : float
        Maugis parameter lambda.
    radius : float
        Sphere radius R [length].
    E_star : float
        Contact modulus E* = E / (1 - nu^2) [pressure].
    work : float
        Work of adhesion w [pressure length].

    Returns
    -------
    (float, float)
        The load P [force] (tensile negative) and the contact radius a [length].
    """
    K = 4 * E_star / 3
    target = penetration / (np.pi**2 * work**2 * radius / K**2) ** (1 / 3)
    A = brentq(lambda a: maugis_load_penetration(a, lam)[1][0] - target, 0.3, 6.0, xtol=1e-13)
    return (float(maugis_load_penetration(A, lam)[0][0]) * np.pi * work * radius,
            A * (np.pi * work * radius**2 / K) ** (1 / 3))


def maugis_pull_off(lam: float) -> float:
    """Dimensionless pull-off force ``P_c / (pi w R)`` of the Maugis-Dugdale sphere under load control:
    the minimum of the load over the contact radius.

    Parameters
    ----------
    lam : float
        Maugis parameter lambda.

    Returns
    -------
    float
        P_c / (pi w R), between -2 (Bradley) and -1.5 (JKR).
    """
    from scipy.optimize import minimize_scalar

    res = minimize_scalar(lambda A: maugis_load_penetration(A, lam)[0][0], bounds=(1e-3, 5.0), method="bounded",
                          options={"xatol": 1e-10})
    return float(res.fun)
