"""Micro scale: the pressure on each asperity from a local FFT solve, the others entering as a known
displacement (seed paper 1, second step).

The surface's grid is split into one small window per asperity, centred on the grid node nearest its
summit and aligned with the grid. Each outer iteration:

1. ``u_all = K p`` on the whole grid, one FFT convolution with the same operator as the full solver
   (:class:`contactlib.model.operators.Compliance`);
2. for each asperity, the displacement due to all the other pressures (and its own far images) on
   its window is ``u_ext = u_all - K_w p_k``, with ``K_w`` the zero-padded half-space kernel on the
   window; at the fixed point ``u_ext + K_w p_k = u_all`` is exactly the full solver's displacement,
   whatever ``K_w``, and the closer ``K_w`` is to the global kernel, the faster the sweep converges;
3. a constrained CG solve of each window alone, with the heights lowered by ``u_ext`` and masked to the
   asperity's footprint, at the common rigid approach: all windows at once, on a stack (:mod:`.local`);
4. a coarse correction by the macro model: the sweep changed the forces by ``dF`` but each asperity saw
   the others' old forces; the forces' answer to that, ``(S^-1 + T) c = -T dF`` on the contacts
   (``S``: Hertz stiffness ``2 E* a`` of each, ``T``: the point-load interaction), scales each
   asperity's new pressure by ``(F_k + c_k) / F_k``. Under load control the approach is a coarse unknown
   too, with ``sum (F + c) = P`` (the bordered system of the macro step).

Without step 4 the sweep is plain block Jacobi, which diverges in an oscillation of the collective mode
(all forces up, all displacements up, all forces down) once the body sags by as much as the summit
scatter (coverage 0.2 of 300 asperities: ratio about -1.4 per sweep).

The first ``p`` holds Hertz's pressure with the macro forces and contact radii. The iteration is a
block Jacobi sweep of the full problem; at its fixed point every local gap is the full solver's gap,
so the answer is the full solver's up to the tolerance. It stops when the relative change of the
whole pressure field, ``||p_new - p_old|| / ||p_new||``, and (load control) the relative force error
are both at most ``tol``; or, given ``force_tol``, when no asperity force would change by more than
``force_tol`` of the largest in the next sweep. That change is estimated before the next sweep's local
solves, from its step 1 (the convolution the returned fields need anyway, so a stop costs nothing more):
each contact answers the shift of its interference, smooth on it, like a rigid one, with its Hertz
stiffness (:func:`_next_force_change`; 10^3 asperities, coverage 0.05-0.4: 4.7e-4, 1.1e-3, 1.9e-3 after
one sweep against true errors of 4.2e-4, 9.9e-4, 1.9e-3). Stopping on the last sweep's own change instead
ran a second sweep whenever the macro start was more than ``force_tol`` off, though one sweep divides
that error by 5-10. A sweep divides the force error by 10-20 on the fields measured (1000 asperities,
coverage 0.05: 4e-3 from the macro step, then 4e-4, 2e-5, 2e-6).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from ..core.grid import Grid
from ..model.operators import Compliance
from ..solvers.state import residual_from_sums
from . import _window_sweeps as sweeps
from .asperities import AsperityTable
from .interaction import PointInteraction
from .local import WindowStack, solve_stack
from .compliance import solve_contact_compliance
from .macro import HertzLaw, MacroState

WINDOW_MARGIN = 1.15
"""Window half-width in macro contact radii (the largest), plus :data:`WINDOW_PAD` nodes."""
WINDOW_PAD = 1
"""One node: 14 instead of 16 nodes a side at 10^3 asperities, coverage 0.4 (contact radii about 3
nodes), 15 % of the two-scale time off, forces as close to the reference (2.1e-3 against 2.2e-3); a
contact that reaches the border still doubles the window (:func:`solve_micro`)."""
COARSE_RTOL = 1e-2
"""Largest relative residual of the coarse correction's linear solve; it follows the outer tolerance
(``tol`` or ``force_tol``) down to 1e-4. The fixed point does not depend on the correction, only a sweep's
contraction does: at ``force_tol=1e-2`` (10^3 asperities) 1e-2 instead of 1e-4 saves 2-9 products and moves
the forces by 1e-6-3e-6 of the largest at coverage 0.05-0.2 and 1.3e-3 at 0.4 (two sweeps; the error
against the full solver 2.42e-3 -> 2.44e-3), well inside the tolerance."""
LOCAL_TOL_FACTOR = 0.1
"""Local solves run at this fraction of the outer tolerance, so the outer change measures the coupling."""
SINGLE_PRECISION_TOL = 1e-4
"""Local tolerances of at least this apply the window compliance in single precision (2x faster products;
its rounding, about 1e-6 of the displacement, lies two orders below the tolerance; ``force_tol=1e-2``
gives local solves at 1e-3)."""


@dataclass(frozen=True)
class MicroState:
    """Two-scale solution on the surface's grid.

    Attributes
    ----------
    pressure, displacement, gap : ndarray
        Fields on the grid [pressure], [length], [length]; ``gap = displacement + z_top - h - delta``.
    force : ndarray
        Force on each asperity, ``sum p dA`` over its window [force].
    contact_nodes : ndarray
        Grid nodes in contact per asperity.
    penetration : float
        Rigid approach [length].
    iterations : int
        Outer (block Jacobi) iterations.
    local_iterations : int
        CG iterations of all local solves together.
    change : float
        Last relative change of the pressure field [1].
    residual : float
        :func:`contactlib.solvers.contact_residual` of the assembled fields [1].
    converged : bool
    window : int
        Window size in nodes.
    force_change : float
        Largest change of an asperity force over the largest force [1]: with ``force_tol``, the one the next
        sweep would make, estimated (the stop's measure); else the last sweep's.
    """

    pressure: np.ndarray
    displacement: np.ndarray
    gap: np.ndarray
    force: np.ndarray
    contact_nodes: np.ndarray
    penetration: float
    iterations: int
    local_iterations: int
    change: float
    residual: float
    converged: bool
    window: int
    force_change: float = math.nan


def hertz_pressure_field(table: AsperityTable, grid: Grid, force: np.ndarray, contact_radius: np.ndarray,
                         window: int, stack: tuple[np.ndarray, ...] | None = None) -> np.ndarray:
    """Hertz pressure ``p0 sqrt(1 - r^2/a^2)`` of each asperity sampled on the grid and scaled so that
    its nodes carry the force exactly [pressure]. ``stack``: :func:`_window_stack`'s output, if at hand."""
    rows, cols, masks, r2 = _window_stack(table, grid, window) if stack is None else stack
    local = np.empty(r2.shape)  # the whole discs (not cut at the footprints): the force is theirs
    sweeps.hertz_stack(np.asarray(force, dtype=float), np.asarray(contact_radius, dtype=float), r2,
                       grid.spacing[0] ** 2, masks, False, local)
    on = local > 0  # inside each contact disc: the discs lie in disjoint footprints, each node once
    field = np.zeros(grid.shape)
    field.ravel()[_flat_nodes(rows, cols, grid.shape[1])[on]] = local[on]
    return field


def window_size(table: AsperityTable, *, grid: Grid, contact_radius: np.ndarray) -> int:
    """Nodes per side of the local windows: the largest contact with :data:`WINDOW_MARGIN`, even."""
    h = grid.spacing[0]
    a = float(np.max(contact_radius)) if contact_radius.size else 0.0
    half = int(math.ceil(WINDOW_MARGIN * a / h)) + WINDOW_PAD
    return int(min(2 * half, grid.shape[0]))


def solve_micro(table: AsperityTable, macro: MacroState, law: HertzLaw, E_star: float, interaction: PointInteraction, *,
                z_top: float, total_force: float | None, tol: float, max_iter: int,
                known_displacement: np.ndarray | None = None, known_force: np.ndarray | None = None,
                initial_pressure: np.ndarray | None = None, local_max_iter: int = 10_000,
                force_tol: float | None = None) -> MicroState:
    """Refine the macro forces into the pressure field (see the module docstring).

    ``known_displacement`` [length], on the grid, is a displacement of the body that does not depend on
    the pressure sought (a time-stepping caller's history term, as in :func:`.solve_macro`): it enters
    every local problem and the gap; the returned ``displacement`` excludes it. ``known_force`` [force],
    per asperity, is the force of the pressure that causes it where that pressure and the one sought
    make one Hertz contact together (a viscoelastic step's history pressure ``g``: ``p + g`` is the
    Hertz-shaped field): the coarse correction then takes each contact's stiffness from ``P_k + G_k``,
    which only speeds the iteration up (its fixed point does not depend on it). ``initial_pressure``
    [pressure], on the grid, replaces Hertz's pressure of the macro forces as the first sweep's (a time
    stepper's previous step: a warm start, same fixed point). ``force_tol`` [1], when given, replaces the
    stop on the field change ``tol``: the sweeps stop once no asperity force changed by more than
    ``force_tol`` times the largest force in a next sweep, estimated (module docstring), and, under load
    control, the total is within ``force_tol``;
    the local solves then run at ``LOCAL_TOL_FACTOR * force_tol``.


    Parameters
    ----------
    table : AsperityTable
        The asperities with the surface's grid.
    macro : MacroState
        The macro step's forces, the sweeps' start.
    law : HertzLaw or TabulatedLaw
        The single-asperity law of the coarse correction.
    E_star : float
        Contact modulus [pressure].
    interaction : PointInteraction
        The macro interaction operator of the coarse correction.
    z_top : float
        Height of the highest summit [length].
    total_force : float or None
        Load control: the total force [force]; None: displacement control at ``macro.penetration``.
    tol : float
        Stop when the field changes by less than this between sweeps (relative).
    max_iter : int
        Bound on the sweeps.
    known_displacement : ndarray, optional
        A displacement that does not depend on the pressure sought [length] (above).
    known_force : ndarray, optional
        Per-asperity force of the pressure causing it [force] (above).
    initial_pressure : ndarray, optional
        The first sweep's pressure [pressure] (above).
    local_max_iter : int
        Iteration bound of each local solve.
    force_tol : float, optional
        Stop on the estimated change of the forces instead (above).


    Returns
    -------
    MicroState
        Fields, forces, approach, sweeps and convergence.

    Raises
    ------
    ValueError
        When a local contact reaches its asperity's footprint edge: the separate-contact assumption
        fails there.
    """
    if int(max_iter) < 1:
        raise ValueError(f"max_iter must be >= 1, got {max_iter!r}")
    radius = law.contact_radius(macro.local_penetration)
    window = window_size(table, grid=table.grid, contact_radius=radius)
    while True:
        try:
            return _solve_in_windows(table, macro, law, E_star, interaction, window, z_top=z_top,
                                     total_force=total_force, tol=tol, max_iter=max_iter,
                                     known_displacement=known_displacement, known_force=known_force,
                                     initial_pressure=initial_pressure, local_max_iter=local_max_iter,
                                     force_tol=force_tol)
        except _WindowTooSmall:  # a contact grew past the macro step's estimate: larger windows
            if window >= table.grid.shape[0]:
                raise ValueError("mean_pressure/penetration: a local contact fills its whole window") from None
            window = min(2 * window, table.grid.shape[0])


class _WindowTooSmall(Exception):
    """A local contact reached its window's border inside the footprint."""


def _solve_in_windows(table: AsperityTable, macro: MacroState, law: HertzLaw, E_star: float,
                      interaction: PointInteraction, window: int, *, z_top: float, total_force: float | None,
                      tol: float, max_iter: int, known_displacement: np.ndarray | None,
                      known_force: np.ndarray | None, initial_pressure: np.ndarray | None,
                      local_max_iter: int, force_tol: float | None = None) -> MicroState:
    """:func:`solve_micro` with windows of ``window`` nodes per side, all solved together on a stack
    (:mod:`.local`): the arrays ``(N, w, w)`` hold every asperity's window; the passes over them are
    compiled (:mod:`._window_sweeps`)."""
    grid, heights = table.grid, table.heights
    if known_displacement is not None:  # the same problem on shifted heights
        heights = heights - np.asarray(known_displacement, dtype=float)
    h = grid.spacing[0]
    dA = h * h
    radius = law.contact_radius(macro.local_penetration)
    # zero-padded windows for either kind of surface: their kernel decays like the global one, so the lagged
    # part u_all - K_w p_k is the small, smooth field of the far images (a periodic window's zero-mean shift
    # would be a large self-coupling the Jacobi sweep lags by one iteration, and oscillates on)
    local_tol = LOCAL_TOL_FACTOR * (tol if force_tol is None else force_tol)
    coarse_rtol = min(COARSE_RTOL, max(tol if force_tol is None else force_tol, 1e-4))
    stack = _window_stack_operator(window, h, E_star, local_tol >= SINGLE_PRECISION_TOL)
    global_op = Compliance(grid, E_star=E_star, periodic=table.periodic)
    rows, cols, masks, r2 = _window_stack(table, grid, window)
    edges = _footprint_edges(masks)
    height_stack = np.empty(masks.shape)
    sweeps.gather(heights, rows, cols, height_stack)
    own = np.empty(masks.shape)  # each asperity's pressure on its window
    if initial_pressure is None:  # Hertz's pressure of the macro forces: its discs lie inside the footprints
        sweeps.hertz_stack(macro.force, radius, r2, dA, masks, True, own)
        pressure = None  # the field is the stack's, scattered where needed
    else:
        pressure = np.array(initial_pressure, dtype=float)
        sweeps.gather(pressure, rows, cols, own)
        own *= masks
    # the pressure off the footprints (an initial_pressure's only): part of the first sweep's change
    off_footprints = 0.0
    if pressure is not None:
        off_footprints = max(float(np.sum(pressure * pressure)) - float(np.sum(own * own)), 0.0)
    delta = macro.penetration
    change, force_change, iterations, local_iterations = np.inf, np.inf, 0, 0
    own_displacement = None  # K_w p_k of each asperity's current pressure, from its last local solve
    last = None  # the last sweep's interference, contact stiffness and coarse change of the forces
    stop = False
    local = np.empty(masks.shape)
    top, low = np.empty(table.count), np.empty(table.count)
    # the convolution at the top of a sweep also serves the previous sweep's stop and the returned fields
    for it in range(1, max_iter + 2):
        if pressure is None:
            sweeps.scatter_footprints(own, masks, rows, cols, global_op.load())
        else:
            global_op.load()[...] = pressure
            pressure = None
        displacement = global_op.convolve()  # a view of the FFT buffer: copied only if kept
        body_level = z_top - delta  # undeformed body surface
        old_force = own.sum(axis=(1, 2)) * dA
        if own_displacement is None:
            own_displacement = stack(own)
        sweeps.local_heights(height_stack, displacement, rows, cols, own_displacement, masks, local, top, low)
        if force_tol is not None and last is not None:
            contact = own > 0
            # an asperity out of contact that the body now reaches: the law's force at its overlap
            arriving = np.where(contact.any(axis=(1, 2)), 0.0, law.force(top - body_level))
            force_change = _next_force_change(local - body_level, contact, old_force, *last, arriving)
            stop = force_change <= force_tol and force_error <= force_tol
        if stop or it > max_iter:
            break
        iterations = it
        touching = np.flatnonzero(top > body_level)
        every = touching.size == table.count  # no copies of the stacks for a subset
        if not every:
            patches, solved = np.zeros_like(own), np.zeros_like(own)
        if touching.size:
            # off the footprint the window is lowered below the footprint's lowest point: no contact there
            rigid = np.empty((touching.size,) + masks.shape[1:])
            scale = np.empty(touching.size)
            sweeps.interference(local, masks, touching, top, low, body_level, rigid, scale)
            warm = old_force[touching] > 0
            start = own if every else own[touching]  # solve_stack does not write into it
            cold = np.flatnonzero(~warm)
            if cold.size:
                start = start.copy() if every else start
                start[cold] = np.maximum(rigid[cold], 0.0) / stack.self_compliance
            # the warm start's displacement is at hand (own_displacement = K_w own): one product fewer
            known = None if cold.size else (own_displacement if every else own_displacement[touching])
            p_local, u_local, local_its, _ = solve_stack(stack, rigid, tol=local_tol, max_iter=local_max_iter,
                                                         initial_pressure=start, scale=scale,
                                                         initial_displacement=known)
            local_iterations += int(local_its.sum())
            p_local *= masks if every else masks[touching]
            _check_inside(p_local, edges if every else tuple(e[touching] for e in edges), touching)
            if every:
                patches, solved = p_local, u_local
            else:
                patches[touching] = p_local
                solved[touching] = u_local  # = K_w p_local: the pressure is zero off the footprint
        new_force = patches.sum(axis=(1, 2)) * dA
        hertz_force = new_force if known_force is None else np.where(new_force > 0, new_force + known_force, 0.0)
        slope = law.stiffness(hertz_force)
        factor, step = _coarse_correction(interaction, slope, old_force, new_force, total_force, rtol=coarse_rtol)
        solved_force = new_force.copy()
        delta += step
        # the change of the field from the stacks: both pressures lie on the footprints (but for an
        # initial_pressure's part off them, in the first sweep); K_w is linear, so the scaled
        # displacement needs no product next sweep
        norm, difference = sweeps.rescale(patches, solved, factor, own)
        change = math.sqrt(difference + off_footprints) / math.sqrt(norm) if norm > 0 else 0.0
        off_footprints = 0.0
        own, own_displacement = patches, solved
        new_force *= factor
        force_error = 0.0
        if total_force is not None and total_force > 0:
            force_error = abs(float(new_force.sum()) - total_force) / total_force
        if force_tol is None:
            largest = float(np.max(new_force)) if new_force.size else 0.0
            force_change = float(np.max(np.abs(new_force - old_force))) / largest if largest > 0 else 0.0
            stop = change <= tol and force_error <= tol
        else:  # the interference the sweep solved for; the coarse step's change of the forces on top of it
            last = (local - body_level, slope, new_force - solved_force)
    gap, kept = np.empty(grid.shape), np.empty(grid.shape)
    below, height_sum, height_squares = sweeps.gap_field(displacement, z_top - delta, heights, gap, kept)
    displacement = kept
    pressure = np.empty(grid.shape)
    sweeps.scatter_footprints(own, masks, rows, cols, pressure)
    force = own.sum(axis=(1, 2)) * dA
    nodes = np.count_nonzero(own > 0, axis=(1, 2))
    total, comp, pen, below_on = sweeps.footprint_sums(own, gap, rows, cols, masks)
    if below > below_on:  # off the footprints the body must stay clear of the surface
        off = np.ones(grid.shape, dtype=bool)
        off.ravel()[_flat_nodes(rows, cols, grid.shape[1])[masks]] = False
        raise ValueError(
            "mean_pressure/penetration: the body reaches the surface between the asperities' footprints (the gap "
            f"there falls to {float(gap[off].min()):.3g}): the load is beyond what separate spherical contacts "
            "carry, so the two-scale method does not apply")
    # off the footprints the pressure is zero and the gap positive: they add nothing but their count
    residual = residual_from_sums(comp, pen, total, gap.size, _height_scale(height_sum, height_squares, gap.size))
    converged = change <= tol if force_tol is None else force_change <= force_tol
    return MicroState(pressure, displacement, gap, force, nodes, float(delta), iterations, local_iterations, change,
                      residual, converged, window, force_change)


def _height_scale(total: float, squares: float, count: int) -> float:
    """:func:`contactlib.solvers.state.height_scale` (rms of the heights about their mean) from the sums of the
    ``count`` heights and of their squares (:func:`._window_sweeps.gap_field`'s pass). The caps' mean and rms are
    of one order, so ``E[h^2] - E[h]^2`` loses no digit that matters to a residual's scale."""
    mean = total / count
    variance = squares / count - mean * mean
    return math.sqrt(variance) if variance > 0 else 1.0


def _window_stack(table: AsperityTable, grid: Grid, window: int) -> tuple[np.ndarray, ...]:
    """Every asperity's window: the grid rows and columns of its nodes, ``(N, w)`` each (node ``(k, i, j)`` at
    ``(rows[k, i], cols[k, j])``), the mask of the nodes inside its footprint and their squared distances from
    its summit [length^2], ``(N, w, w)``. Each window is centred on the grid node nearest its summit and aligned
    with the grid, wrapped if periodic (else shifted inside the grid)."""
    count = table.count
    rows, cols = np.empty((count, window), np.int64), np.empty((count, window), np.int64)
    masks, r2 = np.empty((count, window, window), bool), np.empty((count, window, window))
    sweeps.window_nodes(np.ascontiguousarray(table.centers, dtype=float), float(grid.spacing[0]), int(grid.shape[1]),
                        int(window), bool(table.periodic), float(table.length),
                        np.ascontiguousarray(table.footprint_radius, dtype=float), rows, cols, masks, r2)
    return rows, cols, masks, r2


def _flat_nodes(rows: np.ndarray, cols: np.ndarray, n: int) -> np.ndarray:
    """The flat grid index of every window node, ``(N, w, w)``, on a grid of ``n`` columns."""
    return rows[:, :, None] * n + cols[:, None, :]


def _coarse_correction(interaction: PointInteraction, slope: np.ndarray, old_force: np.ndarray,
                       new_force: np.ndarray, total_force: float | None,
                       rtol: float = COARSE_RTOL) -> tuple[np.ndarray, float]:
    """Scale factors of the new asperity pressures and the approach step from the macro model (step 4);
    ``slope``: the single-asperity law's stiffness dF/dd of each new contact [force/length] (Hertz: ``2 E* a``)."""
    rhs = -interaction(new_force - old_force)
    # loosely: the fixed point does not depend on the correction, only the sweep's contraction does
    correction = solve_contact_compliance(interaction, slope, rhs, rtol=rtol)
    step = 0.0
    if total_force is not None and np.any(slope > 0):
        per_approach = solve_contact_compliance(interaction, slope, np.ones_like(slope), rtol=rtol)
        step = (total_force - float(new_force.sum()) - float(correction.sum())) / float(per_approach.sum())
        correction = correction + per_approach * step
    scale = np.ones_like(new_force)
    carried = new_force > 0
    scale[carried] = np.maximum(new_force[carried] + correction[carried], 0.0) / new_force[carried]
    return scale, step


def _next_force_change(interference: np.ndarray, contact: np.ndarray, force: np.ndarray, solved: np.ndarray,
                       slope: np.ndarray, coarse: np.ndarray, arriving: np.ndarray) -> float:
    """Largest change of an asperity force that the next sweep would make, over the largest force [1],
    estimated from its interference ``interference`` (N, w, w) [length] before its local solves.

    The last sweep solved each window at the interference ``solved``; the next one sees it moved by the
    others' new pressures (and the approach's step). Each contact answers a shift that is smooth on it
    (the far field of the others) like a rigid one, with its stiffness ``slope`` [force/length]: the mean
    shift over its contact nodes ``contact`` times the stiffness, less the coarse step's change ``coarse``
    [force] already in the forces ``force`` [force]; an asperity out of contact gains ``arriving`` [force].
    The local solves' own error is not in it: they run ten times tighter."""
    nodes = np.count_nonzero(contact, axis=(1, 2))
    shift = np.einsum("kij,kij->k", interference - solved, contact)
    predicted = slope * shift / np.maximum(nodes, 1) - coarse + arriving
    largest = float(force.max()) if force.size else 0.0
    return float(np.max(np.abs(predicted))) / largest if largest > 0 else 0.0


def _window_stack_operator(window: int, spacing: float, E_star: float, single: bool) -> WindowStack:
    """:class:`.local.WindowStack` with its dense matrix kept (about 1 ms to build; repeated solves, a
    study's loads or a transient's steps, have the same windows) and scratch buffers of its own (a copy:
    solves in threads do not share them)."""
    return _cached_window_stack(window, spacing, E_star, single).with_own_scratch()


@functools.lru_cache(maxsize=4)
def _cached_window_stack(window: int, spacing: float, E_star: float, single: bool) -> WindowStack:
    return WindowStack(window, spacing, E_star, single=single)


def _footprint_edges(mask: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For :func:`_check_inside`: the nodes next to a node off the footprint, and the window border's
    nodes that are not, stacks ``(N, w, w)`` of the footprint masks ``mask``."""
    edge, border = np.empty_like(mask), np.empty_like(mask)
    sweeps.footprint_edges(mask, edge, border)
    return edge, border


def _check_inside(p_local: np.ndarray, edges: tuple[np.ndarray, np.ndarray], which: np.ndarray) -> None:
    """Refuse a local contact that reaches the footprint's edge (a node in contact next to a node outside);
    one that reaches the window's border inside the footprint asks for larger windows. Stacks ``(M, w, w)``;
    ``edges``: :func:`_footprint_edges` of the stack's masks; ``which`` numbers the asperities of the stack."""
    contact = p_local > 0
    edge, border = edges
    if np.any(contact & border):
        raise _WindowTooSmall()
    reached = np.flatnonzero(np.any(contact & edge, axis=(1, 2)))
    if reached.size:
        raise ValueError(
            f"mean_pressure/penetration: the contact of asperity {int(which[reached[0]])} reaches the edge of its "
            "footprint: the load is beyond what separate spherical contacts carry, so the two-scale method does not "
            "apply")
