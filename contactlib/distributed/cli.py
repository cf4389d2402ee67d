"""``mpirun -n K contactlib surface|solve ...``: the serial commands' distributed runs, writing the same files.

:mod:`contactlib.cli` hands a command over here when an MPI launcher started more than one rank
(:func:`.launch.launched_ranks`). Rank 0 logs and prints; every rank holds only its rows.
"""

from __future__ import annotations

import json
import sys
import time

import numpy as np
import xarray as xr

from .._version import __version__
from ..core.inputs import in_solver_axes
from ..core.labels import attrs_for
from .io import read_slab, write_slabs
from .surfaces import self_affine_slab


def _world():
    from mpi4py import MPI  # the distributed path only

    return MPI.COMM_WORLD


def _log(comm, message: str) -> None:
    if comm.Get_rank() == 0:
        print(message, file=sys.stderr, flush=True)


def surface(args, synthetic_length) -> int:
    """``contactlib surface`` (synthetic, 2D) by slabs: the same file as the serial command."""
    comm = _world()
    if args.source is not None:
        raise ValueError("--from: reading and preparing a measured surface is serial (it detrends and fills the "
                         "whole map); run `contactlib surface --from` without mpirun, then solve it with mpirun")
    missing = [f"--{k.replace('_', '-')}" for k in ("n", "hurst", "q_roll", "q_cutoff") if getattr(args, k) is None]
    if missing or (args.rms_height is None) == (args.rms_slope is None):
        raise ValueError(f"a synthetic surface needs {', '.join(missing) or 'exactly one of'} "
                         f"{'and one of ' if missing else ''}--rms-height or --rms-slope (or --from FILE)")
    start = time.perf_counter()
    h = self_affine_slab(comm, args.n, length=synthetic_length(args.length), hurst=args.hurst, q_low=args.q_low,
                         q_roll=args.q_roll, q_cutoff=args.q_cutoff, rms_height=args.rms_height,
                         rms_slope=args.rms_slope, seed=args.seed, dim=args.dim, anisotropy=args.anisotropy,
                         angle=args.angle)
    h.attrs["command"] = " ".join(sys.argv)
    _log(comm, f"contactlib surface: {args.n}x{args.n} on {comm.Get_size()} ranks in "
               f"{time.perf_counter() - start:.2f} s; writing {args.output}")
    x = np.concatenate(comm.allgather(h["x"].values))
    header = xr.Dataset(coords={"x": ("x", x, dict(h["x"].attrs)), "y": ("y", h["y"].values, dict(h["y"].attrs))})
    rows = in_solver_axes(h).values  # this rank's rows of x, [ix, iy]
    write_slabs(comm, args.output, shape=(x.size, rows.shape[1]), fields={"height": (rows, dict(h.attrs))},
                header=header)
    return 0


def _refuse_serial_only(args) -> None:
    """The options a distributed solve does not have (layers, friction, Love's kernel, the active set)."""
    serial = {"--variable": args.variable != "height", "--thickness": args.thickness is not None,
              "--friction": args.friction != 0.0, "--kernel love": args.kernel != "spectral",
              "--method active-set": args.method != "cg", "--fill": args.fill is not None,
              "--detrend": args.detrend not in (None, "none")}
    used = [name for name, given in serial.items() if given]
    if used:
        raise ValueError(f"{', '.join(used)}: not distributed (an elastic half-space, spectral kernel, CG, on a "
                         "prepared contactlib NetCDF surface); run without mpirun")


