"""Which solver runs on an adhesive scene (``adhesion=``): the one place that chooses among the adhesive solvers.

=====================================================  =========================================================
scene                                                  solver
=====================================================  =========================================================
``Adhesion("jkr", ...)``: the energy balance, no       the energy method (:func:`.adhesive.run_energy`,
cohesive stress (a profile symmetric about its          :mod:`contactlib.solvers.adhesive.energy`): the free energy of the
highest point, or a surface of revolution)              family of contact domains, the stable one at the approach
                                                       or the load
the same, with zero work of adhesion, or where the     the repulsive (frictionless) solve of
grid does not resolve the work at the domain found     :mod:`.solvers.symmetric_choice`
                                                       (:func:`.adhesive.plain_state`)
a cohesive law (``"maugis"``, ``"exponential"``, ...)  the cohesive solve (:func:`.adhesive.run`,
                                                       :func:`contactlib.solvers.adhesive.cohesive.solve_cohesive`): the
                                                       tensile traction frozen around the repulsive solve of
                                                       :mod:`.solvers.symmetric_choice`, then Newton on the
                                                       traction where the frozen rounds stall
=====================================================  =========================================================
"""

from __future__ import annotations

from . import adhesive
from ..model.adhesion import Adhesion
from .adhesive import AdhesiveState


def solve(problem, adhesion: Adhesion, *, warm_penetration=None) -> AdhesiveState:
    """Solve the adhesive scene of ``problem`` (a :class:`contactlib.Problem` with its load) as the table says;
    ``warm_penetration``: the cohesive solve's starting approach (a path's last, :func:`contactlib.adhesion_curve`)."""
    args = problem.solver_args
    if adhesion.model == "jkr":
        return adhesive.run_energy(problem, adhesion, args["mean_pressure"], args["penetration"])
    return adhesive.run(problem, adhesion, warm_penetration=warm_penetration)
