"""Public entry point for frictionless normal contact: :func:`solve`."""

from __future__ import annotations

import dataclasses
import math
import time

import numpy as np
import xarray as xr

from . import accuracy
from ._version import __version__
from .grid import Grid
from .labels import attrs_for
from .materials import contact_modulus
from .operators import KERNELS, Compliance
from .solvers import ContactState, solve_active_set, solve_periodic_displacement, solve_polonsky_keer

METHODS = ("cg", "active-set")


class ConvergenceError(RuntimeError):
    """A solve did not reach its tolerance within ``max_iter``, or stalled before it (the CG
    residual stopped falling, e.g. at the round-off floor of a tolerance set too tight).

    Attributes
    ----------
    residual : float
        The residual reached.
    dataset : xarray.Dataset
        The partial (unconverged) state, labelled like a converged one, ``attrs['converged'] = 0``.
    datasets : list of xarray.Dataset or None
        From :func:`solve_tolerances`: the answer at every tolerance asked, reached or not.
    """

    def __init__(self, message: str, *, residual: float, dataset: xr.Dataset):
        super().__init__(message)
        self.residual = residual
        self.dataset = dataset
        self.datasets = None


def grid_of(heights, length=None) -> tuple[np.ndarray, Grid, tuple[str, ...], dict]:
    """Heights array, grid, dim names and coords of a DataArray or ndarray input."""
    if isinstance(heights, xr.DataArray):
        values = np.asarray(heights.values, dtype=float)
        dims = tuple(heights.dims)
        if length is None:
            lengths = []
            for d in dims:
                if d not in heights.coords:
                    raise ValueError(f"heights: dimension {d!r} has no coordinate; pass length=")
                c = np.asarray(heights[d].values, dtype=float)
                if c.size < 2:
                    raise ValueError(f"heights: grid smaller than 2 points along {d!r}")
                lengths.append(float(c[1] - c[0]) * c.size)
            lengths = tuple(lengths)
        else:
            lengths = _lengths(length, values.ndim)
        coords = {d: heights[d] for d in dims if d in heights.coords}
    else:
        values = np.asarray(heights, dtype=float)
        if values.ndim not in (1, 2):
            raise ValueError(f"heights must be 1D or 2D, got {values.ndim} dimensions")
        dims = ("x", "y")[: values.ndim]
        lengths = _lengths(1.0 if length is None else length, values.ndim)
        coords = {}
    if values.ndim not in (1, 2):
        raise ValueError(f"heights must be 1D or 2D, got {values.ndim} dimensions")
    if min(values.shape) < 2:
        raise ValueError(f"heights: grid smaller than 2 points, shape {values.shape}")
    if not np.all(np.isfinite(values)):
        raise ValueError("heights contain NaN or infinite values")
    grid = Grid(values.shape, lengths)
    if not coords:
        coords = {d: (d, c) for d, c in zip(dims, grid.coordinates())}
    return np.ascontiguousarray(values), grid, dims, coords


def _lengths(length, ndim: int) -> tuple[float, ...]:
    lengths = tuple(float(v) for v in np.broadcast_to(np.asarray(length, dtype=float), (ndim,)))
    for v in lengths:
        if not math.isfinite(v) or v <= 0:
            raise ValueError(f"length must be finite and > 0, got {length!r}")
    return lengths


def _check_tolerance(value, name: str) -> None:
    if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
        raise ValueError(f"{name} must be finite and > 0, got {value!r}")


def _check_loads(mean_pressure, penetration) -> None:
    if (mean_pressure is None) == (penetration is None):
        raise ValueError("give exactly one of mean_pressure or penetration")
    if mean_pressure is not None and (not math.isfinite(mean_pressure) or mean_pressure < 0):
        raise ValueError(f"mean_pressure must be finite and >= 0, got {mean_pressure!r}")
    if penetration is not None and not math.isfinite(penetration):
        raise ValueError(f"penetration must be finite, got {penetration!r}")


