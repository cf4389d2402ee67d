"""Viscoelastic contact in time: :func:`solve_transient`, any load history and in-plane path (the stepper
that :func:`contactlib.problems.reciprocating.solve_reciprocating` drives cycle by cycle).

Each step is one elastic contact solve (:func:`contactlib.solvers.symmetric.choice.constrained_solve`, warm-started from
the previous step) with the step's effective modulus, on heights lowered by the displacement the body's
memory alone would give (:mod:`contactlib.model.hereditary`: the rule, its order, its exact cases). The rigid
surface moves along ``path`` by a phase factor on its spectrum, ``h(x - X(t))``: no re-gridding. Per step:
one contact solve, one convolution for the memory, one transform per Prony branch for the dissipated
power, one transform pair per axis for the slopes, and with a path one inverse transform for the heights. Memory
holds one field per Prony branch and a few more, whatever the number of steps; fields are kept at the times asked
for.

Friction here is the interlocking part only (the pressure's asymmetry, no Coulomb traction): the
tangential force per unit area the rigid surface needs to move, ``tangential_force = -mean(p grad h)``
[pressure] (the indenter's work per unit slide, which the steps' dissipated energy balances;
:func:`contactlib.solve` takes the steady slide's from the deformed surface, the operator's own dissipation, within
the discretisation of each other: 2.3 % at 8 points per shortest wavelength), and
``friction_coefficient_interlocking`` its component along the motion over the mean pressure
(:func:`contactlib.analysis.interlocking_friction`).
"""

from __future__ import annotations

import logging
import math
import time as _time
import warnings
from collections.abc import Callable

import numpy as np
import xarray as xr

from .._version import __version__
from ..analysis.friction import directional_slope
from ..model.bodies import Layer, body_model
from ..errors import ConvergenceError
from ..model.hereditary import PronyHistory
from ..kernels.nyquist import even_on_nyquist
from ..invariants import check_relaxed_limit, contact_checks, relaxed_hold, step_invariants, verify, with_dataset
from ..core.inputs import check_whole, load_history, real_values, time_values, touches_edge
from ..core.labels import attrs_for, field_variable
from ..model.materials import Elastic, material_of
from ..solvers.state import height_scale
from ..solvers.symmetric.choice import constrained_solve
from ..resolution import guard_stepper
from .scene import scene_of

log = logging.getLogger(__name__)

INITIAL_STATES = ("unloaded", "relaxed")
MODELS_KEPT = 3

SLIDE_PER_STEP = 1.0
"""The largest slide of the rigid surface over one step, in grid spacings along each axis, before a
viscoelastic run warns (:class:`TimeStepWarning`). A step takes the pressure rate as constant at each point
of the body, so a surface that moves several spacings in a step smears its features' passage. A 256-point
rough profile reciprocated at an amplitude of 0.3 of its window (E_inf/E0 = 10, f tau = 1e-3) dissipates 41 %
too little per cycle at 7.5 spacings a step and 12 % at 3.8; 1.9 % at 1.9 and 0.2 % at 0.94, with the friction
work then within 1 % of it. On 512 points the same slides err by less (2.8 % at 3.8, 0.02 % at 0.94)."""


class TimeStepWarning(UserWarning):
    """A viscoelastic run's steps slide the rigid surface by more than :data:`SLIDE_PER_STEP` grid spacings:
    the dissipated energy, the friction and the contact's history lose accuracy (more steps, a shorter path)."""


class TransientInterrupted(KeyboardInterrupt):
    """A time-stepping run stopped by the user (Ctrl-C): ``dataset`` holds every step done, labelled,
    ``attrs['status']`` saying where it stopped. Still a ``KeyboardInterrupt``, so it stops a script.

    Parameters
    ----------
    message : str
        Where the run stopped.
    dataset : xarray.Dataset
        Every step done, labelled.

    Attributes
    ----------
    dataset : xarray.Dataset
        Every step done, labelled.
    """

    def __init__(self, message: str, dataset: xr.Dataset):
        super().__init__(message)
        self.dataset = dataset


