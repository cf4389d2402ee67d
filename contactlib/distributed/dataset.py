"""``contactlib.solve(heights, ..., comm=MPI.COMM_WORLD)``: the distributed solve (:func:`.normal_contact.solve`)
behind the serial entry point, its answer labelled as the serial one for this rank's rows.

Each rank passes its own rows of x of the heights (:func:`contactlib.distributed.slabs.slab_of` of a bare array
indexed ``[ix, iy]``, :func:`contactlib.distributed.io.read_slab`) or the generator's arguments, and gets a Dataset of
those rows: the fields on ``("y", "x")`` as the serial ones, with ``x`` its rows' positions in the window (so the
ranks' datasets concatenate along ``x``), the scalars of the whole grid, and ``attrs['row_start']`` / ``attrs['distributed_ranks']``. What is distributed: a 2D
elastic half-space with the spectral kernel, or a periodic frictionless layer, periodic or not, under load or
displacement control. The other options of :func:`contactlib.solve` are refused by name.
"""

from __future__ import annotations

import time

import numpy as np
import xarray as xr

from .._version import __version__
from ..core.inputs import in_solver_axes, lengths_of
from ..core.labels import SOLVER_AXES, attrs_for, field_variable
from ..errors import ConvergenceError
from ..model.materials import Elastic, contact_modulus
from .normal_contact import solve as distributed_solve

SERIAL_ONLY = {"friction": 0.0, "sliding_direction": None, "sliding_velocity": None, "adhesion": None,
               "kernel": "spectral", "method": "cg", "initial_pressure": None, "target_error": None,
               "contact_area": None}
"""The options of :func:`contactlib.solve` that the distributed path does not take, with the value that means
"not asked"."""


def solve(heights, *, comm, E, nu, material, layer, periodic, length, tol, max_iter, mean_pressure, penetration,
          length_unit: str = "m", pressure_unit: str = "Pa", **serial_only) -> xr.Dataset:
    """This rank's rows of the contact, labelled (arguments as :func:`contactlib.solve`).

    Parameters
    ----------
    heights : ndarray, xarray.DataArray or dict
        This rank's rows of the heights [length], or the keyword arguments of
        :func:`contactlib.surfaces.self_affine`.
    comm : mpi4py.MPI.Comm
        The ranks that share the grid.
    E, nu : float
        Young's modulus [pressure] and Poisson ratio (or ``material``, an :class:`contactlib.Elastic`).
    material : contactlib.Elastic or None
        The body's material.
    layer : contactlib.Layer or None
        A periodic, frictionless layer.
    periodic : bool or None
        Periodic window (default) or an isolated footprint.
    length : float or tuple
        Window size [length]; required for an array of heights.
    tol : float or None
        Target of the scale-free residual (default 1e-8).
    max_iter : int
        Iteration bound.
    mean_pressure, penetration : float
        The load, one of them.
    length_unit, pressure_unit : str
        udunits strings of the outputs.
    **serial_only
        The options only the serial path takes (:data:`SERIAL_ONLY`); each must have its "not asked" value.

    Returns
    -------
    xarray.Dataset
        ``pressure``, ``gap``, ``displacement`` on this rank's rows; the scalars of the whole grid.

    Raises
    ------
    ValueError
        Naming an option the distributed path does not take, or a bad value.
    ConvergenceError
        When the solve does not converge, with this rank's partial, labelled state.
    """
    for name, value in serial_only.items():
        if value is not SERIAL_ONLY[name] and value != SERIAL_ONLY[name]:
            raise ValueError(f"{name}: the distributed solve (comm=) takes a frictionless elastic half-space or "
                             f"periodic layer at rest; give {name}={SERIAL_ONLY[name]!r} or solve without comm")
    if material is not None:
        if not isinstance(material, Elastic) or E is not None or nu is not None:
            raise ValueError("material: the distributed solve (comm=) takes an Elastic material, or E and nu")
        E, nu = material.E, material.nu
    if E is None or nu is None:
        raise ValueError("E and nu (or material) are required")
    x_given = None
    if isinstance(heights, xr.DataArray):
        x_given = heights["x"].values if "x" in heights.coords else None
        heights = in_solver_axes(heights).values  # this rank's rows of x, [ix, iy]
    periodic = True if periodic is None else bool(periodic)
    tol = 1e-8 if tol is None else tol
    start = time.perf_counter()
    try:
        state = distributed_solve(heights, comm=comm, E=E, nu=nu, length=length, periodic=periodic,
                                  mean_pressure=mean_pressure, penetration=penetration, tol=tol, max_iter=max_iter,
                                  layer=layer)
    except ConvergenceError as err:
        state = err.state
        ds = _label(comm, state, heights, length, x_given, periodic, E, nu, tol, max_iter, mean_pressure,
                    time.perf_counter() - start, length_unit, pressure_unit)
        raise ConvergenceError(str(err), residual=err.residual, dataset=ds) from err
    return _label(comm, state, heights, length, x_given, periodic, E, nu, tol, max_iter, mean_pressure,
                  time.perf_counter() - start, length_unit, pressure_unit)


def _label(comm, state, heights, length, x_given, periodic, E, nu, tol, max_iter, mean_pressure, wall,
           length_unit, pressure_unit) -> xr.Dataset:
    def a(name):
        return attrs_for(name, length=length_unit, pressure=pressure_unit)

    lengths = lengths_of(heights.get("length", 1.0) if isinstance(heights, dict) else length, 2)
    nx, ny = state.shape
    rows = state.pressure.shape[0]
    x = x_given if x_given is not None else (state.row_start + np.arange(rows)) * (lengths[0] / nx)
    y = np.arange(ny) * (lengths[1] / ny)
    window_area = float(np.prod(lengths))
    scalars = {"contact_area": state.contact_area, "mean_pressure": state.mean_pressure,
               "penetration": state.penetration, "iterations": state.iterations, "residual": state.residual,
               "mean_gap": comm.allreduce(float(np.sum(state.gap))) / float(nx * ny)}
    if not periodic:
        scalars["normal_force"] = state.mean_pressure * window_area
        scalars["contact_radius"] = float(np.sqrt(state.contact_area * window_area / np.pi))
    data = {name: field_variable(SOLVER_AXES, getattr(state, name), a(name))  # rows of x, labelled on (y, x)
            for name in ("pressure", "gap", "displacement")}
    data.update({name: ((), value, a(name)) for name, value in scalars.items()})
    attrs = {"solver": state.solver, "periodic": int(periodic), "tol": tol, "max_iter": int(max_iter), "E": float(E),
             "nu": float(nu), "E_star": contact_modulus(E, nu),
             "load_control": "mean_pressure" if mean_pressure is not None else "penetration",
             "converged": int(state.converged), "wall_time": wall, "contactlib_version": __version__,
             "window_lengths": list(lengths), "distributed_ranks": comm.Get_size(), "row_start": state.row_start}
    if state.invariants_checked:
        attrs["invariants_checked"] = state.invariants_checked
    return xr.Dataset(data, coords={"x": ("x", x, a("x")), "y": ("y", y, a("y"))}, attrs=attrs)
