"""Viscoelastic contact in time: :func:`solve_transient` (any load history and in-plane path) and
:func:`solve_reciprocating` (sinusoidal sliding until the cycle repeats).

Each step is one elastic contact solve (:func:`contactlib.contact.constrained_solve`, warm-started from
the previous step) with the step's effective modulus, on heights lowered by the displacement the body's
memory alone would give (:mod:`contactlib.hereditary`: the rule, its order, its exact cases). The rigid
surface moves along ``path`` by a phase factor on its spectrum, ``h(x - X(t))``: no re-gridding. Per step:
one contact solve, one convolution for the memory, one transform per Prony branch for the dissipated
power, and with a path one inverse transform per axis for the heights and slopes. Memory holds one field
per Prony branch and a few more, whatever the number of steps; fields are kept at the times asked for.

Friction here is the interlocking part only (the pressure's asymmetry, no Coulomb traction): the
tangential force per unit area the rigid surface needs to move, ``tangential_force = -mean(p grad h)``
[pressure], and ``friction_coefficient_interlocking`` its component along the motion over the mean
pressure (:func:`contactlib.analysis.interlocking_friction`).
"""

from __future__ import annotations

import logging
import math
import time as _time
from collections.abc import Callable

import numpy as np
import xarray as xr

from ._version import __version__
from .analysis.friction import directional_slope
from .bodies import Layer, body_model
from .contact import ConvergenceError, _check_friction, _check_tolerance, _touches_edge, constrained_solve, grid_of, \
    periodic_of
from .hereditary import PronyHistory
from .labels import attrs_for
from .materials import Elastic, material_of

log = logging.getLogger(__name__)

INITIAL_STATES = ("unloaded", "relaxed")
MODELS_KEPT = 3