def solve_transient(
    heights,
    *,
    times,
    material=None,
    E: float | None = None,
    nu: float | None = None,
    mean_pressure=None,
    penetration=None,
    path=None,
    layer: Layer | None = None,
    periodic: bool | None = None,
    initial: str = "unloaded",
    save_fields=None,
    tol: float = 1e-8,
    max_iter: int = 10_000,
    length=None,
    progress: Callable | None = None,
    log_every: int | None = None,
    length_unit: str = "m",
    pressure_unit: str = "Pa",
    time_unit: str = "s",
) -> xr.Dataset:
    """Contact of a rigid surface on a viscoelastic (or elastic) body, stepped through ``times``.

    Parameters
    ----------
    heights : xarray.DataArray or ndarray
        Rigid surface heights [length] as :func:`contactlib.solve` takes them (an ndarray is indexed ``[ix, iy]``
        and needs ``length``). The saved fields are on ``("saved_time", "y", "x")``.
    times : sequence of float
        Strictly increasing instants [time]. The body is at rest before ``times[0]``; the load given there
        is applied instantaneously (the glassy response, ``E_inf``), or, with ``initial="relaxed"``, has
        been carried for ever (the relaxed response, ``E0``).
    material : contactlib.Viscoelastic or contactlib.Elastic
        The body (or the elastic shorthand ``E``, ``nu``).
    mean_pressure, penetration : float, sequence or callable
        Exactly one: the mean pressure [pressure] or the rigid approach from first contact [length], as a
        constant, one value per time, or a function of time. Penetration has the meaning it has in
        :func:`contactlib.solve` (a periodic half-space: against the mean deformed plane).
    path : sequence or callable, optional
        Position of the rigid surface relative to the body [length] at each time: shape ``(n,)`` for a
        profile, ``(n, 2)`` for a surface, or a function of time returning one position. The heights
        become ``h(x - X(t))`` (a phase factor on their spectrum: periodic on the window, so an isolated
        indenter must stay clear of the window edge).
    layer : contactlib.Layer, optional
        A finite layer, as in :func:`contactlib.solve` (a non-periodic window takes a confined one).
    periodic : bool, optional
        As in :func:`contactlib.solve`.
    initial : {"unloaded", "relaxed"}
        The state before ``times[0]`` (above).
    save_fields : None, True, int or sequence of float
        Steps whose ``pressure``, ``gap`` and ``displacement`` fields are kept (on the ``saved_time``
        dimension): None, the last step only; True, every step; an integer k, every k-th step and the
        last; a sequence, those times (each must be one of ``times``).
    tol, max_iter : float, int
        Each step's contact tolerance and iteration bound (:func:`contactlib.solve`).
    progress : callable, optional
        ``progress(step, n_steps, time, row)`` after each step, ``row`` a dict of its scalars.
    log_every : int, optional
        Log a line (logger ``contactlib.problems.transient``, INFO) every this many steps (0: none); default a tenth of
        the run when it has 100 steps or more.

    E, nu : float, optional
        The elastic shorthand for ``material=contactlib.Elastic(E, nu)``.
    length : float or tuple, optional
        Window size [length], required for bare-array heights.
    length_unit, pressure_unit, time_unit : str
        udunits strings written to the output's ``units`` attributes.

    Returns
    -------
    xarray.Dataset
        On ``time``: ``mean_pressure``, ``penetration``, ``contact_area``, ``friction_coefficient_interlocking``
        (along the motion; along +x at rest), ``tangential_force_x`` (and ``_y``), ``dissipated_power``,
        ``iterations``, ``residual``, and with a path ``position_x`` (``_y``). On ``saved_time``: the fields.
        ``attrs['status']`` is ``"completed"``.

    Raises
    ------
    ConvergenceError
        A step did not converge: ``err.dataset`` holds the steps before it, labelled, and its residual.
    TransientInterrupted
        Ctrl-C: ``err.dataset`` holds the steps done.

    Warns
    -----
    TimeStepWarning
        When a viscoelastic step slides the surface farther than one grid spacing (``path``).
    ResolutionWarning
        When the grid resolves the scene worse than the measured rule asks for 1 %.
    """
    stepper, times, loads, positions, control = prepare_stepper(
        heights, times=times, material=material_of(material, E, nu), mean_pressure=mean_pressure,
        penetration=penetration, path=path, layer=layer, periodic=periodic, tol=tol, max_iter=max_iter, length=length)
    if initial not in INITIAL_STATES:
        raise ValueError(f"initial must be one of {INITIAL_STATES}, got {initial!r}")
    check_slide(positions, stepper, "path: the surface", "the dissipated power and friction lose accuracy (take "
                 "more times)")
    if log_every is not None:
        check_whole(log_every, "log_every", 0)  # steps between log lines; 0: none
    saved = _saved_steps(save_fields, times)
    record = StepRecord(stepper, times, positions, saved, path is not None)
    n = len(times)
    every = log_every if log_every is not None else (max(1, n // 10) if n >= 100 else 0)
    start = _time.perf_counter()
    try:
        for k in range(n):
            if k == 0:
                step = stepper.first(loads[0], control, positions[0], relaxed=initial == "relaxed")
            else:
                step = stepper.step(times[k] - times[k - 1], loads[k], control, positions[k])
            record.add(k, step)
            if progress is not None:
                progress(k, n, float(times[k]), record.row(k))
            if every and (k + 1) % every == 0:
                log.info("solve_transient: step %d/%d, t = %.4g, contact area %.4g, %d iterations", k + 1, n,
                         times[k], step["contact_area"], step["iterations"])
    except ConvergenceError as err:
        ds = record.dataset(start, units=(length_unit, pressure_unit, time_unit),
                            status=f"not converged at step {record.done} (t = {times[record.done]:g}): {err}")
        raise with_dataset(err, str(ds.attrs["status"]), ds) from err
    except KeyboardInterrupt:
        ds = record.dataset(start, units=(length_unit, pressure_unit, time_unit),
                            status=f"interrupted after {record.done} of {n} steps")
        raise TransientInterrupted(ds.attrs["status"], ds) from None
    ds = record.dataset(start, units=(length_unit, pressure_unit, time_unit), status="completed")
    guard_stepper(ds, stepper, where="solve_transient")  # on the last step's contact, before the relaxed solve
    try:
        _check_relaxed_limit(ds, stepper, times, loads, positions, control, step)
    except ConvergenceError as err:  # the relaxed solve itself failed: the finished series still comes back
        if err.dataset is ds:
            raise
        ds.attrs["converged"] = 0
        ds.attrs["status"] = f"the relaxed solve of the limit check failed: {err}"
        raise with_dataset(err, str(ds.attrs["status"]), ds) from err
    return ds


def _check_relaxed_limit(ds, stepper, times, loads, positions, control, last) -> None:
    """Record the invariants the steps met and, after a hold long enough (:func:`.invariants.relaxed_hold`), check
    the last step against the relaxed elastic solve (one warm-started solve) and record the comparison
    (``attrs['relaxed_limit']``, ``'relaxed_limit_bound'``, ``'relaxed_memory_left'``): raises
    :class:`.invariants.InvariantError` with ``ds`` where it fails."""
    checked = step_invariants(control)
    memory = relaxed_hold(times, loads, positions, stepper.material, control)
    if memory is None:
        ds.attrs["invariants_checked"] = checked
        return
    kept = stepper.pressure, stepper.previous  # the relaxed solve is a check, not a step: the stepper's state stays
    try:
        relaxed = stepper._solve(stepper.material.E0, None, loads[-1], control, positions[-1])
    finally:
        stepper.pressure, stepper.previous = kept
    key = "penetration" if control == "mean_pressure" else "mean_pressure"  # the response to the held control
    scale = height_scale(stepper.values) if key == "penetration" else abs(relaxed[key]) or 1.0
    check = check_relaxed_limit(last[key], relaxed[key], tol=stepper.tol, scale=scale, memory_left=memory)
    ds.attrs.update(relaxed_limit=check.violation, relaxed_limit_bound=check.bound, relaxed_memory_left=memory)
    try:
        verify([check], ds, where="solve_transient")
    finally:
        ds.attrs["invariants_checked"] = f"{checked}, relaxed_limit"
        if ds.attrs.get("converged") == 0:
            ds.attrs["status"] = ds.attrs["convergence_message"]


class Stepper:
    """One scene stepped in time: the body's models per step size, its memory, the moving heights."""

    def __init__(self, values, grid, dims, material, layer, periodic, tol, max_iter, control):
        self.values, self.grid, self.dims, self.material, self.layer = values, grid, dims, material, layer
        self.control = control
        self.periodic, self.tol, self.max_iter = periodic, tol, max_iter
        self.axes = ("x", "y")[: grid.dim]
        self.history = PronyHistory(material, grid.shape)
        self.spectrum = np.fft.rfftn(values)
        self.wavevectors = grid.wavevectors()  # for the phase of a path's translation
        self._models: dict[float, tuple] = {}
        self.pressure = self.previous = None
        # a warm start is near the answer and only a few edge points move: restart the conjugacy when more
        # than 0.1 % of the contact re-enters (the cold-solve rule, 1 %, kept a stale direction there).
        # Measured (12 steps of a 512^2 rough surface at 35-54 % contact; 81 steps of a creeping 128^2
        # sphere), total iterations: 1 %: 347 and 1628 (one step stalled 500); 0.1 %: 379 and 445; 0: 541 and 445
        self.restart_fraction = 0.001

    def model(self, E: float):
        """The body's elastic model at modulus ``E``: the last few are kept (a uniform step needs one, the
        first step another), so log-spaced times rebuild it per step and memory stays flat."""
        if E not in self._models:
            if len(self._models) >= MODELS_KEPT:
                self._models.pop(next(iter(self._models)))
            self._models[E] = body_model(self.grid, material=Elastic(E, self.material.nu), layer=self.layer,
                                         friction=0.0, direction=0.0, tol=self.tol, kernel="spectral",
                                         periodic=self.periodic)
        return self._models[E]

    def predicted(self):
        """The warm start: the last pressure extrapolated linearly over one more step."""
        if self.previous is None or self.pressure is None:
            return self.pressure
        return np.maximum(2 * self.pressure - self.previous, 0.0)

    def heights_at(self, position) -> np.ndarray:
        """The rigid surface ``h(x - X)``: translated by a phase, made even on the Nyquist planes (there a shift by a
        fraction of a spacing has no sign, and ``exp(-i q X)`` at numpy's sign would break the mirrors of a 2D scene,
        :mod:`contactlib.kernels.nyquist`; whole spacings are exact either way)."""
        if position is None or not np.any(position):
            return self.values
        shift = [float(x) for x in position]
        phase = even_on_nyquist(self.grid, lambda *q: np.exp(-1j * sum(qa * x for qa, x in zip(q, shift))))
        return np.fft.irfftn(self.spectrum * phase, s=self.grid.shape, axes=tuple(range(self.grid.dim)))

    def _slopes(self, surface) -> list[np.ndarray]:
        return [directional_slope(surface, lengths=self.grid.lengths, direction=a * math.pi / 2,
                                  periodic=self.periodic) for a in range(self.grid.dim)]

    def first(self, load: float, control: str, position, *, relaxed: bool) -> dict:
        """The first step: the load applied at once (glassy), or carried for ever (relaxed)."""
        if relaxed:
            step = self._solve(self.material.E0, None, load, control, position)
            self.history = PronyHistory(self.material, self.grid.shape, relaxed_pressure=step["pressure"])
            step["dissipated_power"] = 0.0
            return step
        return self.step(0.0, load, control, position)

    def step(self, dt: float, load: float, control: str, position) -> dict:
        E_eff, _, _ = self.history.coefficients(dt)
        g = self.history.history_pressure(dt)
        step = self._solve(E_eff, g, load, control, position)
        self.history.advance(dt, step["pressure"], g)
        compliance = self.model(E_eff).compliance

        def mean_form(field):  # mean(field * C1 field) = E_eff mean(field * C_eff field)
            compliance.load()[...] = field
            return E_eff * compliance.quadratic_form() / field.size

        step["dissipated_power"] = self.history.dissipated_power(mean_form)
        return step

    def _solve(self, E_eff: float, g, load: float, control: str, position) -> dict:
        compliance = self.model(E_eff).compliance
        heights = self.heights_at(position)
        memory = None if g is None else compliance.apply_aside(g)
        effective = heights if memory is None else heights - memory
        shift = float(effective.max() - heights.max())
        args = {"mean_pressure": None, "penetration": None, "tol": self.tol, "max_iter": self.max_iter,
                "initial_pressure": self.predicted(), "restart_fraction": self.restart_fraction}
        if control == "mean_pressure":
            args["mean_pressure"] = float(load)
        else:
            args["penetration"] = float(load) + shift
            if not compliance.definite and args["penetration"] >= effective.max() - effective.mean():
                raise ValueError(f"penetration {float(load)!r} reaches full contact on the deformed surface; in a "
                                 "periodic window the load is then undetermined: give mean_pressure")
        state = constrained_solve(compliance, effective, **args)
        if not state.converged:
            raise ConvergenceError(f"{state.solver} did not converge in {state.iterations} iterations: residual "
                                   f"{state.residual:.3e} > tol {self.tol:.1e}", residual=state.residual, dataset=None)
        if not self.periodic and touches_edge(state.pressure):
            raise ValueError("periodic=False: the contact reaches the edge of the window; enlarge the window")
        verify(contact_checks(state, effective, tol=self.tol, mean_pressure=args["mean_pressure"],
                              penetration=args["penetration"]), where=f"{state.solver} step")
        self.previous, self.pressure = self.pressure, state.pressure
        p = state.pressure
        mean = float(p.mean())
        displacement = state.displacement if memory is None else state.displacement + memory
        # the rigid surface's slopes: the work the indenter does per unit slide, sum p dh (the body follows h on the
        # contact), so a cycle's friction work balances the energy the steps dissipate (TimeStepWarning otherwise);
        # the deformed surface's slopes broke that balance by 0.3 of the work on a coarse 2D map at 256 steps a cycle
        forces = [-float(np.mean(p * s)) for s in self._slopes(heights)]
        return {"pressure": p, "gap": state.gap, "displacement": displacement, "mean_pressure": mean,
                "penetration": float(state.penetration - shift), "contact_area": float(np.count_nonzero(p > 0)) / p.size,
                "iterations": state.iterations, "residual": state.residual,
                **{f"tangential_force_{a}": f for a, f in zip(self.axes, forces)}}


class StepRecord:
    """The scalars of every step and the fields of the saved ones, labelled on demand."""

    SCALARS = ("mean_pressure", "penetration", "contact_area", "friction_coefficient_interlocking",
               "dissipated_power", "iterations", "residual")

    def __init__(self, stepper: Stepper, times, positions, saved, moving: bool):
        self.stepper, self.times, self.positions, self.saved, self.moving = stepper, np.asarray(times), positions, \
            np.asarray(saved), moving
        self.columns = {name: [] for name in self.SCALARS + tuple(f"tangential_force_{a}" for a in stepper.axes)}
        self.fields = {name: [] for name in ("pressure", "gap", "displacement")}
        self.field_times = []
        velocity = np.gradient(positions, self.times, axis=0) if moving and len(self.times) > 1 else None
        self.directions = (np.zeros(len(self.times)) if velocity is None
                           else np.arctan2(velocity[:, -1], velocity[:, 0]) if stepper.grid.dim == 2
                           else np.where(velocity[:, 0] < 0, math.pi, 0.0))
        self.done = 0

    def add(self, k: int, step: dict) -> None:
        direction = self.directions[k]
        along = np.array([math.cos(direction), math.sin(direction)][: self.stepper.grid.dim])
        force = np.array([step[f"tangential_force_{a}"] for a in self.stepper.axes])
        mean = step["mean_pressure"]
        step["friction_coefficient_interlocking"] = float(force @ along) / mean if mean > 0 else 0.0
        for name in self.columns:
            self.columns[name].append(step[name])
        if self.saved[k]:
            for name in self.fields:
                self.fields[name].append(np.array(step[name], copy=True))
            self.field_times.append(float(self.times[k]))
        self.done = k + 1

    def row(self, k: int) -> dict:
        return {name: values[k] for name, values in self.columns.items()}

    def dataset(self, start: float, *, units, status: str) -> xr.Dataset:
        length_unit, pressure_unit, time_unit = units
        stepper = self.stepper

        def a(name):
            return attrs_for(name, length=length_unit, pressure=pressure_unit)

        n = self.done
        time_attrs = {"units": time_unit, "long_name": "time"}
        ds = xr.Dataset(coords={"time": ("time", self.times[:n], time_attrs)})
        for name, values in self.columns.items():
            ds[name] = ("time", np.asarray(values[:n], dtype=float if name != "iterations" else int), a(name))
        if self.moving:
            for i, axis in enumerate(stepper.axes):
                ds[f"position_{axis}"] = ("time", np.asarray(self.positions[:n, i], dtype=float), a(f"position_{axis}"))
        dims = ("saved_time",) + stepper.dims  # labelled by field_variable: a surface's fields on (y, x)
        ds = ds.assign_coords(saved_time=("saved_time", np.array(self.field_times),
                                          {"units": time_unit, "long_name": "time of the saved fields"}))
        ds = ds.assign_coords({d: (d, c, a(d)) for d, c in zip(stepper.dims, stepper.grid.coordinates())})
        for name, values in self.fields.items():
            data = np.stack(values) if values else np.zeros((0,) + stepper.grid.shape)
            ds[name] = field_variable(dims, data, a(name))
        material = stepper.material
        ds.attrs.update({
            "Conventions": "CF-1.10", "contactlib_version": __version__, "status": status, "steps": n,
            "wall_time": _time.perf_counter() - start, "E0": float(material.E0), "E_inf": float(material.E_inf),
            "nu": float(material.nu), "prony": [v for branch in getattr(material, "prony", ()) for v in branch],
            "tol": stepper.tol, "max_iter": stepper.max_iter, "periodic": int(stepper.periodic),
            "window_lengths": list(stepper.grid.lengths), "load_control": stepper.control,
            "time_integration": "displacement at a constant rate over each step, Prony branches integrated exactly "
                                "(second order; exact at fixed displacement): contactlib.model.hereditary",
            "model": next(iter(stepper._models.values())).attrs["model"] if stepper._models else "",
        })
        if stepper.layer is not None:
            ds.attrs.update(layer_thickness=float(stepper.layer.thickness), layer_base=stepper.layer.base)
        return ds


def prepare_stepper(heights, *, times, material, mean_pressure, penetration, path, layer, periodic, tol, max_iter,
                    length):
    """Validate a run: the scene on the one path of every entry point (:func:`contactlib.problems.scene.scene_of`: a
    frictionless body at rest, its material's history stepped here), then the time path this driver adds (times,
    loads, positions). Returns ``(stepper, times, loads, positions, control)``."""
    scene = scene_of(heights, material=material, periodic=periodic, tol=tol, max_iter=max_iter, length=length,
                     layer=layer)
    values, grid, dims, periodic = scene.values, scene.grid, scene.dims, scene.periodic
    times = time_values(times, "times")
    if (mean_pressure is None) == (penetration is None):
        raise ValueError("give exactly one of mean_pressure or penetration")
    control = "mean_pressure" if mean_pressure is not None else "penetration"
    loads = load_history(mean_pressure if mean_pressure is not None else penetration, times, control)
    if control == "mean_pressure" and np.any(loads < 0):
        raise ValueError(f"mean_pressure must be >= 0 at every time, got {loads.min()!r}")
    positions = _positions(path, times, grid.dim)
    stepper = Stepper(values, grid, dims, material, layer, periodic, float(tol), int(max_iter), control)
    return stepper, times, loads, positions, control


def check_slide(positions: np.ndarray, stepper: Stepper, what: str, consequence: str) -> float:
    """The largest slide between consecutive positions ``(n, dim)`` [length] (as :func:`_positions` gives them),
    in grid spacings along each axis (0 without a step); beyond :data:`SLIDE_PER_STEP` on a body with memory,
    a :class:`TimeStepWarning` saying ``what`` slides and ``consequence`` (at the caller's caller)."""
    spacing = np.asarray(stepper.grid.spacing, dtype=float)[: positions.shape[1]]
    slide = float(np.max(np.abs(np.diff(positions, axis=0)) / spacing)) if len(positions) > 1 else 0.0
    if slide > SLIDE_PER_STEP * (1 + 1e-9) and not isinstance(stepper.material, Elastic):
        warnings.warn(f"{what} slides up to {slide:.3g} grid spacings a step, more than {SLIDE_PER_STEP:g}: "
                      f"{consequence}", TimeStepWarning, stacklevel=3)
    return slide


def _positions(path, times: np.ndarray, dim: int) -> np.ndarray:
    """The path as an ``(n, dim)`` array of finite positions (zeros without a path)."""
    if path is None:
        return np.zeros((times.size, dim))
    values = (real_values([np.atleast_1d(real_values(path(t), "path")) for t in times], "path") if callable(path)
              else real_values(path, "path"))
    if values.ndim == 1 and dim == 1:
        values = values[:, None]
    if values.shape != (times.size, dim):
        raise ValueError(f"path must hold one position ({dim} component(s)) per time: shape ({times.size}, {dim}) "
                         f"for {times.size} times, got {values.shape}")
    if not np.all(np.isfinite(values)):
        raise ValueError("path holds non-finite positions")
    return values


def _saved_steps(save_fields, times: np.ndarray) -> np.ndarray:
    """Boolean per step: keep its fields."""
    n = times.size
    keep = np.zeros(n, dtype=bool)
    if save_fields is None or save_fields is False:
        keep[-1] = True
    elif save_fields is True:
        keep[:] = True
    elif isinstance(save_fields, (int, np.integer)):
        if save_fields < 1:
            raise ValueError(f"save_fields as a stride must be >= 1, got {save_fields!r}")
        keep[::save_fields] = True
        keep[-1] = True
    else:
        for t in np.atleast_1d(np.asarray(save_fields, dtype=float)):
            match = np.flatnonzero(np.isclose(times, t, rtol=1e-12, atol=1e-12 * max(1.0, abs(t))))
            if match.size == 0:
                raise ValueError(f"save_fields: {t!r} is not one of the times")
            keep[match[0]] = True
    return keep


__all__ = ["solve_transient", "TransientInterrupted", "TimeStepWarning", "Stepper", "StepRecord", "prepare_stepper",
           "check_slide"]
