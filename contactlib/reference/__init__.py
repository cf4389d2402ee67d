"""Analytic reference solutions, shared by tests, benchmarks and figures: Hertz, Westergaard, the adhesive sphere and
cylinder (JKR, DMT, Maugis), the steadily sliding viscoelastic cylinder, Hunter's rolling cylinder and the
viscoelastic profile. All are imported here, so ``contactlib.reference.adhesive`` works without a separate import
(none of them imports the contact solvers' entry points: no cycle, and numpy and scipy only)."""

from . import adhesive, hertz, hunter, maugis, sliding_cylinder, viscoelastic_profile, westergaard

__all__ = ["adhesive", "hertz", "hunter", "maugis", "sliding_cylinder", "viscoelastic_profile", "westergaard"]
