"""Hunter (1961): a rigid cylinder sliding steadily on a standard-linear-solid half-space, frictionless,
plane strain, isolated (not periodic): an independent route to the steady viscoelastic solver.

J. Appl. Mech. 28, 611-617 (1961); K. L. Johnson, *Contact Mechanics* (1985), section 7.4. The cylinder
(profile ``x^2 / (2R)``) moves in ``+x`` relative to the body, as :func:`contactlib.solve`'s
``sliding_velocity`` does. A material point now at ``x`` (slider frame) was at ``x + V t`` a time ``t`` ago,
so a unit line load at the origin displaces the surface by (seed 2, eq 25, with the plane-strain
elastic Green's function ``-(2 (1 - nu^2)/pi) ln|r|`` at unit modulus) ::

    G_V(r) = J(0+) G1(r) + int_0^inf G1(r + V t) J'(t) dt.

For the standard linear solid ``J(t) = 1/E0 - D exp(-t/T)``, ``D = 1/E0 - 1/E_inf`` and the creep
(retardation) time ``T = tau E_inf/E0``; the time integral is closed form (by parts) ::

    G_V(r) = -(2 (1 - nu^2)/pi) [ln|r| / E0 + D e^(r/c) E1(r/c)],   c = V T,

with ``E1`` the exponential integral (principal value, ``e^y E1(y) = -e^y Ei(-y)``, for ``r < 0``, behind
the load). Its antiderivative is closed form too (``d/dy [e^y E1(y) + ln|y|] = e^y E1(y)``), so the
influence of a uniform pressure on each element is exact, however short the wake ``c`` against an
element. The dense non-symmetric matrix is solved on a trial contact set with the load as a constraint (LU of
the bordered system for the pressures and the approach), dropping tensile and adding interpenetrating
elements until the set is stable (the seed's active-set method under load control). Nothing here comes from a Fourier multiplier or a periodic
window: the limits are ``E0`` (``c -> 0``) and ``E_inf`` (``c -> inf``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.special import exp1, expi

from ..solvers.state import contact_residual, height_scale

_EULER = 0.5772156649015329
_ASYMPTOTIC_FROM = 40.0


def _exp_e1(y: np.ndarray) -> np.ndarray:
    """``e^y E1(y)`` for real ``y != 0`` (principal value for ``y < 0``), without overflow."""
    out = np.empty_like(y)
    far = np.abs(y) >= _ASYMPTOTIC_FROM
    near = ~far
    pos, neg = near & (y > 0), near & (y < 0)
    out[pos] = np.exp(y[pos]) * exp1(y[pos])
    out[neg] = -np.exp(y[neg]) * expi(-y[neg])
    # e^y E1(y) ~ sum_k (-1)^k k! / y^(k+1): 12 terms are 12!/40^13 ~ 1e-12 relative at |y| = 40
    yf = y[far]
    term, total = 1.0 / yf, np.zeros_like(yf)
    for k in range(12):
        total += term
        term = term * -(k + 1) / yf
    out[far] = total
    return out


def _wake_antiderivative(y: np.ndarray) -> np.ndarray:
    """``F(y) = e^y E1(y) + ln|y|`` (``F' = e^y E1(y)``), continuous at 0 where it is ``-gamma``."""
    out = np.full_like(y, -_EULER)
    nz = y != 0
    out[nz] = _exp_e1(y[nz]) + np.log(np.abs(y[nz]))
    return out


def element_influence(r_lo: np.ndarray, r_hi: np.ndarray, *, material, speed: float) -> np.ndarray:
    """``int G_V(r) dr`` from ``r_lo`` to ``r_hi`` [length^2/pressure]: the displacement at a point a distance
    ``r`` (field minus source, along the sliding) from a unit uniform pressure, over the element.

    Parameters
    ----------
    r_lo, r_hi : ndarray
        Ends of the element relative to the field point, along the sliding [length].
    material : contactlib.Viscoelastic
        A standard linear solid.
    speed : float
        Sliding speed [length/time].

    Returns
    -------
    ndarray
        The influence [length^2/pressure].
    """
    (E, tau), = material.prony
    E0, E_inf, nu = material.E0, material.E0 + E, material.nu
    D = 1 / E0 - 1 / E_inf
    c = speed * tau * E_inf / E0

    def primitive(r):
        a = np.abs(r)
        with np.errstate(divide="ignore", invalid="ignore"):
            rlog = np.where(a > 0, r * np.log(np.where(a > 0, a, 1.0)), 0.0)
        wake = D * c * _wake_antiderivative(r / c) if c > 0 else 0.0
        return -(2 * (1 - nu**2) / np.pi) * ((rlog - r) / E0 + wake)

    return primitive(np.asarray(r_hi, float)) - primitive(np.asarray(r_lo, float))


def _active_set(dense: np.ndarray, heights: np.ndarray, force: float, h: float, max_sets: int = 200):
    """``(p, gap)`` with ``p >= 0``, ``gap = dense p - heights - d >= 0``, ``p gap = 0``, ``h sum p = force``."""
    n = heights.size
    active = np.flatnonzero(heights >= np.quantile(heights, 0.75))
    for _ in range(max_sets):
        m = active.size
        system = np.zeros((m + 1, m + 1))
        system[:m, :m] = dense[np.ix_(active, active)]
        system[:m, m] = -1.0
        system[m, :m] = h
        solution = np.linalg.solve(system, np.concatenate([heights[active], [force]]))
        p = np.zeros(n)
        p[active] = solution[:m]
        gap = dense @ p - heights - solution[m]
        keep = active[p[active] > 0]
        outside = np.ones(n, dtype=bool)
        outside[active] = False
        new = np.union1d(keep, np.flatnonzero(outside & (gap < 0)))
        if np.array_equal(new, active):
            return p, gap
        active = new
    raise RuntimeError(f"the contact set did not settle in {max_sets} updates")


@dataclass(frozen=True)
class SlidingCylinder:
    """Hunter's results for one speed: ``x`` [length] element centres, ``pressure`` [pressure], and the
    contact's ``leading`` / ``trailing`` edges (element edges of the outermost loaded elements), ``width``,
    ``offset`` (its centre ahead of the axis) and the friction coefficient ``mu = int p x dx / (R P)``.

    Attributes
    ----------
    x : ndarray
        Element centres [length].
    pressure : ndarray
        Pressure on the elements [pressure].
    leading, trailing : float
        Edges of the contact [length].
    width : float
        Contact width [length].
    offset : float
        Centre of the contact ahead of the axis [length].
    friction_coefficient : float
        ``int p x dx / (R P)`` [1].
    residual : float
        Residual of the active-set solve.
    """

    x: np.ndarray
    pressure: np.ndarray
    leading: float
    trailing: float
    width: float
    offset: float
    friction_coefficient: float
    residual: float


def solve(*, radius: float, load: float, material, speed: float, half_span: float, n: int) -> SlidingCylinder:
    """The cylinder of ``radius`` [length] pressed by ``load`` [force/length] sliding at ``speed``
    [length/time] on the standard linear solid ``material``, on ``n`` elements over ``|x| < half_span``
    (which must hold the contact).

    Parameters
    ----------
    radius : float
        Cylinder radius [length].
    load : float
        Load per unit width [force/length].
    material : contactlib.Viscoelastic
        A standard linear solid (one Prony branch).
    speed : float
        Sliding speed [length/time], > 0.
    half_span : float
        Half-length of the solved span [length], which must hold the contact.
    n : int
        Number of elements.

    Returns
    -------
    SlidingCylinder
        Pressure, edges, offset and friction coefficient.

    Raises
    ------
    ValueError
        Naming ``material`` (not a standard linear solid), ``speed`` (not > 0) or ``half_span`` (the contact reaches
        the span's end).
    RuntimeError
        When the active set does not settle.
    """
    if len(material.prony) != 1:
        raise ValueError("material: Hunter's solution is for a standard linear solid (one Prony branch)")
    if not speed > 0:
        raise ValueError(f"speed must be > 0, got {speed!r}")
    h = 2 * half_span / n
    x = -half_span + h * (np.arange(n) + 0.5)
    r = x[:, None] - x[None, :]
    dense = element_influence(r - h / 2, r + h / 2, material=material, speed=speed)
    heights = -x**2 / (2 * radius)
    p, gap = _active_set(dense, heights, load, h)
    loaded = np.flatnonzero(p > 0)
    if loaded[0] == 0 or loaded[-1] == n - 1:
        raise ValueError("half_span: the contact reaches the end of the span; enlarge it")
    leading, trailing = x[loaded[-1]] + h / 2, x[loaded[0]] - h / 2
    mu = float(np.sum(p * x) / (radius * np.sum(p)))
    return SlidingCylinder(x, p, leading, trailing, leading - trailing, 0.5 * (leading + trailing), mu,
                           contact_residual(p, gap, height_scale(heights)))
