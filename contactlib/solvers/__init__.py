"""Contact solvers: plain functions sharing one signature, returning a :class:`ContactState`."""

from .active_set import solve_active_set
from .ccg import solve_polonsky_keer
from .state import ContactState, contact_residual

__all__ = ["ContactState", "contact_residual", "solve_polonsky_keer", "solve_active_set"]
