"""The adhesive interface of a scene: :class:`Adhesion` (work of adhesion, range, law) and its laws.

Two cohesive laws give the tensile traction ``sigma(g)`` [pressure] across a gap ``g >= 0``, both with
the work of adhesion ``w = int_0^inf sigma(g) dg``:

* ``"maugis"`` (Maugis-Dugdale): ``sigma = sigma_0 = w / range`` for ``g <= range``, 0 beyond (Maugis,
  J. Colloid Interface Sci. 150, 243-269, 1992, doi:10.1016/0021-9797(92)90285-T), its step a narrow
  ramp on the grid (:data:`MAUGIS_RAMP`);
* ``"exponential"``: the potential ``-w exp(-g / range)``, ``sigma = (w / range) exp(-g / range)``
  (the law of tamaas' ``ExponentialAdhesionFunctional``).

Both act on contact too (``g = 0``: ``sigma(0) = w / range``), where the repulsive pressure balances it.
As ``range -> 0`` at fixed ``w`` they tend to the JKR limit: ``"jkr"`` is that limit itself, solved by
the energy balance of the seed paper (eqs 9-11, :mod:`contactlib.solvers.adhesive.energy`), with no range.

The process zone of a cohesive crack in plane strain is ``l = pi E* w / (4 sigma_0^2)`` long (Dugdale's
zone ``pi K_I^2 / (8 sigma_0^2)`` with ``K_I^2 = 2 E* w`` at a rigid-elastic interface). A grid that puts fewer than
:data:`ZONE_ELEMENTS` elements across it cannot resolve the law: :func:`check_resolution` warns.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from ..core.inputs import number

MODELS = ("maugis", "exponential", "jkr")

MAUGIS_RAMP = 0.25
"""The Maugis-Dugdale step is a linear ramp from ``sigma_0`` at ``(1 - e) range`` to 0 at ``(1 + e) range``,
``e`` this fraction: the work stays ``w`` exactly, a grid point near the edge of the zone carries a share
of the stress instead of all or nothing (a node-wise step made the load first order in the grid and 2-4 %
off Maugis' at lambda = 1 on 128-256 points across; with the ramp 0.05-0.2 % on 128), and Newton sees the
edge move (``a' != 0`` there). 0.1 made the slope so stiff that Newton flipped ramp points near the
answer; 0.25 converges on the same scenes."""

ZONE_ELEMENTS = 3.0
"""Fewest grid elements across the process zone ``pi E* w / (4 sigma_0^2)`` before a cohesive solve
warns (:class:`CohesiveZoneWarning`): with fewer, the zone is a step a single element wide and the
pull-off force depends on the grid (the Maugis law was off by 3x on tamaas' solver at 1/4 of this)."""


class CohesiveZoneWarning(UserWarning):
    """The grid does not resolve the cohesive (process) zone of the adhesion law."""


@dataclass(frozen=True)
class Adhesion:
    """An adhesive interface.

    Parameters
    ----------
    work : float
        Work of adhesion (Dupre energy) ``w`` [pressure * length = energy / area], ``> 0`` for a cohesive law,
        ``>= 0`` for ``"jkr"``.
    range : float, optional
        Range of the cohesive law [length], ``> 0``: the gap over which the Maugis-Dugdale stress
        ``w / range`` acts, or the decay length of the exponential law. Ignored (optional) for ``"jkr"``.
    model : {"maugis", "exponential", "jkr"}
        Cohesive law inside the constrained solver, or ``"jkr"``: the range-free energy balance
        (a profile symmetric about its highest point or a surface of revolution,
        :mod:`contactlib.solvers.adhesive.energy`).

    Raises
    ------
    ValueError
        Naming the parameter: ``work`` negative, NaN or infinite (or 0 for a cohesive law); ``range`` not
        finite and ``> 0`` for a cohesive law; an unknown ``model``.
    """

    work: float
    range: float | None = None
    model: str = "maugis"

    def __post_init__(self):
        if not isinstance(self.model, str) or self.model not in MODELS:
            raise ValueError(f"model (adhesion law) must be one of {MODELS}, got {self.model!r}")
        w = number("work (work of adhesion)", self.work, lower=0.0)
        if self.model != "jkr":
            if w == 0:  # a law without stress: its residual's scale sigma_0 + |P| vanished at zero load
                raise ValueError(f"work (work of adhesion) must be > 0 for model={self.model!r}: without adhesion, "
                                 "leave adhesion= out")
            number(f"range (cohesive range, model={self.model!r})", self.range, lower=0.0, lower_open=True)

    @property
    def cohesive(self) -> bool:
        """Whether the law is a cohesive stress (solved inside the constrained solver)."""
        return self.model != "jkr"

    @property
    def peak_stress(self) -> float:
        """``sigma_0 = w / range`` [pressure], the stress at contact (0 for ``"jkr"``: it has none)."""
        return self.work / self.range if self.cohesive else 0.0

    def traction(self, gap: np.ndarray, out: np.ndarray | None = None) -> np.ndarray:
        """The adhesive traction ``-sigma(max(g, 0))`` [pressure], tensile negative, at the gaps ``gap``."""
        g = np.maximum(gap, 0.0)
        if self.model == "maugis":
            share = np.clip(((1 + MAUGIS_RAMP) * self.range - g) / (2 * MAUGIS_RAMP * self.range), 0.0, 1.0)
            return -self.peak_stress * share
        if self.model == "exponential":
            return -self.peak_stress * np.exp(-g / self.range)
        raise ValueError("traction: the 'jkr' model has no cohesive law")

    def traction_slope(self, gap: np.ndarray) -> np.ndarray:
        """``d traction / d gap`` [pressure/length], ``>= 0`` (0 on contact, where ``g < 0`` is held at 0)."""
        g = np.asarray(gap)
        if self.model == "maugis":
            e = MAUGIS_RAMP * self.range
            ramp = (g > self.range - e) & (g < self.range + e)
            return np.where(ramp, self.peak_stress / (2 * e), 0.0)
        if self.model == "exponential":
            return np.where(g > 0, self.peak_stress / self.range * np.exp(-np.maximum(g, 0.0) / self.range), 0.0)
        raise ValueError("traction_slope: the 'jkr' model has no cohesive law")

    def interacting(self, gap: np.ndarray) -> np.ndarray:
        """Where the cohesive stress acts in earnest: the gap is at most the range (Maugis: exactly where
        it acts; exponential: where it is at least ``sigma_0 / e``)."""
        return gap <= self.range

    def attrs(self) -> dict:
        """The law, for a Dataset's attrs."""
        out = {"adhesion_model": self.model, "work_of_adhesion": float(self.work)}
        if self.cohesive:
            out.update(adhesion_range=float(self.range), peak_adhesive_stress=self.peak_stress)
        return out


def process_zone_length(adhesion: Adhesion, E_star: float) -> float:
    """Length of the cohesive (process) zone at a crack tip, ``pi E* w / (4 sigma_0^2)`` [length]."""
    return math.pi * E_star * adhesion.work / (4.0 * adhesion.peak_stress**2) if adhesion.work > 0 else math.inf


def maugis_parameter(adhesion: Adhesion, E_star: float, radius: float) -> float:
    """Maugis' transition parameter ``lambda = 2 sigma_0 (R / (pi w K^2))^(1/3)``, ``K = 4 E* / 3``, of a
    tip of curvature radius ``radius`` [length]; ``lambda = 1.16 mu`` (Tabor's ``mu = (R w^2 / (E*^2
    z_0^3))^(1/3)``) for the Lennard-Jones equivalent. Large: the JKR limit; small: DMT."""
    K = 4.0 * E_star / 3.0
    return 2.0 * adhesion.peak_stress * (radius / (math.pi * adhesion.work * K**2)) ** (1.0 / 3.0)


def tip_radius(heights: np.ndarray, spacing: tuple[float, ...]) -> float:
    """Curvature radius [length] of the highest point: ``-1 / h''`` (1D) or ``-2 / lap h`` (2D, the mean
    curvature), by second differences (``inf`` where the summit is flat)."""
    index = np.unravel_index(int(np.argmax(heights)), heights.shape)
    curvature = 0.0
    for axis, dx in enumerate(spacing):
        n = heights.shape[axis]
        i = index[axis]
        lo, hi = list(index), list(index)
        lo[axis], hi[axis] = (i - 1) % n, (i + 1) % n
        curvature += (heights[tuple(lo)] - 2 * heights[index] + heights[tuple(hi)]) / dx**2
    curvature /= len(spacing)
    return -1.0 / curvature if curvature < 0 else math.inf


def scene_attrs(adhesion: Adhesion, heights: np.ndarray, spacing: tuple[float, ...], E_star: float) -> dict:
    """The law's attrs, plus (cohesive) the process zone in elements and the Maugis parameter of the
    highest summit; warns (:class:`CohesiveZoneWarning`) where the zone is under-resolved."""
    out = adhesion.attrs()
    if not adhesion.cohesive or adhesion.work == 0:
        return out
    zone = process_zone_length(adhesion, E_star)
    elements = zone / max(spacing)
    out.update(process_zone_length=zone, process_zone_elements=elements)
    radius = tip_radius(heights, spacing)
    if math.isfinite(radius):
        out.update(tip_radius=radius, maugis_parameter=maugis_parameter(adhesion, E_star, radius))
    if elements < ZONE_ELEMENTS:
        warnings.warn(
            f"adhesion: the process zone pi E* w / (4 sigma_0^2) = {zone:.3g} spans {elements:.2g} grid elements, "
            f"fewer than {ZONE_ELEMENTS:g}: the cohesive law is not resolved (refine the grid or widen the range)",
            CohesiveZoneWarning, stacklevel=4)
    return out
