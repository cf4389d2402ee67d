"""Adhesive contact references: the JKR and Maugis-Dugdale spheres, Johnson's (1995) wavy profile.

Rigid sphere (paraboloid of radius ``R``) on an elastic half-space of contact modulus
``E_star = E / (1 - nu^2)``, work of adhesion ``w``; ``K = 4 E* / 3``.

* JKR: Johnson, Kendall & Roberts, Proc. R. Soc. A 324, 301-313 (1971), doi:10.1098/rspa.1971.0141;
  Johnson, *Contact Mechanics* (1985), section 5.5.
* Maugis-Dugdale: Maugis, J. Colloid Interface Sci. 150, 243-269 (1992),
  doi:10.1016/0021-9797(92)90285-T, eqs. (6.17), (6.19), (6.21) in the dimensionless variables
  ``A = a (K / (pi w R^2))^(1/3)``, ``P = P / (pi w R)``, ``D = d (K^2 / (pi^2 w^2 R))^(1/3)``,
  ``lambda = 2 sigma_0 (R / (pi w K^2))^(1/3)``, ``m = c / a`` (``c`` the outer radius of the Dugdale zone).
* Wavy profile ``h = amplitude cos(2 pi x / wavelength)`` on a half-space in plane strain: Johnson,
  Int. J. Solids Struct. 32, 423-430 (1995), doi:10.1016/0020-7683(94)00111-9.
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import brentq


def jkr_load(contact_radius, *, radius: float, E_star: float, work: float):
    """JKR load ``P = 4 E* a^3 / (3 R) - sqrt(8 pi w E* a^3)`` [force] at contact radius ``a`` [length]."""
    a = np.asarray(contact_radius, dtype=float)
    return 4 * E_star * a**3 / (3 * radius) - np.sqrt(8 * np.pi * work * E_star * a**3)


def jkr_penetration(contact_radius, *, radius: float, E_star: float, work: float):
    """JKR approach ``d = a^2 / R - sqrt(2 pi w a / E*)`` [length] at contact radius ``a``."""
    a = np.asarray(contact_radius, dtype=float)
    return a**2 / radius - np.sqrt(2 * np.pi * work * a / E_star)


def jkr_pull_off(*, radius: float, work: float) -> float:
    """Pull-off force under load control, ``-3/2 pi w R`` [force] (the most tensile load of the curve)."""
    return -1.5 * np.pi * work * radius


def jkr_pull_off_radius(*, radius: float, E_star: float, work: float) -> float:
    """Contact radius at pull-off under load control, ``(9 pi w R^2 / (8 E*))^(1/3)`` [length]."""
    return float((9 * np.pi * work * radius**2 / (8 * E_star)) ** (1 / 3))


def maugis_parameter(*, radius: float, E_star: float, work: float, peak_stress: float) -> float:
    """``lambda = 2 sigma_0 (R / (pi w K^2))^(1/3)``."""
    K = 4 * E_star / 3
    return float(2 * peak_stress * (radius / (np.pi * work * K**2)) ** (1 / 3))


def maugis_zone_ratio(A: float, lam: float) -> float:
    """``m = c / a`` solving Maugis' eq. (6.21) at dimensionless contact radius ``A`` and ``lambda``."""
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
    contact radii ``A`` (eqs. 6.17, 6.19)."""
    A = np.atleast_1d(np.asarray(A, dtype=float))
    P, D = np.empty_like(A), np.empty_like(A)
    for i, a in enumerate(A):
        m = maugis_zone_ratio(a, lam)
        s = np.sqrt(m * m - 1)
        P[i] = a**3 - lam * a**2 * (s + m * m * np.arctan(s))
        D[i] = a**2 - 4 / 3 * lam * a * s
    return P, D


def maugis_load(contact_radius, *, radius: float, E_star: float, work: float, peak_stress: float):
    """Maugis-Dugdale load [force] at contact radius ``a`` [length] (the repulsive contact, inside the zone)."""
    K = 4 * E_star / 3
    lam = maugis_parameter(radius=radius, E_star=E_star, work=work, peak_stress=peak_stress)
    A = np.asarray(contact_radius, dtype=float) * (K / (np.pi * work * radius**2)) ** (1 / 3)
    return maugis_load_penetration(A, lam)[0] * np.pi * work * radius


def maugis_pull_off(lam: float) -> float:
    """Dimensionless pull-off force ``P_c / (pi w R)`` of the Maugis-Dugdale sphere under load control:
    the minimum of the load over the contact radius."""
    from scipy.optimize import minimize_scalar

    res = minimize_scalar(lambda A: maugis_load_penetration(A, lam)[0][0], bounds=(1e-3, 5.0), method="bounded",
                          options={"xatol": 1e-10})
    return float(res.fun)


def jkr_limit(value_1, lam_1: float, value_2, lam_2: float):
    """The ``lambda -> infinity`` (JKR) limit of a Maugis-Dugdale quantity known at two transition parameters,
    by Richardson extrapolation in ``1 / lambda^2``: ``(lam_2^2 v_2 - lam_1^2 v_1) / (lam_2^2 - lam_1^2)``.

    Why ``1 / lambda^2``: for large ``lambda`` the zone ratio of eq. (6.21) has ``s = sqrt(m^2 - 1) =
    sqrt(3 / (2 A)) / lambda (1 + O(lambda^-2))``, so eqs. (6.17) and (6.19) give ``P = A^3 - sqrt(6 A^3) +
    O(lambda^-2)`` and ``D = A^2 - sqrt(8 A / 3) + O(lambda^-2)`` at a fixed contact radius ``A``: JKR's
    curves plus a correction in ``1 / lambda^2`` (the next one is ``O(lambda^-4)``, with coefficients that
    grow as ``A`` falls or rises). Applied to Maugis' own loads at lambda = 2 and 2.5 the limit is within
    1.4 % of ``|P_c|`` of JKR's over 0.88-1.3 a_c (2.4 % at 1.4 a_c, 3.6 % at 1.5 a_c); at lambda = 2 and
    3, 1.1 % (1.8 %, 2.6 %). Pass values at the same contact radius (or the same approach)."""
    w_1 = lam_1**2 / (lam_2**2 - lam_1**2)
    return (1 + w_1) * np.asarray(value_2, dtype=float) - w_1 * np.asarray(value_1, dtype=float)


def johnson_wavy_alpha(*, amplitude: float, wavelength: float, E_star: float, work: float) -> float:
    """Johnson's (1995) adhesion parameter ``alpha = sqrt(2 wavelength w / (pi^2 E* amplitude^2))``."""
    return float(np.sqrt(2 * wavelength * work / (np.pi**2 * E_star * amplitude**2)))


def johnson_wavy_pressure(half_width, *, amplitude: float, wavelength: float, E_star: float, work: float):
    """Mean pressure [pressure] of the adhesive wavy profile at contact half-width ``a`` [length]:
    ``p / p* = sin^2(pi a / wavelength) - alpha sqrt(tan(pi a / wavelength))``, ``p* = pi E* amplitude /
    wavelength`` (the pressure of full contact without adhesion)."""
    s = np.pi * np.asarray(half_width, dtype=float) / wavelength
    p_star = np.pi * E_star * amplitude / wavelength
    alpha = johnson_wavy_alpha(amplitude=amplitude, wavelength=wavelength, E_star=E_star, work=work)
    return p_star * (np.sin(s) ** 2 - alpha * np.sqrt(np.tan(s)))
