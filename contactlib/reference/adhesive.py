"""Adhesive contact references: the JKR sphere and its limit of Maugis-Dugdale quantities, Johnson's (1995) wavy
profile. The Maugis-Dugdale sphere itself is :mod:`contactlib.reference.maugis`.

Rigid sphere (paraboloid of radius ``R``) on an elastic half-space of contact modulus
``E_star = E / (1 - nu^2)``, work of adhesion ``w``; ``K = 4 E* / 3``.

* JKR: Johnson, Kendall & Roberts, Proc. R. Soc. A 324, 301-313 (1971), doi:10.1098/rspa.1971.0141;
  Johnson, *Contact Mechanics* (1985), section 5.5.
* Wavy profile ``h = amplitude cos(2 pi x / wavelength)`` on a half-space in plane strain: Johnson,
  Int. J. Solids Struct. 32, 423-430 (1995), doi:10.1016/0020-7683(94)00111-9.
"""

from __future__ import annotations

import numpy as np


def jkr_load(contact_radius, *, radius: float, E_star: float, work: float):
    """JKR load ``P = 4 E* a^3 / (3 R) - sqrt(8 pi w E* a^3)`` [force] at contact radius ``a`` [length].

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

    Returns
    -------
    float or ndarray
        The load P [force] (negative: tensile).
    """
    a = np.asarray(contact_radius, dtype=float)
    return 4 * E_star * a**3 / (3 * radius) - np.sqrt(8 * np.pi * work * E_star * a**3)


def jkr_penetration(contact_radius, *, radius: float, E_star: float, work: float):
    """JKR approach ``d = a^2 / R - sqrt(2 pi w a / E*)`` [length] at contact radius ``a``.

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

    Returns
    -------
    float or ndarray
        The approach d [length].
    """
    a = np.asarray(contact_radius, dtype=float)
    return a**2 / radius - np.sqrt(2 * np.pi * work * a / E_star)


def jkr_pull_off(*, radius: float, work: float) -> float:
    """Pull-off force under load control, ``-3/2 pi w R`` [force] (the most tensile load of the curve).

    Parameters
    ----------
    radius : float
        Sphere radius R [length].
    work : float
        Work of adhesion w [pressure length].

    Returns
    -------
    float
        The pull-off force [force], negative.

    Examples
    --------
    >>> from contactlib.reference import adhesive
    >>> round(adhesive.jkr_pull_off(radius=1.0, work=2.0 / 3.0), 6)
    -3.141593
    """
    return -1.5 * np.pi * work * radius


def jkr_pull_off_radius(*, radius: float, E_star: float, work: float) -> float:
    """Contact radius at pull-off under load control, ``(9 pi w R^2 / (8 E*))^(1/3)`` [length].

    Parameters
    ----------
    radius : float
        Sphere radius R [length].
    E_star : float
        Contact modulus E* = E / (1 - nu^2) [pressure].
    work : float
        Work of adhesion w [pressure length].

    Returns
    -------
    float
        The contact radius a_c at pull-off [length].
    """
    return float((9 * np.pi * work * radius**2 / (8 * E_star)) ** (1 / 3))


def jkr_limit(value_1, lam_1: float, value_2, lam_2: float):
    """The ``lambda -> infinity`` (JKR) limit of a Maugis-Dugdale quantity known at two transition parameters,
    by Richardson extrapolation in ``1 / lambda^2``: ``(lam_2^2 v_2 - lam_1^2 v_1) / (lam_2^2 - lam_1^2)``
    (:func:`jkr_extrapolation` with two points; its docstring says why ``1 / lambda^2``). Applied to Maugis'
    own loads at lambda = 2 and 2.5 the limit is within 1.4 % of ``|P_c|`` of JKR's over 0.88-1.3 a_c (2.4 %
    at 1.4 a_c, 3.6 % at 1.5 a_c); at lambda = 2 and 3, 1.1 % (1.8 %, 2.6 %). Pass values at the same
    contact radius (or the same approach).

    Parameters
    ----------
    value_1, value_2 : float or ndarray
        The quantity at the two transition parameters.
    lam_1, lam_2 : float
        The two Maugis parameters.

    Returns
    -------
    float or ndarray
        The extrapolated JKR limit.
    """
    return jkr_extrapolation([value_1, value_2], [lam_1, lam_2])


def jkr_weights(lams) -> np.ndarray:
    """Weights ``c_i`` of the Richardson extrapolation ``sum_i c_i v(lambda_i)`` that removes the terms in
    ``lambda^-2, ..., lambda^-2(k-1)`` of ``k`` values (they sum to 1; ``sum |c_i|`` is how much the
    values' own errors can grow).

    Parameters
    ----------
    lams : array_like
        At least two distinct finite Maugis parameters.

    Returns
    -------
    ndarray
        One weight per parameter, summing to 1.

    Raises
    ------
    ValueError
        Naming ``lams`` when fewer than two distinct finite values are given.
    """
    x = np.asarray(lams, dtype=float) ** -2
    if x.ndim != 1 or x.size < 2 or np.unique(x).size != x.size or not np.all(np.isfinite(x)):
        raise ValueError(f"lams must be at least two distinct finite transition parameters, got {lams!r}")
    return np.linalg.solve(np.vander(x, x.size, increasing=True).T, np.eye(x.size)[0])


