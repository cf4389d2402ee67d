"""Reciprocating sliding on a viscoelastic body: :func:`solve_reciprocating` drives the time stepper of
:mod:`contactlib.problems.transient` cycle by cycle, extrapolates the body's memory to the cycle's fixed point and
stops when the cycle repeats.
"""

from __future__ import annotations

import logging
import math
import time as _time
import warnings
from collections.abc import Callable

import numpy as np
import xarray as xr

from ..model.bodies import Layer
from ..errors import ConvergenceError
from ..invariants import step_invariants, with_dataset
from ..core.inputs import check_tolerance, check_whole, grid_of, number
from ..core.labels import attrs_for
from ..model.materials import Elastic, material_of
from ..resolution import guard_stepper
from ..solvers.state import dot
from .transient import SLIDE_PER_STEP, StepRecord, TimeStepWarning, TransientInterrupted, check_slide, prepare_stepper

log = logging.getLogger(__name__)

MIN_STEPS_PER_CYCLE = 64
"""``steps_per_cycle``'s least default, however small the amplitude (and an elastic body's): the cycle's own shape
in time."""

ENERGY_BALANCE = 0.05
"""A settled cycle whose friction work and dissipated energy differ by more than this fraction of its absolute
work warns (:class:`.TimeStepWarning`): the steps do not resolve it. Over 72 scenes at the default steps (1D
256 points, 2D 32^2 and 64^2; E_inf/E0 10 and 1000; f tau 1e-3..10; amplitudes 0.01 and 0.3 of the window;
two loads), 52 settled and five of them passed it: the 2D amplitudes of 0.3 at f tau = 1e-3 under the small
load (tiny contacts that a spacing a step still jumps across; the energy moved 6-12 % on doubling the steps, a
first-order convergence) and one 1D profile whose loop work alone lagged (+0.16; its energy moved 0.45 %).
Below it the energy moved at most 3.8 % on doubling, and less than 1 % in 41 of the 47 settled scenes below
it."""


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
    steps_per_cycle: int | None = None,
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
    change relative to the cycle's absolute work (``oint |tau_a dX_a|`` summed over the axes). A tangential
    force below the steps' error (``tol`` times the mean pressure) counts as zero there: an elastic body's
    loop, 1e-18 of the load, settles at ``min_cycles``. Past ``max_cycles`` the cycles done are returned with
    ``attrs['status']`` saying the cycle did not settle and the last change.

    Parameters as :func:`solve_transient`; ``amplitude`` [length] and ``frequency`` [1/time] > 0;
    ``direction`` [rad] (a profile: 0 or pi); ``tol`` at most a tenth of ``cycle_tol`` (else ValueError: the
    steps' own error would keep the cycles from settling). ``steps_per_cycle``: by default the fewest, and at
    least :data:`MIN_STEPS_PER_CYCLE`, that slide the surface at most :data:`.transient.SLIDE_PER_STEP` grid
    spacing a step (``2 pi amplitude`` over the spacing along ``direction``, rounded up to a multiple of 4: 484
    for an amplitude of 0.3 of a 256-point window, 324 for 0.1 of a 512^2 map; an elastic body, which has no
    memory, takes 64). Fewer, given, warn (:class:`contactlib.TimeStepWarning`): at 7.5 spacings a step that
    profile dissipated 41 % too little (the profile: 256 points, amplitude 0.3 of the window, standard linear
    solid E_inf/E0 = 10, f tau = 1e-3).


    Parameters
    ----------
    heights : xarray.DataArray or ndarray
        Rigid surface heights [length], as :func:`contactlib.solve` takes them.
    amplitude : float
        Amplitude ``A`` of the motion [length], > 0.
    frequency : float
        Frequency ``f`` [1/time], > 0.
    mean_pressure : float
        The constant load [pressure].
    material : contactlib.Viscoelastic or contactlib.Elastic, optional
        The body (or ``E``, ``nu``).
    E, nu : float, optional
        The elastic shorthand.
    direction : float
        Direction of the motion [rad]; a profile: 0 or pi.
    steps_per_cycle : int, optional
        Time steps per cycle, a multiple of 4; default by the slide a step (above).
    max_cycles, min_cycles : int
        Bounds on the cycles run, ``2 <= min_cycles <= max_cycles``.
    cycle_tol : float
        Settling tolerance on the change between cycles.
    accelerate : bool
        Aitken's extrapolation of the memory every second cycle.
    layer : contactlib.Layer, optional
        A finite layer, as in :func:`contactlib.solve`.
    periodic : bool, optional
        As in :func:`contactlib.solve`.
    tol, max_iter : float, int
        Each step's contact tolerance (at most a tenth of ``cycle_tol``) and iteration bound.
    length : float or tuple, optional
        Window size [length], required for bare-array heights.
    progress : callable, optional
        Called after each step, as in :func:`solve_transient`.
    length_unit, pressure_unit, time_unit : str
        udunits strings written to the output's ``units`` attributes.

    Returns
    -------
    xarray.Dataset
        The last cycle on ``time`` (``position_x``, ``tangential_force_x``, ``friction_coefficient_interlocking``,
        ``contact_area``, ``penetration``, ``dissipated_power``, ...: the hysteresis loop is
        ``tangential_force_x / mean_pressure`` against ``position_x``), and on ``cycle``:
        ``dissipated_energy`` (the integral of the dissipated power over the cycle) and ``friction_work``
        (``oint tau . dX``, the work the motion puts in: equal to it once the cycle repeats) [pressure
        length], and ``cycle_change``. Scalars ``dissipated_energy_per_cycle`` and
        ``friction_work_per_cycle`` of the last cycle, and ``energy_balance``, their difference over the
        cycle's absolute work (the time stepping's error shows there: -0.77 at 7.5 spacings a step, -0.012
        at 1.0, -0.003 at 0.47 on the profile above; a settled cycle beyond :data:`ENERGY_BALANCE` warns; NaN
        where the absolute work is below the steps' error, as on an elastic body); ``attrs['status']``
        ``"settled"`` or not, ``attrs['slide_per_step']`` the largest slide of a step [grid spacings].

    Raises
    ------
    ValueError
        Naming the parameter: a bad value, ``tol`` above a tenth of ``cycle_tol``, ``direction`` other than 0 or pi on
        a profile, ``min_cycles`` above ``max_cycles``.
    ConvergenceError
        A step did not converge: ``err.dataset`` holds the run so far.
    TransientInterrupted
        Ctrl-C: ``err.dataset`` holds the cycles done.

    Warns
    -----
    TimeStepWarning
        When a step slides farther than one grid spacing, or a settled cycle's energy balance exceeds
        :data:`ENERGY_BALANCE`.
    """
    amplitude = number("amplitude", amplitude, lower=0.0, lower_open=True)
    frequency = number("frequency", frequency, lower=0.0, lower_open=True)
    mean_pressure = number("mean_pressure", mean_pressure, lower=0.0)
    if steps_per_cycle is not None:
        steps_per_cycle = check_whole(steps_per_cycle, "steps_per_cycle (None: by the slide a step)", 4)
    min_cycles = check_whole(min_cycles, "min_cycles", 2)
    max_cycles = check_whole(max_cycles, "max_cycles", 2)
    if min_cycles > max_cycles:
        raise ValueError(f"need integers 2 <= min_cycles <= max_cycles, got min_cycles={min_cycles!r}, "
                         f"max_cycles={max_cycles!r}")
    check_tolerance(cycle_tol, "cycle_tol")
    check_tolerance(tol, "tol")
    if tol > cycle_tol / 10 * (1 + 1e-9):  # the steps' own error then holds the cycle change above cycle_tol
        raise ValueError(f"tol {tol!r} must be at most a tenth of cycle_tol {cycle_tol!r}: the change between cycles "
                         "cannot settle below the error of the steps' solves (a rough profile at tol 1e-3 and 3e-4 "
                         "against cycle_tol 1e-3 did not settle in 40 cycles; 1e-4 settled in 6)")
    direction = number("direction (angle [rad])", direction)
    unit = np.array([math.cos(direction), math.sin(direction)])
    material = material_of(material, E, nu)
    grid = grid_of(heights, length)[1]
    dim = grid.dim
    # the sine's steepest step, 2 sin(pi / steps) <= 2 pi / steps of the amplitude, along each axis
    spacings = 2 * math.pi * amplitude * float(np.max(np.abs(unit[:dim]) / np.asarray(grid.spacing, dtype=float)))
    memory = not isinstance(material, Elastic)  # an elastic body's steps are static solves: the slide is free
    fewest = max(MIN_STEPS_PER_CYCLE, 4 * math.ceil(spacings / SLIDE_PER_STEP / 4)) if memory else MIN_STEPS_PER_CYCLE
    given = steps_per_cycle is not None
    steps_per_cycle = steps_per_cycle if given else fewest
    log.info("solve_reciprocating: %d steps a cycle (%s)", steps_per_cycle, "given" if given else "by the slide a step")
    dt = 1.0 / (frequency * steps_per_cycle)
    cycle_times = np.arange(steps_per_cycle + 1) * dt

    def path(t):
        return amplitude * math.sin(2 * math.pi * frequency * t) * unit[:dim]

    stepper, _, _, positions, control = prepare_stepper(
        heights, times=cycle_times, material=material, mean_pressure=mean_pressure, penetration=None, path=path,
        layer=layer, periodic=periodic, tol=tol, max_iter=max_iter, length=length)
    if stepper.grid.dim == 1 and abs(math.sin(direction)) > 1e-12:
        raise ValueError(f"direction must be 0 or pi for a profile (it slides along x), got {direction!r}")
    slide = check_slide(positions, stepper, f"steps_per_cycle {steps_per_cycle}: the surface", "the energy per cycle "
                         f"and the loop lose accuracy (the default, None, takes {fewest})")  # by default within it
    units = (length_unit, pressure_unit, time_unit)
    # below the steps' solve error a tangential force is noise (an elastic body's loop is 1e-18 of the load): the
    # floors of the loop's norm and of the cycle's absolute work in the change and the balance
    noise = tol * float(mean_pressure)
    noise_work = noise * 4 * amplitude  # over a cycle's travel
    start = _time.perf_counter()
    last = stepper.first(mean_pressure, control, positions[0], relaxed=True)
    energies, works, changes, previous_loop = [], [], [], None
    ends = [stepper.history.state()]  # the memory at the ends of the cycles since the last extrapolation
    status, record = None, None
    try:
        for cycle in range(max_cycles):
            record = StepRecord(stepper, cycle_times[1:] + cycle / frequency, positions[1:],
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
            absolute = float(np.sum(np.abs(mid * moved.T)))  # sum over the axes of |tau_a dX_a|
            scale = max(absolute, noise_work) or 1.0
            balance = (works[-1] - energies[-1]) / absolute if absolute > noise_work else math.nan
            log.info("solve_reciprocating: cycle %d, energy %.6g, loop work %.6g", cycle + 1, energies[-1], works[-1])
            if previous_loop is not None:
                norm = max(float(np.linalg.norm(loop)), noise * math.sqrt(loop.size)) or 1.0
                changes.append(max(float(np.linalg.norm(loop - previous_loop)) / norm,
                                   abs(energies[-1] - energies[-2]) / scale))
                if len(energies) >= min_cycles and _settled(changes, cycle_tol, tol):
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
        raise with_dataset(err, str(ds.attrs["status"]), ds) from err
    except KeyboardInterrupt:
        ds = record.dataset(start, units=units, status=f"interrupted in cycle {len(energies) + 1}")
        raise TransientInterrupted(ds.attrs["status"], ds) from None
    if status is None:
        status = (f"not settled after {max_cycles} cycles: last change between cycles "
                  f"{changes[-1] if changes else float('nan'):.3g} > cycle_tol {cycle_tol:g}")
    elif math.isfinite(balance) and abs(balance) > ENERGY_BALANCE:
        warnings.warn(f"energy_balance {balance:.3g}: the settled cycle's friction work and dissipated energy differ "
                      f"by more than {ENERGY_BALANCE:g} of its absolute work; the {steps_per_cycle} steps a cycle do "
                      f"not resolve it (give steps_per_cycle, e.g. {2 * steps_per_cycle})", TimeStepWarning,
                      stacklevel=2)
    ds = record.dataset(start, units=units, status=status)
    length_u, pressure_u, _ = units
    energy_attrs = attrs_for("dissipated_energy", length=length_u, pressure=pressure_u)
    ds = ds.assign_coords(cycle=("cycle", np.arange(1, len(energies) + 1), attrs_for("cycle")))
    ds["dissipated_energy"] = ("cycle", np.array(energies), energy_attrs)
    ds["friction_work"] = ("cycle", np.array(works), attrs_for("friction_work", length=length_u, pressure=pressure_u))
    ds["cycle_change"] = ("cycle", np.array([np.nan] + changes), attrs_for("cycle_change"))
    ds["dissipated_energy_per_cycle"] = ((), energies[-1], energy_attrs)
    ds["friction_work_per_cycle"] = ((), works[-1], attrs_for("friction_work", length=length_u, pressure=pressure_u))
    ds["energy_balance"] = ((), balance, attrs_for("energy_balance"))
    ds.attrs.update(amplitude=float(amplitude), frequency=float(frequency), direction=float(direction),
                    steps_per_cycle=steps_per_cycle, slide_per_step=slide, cycles=len(energies),
                    cycle_tol=float(cycle_tol),
                    max_cycles=max_cycles, initial="relaxed under the mean load at X = 0",
                    invariants_checked=step_invariants(control))  # the settled cycle's energy balance: a warning
    guard_stepper(ds, stepper, where="solve_reciprocating")
    return ds


def _extrapolate(first, second, third):
    """The fixed point of the cycle map from three successive cycle-end states, assuming one slow mode
    (Aitken's delta-squared on the whole state): ``third + d (r / (1 - r))``, ``d = third - second``, ``r``
    the ratio of the last two changes; the state unchanged unless ``0 < r < 1``."""
    d1 = [b - a for a, b in zip(first, second)]
    d2 = [b - a for a, b in zip(second, third)]
    norm = sum(dot(x, x) for x in d1)
    if norm <= 0:
        return third
    ratio = sum(dot(x, y) for x, y in zip(d1, d2)) / norm
    if not 0 < ratio < 0.99:
        return third
    return [x + d * (ratio / (1 - ratio)) for x, d in zip(third, d2)]


def _settled(changes: list[float], cycle_tol: float, noise: float = 0.0) -> bool:
    """The cycle repeats to ``cycle_tol``: the last change, and the rest of a geometric decrease, below it; or the
    last change is within ``noise`` (the steps' own tolerance), where the ratio of two changes means nothing."""
    last = changes[-1]
    if last > cycle_tol:
        return False
    if last <= noise:
        return True
    if len(changes) < 2 or changes[-2] <= 0:
        return True
    ratio = last / changes[-2]
    return ratio < 1 and last * ratio / (1 - ratio) <= cycle_tol
