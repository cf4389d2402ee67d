"""Constrained conjugate gradients for frictionless normal contact.

Polonsky & Keer (1999), doi:10.1016/S0043-1648(99)00113-1: conjugate gradients on the
current contact set, with projection onto ``p >= 0`` and re-entry of interpenetrating points
(which restarts the conjugacy when enough points re-enter: :data:`RESTART_FRACTION`). Load
control fixes ``mean(p)`` and finds the rigid approach as the mean gap offset over the contact
set; displacement control fixes the approach.

Per iteration one convolution ``K p`` and, for the step length, ``<t, K t>`` from the forward
transform of ``t`` alone (Parseval). The pressure, the masked gap and the direction live in the
input buffers of their transforms (:meth:`~contactlib.model.operators.Compliance.iteration_transforms`),
which never write over them; the heights are subtracted in Fourier space, so ``K p - hp`` comes out
of the inverse transform and no gap field is written. Everything else is fused sweeps
(:mod:`._fused`) with the approach subtracted inside them, over a byte mask of the contact set. The
Fourier preconditioner adds one FFT pair, a sum over the contact set, and gives ``<r, P r>`` by
Parseval. Under load control the search direction is centred exactly on the contact set (so a step
keeps the load), and the pressure is kept unnormalised and scaled to the load inside the sweeps.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from . import fused as fz
from ..state import ContactState, height_scale, residual_from_sums

RESTART_FRACTION = 0.01
"""The conjugacy restarts (``beta = 0``) when a step re-enters more than this fraction of the contact
set. Polonsky & Keer restart on any re-entry; on rough surfaces some points re-enter at nearly every
step, which left a preconditioned steepest descent (1024^2 at 48 % contact: 108 restarts in 109
iterations). Keeping the direction through small re-entries takes 1.15-1.8x fewer iterations at ~10 %
contact and 1.7-2.9x at ~50 % on 512^2-2048^2 grids, 1.5-5.3x on a 65536-point profile, to the same
accuracy at the same ``tol``; at 1 % contact or less it changes little, near full contact it may cost
a few (23 -> 32 at 97 %). A solve that stalls with it goes on with restarts on every re-entry
(``benchmarks/bench_restart.py``)."""

STALL_ITERATIONS = 500
"""Stop when the best residual has not dropped by 1 % for this many iterations: near round-off
(about 1e-12 relative on 2048^2 grids) the residual wanders instead of falling, and waiting for
``max_iter`` would cost minutes for nothing. A stall with the fraction rule of :data:`RESTART_FRACTION`
switches to restarts on every re-entry and gives that another ``STALL_ITERATIONS``; a stall then
returns the state as not converged."""


def solve_polonsky_keer(
    operator,
    heights: np.ndarray,
    *,
    mean_pressure: float | None = None,
    penetration: float | None = None,
    tol: float = 1e-8,
    max_iter: int = 10_000,
    initial_pressure: np.ndarray | None = None,
    precondition: bool = True,
    monitor: Callable[[int, float, Callable[[], ContactState]], None] | None = None,
    verify: Callable[[ContactState], float] | None = None,
    verify_below: float | None = None,
    restart_fraction: float = RESTART_FRACTION,
    rounds=None,
) -> ContactState:
    """Solve for the contact pressure under load or displacement control.

    Parameters
    ----------
    operator : Compliance
        Linear symmetric compliance whose ``iteration_transforms(offset)`` gives the loop's transforms
        on buffers of their own (see :class:`contactlib.model.operators.IterationTransforms`).
    heights : ndarray
        Rigid surface heights [length]; higher points touch first.
    mean_pressure, penetration : float
        Exactly one: the mean pressure over the window [pressure], or the rigid approach from
        first contact of the highest point [length].
    tol : float
        Target of :func:`~contactlib.solvers.contact_residual`, evaluated every iteration.
    initial_pressure : ndarray, optional
        Warm start (e.g. the previous point of a load path).
    precondition : bool
        Precondition the search direction with the inverse half-space kernel ``E*|q|/2`` restricted
        to the contact set (in the spirit of Vollebregt, J. Comput. Phys. 257, 333-351, 2014): one
        more FFT pair per iteration, 3-7x fewer iterations on rough surfaces (benchmarks/). Load
        control, and displacement control of non-periodic problems.
    monitor : callable, optional
        ``monitor(iteration, residual, snapshot)`` after each residual evaluation; ``snapshot()``
        returns the current iterate as a :class:`ContactState` (a copy, bit for bit what a solve
        stopping here would return). The iterates do not depend on ``tol``, so one solve at the
        tightest tolerance passes through every looser solve's answer.
    verify : callable, optional
        A second residual that must reach ``tol`` too: ``verify(state)`` for the current iterate,
        evaluated when the loop's own residual is at most ``verify_below`` (default ``tol``); the
        residual reported, monitored and tested is then the larger of the two. The dual solver
        (:mod:`.dual`) uses it to stop on the residual of the primal answer. The stall rule watches
        the loop's own residual only, so the iterates stay independent of ``tol`` and ``verify_below``.
    restart_fraction : float
        Restart the conjugacy when a step re-enters more than this fraction of the contact points
        (:data:`RESTART_FRACTION`); 0 restarts on any re-entry, as Polonsky & Keer do.
    rounds : object, optional
        Outer rounds that move the heights during the solve, without a new set-up (the frozen-traction
        cohesive iteration, :class:`contactlib.solvers.adhesive.cohesive_rounds.Rounds`). At each evaluation where
        ``rounds.due(iteration, residual)``, ``rounds.advance(p, factor, w, approach, hp, transforms)`` either
        returns None, which ends the solve at this iterate, or moves the heights: it lowers ``hp`` and the
        transforms' offset by ``K`` of a field, updates ``w`` to them in place and returns the new
        ``(mean_pressure, factor)`` (``(None, 1.0)`` under displacement control); the conjugacy then restarts.
        Only ``rounds`` ends such a solve before ``max_iter``: give ``tol`` 0.
    """
    load_control = mean_pressure is not None
    # Periodic displacement control has no load constraint to centre the direction, and the
    # periodic compliance is blind to the mean pressure (zero mode 0). Preconditioned, the first
    # steps overshoot to full contact (256^2, 64 % contact at the solution): there the direction's
    # mean has zero curvature, the step length blows up and p reaches 1e19. With the
    # preconditioner's zero mode set to 0 as well, it stays stuck at full contact instead. Plain CG
    # converges, slowly; contactlib.solve runs the dual problem there instead (.dual: the gap as
    # unknown, its mean fixed, preconditioned). A definite compliance (non-periodic, or a confined
    # compressible layer's) has no such mode, and the preconditioner works under either control.
    # A plate-like body (operator.preconditionable False) stalls preconditioned: see PRECONDITION_SOFTENING.
    precondition = precondition and (load_control or operator.definite) and operator.preconditionable
    hp = fz.as2d(heights - heights.max())  # <= 0; gap = K p - hp - approach
    scale = height_scale(heights)
    n = heights.size
    self_compliance = operator.self_compliance()
    # Re-entry sets p = -tau gap (Polonsky & Keer). Preconditioned, t is a pressure and tau is
    # dimensionless, so the gap needs a stiffness to become a pressure: without one, re-entered
    # pressures scaled with 1/E* and solves with E* ~ 1e-6 Pa never converged. The stiffness of the
    # longest wave keeps re-entry gentle; an element's own stiffness (1/self-compliance, about n/4
    # times larger on n x n points) overshot and diverged at ~45 % contact.
    reentry = operator.reentry_scale() if precondition else 1.0

    if load_control:
        if mean_pressure == 0:
            return zero_state(heights, penetration=0.0)
        start = float(mean_pressure) if initial_pressure is None else fz.as2d(np.maximum(initial_pressure, 0.0))
        if np.sum(start) <= 0:
            start = float(mean_pressure)  # a uniform start: no grid-sized temporary
    else:
        interference = np.maximum(hp + penetration, 0.0)
        if not interference.any():
            return zero_state(heights, penetration=float(penetration))
        start = interference / self_compliance if initial_pressure is None else \
            fz.as2d(np.maximum(initial_pressure, 0.0))
    shape = heights.shape
    with operator.iteration_transforms(offset=hp.reshape(shape)) as transforms:
        # p, the residual and t stay in the transforms' input buffers; w = K p - hp / factor comes out
        p, masked, t = fz.as2d(transforms.pressure), fz.as2d(transforms.residual), fz.as2d(transforms.direction)
        p[...] = start
        del start
        contact = p > 0.0
        n_contact = int(np.count_nonzero(contact))
        # the pressure is ``factor * p``: load control rescales it to the load lazily, inside the sweeps
        factor = mean_pressure * n / p.sum() if load_control else 1.0
        sweeps = fz.select(p.shape)
        unused = np.empty((1, 1))
        G_old, restart, t_kept = 1.0, True, 0.0
        residual, approach = np.inf, float(penetration or 0.0)
        best, best_it = np.inf, 0
        it = 0
        for it in range(max_iter + 1):
            # the gap is factor * w - approach: the heights are subtracted in Fourier space
            w = fz.as2d(transforms.displacement(1.0 / factor))
            if load_control:
                approach = factor * sweeps.contact_sum(w, contact) / n_contact
            comp, pen, G, psum = sweeps.measure(w, factor, approach, p, masked if precondition else unused, precondition)
            residual = residual_from_sums(comp, pen, psum, n, scale)
            own = residual
            if rounds is not None and rounds.due(it, residual):
                moved = rounds.advance(p, factor, w, approach, hp, transforms)
                if moved is None:
                    break
                mean_pressure, factor = moved  # the same p and contact set on the new heights
                if load_control:
                    approach = factor * sweeps.contact_sum(w, contact) / n_contact
                comp, pen, G, psum = sweeps.measure(w, factor, approach, p, masked if precondition else unused,
                                                    precondition)
                residual = own = residual_from_sums(comp, pen, psum, n, scale)
                restart, best, best_it = True, np.inf, it
            if verify is not None and residual <= (tol if verify_below is None else verify_below):
                residual = max(residual, verify(_state(p * factor, factor * w - approach, hp, shape, approach, it,
                                                       residual, tol)))
            if monitor is not None:
                monitor(it, residual, lambda f=factor, a=approach, i=it, r=residual, u=w:
                        _state(p * f, f * u - a, hp, shape, a, i, r, tol))
            if residual <= tol or it == max_iter:
                break
            if own < 0.99 * best:
                best, best_it = own, it
            elif it - best_it >= STALL_ITERATIONS:
                if restart_fraction == 0:
                    break
                # kept directions may stall a hard scene (a 65536-point profile at 20 % contact, seen with
                # other restart rules): go on from here restarting on every re-entry, which is slower but
                # steady, and stop only if that stalls too
                restart_fraction, best_it, restart = 0.0, it, True
            if precondition:  # z = P gap on the contact set; G = <masked gap, P masked gap>
                z, G = transforms.precondition()
                z = fz.as2d(z)
                z_sum = sweeps.contact_sum(z, contact) if load_control else 0.0
                z_scale, z_offset = 1.0, 0.0
            else:  # z = the gap, centred on the contact set under load control
                z, z_sum, z_scale, z_offset = w, 0.0, factor, approach
            beta = 0.0 if restart or G_old <= 0 else G / G_old
            G_old = G
            # under load control t is centred on the contact set, so a step keeps the load; t_kept is
            # the previous direction's sum over the current contact set
            shift = z_offset + ((z_sum + beta * t_kept) / n_contact if load_control else 0.0)
            gt = sweeps.conjugate_direction(z, z_scale, shift, w, factor, approach, contact, beta, t)[1]
            tKt = transforms.direction_energy()  # <t, K t> by Parseval: no inverse transform
            tau = gt / tKt if tKt > 0 else 1.0 / (self_compliance * reentry)  # no direction: re-entry only
            psum, n_overlap, t_kept, n_contact = sweeps.step_project_reenter(p, factor, t, w, approach, tau,
                                                                             tau * reentry, contact)
            restart = n_overlap > restart_fraction * n_contact
            if load_control:
                if psum <= 0:  # lost every point: restart from the highest point
                    p[...] = np.where(hp == hp.max(), 1.0, 0.0)
                    np.greater(p, 0.0, out=contact)
                    psum, n_contact, restart = p.sum(), int(np.count_nonzero(contact)), True
                factor = mean_pressure * n / psum
        # the answer in the buffers themselves (periodic): no grid-sized copy at the memory peak
        pressure = fz.as2d(transforms.take("pressure"))
        pressure *= factor
        gap = fz.as2d(transforms.take("displacement"))
        gap *= factor
        gap -= approach
        return _state(pressure, gap, hp, shape, approach, it, residual, tol, fz.as2d(transforms.take("residual")))


def _state(p, gap, hp, shape, approach, it, residual, tol, out=None) -> ContactState:
    """The iterate as a ContactState: ``p`` scaled to the load, ``gap`` shifted by the approach; the
    displacement is written to ``out`` if given."""
    # the gap was formed from K p of this very p: u = gap + hp + approach, without another convolution
    displacement = np.add(gap, hp, out=out)
    displacement += approach
    displacement = displacement.reshape(shape)
    return ContactState(
        pressure=p.reshape(shape), gap=gap.reshape(shape), displacement=displacement,
        penetration=float(approach), mean_pressure=float(p.mean()), iterations=it, residual=float(residual),
        converged=bool(residual <= tol), solver="polonsky-keer",
    )


def zero_state(heights: np.ndarray, *, penetration: float) -> ContactState:
    p = np.zeros_like(heights)
    g = heights.max() - heights - penetration
    pen = float(np.mean(np.maximum(-g, 0.0)) / height_scale(heights))
    return ContactState(
        pressure=p, gap=g, displacement=np.zeros_like(heights), penetration=penetration, mean_pressure=0.0,
        iterations=0, residual=pen, converged=True, solver="polonsky-keer",
    )