def solve(args) -> int:
    """``contactlib solve`` by slabs: the same file as the serial command (less the serial-only checks' attrs)."""
    from ..model.bodies import body_model
    from ..errors import ConvergenceError
    from ..core.grid import Grid
    from ..model.materials import Elastic, contact_modulus
    from .normal_contact import solve as distributed_solve

    comm = _world()
    _refuse_serial_only(args)
    length = None if args.length is None else (args.length[0] if len(args.length) == 1 else args.length)
    heights = read_slab(comm, args.surface, length=length, unit=args.unit, periodic=args.periodic)
    periodic = bool(heights.attrs["periodic"])
    lengths = tuple(heights.attrs["length"])
    rows = in_solver_axes(heights).values  # this rank's rows of x, [ix, iy]
    shape = (comm.allreduce(rows.shape[0]), rows.shape[1])
    _log(comm, f"contactlib solve: {shape[0]}x{shape[1]} on {comm.Get_size()} ranks, "
               f"{'periodic' if periodic else 'non-periodic'}")
    last = [time.perf_counter()]

    def progress(iteration: int, residual: float) -> None:
        now = time.perf_counter()
        if comm.Get_rank() == 0 and (iteration == 0 or now - last[0] >= 1.0):
            print(f"  iteration {iteration}: residual {residual:.3e} (tol {args.tol:.1e})", file=sys.stderr,
                  flush=True)
            last[0] = now

    start = time.perf_counter()
    status = 0
    try:
        state = distributed_solve(rows, comm=comm, E=args.E, nu=args.nu, length=lengths, periodic=periodic,
                                  mean_pressure=args.mean_pressure, penetration=args.penetration, tol=args.tol,
                                  max_iter=args.max_iter, progress=progress, overwrite_heights=True)
    except ConvergenceError as err:
        _log(comm, f"contactlib solve: {err}")
        state, status = err.state, 3
    wall = time.perf_counter() - start
    E_star = contact_modulus(args.E, args.nu)
    body = body_model(Grid((4, 4), lengths), material=Elastic(args.E, args.nu), layer=None, friction=0.0,
                      direction=0.0, tol=args.tol, kernel="spectral", periodic=periodic, velocity=None)
    full = comm.allreduce(bool(np.all(state.pressure > 0)), op=_land())
    attrs = {"Conventions": "CF-1.10", "solver": state.solver, "kernel": "spectral", "periodic": int(periodic),
             "tol": args.tol, "max_iter": int(args.max_iter), "E": float(args.E), "nu": float(args.nu),
             "E_star": E_star, "load_control": "mean_pressure" if args.mean_pressure is not None else "penetration",
             **body.attrs, "converged": int(state.converged), "wall_time": wall, "contactlib_version": __version__,
             "window_lengths": list(lengths), "full_contact": int(full)}
    if full:
        attrs["full_contact_message"] = ("full contact: every element carries pressure, so the contact area "
                                         "cannot grow with the load (a thin remote-pressure layer wraps the "
                                         "surface at a lower load than a thick one)")
    if not state.converged:
        attrs["convergence_message"] = (f"{state.solver} did not converge in {state.iterations} iterations: "
                                        f"residual {state.residual:.3e} > tol {args.tol:.1e}")
    if state.invariants_checked:
        attrs["invariants_checked"] = state.invariants_checked
    attrs.update(distributed_ranks=comm.Get_size(), source_surface=args.surface,
                 surface_attrs=json.dumps({k: str(v) for k, v in heights.attrs.items()}))
    scalars = {"contact_area": state.contact_area, "mean_pressure": state.mean_pressure,
               "penetration": state.penetration, "iterations": np.int64(state.iterations), "residual": state.residual}
    # the window's scalars of contactlib.core.labels.window_variables, from sums over the ranks
    scalars["mean_gap"] = comm.allreduce(float(np.sum(state.gap))) / float(np.prod(shape))
    if not periodic:
        window_area = float(np.prod(lengths))
        scalars["normal_force"] = state.mean_pressure * window_area
        scalars["contact_radius"] = float(np.sqrt(state.contact_area * window_area / np.pi))
    x = np.concatenate(comm.allgather(heights["x"].values))
    header = xr.Dataset({k: ((), v, attrs_for(k)) for k, v in scalars.items()},
                        coords={"x": ("x", x, dict(heights["x"].attrs)),
                                "y": ("y", heights["y"].values, dict(heights["y"].attrs))}, attrs=attrs)
    fields = {name: (getattr(state, name), attrs_for(name)) for name in ("pressure", "gap", "displacement")}
    write_slabs(comm, args.output, shape=shape, fields=fields, header=header)
    if comm.Get_rank() == 0:
        print(f"contact_area={state.contact_area:.6g} mean_pressure={state.mean_pressure:.6g} "
              f"penetration={state.penetration:.6g} iterations={state.iterations} residual={state.residual:.3e}")
    return status


def _land():
    from mpi4py import MPI

    return MPI.LAND
