"""Which solver runs on a non-symmetric scene (Coulomb friction coupled, steady viscoelastic sliding: a body with a
skew part): the one place that chooses among the three solvers of this class, and in what order the others follow.

* The semismooth Newton loop with GMRES on each contact set (:mod:`.krylov`; on plates with the
  long-wave coarse space, :class:`.coarse.PlateCompliance`): periodic scenes under load control.
* The fixed point on the skew part around the symmetric constrained solver (:mod:`.coupled`):
  displacement control, non-periodic windows, and the fallback of the first.
* Douglas-Rachford on the whole complex multiplier (:mod:`.splitting`): loss-dominated bodies,
  after a bounded first try of the Newton loop, and the last fallback. Where the Newton loop applies, its
  iterates are handed to that loop (bounded by :data:`FINISH_ITERATIONS`) to finish from near the answer.
  Where it does not converge on a loss-dominated body, the fixed point is tried after it: on a thin confined
  layer with one point in contact (E_inf/E0 = 1000) Douglas-Rachford found that point only after 10 590
  iterations, the fixed point in 29. Where neither converges, the Newton loop is tried once more, from the
  better state: on a 64^2 surface at 99 % contact, sliding off the grid's axes (E_inf/E0 = 1000, V tau q0 =
  1e-3), Douglas-Rachford stagnated at 2e-5, the fixed point stalled at 2-3e-8, and the loop converged from
  the latter in 100 iterations. That stagnation was the viscoelastic factor's odd part on the Nyquist column
  (:mod:`contactlib.kernels.nyquist`); with it made even, Douglas-Rachford converges on that scene alone, and no scene
  known now reaches this last resort.

A converged answer is preferred to an unconverged one, and of two unconverged ones the smaller residual.
"""

from __future__ import annotations

import dataclasses
from functools import partial

import numpy as np

from ..symmetric import coarse
from .. import krylov
from . import splitting
from .coupled import solve_coupled
from ..symmetric.semismooth import solve_semismooth
from ..state import ContactState
from ..symmetric.choice import constrained_solve


FINISH_ITERATIONS = 100
"""GMRES iterations of a Newton loop finishing a Douglas-Rachford solve (:func:`.splitting.solve_splitting`'s
``finish``). From iterates within 1e-4 the loop converged in 2-39 iterations on 1024-point profiles (E_inf/E0 =
1000, 0.3-4 % contact) and in 200-400 on 128^2 surfaces, where Douglas-Rachford itself needs only 500-1000: a
larger budget would cost more there than it saves."""

FINISH_SET_ITERATIONS = 30
"""GMRES iterations on one contact set in such a finish: the converging ones used at most 27."""


def solve(problem) -> ContactState:
    """Solve a scene with a skew part, as the module docstring says: ``problem`` a :class:`contactlib.Problem` with its
    load (``body``, ``grid``, ``values``, ``solver_args``, ``operator``)."""
    first = None
    if krylov_applies(problem):
        first = solve_krylov(problem)
        if first.converged:
            return first
    if problem.operator.periodic and splitting.loss_dominated(problem.body.factor):
        if first is None and finishable(problem):
            first = solve_krylov(problem, first_try=True)  # cheap where it converges, bounded where it diverges
            if first.converged:
                return first
        state = solve_split(problem)
        if not state.converged:  # the fixed point on the skew part may still converge
            coupled = _coupled(problem)
            state = coupled if coupled.converged or coupled.residual < state.residual else state
        if not state.converged and finishable(problem):  # the last resort: the Newton loop from the best state
            finished = solve_krylov(problem, first_try=True, initial_pressure=state.pressure)
            if finished.converged:
                state = dataclasses.replace(finished, iterations=state.iterations + finished.iterations,
                                            solver=f"{state.solver}+{finished.solver}")
    else:
        state = _coupled(problem)
        if not state.converged and problem.operator.periodic:  # a stalled outer loop: the method that needs no split
            fallback = solve_split(problem)
            state = fallback if fallback.residual < state.residual else state
    if first is None or (state.converged and not first.converged):
        return state
    return state if not first.converged and state.residual <= first.residual else first


def _coupled(problem) -> ContactState:
    """The fixed point on the skew part around the symmetric constrained solve (:mod:`.coupled`)."""
    return solve_coupled(partial(constrained_solve, problem.operator), problem.body.coupling, problem.values,
                         **problem.solver_args)


