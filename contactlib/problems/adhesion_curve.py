"""Loading-unloading paths of adhesive contact: :func:`adhesion_curve`.

A path is a sequence of approaches (or of mean pressures) taken up, then back down. Each state is
solved from the previous one (a warm start), so the solve follows the branch it is on; where that
branch ends the state jumps, and the jump is recorded:

* cohesive laws: the warm-started Newton solve lands on whatever equilibrium is nearest. A penetration path starts
  from separation, as the energy method's does: a first approach below the highest point is solved from the open
  state (which holds where the surface is beyond the law's reach). A jump is a
  step where the closed (repulsive) area appears or vanishes, or full contact is reached or left. A step
  whose solve fails is retried from the non-adhesive state and from the open one; if those fail too, the step is kept
  with ``converged = 0`` and NaN scalars and the path goes on (it never raises). Under load control, beyond the
  pull-off there is no equilibrium: those steps are NaN, ``converged = 0``, and ``attrs['detached']`` says from where.
* ``"jkr"`` (the energy method): the state is the domain reached from the previous domain by moving its
  edge (:meth:`contactlib.solvers.adhesive.energy.EnergyFamily.descend`): it grows where the approach exceeds the
  tensile Griffith root of ``G = w`` and shrinks below the previous one's, so it leaves a domain exactly
  where its local minimum of ``F_m(d)`` disappears, and never descends into smaller, interpenetrating
  domains after a large step. Under load control the state carries the load asked exactly: the domain in
  whose cell the equilibrium curve ``G = w`` carries it, at the approach that makes its load the one asked
  (:meth:`contactlib.solvers.adhesive.energy.EnergyFamily.load_state`); beyond the pull-off, NaN
  (``attrs['detached']``). A state that would need a larger domain than the family holds (2D: the disc the window
  holds) is refused with a ValueError naming the limit.

Reported (Clarifications, "Adhesion"): ``pull_off_pressure``, the pull-off of load control (cohesive laws: the
most tensile mean pressure along the path where the path went past it, else NaN with ``attrs['pull_off_status']``;
``"jkr"``: the least load of the equilibrium curve ``G = w`` on its
rising stretch, :meth:`~contactlib.solvers.adhesive.energy.EnergyFamily.pull_off`, whatever the path's sampling);
``pull_off_penetration``, the approach of the jump out of contact on unloading (cohesive: of the last state
before it; ``"jkr"``: where the edge retreats past the curve's least approach under penetration control, the
curve's approach at the pull-off under load control; NaN where the path does not leave contact);
``jump_in_penetration``, the
approach of the first closed state on loading; ``full_contact_penetration``; and
``hysteresis_energy``, the loop integral of the mean pressure over the approach (trapezoids, so jumps
are resolved only to the step).
"""

from __future__ import annotations

import math
import time

import numpy as np
import xarray as xr

from . import adhesive_choice, adhesive
from .._version import __version__
from ..model.adhesion import Adhesion
from ..invariants import adhesive_state_holds, verify_path
from ..core.inputs import check_below_full_contact, real_values
from ..core.labels import attrs_for
from .problem import prepare
from ..resolution import guard_path


