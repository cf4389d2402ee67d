"""Accuracy against cost: the measured resolution and tolerance rules that ``solve(..., target_error=)`` uses.

The ``speed_vs_error`` study (:func:`contactlib.studies.speed_error_point`, ``snakemake --cores 2``)
solves scenes with known answers over grid size, solver tolerance and kernel. Two rules follow from
it and are used here:

* **Resolution.** On a self-affine surface the contact area converges at first order in the grid
  spacing: ``error = C * ppw**-p`` with ``ppw = n / q_cutoff`` the grid points per shortest
  wavelength (:data:`ROUGH_FITS`, p = 1.0). So ``ppw = (C / target) ** (1 / p)``: about 120 points
  per shortest wavelength for 1 % on the contact area (61 without the safety factor 2).
* **Tolerance.** The residual of :func:`contactlib.solve` bounds how far the solution is from
  converged; the study gives the largest change of any error quantity that a tolerance causes
  (against the smallest tolerance on the same grid) as ``<= TOLERANCE_GAIN * tol``
  (:data:`TOLERANCE_GAIN`). So ``tol = target / (10 * TOLERANCE_GAIN)`` keeps the solver's share of
  the error below a tenth of the target.

:func:`settings_for` returns both, :func:`points_per_wavelength` and :func:`tolerance_for` each,
and ``contactlib.solve(..., target_error=...)`` uses them (it picks ``tol`` and warns with
:class:`AccuracyWarning` when the grid is coarser than the rule asks). Without ``target_error``, every entry point
still measures its resolution and warns where the fit predicts more than 1 % (:mod:`contactlib.resolution`). The
analysis of the study's dataset that gave the rules (orders of convergence, Pareto fronts, the cheapest settings) is
:mod:`contactlib.analysis.convergence`.
"""

from __future__ import annotations

import dataclasses
import math
import numbers
import warnings

import numpy as np
import xarray as xr

from .core import fft
from .core.grid import Grid
from .core.inputs import in_solver_axes
from .solvers.state import height_scale

REFERENCE_FACTOR = 4
"""The rough references of the study are this much finer: with ``error = C ppw**-p`` against the
continuum, the measured error against the reference is ``C (1 - 4**-p) ppw**-p``."""

SAFETY = 2.0
"""Factor on the fitted constants. The fit is one surface (seed 0, H = 0.8, q_cutoff 8, reduced
pressure 0.05); on six other surfaces (seeds 2, 3, 5, 7, 9, 11; H 0.3-0.8; q_cutoff 4-8; reduced
pressure 0.02-0.1) the contact-area error at the fitted resolution was up to 1.43x the fit (lower
loads, smaller contact patches, are worse). Validity: reduced pressure >= 0.02."""


def _fit(order: float, measured_constant: float) -> dict:
    return {"order": order, "measured_constant": measured_constant,
            "constant": SAFETY * measured_constant / (1 - REFERENCE_FACTOR**-order)}


ROUGH_FITS = {
    "contact_area": _fit(0.9954, 0.4558),
    "pressure": _fit(0.9722, 0.2657),
}
"""Measured ``error = constant * ppw**-order`` of the rough scene, spectral kernel, tol 1e-12.

Measurement: ``snakemake --cores 2 results/speed_vs_error_table.md`` (quick scale: self-affine surface,
H = 0.8, q_low 1, q_roll 2, q_cutoff 8, rms slope 0.1, seed 0, reduced pressure 0.05; n = 32-512, i.e.
4-64 points per shortest wavelength; reference 4x finer at tol 1e-12), 2026-11-21, contactlib 0.1.0.
Fitted (:func:`convergence_orders`): contact area order 0.995, constant 0.456; pressure (relative
L2) order 0.972, constant 0.266. ``constant`` is the measured one corrected for the 4x reference
(:data:`REFERENCE_FACTOR`) and multiplied by :data:`SAFETY`. The Love kernel measured 0.992 / 0.386
(area): slightly smaller errors at the same cost. Rerunning the study reproduces these numbers (wall
times aside) in ``results/speed_vs_error_table.md``. The paper scale (q_cutoff 16, 4-128 points per
shortest wavelength, 2026-11-22) measured area 0.97 / 0.243 and pressure 1.00 / 0.182: the same
orders, smaller constants, so the rule built on the quick fit is conservative there."""

