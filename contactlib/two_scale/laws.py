"""Single-asperity laws ``P = f(d)`` of the macro scale: Hertz's for spheres (:class:`.macro.HertzLaw`), or
a law tabulated from full solves of one asperity of any axisymmetric shape (:func:`tabulated_law`).

The table holds the force and the contact radius at penetrations spaced geometrically up to
``max_penetration``. It is interpolated in ``log d`` by a monotone cubic (PCHIP) of ``log P`` and
``log a``: exact for a power law ``P ~ d^m`` (the sphere's 3/2, the cone's 2, Galin's ``(n+1)/n`` for
``h ~ r^n``), C^1, and increasing whatever the data's noise. Below the first penetration the first
interval's power law goes on to ``d = 0`` (so ``f(0) = 0``); above the last one the last interval's, and
:func:`contactlib.two_scale.solve` refuses a solution that needs it (naming ``max_penetration``).

Each penetration gets its own grid: a non-periodic window of ``WINDOW`` times the geometric contact radius
``r_g`` (``drop(r_g) = d``) on ``nodes`` points per side, so the contact spans the same number of nodes at
every penetration and the table's discretisation error is the same along it (a sphere: within 0.3 % of
Hertz at the default 128 nodes).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from scipy.interpolate import PchipInterpolator

from ..problems.contact import solve as full_solve
from ..core.inputs import check_whole
from ..model.materials import contact_modulus

WINDOW = 3.0
"""Window side over the geometric contact radius ``r_g`` of each tabulated penetration (a contact radius
is below ``r_g`` for a convex shape: the window holds it with room for the decay of the load's field)."""


class TabulatedLaw:
    """A single-asperity law interpolated from a table (see the module docstring).


    Raises
    ------
    ValueError
        When the tables are not 1D, of one length >= 3, positive and increasing (a convex asperity).

    Attributes
    ----------
    penetration, force, contact_radius : ndarray
        The table [length], [force], [length].
    footprint_radius : float
        Radius of the asperity's support [length] (its contact must stay inside).
    attrs : dict
        How it was made.
    """

    def __init__(self, penetration, force, contact_radius, *, footprint_radius: float, attrs: dict | None = None):
        d, P, a = (np.asarray(v, dtype=float) for v in (penetration, force, contact_radius))
        if d.ndim != 1 or d.size < 3 or not (d.shape == P.shape == a.shape):
            raise ValueError("penetration, force, contact_radius: three 1D tables of the same length >= 3")
        if not (np.all(d > 0) and np.all(np.diff(d) > 0)):
            raise ValueError("penetration must be > 0 and increasing")
        if not (np.all(P > 0) and np.all(np.diff(P) > 0)):
            raise ValueError("force must be > 0 and increase with the penetration (a convex asperity)")
        if not np.all(a > 0):
            raise ValueError("contact_radius must be > 0")
        self.penetration, self.force_table, self.radius_table = d, P, a
        self.footprint_radius = float(footprint_radius)
        self.max_penetration = float(d[-1])
        self.attrs = dict(attrs or {})
        x = np.log(d)
        self._log_force = PchipInterpolator(x, np.log(P), extrapolate=True)
        self._log_radius = PchipInterpolator(x, np.log(a), extrapolate=True)
        self._log_penetration = PchipInterpolator(np.log(P), x, extrapolate=True)  # the inverse, for stiffness
        self._x = x
        # power laws beyond the table: the end intervals' exponents
        self._ends = [((x[0], np.log(P[0]), np.log(a[0])), (np.diff(np.log(P))[0] / np.diff(x)[0],
                                                            np.diff(np.log(a))[0] / np.diff(x)[0])),
                      ((x[-1], np.log(P[-1]), np.log(a[-1])), (np.diff(np.log(P))[-1] / np.diff(x)[-1],
                                                               np.diff(np.log(a))[-1] / np.diff(x)[-1]))]

    @property
    def length_scale(self) -> float:
        """A length of the law [length]: the largest tabulated penetration."""
        return self.max_penetration

    def at_modulus(self, E_star: float) -> "TabulatedLaw":
        """The same asperity on a body of contact modulus ``E_star`` [pressure]: a rigid shape pressed to a
        given penetration into an elastic half-space has a contact independent of the modulus and a
        pressure proportional to it, so the forces scale by ``E_star / law_E_star`` and the radii stay."""
        if "law_E_star" not in self.attrs:
            raise ValueError("law: attrs['law_E_star'] (the contact modulus the table was made with) is needed to "
                             "use it at another modulus")
        factor = float(E_star) / float(self.attrs["law_E_star"])
        return TabulatedLaw(self.penetration, self.force_table * factor, self.radius_table,
                            footprint_radius=self.footprint_radius, attrs={**self.attrs, "law_E_star": float(E_star)})

    def _log_values(self, d: np.ndarray, which: int) -> tuple[np.ndarray, np.ndarray]:
        """``log f`` and ``d log f / d log d`` at ``d > 0`` (force: ``which=1``, radius: 2)."""
        x = np.log(d)
        spline = self._log_force if which == 1 else self._log_radius
        value, exponent = spline(x), spline(x, 1)
        for (x0, *logs), slopes in self._ends:
            outside = x < x0 if x0 == self._x[0] else x > x0
            value = np.where(outside, logs[which - 1] + slopes[which - 1] * (x - x0), value)
            exponent = np.where(outside, slopes[which - 1], exponent)
        return value, exponent

    def force(self, d: np.ndarray) -> np.ndarray:
        """``P = f(d)`` [force], 0 for ``d <= 0``."""
        return _where_positive(d, lambda on: np.exp(self._log_values(on, 1)[0]))

    def slope(self, d: np.ndarray) -> np.ndarray:
        """``dP/dd`` [force/length], 0 for ``d <= 0``."""
        def evaluate(on):
            value, exponent = self._log_values(on, 1)
            return np.exp(value) * exponent / on
        return _where_positive(d, evaluate)

    def contact_radius(self, d: np.ndarray) -> np.ndarray:
        """Contact radius [length], 0 for ``d <= 0``."""
        return _where_positive(d, lambda on: np.exp(self._log_values(on, 2)[0]))

    def stiffness(self, force: np.ndarray) -> np.ndarray:
        """``dP/dd`` at the penetration that carries ``force`` [force/length], 0 for ``force <= 0``."""
        force = np.asarray(force, dtype=float)
        on = force > 0
        d = np.zeros_like(force)
        if np.any(on):
            logP = np.log(force[on])
            # the inverse of the two end power laws beyond the table, the inverse spline inside it
            x = self._log_penetration(logP)
            for (x0, lp0, _), (m, _) in self._ends:
                outside = logP < lp0 if x0 == self._x[0] else logP > lp0
                x = np.where(outside, x0 + (logP - lp0) / m, x)
            d[on] = np.exp(x)
        return self.slope(d)


def _geometric_radius(drop: Callable, d: float, footprint: float) -> float:
    """``r`` with ``drop(r) = d`` by bisection on ``[0, footprint]`` (``drop`` increasing)."""
    lo, hi = 0.0, footprint
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        if float(drop(mid)) < d:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def tabulated_law(drop: Callable[[np.ndarray], np.ndarray], *, footprint_radius: float, max_penetration: float,
                  material=None, E: float | None = None, nu: float | None = None, points: int = 16,
                  smallest: float = 1e-2, nodes: int = 128, tol: float = 1e-8) -> TabulatedLaw:
    """Tabulate the law of one axisymmetric asperity from the full solver.

    Parameters
    ----------
    drop : callable
        ``drop(r)`` [length]: the height below the summit at distance ``r`` [length] from it, increasing
        from ``drop(0) = 0`` (e.g. ``lambda r: r**2 / (2 R)`` near a sphere's summit, ``r / tan(alpha)``
        for a cone of half-angle ``alpha``).
    footprint_radius : float
        Radius of the asperity's support [length]: every tabulated contact must stay inside it.
    max_penetration : float
        Largest penetration tabulated [length] (the macro step refuses to go beyond it).
    material, E, nu
        ``contactlib.Elastic(E, nu)`` or the two numbers [pressure], [1].
    points : int
        Penetrations in the table, spaced geometrically from ``smallest * max_penetration``.
    nodes : int
        Grid points per side of each solve.
    tol : float
        The full solver's tolerance.

    smallest : float
        The smallest tabulated penetration, as a fraction of ``max_penetration``.

    Returns
    -------
    TabulatedLaw

    Raises
    ------
    ValueError
        Naming ``material`` (not elastic, or given with ``E``, ``nu``), ``drop`` (not callable) or a size that is
        not finite and > 0.
    """
    if material is not None:
        if E is not None or nu is not None:
            raise ValueError("material: give material=... or E= and nu=, not both")
        if not (hasattr(material, "E") and hasattr(material, "nu")):
            raise ValueError(f"material: a tabulated law is elastic, give contactlib.Elastic(E, nu), got {material!r}")
        E, nu = material.E, material.nu
    if E is None or nu is None:
        raise ValueError("material: give material=contactlib.Elastic(E, nu) or both E= and nu=")
    if not callable(drop):
        raise ValueError(f"drop must be a callable drop(r) [length], got {drop!r}")
    for name, value in (("footprint_radius", footprint_radius), ("max_penetration", max_penetration),
                        ("smallest", smallest)):
        if not (math.isfinite(value) and value > 0):
            raise ValueError(f"{name} must be finite and > 0, got {value!r}")
    check_whole(points, "points", 3)
    check_whole(nodes, "nodes", 16)
    if not smallest < 1:
        raise ValueError(f"smallest must be < 1 (a fraction of max_penetration), got {smallest!r}")
    if float(drop(footprint_radius)) <= max_penetration:
        raise ValueError(f"max_penetration {max_penetration!r} reaches the base: drop(footprint_radius) = "
                         f"{float(drop(footprint_radius))!r}")
    n = int(nodes)
    penetrations = max_penetration * np.geomspace(smallest, 1.0, int(points))
    force, radius = np.zeros(penetrations.size), np.zeros(penetrations.size)
    for i, d in enumerate(penetrations):
        length = WINDOW * _geometric_radius(drop, d, footprint_radius)
        x = (np.arange(n) - n // 2) * (length / n)  # the summit on the centre node
        r = np.sqrt(x[:, None] ** 2 + x[None, :] ** 2)
        heights = -np.asarray(drop(np.minimum(r, footprint_radius)), dtype=float)
        out = full_solve(heights, E=E, nu=nu, penetration=float(d), periodic=False, length=length, tol=tol)
        if np.any(out.pressure.values[[0, -1], :] > 0) or np.any(out.pressure.values[:, [0, -1]] > 0):
            raise ValueError(f"drop: the contact at penetration {d:.4g} reaches the window's edge (a concave shape?)")
        force[i] = float(out.mean_pressure) * length * length
        radius[i] = math.sqrt(float(out.contact_area) * length * length / math.pi)
    if radius[-1] >= footprint_radius:
        raise ValueError(f"max_penetration {max_penetration!r}: the contact reaches the footprint's edge")
    return TabulatedLaw(penetrations, force, radius, footprint_radius=footprint_radius,
                        attrs={"single_asperity_law": "tabulated", "law_points": int(points), "law_nodes": n,
                               "law_max_penetration": float(max_penetration), "law_E_star": contact_modulus(E, nu)})


def _where_positive(d, evaluate) -> np.ndarray:
    """``evaluate`` on the positive penetrations of ``d``, 0 elsewhere (out of contact)."""
    d = np.asarray(d, dtype=float)
    on = d > 0
    out = np.zeros_like(d)
    if np.any(on):
        out[on] = evaluate(d[on])
    return out
