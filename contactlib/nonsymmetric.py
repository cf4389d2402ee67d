"""The non-symmetric scenes of :func:`contactlib.solve` (Coulomb friction coupled, steady viscoelastic sliding):
which of the three solvers of this class runs, and in what order the others follow it.

* The semismooth Newton loop with GMRES on each contact set (:mod:`.solvers.krylov`; on plates with the
  long-wave coarse space, :class:`.solvers.coarse.PlateCompliance`): periodic scenes under load control.
* The fixed point on the skew part around the symmetric constrained solver (:mod:`.solvers.coupled`):
  displacement control, non-periodic windows, and the fallback of the first.
* Douglas-Rachford on the whole complex multiplier (:mod:`.solvers.splitting`): loss-dominated bodies,
  after a bounded first try of the Newton loop, and the last fallback. Where the Newton loop applies, its
  iterates are handed to that loop (bounded by :data:`FINISH_ITERATIONS`) to finish from near the answer.
  Where it does not converge on a loss-dominated body, the fixed point is tried after it: on a thin confined
  layer with one point in contact (E_inf/E0 = 1000) Douglas-Rachford found that point only after 10 590
  iterations, the fixed point in 29. Where neither converges, the Newton loop is tried once more, from the
  better state: on a 64^2 surface at 99 % contact, sliding off the grid's axes (E_inf/E0 = 1000, V tau q0 =
  1e-3), Douglas-Rachford stagnated at 2e-5, the fixed point stalled at 2-3e-8, and the loop converged from
  the latter in 100 iterations. That stagnation was the viscoelastic factor's odd part on the Nyquist column
  (:mod:`.kernels.nyquist`); with it made even, Douglas-Rachford converges on that scene alone, and no scene
  known now reaches this last resort.

A converged answer is preferred to an unconverged one, and of two unconverged ones the smaller residual.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from .solvers import ContactState, coarse, krylov, solve_coupled, solve_semismooth, splitting


FINISH_ITERATIONS = 100
"""GMRES iterations of a Newton loop finishing a Douglas-Rachford solve (:func:`.splitting.solve_splitting`'s
``finish``). From iterates within 1e-4 the loop converged in 2-39 iterations on 1024-point profiles (E_inf/E0 =
1000, 0.3-4 % contact) and in 200-400 on 128^2 surfaces, where Douglas-Rachford itself needs only 500-1000: a
larger budget would cost more there than it saves."""

FINISH_SET_ITERATIONS = 30
"""GMRES iterations on one contact set in such a finish: the converging ones used at most 27."""


class NonSymmetricSolve:
    """The dispatch of a scene with a skew part, mixed into :class:`contactlib.contact._Setup` (which gives
    ``body``, ``grid``, ``values``, ``solver_args``, ``operator`` and ``_symmetric``)."""

    def _run_nonsymmetric(self) -> ContactState:
        """Solve a scene with a skew part, as the module docstring says."""
        first = None
        if self._krylov_applies():
            first = self._krylov()
            if first.converged:
                return first
        if self.operator.periodic and splitting.loss_dominated(self.body.factor):
            if first is None and self._finishable():
                first = self._krylov(first_try=True)  # cheap where it converges, bounded where it diverges
                if first.converged:
                    return first
            state = self._splitting()
            if not state.converged:  # the fixed point on the skew part may still converge
                coupled = solve_coupled(self._symmetric, self.body.coupling, self.values, **self.solver_args)
                state = coupled if coupled.converged or coupled.residual < state.residual else state
            if not state.converged and self._finishable():  # the last resort: the Newton loop from the best state
                finished = self._krylov(first_try=True, initial_pressure=state.pressure)
                if finished.converged:
                    state = dataclasses.replace(finished, iterations=state.iterations + finished.iterations,
                                                solver=f"{state.solver}+{finished.solver}")
        else:
            state = solve_coupled(self._symmetric, self.body.coupling, self.values, **self.solver_args)
            if not state.converged and self.operator.periodic:  # a stalled outer loop: the method that needs no split
                fallback = self._splitting()
                state = fallback if fallback.residual < state.residual else state
        if first is None or (state.converged and not first.converged):
            return state
        return state if not first.converged and state.residual <= first.residual else first

    def _finishable(self) -> bool:
        """Whether the bounded Newton loop can start from another solver's state: periodic, load control, no
        plate."""
        return (self.operator.periodic and self.solver_args["mean_pressure"] is not None
                and self.operator.preconditionable)

    def _krylov_applies(self) -> bool:
        """Periodic, load-controlled and not loss-dominated (where the sets cycle; Douglas-Rachford converges):
        the semismooth Newton loop with GMRES on the complex multiplier, the other solvers its fallback. A
        plate-like body's GMRES carries the long-wave coarse space (:class:`.coarse.PlateCompliance`)."""
        return (self.operator.periodic and self.solver_args["mean_pressure"] is not None
                and not splitting.loss_dominated(self.body.factor))

    def _krylov(self, first_try: bool = False, initial_pressure=None, budget: int | None = None,
                set_cap: int | None = None) -> ContactState:
        """The semismooth Newton loop with GMRES on each contact set (:mod:`contactlib.solvers.krylov`), from the
        warm start or from the symmetric part's constrained CG stopped early. ``first_try`` (a loss-dominated
        body, Douglas-Rachford after it): within :data:`~contactlib.solvers.krylov.TRY_ITERATIONS` in all,
        :data:`~contactlib.solvers.krylov.TRY_SET_ITERATIONS` a set, stopped on a residual growing past
        :data:`~contactlib.solvers.krylov.TRY_GROWTH` times its first set's (returned unconverged, with its
        residual); ``budget`` and ``set_cap``: its iterations in all and on one set (default the first try's),
        from ``initial_pressure`` when given (else the solve's own start)."""
        budget = krylov.TRY_ITERATIONS if budget is None else budget
        set_cap = krylov.TRY_SET_ITERATIONS if set_cap is None else set_cap
        args = self.solver_args
        if initial_pressure is not None:
            args = {**args, "initial_pressure": initial_pressure}
        max_iter = min(args["max_iter"], budget) if first_try else args["max_iter"]
        multiplier = splitting.fourier_multiplier(self.body.compliance, self.body.coupling)
        op = self.operator
        if op.preconditionable:
            body = krylov.ComplexCompliance(multiplier, self.grid, cap=set_cap if first_try else None)
        else:  # a plate: GMRES with the soft long waves solved exactly on each set
            modes = coarse.soft_modes(op.grid, op.multiplier * float(np.prod(op.work_shape)), op.E_star)
            body = coarse.PlateCompliance(multiplier, self.grid, modes)
        start, used = args["initial_pressure"], 0
        if start is None or not np.any(start > 0):
            tol = max(krylov.START_TOL, args["tol"])
            # a plate's semismooth start stops at that residual: asked to converge to it, its loose set solves
            # cycled between sets (2000 CG iterations at 50 % contact on 2^14 points, 260 to converge to 1e-8)
            stop = None if op.preconditionable else (lambda k, residual, snapshot: residual <= tol)
            first = self._symmetric(self.values, **{**args, "tol": tol, "max_iter": max_iter}, monitor=stop)
            start, used = first.pressure, first.iterations
        stall = krylov.Stall(growth=krylov.TRY_GROWTH) if first_try else krylov.Stall()
        state = solve_semismooth(body, self.values, mean_pressure=args["mean_pressure"], tol=args["tol"],
                                 max_iter=max(max_iter - used, 1), initial_pressure=start,
                                 set_solver=body.solve_on_set, name="semismooth-gmres", monitor=stall,
                                 set_floor=None if op.preconditionable else coarse.PLATE_SET_FLOOR)
        return dataclasses.replace(state, iterations=state.iterations + used, outer_iterations=stall.sets)

    def _splitting(self) -> ContactState:
        """Douglas-Rachford on the whole complex multiplier (:mod:`contactlib.solvers.splitting`), finished by the
        bounded Newton loop where that applies (periodic, load control, no plate)."""
        multiplier = splitting.fourier_multiplier(self.body.compliance, self.body.coupling)
        finish = None
        if self._finishable():
            def finish(pressure):
                return self._krylov(first_try=True, initial_pressure=pressure, budget=FINISH_ITERATIONS,
                                    set_cap=FINISH_SET_ITERATIONS)
        return splitting.solve_splitting(multiplier, self.values, **self.solver_args, finish=finish)
