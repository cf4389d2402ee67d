"""Which solver runs on a symmetric compliance (frictionless contact of an elastic body, or a viscoelastic one at rest,
a half-space or a layer): the one place that chooses among the three solvers of this class.

==================================================  ============================================================
scene                                               solver
==================================================  ============================================================
``method="active-set"`` (the user's choice)         the seed paper's active set + Gauss-Seidel
                                                    (:func:`.active_set.solve_active_set`): small grids, a cross-check
a plate-like body (a thin remote-pressure layer:    semismooth Newton with a coarse space of the soft long waves
not :attr:`~contactlib.model.operators.Compliance.        (:func:`.semismooth.solve_semismooth`, sets floored at
preconditionable`), either control                  :data:`.coarse.PLATE_SET_FLOOR`): the dual iteration stalled there
                                                    beyond about 5 % contact at q0 h = 0.1
periodic displacement control (an indefinite        the dual of Polonsky-Keer, the gap as unknown
compliance: its mean mode is free)                  (:func:`.dual.solve_periodic_displacement`): the primal iteration
                                                    cannot be preconditioned there
everything else                                     Polonsky-Keer's constrained conjugate gradients
                                                    (:func:`.ccg.solve_polonsky_keer`)
==================================================  ============================================================

The non-symmetric scenes (friction coupled, steady viscoelastic sliding) are chosen in :mod:`.nonsymmetric_choice`,
which runs :func:`constrained_solve` as its inner solver; adhesive ones in :mod:`contactlib.problems.adhesive_choice`.
"""

from __future__ import annotations

from .active_set import solve_active_set
from .ccg import solve_polonsky_keer
from .coarse import PLATE_SET_FLOOR
from .dual import solve_periodic_displacement
from .semismooth import solve_semismooth
from ..state import ContactState


def solve(problem, *, monitor=None, verify_below=None) -> ContactState:
    """Solve a frictionless scene on a symmetric compliance: ``problem`` a :class:`contactlib.Problem` with its load
    (``operator``, ``values``, ``method``, ``solver_args``). ``monitor``, ``verify_below``: see
    :func:`constrained_solve`."""
    if problem.method == "cg":
        return constrained_solve(problem.operator, problem.values, monitor=monitor, verify_below=verify_below,
                                 **problem.solver_args)
    args = {k: v for k, v in problem.solver_args.items() if k != "initial_pressure"}
    return solve_active_set(problem.operator, problem.values, **args)


def constrained_solve(operator, heights, *, monitor=None, verify_below=None, restart_fraction=None,
                      **args) -> ContactState:
    """Frictionless contact on a symmetric compliance by the constrained iterations of the module's table:
    Polonsky-Keer, its dual under periodic displacement control, or, on a plate-like body, the semismooth Newton
    method with a coarse space under either control.
    ``args``: ``mean_pressure``, ``penetration`` (one of them None), ``tol``, ``max_iter``, ``initial_pressure``;
    ``restart_fraction``: Polonsky-Keer's (default :data:`contactlib.solvers.symmetric.ccg.RESTART_FRACTION`; the dual
    restarts on every re-entry); ``verify_below``: see :func:`contactlib.solvers.solve_periodic_displacement`."""
    if not operator.preconditionable:
        return solve_semismooth(operator, heights, monitor=monitor, set_floor=PLATE_SET_FLOOR, **args)
    if not operator.definite and args["penetration"] is not None:
        args = {k: v for k, v in args.items() if k != "mean_pressure"}
        return solve_periodic_displacement(operator, heights, monitor=monitor, verify_below=verify_below, **args)
    if restart_fraction is not None:
        args["restart_fraction"] = restart_fraction
    return solve_polonsky_keer(operator, heights, monitor=monitor, **args)
