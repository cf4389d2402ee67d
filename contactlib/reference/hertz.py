"""Hertz contact of a rigid paraboloid (sphere) or cylinder on an elastic half-space.

Johnson, *Contact Mechanics* (1985), sections 4.2 (cylinder, plane strain) and 3.4 (sphere).
``E_star = E / (1 - nu^2)`` [pressure], ``radius`` R [length].
"""

from __future__ import annotations

import numpy as np


def sphere_load(penetration: float, *, radius: float, E_star: float) -> float:
    """Total load P = (4/3) E* R^(1/2) d^(3/2) [force].

    Parameters
    ----------
    penetration : float or ndarray
        Rigid approach d [length], >= 0.
    radius : float
        Sphere radius R [length].
    E_star : float
        Contact modulus E* = E / (1 - nu^2) [pressure].

    Returns
    -------
    float or ndarray
        The load P [force].
    """
    return 4.0 / 3.0 * E_star * np.sqrt(radius) * penetration**1.5


def sphere_contact_radius(penetration: float, *, radius: float) -> float:
    """Contact radius a = sqrt(R d) [length].

    Parameters
    ----------
    penetration : float
        Rigid approach d [length], >= 0.
    radius : float
        Sphere radius R [length].

    Returns
    -------
    float
        The contact radius a [length].
    """
    return float(np.sqrt(radius * penetration))


def sphere_penetration(load: float, *, radius: float, E_star: float) -> float:
    """Approach d = (3 P / (4 E* sqrt(R)))^(2/3) [length].

    Parameters
    ----------
    load : float
        Total load P [force], >= 0.
    radius : float
        Sphere radius R [length].
    E_star : float
        Contact modulus E* = E / (1 - nu^2) [pressure].

    Returns
    -------
    float
        The approach d [length].
    """
    return float((3.0 * load / (4.0 * E_star * np.sqrt(radius))) ** (2.0 / 3.0))


def sphere_pressure(r, *, load: float, radius: float, E_star: float):
    """Pressure p(r) = p0 sqrt(1 - r^2/a^2), p0 = 3P/(2 pi a^2) [pressure].

    Parameters
    ----------
    r : float or array_like
        Distance from the axis [length].
    load : float
        Total load P [force].
    radius : float
        Sphere radius R [length].
    E_star : float
        Contact modulus E* = E / (1 - nu^2) [pressure].

    Returns
    -------
    float or ndarray
        The pressure at ``r`` [pressure], zero outside the contact.

    Examples
    --------
    >>> from contactlib.reference import hertz
    >>> p0 = hertz.sphere_pressure(0.0, load=1.0, radius=1.0, E_star=1.0)
    >>> bool(abs(p0 - 1.5 / (3.14159265 * 0.75 ** (2 / 3))) < 1e-6)
    True
    """
    a = sphere_contact_radius(sphere_penetration(load, radius=radius, E_star=E_star), radius=radius)
    p0 = 3.0 * load / (2.0 * np.pi * a**2)
    return p0 * np.sqrt(np.clip(1.0 - (np.asarray(r) / a) ** 2, 0.0, None))


def cylinder_half_width(line_load: float, *, radius: float, E_star: float) -> float:
    """Half-width b = sqrt(4 P' R / (pi E*)) for line load P' [force/length].

    Parameters
    ----------
    line_load : float
        Load per unit length P' [force/length].
    radius : float
        Cylinder radius R [length].
    E_star : float
        Contact modulus E* = E / (1 - nu^2) [pressure].

    Returns
    -------
    float
        The contact half-width b [length].
    """
    return float(np.sqrt(4.0 * line_load * radius / (np.pi * E_star)))


def cylinder_pressure(x, *, line_load: float, radius: float, E_star: float):
    """Pressure p(x) = p0 sqrt(1 - x^2/b^2), p0 = 2 P' / (pi b) [pressure].

    Parameters
    ----------
    x : float or array_like
        Distance from the axis [length].
    line_load : float
        Load per unit length P' [force/length].
    radius : float
        Cylinder radius R [length].
    E_star : float
        Contact modulus E* = E / (1 - nu^2) [pressure].

    Returns
    -------
    float or ndarray
        The pressure at ``x`` [pressure], zero outside the contact.
    """
    b = cylinder_half_width(line_load, radius=radius, E_star=E_star)
    p0 = 2.0 * line_load / (np.pi * b)
    return p0 * np.sqrt(np.clip(1.0 - (np.asarray(x) / b) ** 2, 0.0, None))