def adhesion_curve(
    heights,
    *,
    E: float | None = None,
    nu: float | None = None,
    adhesion: Adhesion,
    penetrations=None,
    mean_pressures=None,
    layer=None,
    periodic: bool | None = None,
    tol: float | None = None,
    kernel: str = "spectral",
    length=None,
    length_unit: str = "m",
    pressure_unit: str = "Pa",
    material=None,
) -> xr.Dataset:
    """Adhesive contact along a loading-unloading path.

    Parameters
    ----------
    heights : xarray.DataArray or ndarray
        Rigid surface heights [length] as for :func:`contactlib.solve` (an ndarray needs ``length``).
    E, nu : float
        Young's modulus [pressure] and Poisson ratio: the shorthand for ``material=contactlib.Elastic(E, nu)``.
    material : contactlib.Elastic or contactlib.Viscoelastic, optional
        The body's material instead of ``E, nu``; a viscoelastic body is taken relaxed (``E0``): the path is
        quasi-static.
    adhesion : contactlib.Adhesion
        The interface.
    penetrations : sequence of float
        Displacement control: the loading approaches [length], increasing; the path goes through them
        and back (unloading) in reverse order.
    mean_pressures : sequence of float
        Load control instead: the loading mean pressures [pressure], increasing, then back.
    layer, periodic, tol, kernel, length, length_unit, pressure_unit
        As for :func:`contactlib.solve`.

    Returns
    -------
    xarray.Dataset
        Along dimension ``step``: ``penetration``, ``mean_pressure``, ``contact_area``,
        ``interaction_area``, ``unloading``, ``jump``, ``converged``, ``residual``; scalars ``pull_off_pressure``,
        ``pull_off_penetration``, ``jump_in_penetration``, ``full_contact_penetration`` and
        ``full_contact_pressure`` (the first fully closed state on loading),
        ``hysteresis_energy``. ``attrs['converged']`` is 0 where a step of a penetration-controlled path failed:
        the scalars are then NaN and ``attrs['convergence_message']`` names the steps.

    Raises
    ------
    ValueError
        Naming the parameter: ``adhesion`` not an Adhesion, not exactly one of ``penetrations`` and
        ``mean_pressures``, fewer than 2 strictly increasing values, a penetration beyond full contact, a contact cut by
        a non-periodic window's edge, or a state beyond the energy method's family of discs.
    """
    if adhesion is None or not hasattr(adhesion, "model"):
        raise ValueError(f"adhesion must be a contactlib.Adhesion, got {adhesion!r}")
    if (penetrations is None) == (mean_pressures is None):
        raise ValueError("give exactly one of penetrations or mean_pressures")
    load_control = mean_pressures is not None
    name = "mean_pressures" if load_control else "penetrations"
    values = real_values(mean_pressures if load_control else penetrations, name).ravel()
    if values.size < 2 or not np.all(np.isfinite(values)) or np.any(np.diff(values) <= 0):
        raise ValueError(f"{name} must hold at least 2 finite, strictly increasing values")
    path = np.concatenate([values, values[::-1][1:]])
    unloading = np.concatenate([np.zeros(values.size), np.ones(values.size - 1)]).astype(int)
    first = {"mean_pressure": float(path[0])} if load_control else {"penetration": float(path[0])}
    problem = prepare(heights, E=E, nu=nu, material=material, layer=layer, adhesion=adhesion, periodic=periodic,
                      length=length, tol=tol, max_iter=10_000, kernel=kernel, method="cg")
    setup = problem.loaded(**first)  # the path's first load: its checks; each step sets its own
    if not load_control and not setup.body.compliance.definite:
        # as solve refuses one such penetration (its steps failed one by one, the path's scalars NaN)
        check_below_full_contact(float(values.max()), setup.values, "penetrations",
                                 "stop below it, or give mean_pressures")
    start = time.perf_counter()
    curve_scalars = {}
    if adhesion.model == "jkr":
        rows, curve_scalars = _energy_path(setup, adhesion, path, load_control, unloading)
    else:
        rows = _cohesive_path(setup, adhesion, path, load_control)
    wall = time.perf_counter() - start
    ds = _label(setup, adhesion, rows, unloading, load_control, wall, length_unit, pressure_unit)
    verify_path(ds, path, setup.values, adhesion, load_control=load_control, tol=setup.solver_args["tol"])
    _curve_scalars(ds, curve_scalars, length_unit, pressure_unit)
    guard_path(ds, setup)
    return ds


BISECTIONS = 3
"""A step of a penetration-controlled path that no start converges is approached through midpoints of its increment,
each warm-started from the last, this many halvings deep at most. On a 64^2 rough surface of the quick workflow
(exponential law, range 1.3 rms heights) the step from 0 to 0.5 rms heights failed from every start (residual
5.3e-3) and converged through 0.25."""


