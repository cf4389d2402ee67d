"""Contact solvers: plain functions sharing one signature, returning a :class:`ContactState`."""

from .active_set import solve_active_set
from .ccg import solve_polonsky_keer
from .coupled import solve_coupled
from .dual import solve_periodic_displacement
from .semismooth import solve_semismooth
from .splitting import solve_splitting
from .state import ContactState, contact_residual

__all__ = ["ContactState", "contact_residual", "solve_polonsky_keer", "solve_periodic_displacement", "solve_active_set",
           "solve_coupled", "solve_semismooth", "solve_splitting"]
