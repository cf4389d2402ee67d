"""The cohesive law a solve runs on its grid: the user's, with Maugis' step ramped as wide as the grid needs.

The Maugis-Dugdale step is solved as a linear ramp of half-width ``e range`` about the range
(:data:`contactlib.adhesion.MAUGIS_RAMP`, ``e = 0.25``): the work stays ``w``. Its slope ``sigma_0 / (2 e range)``
against the compliance of one element ``K_ii`` (the displacement of an element under a unit pressure on it) is the
gain of a point on the ramp: where ``gain = sigma_0 K_ii / (2 e range) > 1`` the point's own equilibrium on the ramp
is unstable (its traction falls faster with the gap than its own compliance opens it), and every equilibrium with a
point there is a saddle. That happens where the process zone spans fewer than about two elements (a Maugis sphere
at lambda >= 5 on the 256^2 scene of issue 38): the frozen-traction rounds then cycle on the ramp points at a
residual of 1e-6 (lambda 3.5, gain 0.51) and the semi-smooth Newton swings between them. Two regularisations,
neither of which touches a zone the grid resolves:

* the ramp is widened until the gain is :data:`RAMP_GAIN` (at most :data:`MAX_RAMP`, a ramp from ``sigma_0`` at
  contact to 0 at twice the range): the same work and peak stress, the step smeared within the element the grid
  cannot resolve it in anyway. Up front where the gain at ``e = 0.25`` exceeds :data:`UNSTABLE_GAIN`; between
  :data:`RAMP_GAIN` and that, only when the law as asked fails (:meth:`GridLaw.widened`, in
  :func:`.cohesive.solve_cohesive`);
* below :data:`ZONE_FLOOR` elements across the zone, the peak stress is capped (the range lengthened, the work kept):
  a narrower zone makes a whole ring of ramp points unstable at once, and the lattice traps the contact edge (the
  parent returned a 128^2 sphere at lambda 10 converged with its contact radius 10 % short and its force 72 % off
  Maugis', the law holding on every open point).

:func:`contactlib.solve` says what was solved in ``attrs['adhesion_branch']``, and the invariants check the state
against that law.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from ...model.adhesion import MAUGIS_RAMP, Adhesion

ZONE_FLOOR = 1.7
"""The fewest elements across the process zone ``pi E* w / (4 sigma_0^2)`` a Maugis law is solved with: below, its
peak stress is lowered (its range lengthened, the work kept) until the zone spans this many, the finest zone the
grid holds. Issue 38's sphere on 256^2 converged at lambda 5 (1.7 elements, 4.5 s CPU) and failed at lambda 7 (0.88)
and 10 (0.43) even with the widest ramp: their zone rings are unstable as a whole (a line of ramp points has a
compliance of several ``K_ii``). What it costs: the answer is Maugis' at the grid's own largest lambda, which near
the JKR limit moves little (the closed form at the approach 0.002 of that scene: the force 0.4 % and the contact
radius 0.8 % from lambda 5 to 10); the :class:`~contactlib.adhesion.CohesiveZoneWarning` of fewer than 3 elements is
raised, and the result's ``attrs['adhesion_branch']`` says what was solved."""

RAMP_GAIN = 0.25
"""The gain ``sigma_0 K_ii / (2 e range)`` up to which the ramp keeps :data:`contactlib.adhesion.MAUGIS_RAMP`, and to
which it is widened (at most to :data:`MAX_RAMP`). Issue 38's sphere on 512^2 at lambda 7 and 10 (zones of 1.7
elements): at the parent's 0.45 (ramps of half-width 0.56-0.58 range) the last range stage of many path steps missed
from its warm start (Newton's steps flipping the contact edge near the answer, the frozen traction's finishing rounds
stalling at 1e-5), and 13-state paths took 200-500 s, with steps reached through midpoints; at 0.25 (the widest ramp
there) every step converged from its warm start, 98 s and 107 s (``benchmarks/bench_maugis.py``). The ramp then covers
three times the points (1160 to 3692 at lambda 7), the contact edge spread over several rings. Not the stability of the
answer: the largest eigenvalue of ``S^1/2 G S^1/2`` (``S`` the ramp's slopes, ``G`` the compliance of the open points
with the contact held) is 0.94-0.97 at both gains, on 256^2 and 512^2, as at the edge of a JKR-like contact. What it
costs: the law reaches further, to twice the range, and jumps in from further apart (that sphere at lambda 10: it
reaches 0.56e-3 apart against 0.44e-3, and jumps in between 0.57e-3 and 0.54e-3). On 256^2 at lambda 3.5 (gain 0.51
at e = 0.25) the law as asked cycled at residual 1.2e-6 for 90 rounds and failed in Newton; at e = 0.5 (gain 0.26) it
converged in the rounds alone, 0.27 % from Maugis' force. Between this gain and :data:`UNSTABLE_GAIN` the law is
solved as asked first, and widened only if that fails (the test suite's hard scenes: gain 0.42 at lambda 3.58 on
256^2)."""

MAX_RAMP = 1.0
"""The widest ramp: from ``sigma_0`` at contact to 0 at twice the range (the work still ``w``)."""