def _cohesive_step(setup, adhesion, args, warm, warm_d, *, cold=True, open_first=False):
    """The converged state at ``args``' load or penetration from the warm start ``(warm, warm_d)``, then (``cold``)
    the non-adhesive state, then the open one (a jump lands on either; ``open_first``: the open one alone, a path's
    first state apart); ``(None, smallest residual)`` if none."""
    closest = math.nan
    # without a warm start the first attempt is the cold one: it is not solved twice. Apart (open_first: a path's
    # first state at a negative approach) the non-adhesive state is the open one, so the cold start is left out: its
    # continuations spent 45 s there on issue 38's sphere on 512^2 and found nothing (_from_contact does)
    starts = [np.zeros_like(setup.values)] if open_first else [None, np.zeros_like(setup.values)]
    attempts = ([warm] if warm is not None else []) + (starts if cold else [])
    for attempt in attempts:
        setup.solver_args = dict(args, initial_pressure=attempt)
        try:
            candidate = adhesive_choice.solve(setup, adhesion, warm_penetration=warm_d if attempt is not None
                                              else None)
        except (ValueError, np.linalg.LinAlgError, FloatingPointError):
            continue
        if candidate.converged and adhesive_state_holds(candidate, setup.values, adhesion, tol=args["tol"],
                                                        mean_pressure=args["mean_pressure"],
                                                        penetration=args["penetration"]):
            return candidate, closest
        closest = float(np.fmin(closest, candidate.residual))
    return None, closest


def _bisected_step(setup, adhesion, args, warm, warm_d, value, depth=BISECTIONS):
    """The state at penetration ``value`` reached through the midpoint of the increment from ``warm_d`` (halved
    again where the midpoint fails, ``depth`` times at most); None where no midpoint leads there."""
    if depth == 0 or warm is None or warm_d is None:
        return None
    middle = 0.5 * (warm_d + value)
    state, _ = _cohesive_step(setup, adhesion, dict(args, penetration=middle), warm, warm_d, cold=False)
    if state is None:
        state = _bisected_step(setup, adhesion, args, warm, warm_d, middle, depth - 1)
    if state is None:
        return None
    return _stepped(setup, adhesion, args, state.pressure, state.penetration, value, depth - 1)


def _stepped(setup, adhesion, args, warm, warm_d, value, depth=BISECTIONS):
    """The state at penetration ``value`` from the warm start ``(warm, warm_d)`` in one step, through midpoints
    (:func:`_bisected_step`, ``depth`` halvings) where that fails; None where both fail."""
    done, _ = _cohesive_step(setup, adhesion, args, warm, warm_d, cold=False)
    return done if done is not None else _bisected_step(setup, adhesion, args, warm, warm_d, value, depth)


def _from_contact(setup, adhesion, args, value):
    """A path's first state apart (approach ``value < 0``) where the open state does not hold: past the jump in, so
    the state is in contact. It is reached from contact, as the unloading path reaches it: the cold state at the
    mirrored approach ``-value``, unloaded to ``value`` in one step, through midpoints where that fails; None where
    those fail too. Issue 38's sphere on 512^2 at lambda 10, from 0.5e-3 apart (the law as the grid solves it jumps in
    from 0.54-0.57e-3): the step converges in 6 s, and the first state costs about 14 s, against 33 s through the
    midpoint 0 first (the cold start at the state itself failed after 45 s)."""
    touching, _ = _cohesive_step(setup, adhesion, dict(args, penetration=-value), None, None)
    if touching is None:
        return None
    return _stepped(setup, adhesion, args, touching.pressure, touching.penetration, value)


def _cohesive_path(setup, adhesion, path, load_control):
    rows, warm, warm_d, area_before = [], None, None, 0.0
    for value in path:
        args = dict(setup.solver_args, mean_pressure=None, penetration=None)
        args["mean_pressure" if load_control else "penetration"] = float(value)
        # penetration control: a failed warm start is approached through midpoints (from warm starts) before the
        # cold and open starts are tried, which only a jump needs (issue 38's Maugis sphere at lambda 5 on 256^2: a
        # failed unloading step cost 57 s of cold and open starts before its midpoint converged in 0.5 s)
        # a penetration path starts from separation, as the energy method's does: its first state is solved from the
        # open state where the surface is apart (issue 38's sphere on 512^2 at lambda 7: the open state, which holds
        # there, came back after 46 s of the cold start's continuation in the range, at once from the open one)
        apart = bool(warm is None and not load_control and value < 0)  # a penetration path's first state, apart
        state, closest = _cohesive_step(setup, adhesion, args, warm, warm_d, cold=load_control or warm is None,
                                        open_first=apart)
        if state is None and apart:
            state = _from_contact(setup, adhesion, args, float(value))
        if state is None and not load_control:
            state = _bisected_step(setup, adhesion, args, warm, warm_d, float(value))
        if state is None and not load_control and warm is not None:
            state, closest = _cohesive_step(setup, adhesion, args, None, None)
        if state is not None:
            setup.check_window(state.pressure)  # a window that cuts the contact or its cohesive zone: refused
        if state is None:
            rows.append(_failed_row(value, load_control, closest))
            continue
        area = float(np.count_nonzero(state.in_contact)) / state.in_contact.size
        jump = _jumped(area, area_before, state.in_contact.size)
        rows.append({"penetration": state.penetration, "mean_pressure": state.mean_pressure, "contact_area": area,
                     "interaction_area": float(np.count_nonzero(adhesion.interacting(state.gap)))
                     / state.gap.size, "jump": int(jump and bool(rows)), "converged": 1,
                     "residual": state.residual})
        warm, warm_d, area_before = state.pressure, state.penetration, area
    return rows


