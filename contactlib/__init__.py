"""contactlib: rough-surface contact mechanics with FFT boundary elements.

Entry points (each returns a labelled xarray.Dataset; heights from contactlib.surfaces or an array with length=):
  solve(heights, E=, nu=, mean_pressure= | penetration= | contact_area=)   normal contact on an elastic or
      viscoelastic half-space or Layer; friction=, sliding_velocity= (steady sliding), adhesion=, target_error=
  prepare(heights, ...) -> Problem: a scene validated once, solved at many loads
  solve_tolerances(heights, tols, ...)          one solve, the answers at several tolerances
  solve_speeds(heights, sliding_velocities, ...) steady sliding along a path of speeds, warm-started
  predict_pressure(speeds, pressures, speed)    the warm start solve_speeds uses
  solve_transient(heights, times=, material=, mean_pressure= | penetration=, path=)   viscoelastic time stepping
  solve_reciprocating(heights, amplitude=, frequency=, mean_pressure=, material=)   sliding back and forth
  adhesion_curve(heights, adhesion=, penetrations= | mean_pressures=)   loading-unloading path and pull-off
  two_scale.solve(asperities, ...), two_scale.solve_transient(...)   fields of separate spherical asperities
Bodies and interfaces: Elastic(E, nu), Viscoelastic(E0=, prony=, nu=), Layer(thickness, base=), Adhesion(work=, ...).
Modules: surfaces (self_affine, wavy, paraboloid, spheres, resample, read), analysis, reference (closed forms),
  accuracy (target_error rules), resolution (the resolution guard), invariants, two_scale; Grid.
Errors and warnings: ConvergenceError (with .residual and .dataset), invariants.InvariantError, ResolutionWarning,
  accuracy.AccuracyWarning, TimeStepWarning, TransientInterrupted; bad input raises ValueError naming the parameter.
Command line: ``contactlib surface ...`` and ``contactlib solve ...``; the study workflow: ``snakemake --cores 2``.
Documentation: ``sphinx-build -W -b html docs docs/_build/html`` (user guide per physics, tutorials, API).
"""

from . import accuracy, analysis, reference, resolution, surfaces, two_scale
from ._version import __version__
from .model.adhesion import Adhesion
from .problems.adhesion_curve import adhesion_curve
from .model.bodies import Layer
from .problems.contact import ConvergenceError, solve, solve_tolerances
from .core.grid import Grid
from .model.materials import Elastic, Viscoelastic
from .problems.problem import Problem, prepare
from .problems.reciprocating import solve_reciprocating
from .resolution import ResolutionWarning
from .problems.speed_path import predict_pressure, solve_speeds
from .problems.transient import TimeStepWarning, TransientInterrupted, solve_transient

__all__ = ["solve", "prepare", "Problem", "Adhesion", "adhesion_curve", "solve_transient", "solve_reciprocating",
           "TransientInterrupted",
           "TimeStepWarning", "ResolutionWarning",
           "solve_speeds", "predict_pressure",
           "Layer", "Elastic", "Viscoelastic", "solve_tolerances", "ConvergenceError", "Grid", "surfaces", "analysis",
           "reference", "accuracy", "resolution", "two_scale", "__version__"]