def solve(
    heights,
    *,
    E: float,
    nu: float,
    mean_pressure: float | None = None,
    penetration: float | None = None,
    periodic: bool = True,
    tol: float | None = None,
    max_iter: int = 10_000,
    kernel: str = "spectral",
    method: str = "cg",
    length=None,
    initial_pressure=None,
    length_unit: str = "m",
    pressure_unit: str = "Pa",
    target_error: float | None = None,
) -> xr.Dataset:
    """Frictionless normal contact of a rigid rough surface on an elastic half-space.

    Parameters
    ----------
    heights : xarray.DataArray or ndarray
        Rigid surface heights [length], 1D (plane strain, per unit width) or 2D. Higher points
        touch first. A DataArray's coordinates give the physical size; an ndarray needs ``length``.
    E, nu : float
        Young's modulus [pressure] and Poisson ratio of the body, ``E > 0``, ``-1 < nu <= 0.5``.
    mean_pressure : float
        Load control: mean pressure over the window [pressure] (1D: line load per unit width over
        the window length). Non-periodic: total load divided by the window area.
    penetration : float
        Displacement control: rigid approach from first contact of the highest point [length].
        Periodic displacements are zero-mean (the q = 0 mode of a half-space is infinite), so the
        approach is measured against the mean deformed plane; beyond full contact it does not fix
        the load and is refused.
    periodic : bool
        Periodic window (default) or an isolated footprint (zero padding, free boundary).
    tol : float, optional
        Target of the scale-free residual (:func:`contactlib.solvers.contact_residual`); default
        1e-8, or the rule of ``target_error``.
    max_iter : int
        Iteration bound; beyond it :class:`ConvergenceError` is raised with the partial state.
    kernel : {"spectral", "love"}
        Continuous multiplier ``2/(E*|q|)`` or Love's uniform-element kernel.
    method : {"cg", "active-set"}
        Polonsky-Keer constrained conjugate gradients, or the seed paper's active-set +
        Gauss-Seidel scheme (small grids; a cross-check).
    length : float or tuple, optional
        Window size [length] for ndarray heights (default 1).
    initial_pressure : ndarray, optional
        Warm start for ``method="cg"``.
    length_unit, pressure_unit : str
        udunits strings written to the output's ``units`` attributes.
    target_error : float, optional
        Relative error in (0, 1) wanted on the contact area (the slowest quantity to converge):
        picks ``tol`` by :func:`contactlib.accuracy.tolerance_for` (give ``tol`` or ``target_error``,
        not both) and, for a periodic surface, warns with :class:`contactlib.accuracy.AccuracyWarning`
        when the grid has fewer points per shortest wavelength than
        :func:`contactlib.accuracy.points_per_wavelength` asks (the grid is the caller's: refine
        the surface with :func:`contactlib.surfaces.resample` or generate it at
        :func:`contactlib.accuracy.settings_for`'s ``n``). Recorded in ``attrs``.

    Returns
    -------
    xarray.Dataset
        ``pressure``, ``gap``, ``displacement`` fields and scalars ``contact_area``,
        ``mean_pressure``, ``penetration``, ``iterations``, ``residual``.

    Examples
    --------
    >>> import contactlib
    >>> h = contactlib.surfaces.self_affine(64, hurst=0.8, q_roll=2, q_cutoff=16, rms_slope=0.1, seed=1)
    >>> out = contactlib.solve(h, E=1.0, nu=0.5, mean_pressure=0.01)
    >>> 0 < float(out.contact_area) < 1
    True
    """
    setup = _setup(heights, E=E, nu=nu, mean_pressure=mean_pressure, penetration=penetration, periodic=periodic,
                   tol=tol, max_iter=max_iter, kernel=kernel, method=method, length=length,
                   initial_pressure=initial_pressure, target_error=target_error)
    start = time.perf_counter()
    state = setup.run()
    wall = time.perf_counter() - start
    ds = setup.label(state, wall, length_unit=length_unit, pressure_unit=pressure_unit)
    setup.check(state, ds)
    return ds


