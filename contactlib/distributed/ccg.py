"""The Polonsky-Keer constrained conjugate gradient on slabs:
:func:`contactlib.solvers.symmetric.ccg.solve_polonsky_keer` with its sums reduced over the ranks.

The same algorithm, step for step: the same residual (:func:`contactlib.solvers.contact_residual`, from the
same fused sums), the same preconditioner (the Fourier multiplier ``E*|q|/2`` restricted to the contact set),
the same restart rule (:data:`contactlib.solvers.symmetric.ccg.RESTART_FRACTION`) and stall rule
(:data:`contactlib.solvers.symmetric.ccg.STALL_ITERATIONS`). Each rank runs the serial fused sweeps on its rows and the
sweeps' sums go through one ``Allreduce`` each, so every rank takes the same decisions; the iterates equal the
serial ones to round-off (the sums are added in another order).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numba
import numpy as np

from ..solvers.symmetric import fused as fz
from ..solvers.symmetric.ccg import RESTART_FRACTION, STALL_ITERATIONS
from ..solvers.state import residual_from_sums
from .operator import DistributedCompliance


@dataclass(frozen=True)
class LocalState:
    """A solve's answer on this rank's rows (fields) and over the whole grid (scalars)."""

    pressure: np.ndarray
    gap: np.ndarray
    displacement: np.ndarray
    penetration: float
    mean_pressure: float
    contact_area: float
    iterations: int
    residual: float
    converged: bool
    solver: str
    row_start: int
    shape: tuple[int, int]
    invariants_checked: str = ""
    """The invariants the converged state was checked against (:mod:`.checks`), comma-separated."""


def global_max(comm, value: float) -> float:
    from mpi4py import MPI  # the distributed path only

    return float(comm.allreduce(float(value), op=MPI.MAX))


@numba.njit(cache=True, nogil=True)
def _squares_about(values, mean):
    """``sum((values - mean)^2)`` without a temporary field."""
    total = 0.0
    for i in range(values.shape[0]):
        for j in range(values.shape[1]):
            d = values[i, j] - mean
            total += d * d
    return total


def global_height_scale(op: DistributedCompliance, heights: np.ndarray) -> float:
    """:func:`contactlib.solvers.state.height_scale` over the whole grid: the rms about the mean."""
    n = op.shape[0] * op.shape[1]
    mean = float(op.allsum(float(np.sum(heights)))[0]) / n
    s = float(np.sqrt(op.allsum(_squares_about(heights, mean))[0] / n))
    return s if s > 0 else 1.0


def solve_polonsky_keer(op: DistributedCompliance, heights: np.ndarray, *, mean_pressure: float | None = None,
                        penetration: float | None = None, tol: float = 1e-8, max_iter: int = 10_000,
                        precondition: bool = True, restart_fraction: float = RESTART_FRACTION,
                        verify: Callable[[LocalState], float] | None = None,
                        progress: Callable[[int, float], None] | None = None, row_start: int = 0,
                        overwrite_heights: bool = False) -> LocalState:
    """This rank's rows of the contact pressure under load or displacement control.

    Arguments as :func:`contactlib.solvers.symmetric.ccg.solve_polonsky_keer` (``heights``: this rank's rows);
    ``verify(state)``, a second residual evaluated once the loop's own reaches ``tol``, as there;
    ``progress(iteration, residual)`` after each evaluation (rank 0 logs); ``overwrite_heights``: the heights'
    buffer becomes the heights below their maximum (one field less per rank).
    """
    load_control = mean_pressure is not None
    precondition = precondition and (load_control or op.definite)
    n = op.shape[0] * op.shape[1]
    hmax = global_max(op.comm, heights.max())
    scale = global_height_scale(op, heights)
    if overwrite_heights:
        heights -= hmax
        hp = heights
    else:
        hp = heights - hmax
    del heights
    self_compliance = op.self_compliance()
    reentry = op.reentry_scale() if precondition else 1.0
    sweeps = fz.SERIAL

    def state(p, gap, approach, it, residual, displacement=None):
        disp = np.add(gap, hp) if displacement is None else np.add(gap, hp, out=displacement)
        disp += approach
        psum, n_contact = op.allsum(float(p.sum()), float(np.count_nonzero(p > 0)))
        return LocalState(pressure=p, gap=gap, displacement=disp, penetration=float(approach),
                          mean_pressure=float(psum) / n, contact_area=float(n_contact) / n, iterations=it,
                          residual=float(residual), converged=bool(residual <= tol), solver="polonsky-keer",
                          row_start=row_start, shape=op.shape)

    if load_control:
        if mean_pressure == 0:
            return zero_state(op, hp, scale, 0.0, row_start)
        start = float(mean_pressure)
    else:
        interference = np.maximum(hp + penetration, 0.0)
        if not op.allsum(float(interference.any()))[0]:
            return zero_state(op, hp, scale, float(penetration), row_start)
        start = interference / self_compliance
    transforms = op.iteration_transforms(hp)
    p, masked, t = transforms.pressure, transforms.residual, transforms.direction
    p[...] = start
    del start
    contact = p > 0.0
    n_contact = int(op.allsum(float(np.count_nonzero(contact)))[0])
    factor = mean_pressure * n / float(op.allsum(float(p.sum()))[0]) if load_control else 1.0
    unused = np.empty((1, 1))
    G_old, restart, t_kept = 1.0, True, 0.0
    residual, approach = np.inf, float(penetration or 0.0)
    best, best_it = np.inf, 0
    it = 0
    for it in range(max_iter + 1):
        w = transforms.displacement(1.0 / factor)
        if load_control:
            approach = factor * float(op.allsum(sweeps.contact_sum(w, contact))[0]) / n_contact
        comp, pen, G, psum = op.allsum(*sweeps.measure(w, factor, approach, p, masked if precondition else unused,
                                                       precondition))
        residual = own = residual_from_sums(comp, pen, psum, n, scale)
        if verify is not None and residual <= tol:
            residual = max(residual, verify(state(p * factor, factor * w - approach, approach, it, residual)))
        if progress is not None:
            progress(it, residual)
        if residual <= tol or it == max_iter:
            break
        if own < 0.99 * best:
            best, best_it = own, it
        elif it - best_it >= STALL_ITERATIONS:
            if restart_fraction == 0:
                break
            restart_fraction, best_it, restart = 0.0, it, True
        if precondition:
            z, G = transforms.precondition()
            z_sum = float(op.allsum(sweeps.contact_sum(z, contact))[0]) if load_control else 0.0
            z_scale, z_offset = 1.0, 0.0
        else:
            z, z_sum, z_scale, z_offset = w, 0.0, factor, approach
        beta = 0.0 if restart or G_old <= 0 else G / G_old
        G_old = G
        shift = z_offset + ((z_sum + beta * t_kept) / n_contact if load_control else 0.0)
        gt = float(op.allsum(sweeps.conjugate_direction(z, z_scale, shift, w, factor, approach, contact, beta,
                                                        t)[1])[0])
        tKt = transforms.direction_energy()
        tau = gt / tKt if tKt > 0 else 1.0 / (self_compliance * reentry)
        psum, n_overlap, t_kept, n_contact = op.allsum(*sweeps.step_project_reenter(
            p, factor, t, w, approach, tau, tau * reentry, contact))
        n_overlap, n_contact = int(n_overlap), int(n_contact)
        restart = n_overlap > restart_fraction * n_contact
        if load_control:
            if psum <= 0:  # lost every point: restart from the highest point (hp == 0 there)
                p[...] = np.where(hp == 0.0, 1.0, 0.0)
                np.greater(p, 0.0, out=contact)
                psum, n_contact = op.allsum(float(p.sum()), float(np.count_nonzero(contact)))
                n_contact, restart = int(n_contact), True
            factor = mean_pressure * n / psum
    # the answer in the transforms' own buffers, as the serial solver returns it: no grid-sized copies at the peak
    pressure, gap = p, w
    pressure *= factor
    gap *= factor
    gap -= approach
    return state(pressure, gap, approach, it, residual, displacement=masked)


def zero_state(op, hp, scale, penetration, row_start) -> LocalState:
    """No pressure: the gap of the undeformed surface (``-hp`` is the serial ``max(h) - h``, bit for bit)."""
    n = op.shape[0] * op.shape[1]
    g = -hp - penetration
    pen = float(op.allsum(float(np.sum(np.maximum(-g, 0.0))))[0]) / n / scale
    return LocalState(pressure=np.zeros_like(hp), gap=g, displacement=np.zeros_like(hp),
                      penetration=penetration, mean_pressure=0.0, contact_area=0.0, iterations=0, residual=pen,
                      converged=True, solver="polonsky-keer", row_start=row_start, shape=op.shape)
