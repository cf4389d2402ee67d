"""What :func:`contactlib.solve` does with ``adhesion=``: validate, run and label an adhesive scene.

Kept apart from :mod:`contactlib.contact`, which calls :func:`check`, :func:`run` and :func:`label` and
nothing else. The cohesive laws go to :func:`contactlib.solvers.cohesive.solve_cohesive` with the
scene's compliance (half-space or layer, periodic or zero-padded); ``"jkr"`` to the energy method of
:mod:`contactlib.solvers.energy` on the compliance matrix of the profile.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import xarray as xr

from .adhesion import Adhesion, scene_attrs
from .labels import attrs_for
from .solvers.cohesive import MAX_NEWTON, solve_cohesive
from .solvers.energy import MAX_POINTS, EnergyFamily, check_symmetric, energy_family, growth_order
from .solvers.state import ContactState, height_scale


DEFAULT_TOL = 1e-6
"""Default ``tol`` of an adhesive solve. The semi-smooth Newton meets 1e-8 on most states, but where a
grid point sits exactly at the contact edge (``p_r`` and ``g`` both ~0) its active set can flip between
two sets whose residuals are ~5e-8 (1D, 1024 points); 1e-6 of the rms height is far below any
resolution the grid has."""


@dataclass(frozen=True)
class AdhesiveState(ContactState):
    """A :class:`ContactState` with the repulsive part of the traction and the closed (contact) set."""

    repulsive_pressure: np.ndarray | None = None
    in_contact: np.ndarray | None = None
    notes: tuple = ()


def check(adhesion, values: np.ndarray, *, spacing, mean_pressure, penetration, friction, method, periodic) -> None:
    """Refuse, naming the parameter, what the adhesive solvers do not model."""
    if not isinstance(adhesion, Adhesion):
        raise ValueError(f"adhesion must be a contactlib.Adhesion or None, got {adhesion!r}")
    if (mean_pressure is None) == (penetration is None):
        raise ValueError("give exactly one of mean_pressure or penetration")
    for name, v in (("mean_pressure", mean_pressure), ("penetration", penetration)):
        if v is not None and not math.isfinite(v):
            raise ValueError(f"{name} must be finite, got {v!r}")
    if friction:
        raise ValueError("friction: adhesion is modelled frictionless (friction=0)")
    if mean_pressure is not None and adhesion.cohesive and mean_pressure < -adhesion.peak_stress:
        # the tension of a point is at most sigma_0 (at any gap): so is the window's mean
        raise ValueError(f"mean_pressure {mean_pressure!r}: a tension beyond the cohesive law's peak stress sigma_0 = "
                         f"work / range = {adhesion.peak_stress:.4g} over the whole window, which no state carries "
                         "(the pull-off is smaller still; contactlib.adhesion_curve finds it)")
    if method != "cg":
        raise ValueError("method: adhesion is solved by its own solvers (method='cg')")
    if adhesion.model == "jkr":
        check_symmetric(values, spacing)


def run(setup, adhesion: Adhesion, *, warm_penetration=None) -> AdhesiveState:
    """Solve the adhesive scene of a validated ``contactlib.contact._Setup``."""
    args = setup.solver_args
    if adhesion.model == "jkr":
        return _run_energy(setup, adhesion, args["mean_pressure"], args["penetration"])

    def repulsive(h, *, mean_pressure, penetration, tol=args["tol"], max_iter=args["max_iter"],
                  initial_pressure=None):
        return setup._symmetric(h, mean_pressure=mean_pressure, penetration=penetration, tol=tol,
                                max_iter=max_iter, initial_pressure=initial_pressure)

    state, p_r = solve_cohesive(setup.operator, setup.values, adhesion=adhesion,
                                mean_pressure=args["mean_pressure"], penetration=args["penetration"],
                                tol=args["tol"], max_iter=MAX_NEWTON, initial_pressure=args["initial_pressure"],
                                initial_penetration=warm_penetration, solve_repulsive=repulsive)
    return AdhesiveState(**vars(state), repulsive_pressure=p_r, in_contact=p_r > 0)


def family(setup, max_radius: float | None = None) -> EnergyFamily:
    """The energy method's family of contact domains of the scene (``max_radius`` [length] bounds the
    largest 2D disc; its elements, at most :data:`MAX_POINTS`, make a dense matrix)."""
    order, ends = growth_order(setup.values, setup.grid.spacing, periodic=setup.operator.periodic,
                               max_radius=max_radius)
    if order.size > MAX_POINTS:
        keep = int(np.searchsorted(ends, MAX_POINTS, side="right"))
        if keep < 2:
            raise ValueError(f"adhesion model 'jkr': the energy method takes at most {MAX_POINTS} elements "
                             f"in its largest domain")
        ends = ends[:keep]
        order = order[: ends[-1]]
    matrix = setup.operator.matrix(order)
    return energy_family(matrix, setup.values, setup.grid.element_area, order, ends)


def energy_state(setup, fam: EnergyFamily, m: int, penetration: float, note: str) -> AdhesiveState:
    """The state of domain ``m`` (``-1``: out of contact) at approach ``penetration``."""
    values = setup.values
    h0 = values.max() - values
    if m < 0:
        p = np.zeros_like(values)
        displacement = np.zeros_like(values)
    else:
        p = fam.pressure(m, penetration).reshape(values.shape)
        displacement = setup.operator(p)
    gap = displacement + h0 - penetration
    closed = np.zeros(values.shape, dtype=bool)
    if m >= 0:
        closed.flat[fam.domain(m)] = True
    open_gap = np.where(closed, 0.0, gap)
    # the equilibrium holds by construction; what can fail is the gap outside the domain (interpenetration)
    residual = float(np.max(np.maximum(-open_gap, 0.0))) / height_scale(values)
    return AdhesiveState(pressure=p, gap=np.where(closed, 0.0, gap), displacement=displacement,
                         penetration=float(penetration), mean_pressure=float(p.mean()), iterations=0,
                         residual=residual, converged=residual <= setup.solver_args["tol"],
                         solver="energy-balance (jkr)", repulsive_pressure=np.where(closed, np.maximum(p, 0), 0.0),
                         in_contact=closed, notes=(note,))


def _run_energy(setup, adhesion: Adhesion, mean_pressure, penetration) -> AdhesiveState:
    fam = family(setup)
    w = adhesion.work
    if penetration is not None:
        minima = fam.stable_domains(penetration, w)
        F = np.concatenate([[0.0], fam.free_energy(penetration, w)])
        m = int(minima[np.argmin(F[minima + 1])])
        note = (f"least free energy among the stable domains at this approach ({minima.size} stable "
                f"states: adhesion_curve follows a path)")
        return energy_state(setup, fam, m, penetration, note)
    _, d, P = fam.equilibrium_curve(w)
    # under load control a state is stable where the load grows with the contact
    stable = np.isfinite(P[:-1]) & np.isfinite(P[1:]) & (np.diff(P) > 0)
    candidates = np.flatnonzero(stable & (np.minimum(P[:-1], P[1:]) <= mean_pressure)
                                & (np.maximum(P[:-1], P[1:]) >= mean_pressure))
    if candidates.size == 0:
        raise ValueError(f"mean_pressure {mean_pressure!r}: no stable adhesive contact carries it (pull-off "
                         f"pressure {np.nanmin(P):.6g}, or beyond the largest domain)")
    k = int(candidates[-1])  # the branch of largest contact
    frac = (mean_pressure - P[k]) / (P[k + 1] - P[k])
    mk = k if frac < 0.5 else k + 1
    note = "stable load-control branch of largest contact (Griffith balance G = w at the edges)"
    return energy_state(setup, fam, mk, float(d[mk]) if np.isfinite(d[mk]) else float(d[k]), note)


def label(ds: xr.Dataset, state: AdhesiveState, adhesion: Adhesion, setup, *, length_unit: str,
          pressure_unit: str) -> None:
    """Add the adhesive variables and attrs to ``ds`` (in place)."""
    def a(name):
        return attrs_for(name, length=length_unit, pressure=pressure_unit)

    if adhesion.cohesive:
        interacting = adhesion.interacting(state.gap)
    else:
        interacting = state.in_contact
    size = state.pressure.size
    ds.update({  # one merge: each assignment of a variable aligns the whole Dataset (about 1.5 ms at 256^2)
        "adhesive_pressure": (tuple(ds["pressure"].dims), np.minimum(state.pressure, 0.0), a("adhesive_pressure")),
        "contact_area": ((), float(np.count_nonzero(state.in_contact)) / size,
                         {**a("contact_area"), "long_name": "repulsive (closed) contact area fraction"}),
        "interaction_area": ((), float(np.count_nonzero(interacting)) / size, a("interaction_area")),
    })
    ds.attrs.update(scene_attrs(adhesion, setup.values, setup.grid.spacing, setup.attrs["E_star"]))
    ds.attrs["full_contact"] = int(bool(np.all(state.in_contact)))
    if state.notes:
        ds.attrs["adhesion_branch"] = "; ".join(state.notes)
    if state.outer_iterations:
        ds["outer_iterations"].attrs["long_name"] = (
            "frozen-traction rounds (iterations: their inner CG iterations)" if "frozen" in state.solver
            else "Krylov (GMRES) iterations of the Newton steps")
