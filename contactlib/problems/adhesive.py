"""What :func:`contactlib.solve` does with ``adhesion=``: validate, run and label an adhesive scene.

Kept apart from :mod:`contactlib.problems.problem`, which calls :func:`check_scene`, :func:`check_load`, :func:`label`
and (through :mod:`contactlib.problems.adhesive_choice`) :func:`run` or :func:`run_energy`, and nothing else. The
cohesive laws go to :func:`contactlib.solvers.adhesive.cohesive.solve_cohesive` with the scene's compliance
(half-space or layer, periodic or zero-padded); ``"jkr"`` to the energy method of
:mod:`contactlib.solvers.adhesive.energy` on the compliance matrix of the profile or sphere (reduced to the orbits of
its symmetries), which :func:`family` builds to the largest domain the window holds.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import xarray as xr

from ..model.adhesion import Adhesion, scene_attrs
from .. import resolution
from ..core.inputs import number
from ..core.labels import attrs_for, field_variable
from ..solvers.adhesive.cohesive import MAX_NEWTON, solve_cohesive
from ..solvers.adhesive.cohesive_law import grid_law
from ..solvers.adhesive.energy import EnergyFamily, check_symmetric, energy_family, growth_order
from ..solvers.state import ContactState, height_scale


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
    law: object = None  # the cohesive law as solved on the grid (:class:`.solvers.cohesive_law.GridLaw`)


def check_scene(adhesion, values: np.ndarray, *, spacing, friction, method) -> None:
    """Refuse, naming the parameter, the scenes the adhesive solvers do not model (:func:`contactlib.prepare`)."""
    if not isinstance(adhesion, Adhesion):
        raise ValueError(f"adhesion must be a contactlib.Adhesion or None, got {adhesion!r}")
    if friction:
        raise ValueError("friction: adhesion is modelled frictionless (friction=0)")
    if method != "cg":
        raise ValueError("method: adhesion is solved by its own solvers (method='cg')")
    if adhesion.model == "jkr":
        check_symmetric(values, spacing)


def check_load(adhesion: Adhesion, *, mean_pressure, penetration) -> None:
    """Refuse, naming the parameter, the loads no adhesive state carries (:meth:`contactlib.Problem.solve`)."""
    if (mean_pressure is None) == (penetration is None):
        raise ValueError("give exactly one of mean_pressure or penetration")
    for name, v in (("mean_pressure", mean_pressure), ("penetration", penetration)):
        if v is not None:
            number(name, v)  # a finite number of either sign (tension, an approach below first contact)
    if mean_pressure is not None and adhesion.cohesive and mean_pressure < -adhesion.peak_stress:
        # the tension of a point is at most sigma_0 (at any gap): so is the window's mean
        raise ValueError(f"mean_pressure {mean_pressure!r}: a tension beyond the cohesive law's peak stress sigma_0 = "
                         f"work / range = {adhesion.peak_stress:.4g} over the whole window, which no state carries "
                         "(the pull-off is smaller still; contactlib.adhesion_curve finds it)")


def run(setup, adhesion: Adhesion, *, warm_penetration=None) -> AdhesiveState:
    """Solve the cohesive scene of a prepared :class:`contactlib.Problem` with its load (``setup``;
    :mod:`contactlib.problems.adhesive_choice` sends the cohesive laws here)."""
    args = setup.solver_args

    def repulsive(h, *, mean_pressure, penetration, tol=args["tol"], max_iter=args["max_iter"],
                  initial_pressure=None):
        return setup.solve_symmetric(h, mean_pressure=mean_pressure, penetration=penetration, tol=tol,
                                     max_iter=max_iter, initial_pressure=initial_pressure)

    report = {}  # the law solved: a zone narrower than the grid holds is regularised, and said so
    state, p_r = solve_cohesive(setup.operator, setup.values, adhesion=grid_law(adhesion, setup.operator),
                                mean_pressure=args["mean_pressure"], penetration=args["penetration"],
                                tol=args["tol"], max_iter=MAX_NEWTON, initial_pressure=args["initial_pressure"],
                                initial_penetration=warm_penetration, solve_repulsive=repulsive, report=report)
    law = report["law"]
    return AdhesiveState(**vars(state), repulsive_pressure=p_r, in_contact=p_r > 0,
                         notes=(law.note(),) if law.regularised else (), law=law)


def family(setup, max_radius: float | None = None) -> EnergyFamily:
    """The energy method's family of contact domains of the scene, to the largest the window holds (2D: the disc
    of radius ``min(shape) // 2 - 1`` spacings about the apex; ``max_radius`` [length] bounds it) or to
    :data:`contactlib.solvers.adhesive.energy.MAX_UNKNOWNS` (its
    :attr:`~contactlib.solvers.adhesive.energy.EnergyFamily.limit`)."""
    order, ends = growth_order(setup.values, setup.grid.spacing, periodic=setup.operator.periodic,
                               max_radius=max_radius)
    limit = None
    if setup.values.ndim == 2 or max_radius is not None:
        spacing = max(setup.grid.spacing)
        limit = (f"the largest disc about the apex the family was given (radius {len(ends) - 0.5:g} spacings, "
                 f"max_radius {max_radius!r})" if max_radius is not None else
                 f"the largest disc about the apex that the window holds (radius {len(ends) - 0.5:g} spacings = "
                 f"{(len(ends) - 0.5) * spacing:.4g}): a larger window (length, the same spacing) holds a larger "
                 "contact")
    return energy_family(setup.operator.response(), setup.values, setup.grid.spacing, setup.grid.element_area,
                         order, ends, periodic=setup.operator.periodic, limit=limit)


def energy_state(setup, fam: EnergyFamily, m: int, penetration: float, note: str,
                 mean_pressure: float | None = None) -> AdhesiveState:
    """The state of domain ``m`` (``-1``: out of contact) at approach ``penetration``; ``mean_pressure``: the load
    it was asked to carry (its miss joins the residual)."""
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
    if mean_pressure is not None:  # exact up to round-off (the penetration is solved for it)
        residual = max(residual, abs(float(p.mean()) - mean_pressure) / max(abs(mean_pressure),
                                                                             float(np.abs(p).mean()), 1e-300))
    return AdhesiveState(pressure=p, gap=np.where(closed, 0.0, gap), displacement=displacement,
                         penetration=float(penetration), mean_pressure=float(p.mean()), iterations=0,
                         residual=residual, converged=residual <= setup.solver_args["tol"],
                         solver="energy-balance (jkr)", repulsive_pressure=np.where(closed, np.maximum(p, 0), 0.0),
                         in_contact=closed, notes=(note,))


def unresolved_work(fam: EnergyFamily, m: int, work: float) -> bool:
    """Whether the grid does not resolve ``work`` at domain ``m``: a step into or out of it has no root of
    ``G = w`` (:meth:`~contactlib.solvers.adhesive.energy.EnergyFamily.resolved`), so its edge is placed where ``G`` is
    least, whatever ``w`` is: the disc family's non-adhesive contact."""
    if m < 0 or fam.a.size < 2:
        return False
    ok = fam.resolved(work)
    steps = [k for k in (m - 1, m) if 0 <= k < ok.size]
    return any(not ok[k] for k in steps)


