"""Solvers of adhesive contact: the cohesive law as a term (frozen traction rounds :mod:`.cohesive`,
:mod:`.cohesive_rounds`, semismooth Newton :mod:`.cohesive_newton`, compiled sweeps :mod:`.sweeps`) and the JKR
energy method (:mod:`.energy`, its symmetry orbits :mod:`.energy_orbits`). Which one runs is chosen with the
adhesive scene, :mod:`contactlib.problems.adhesive_choice` (it needs the resolution guard, above the solvers)."""