TOLERANCE_GAIN = 166.0
"""Largest ``|error(tol) - error(1e-12)| / tol`` over every scene, grid, kernel, tolerance and error
quantity of the same quick-scale run (:func:`tolerance_gain`; 166 at tol 1e-4 on the Hertz contact
area, whose node count is the most sensitive to a loose tolerance; at most 65 for tol <= 1e-6).
At the paper scale the ratio reaches 3255, but only where one contact node flips at the edge of a
fine grid's contact (a jump of 1 / (contact nodes), not a drift in tol); there, wherever the
converged error ``E >= 10 * TOLERANCE_GAIN * tol``, the tolerance moved the error by at most 4.8 %
of ``E``, except where ``E`` itself was below one contact node."""



class AccuracyWarning(UserWarning):
    """The grid is coarser than the resolution rule asks for the requested ``target_error``."""


# --- the rule ------------------------------------------------------------------------------------


def points_per_wavelength(target_error: float, *, quantity: str = "contact_area") -> float:
    """Grid points per shortest wavelength for a relative error ``target_error`` of ``quantity``.

    ``quantity="contact_area"`` (the slowest to converge of the measured ones) or ``"pressure"``
    (relative L2 error of the pressure field). Uses the fits of :data:`ROUGH_FITS`.


    Parameters
    ----------
    target_error : float
        Relative error in (0, 1).
    quantity : {"contact_area", "pressure"}
        The error measured: contact area or the pressure field's relative L2 error.


    Returns
    -------
    float
        Grid points per shortest wavelength.


    Raises
    ------
    ValueError
        Naming ``quantity`` when it is not one of :data:`ROUGH_FITS`. Or ``target_error`` outside (0, 1).

    Examples
    --------
    >>> from contactlib import accuracy
    >>> accuracy.points_per_wavelength(0.1) < accuracy.points_per_wavelength(0.01)
    True
    """
    _check_target(target_error)
    if quantity not in ROUGH_FITS:
        raise ValueError(f"quantity must be one of {tuple(ROUGH_FITS)}, got {quantity!r}")
    fit = ROUGH_FITS[quantity]
    return float((fit["constant"] / target_error) ** (1.0 / fit["order"]))


def expected_error(points_per_wavelength, *, quantity: str = "contact_area", bound: bool = False):
    """Relative error the rule expects at a resolution (points per shortest wavelength).

    ``bound=False``: the fit against the continuum (the measured constant corrected for the 4x
    reference); ``bound=True``: with :data:`SAFETY`, the value :func:`points_per_wavelength` inverts.


    Parameters
    ----------
    points_per_wavelength : float or array_like
        Grid points per shortest wavelength.
    quantity : {"contact_area", "pressure"}
        The error measured: contact area or the pressure field's relative L2 error.
    bound : bool
        With the safety factor :data:`SAFETY`.


    Returns
    -------
    float or ndarray
        The expected relative error.


    Raises
    ------
    ValueError
        Naming ``quantity`` when it is not one of :data:`ROUGH_FITS`.

    Examples
    --------
    >>> from contactlib import accuracy
    >>> round(float(accuracy.expected_error(8.0)), 3)   # 8 points per shortest wavelength
    0.077
    """
    if quantity not in ROUGH_FITS:
        raise ValueError(f"quantity must be one of {tuple(ROUGH_FITS)}, got {quantity!r}")
    fit = ROUGH_FITS[quantity]
    constant = fit["constant"] if bound else fit["constant"] / SAFETY
    return constant * np.asarray(points_per_wavelength, dtype=float) ** -fit["order"]


def tolerance_for(target_error: float) -> float:
    """Solver tolerance whose share of the error stays below ``target_error / 10``:
    ``target_error / (10 * TOLERANCE_GAIN)``, at most 1e-4 (the loosest tolerance the study measured).

    Parameters
    ----------
    target_error : float
        Relative error in (0, 1).

    Returns
    -------
    float
        The solver tolerance.

    Raises
    ------
    ValueError
        Naming ``target_error`` outside (0, 1).

    Examples
    --------
    >>> from contactlib import accuracy
    >>> accuracy.tolerance_for(0.01) < 1e-5
    True
    """
    _check_target(target_error)
    return float(min(1e-4, target_error / (10.0 * TOLERANCE_GAIN)))


PENETRATION_RATIO = 2.34
"""The largest rms height over penetration among the scenes that measured :data:`TOLERANCE_GAIN`: the study's Hertz
sphere (contact radius 0.15 of the window, ``R`` = 1: rms height 0.0527 of the window's heights, approach 0.0225);
its rough scenes sit near 0.5. The residual measures gaps against the rms height, so where the approach is far below
it (a small contact in a wide window) the same tolerance leaves a larger error: a sphere under the approach 1e-3
on windows of 1, 4 and 8 radii (rms height over approach 53, 843, 3373) kept a pressure error of 1.2e-4, 3.1e-3 and
6.4e-3 at tol 1e-6."""


