"""contactlib: rough-surface contact mechanics with FFT boundary elements.

The public API: :func:`solve` for normal contact on a half-space or :class:`Layer`, with Coulomb
friction or :class:`Adhesion` (and :func:`adhesion_curve` for loading-unloading paths), :mod:`contactlib.surfaces` to
generate surfaces or read measured ones (``surfaces.read``), :mod:`contactlib.analysis` to measure them and their contact fields,
:mod:`contactlib.accuracy` for the measured grid and tolerance rules
(``solve(..., target_error=...)``).
"""

from . import accuracy, analysis, reference, surfaces
from ._version import __version__
from .adhesion import Adhesion
from .adhesion_curve import adhesion_curve
from .bodies import Layer
from .contact import ConvergenceError, solve, solve_tolerances
from .grid import Grid

__all__ = ["solve", "Adhesion", "adhesion_curve", "Layer", "solve_tolerances", "ConvergenceError", "Grid", "surfaces", "analysis", "reference", "accuracy", "__version__"]