def jkr_extrapolation(values, lams):
    """The ``lambda -> infinity`` (JKR) limit of a Maugis-Dugdale quantity known at ``k >= 2`` transition
    parameters: Richardson extrapolation in powers of ``1 / lambda^2`` (the polynomial of degree ``k - 1`` in
    ``1 / lambda^2`` through the ``k`` values, taken at 0; weights :func:`jkr_weights`).

    Why even powers only: with ``t = lambda s``, ``s = sqrt(m^2 - 1)``, Maugis' eq. (6.21) reads
    ``(2/3) A t^2 + (1 / lambda^2) [(2/3) A^2 t^3 - (5/18) A t^4] + O(lambda^-4) = 1`` (the series of
    ``arctan`` and ``sqrt(1 + s^2)`` in ``s^2``), so ``t = sqrt(3 / (2 A)) + O(lambda^-2)`` is a series in
    ``1 / lambda^2``, and so are eq. (6.17), ``P = A^3 - 2 A^2 t - (2/3) A^2 t^3 / lambda^2 + ...``, and
    eq. (6.19), ``D = A^2 - (4/3) A t + ...``, at a fixed contact radius ``A``: JKR's curves (``A^3 -
    sqrt(6 A^3)``, ``A^2 - sqrt(8 A / 3)``) plus terms in ``lambda^-2, lambda^-4, ...``. Checked on the
    closed form: its departure from JKR falls by 3.9-4.0x per doubling of lambda (lambda 10 -> 20 -> 40).
    Their coefficients grow with ``A`` (the zone's share of the edge, ``A t / lambda^2 ~ sqrt(A) /
    lambda^2``), so far into compression more terms are needed: extrapolating Maugis' own loads, two points
    (2, 2.5) are within 3 % of ``|P_c|`` of JKR's to 1.4 a_c only, three (2, 2.5, 3) to 2.0 a_c (2.2 %;
    4.9 % at 2.5 a_c), four (1.5, 2, 2.5, 3) to 2.5 a_c (2.8 %). Values at the same contact radius (or the
    same approach); ``values`` is a sequence of scalars or arrays, one per lambda.

    Parameters
    ----------
    values : sequence of float or ndarray
        The quantity at each transition parameter.
    lams : array_like
        The Maugis parameters, one per value.

    Returns
    -------
    float or ndarray
        The extrapolated JKR limit.

    Raises
    ------
    ValueError
        Naming ``values`` or ``lams`` when they do not pair up (see :func:`jkr_weights`).
    """
    weights = jkr_weights(lams)
    if len(values) != weights.size:
        raise ValueError(f"values: one per lambda ({weights.size}), got {len(values)}")
    return sum(c * np.asarray(v, dtype=float) for c, v in zip(weights, values))


def jkr_equivalent_radius(contact_radius, zone_radius):
    """The radius ``a + 2/3 (c - a)`` [length] at which a Maugis-Dugdale sphere of contact radius ``a`` and
    cohesive-zone outer radius ``c`` is compared with JKR, for the extrapolation to ``lambda -> infinity``.

    Why: at a fixed contact radius the load departs from JKR's by ``(1.5 A^2 - (13/12) (3/2)^(3/2) A^(1/2))
    / lambda^2 + O(lambda^-4)`` (from the series of :func:`jkr_extrapolation`: ``t = t_0 - (A t_0^2 / 2 -
    (5/24) t_0^3) / lambda^2``, ``t_0^2 = 3 / (2 A)``), and the zone is ``C - A = 3 / (4 lambda^2)`` long
    (``m - 1 = s^2 / 2``). Moving the radius by ``kappa (C - A)`` moves JKR's load by ``kappa (3/4) (3 A^2 -
    (3/2) sqrt(6 A)) / lambda^2``: ``kappa = 2/3`` cancels the ``A^2`` part of the ``1 / lambda^2`` term,
    the part that grows into compression, and the remainder is small where the load is (``JKR' = 0`` at
    ``a_c``, where no shift helps). Both radii tend to ``a``, so the limit is JKR's curve against the contact
    radius; the terms left are smaller: Maugis' own loads extrapolated at a fixed ``a + 2/3 (c - a)`` from
    lambda = 1.5, 2 and 2.5 are within 2.3 % of ``|P_c|`` of JKR's to 2.5 a_c (11.5 % at a fixed ``a``).

    Parameters
    ----------
    contact_radius : float or array_like
        Contact radius a [length].
    zone_radius : float or array_like
        Outer radius c of the cohesive zone [length].

    Returns
    -------
    float or ndarray
        ``a + 2/3 (c - a)`` [length].
    """
    a = np.asarray(contact_radius, dtype=float)
    return a + 2.0 / 3.0 * (np.asarray(zone_radius, dtype=float) - a)