def finishable(problem) -> bool:
    """Whether the bounded Newton loop can start from another solver's state: periodic, load control, no plate."""
    return (problem.operator.periodic and problem.solver_args["mean_pressure"] is not None
            and problem.operator.preconditionable)


def krylov_applies(problem) -> bool:
    """Periodic, load-controlled and not loss-dominated (where the sets cycle; Douglas-Rachford converges): the
    semismooth Newton loop with GMRES on the complex multiplier, the other solvers its fallback. A plate-like body's
    GMRES carries the long-wave coarse space (:class:`.coarse.PlateCompliance`)."""
    return (problem.operator.periodic and problem.solver_args["mean_pressure"] is not None
            and not splitting.loss_dominated(problem.body.factor))


def solve_krylov(problem, first_try: bool = False, initial_pressure=None, budget: int | None = None,
                 set_cap: int | None = None) -> ContactState:
    """The semismooth Newton loop with GMRES on each contact set (:mod:`.krylov`), from the warm start or from the
    symmetric part's constrained CG stopped early. ``first_try`` (a loss-dominated body, Douglas-Rachford after it):
    within :data:`~.krylov.TRY_ITERATIONS` in all, :data:`~.krylov.TRY_SET_ITERATIONS` a set, stopped on a residual
    growing past :data:`~.krylov.TRY_GROWTH` times its first set's (returned unconverged, with its residual);
    ``budget`` and ``set_cap``: its iterations in all and on one set (default the first try's), from
    ``initial_pressure`` when given (else the solve's own start). The GMRES set solves carry the problem's
    ``recycled`` Krylov vectors where it holds them (:mod:`.recycle`)."""
    budget = krylov.TRY_ITERATIONS if budget is None else budget
    set_cap = krylov.TRY_SET_ITERATIONS if set_cap is None else set_cap
    args = problem.solver_args
    if initial_pressure is not None:
        args = {**args, "initial_pressure": initial_pressure}
    max_iter = min(args["max_iter"], budget) if first_try else args["max_iter"]
    multiplier = splitting.fourier_multiplier(problem.body.compliance, problem.body.coupling)
    op = problem.operator
    space = getattr(problem, "recycled", None)
    if op.preconditionable:
        body = krylov.ComplexCompliance(multiplier, problem.grid, cap=set_cap if first_try else None, space=space)
    else:  # a plate: GMRES with the soft long waves solved exactly on each set
        modes = coarse.soft_modes(op.grid, op.multiplier * float(np.prod(op.work_shape)), op.E_star)
        body = coarse.PlateCompliance(multiplier, problem.grid, modes, space=space)
    start, used = args["initial_pressure"], 0
    if start is None or not np.any(start > 0):
        tol = max(krylov.START_TOL, args["tol"])
        # a plate's semismooth start stops at that residual: asked to converge to it, its loose set solves
        # cycled between sets (2000 CG iterations at 50 % contact on 2^14 points, 260 to converge to 1e-8)
        stop = None if op.preconditionable else (lambda k, residual, snapshot: residual <= tol)
        first = constrained_solve(op, problem.values, **{**args, "tol": tol, "max_iter": max_iter}, monitor=stop)
        start, used = first.pressure, first.iterations
    stall = krylov.Stall(growth=krylov.TRY_GROWTH) if first_try else krylov.Stall()
    state = solve_semismooth(body, problem.values, mean_pressure=args["mean_pressure"], tol=args["tol"],
                             max_iter=max(max_iter - used, 1), initial_pressure=start,
                             set_solver=body.solve_on_set, name="semismooth-gmres", monitor=stall,
                             set_floor=None if op.preconditionable else coarse.PLATE_SET_FLOOR)
    return dataclasses.replace(state, iterations=state.iterations + used, outer_iterations=stall.sets)


def solve_split(problem) -> ContactState:
    """Douglas-Rachford on the whole complex multiplier (:mod:`.splitting`), finished by the bounded Newton loop
    where that applies (periodic, load control, no plate)."""
    multiplier = splitting.fourier_multiplier(problem.body.compliance, problem.body.coupling)
    finish = None
    if finishable(problem):
        def finish(pressure):
            return solve_krylov(problem, first_try=True, initial_pressure=pressure, budget=FINISH_ITERATIONS,
                                set_cap=FINISH_SET_ITERATIONS)
    return splitting.solve_splitting(multiplier, problem.values, **problem.solver_args, finish=finish)