def solve_tolerances(
    heights,
    tols,
    *,
    E: float,
    nu: float,
    mean_pressure: float | None = None,
    penetration: float | None = None,
    periodic: bool = True,
    max_iter: int = 10_000,
    kernel: str = "spectral",
    length=None,
    initial_pressure=None,
    length_unit: str = "m",
    pressure_unit: str = "Pa",
) -> list[xr.Dataset]:
    """The answers of :func:`solve` at several tolerances, for the cost of the tightest one.

    The conjugate-gradient iterates do not depend on ``tol`` (it only stops them), so one solve at
    ``min(tols)`` passes through the state each looser solve would return: it is recorded at the
    first iteration whose residual reaches that tolerance, bit for bit the same pressure, gap,
    iterations and residual as ``solve(..., tol=t)``. Each Dataset's ``attrs['wall_time']`` is the
    time from the first iteration to reaching it [s], its own labelling included and the recording
    of the others not: the separate solve's time (argument checks and operator set-up excluded).
    Holds one copy of the fields per tolerance. Arguments as :func:`solve` (``method="cg"`` only).
    Periodic displacement control (the dual solver) checks the primal residual, one convolution,
    at every iteration whose own residual is below the loosest tolerance, not only the tightest:
    its times there include those checks, which a separate looser solve partly skips.

    Returns
    -------
    list of xarray.Dataset
        One per tolerance, in the order of ``tols``, ``attrs['tol']`` set to it.

    Raises
    ------
    ConvergenceError
        When a tolerance is not reached (``max_iter`` or a stall): ``err.datasets`` holds the whole
        list, the unreached tolerances carrying the final state with ``attrs['converged'] = 0``.
    """
    tols = [float(t) for t in np.atleast_1d(np.asarray(tols, dtype=float))]
    if not tols:
        raise ValueError("tols must hold at least one tolerance")
    for t in tols:
        _check_tolerance(t, "tols")
    setup = _setup(heights, E=E, nu=nu, mean_pressure=mean_pressure, penetration=penetration, periodic=periodic,
                   tol=min(tols), max_iter=max_iter, kernel=kernel, method="cg", length=length,
                   initial_pressure=initial_pressure, target_error=None)
    pending = sorted(set(tols), reverse=True)
    found: dict[float, tuple[ContactState, float]] = {}
    paused = 0.0

    def monitor(it, residual, snapshot):
        nonlocal paused
        if not pending or residual > pending[0]:
            return
        reached = time.perf_counter() - start - paused
        t0 = time.perf_counter()
        state = snapshot()
        paused += time.perf_counter() - t0
        while pending and residual <= pending[0]:
            found[pending.pop(0)] = (state, reached)

    start = time.perf_counter()
    final = setup.run(monitor=monitor, verify_below=max(tols))
    total = time.perf_counter() - start - paused
    out, failed = [], None
    for t in tols:
        state, wall = found.get(t, (final, total))
        state = dataclasses.replace(state, converged=bool(state.residual <= t))
        t0 = time.perf_counter()
        ds = setup.label(state, 0.0, length_unit=length_unit, pressure_unit=pressure_unit, tol=t)
        ds.attrs["wall_time"] = wall + (time.perf_counter() - t0)
        try:
            setup.check(state, ds)
        except ConvergenceError as err:
            failed = failed or err
        out.append(ds)
    if failed is not None:
        failed.datasets = out
        raise failed
    return out


@dataclasses.dataclass
class _Setup:
    """A validated contact problem: its operator and solver arguments, and how to label the answer."""

    values: np.ndarray
    grid: Grid
    dims: tuple
    coords: dict
    operator: Compliance
    solver_args: dict
    attrs: dict
    method: str

    def run(self, monitor=None, verify_below=None) -> ContactState:
        """Solve; ``verify_below``: see :func:`contactlib.solvers.solve_periodic_displacement`."""
        if self.method == "cg":
            if self.operator.periodic and self.solver_args["penetration"] is not None:
                # the primal iteration cannot be preconditioned there; its dual can (solvers/dual.py)
                args = {k: v for k, v in self.solver_args.items() if k != "mean_pressure"}
                return solve_periodic_displacement(self.operator, self.values, monitor=monitor,
                                                   verify_below=verify_below, **args)
            return solve_polonsky_keer(self.operator, self.values, monitor=monitor, **self.solver_args)
        args = {k: v for k, v in self.solver_args.items() if k != "initial_pressure"}
        return solve_active_set(self.operator, self.values, **args)

    def label(self, state: ContactState, wall: float, *, length_unit: str, pressure_unit: str,
              tol: float | None = None) -> xr.Dataset:
        ds = to_dataset(state, dims=self.dims, coords=self.coords, length_unit=length_unit,
                        pressure_unit=pressure_unit)
        ds.attrs.update({"solver": state.solver, **self.attrs, "converged": int(state.converged), "wall_time": wall,
                         "contactlib_version": __version__, "window_lengths": list(self.grid.lengths)})
        if tol is not None:
            ds.attrs["tol"] = tol
        return ds

    def check(self, state: ContactState, ds: xr.Dataset) -> None:
        """Refuse a footprint cut by the window edge; raise :class:`ConvergenceError` if unconverged."""
        if not self.operator.periodic and _touches_edge(state.pressure):
            raise ValueError(
                "periodic=False: the contact reaches the edge of the window, so the surface outside it would "
                "carry load too; enlarge the window (or use periodic=True for a periodic surface)"
            )
        if not state.converged:
            tol, max_iter = ds.attrs["tol"], self.solver_args["max_iter"]
            stalled = state.solver.startswith("polonsky-keer") and state.iterations < max_iter
            message = (f"{state.solver} did not converge in {state.iterations} iterations: residual "
                       f"{state.residual:.3e} > tol {tol:.1e}"
                       + (" (stalled: no progress over the last iterations; round-off floor or an ill-posed scene)"
                          if stalled else ""))
            ds.attrs["convergence_message"] = message  # the partial state says why it is partial
            raise ConvergenceError(message, residual=state.residual, dataset=ds)