def plain_state(setup, fam: EnergyFamily | None, work: float, *, mean_pressure=None, penetration=None,
                m: int | None = None) -> AdhesiveState:
    """The non-adhesive solve of the scene at the load or approach asked, for a state whose work of adhesion the
    energy method does not resolve (:func:`unresolved_work`) or is zero.

    There the energy method's own state is the non-adhesive contact made of discs of whole spacings: its edge is
    placed where ``G`` is least, which leaves elements between discs interpenetrating (1.6 % of the approach on a
    40^2 sphere at 5 spacings of contact, a residual of 5e-3) or pulling without adhesion. The grid's own
    non-adhesive contact is the same physics without that artefact. A ``w`` the family does resolve nearby
    changes the load by about :meth:`~contactlib.solvers.adhesive.energy.EnergyFamily.adhesive_load`: a
    :class:`~contactlib.ResolutionWarning` says so where that exceeds its threshold of the load."""
    args = setup.solver_args
    state = setup.solve_symmetric(setup.values, mean_pressure=mean_pressure, penetration=penetration,
                                  tol=args["tol"], max_iter=args["max_iter"], initial_pressure=None)
    if work == 0:
        note = "work of adhesion 0: solved without adhesion (the energy method models nothing there)"
    else:
        step = min(max(int(m if m is not None else 0), 0), fam.a.size - 2)
        least = float(fam.least_release_rate()[step])
        change = fam.adhesive_load(step, work) / max(abs(float(state.mean_pressure)), 1e-300)
        note = (f"work of adhesion {work:.4g} below the energy method's resolution here (the least energy release "
                f"rate of its disc's growth step, {least:.4g}): solved without adhesion; w would change the load by "
                f"about {change:.2g} of it here (a finer grid resolves it, or a cohesive model)")
        if change > resolution.THRESHOLD:
            resolution.warn(f"solve: {note}", stacklevel=7)  # at the caller of solve
    p = state.pressure
    return AdhesiveState(**vars(state), repulsive_pressure=np.maximum(p, 0.0), in_contact=p > 0, notes=(note,))