TIGHTEST_TOL = 1e-12
""":func:`tolerance_for_scene` tightens no further: the study's references were solved at this tol, and a solver's
residual stalls near 1e-14 (a flat punch pressed by 1e-12 of its rms height asked for 1.1e-16)."""


def tolerance_for_scene(tol: float, heights: np.ndarray, penetration: float) -> float:
    """:func:`tolerance_for`'s ``tol`` for a scene whose ``penetration`` [length] is below the rms of its ``heights``
    (the residual's scale, :func:`contactlib.solvers.state.height_scale`) over :data:`PENETRATION_RATIO`: ``tol`` times
    their ratio over it, no tighter than :data:`TIGHTEST_TOL`, so that the gaps the residual allows stay as small beside
    the approach as in the scenes the rule was measured on; ``tol`` itself otherwise.

    Parameters
    ----------
    tol : float
        The rule's tolerance (:func:`tolerance_for`).
    heights : ndarray
        The scene's heights [length].
    penetration : float
        The solved approach [length].

    Returns
    -------
    float
        The tolerance for this scene, at most ``tol``.
    """
    if not (math.isfinite(penetration) and penetration > 0):
        return tol
    ratio = height_scale(np.asarray(heights, dtype=float)) / penetration
    return tol if ratio <= PENETRATION_RATIO else max(tol * PENETRATION_RATIO / ratio, min(tol, TIGHTEST_TOL))


def solve_on_for_scene(setup, state):
    """``contactlib.solve(..., target_error=)``'s rule measured its tol where the approach is about the rms height;
    far below it, solve ``setup`` (the validated problem of :func:`contactlib.solve`) on from ``state`` to
    :func:`tolerance_for_scene`'s tighter tol, recorded in its attrs; the state reached (its iterations both solves').
    Where that solve does not converge, ``state`` stands, with an :class:`AccuracyWarning`.

    Parameters
    ----------
    setup : contactlib.Problem
        The validated problem of :func:`contactlib.solve`.
    state : contactlib.solvers.ContactState
        Its state at the rule's tolerance.

    Returns
    -------
    contactlib.solvers.ContactState
        The state at the tighter tolerance, or ``state``.

    Warns
    -----
    AccuracyWarning
        When the tighter tolerance is not reached.
    """
    tol = setup.solver_args["tol"]
    tighter = tolerance_for_scene(tol, setup.values, state.penetration)
    if not (tighter < tol and state.converged):
        return state
    setup.solver_args.update(tol=tighter, initial_pressure=state.pressure)  # the active-set method starts afresh
    try:
        finer = setup.run()
    except (RuntimeError, FloatingPointError):  # a solver's ConvergenceError among them
        finer = None
    if finer is None or not finer.converged:
        setup.solver_args["tol"] = tol
        warnings.warn(f"target_error: the approach {state.penetration:.3g} is far below the rms height, and the "
                      f"tighter tol {tighter:.2g} that asks was not reached: the answer is at the rule's tol {tol:.2g} "
                      "and may miss the target", AccuracyWarning, stacklevel=3)
        return state
    setup.attrs["tol"] = tighter
    return dataclasses.replace(finer, iterations=state.iterations + finer.iterations)


def settings_for(target_error: float, *, quantity: str = "contact_area", q_cutoff: float | None = None) -> dict:
    """Grid and tolerance for a self-affine surface and a target relative error.

    Parameters
    ----------
    target_error : float
        Relative error in (0, 1) of ``quantity``.
    quantity : {"contact_area", "pressure"}
    q_cutoff : float, optional
        Short-wavelength cutoff of the surface [2 pi / L]; gives ``n``, the smallest power of two with
        at least ``points_per_wavelength * q_cutoff`` points per side.

    Returns
    -------
    dict
        ``points_per_wavelength``, ``tol``, ``kernel`` and, with ``q_cutoff``, ``n``.


    Raises
    ------
    ValueError
        Naming ``target_error`` outside (0, 1), ``quantity`` or ``q_cutoff`` (not > 0).

    Examples
    --------
    >>> from contactlib import accuracy
    >>> s = accuracy.settings_for(0.05, q_cutoff=8)
    >>> s["n"] >= s["points_per_wavelength"] * 8
    True
    """
    ppw = points_per_wavelength(target_error, quantity=quantity)
    out = {"points_per_wavelength": ppw, "tol": tolerance_for(target_error), "kernel": "spectral"}
    if q_cutoff is not None:
        if not q_cutoff > 0:
            raise ValueError(f"q_cutoff must be > 0, got {q_cutoff!r}")
        out["n"] = int(2 ** math.ceil(math.log2(max(ppw * q_cutoff, 2 * q_cutoff + 1))))
    return out


