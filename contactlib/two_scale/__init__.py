"""The two-scale asperity method (seed paper 1): macro-scale forces per asperity with their elastic
interaction, then micro-scale local FFT solves, for fields of separate spherical asperities.

:func:`solve` is the elastic half-space; :func:`solve_transient` the viscoelastic extension (the seed's
last paragraph), the same two scales inside each step of :func:`contactlib.solve_transient`'s time
stepping (:mod:`.transient`).
"""

from .asperities import AsperityTable, asperity_forces, asperity_table
from .fields import random_asperity_field
from .interaction import PointInteraction
from .laws import TabulatedLaw, tabulated_law
from .macro import HertzLaw, MacroState, solve_macro
from .micro import MicroState, solve_micro
from .scene import SCALES
from .static import solve
from .transient import solve_transient

__all__ = ["solve", "solve_transient", "asperity_table", "asperity_forces", "random_asperity_field", "AsperityTable",
           "PointInteraction", "HertzLaw", "TabulatedLaw", "tabulated_law", "solve_macro", "solve_micro",
           "MacroState", "MicroState", "SCALES"]
