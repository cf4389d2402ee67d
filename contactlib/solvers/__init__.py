"""Contact solvers by operator class: plain functions sharing one signature, returning a :class:`ContactState`
(:mod:`.state`, with the one residual). :mod:`.symmetric`, :mod:`.nonsymmetric` and :mod:`.adhesive` each hold their
solvers and the module that chooses among them; :mod:`.anderson` is the one Anderson mixer they share. Imports
:mod:`contactlib.core` and :mod:`contactlib.kernels` (and the cohesive law of :mod:`contactlib.model.adhesion`),
never a problem."""

from .nonsymmetric.coupled import solve_coupled
from .nonsymmetric.splitting import solve_splitting
from .state import ContactState, contact_residual
from .symmetric.active_set import solve_active_set
from .symmetric.ccg import solve_polonsky_keer
from .symmetric.dual import solve_periodic_displacement
from .symmetric.semismooth import solve_semismooth

__all__ = ["ContactState", "contact_residual", "solve_polonsky_keer", "solve_periodic_displacement", "solve_active_set",
           "solve_coupled", "solve_semismooth", "solve_splitting"]