def _full(area: float, size: int) -> bool:
    """Full contact: every element closed but at most one (the energy method's largest domain leaves out
    the last element, which a periodic half-space closes only at ``d = mean(max h - h)``)."""
    return area >= 1.0 - 1.5 / size


def _jumped(area: float, before: float, size: int) -> bool:
    """Whether the closed area appeared, vanished, reached or left full contact between two steps."""
    return (area > 0) != (before > 0) or _full(area, size) != _full(before, size)


def _failed_row(value, load_control, residual=math.nan):
    row = {"penetration": math.nan, "mean_pressure": math.nan, "contact_area": math.nan,
           "interaction_area": math.nan, "jump": 1, "converged": 0, "residual": residual}
    row["mean_pressure" if load_control else "penetration"] = float(value)
    return row


def _energy_path(setup, adhesion, path, load_control, unloading):
    """The energy method's states along ``path``, and the path's scalars that its equilibrium curve fixes
    whatever the sampling (:func:`_curve_scalars`)."""
    fam = adhesive.family(setup)
    w = adhesion.work
    rows, m = [], -1
    largest = fam.a.size  # the index of the closed window (one past the largest partial domain)
    fam_definite = setup.operator.definite
    pull_off, k_pull_off = fam.pull_off(w)
    turned = -1  # the domain unloading starts from
    for value, back in zip(path, unloading):
        if back and turned < 0 <= m:
            turned = min(m, largest - 1)
        if load_control:
            found = fam.load_state(float(value), w, near=m)
            if found is None and fam.limit is not None and not value < pull_off:
                raise fam.refusal("mean_pressures", float(value))
            m_new, d = found if found is not None else (None, None)
            # no stable partial contact carries a compressive load: the contact jumps to full (a thin
            # remote-pressure layer has no stable partial contact at all)
            full = m_new is None and (value > 0 or (m == largest and value >= 0))
            if full and not fam_definite:
                # the closed window: its penetration is the mean of max h - h, its load whatever is applied
                rows.append({"penetration": float(np.mean(fam.h0)), "mean_pressure": float(value),
                             "contact_area": 1.0, "interaction_area": 1.0, "converged": 1,
                             "jump": int(m != largest), "residual": 0.0})  # exact: the flat punch
                m = largest
                continue
            if m_new is None:  # beyond the pull-off: no equilibrium under load control
                rows.append(_failed_row(value, True))
                m = -1
                continue
        else:
            d = float(value)
            m_new = fam.descend(m if m < largest else largest - 1, d, w)
            if fam.beyond(m_new):
                raise fam.refusal("penetrations", d)
        # where the grid does not resolve w at this domain, the non-adhesive solve (adhesive.energy_or_plain)
        state = adhesive.energy_or_plain(setup, fam, w, m_new, d, "", mean_pressure=float(value)
                                                 if load_control else None)
        setup.check_window(state.pressure)
        area = float(np.count_nonzero(state.in_contact)) / state.in_contact.size
        before = 0.0 if m < 0 else 1.0 if m >= fam.ends.size else float(fam.ends[m]) / fam.size
        jump = _jumped(area, before, fam.size)
        rows.append({"penetration": state.penetration, "mean_pressure": state.mean_pressure, "contact_area": area,
                     "interaction_area": area, "converged": int(state.converged), "jump": int(bool(rows) and jump),
                     "residual": state.residual})
        m = m_new
    # the jump out of contact on unloading, where the path makes it: a closed state, then an open or detached one
    left = any(b and a > 0 and not c > 0 for (a, b, c) in zip([r["contact_area"] for r in rows],
                                                             unloading[1:], [r["contact_area"] for r in rows[1:]]))
    jump_out = math.nan
    if left and load_control:
        jump_out = fam.pull_off_penetration(w)
    elif left:
        jump_out = fam.detachment_penetration(w, start=turned if turned >= 0 else None)
    scalars = {"pull_off_pressure": pull_off, "pull_off_penetration": jump_out}
    if k_pull_off == -1 and w > 0 and fam.a.size > 1 and w < float(fam.least_release_rate()[0]):
        scalars["pull_off_status"] = (
            f"the pull-off's contact is under a spacing (work {w:.4g} below {float(fam.least_release_rate()[0]):.4g}, "
            "the least energy release rate of the first growth step): the first touch's pull-off at that work, "
            "scaled to this one as the continuum's (EnergyFamily.open_point); a finer grid resolves it")
    return rows, scalars