def jkr_contact_radius(load, *, radius: float, E_star: float, work: float):
    """JKR contact radius [length] at load ``P`` [force] on the branch stable under load control
    (``a >= a_c``, ``P >= -3/2 pi w R``): the root of ``4 E* a^3 / (3 R) - sqrt(8 pi w E* a^3) = P``,
    a quadratic in ``a^(3/2)``. Raises ValueError for a load below pull-off.

    Parameters
    ----------
    load : float or array_like
        Load P [force], at least the pull-off.
    radius : float
        Sphere radius R [length].
    E_star : float
        Contact modulus E* = E / (1 - nu^2) [pressure].
    work : float
        Work of adhesion w [pressure length].

    Returns
    -------
    float or ndarray
        The contact radius a [length].

    Raises
    ------
    ValueError
        Naming ``load`` below the pull-off (no equilibrium).
    """
    P = np.asarray(load, dtype=float)
    if np.any(P < jkr_pull_off(radius=radius, work=work) * (1 + 1e-12)):
        raise ValueError("load: below the JKR pull-off -3/2 pi w R, no contact")
    alpha, beta = 4 * E_star / (3 * radius), np.sqrt(8 * np.pi * work * E_star)
    u = (beta + np.sqrt(np.maximum(beta**2 + 4 * alpha * P, 0.0))) / (2 * alpha)  # u = a^(3/2)
    return u ** (2 / 3)


def apex_disc_radius(heights, count: int, *, radius: float) -> float:
    """Contact radius [length] of a set of ``count`` grid points about the apex of a paraboloid of radius
    ``radius``: halfway between the distances of the ``count``-th and the next-nearest grid points to the
    apex (the distances from the heights, ``r = sqrt(2 R (h_max - h))``). Why not ``sqrt(count dA / pi)``:
    the number of lattice points in a disc scatters about its area by a few perimeter points (Gauss' circle
    problem), about 0.02 % of the radius at 100 elements across, which is 0.6 % of ``|P_c|`` in the JKR load
    at 2.4 a_c; a disc of points has its radius pinned between two lattice shells.

    Parameters
    ----------
    heights : array_like
        Grid heights of the paraboloid [length].
    count : int
        Number of grid points in contact.
    radius : float
        Radius of the paraboloid [length].

    Returns
    -------
    float
        The contact radius [length].

    Raises
    ------
    ValueError
        Naming ``count`` outside 1 to the number of points less one.
    """
    h = np.asarray(heights, dtype=float).ravel()
    r = np.sort(np.sqrt(np.maximum(2 * radius * (h.max() - h), 0.0)))
    if not 0 < count < r.size:
        raise ValueError(f"count must be between 1 and {r.size - 1} grid points, got {count!r}")
    return float(0.5 * (r[count - 1] + r[count]))


def johnson_wavy_alpha(*, amplitude: float, wavelength: float, E_star: float, work: float) -> float:
    """Johnson's (1995) adhesion parameter ``alpha = sqrt(2 wavelength w / (pi^2 E* amplitude^2))``.

    Parameters
    ----------
    amplitude : float
        Amplitude of the wavy profile [length].
    wavelength : float
        Its wavelength [length].
    E_star : float
        Contact modulus E* = E / (1 - nu^2) [pressure].
    work : float
        Work of adhesion w [pressure length].

    Returns
    -------
    float
        Johnson's alpha [1].
    """
    return float(np.sqrt(2 * wavelength * work / (np.pi**2 * E_star * amplitude**2)))


def johnson_wavy_pressure(half_width, *, amplitude: float, wavelength: float, E_star: float, work: float):
    """Mean pressure [pressure] of the adhesive wavy profile at contact half-width ``a`` [length]:
    ``p / p* = sin^2(pi a / wavelength) - alpha sqrt(tan(pi a / wavelength))``, ``p* = pi E* amplitude /
    wavelength`` (the pressure of full contact without adhesion).

    Parameters
    ----------
    half_width : float or array_like
        Contact half-width a [length].
    amplitude : float
        Amplitude of the wavy profile [length].
    wavelength : float
        Its wavelength [length].
    E_star : float
        Contact modulus E* = E / (1 - nu^2) [pressure].
    work : float
        Work of adhesion w [pressure length].

    Returns
    -------
    float or ndarray
        The mean pressure [pressure].
    """
    s = np.pi * np.asarray(half_width, dtype=float) / wavelength
    p_star = np.pi * E_star * amplitude / wavelength
    alpha = johnson_wavy_alpha(amplitude=amplitude, wavelength=wavelength, E_star=E_star, work=work)
    return p_star * (np.sin(s) ** 2 - alpha * np.sqrt(np.tan(s)))
