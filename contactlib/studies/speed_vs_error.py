"""The ``speed_vs_error`` study: errors and wall time of the solver on four scenes with a known answer
(``hertz``, ``westergaard_1d``, ``wavy_2d``, ``rough``), over grid size, tolerance and kernel.

Its points share one task per scene and ``n`` (``group_dims``): the rough reference
(:func:`rough_reference`) and the one solve of every tolerance (``tol_ladder``) are cached in the
task's process.
"""

from __future__ import annotations

import functools
import math

import numpy as np
import xarray as xr

from .. import surfaces
from ..analysis import convergence
from ..core.inputs import solver_values
from ..problems.contact import ConvergenceError, solve, solve_tolerances
from ..model.materials import contact_modulus
from ..reference import hertz, westergaard

VARIABLES: dict[str, dict[str, str]] = {
    "scene": {"units": "1", "long_name": "test scene (hertz, westergaard_1d, wavy_2d, rough)"},
    "load_error": {"units": "1", "long_name": "relative error of the total load"},
    "area_error": {"units": "1", "long_name": "relative error of the contact area"},
    "pressure_error": {"units": "1", "long_name": "relative L2 error of the pressure field"},
    "gap_error": {"units": "1", "long_name": "relative error of the mean gap (mean-plane separation)"},
    "max_error": {"units": "1", "long_name": "largest relative error of the scene's defined quantities"},
    "solve_time": {"units": "s", "long_name": "wall-clock time of contactlib.solve alone"},
    "reference_residual": {"units": "1", "long_name": "residual reached by the rough reference solve"},
    "resolution": {"units": "1", "long_name": "grid points per characteristic length (rough: per shortest wavelength)"},
}
"""Labels of the study's own names (the shared ones are in :data:`contactlib.studies._common.COMMON_VARIABLES`)."""

SCENES = ("hertz", "westergaard_1d", "wavy_2d", "rough")
"""Scenes of :func:`speed_error_point`; all but ``westergaard_1d`` are 2D."""


def _timed_solves(h, tols, **kw) -> list[xr.Dataset]:
    """:func:`solve_tolerances` at ``tols``, after an untimed one-iteration solve has built (and
    cached) the kernel and planned the FFTs of this grid: ``attrs['wall_time']`` is the solve, not the
    set-up. Unreached tolerances come back with ``attrs['converged'] = 0``."""
    try:
        solve(h, **{**kw, "max_iter": 1, "tol": 0.5})
    except ConvergenceError:
        pass
    try:
        return solve_tolerances(h, tols, **kw)
    except ConvergenceError as err:
        return err.datasets


def _l2(p, exact) -> float:
    """Relative l2 distance of a pressure (a DataArray read by name, ``[ix, iy]``) from ``exact`` (``[ix, iy]``)."""
    return float(np.linalg.norm(solver_values(p, "pressure") - exact) / np.linalg.norm(exact))


def _rel(value, exact) -> float:
    return abs(float(value) / float(exact) - 1.0)


def rough_master(*, hurst: float, seed: int, q_low: float, q_roll: float, q_cutoff: float, rms_slope: float):
    """The one continuous surface of the ``rough`` scene: synthesised on the smallest power-of-two grid
    with ``n >= 4 q_cutoff``; every resolution samples its trigonometric interpolant
    (:func:`contactlib.surfaces.resample`), so all grids resolve the same modes."""
    n0 = 2 ** math.ceil(math.log2(4 * q_cutoff))
    return surfaces.self_affine(n0, length=1.0, hurst=hurst, q_low=q_low, q_roll=q_roll, q_cutoff=q_cutoff,
                                rms_slope=rms_slope, seed=seed)


REFERENCE_FLOOR = 1000.0
"""A rough reference whose residual stalls within this factor of its tolerance is accepted: the
round-off floor of the residual grows with the grid (1.2e-12 on 2048^2, above 1e-11 on 8192^2), and a
reference at 1e-9 is still far below the 1e-6 and larger errors it measures (``reference_residual``
records what each reached)."""
REFERENCE_MAX_ITER = 120
"""Iteration bound of the rough reference solve (it converges in 30-50 iterations when it can)."""