def run_energy(setup, adhesion: Adhesion, mean_pressure, penetration) -> AdhesiveState:
    """Solve the ``"jkr"`` scene of a prepared :class:`contactlib.Problem` by the energy method (its load given)."""
    w = adhesion.work
    if w == 0 and (penetration is not None or mean_pressure >= 0):  # an Adhesion of zero work models nothing
        return plain_state(setup, None, w, mean_pressure=mean_pressure, penetration=penetration)
    fam = family(setup)
    if penetration is not None:
        minima = fam.stable_domains(penetration, w)
        if fam.beyond(int(minima[-1])):  # the largest domain is stable: a larger one may be too, and lower
            raise fam.refusal("penetration", penetration)
        F = np.concatenate([[0.0], fam.free_energy(penetration, w)])
        m = int(minima[np.argmin(F[minima + 1])])
        note = (f"least free energy among the stable domains at this approach ({minima.size} stable "
                f"states: adhesion_curve follows a path)")
        return energy_or_plain(setup, fam, w, m, penetration, note)
    found = fam.load_state(mean_pressure, w)
    if found is None:
        pull_off, _ = fam.pull_off(w)
        if np.isnan(pull_off):
            raise ValueError(f"mean_pressure {mean_pressure!r}: no partial contact is stable under load control here "
                             "(the equilibrium curve G = w nowhere rises with the contact)")
        if mean_pressure < pull_off:
            raise ValueError(f"mean_pressure {mean_pressure!r}: no adhesive equilibrium carries it under load "
                             f"control: beyond the pull-off {pull_off:.6g} (the least load of the equilibrium "
                             "curve G = w; contactlib.adhesion_curve reports it as pull_off_pressure)")
        if fam.limit is not None:
            raise fam.refusal("mean_pressure", mean_pressure)
        raise ValueError(f"mean_pressure {mean_pressure!r}: no stable partial contact carries it (beyond the "
                         "largest interval, the closed window; contactlib.adhesion_curve follows it there)")
    m, d = found
    note = ("load control: the domain in whose cell the equilibrium curve G = w carries this load, at the "
            "penetration that carries it exactly (stable under load control: the curve rises there)")
    return energy_or_plain(setup, fam, w, m, d, note, mean_pressure=mean_pressure)


def energy_or_plain(setup, fam: EnergyFamily, work: float, m: int, penetration: float, note: str,
                    mean_pressure: float | None = None) -> AdhesiveState:
    """:func:`energy_state`, or where the grid does not resolve ``work`` at domain ``m`` (:func:`unresolved_work`),
    :func:`plain_state` at the same load (load control) or approach: there the disc's state either interpenetrates
    outside (a residual of 5e-3 on a 40^2 sphere, which raised ConvergenceError as ``w -> 0``) or pulls on its
    edge without adhesion (21 % of the peak pressure there, a silent error), whatever ``w``."""
    if not unresolved_work(fam, m, work) or (mean_pressure is not None and mean_pressure < 0) or penetration < 0:
        return energy_state(setup, fam, m, penetration, note, mean_pressure=mean_pressure)
    if mean_pressure is not None:
        return plain_state(setup, fam, work, mean_pressure=mean_pressure, m=m)
    return plain_state(setup, fam, work, penetration=penetration, m=m)


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
        "adhesive_pressure": field_variable(setup.dims, np.minimum(state.pressure, 0.0), a("adhesive_pressure")),
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