def _curve_scalars(ds: xr.Dataset, scalars: dict, length_unit: str, pressure_unit: str) -> None:
    """Put the scalars an equilibrium curve fixes in place of those read off the sampled states (in place): the
    energy method's pull-off, the least load of its equilibrium curve ``G = w`` (the sawtooth of its states, whose
    domain grows by whole elements, reaches below it by a step-dependent amount), and the penetration at which
    the path leaves contact (:meth:`contactlib.solvers.adhesive.energy.EnergyFamily.detachment_penetration`; under load
    control, the curve's at the pull-off,
    :meth:`~contactlib.solvers.adhesive.energy.EnergyFamily.pull_off_penetration`). Not where a failed step withheld
    the scalars."""
    if not scalars or ds.attrs.get("converged") != 1:
        return
    status = scalars.pop("pull_off_status", "")
    for name, value in scalars.items():
        ds[name] = ((), float(value), attrs_for(name, length=length_unit, pressure=pressure_unit))
    ds.attrs.pop("pull_off_status", None)  # the sampled states' status: the curve's pull-off is whatever they are
    if status:
        ds.attrs["pull_off_status"] = status
    ds.attrs["pull_off_definition"] = (
        "pull_off_pressure: the least mean pressure of the equilibrium curve G = w (its points between consecutive "
        "domains, second order in the spacing), whatever the path's sampling; pull_off_penetration: where the path "
        "leaves contact (penetration control: the edge retreating past the curve's least approach; load control: "
        "the curve's approach at the pull-off), NaN where the path does not")


def _sampled_pull_off(P: np.ndarray, area: np.ndarray, ok: np.ndarray, load_control: bool) -> tuple[float, str]:
    """A path's pull-off from its states (cohesive laws; the energy method's is its curve's, :func:`_curve_scalars`)
    and, where it is NaN, why. The pull-off is the turning point of the converged branch (Clarifications,
    "Adhesion"): the least sampled load is one only where the path went past it. Under penetration control: a
    later solved state carries more, or it or a later one is out of contact (the branch detached), and the least is
    not the path's first state unless that one is out of contact (else the branch before it is unsampled). Under
    load control: a later load had no equilibrium (``detached``). A path that stops short (a w -> 0 path of
    compressive states gave +4.5e-4, its least sampled compressive state, as its pull-off) has NaN. The turning
    point is the least sampled load: within the step."""
    solved = np.flatnonzero(ok)
    if solved.size == 0:
        return math.nan, ""
    least = solved[int(np.argmin(P[solved]))]
    lowest = float(P[least])
    if load_control:
        if np.any(~ok[least:]):
            return lowest, ""
        return math.nan, ("the path did not reach pull-off: every load asked has an equilibrium (ask more tension "
                          "under load control, or follow the approach)")
    later = solved[solved > least]
    out = area[least] == 0  # the least is out of contact: the branch has detached by then
    passed = out or bool(np.any((P[later] > lowest) | (area[later] == 0)))
    started = out or least != solved[0]
    if passed and started:
        return lowest, ""
    return math.nan, (f"the path did not reach pull-off: its least mean pressure {lowest:.6g} is at its "
                      f"{'last' if not passed else 'first'} solved state, in contact, where the branch may still "
                      "fall (extend the path past the turning point: from and back out of contact)")