@functools.lru_cache(maxsize=4)
def rough_reference(*, n: int, factor: int, tol: float, hurst: float, seed: int, q_low: float, q_roll: float,
                    q_cutoff: float, rms_slope: float, reduced_pressure: float, E: float, nu: float,
                    max_iter: int) -> dict:
    """Reference of the ``rough`` scene at ``n``: the same surface on a ``factor`` x finer grid, spectral
    kernel, ``tol``; cached per process (the points of one task share it). The fine pressure is
    restricted (injected) onto the coarse nodes, which coincide with every ``factor``-th fine node.

    ``tol = 1e-12`` sits at the round-off floor of the residual on large grids (it stalls near
    1.2e-12 on 2048^2): the reference is accepted, unconverged, once its residual is within
    ``REFERENCE_FLOOR * tol``, after ``max_iter`` iterations (:data:`REFERENCE_MAX_ITER` in the study).
    A reference short of that is returned with ``failed`` set (cached like a success, so the
    points of a task do not each solve it again) and its points report it as not converged."""
    master = rough_master(hurst=hurst, seed=seed, q_low=q_low, q_roll=q_roll, q_cutoff=q_cutoff, rms_slope=rms_slope)
    fine = surfaces.resample(master, factor * n)
    load = reduced_pressure * contact_modulus(E, nu) * rms_slope
    try:
        out = solve(fine, E=E, nu=nu, mean_pressure=load, tol=tol, max_iter=max_iter, kernel="spectral")
    except ConvergenceError as err:  # round-off floor: ~1e-12 is not always reachable on 2048^2 and up
        if not err.residual <= REFERENCE_FLOOR * tol:
            return {"failed": f"rough reference on {factor * n}^2: {err}", "residual": float(err.residual)}
        out = err.dataset
    return {"contact_area": float(out.contact_area), "mean_gap": float(out.gap.mean()),
            "pressure": solver_values(out.pressure, "pressure")[::factor, ::factor].copy(),  # [ix, iy]
            "residual": float(out.residual),
            "failed": ""}


def speed_error_point(*, scene: str, n: int, tol: float, kernel: str, E: float, nu: float, max_iter: int,
                      radius: float, contact_fraction: float, amplitude: float, full_contact_margin: float,
                      hurst: float, seed: int, q_low: float, q_roll: float, q_cutoff: float, rms_slope: float,
                      reduced_pressure: float, n_max_2d: int, n_max_rough: int, reference_factor: int = 4,
                      reference_tol: float = 1e-12, tol_ladder: tuple | list | None = None) -> dict:
    """Errors and wall time of one solve of a scene with a known answer, at grid ``n``, ``tol``, ``kernel``.

    Scenes (window L = 1; relative errors; NaN where a quantity is prescribed or undefined):

    * ``hertz``: sphere of ``radius`` on a non-periodic window under displacement control at the Hertz
      approach ``a^2/R`` of contact radius ``a = contact_fraction L / 4``: errors of the total load, the
      contact area (against ``pi a^2``) and the pressure field, all against Hertz.
    * ``westergaard_1d``: profile ``amplitude cos(2 pi x)`` in partial contact, load control at the
      Westergaard mean pressure of contact fraction ``contact_fraction``: contact fraction and pressure
      field against :mod:`contactlib.reference.westergaard`.
    * ``wavy_2d``: egg-box ``amplitude cos(2 pi x) cos(2 pi y)`` in full contact, load control at
      ``full_contact_margin`` times the full-contact threshold ``E* |q| amplitude / 2``: pressure field
      against :func:`contactlib.reference.westergaard.full_contact_field` (area is 1, load prescribed).
    * ``rough``: the self-affine surface of :func:`rough_master` (``hurst``, ``seed``, band edges,
      ``rms_slope``), load control at ``reduced_pressure * E* * rms_slope``, against
      :func:`rough_reference` (the same continuous surface on a ``reference_factor`` x finer grid,
      spectral kernel, ``reference_tol``): contact area, mean gap, and the pressure field against the
      fine pressure restricted to the coarse nodes (injection, not averaging).

    2D scenes refuse ``n > n_max_2d`` and ``rough`` refuses ``n > n_max_rough`` or ``n <= 2 q_cutoff``
    (``ValueError``: the sweep records status 2 and NaN), so one ``n`` axis serves 1D grids up to 65536
    and 2D grids up to a few thousand, and the 4x finer rough reference stays within memory.

    ``resolution`` is the number of grid points per characteristic length: the shortest wavelength
    ``L / q_cutoff`` (rough), the contact radius (hertz), the contact half-width (westergaard_1d), the
    wavelength (wavy_2d). Errors against it give the convergence orders of :mod:`contactlib.accuracy`.

    ``tol_ladder`` (every ``tol`` of the grid) makes one :func:`contactlib.solve_tolerances` run per
    scene, ``n`` and ``kernel`` serve all its tolerances (cached in the task's process): the iterates
    do not depend on ``tol``, so each point gets exactly the answer and iterations of its own solve,
    and ``solve_time`` the time that solve takes to reach it, at the cost of the tightest tolerance
    alone. Without it each point solves on its own.

    Returns
    -------
    dict
        ``load_error``, ``area_error``, ``pressure_error``, ``gap_error``, ``max_error`` (the largest
        defined one), ``solve_time`` (``contactlib.solve`` alone, kernel set-up excluded),
        ``iterations``, ``residual``, ``resolution``, ``reference_residual`` (rough only).
    """
    scene_args = {"scene": scene, "n": n, "kernel": kernel, "E": E, "nu": nu, "max_iter": max_iter,
                  "radius": radius, "contact_fraction": contact_fraction, "amplitude": amplitude,
                  "full_contact_margin": full_contact_margin, "hurst": hurst, "seed": seed, "q_low": q_low,
                  "q_roll": q_roll, "q_cutoff": q_cutoff, "rms_slope": rms_slope,
                  "reduced_pressure": reduced_pressure, "n_max_2d": n_max_2d, "n_max_rough": n_max_rough,
                  "reference_factor": reference_factor, "reference_tol": reference_tol}
    if tol_ladder is None:
        return _speed_error_results(tols=(tol,), **scene_args)[tol].result()
    if tol not in tol_ladder:
        raise ValueError(f"tol={tol!r} is not in tol_ladder={tuple(tol_ladder)}")
    return _speed_error_results(tols=tuple(sorted(tol_ladder)), **scene_args)[tol].result()


