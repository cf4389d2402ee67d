"""What every returned result must satisfy, checked in one place just before an entry point returns it.

Each ``check_<invariant>`` is a pure function of a few numbers that returns a :class:`Check`: the violation,
scale-free, and the bound it must stay within. :func:`verify` runs a list of them, records their names in
``attrs['invariants_checked']`` and raises :class:`InvariantError` (a :class:`contactlib.ConvergenceError`)
naming the first that fails and by how much: a result that breaks one is never returned as converged.

The bounds come from the residual the solvers stop on (:func:`contactlib.solvers.contact_residual`,
``R = [mean(p |g|) + mean(p) mean(max(-g, 0))] / (mean(p) h_rms) <= tol``): the load is held to ``tol`` of the
mean pressure, the penetration to ``tol`` of the rms height, the complementarity term ``mean(p |g|) / (mean(p)
h_rms)`` (a part of ``R``) to ``tol`` with the margin of :data:`RESIDUAL_MARGIN`, a negative pressure to ``tol`` of
the mean one, and the largest interpenetration of a point to :data:`POINTWISE_GAP` ``tol`` rms heights. Measured on
converged solves (64^2 rough surfaces, tol 1e-8 and 1e-5; Polonsky-Keer, its dual, the semismooth Newton, GMRES and
coupled solvers; periodic and non-periodic, layers, friction and steady viscoelastic sliding): the load within 4e-8
``tol`` (round-off), no negative pressure, the complementarity term at most 0.9 ``tol`` (up to 1.19 times the solver's
own residual: Polonsky-Keer reports the residual of its last iterate before the final projection), the largest
interpenetration at most 5.9 ``tol`` rms heights (a thin remote-pressure layer; 264 on the warm-started steps of a
time series), ``gap = displacement + max(h) - h - penetration`` to 2e-7 ``tol``. All of them on one fused pass over
the fields (:func:`field_measures`). Adhesion, energy balance and the relaxed limit of time stepping: their constants
below.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .core._numba import vector_jit
from .errors import ConvergenceError
from .core.inputs import in_solver_axes
from .solvers.adhesive.cohesive_newton import LAW_WEIGHT

RESIDUAL_MARGIN = 2.0
"""The complementarity term of the returned fields may exceed ``tol`` by this factor: Polonsky-Keer's returned state
measured up to 1.19 times the residual it reported (its last projection moves the gap after the residual is taken)."""

POINTWISE_GAP = 1000.0
"""The largest interpenetration of one point, in ``tol`` rms heights. The residual bounds the mean interpenetration
by ``tol`` rms heights (a single point's by ``n tol``, which means nothing on a large grid); at convergence the
largest one measured at most 5.9 ``tol`` on cold solves (0.5-3.8 on rough surfaces and spheres, 5.9 on a thin
remote-pressure layer) and 264 ``tol`` on the warm-started steps of a time series (64^2 rough surface and sphere,
creep under constant load, tol 1e-8 and 1e-6)."""

ROUND_OFF = 1e-12
"""The floor of every relative bound: double-precision sums over up to 10^8 points."""

ENERGY_BALANCE_FACTOR = 1.0
"""Steady frictionless viscoelastic sliding: the friction power ``mu_a mean(p) |V|`` and the ``dissipated_power``
may differ by this many ``tol`` of ``mean(p) |V| s_rms`` (``s_rms`` the rms slope of the heights along the sliding
direction, the scale of ``mu_a``). With ``mu_a`` taken from the deformed surface (the returned displacement) the two
are the same sum over the spectrum of the pressure, so they agree to round-off where the displacement is the body's
response to the pressure: measured at most 2.5e-15 (relative to the dissipated power 1.3e-14) over self-affine
surfaces (H = 0.8, rms slope 0.1; 2D 128^2 and 256^2 at 4 and 16 points per shortest wavelength, 1D 1024 points;
standard linear solids E_inf/E0 = 10 and 1000, V tau q0 = 1e-3, 0.05 and 1; 0-42 % contact; tol 1e-8 and 1e-5).
The check is then the one that the displacement returned is the compliance applied to the pressure. (With ``mu_a``
from the rigid heights' finite differences, before, they differed by up to 0.125 of that scale, and by 15 % of the
dissipated power in 2D at 4 points per wavelength.)"""

RELAXED_MEMORY = 1e-4
"""A time series that ends holding a constant load (or penetration) at rest is checked against the relaxed elastic
solve where the memory left by the steps of the hold (:func:`relaxed_hold`) is at most this fraction of the creep:
about 9 retardation times of a standard linear solid in steps much shorter than them, 15-40 in log-spaced steps."""

RELAXED_MARGIN = 1000.0
"""The relaxed-limit check allows the end state to differ from the relaxed solve by this many ``tol`` (rms heights of
penetration, or relative mean pressure) beyond the memory left: each step's solve is exact only to ``tol``, and the
penetration (or load) error is that of the gap at the contact edge. Measured at most 88 ``tol`` (a 64^2 sphere held at
a penetration, tol 1e-6; 5 on a rough surface) where the memory left was negligible."""


@dataclass(frozen=True)
class Check:
    """One invariant's verdict: ``violation`` (scale-free, NaN where the result held a NaN) within ``bound``.

    Parameters
    ----------
    invariant : str
        Its name.
    violation : float
        The measured violation (scale-free; NaN where the result held a NaN).
    bound : float
        The bound it must stay within.
    measure : str
        How the violation is measured, for the message.
    """

    invariant: str
    violation: float
    bound: float
    measure: str
    """What ``violation`` is, for the message (e.g. ``"|mean_pressure - asked| / asked"``)."""

    @property
    def passed(self) -> bool:
        return bool(self.violation <= self.bound)  # NaN fails


class InvariantError(ConvergenceError):
    """A result broke an invariant: it is not returned as converged.


    Parameters
    ----------
    message : str
        The invariant, by how much it failed and the bound.
    invariant : str
        The invariant's name.
    violation, bound : float
        By how much it failed, and the bound it broke.
    dataset : xarray.Dataset, optional
        The labelled state.

    Attributes
    ----------
    invariant : str
        The invariant's name (``"load"``, ``"sign"``, ``"gap"``, ``"complementarity"``, ...).
    violation, bound : float
        By how much it failed (scale-free: the check's ``measure``), and what it must stay within.
    residual : float
        The violation (as :class:`ConvergenceError`'s residual).
    dataset : xarray.Dataset or None
        The labelled result, ``attrs['converged'] = 0`` and ``attrs['convergence_message']`` saying why.
    """

    def __init__(self, message: str, *, invariant: str, violation: float, bound: float, dataset=None):
        super().__init__(message, residual=violation, dataset=dataset)
        self.invariant, self.violation, self.bound = invariant, violation, bound


@dataclass(frozen=True)
class FieldMeasures:
    """The sums and extremes of one state's fields that the contact invariants need (:func:`field_measures`)."""

    mean_pressure: float
    min_pressure: float
    complementarity: float
    """``mean(p |g|)``."""
    min_gap: float
    height_rms: float
    gap_definition: float
    """``max |g - (u + max(h) - h - d)|``."""
    round_off: float
    """The size of the numbers in that identity, ``max |u| + max |h| + |d|``."""


@vector_jit
def _sweep(p, g, u, h, d):
    """One pass over the fields: ``(sum p, min p, sum p|g|, min g, sum dh, sum dh^2, max h, min k, max k, sum k, max
    |u|, max |h|)`` with ``dh = h - h[0]`` and ``k = g - u + h``, which is ``max(h) - d`` everywhere."""
    n = p.size
    psum, comp, hs, hs2, ksum = 0.0, 0.0, 0.0, 0.0, 0.0
    pmin, gmin, kmin = np.inf, np.inf, np.inf
    hmax, kmax, umax, habs = -np.inf, -np.inf, 0.0, 0.0
    h0 = h[0]
    for i in range(n):
        pi, gi, hi, ui = p[i], g[i], h[i], u[i]
        psum += pi
        comp += pi * abs(gi)
        pmin = min(pmin, pi)
        gmin = min(gmin, gi)
        dh = hi - h0
        hs += dh
        hs2 += dh * dh
        hmax = max(hmax, hi)
        k = gi - ui + hi
        ksum += k
        kmin = min(kmin, k)
        kmax = max(kmax, k)
        umax = max(umax, abs(ui))
        habs = max(habs, abs(hi))
    return psum, pmin, comp, gmin, hs, hs2, hmax, kmin, kmax, ksum, umax, habs


def field_measures(pressure, gap, displacement, heights, penetration: float) -> FieldMeasures:
    """The measures of a state on ``heights`` in one fused pass (arrays of one shape; ``gap = displacement +
    max(heights) - heights - penetration`` is what the solvers return)."""
    flat = [np.ascontiguousarray(a, dtype=float).reshape(-1) for a in (pressure, gap, displacement, heights)]
    n = flat[0].size
    psum, pmin, comp, gmin, hs, hs2, hmax, kmin, kmax, ksum, umax, habs = _sweep(*flat, float(penetration))
    variance = max(hs2 / n - (hs / n) ** 2, 0.0)
    rms = math.sqrt(variance) if variance > 0 else 1.0  # as contactlib.solvers.state.height_scale
    target = hmax - float(penetration)
    definition = max(abs(kmax - target), abs(kmin - target)) if math.isfinite(ksum) else math.nan
    return FieldMeasures(mean_pressure=psum / n, min_pressure=pmin if math.isfinite(psum) else math.nan,
                         complementarity=comp / n, min_gap=gmin if math.isfinite(comp) else math.nan, height_rms=rms,
                         gap_definition=definition, round_off=umax + habs + abs(float(penetration)))


# ---- the checks: pure functions of numbers ----------------------------------------------------------------------

def _floor(bound: float) -> float:
    return max(bound, ROUND_OFF)


def check_load(mean_pressure: float, asked: float, *, tol: float, scale: float) -> Check:
    """The mean pressure asked, to ``tol`` of ``scale`` (the asked load; an adhesive law's ``sigma_0 + |P|``).

    Parameters
    ----------
    mean_pressure : float
        The answer's mean pressure.
    asked : float
        The mean pressure asked.
    tol : float
        The tolerance the answer was solved to.
    scale : float
        The load scale.

    Returns
    -------
    Check
        The verdict.
    """
    return Check("load", abs(mean_pressure - asked) / scale if scale > 0 else abs(mean_pressure - asked), _floor(tol),
                 f"|mean_pressure - asked| / {scale:.6g} (asked {asked:.6g}, returned {mean_pressure:.6g})")


def check_penetration(penetration: float, asked: float, *, tol: float, height_rms: float) -> Check:
    """The penetration asked, to ``tol`` rms heights.

    Parameters
    ----------
    penetration : float
        The answer's approach [length].
    asked : float
        The approach asked [length].
    tol : float
        The tolerance the answer was solved to.
    height_rms : float
        The heights' rms [length].

    Returns
    -------
    Check
        The verdict.
    """
    return Check("penetration", abs(penetration - asked) / height_rms, _floor(tol),
                 f"|penetration - asked| / h_rms (asked {asked:.6g}, returned {penetration:.6g})")


def check_sign(measures: FieldMeasures, *, tol: float) -> Check:
    """``p >= 0`` without adhesion: a negative pressure within ``tol`` of the mean one (the solvers project exactly).

    Parameters
    ----------
    measures : FieldMeasures
        The fused pass's measures of the fields.
    tol : float
        The tolerance the answer was solved to.

    Returns
    -------
    Check
        The verdict.
    """
    scale = measures.mean_pressure if measures.mean_pressure > 0 else 1.0
    return Check("sign", max(-measures.min_pressure, 0.0) / scale if math.isfinite(measures.min_pressure) else math.nan,
                 _floor(tol), "max(-pressure) / mean_pressure")


def check_gap(min_gap: float, *, tol: float, height_rms: float) -> Check:
    """No interpenetration: the most negative gap within :data:`POINTWISE_GAP` ``tol`` rms heights.

    Parameters
    ----------
    min_gap : float
        The most negative gap [length].
    tol : float
        The tolerance the answer was solved to.
    height_rms : float
        The heights' rms [length].

    Returns
    -------
    Check
        The verdict.
    """
    return Check("gap", max(-min_gap, 0.0) / height_rms if math.isfinite(min_gap) else math.nan,
                 _floor(POINTWISE_GAP * tol), "max(-gap) / h_rms")


def check_complementarity(measures: FieldMeasures, *, tol: float) -> Check:
    """``p g = 0``: the residual's complementarity term ``mean(p |g|) / (mean(p) h_rms)`` within
    :data:`RESIDUAL_MARGIN` ``tol``.

    Parameters
    ----------
    measures : FieldMeasures
        The fused pass's measures of the fields.
    tol : float
        The tolerance the answer was solved to.

    Returns
    -------
    Check
        The verdict.
    """
    pbar = measures.mean_pressure
    value = measures.complementarity / (pbar * measures.height_rms) if pbar > 0 else 0.0
    return Check("complementarity", value if math.isfinite(pbar) else math.nan, _floor(RESIDUAL_MARGIN * tol),
                 "mean(pressure |gap|) / (mean_pressure h_rms)")


def check_gap_definition(measures: FieldMeasures, *, tol: float) -> Check:
    """The returned fields agree: ``gap = displacement + max(h) - h - penetration``, to ``tol`` rms heights (round-off
    of the numbers in it at least).

    Parameters
    ----------
    measures : FieldMeasures
        The fused pass's measures of the fields.
    tol : float
        The tolerance the answer was solved to.

    Returns
    -------
    Check
        The verdict.
    """
    floor = 1e3 * np.finfo(float).eps * measures.round_off / measures.height_rms
    return Check("gap_definition", measures.gap_definition / measures.height_rms, _floor(max(tol, floor)),
                 "max |gap - (displacement + max(h) - h - penetration)| / h_rms")


def check_closed_gap(gap_on_closed: float, *, tol: float, height_rms: float) -> Check:
    """Adhesion: the closed (repulsive) set is in contact, ``|gap| ~ 0`` there, to :data:`POINTWISE_GAP` ``tol`` rms
    heights (``gap_on_closed`` its largest magnitude, from the displacement).

    Parameters
    ----------
    gap_on_closed : float
        The largest gap magnitude on the closed set [length].
    tol : float
        The tolerance the answer was solved to.
    height_rms : float
        The heights' rms [length].

    Returns
    -------
    Check
        The verdict.
    """
    return Check("closed_gap", gap_on_closed / height_rms, _floor(POINTWISE_GAP * tol), "max |gap| on the closed set / "
                 "h_rms")


def check_tension(excess: float, *, tol: float, scale: float) -> Check:
    """Adhesion: tension only where the law allows it. ``excess`` is the tension beyond the law's, summed over the
    points (a cohesive law: beyond its traction at the point's gap, and on the open points short of it; JKR: any
    tension outside the closed set), and
    ``scale`` the tractions present; within :data:`RESIDUAL_MARGIN` ``tol`` (a cohesive law's ``tol`` is the
    solve's over ``LAW_WEIGHT``, as its residual's law term weighs it:
    :mod:`contactlib.solvers.adhesive.cohesive_newton`).

    Parameters
    ----------
    excess : float
        Tension beyond the law's, summed over the points.
    tol : float
        The tolerance the answer was solved to.
    scale : float
        The tractions present.

    Returns
    -------
    Check
        The verdict.
    """
    return Check("tension", excess / scale if scale > 0 else excess, _floor(RESIDUAL_MARGIN * tol),
                 "sum of the tension beyond the law / sum |pressure|")


def check_energy_balance(friction_power: float, dissipated_power: float, *, scale: float, tol: float) -> Check:
    """Steady sliding: the work of the friction force equals the power the body dissipates, within
    :data:`ENERGY_BALANCE_FACTOR` ``tol`` of ``scale`` (``mean(p) |V| s_rms``).

    Parameters
    ----------
    friction_power : float
        ``mu_a p_m V`` [pressure length/time].
    dissipated_power : float
        The body's dissipation [pressure length/time].
    scale : float
        ``mean(p) |V| s_rms``.
    tol : float
        The tolerance the answer was solved to.

    Returns
    -------
    Check
        The verdict.
    """
    return Check("energy_balance", abs(friction_power - dissipated_power) / scale if scale > 0 else 0.0,
                 _floor(ENERGY_BALANCE_FACTOR * tol),
                 "|mu_a mean_pressure |V| - dissipated_power| / (mean_pressure |V| rms_slope)")


def check_relaxed_limit(end: float, relaxed: float, *, tol: float, scale: float, memory_left: float) -> Check:
    """A long hold under a constant load ends at the relaxed elastic solve: ``|end - relaxed| / scale`` within
    :data:`RELAXED_MARGIN` ``tol`` plus the memory left (``memory_left`` times ``|relaxed| / scale``; the creep still to
    come is at most the relaxed response itself).

    Parameters
    ----------
    end : float
        The last step's load or approach.
    relaxed : float
        The relaxed elastic solve's.
    tol : float
        The tolerance the answer was solved to.
    scale : float
        Its scale.
    memory_left : float
        The fraction of the creep still to come (:func:`relaxed_hold`).

    Returns
    -------
    Check
        The verdict.
    """
    return Check("relaxed_limit", abs(end - relaxed) / scale,
                 _floor(RELAXED_MARGIN * tol + memory_left * abs(relaxed) / scale),
                 f"|end - relaxed| / {scale:.6g} (end {end:.8g}, relaxed {relaxed:.8g})")


# ---- running them --------------------------------------------------------------------------------------------------

def failure_message(check: Check, where: str) -> str:
    return (f"{where}: invariant '{check.invariant}' failed: {check.measure} = {check.violation:.3e} > "
            f"{check.bound:.3e}; the result is not returned as converged")


def verify(checks: list[Check], dataset=None, *, where: str) -> None:
    """Record the invariants checked in ``dataset.attrs['invariants_checked']`` (names, comma-separated) and raise
    :class:`InvariantError` on the first that failed (``dataset``, if given, then says so:
    ``attrs['converged'] = 0``, ``attrs['convergence_message']``).

    Parameters
    ----------
    checks : list of Check
        The verdicts.
    dataset : xarray.Dataset, optional
        The labelled answer, whose ``attrs`` record them.
    where : str
        The entry point's name, for the message.

    Raises
    ------
    InvariantError
        On the first invariant that failed, with the labelled state.
    """
    if dataset is not None:
        names = list(dict.fromkeys(c.invariant for c in checks))
        dataset.attrs["invariants_checked"] = ", ".join(names)
    for check in checks:
        if not check.passed:
            message = failure_message(check, where)
            if dataset is not None:
                dataset.attrs["converged"] = 0
                dataset.attrs["convergence_message"] = message
                dataset.attrs["invariant_failed"] = check.invariant
            raise InvariantError(message, invariant=check.invariant, violation=check.violation, bound=check.bound,
                                 dataset=dataset)


def contact_checks(state, heights: np.ndarray, *, tol: float, mean_pressure: float | None = None,
                   penetration: float | None = None) -> list[Check]:
    """The invariants of a non-adhesive contact state on ``heights``: the load or penetration asked (either given),
    ``p >= 0``, no interpenetration, complementarity and the gap's definition.

    Parameters
    ----------
    state : contactlib.solvers.ContactState
        The solved state.
    heights : ndarray
        The heights it was solved on [length].
    tol : float
        The tolerance the answer was solved to.
    mean_pressure, penetration : float or None
        The load or approach asked (one of them).

    Returns
    -------
    list of Check
        One verdict per invariant.
    """
    m = field_measures(state.pressure, state.gap, state.displacement, heights, state.penetration)
    checks = []
    if mean_pressure is not None:
        checks.append(check_load(state.mean_pressure, mean_pressure, tol=tol, scale=max(abs(mean_pressure), 1e-300)))
    if penetration is not None:
        checks.append(check_penetration(state.penetration, penetration, tol=tol, height_rms=m.height_rms))
    return checks + [check_sign(m, tol=tol), check_gap(m.min_gap, tol=tol, height_rms=m.height_rms),
                     check_complementarity(m, tol=tol), check_gap_definition(m, tol=tol)]


def adhesive_checks(state, heights: np.ndarray, adhesion, *, tol: float, mean_pressure: float | None = None,
                    penetration: float | None = None) -> list[Check]:
    """The invariants of an adhesive state (:class:`contactlib.problems.adhesive.AdhesiveState`): the load or
    penetration asked, no interpenetration, the closed set's gap ~0 (from the displacement: the energy method zeroes
    its returned gap there) and tension only where the law allows it. The load's scale is the cohesive residual's,
    ``sigma_0 + |P|`` (JKR: ``|P| + mean|p|``).

    Parameters
    ----------
    state : contactlib.solvers.ContactState
        The solved state.
    heights : ndarray
        The heights it was solved on [length].
    adhesion : contactlib.Adhesion
        The interface.
    tol : float
        The tolerance the answer was solved to.
    mean_pressure, penetration : float or None
        The load or approach asked (one of them).

    Returns
    -------
    list of Check
        One verdict per invariant.
    """
    m = field_measures(state.pressure, state.gap, state.displacement, heights, state.penetration)
    p = state.pressure
    closed = state.in_contact
    if getattr(state, "law", None) is not None:  # the cohesive law as solved on the grid (a regularised zone)
        adhesion = state.law
    kinematic = state.displacement + (float(np.max(heights)) - heights) - state.penetration  # the gap, closed set too
    on_closed = float(np.max(np.abs(kinematic[closed]))) if np.any(closed) else 0.0
    mean_abs = float(np.mean(np.abs(p)))
    if adhesion.cohesive:
        scale = adhesion.peak_stress + abs(mean_pressure if mean_pressure is not None else state.mean_pressure)
        # the tension beyond the law's at each point's gap (less the gap's own error), summed as the cohesive
        # residual's law term sums |phi|: over the tractions present, floored at sigma_0 a point within the range
        slack = POINTWISE_GAP * tol * m.height_rms
        beyond = np.maximum(adhesion.traction(np.maximum(state.gap - slack, 0.0)) - p, 0.0)
        # and on the open points, the tension short of the law's (a missing adhesive ring, compression off contact):
        # the same law term bounds it (phi = p_r off the closed set)
        open_points = state.gap > slack if closed is None else (state.gap > slack) & ~closed
        short = np.maximum(p - adhesion.traction(state.gap + slack), 0.0)[open_points]
        present = max(float(np.sum(np.abs(p))), adhesion.peak_stress * max(int(np.count_nonzero(
            adhesion.interacting(state.gap))), 1))
        tension = check_tension(float(np.sum(beyond)) + float(np.sum(short)), tol=tol / LAW_WEIGHT, scale=present)
    else:
        scale = abs(mean_pressure if mean_pressure is not None else state.mean_pressure) + mean_abs
        outside = float(np.sum(np.maximum(-p[~closed], 0.0))) if closed is not None else 0.0  # JKR: tension off contact
        tension = check_tension(outside, tol=tol, scale=max(float(np.sum(np.abs(p))), 1e-300))
    checks = []
    if mean_pressure is not None:
        checks.append(check_load(state.mean_pressure, mean_pressure, tol=tol, scale=scale))
    if penetration is not None:
        checks.append(check_penetration(state.penetration, penetration, tol=tol, height_rms=m.height_rms))
    return checks + [check_gap(m.min_gap, tol=tol, height_rms=m.height_rms),
                     check_closed_gap(on_closed, tol=tol, height_rms=m.height_rms),
                     tension]


def rms_slope_along(heights: np.ndarray, lengths, direction: float) -> float:
    """The rms of the heights' slope along ``direction`` [rad] by central differences on the periodic window (the
    scale of the interlocking friction)."""
    slope = np.zeros_like(heights, dtype=float)
    components = (math.cos(direction), math.sin(direction))[: heights.ndim]
    for axis, (c, length) in enumerate(zip(components, lengths)):
        if c != 0:
            spacing = length / heights.shape[axis]
            slope += c * (np.roll(heights, -1, axis) - np.roll(heights, 1, axis)) / (2 * spacing)
    return float(np.sqrt(np.mean(slope**2)))


def sliding_checks(ds, heights: np.ndarray, *, lengths, velocity, direction: float, tol: float) -> list[Check]:
    """Steady frictionless sliding: the energy balance (:func:`check_energy_balance`), with the measured balance put
    in ``ds.attrs``: ``energy_balance`` (relative to the dissipated power), ``energy_balance_scaled`` (the checked
    measure) and ``energy_balance_bound``.

    Parameters
    ----------
    ds : xarray.Dataset
        The labelled answer (its ``attrs`` get the balance).
    heights : ndarray
        The heights [length].
    lengths : sequence of float
        Window size per axis [length].
    velocity : sequence of float
        Sliding velocity [length/time].
    direction : float
        Sliding direction [rad].
    tol : float
        The tolerance the answer was solved to.

    Returns
    -------
    list of Check
        One verdict per invariant.
    """
    speed = math.hypot(*velocity)  # no overflow at 1e200
    pbar = float(ds["mean_pressure"])
    friction_power = float(ds["friction_coefficient_interlocking"]) * pbar * speed
    dissipated = float(ds["dissipated_power"])
    scale = pbar * speed * rms_slope_along(heights, lengths, direction)
    check = check_energy_balance(friction_power, dissipated, scale=scale, tol=tol)
    ds.attrs["energy_balance"] = (friction_power - dissipated) / dissipated if dissipated != 0 else \
        (0.0 if friction_power == 0 else math.inf)
    ds.attrs["energy_balance_scaled"] = check.violation
    ds.attrs["energy_balance_bound"] = check.bound
    return [check]


def relaxed_hold(times: np.ndarray, loads: np.ndarray, positions: np.ndarray, material, control: str):
    """The memory left at the end of a time series that ends in a hold (the load, or penetration by ``control``, and
    the position constant over its last steps), relative to the relaxed response: the fraction of the creep still to
    come (load control; the creep is at most the relaxed penetration), or the relaxation still to come over the
    relaxed load (penetration control, up to ``E_inf / E0 - 1`` at first); None where it is above
    :data:`RELAXED_MEMORY` (too short a hold for :func:`check_relaxed_limit`) or the body has no memory.

    The fraction is the time stepping's own, step by step: at a fixed displacement a branch decays by ``a =
    exp(-dt / tau)`` exactly; under a constant load the creep of a standard linear solid decays by ``(a + beta) / (1
    + beta)`` (``beta = (E_eff - E0) / E0``, the step's effective modulus), which tends to ``beta`` rather than 0 for
    long steps: log-spaced steps leave more memory than ``exp(-hold / lambda)``. Several branches take the slowest.

    Parameters
    ----------
    times : ndarray
        The instants [time].
    loads : ndarray
        The load or approach at each.
    positions : ndarray
        The rigid surface's position at each [length].
    material : contactlib.Viscoelastic or contactlib.Elastic
        The body.
    control : {"mean_pressure", "penetration"}
        What ``loads`` holds.

    Returns
    -------
    float or None
        The memory left, None where the series does not end in a hold.
    """
    branches = getattr(material, "prony", ())
    if not branches:
        return None
    still = (loads == loads[-1]) & np.all(positions == positions[-1], axis=1)
    start = len(still) - int(np.argmin(still[::-1])) if not np.all(still) else 0  # first of the final run
    moduli = np.array([E for E, _ in branches])
    taus = np.array([tau for _, tau in branches])
    left = 1.0
    for dt in np.diff(times[start:]):
        a = np.exp(-dt / taus)
        if control == "mean_pressure":
            beta = float(np.sum(-taus * np.expm1(-dt / taus) / dt * moduli)) / float(material.E0)
            left *= float(np.max((a + beta) / (1 + beta)))
        else:
            left *= float(np.max(a))
    if control != "mean_pressure":  # the relaxation still to come, relative to the relaxed load: up to E_inf / E0 - 1
        left *= float(np.sum(moduli)) / float(material.E0)
    return left if left <= RELAXED_MEMORY else None


def step_invariants(control: str) -> str:
    """``attrs['invariants_checked']`` of a time series whose steps :func:`contact_checks` checks.

    Parameters
    ----------
    control : {"mean_pressure", "penetration"}
        The series' control.

    Returns
    -------
    str
        The names, comma-separated.
    """
    return f"{'load' if control == 'mean_pressure' else 'penetration'}, sign, gap, complementarity, gap_definition " \
           "(every step)"

def verify_two_scale(ds, heights, *, scale: str, tol: float, macro_tol: float, mean_pressure: float | None,
                     penetration: float | None) -> None:
    """:func:`contactlib.two_scale.solve`'s invariants of its labelled answer ``ds``: the load asked (to ``macro_tol``
    for ``scale="macro"``, whose Newton residual bounds it, else to ``tol``, the outer tolerance: the sweeps hold
    the total force), the penetration asked, every asperity force ``>= 0`` and, with the two-scale fields, ``p >=
    0``, no interpenetration and complementarity as :func:`contact_checks` (the macro scale's fields are Hertz's
    pressures, not a contact solution: not checked).

    Parameters
    ----------
    ds : xarray.Dataset
        The labelled answer.
    heights : xarray.DataArray or None
        The heights, for the fields' checks.
    scale : {"two-scale", "macro"}
        The method that ran.
    tol, macro_tol : float
        Its tolerances.
    mean_pressure, penetration : float or None
        The load or approach asked (one of them).

    Raises
    ------
    InvariantError
        On the first invariant that failed, with the labelled state.
    """
    load_tol = macro_tol if scale == "macro" else tol
    checks = []
    if mean_pressure is not None:
        checks.append(check_load(float(ds["mean_pressure"]), mean_pressure, tol=load_tol,
                                 scale=max(abs(mean_pressure), 1e-300)))
    forces = ds["force"].values
    largest = float(np.max(np.abs(forces), initial=0.0)) or 1.0
    checks.append(Check("sign", max(-float(np.min(forces, initial=0.0)), 0.0) / largest, _floor(load_tol),
                        "max(-asperity force) / largest force"))
    if scale != "macro" and "pressure" in ds and heights is not None:
        m = field_measures(*(in_solver_axes(ds[k]).values for k in ("pressure", "gap", "displacement")), heights,
                           float(ds["penetration"]))  # by name: [ix, iy] as the heights
        if penetration is not None:
            checks.append(check_penetration(float(ds["penetration"]), penetration, tol=tol, height_rms=m.height_rms))
        checks += [check_sign(m, tol=tol), check_gap(m.min_gap, tol=tol, height_rms=m.height_rms),
                   check_complementarity(m, tol=tol)]
    verify(checks, ds, where=f"two_scale.solve (scale={scale!r})")


def verify_two_scale_series(ds, loads: np.ndarray, *, control: str, scale: str, tol: float, macro_tol: float) -> None:
    """:func:`contactlib.two_scale.solve_transient`'s invariants over its steps: under load control each step's mean
    pressure is the one asked (to ``macro_tol`` for ``scale="macro"``, else ``tol``, as :func:`verify_two_scale`);
    two-scale, every asperity force ``>= 0`` (the macro scale's per-asperity memory may pull a receding contact,
    which it warns of instead).

    Parameters
    ----------
    ds : xarray.Dataset
        The labelled time series.
    loads : ndarray
        The load or approach asked at each step.
    control : {"mean_pressure", "penetration"}
        What ``loads`` holds.
    scale : {"two-scale", "macro"}
        The method that ran.
    tol, macro_tol : float
        Its tolerances.

    Raises
    ------
    InvariantError
        On the first invariant that failed, with the labelled state.
    """
    load_tol = macro_tol if scale == "macro" else tol
    checks = []
    if control == "mean_pressure":
        asked = np.asarray(loads, dtype=float)[: ds.sizes["time"]]
        error = np.abs(ds["mean_pressure"].values - asked) / np.maximum(np.abs(asked), 1e-300)
        k = int(np.argmax(error))
        checks.append(check_load(float(ds["mean_pressure"].values[k]), float(asked[k]), tol=load_tol,
                                 scale=max(abs(float(asked[k])), 1e-300)))
    if scale != "macro":
        forces = ds["force"].values
        largest = float(np.max(np.abs(forces), initial=0.0)) or 1.0
        checks.append(Check("sign", max(-float(np.min(forces, initial=0.0)), 0.0) / largest, _floor(load_tol),
                            "max(-asperity force) / largest force"))
    verify(checks, ds, where=f"two_scale.solve_transient (scale={scale!r})")


PATH_SCALARS = ("pull_off_pressure", "pull_off_penetration", "jump_in_penetration", "full_contact_penetration",
                "full_contact_pressure", "hysteresis_energy")


def verify_path(ds, path: np.ndarray, heights: np.ndarray, adhesion, *, load_control: bool, tol: float) -> None:
    """:func:`contactlib.adhesion_curve`'s invariant over its states: each state returned as converged holds the load
    (or penetration) asked, to ``tol`` of the cohesive residual's load scale ``sigma_0 + |P|`` (JKR: ``|P|`` plus the
    path's largest ``|P|``) or of the rms height. A state that misses it is not returned as converged, as a failed
    step is not (the path never raises): ``converged`` 0 at that step, its scalars NaN, the path's scalars NaN,
    ``attrs['converged'] = 0`` and ``attrs['invariant_failures']`` naming the steps and by how much.

    Parameters
    ----------
    ds : xarray.Dataset
        The labelled path.
    path : ndarray
        The loads or approaches asked.
    heights : ndarray
        The heights [length].
    adhesion : contactlib.Adhesion
        The interface.
    load_control : bool
        Whether ``path`` holds loads.
    tol : float
        The tolerance the answer was solved to.
    """
    name = "mean_pressure" if load_control else "penetration"
    asked = np.asarray(path, dtype=float)
    returned = ds[name].values.copy()
    if load_control:
        # the cohesive residual's load scale; JKR has no stress of its own: the path's largest load instead
        scale = (adhesion.peak_stress if adhesion.cohesive else float(np.max(np.abs(asked)))) + np.abs(asked)
        scale = np.where(scale > 0, scale, 1.0)
    else:
        scale = np.full(asked.shape, _height_rms(heights))
    error = np.abs(returned - asked) / scale
    claimed = ds["converged"].values == 1
    bad = claimed & ~(error <= _floor(tol))
    ds.attrs["invariants_checked"] = f"{'load' if load_control else 'penetration'}" + (
        ", gap, closed_gap, tension" if adhesion.cohesive else "") + " (each state)"
    if not bad.any():
        return
    steps = np.flatnonzero(bad)
    worst = int(steps[np.argmax(error[steps])])
    ds["converged"].values[steps] = 0
    for key in ("penetration", "mean_pressure", "contact_area", "interaction_area"):
        ds[key].values[steps] = math.nan
    ds[name].values[steps] = asked[steps]  # the asked value stays, as on a failed step
    for key in PATH_SCALARS:
        if key in ds:
            ds[key] = ((), math.nan, ds[key].attrs)
    message = (f"adhesion_curve: invariant '{'load' if load_control else 'penetration'}' failed at steps "
               f"{steps.tolist()[:10]}: |{name} - asked| / scale up to {error[worst]:.3e} > {_floor(tol):.3e} (step "
               f"{worst}: asked {asked[worst]:.6g}, returned {returned[worst]:.6g}); those states are not converged "
               "and the path's scalars are NaN")
    ds.attrs.update(converged=0, convergence_message=message, invariant_failures=message)


def adhesive_state_holds(state, heights: np.ndarray, adhesion, *, tol: float, mean_pressure: float | None,
                         penetration: float | None) -> bool:
    """Whether a converged adhesive state of a path meets :func:`adhesive_checks`: one that does not is taken for an
    unconverged attempt (:func:`contactlib.adhesion_curve` tries its next start).

    Parameters
    ----------
    state : contactlib.solvers.ContactState
        The solved state.
    heights : ndarray
        The heights it was solved on [length].
    adhesion : contactlib.Adhesion
        The interface.
    tol : float
        The tolerance the answer was solved to.
    mean_pressure, penetration : float or None
        The load or approach asked (one of them).

    Returns
    -------
    bool
        True where every check holds.
    """
    return all(c.passed for c in adhesive_checks(state, heights, adhesion, tol=tol, mean_pressure=mean_pressure,
                                                 penetration=penetration))

def _height_rms(heights: np.ndarray) -> float:
    s = float(np.sqrt(np.mean((heights - heights.mean()) ** 2)))
    return s if s > 0 else 1.0

def with_dataset(err: ConvergenceError, message: str, dataset) -> ConvergenceError:
    """``err`` raised again by a time series with its steps so far (``dataset``): an :class:`InvariantError` stays
    one, and its ``dataset`` says so as :func:`verify`'s does (``attrs['converged'] = 0``, the message).

    Parameters
    ----------
    err : ConvergenceError
        The error raised by a step.
    message : str
        The series' status.
    dataset : xarray.Dataset
        The steps so far.

    Returns
    -------
    ConvergenceError
        An error of ``err``'s class carrying ``dataset``.
    """
    if isinstance(err, InvariantError):
        dataset.attrs.update(converged=0, convergence_message=message, invariant_failed=err.invariant)
        return InvariantError(message, invariant=err.invariant, violation=err.violation, bound=err.bound,
                              dataset=dataset)
    return ConvergenceError(message, residual=err.residual, dataset=dataset)


def verify_solve(setup, state, ds) -> None:
    """:func:`contactlib.solve`'s invariants of a converged ``state`` of ``setup`` (a :class:`contactlib.Problem`
    with its load), labelled as ``ds`` (its ``attrs['tol']`` the tolerance reached): :func:`contact_checks` or, with
    adhesion, :func:`adhesive_checks`; steady frictionless sliding adds the energy balance.

    Parameters
    ----------
    setup : contactlib.Problem
        The validated problem, with its load.
    state : contactlib.solvers.ContactState
        Its converged state.
    ds : xarray.Dataset
        The labelled answer.

    Raises
    ------
    InvariantError
        On the first invariant that failed, with the labelled state.
    """
    args, tol = setup.solver_args, float(ds.attrs["tol"])
    asked = {"mean_pressure": args["mean_pressure"], "penetration": args["penetration"]}
    if setup.adhesion is not None:
        checks = adhesive_checks(state, setup.values, setup.adhesion, tol=tol, **asked)
    else:
        checks = contact_checks(state, setup.values, tol=tol, **asked)
    velocity = setup.attrs.get("sliding_velocity")
    if velocity is not None and setup.attrs["friction"] == 0 and "dissipated_power" in ds:
        checks += sliding_checks(ds, setup.values, lengths=setup.grid.lengths, velocity=velocity,
                                 direction=setup.attrs["sliding_direction"], tol=tol)
    verify(checks, ds, where="solve")


__all__ = ["InvariantError", "Check", "verify", "contact_checks", "adhesive_checks", "sliding_checks",
           "check_load", "check_penetration", "check_sign", "check_gap", "check_complementarity",
           "check_gap_definition", "check_closed_gap", "check_tension", "check_energy_balance", "check_relaxed_limit",
           "relaxed_hold", "verify_solve", "verify_two_scale", "verify_two_scale_series", "verify_path",
           "adhesive_state_holds", "with_dataset", "step_invariants"]
