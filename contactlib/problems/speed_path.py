"""Steady sliding along a path of speeds: each speed's solve starts from a prediction of its pressure.

The pressure of a steady viscoelastic (or coupled) contact varies smoothly with the speed away from the
contact set's changes. The prediction (:func:`predict_pressure`) extrapolates the last three answers with a
geometric ratio of their changes (the secant through the last two in log speed where there are only two, or
they are unequally spaced), clipped at zero (which also predicts the contact set); on request the GMRES set solves
carry their Krylov vectors from speed to speed (:mod:`.solvers.recycle`). On a 256^2 rough surface, 30 speeds over
zeta = V tau q0 1e-3..1e3 (E_inf/E0 = 10, 10 % contact, tol 1e-8), GMRES iterations in all: 938 from the last
answer, 884 from the secant, 816 from the geometric prediction, 711 with the carried vectors too (and the held
set's known start image, :func:`.solvers.semismooth.solve_semismooth`); with the held and the last sets solved to
``tol / 2`` instead of ``tol / 16`` (:data:`.solvers.semismooth.HELD_FRACTION`), 839 from the last answer, 726
from the prediction, 661 with the carried vectors (1050 from the prediction at 512^2, 963 carried). In the
transition (zeta 3e-3..0.3) the pressure moves 30-40 % between neighbouring speeds (the patches shift and the
area falls from 9 % to 1.2 %), no prediction is within 25 % there, and each speed still takes 6-9 contact-set
updates and 28-47 iterations: that is where the iterations of a sweep go. Every solve reaches the tolerance asked
(a warm start changes the iterations, not the answer). Within :func:`solve_speeds` what does not depend on the
speed is built once: the path is one prepared problem (:func:`contactlib.prepare`) moved from speed to speed by
:meth:`contactlib.Problem.at_speed`, which keeps its caches (the half-space Green's tensor, and the carried Krylov
vectors); ``mu_a`` comes from each speed's own displacement.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import xarray as xr

from ..core.inputs import solver_values
from .problem import prepare
from ..resolution import recording, report, worst
from ..solvers.recycle import RecycledSpace
from ..solvers.state import dot


RATIO_MAX = 2.0
"""The largest ratio of successive changes :func:`predict_pressure` extrapolates with (the low-speed end grows
by about 1.4-1.6 per step of 0.2 decade, the high-speed end decays by 0.62)."""


def predict_pressure(speeds: Sequence[float], pressures: Sequence[np.ndarray], speed: float) -> np.ndarray | None:
    """The pressure [pressure] expected at ``speed`` from the answers ``pressures`` at ``speeds`` [length/time,
    magnitudes > 0], clipped at zero; the last answer when there is one answer, the last two speeds coincide (to
    1e-9 in ``log(speed)``) or the extrapolation overflows; None with none.

    With three answers equally spaced in ``log(speed)``, the changes between them are taken to grow or decay
    geometrically, by the least-squares ratio ``r = <d1, d2> / <d2, d2>`` (``d1`` the last change, ``d2`` the one
    before; clipped to ``[0, RATIO_MAX]``), and the prediction a step ``t`` (in that spacing) ahead is
    ``last + d1 r (1 - r^t) / (1 - r)``. Away from the transition the deviation from either elastic limit goes
    as a power of the speed (``(V tau q)^{+-1}`` for a standard linear solid), so the changes do shrink by a
    constant ratio: on a 256^2 sweep (30 speeds, zeta 1e-3..1e3) the start is 3-10x closer than the secant's
    at zeta >= 1 (relative errors 2e-2 -> 2e-5 against 4e-2 -> 1e-4). Otherwise the secant through the last
    two answers in ``log(speed)``.

    Parameters
    ----------
    speeds : sequence of float
        Speed magnitudes of the answers [length/time], > 0.
    pressures : sequence of ndarray
        The pressure fields solved at ``speeds`` [pressure].
    speed : float
        The speed to predict at [length/time], > 0.

    Returns
    -------
    ndarray or None
        The predicted pressure field, or None without answers.

    Raises
    ------
    ValueError
        Naming ``speeds`` (not one per answer, or not finite and > 0), ``pressures`` (NaN or infinite values) or
        ``speed``.
    """
    if not pressures:
        return None
    if len(speeds) < len(pressures):
        raise ValueError(f"speeds: one per answer in pressures, got {len(speeds)} speeds for {len(pressures)} answers")
    last = np.asarray(pressures[-1], dtype=float)
    if not all(np.all(np.isfinite(p)) for p in pressures[-3:]):
        raise ValueError("pressures: the answers to extrapolate contain NaN or infinite values")
    if len(pressures) < 2 or speeds[-1] == speeds[-2]:
        return last.copy()
    for value, name in [*((v, "speeds") for v in speeds[-3:]), (speed, "speed")]:
        if not (np.isfinite(value) and value > 0):
            raise ValueError(f"{name}: a speed magnitude must be finite and > 0 for the prediction, got {value!r}")
    logs = np.log(np.asarray(speeds[-3:], dtype=float))
    spacing = logs[-1] - logs[-2]
    if abs(spacing) <= 1e-9:  # speeds a round-off apart: their secant is noise over nothing (it overflowed to NaN)
        return last.copy()
    step = (np.log(speed) - logs[-1]) / spacing
    change = last - np.asarray(pressures[-2], dtype=float)
    if len(logs) == 3 and abs(logs[1] - logs[0] - spacing) <= 1e-6 * abs(spacing):
        before = (np.asarray(pressures[-2], dtype=float) - np.asarray(pressures[-3], dtype=float)).ravel()
        norm = dot(before, before)
        ratio = float(np.clip(dot(change.ravel(), before) / norm, 0.0, RATIO_MAX)) if norm > 0 else 1.0
        if abs(ratio - 1.0) > 1e-12:
            step = ratio * (1.0 - ratio**step) / (1.0 - ratio)
    predicted = np.maximum(last + step * change, 0.0)
    return predicted if np.all(np.isfinite(predicted)) else last.copy()  # a ratio's power can overflow far away


def solve_speeds(heights, sliding_velocities, *, recycle: bool | RecycledSpace = False, **kwargs) -> list[xr.Dataset]:
    """:func:`contactlib.solve` at each of ``sliding_velocities`` in the order given (walk them in increasing or
    decreasing speed), each from :func:`predict_pressure` of the answers before it.

    Parameters
    ----------
    heights
        As :func:`contactlib.solve`.
    sliding_velocities : sequence
        One ``sliding_velocity`` per solve [length/time] (a float in 1D, ``(Vx, Vy)`` in 2D), none zero.
    recycle : bool
        Carry the GMRES set solves' Krylov vectors from speed to speed (:mod:`contactlib.solvers.recycle`):
        the same answers, 8-10 % fewer GMRES iterations over a 30-speed sweep, but no less time at 512^2 (the
        correction's own cost eats the saving: 963 against 1050 iterations, 26.4x against 25.7x one elastic
        solve), hence off by default. A :class:`contactlib.solvers.recycle.RecycledSpace` given here is the one
        carried (its ``uses`` then count the set solves it corrected).
    **kwargs
        The other arguments of :func:`contactlib.solve` (``material``, ``mean_pressure``, ``tol``, ...), the
        same at every speed; not ``initial_pressure`` (the path supplies it). The scene is prepared once
        (:func:`contactlib.prepare`) and moved along the path (:meth:`contactlib.Problem.at_speed`).

    Returns
    -------
    list of xarray.Dataset
        One per velocity, in order. A solve that does not converge raises
        :class:`contactlib.ConvergenceError` as :func:`contactlib.solve` does.

    Raises
    ------
    ValueError
        Naming ``sliding_velocities`` (empty, not a sequence, a zero or non-finite velocity) or ``initial_pressure``
        (given: the path supplies it), and whatever :func:`contactlib.solve` refuses.
    ConvergenceError
        As :func:`contactlib.solve`; the answers before it are lost.
    """
    if "initial_pressure" in kwargs:
        raise ValueError("initial_pressure: solve_speeds predicts each speed's start itself; give none")
    if "sliding_velocity" in kwargs:
        raise ValueError("sliding_velocity: give the path as sliding_velocities")
    if isinstance(sliding_velocities, (str, bytes)) or not hasattr(sliding_velocities, "__iter__"):
        raise ValueError(f"sliding_velocities must be a sequence of velocities, got {sliding_velocities!r}")
    sliding_velocities = list(sliding_velocities)
    if not sliding_velocities:
        raise ValueError("sliding_velocities is empty: give at least one velocity")
    load = {k: kwargs.pop(k) for k in ("mean_pressure", "penetration") if k in kwargs}
    speeds, pressures, out, problem = [], [], [], None
    with recording() as seen:  # one resolution warning for the whole path, below
        for velocity in sliding_velocities:
            speed = float(np.linalg.norm(np.atleast_1d(np.asarray(velocity, dtype=float))))
            if not (np.isfinite(speed) and speed > 0):
                raise ValueError(f"sliding_velocities: each velocity must be finite and nonzero, got {velocity!r}")
            start = predict_pressure(speeds, pressures, speed) if kwargs.get("method", "cg") == "cg" else None
            if problem is None:
                problem = prepare(heights, sliding_velocity=velocity, **kwargs)
                if recycle is not False:
                    problem = problem.recycling(None if recycle is True else recycle)
            else:
                problem = problem.at_speed(velocity)
            ds = problem.solve(**load, initial_pressure=start)
            speeds.append(speed)
            pressures.append(solver_values(ds.pressure, "pressure"))  # [ix, iy], as the warm start reads a bare array
            out.append(ds)
    report([worst(seen)] if seen else [], where="solve_speeds", guarantee=kwargs.get("target_error") is not None)
    return out