def _label(setup, adhesion, rows, unloading, load_control, wall, length_unit, pressure_unit) -> xr.Dataset:
    def a(name):
        return attrs_for(name, length=length_unit, pressure=pressure_unit)

    step = np.arange(len(rows))
    data = {}
    for key in ("penetration", "mean_pressure", "contact_area", "interaction_area", "jump"):
        data[key] = ("step", np.array([r[key] for r in rows], dtype=float if key != "jump" else int), a(key))
    data["converged"] = ("step", np.array([r["converged"] for r in rows]),
                         {"units": "1", "long_name": "1 where the state's solve met its tolerance"})
    data["residual"] = ("step", np.array([r.get("residual", math.nan) for r in rows], dtype=float),
                        {"units": "1", "long_name": "scale-free contact residual of the state (a failed step: the "
                                                   "smallest its attempts reached; NaN: none returned one)"})
    data["unloading"] = ("step", unloading, a("unloading"))
    ds = xr.Dataset(data, coords={"step": ("step", step, a("step"))})
    d, P, area = ds["penetration"].values, ds["mean_pressure"].values, ds["contact_area"].values
    ok = np.isfinite(P) & np.isfinite(d)
    pull_off, pull_off_status = _sampled_pull_off(P, area, ok, load_control)
    # the jump out of contact on unloading: the last closed state before an open one
    pull_off_d = math.nan
    solved = [k for k in range(step.size) if ok[k] and unloading[k]]
    for before, after in zip(solved, solved[1:]):  # failed steps are skipped, not taken for a jump
        if area[before] > 0 and area[after] == 0:
            pull_off_d = float(d[before])
            break
    jump_in = math.nan
    for k in range(step.size):
        if not unloading[k] and ok[k] and area[k] > 0:
            jump_in = float(d[k])
            break
    full, full_p = math.nan, math.nan
    for k in range(step.size):
        if not unloading[k] and ok[k] and _full(area[k], setup.values.size):
            full, full_p = float(d[k]), float(P[k])
            break
    keep = ok
    loop = float(np.sum(0.5 * (P[keep][1:] + P[keep][:-1]) * np.diff(d[keep]))) if keep.sum() > 1 else math.nan
    ds["pull_off_pressure"] = ((), pull_off, a("pull_off_pressure"))
    ds["pull_off_penetration"] = ((), pull_off_d, a("pull_off_penetration"))
    ds["jump_in_penetration"] = ((), jump_in, a("jump_in_penetration"))
    ds["full_contact_penetration"] = ((), full, a("full_contact_penetration"))
    ds["full_contact_pressure"] = ((), full_p, a("full_contact_pressure"))
    ds["hysteresis_energy"] = ((), loop, a("hysteresis_energy"))
    ds.attrs.update({"Conventions": "CF-1.10", "title": "adhesive loading-unloading path",
                     "contactlib_version": __version__,
                     "load_control": "mean_pressure" if load_control else "penetration", "wall_time": wall,
                     **{k: v for k, v in setup.attrs.items() if k != "load_control"}, **adhesion.attrs()})
    if pull_off_status:
        ds.attrs["pull_off_status"] = pull_off_status
    if load_control and not ok.all():
        first = int(np.flatnonzero(~ok)[0])
        ds.attrs["detached"] = (f"no adhesive equilibrium from step {first} (mean pressure "
                                f"{ds['mean_pressure'].values[first]:.6g}): pulled off under load control")
    failed = np.flatnonzero(ds["converged"].values == 0)
    if failed.size and not load_control:
        # under penetration control every step has an equilibrium: a failed one leaves a hole in the path, and
        # the path's scalars read across it (a pull-off from the compressive steps alone came out positive)
        for name in ("pull_off_pressure", "pull_off_penetration", "jump_in_penetration", "full_contact_penetration",
                     "full_contact_pressure", "hysteresis_energy"):
            ds[name] = ((), math.nan, a(name))
        ds.attrs["converged"] = 0
        ds.attrs["convergence_message"] = (f"steps {failed.tolist()[:10]} did not converge (residual per step in "
                                           "`residual`): the path's scalars are NaN")
    else:
        ds.attrs["converged"] = 1
    return ds
