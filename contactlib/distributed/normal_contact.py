"""The distributed elastic contact solve: :func:`solve`, each rank holding a slab of rows of every field."""

from __future__ import annotations

import dataclasses
from collections.abc import Callable

import numpy as np

from ..core.inputs import check_iterations, check_loads, check_tolerance, in_solver_axes, lengths_of, round_off_floor
from ..model.materials import contact_modulus
from .ccg import LocalState, solve_polonsky_keer
from .checks import verify_state
from .dual import solve_periodic_displacement
from .operator import DistributedCompliance
from .slabs import Slabs


def solve(heights, *, comm, E: float, nu: float, length=None, periodic: bool = True,
          mean_pressure: float | None = None, penetration: float | None = None, tol: float = 1e-8,
          max_iter: int = 10_000, progress: Callable[[int, float], None] | None = None,
          overwrite_heights: bool = False, layer=None) -> LocalState:
    """Frictionless contact of a rigid rough surface on an elastic half-space, over the ranks of ``comm``.

    The distributed counterpart of :func:`contactlib.solve` for a 2D elastic half-space with the spectral
    kernel: the same solvers (Polonsky-Keer, or its dual under periodic displacement control), the same
    residual and stopping rule, so the answer is the serial one to round-off.

    Parameters
    ----------
    heights : ndarray or dict
        This rank's rows of the heights [length] (rank ``r`` holds rows ``Slabs(nx, P).slice(r)``:
        :func:`contactlib.distributed.slabs.slab_of`, :func:`contactlib.distributed.io.read_slab`), or the
        keyword arguments of :func:`contactlib.surfaces.self_affine` (2D), from which each rank generates its own
        rows (:func:`contactlib.distributed.surfaces.self_affine_slab`; ``length`` then comes from them).
    comm : mpi4py.MPI.Comm
        The ranks that share the grid (``MPI.COMM_WORLD``).
    E, nu : float
        Young's modulus [pressure] and Poisson ratio.
    length : float or (float, float)
        Window size [length] (required for an array of heights).
    periodic : bool
        Periodic window, or an isolated footprint (the zero-padded transform on the doubled box).
    mean_pressure, penetration : float
        Exactly one: load or displacement control, as for :func:`contactlib.solve`.
    tol, max_iter : float, int
        Target of :func:`contactlib.solvers.contact_residual` and iteration bound.
    progress : callable, optional
        ``progress(iteration, residual)`` on every rank after each residual evaluation.
    layer : contactlib.Layer, optional
        A periodic, frictionless layer instead of the half-space (its compliance on each rank's spectral columns,
        :mod:`.layer`; reduced to the half-space where it is within tolerance of it, as :func:`contactlib.solve`
        does). A plate-like layer (the serial semismooth solver's) and a non-periodic one are refused.
    overwrite_heights : bool
        Let the solve reuse the heights' buffer (a float64 C-contiguous array) for the heights below their
        maximum: one field less per rank (the command line does; the caller's array is then changed).

    Returns
    -------
    LocalState
        This rank's rows of ``pressure``, ``gap``, ``displacement`` and the global ``contact_area``,
        ``mean_pressure``, ``penetration``, ``iterations``, ``residual``, ``converged``.

    Raises
    ------
    contactlib.ConvergenceError
        Unconverged at ``max_iter`` or stalled; ``err.state`` holds this rank's partial state.
    ValueError
        Bad input, named; non-periodic, a footprint that reaches the window's edge.
    """
    E_star = contact_modulus(E, nu)
    check_loads(mean_pressure, penetration)
    check_tolerance(tol, "tol")
    check_iterations(max_iter)
    if isinstance(heights, dict):
        from .surfaces import self_affine_slab

        spec = dict(heights)
        if length is not None and float(np.atleast_1d(length)[0]) != float(spec.get("length", 1.0)):
            raise ValueError(f"length={length!r} contradicts the surface's length={spec.get('length', 1.0)!r}")
        heights = self_affine_slab(comm, **spec)
        length = spec.get("length", 1.0)
    local = np.ascontiguousarray(in_solver_axes(heights), dtype=float)  # rows of x: a DataArray's by name
    if local.ndim != 2:
        raise ValueError(f"heights must be this rank's rows of a 2D surface, got {local.ndim} dimensions")
    if length is None:
        raise ValueError("length: the window size is required for an array of heights")
    lengths = lengths_of(length, 2)
    if not np.all(np.isfinite(local)):
        raise ValueError("heights contains NaN or infinite values")
    rows = comm.allgather((local.shape[0], local.shape[1]))
    nx, ny = sum(r for r, _ in rows), rows[0][1]
    expected = Slabs(nx, comm.Get_size()).counts
    if any(c != ny for _, c in rows) or [r for r, _ in rows] != list(expected):
        raise ValueError(f"heights: rank r must hold rows Slabs({nx}, {comm.Get_size()}).slice(r) of one grid, "
                         f"got (rows, columns) {rows}")
    row_start = int(Slabs(nx, comm.Get_size()).starts[comm.Get_rank()])
    op = DistributedCompliance(comm, (nx, ny), lengths, E_star=E_star, periodic=periodic, layer=layer, E=E, nu=nu,
                               tol=tol)
    height_max = comm.allreduce(float(local.max()), op=_max())  # before a solve that may overwrite the heights
    overwritten = overwrite_heights and local is heights
    if not op.definite and penetration is not None:
        state = solve_periodic_displacement(op, local, penetration=penetration, tol=tol, max_iter=max_iter,
                                            progress=progress, row_start=row_start)
    else:
        state = solve_polonsky_keer(op, local, mean_pressure=mean_pressure, penetration=penetration, tol=tol,
                                    max_iter=max_iter, progress=progress, row_start=row_start,
                                    overwrite_heights=overwritten)
    if not periodic:
        _check_window(op, state.pressure, row_start)
    if not state.converged:
        from ..errors import ConvergenceError

        message = (f"{state.solver} did not converge in {state.iterations} iterations: residual "
                   f"{state.residual:.3e} > tol {tol:.1e}")
        err = ConvergenceError(message, residual=state.residual, dataset=None)
        err.state = state
        raise err
    below_max = local if overwritten else local - height_max  # the overwritten buffer holds h - max h already
    checked = verify_state(comm, state, below_max, height_max, tol=tol, mean_pressure=mean_pressure,
                           penetration=penetration)
    return dataclasses.replace(state, invariants_checked=checked)


def _max():
    from mpi4py import MPI  # the distributed path only

    return MPI.MAX


def _check_window(op: DistributedCompliance, pressure: np.ndarray, row_start: int) -> None:
    """:meth:`contactlib.problems.contact._Setup.check_window` over the ranks: compression on the window's edge."""
    from mpi4py import MPI  # the distributed path only

    peak = op.comm.allreduce(float(np.max(np.abs(pressure), initial=0.0)), op=MPI.MAX)
    floor = round_off_floor(np.array([peak]))
    edges = [pressure[:, 0], pressure[:, -1]]
    if row_start == 0:
        edges.append(pressure[0])
    if row_start + pressure.shape[0] == op.shape[0]:
        edges.append(pressure[-1])
    touches = op.comm.allreduce(any(bool(np.any(e > floor)) for e in edges), op=MPI.LOR)
    if touches:
        raise ValueError("periodic=False: the contact reaches the edge of the window, so the surface outside it "
                         "would carry load too; enlarge the window (or use periodic=True for a periodic surface)")
