"""contactlib: rough-surface contact mechanics with FFT boundary elements.

The public API: :func:`solve` for normal contact (:func:`prepare` for a :class:`Problem` solved at many loads) on a
half-space or :class:`Layer` of an :class:`Elastic` or :class:`Viscoelastic` material, with Coulomb friction and
steady sliding, or with :class:`Adhesion` (and :func:`adhesion_curve` for loading-unloading paths);
:mod:`contactlib.surfaces` to generate surfaces or read measured ones (``surfaces.read``);
:mod:`contactlib.analysis` to measure them and their contact fields; :mod:`contactlib.accuracy` for the measured
grid and tolerance rules (``solve(..., target_error=...)``); :mod:`contactlib.two_scale` for fields of separate
spherical asperities (the seed's two-scale method: per-asperity forces with their interaction, then local FFT
solves).
"""

from . import accuracy, analysis, reference, resolution, surfaces, two_scale
from ._version import __version__
from .adhesion import Adhesion
from .adhesion_curve import adhesion_curve
from .bodies import Layer
from .contact import ConvergenceError, solve, solve_tolerances
from .grid import Grid
from .materials import Elastic, Viscoelastic
from .problem import Problem, prepare
from .reciprocating import solve_reciprocating
from .resolution import ResolutionWarning
from .speed_path import predict_pressure, solve_speeds
from .transient import TimeStepWarning, TransientInterrupted, solve_transient

__all__ = ["solve", "prepare", "Problem", "Adhesion", "adhesion_curve", "solve_transient", "solve_reciprocating",
           "TransientInterrupted",
           "TimeStepWarning", "ResolutionWarning",
           "solve_speeds", "predict_pressure",
           "Layer", "Elastic", "Viscoelastic", "solve_tolerances", "ConvergenceError", "Grid", "surfaces", "analysis",
           "reference", "accuracy", "resolution", "two_scale", "__version__"]