class TransientInterrupted(KeyboardInterrupt):
    """A time-stepping run stopped by the user (Ctrl-C): ``dataset`` holds every step done, labelled,
    ``attrs['status']`` saying where it stopped. Still a ``KeyboardInterrupt``, so it stops a script."""

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
        Rigid surface heights [length] as :func:`contactlib.solve` takes them (an ndarray needs ``length``).
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
        A finite layer (periodic windows), as in :func:`contactlib.solve`.
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
        Log a line (logger ``contactlib.transient``, INFO) every this many steps; default a tenth of the
        run when it has 100 steps or more.

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
    """
    stepper, times, loads, positions, control = _prepare(
        heights, times=times, material=material_of(material, E, nu), mean_pressure=mean_pressure,
        penetration=penetration, path=path, layer=layer, periodic=periodic, tol=tol, max_iter=max_iter, length=length)
    if initial not in INITIAL_STATES:
        raise ValueError(f"initial must be one of {INITIAL_STATES}, got {initial!r}")
    saved = _saved_steps(save_fields, times)
    record = _Record(stepper, times, positions, saved, path is not None)
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
        raise ConvergenceError(str(ds.attrs["status"]), residual=err.residual, dataset=ds) from err
    except KeyboardInterrupt:
        ds = record.dataset(start, units=(length_unit, pressure_unit, time_unit),
                            status=f"interrupted after {record.done} of {n} steps")
        raise TransientInterrupted(ds.attrs["status"], ds) from None
    return record.dataset(start, units=(length_unit, pressure_unit, time_unit), status="completed")


def solve_reciprocating(
    heights,
    *,
    amplitude: float,
    frequency: float,
    mean_pressure: float,
    material=None,
    E: float | None = None,
    nu: float | None = None,
    direction: float = 0.0,
    steps_per_cycle: int = 64,
    max_cycles: int = 20,
    min_cycles: int = 3,
    cycle_tol: float = 1e-3,
    accelerate: bool = True,
    layer: Layer | None = None,
    periodic: bool | None = None,
    tol: float = 1e-8,
    max_iter: int = 10_000,
    length=None,
    progress: Callable | None = None,
    length_unit: str = "m",
    pressure_unit: str = "Pa",
    time_unit: str = "s",
) -> xr.Dataset:
    """Reciprocating sliding ``X(t) = amplitude sin(2 pi frequency t)`` along ``direction`` under a constant
    ``mean_pressure``, run cycle by cycle until the cycle repeats.

    The run starts from the body relaxed under the load at ``X = 0`` (as if pressed for ever, then set
    moving), so a slow material needs few cycles. **Settled** when, from ``min_cycles`` on, the change
    between consecutive cycles, and the change still to come estimated from their geometric decrease
    (``c r / (1 - r)`` with ``r`` the ratio of the last two changes), are both at most ``cycle_tol``. The
    change is the larger of the tangential-force loop's relative L2 change and the dissipated energy's
    change relative to the cycle's absolute work ``oint |tau_x dX|``. Past ``max_cycles`` the cycles done
    are returned with ``attrs['status']`` saying the cycle did not settle and the last change.

    Parameters as :func:`solve_transient`; ``amplitude`` [length] and ``frequency`` [1/time] > 0;
    ``direction`` [rad] (a profile: 0 or pi).

    Returns
    -------
    xarray.Dataset
        The last cycle on ``time`` (``position_x``, ``tangential_force_x``, ``friction_coefficient_interlocking``,
        ``contact_area``, ``penetration``, ``dissipated_power``, ...: the hysteresis loop is
        ``tangential_force_x / mean_pressure`` against ``position_x``), and on ``cycle``:
        ``dissipated_energy`` (the integral of the dissipated power over the cycle) and ``friction_work``
        (``oint tau . dX``, the work the motion puts in: equal to it once the cycle repeats) [pressure
        length], and ``cycle_change``. Scalars ``dissipated_energy_per_cycle`` and
        ``friction_work_per_cycle`` of the last cycle; ``attrs['status']`` ``"settled"`` or not.
    """
    for value, name in ((amplitude, "amplitude"), (frequency, "frequency")):
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) or value <= 0:
            raise ValueError(f"{name} must be a finite number > 0, got {value!r}")
    if isinstance(steps_per_cycle, bool) or not isinstance(steps_per_cycle, int) or steps_per_cycle < 4:
        raise ValueError(f"steps_per_cycle must be an integer >= 4, got {steps_per_cycle!r}")
    if not isinstance(max_cycles, int) or not isinstance(min_cycles, int) or not 2 <= min_cycles <= max_cycles:
        raise ValueError(f"need integers 2 <= min_cycles <= max_cycles, got min_cycles={min_cycles!r}, "
                         f"max_cycles={max_cycles!r}")
    _check_tolerance(cycle_tol, "cycle_tol")
    if not isinstance(direction, (int, float)) or not math.isfinite(direction):
        raise ValueError(f"direction must be a finite angle [rad], got {direction!r}")
    dt = 1.0 / (frequency * steps_per_cycle)
    cycle_times = np.arange(steps_per_cycle + 1) * dt
    unit = np.array([math.cos(direction), math.sin(direction)])

    material = material_of(material, E, nu)
    dim = grid_of(heights, length)[1].dim

    def path(t):
        return amplitude * math.sin(2 * math.pi * frequency * t) * unit[:dim]

    stepper, _, _, positions, control = _prepare(
        heights, times=cycle_times, material=material, mean_pressure=mean_pressure, penetration=None, path=path,
        layer=layer, periodic=periodic, tol=tol, max_iter=max_iter, length=length)
    if stepper.grid.dim == 1 and abs(math.sin(direction)) > 1e-12:
        raise ValueError(f"direction must be 0 or pi for a profile (it slides along x), got {direction!r}")
    units = (length_unit, pressure_unit, time_unit)
    start = _time.perf_counter()
    last = stepper.first(mean_pressure, control, positions[0], relaxed=True)
    energies, works, changes, previous_loop = [], [], [], None
    ends = [stepper.history.state()]  # the memory at the ends of the cycles since the last extrapolation
    status, record = None, None
    try:
        for cycle in range(max_cycles):
            record = _Record(stepper, cycle_times[1:] + cycle / frequency, positions[1:],
                             np.arange(steps_per_cycle) == steps_per_cycle - 1, True)
            before = last
            for k in range(1, steps_per_cycle + 1):
                last = stepper.step(dt, mean_pressure, control, positions[k])
                record.add(k - 1, last)
                if progress is not None:
                    progress(cycle * steps_per_cycle + k - 1, max_cycles * steps_per_cycle,
                             float(record.times[k - 1]), record.row(k - 1))
            loop = np.stack([np.array(record.columns[f"tangential_force_{a}"]) for a in stepper.axes])
            moved = np.diff(positions, axis=0)
            forces = np.concatenate([np.stack([before[f"tangential_force_{a}"] for a in stepper.axes])[:, None], loop],
                                    axis=1)
            mid = 0.5 * (forces[:, 1:] + forces[:, :-1])
            works.append(float(np.sum(mid * moved.T)))
            energies.append(float(np.sum(record.columns["dissipated_power"]) * dt))
            scale = float(np.sum(np.abs(mid * moved.T))) or 1.0
            log.info("solve_reciprocating: cycle %d, energy %.6g, loop work %.6g", cycle + 1, energies[-1], works[-1])
            if previous_loop is not None:
                norm = float(np.linalg.norm(loop)) or 1.0
                changes.append(max(float(np.linalg.norm(loop - previous_loop)) / norm,
                                   abs(energies[-1] - energies[-2]) / scale))
                if len(energies) >= min_cycles and _settled(changes, cycle_tol):
                    status = "settled"
                    break
            previous_loop = loop
            if accelerate:
                ends.append(stepper.history.state())
                if len(ends) == 3:
                    stepper.history.set_state(_extrapolate(*ends))
                    ends = [stepper.history.state()]
    except ConvergenceError as err:
        ds = record.dataset(start, units=units, status=f"not converged in cycle {len(energies) + 1}: {err}")
        raise ConvergenceError(str(ds.attrs["status"]), residual=err.residual, dataset=ds) from err
    except KeyboardInterrupt:
        ds = record.dataset(start, units=units, status=f"interrupted in cycle {len(energies) + 1}")
        raise TransientInterrupted(ds.attrs["status"], ds) from None
    if status is None:
        status = (f"not settled after {max_cycles} cycles: last change between cycles "
                  f"{changes[-1] if changes else float('nan'):.3g} > cycle_tol {cycle_tol:g}")
    ds = record.dataset(start, units=units, status=status)
    length_u, pressure_u, _ = units
    energy_attrs = attrs_for("dissipated_energy", length=length_u, pressure=pressure_u)
    ds = ds.assign_coords(cycle=("cycle", np.arange(1, len(energies) + 1), attrs_for("cycle")))
    ds["dissipated_energy"] = ("cycle", np.array(energies), energy_attrs)
    ds["friction_work"] = ("cycle", np.array(works), attrs_for("friction_work", length=length_u, pressure=pressure_u))
    ds["cycle_change"] = ("cycle", np.array([np.nan] + changes), attrs_for("cycle_change"))
    ds["dissipated_energy_per_cycle"] = ((), energies[-1], energy_attrs)
    ds["friction_work_per_cycle"] = ((), works[-1], attrs_for("friction_work", length=length_u, pressure=pressure_u))
    ds.attrs.update(amplitude=float(amplitude), frequency=float(frequency), direction=float(direction),
                    steps_per_cycle=steps_per_cycle, cycles=len(energies), cycle_tol=float(cycle_tol),
                    max_cycles=max_cycles, initial="relaxed under the mean load at X = 0")
    return ds


def _extrapolate(first, second, third):
    """The fixed point of the cycle map from three successive cycle-end states, assuming one slow mode
    (Aitken's delta-squared on the whole state): ``third + d (r / (1 - r))``, ``d = third - second``, ``r``
    the ratio of the last two changes; the state unchanged unless ``0 < r < 1``."""
    d1 = [b - a for a, b in zip(first, second)]
    d2 = [b - a for a, b in zip(second, third)]
    norm = sum(float(np.vdot(x, x)) for x in d1)
    if norm <= 0:
        return third
    ratio = sum(float(np.vdot(x, y)) for x, y in zip(d1, d2)) / norm
    if not 0 < ratio < 0.99:
        return third
    return [x + d * (ratio / (1 - ratio)) for x, d in zip(third, d2)]


def _settled(changes: list[float], cycle_tol: float) -> bool:
    """The cycle repeats to ``cycle_tol``: the last change, and the rest of a geometric decrease, below it."""
    last = changes[-1]
    if last > cycle_tol:
        return False
    if len(changes) < 2 or changes[-2] <= 0:
        return True
    ratio = last / changes[-2]
    return ratio < 1 and last * ratio / (1 - ratio) <= cycle_tol


class _Stepper:
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
        self._at_rest = None  # the heights and slopes at the origin
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

    def heights_at(self, position) -> tuple[np.ndarray, list[np.ndarray]]:
        """The rigid surface ``h(x - X)`` and its slopes along each axis."""
        if position is None or not np.any(position):
            if self._at_rest is None:
                self._at_rest = self.values, self._slopes(self.values)
            return self._at_rest
        phase = np.exp(-1j * sum(q * float(x) for q, x in zip(self.wavevectors, position)))
        heights = np.fft.irfftn(self.spectrum * phase, s=self.grid.shape, axes=tuple(range(self.grid.dim)))
        return heights, self._slopes(heights)

    def _slopes(self, heights) -> list[np.ndarray]:
        return [directional_slope(heights, lengths=self.grid.lengths, direction=a * math.pi / 2,
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
        heights, slopes = self.heights_at(position)
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
                raise ValueError(f"penetration {load!r} reaches full contact on the deformed surface; in a periodic "
                                 "window the load is then undetermined: give mean_pressure")
        state = constrained_solve(compliance, effective, **args)
        if not state.converged:
            raise ConvergenceError(f"{state.solver} did not converge in {state.iterations} iterations: residual "
                                   f"{state.residual:.3e} > tol {self.tol:.1e}", residual=state.residual, dataset=None)
        if not self.periodic and _touches_edge(state.pressure):
            raise ValueError("periodic=False: the contact reaches the edge of the window; enlarge the window")
        self.previous, self.pressure = self.pressure, state.pressure
        p = state.pressure
        mean = float(p.mean())
        forces = [-float(np.mean(p * s)) for s in slopes]
        displacement = state.displacement if memory is None else state.displacement + memory
        return {"pressure": p, "gap": state.gap, "displacement": displacement, "mean_pressure": mean,
                "penetration": float(state.penetration - shift), "contact_area": float(np.count_nonzero(p > 0)) / p.size,
                "iterations": state.iterations, "residual": state.residual,
                **{f"tangential_force_{a}": f for a, f in zip(self.axes, forces)}}


class _Record:
    """The scalars of every step and the fields of the saved ones, labelled on demand."""

    SCALARS = ("mean_pressure", "penetration", "contact_area", "friction_coefficient_interlocking",
               "dissipated_power", "iterations", "residual")

    def __init__(self, stepper: _Stepper, times, positions, saved, moving: bool):
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
        dims = ("saved_time",) + stepper.dims
        ds = ds.assign_coords(saved_time=("saved_time", np.array(self.field_times),
                                          {"units": time_unit, "long_name": "time of the saved fields"}))
        ds = ds.assign_coords({d: (d, c, a(d)) for d, c in zip(stepper.dims, stepper.grid.coordinates())})
        for name, values in self.fields.items():
            data = np.stack(values) if values else np.zeros((0,) + stepper.grid.shape)
            ds[name] = (dims, data, a(name))
        material = stepper.material
        ds.attrs.update({
            "Conventions": "CF-1.10", "contactlib_version": __version__, "status": status, "steps": n,
            "wall_time": _time.perf_counter() - start, "E0": float(material.E0), "E_inf": float(material.E_inf),
            "nu": float(material.nu), "prony": [v for branch in getattr(material, "prony", ()) for v in branch],
            "tol": stepper.tol, "max_iter": stepper.max_iter, "periodic": int(stepper.periodic),
            "window_lengths": list(stepper.grid.lengths), "load_control": stepper.control,
            "time_integration": "displacement at a constant rate over each step, Prony branches integrated exactly "
                                "(second order; exact at fixed displacement): contactlib.hereditary",
            "model": next(iter(stepper._models.values())).attrs["model"] if stepper._models else "",
        })
        if stepper.layer is not None:
            ds.attrs.update(layer_thickness=float(stepper.layer.thickness), layer_base=stepper.layer.base)
        return ds


def _prepare(heights, *, times, material, mean_pressure, penetration, path, layer, periodic, tol, max_iter, length):
    """Validate a run; returns ``(stepper, times, loads, positions, control)``."""
    values, grid, dims, _ = grid_of(heights, length)
    periodic = periodic_of(heights, periodic)
    _check_tolerance(tol, "tol")
    if isinstance(max_iter, bool) or not isinstance(max_iter, (int, np.integer)) or max_iter < 1:
        raise ValueError(f"max_iter must be an integer >= 1, got {max_iter!r}")
    _check_friction(layer, 0.0, 0.0, material.nu, "cg", "spectral", periodic)
    times = _times(times)
    if (mean_pressure is None) == (penetration is None):
        raise ValueError("give exactly one of mean_pressure or penetration")
    control = "mean_pressure" if mean_pressure is not None else "penetration"
    loads = _history(mean_pressure if mean_pressure is not None else penetration, times, control)
    if control == "mean_pressure" and np.any(loads < 0):
        raise ValueError(f"mean_pressure must be >= 0 at every time, got {loads.min()!r}")
    positions = _positions(path, times, grid.dim)
    stepper = _Stepper(values, grid, dims, material, layer, periodic, float(tol), int(max_iter), control)
    return stepper, times, loads, positions, control


def _times(times) -> np.ndarray:
    """The instants as a finite, strictly increasing 1D array."""
    times = np.asarray(times, dtype=float)
    if times.ndim != 1 or times.size < 1:
        raise ValueError(f"times must be a 1D sequence of at least one time, got shape {times.shape}")
    if not np.all(np.isfinite(times)):
        raise ValueError("times must be finite")
    if np.any(np.diff(times) <= 0):
        k = int(np.argmax(np.diff(times) <= 0))
        raise ValueError(f"times must increase strictly (every dt > 0): times[{k + 1}] = {times[k + 1]!r} after "
                         f"times[{k}] = {times[k]!r}")
    return times


def _history(load, times: np.ndarray, name: str) -> np.ndarray:
    """A load as one value per time: a constant, a sequence or a function of time; NaN refused."""
    if callable(load):
        values = np.array([float(load(t)) for t in times])
    else:
        values = np.asarray(load, dtype=float)
        if values.ndim == 0:
            values = np.full(times.shape, float(values))
        elif values.shape != times.shape:
            raise ValueError(f"{name} has {values.size} values for {times.size} times: give one per time")
    if not np.all(np.isfinite(values)):
        k = int(np.argmax(~np.isfinite(values)))
        raise ValueError(f"{name} history holds a non-finite value ({values[k]!r}) at times[{k}] = {times[k]!r}")
    return values


def _positions(path, times: np.ndarray, dim: int) -> np.ndarray:
    """The path as an ``(n, dim)`` array of finite positions (zeros without a path)."""
    if path is None:
        return np.zeros((times.size, dim))
    values = (np.array([np.atleast_1d(np.asarray(path(t), dtype=float)) for t in times]) if callable(path)
              else np.asarray(path, dtype=float))
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


__all__ = ["solve_transient", "solve_reciprocating", "TransientInterrupted"]