class _Outcome:
    """One point's result, or the convergence failure its own solve would raise (re-raised per point)."""

    def __init__(self, values: dict | None = None, error: ConvergenceError | None = None):
        self.values, self.error = values, error

    def result(self) -> dict:
        if self.error is not None:
            raise self.error
        return dict(self.values)


@functools.lru_cache(maxsize=2)
def _speed_error_results(*, tols: tuple, scene: str, n: int, kernel: str, E: float, nu: float, max_iter: int,
                         radius: float, contact_fraction: float, amplitude: float, full_contact_margin: float,
                         hurst: float, seed: int, q_low: float, q_roll: float, q_cutoff: float, rms_slope: float,
                         reduced_pressure: float, n_max_2d: int, n_max_rough: int, reference_factor: int,
                         reference_tol: float) -> dict:
    """tol -> :class:`_Outcome` of the scene at ``n`` and ``kernel``, all ``tols`` from one solve."""
    if scene not in SCENES:
        raise ValueError(f"scene must be one of {SCENES}, got {scene!r}")
    if scene != "westergaard_1d" and n > n_max_2d:
        raise ValueError(f"n={n} is above n_max_2d={n_max_2d} for the 2D scene {scene!r}")
    if scene == "rough" and not 2 * q_cutoff < n <= n_max_rough:
        raise ValueError(f"rough: n={n} outside (2 q_cutoff, n_max_rough] = ({2 * q_cutoff:g}, {n_max_rough}]")
    E_star = contact_modulus(E, nu)
    kw = {"E": E, "nu": nu, "max_iter": max_iter, "kernel": kernel}
    ref = None
    if scene == "hertz":
        a = contact_fraction / 4.0
        depth = a * a / radius
        h, load = surfaces.paraboloid(n, length=1.0, radius=radius), {"penetration": depth, "periodic": False}
        total = hertz.sphere_load(depth, radius=radius, E_star=E_star)
        x = h.x.values - 0.5
        exact = hertz.sphere_pressure(np.hypot(x[:, None], x[None, :]), load=total, radius=radius, E_star=E_star)

        def errors(out):
            return {"load_error": _rel(out.mean_pressure, total), "area_error": _rel(out.contact_area, math.pi * a * a),
                    "pressure_error": _l2(out.pressure, exact)}
    elif scene == "westergaard_1d":
        p_mean = float(westergaard.mean_pressure(contact_fraction, amplitude=amplitude, wavelength=1.0, E_star=E_star))
        h, load = surfaces.wavy(n, length=1.0, amplitude=amplitude, dim=1), {"mean_pressure": p_mean}
        exact = westergaard.partial_contact_pressure(h.x.values, mean_pressure=p_mean, amplitude=amplitude,
                                                     wavelength=1.0, E_star=E_star)

        def errors(out):
            return {"area_error": _rel(out.contact_area, contact_fraction), "pressure_error": _l2(out.pressure, exact)}
    elif scene == "wavy_2d":
        p_mean = full_contact_margin * westergaard.full_contact_pressure(amplitude=amplitude, wavelength=1.0,
                                                                         E_star=E_star, wavelength_y=1.0)
        h, load = surfaces.wavy(n, length=1.0, amplitude=amplitude, dim=2), {"mean_pressure": p_mean}
        x = h.x.values
        exact = westergaard.full_contact_field(x[:, None], x[None, :], mean_pressure=p_mean, amplitude=amplitude,
                                               wavelength=1.0, E_star=E_star)

        def errors(out):
            return {"pressure_error": _l2(out.pressure, exact)}
    else:
        spectrum = {"hurst": hurst, "seed": seed, "q_low": q_low, "q_roll": q_roll, "q_cutoff": q_cutoff,
                    "rms_slope": rms_slope}
        ref = rough_reference(n=n, factor=reference_factor, tol=reference_tol, reduced_pressure=reduced_pressure,
                              E=E, nu=nu, max_iter=min(max_iter, REFERENCE_MAX_ITER), **spectrum)
        if ref["failed"]:
            return {tol: _Outcome(error=ConvergenceError(ref["failed"], residual=ref["residual"], dataset=None))
                    for tol in tols}
        h = surfaces.resample(rough_master(**spectrum), n)
        load = {"mean_pressure": reduced_pressure * E_star * rms_slope}

        def errors(out):
            return {"area_error": _rel(out.contact_area, ref["contact_area"]),
                    "gap_error": _rel(out.gap.mean(), ref["mean_gap"]),
                    "pressure_error": _l2(out.pressure, ref["pressure"])}
    length = {"hertz": contact_fraction / 4, "westergaard_1d": contact_fraction / 2, "wavy_2d": 1.0,
              "rough": 1.0 / q_cutoff}[scene]
    outcomes = {}
    for tol, out in zip(tols, _timed_solves(h, tols, **kw, **load)):
        if out.attrs["converged"] != 1:
            outcomes[tol] = _Outcome(error=ConvergenceError(out.attrs["convergence_message"],
                                                            residual=float(out.residual), dataset=None))
            continue
        found = dict.fromkeys(convergence.QUANTITIES, math.nan)
        found.update(errors(out))
        outcomes[tol] = _Outcome({
            **found, "max_error": max(v for v in found.values() if not math.isnan(v)),
            "solve_time": float(out.attrs["wall_time"]), "iterations": float(out.iterations),
            "residual": float(out.residual), "resolution": n * length,
            "reference_residual": ref["residual"] if ref is not None else math.nan})
    return outcomes


def speed_error_shapes(grid: dict, constants: dict) -> list[tuple[int, ...]]:
    """FFT shapes of the speed_vs_error study (2D scenes up to ``n_max_2d``, padded for Hertz)."""
    shapes = []
    for n in grid["n"]:
        shapes.append((n,))
        if n <= constants["n_max_2d"]:
            shapes += [(n, n), (2 * n, 2 * n)]
        if 2 * constants["q_cutoff"] < n <= min(constants["n_max_2d"], constants["n_max_rough"]):
            shapes.append((constants.get("reference_factor", 4) * n,) * 2)
    return shapes


STUDY = {"point": speed_error_point, "fft_shapes": speed_error_shapes, "group_dims": ("kernel", "tol"),
         "ladder_dim": "tol"}
"""This study's entry of :data:`contactlib.studies.STUDIES`."""