def _setup(heights, *, E, nu, mean_pressure, penetration, periodic, tol, max_iter, kernel, method, length,
           initial_pressure, target_error) -> _Setup:
    """Validate every argument of :func:`solve` and build the compliance operator."""
    values, grid, dims, coords = grid_of(heights, length)
    E_star = contact_modulus(E, nu)
    _check_loads(mean_pressure, penetration)
    if target_error is not None:
        if tol is not None:
            raise ValueError("give tol or target_error, not both")
        tol = accuracy.tolerance_for(target_error)
        if periodic:
            accuracy.check_resolution(values, target_error, length=grid.lengths)
    tol = 1e-8 if tol is None else tol
    _check_tolerance(tol, "tol")
    if int(max_iter) < 1:
        raise ValueError(f"max_iter must be >= 1, got {max_iter!r}")
    if kernel not in KERNELS:
        raise ValueError(f"kernel must be one of {KERNELS}, got {kernel!r}")
    if method not in METHODS:
        raise ValueError(f"method must be one of {METHODS}, got {method!r}")
    if periodic and penetration is not None and penetration >= values.max() - values.mean():
        raise ValueError(
            f"penetration {penetration!r} reaches full contact (max - mean height = "
            f"{values.max() - values.mean():.6g}); in a periodic window the load is then undetermined: "
            "give mean_pressure instead"
        )
    warm = None
    if method == "cg" and initial_pressure is not None:
        warm = np.asarray(initial_pressure, dtype=float)
        if warm.shape != values.shape:
            raise ValueError(f"initial_pressure has shape {warm.shape}, heights {values.shape}")
    operator = Compliance(grid, E_star=E_star, kernel=kernel, periodic=periodic)
    attrs = {"kernel": kernel, "periodic": int(periodic), "tol": tol, "max_iter": int(max_iter), "E": float(E),
             "nu": float(nu), "E_star": E_star,
             "load_control": "mean_pressure" if mean_pressure is not None else "penetration"}
    if target_error is not None:
        attrs["target_error"] = float(target_error)
    solver_args = {"mean_pressure": mean_pressure, "penetration": penetration, "tol": tol,
                   "max_iter": int(max_iter), "initial_pressure": warm}
    return _Setup(values, grid, dims, coords, operator, solver_args, attrs, method)


def _touches_edge(pressure: np.ndarray) -> bool:
    edges = [np.take(pressure, i, axis=a) for a in range(pressure.ndim) for i in (0, -1)]
    return any(np.any(e > 0) for e in edges)


def to_dataset(state: ContactState, *, dims, coords, length_unit="m", pressure_unit="Pa") -> xr.Dataset:
    """Label a :class:`ContactState` as a CF-style Dataset."""
    def a(name):
        return attrs_for(name, length=length_unit, pressure=pressure_unit)

    fields = {name: (dims, getattr(state, name), a(name)) for name in ("pressure", "gap", "displacement")}
    scalars = {
        "contact_area": float(np.count_nonzero(state.pressure > 0)) / state.pressure.size,
        "mean_pressure": state.mean_pressure,
        "penetration": state.penetration,
        "iterations": state.iterations,
        "residual": state.residual,
    }
    data = dict(fields)
    data.update({k: ((), v, a(k)) for k, v in scalars.items()})
    ds = xr.Dataset(data, coords=coords)
    for d in dims:
        if not ds[d].attrs:
            ds[d].attrs.update(a(d))
    ds.attrs["Conventions"] = "CF-1.10"
    return ds