def grid_points_per_wavelength(heights, *, length=None, floor: float = 1e-10) -> float:
    """Grid points per shortest wavelength present in a periodic surface.

    The shortest wavelength is ``2 pi / q_max``, with ``q_max`` the largest wavenumber carrying more
    than ``floor`` of the largest mode's power; it is divided by the coarser grid spacing. ``length``
    is the window size (default: a DataArray's coordinates, else 1). ``inf`` for a flat surface.


    Parameters
    ----------
    heights : xarray.DataArray or ndarray
        Periodic heights [length]: a DataArray's ``x`` and ``y`` read by name, a bare array indexed ``[ix, iy]``.
    length : float or tuple, optional
        Window size [length], required for a bare array.
    floor : float
        Power, relative to the largest mode's, below which a mode counts as absent.


    Returns
    -------
    float
        Grid points per shortest wavelength present.

    Examples
    --------
    >>> import contactlib
    >>> h = contactlib.surfaces.self_affine(64, hurst=0.8, q_roll=2, q_cutoff=8, rms_slope=0.1, seed=0)
    >>> contactlib.accuracy.grid_points_per_wavelength(h)
    8.0
    """
    heights = in_solver_axes(heights)  # a DataArray's x and y by name
    values = np.asarray(getattr(heights, "values", heights), dtype=float)
    if length is None and isinstance(heights, xr.DataArray):
        length = [float(heights[d][1] - heights[d][0]) * heights.sizes[d] for d in heights.dims]
    lengths = np.broadcast_to(np.asarray(1.0 if length is None else length, dtype=float), (values.ndim,))
    # an FFTW of its own, planned by estimate and dropped after use: pocketfft took 3x longer at 1024^2, a measured
    # plan 4.8 ms at 512^2 (2.6 % of a solve; estimate: 1.5 ms with the transform), sharing the solver's work plan
    # changed the round-off of concurrent threaded solves, and a cached one would hold a grid's memory between solves
    plan = fft.RealFFT(values.shape, 1, "FFTW_ESTIMATE")
    plan.real[...] = values
    spectrum = plan.forward()
    power = np.square(spectrum.real)
    power += np.square(spectrum.imag)
    del plan, spectrum
    power.flat[0] = 0.0  # the mean
    top = power.max()
    if top == 0:
        return math.inf
    # the largest |q|^2 over the modes above the floor, without a |q| field: per axis-0 row, |q_x|^2 + the row's
    # largest |q_y|^2 (its last index above the floor: |q_y| grows along the rfft axis)
    q = Grid(values.shape, tuple(float(L) for L in lengths)).wavevectors()  # [rad/length], broadcastable
    above = power > floor * top
    if values.ndim == 1:
        q2_max = float(np.max(q[0][above] ** 2))
    else:
        rows = np.flatnonzero(above.any(axis=1))
        last = above.shape[1] - 1 - np.argmax(above[rows, ::-1], axis=1)
        q2_max = float(np.max(q[0].ravel()[rows] ** 2 + q[1].ravel()[last] ** 2))
    q_max = math.sqrt(q2_max) / (2 * math.pi)  # cycles per length
    return float(1.0 / q_max / max(L / n for n, L in zip(values.shape, lengths)))


def check_resolution(heights, target_error: float, *, length=None, quantity: str = "contact_area") -> float:
    """Warn (:class:`AccuracyWarning`) if ``heights`` has fewer points per shortest wavelength than
    :func:`points_per_wavelength` asks for ``target_error``; returns the grid's points per wavelength.

    Parameters
    ----------
    heights : xarray.DataArray or ndarray
        Periodic heights [length].
    target_error : float
        Relative error in (0, 1).
    length : float or tuple, optional
        Window size [length], required for a bare array.
    quantity : {"contact_area", "pressure"}
        The error measured: contact area or the pressure field's relative L2 error.

    Returns
    -------
    float
        The grid's points per shortest wavelength.

    Warns
    -----
    AccuracyWarning
        When the grid is coarser than :func:`points_per_wavelength` asks.
    """
    have = grid_points_per_wavelength(heights, length=length)
    need = points_per_wavelength(target_error, quantity=quantity)
    if have < need:
        warnings.warn(
            f"target_error={target_error:g}: the grid has {have:.3g} points per shortest wavelength, the "
            f"measured rule asks for {need:.3g} ({quantity}); refine the surface (contactlib.surfaces.resample "
            f"or settings_for(..., q_cutoff=...)) or expect a larger error", AccuracyWarning, stacklevel=3)
    return have


def _check_target(target_error) -> None:
    if not (isinstance(target_error, numbers.Real) and 0 < target_error < 1):
        raise ValueError(f"target_error must lie in (0, 1), got {target_error!r}")