UNSTABLE_GAIN = 1.0
"""Above this gain at :data:`~contactlib.adhesion.MAUGIS_RAMP` a point on the ramp is unstable by itself, and the ramp
is widened from the start. Between :data:`RAMP_GAIN` and this, the law is solved as asked first and widened only if
that fails (:meth:`GridLaw.widened`): the test suite's 160^2 sphere at lambda 3.4 (gain 0.60) converges as asked."""


def element_compliance(operator) -> float:
    """The displacement [length] of an element under a unit pressure on it alone (the largest of the response to a
    point load; one FFT pair)."""
    field = np.zeros(operator.grid.shape)
    centre = tuple(s // 2 for s in field.shape)
    field[centre] = 1.0
    return float(operator(field)[centre])


@dataclasses.dataclass(frozen=True)
class GridLaw:
    """An :class:`contactlib.Adhesion` cohesive law (``adhesion``, the user's) as solved on a grid: ``solved``, the
    same law with its peak stress capped at ``stress_cap`` (:data:`ZONE_FLOOR`), and the ramp half-width ``ramp``
    (``e``) for the element compliance ``compliance`` (:func:`grid_law`). The solvers' interface of the law
    (``model``, ``work``, ``range``, ``peak_stress``, ``traction``, ``traction_slope``) is the solved one's."""

    adhesion: Adhesion
    solved: Adhesion
    ramp: float
    compliance: float
    stress_cap: float
    fallback_ramp: float = MAUGIS_RAMP

    model = property(lambda self: self.solved.model)
    work = property(lambda self: self.solved.work)
    range = property(lambda self: self.solved.range)
    peak_stress = property(lambda self: self.solved.peak_stress)
    cohesive = property(lambda self: True)

    @property
    def regularised(self) -> bool:
        """Whether the grid's law differs from the user's (a zone the grid does not resolve)."""
        return self.model == "maugis" and (self.ramp > MAUGIS_RAMP or self.solved != self.adhesion)

    def note(self) -> str:
        """What was solved, for ``attrs['adhesion_branch']``."""
        return (f"Maugis law solved as the grid resolves it: peak stress {self.peak_stress:.4g} (asked "
                f"{self.adhesion.peak_stress:.4g}; the process zone spans at least {ZONE_FLOOR:g} elements), range "
                f"{self.range:.4g}, the step a ramp of half-width {self.ramp:.3g} range (work kept)")

    def replace(self, **changes) -> GridLaw:
        """The law with ``work`` or ``range`` changed (a continuation stage), set again for the grid."""
        law = _build(dataclasses.replace(self.adhesion, **changes), self.compliance, self.stress_cap)
        wider = law.widened() if self.ramp > law.ramp else None  # widened here: widened there too
        return law if wider is None else wider

    def widened(self) -> GridLaw | None:
        """The law with the ramp widened to a gain of :data:`RAMP_GAIN` where it was kept as asked (a gain between
        that and :data:`UNSTABLE_GAIN`); None where there is nothing to widen."""
        if self.fallback_ramp <= self.ramp:
            return None
        return dataclasses.replace(self, ramp=self.fallback_ramp)

    def traction(self, gap: np.ndarray) -> np.ndarray:
        """The adhesive traction ``-sigma(max(g, 0))`` [pressure] (:meth:`contactlib.Adhesion.traction`, this
        ramp)."""
        if self.model != "maugis":
            return self.solved.traction(gap)
        g = np.maximum(gap, 0.0)
        e = self.ramp
        return -self.peak_stress * np.clip(((1 + e) * self.range - g) / (2 * e * self.range), 0.0, 1.0)

    def traction_slope(self, gap: np.ndarray) -> np.ndarray:
        """``d traction / d gap`` [pressure/length], ``>= 0``."""
        if self.model != "maugis":
            return self.solved.traction_slope(gap)
        g, e = np.asarray(gap), self.ramp * self.range
        return np.where((g > self.range - e) & (g < self.range + e) & (g > 0), self.peak_stress / (2 * e), 0.0)

    def interacting(self, gap: np.ndarray) -> np.ndarray:
        """:meth:`contactlib.Adhesion.interacting` of the solved law."""
        return self.solved.interacting(gap)


def _build(adhesion: Adhesion, compliance: float, stress_cap: float) -> GridLaw:
    solved, ramp, fallback = adhesion, MAUGIS_RAMP, MAUGIS_RAMP
    if adhesion.model == "maugis":
        if adhesion.peak_stress > stress_cap:
            solved = dataclasses.replace(adhesion, range=adhesion.work / stress_cap)
        needed = solved.peak_stress * compliance / (2.0 * solved.range * RAMP_GAIN)
        fallback = float(min(max(MAUGIS_RAMP, needed), MAX_RAMP))
        if needed * RAMP_GAIN / MAUGIS_RAMP > UNSTABLE_GAIN or solved != adhesion:
            ramp = fallback
    return GridLaw(adhesion, solved, ramp, float(compliance), float(stress_cap), fallback)


def grid_law(adhesion, operator) -> GridLaw:
    """``adhesion`` as solved on the grid of ``operator`` (a :class:`GridLaw` is returned as it is)."""
    if isinstance(adhesion, GridLaw):
        return adhesion
    zone_floor = ZONE_FLOOR * max(operator.grid.spacing)  # pi E* w / (4 sigma^2) >= that
    stress_cap = float(np.sqrt(np.pi * operator.E_star * adhesion.work / (4.0 * zone_floor)))
    return _build(adhesion, element_compliance(operator), stress_cap)
