"""The two-scale asperity method in viscoelastic time stepping (seed paper 1, last paragraph; eq. 4).

The time-stepping rule is :func:`contactlib.solve_transient`'s (:mod:`contactlib.model.hereditary`): over a step
``dt`` the displacement changes at a constant rate and the Prony branches are integrated exactly, so the
step is an elastic contact problem at the modulus ``E_eff`` in which the body answers the pressure ``p``
with ``u = C_eff (p + g)``, ``g`` the history pressure of :class:`contactlib.model.hereditary.PronyHistory`.

**Macro scale, one history per asperity.** The macro step needs each contact to be a Hertz contact. In
the step's problem the field that is Hertz-shaped is ``p + g`` (the body's "strain" ``S u`` times
``E_eff``), not ``p``: on a contact that does not recede, ``g`` lives inside the contact, and the
displacement inside is the sphere's shape (Lee and Radok's solution). So the macro step solves the
elastic problem of seed eq. 3 at ``E_eff`` for the forces ``F_k = P_k + G_k`` (total ``P + sum G``) and
returns ``P_k = F_k - G_k``, with ``G_k`` the history force of asperity ``k``: a
:class:`~contactlib.model.hereditary.PronyHistory` on an array of ``N`` forces instead of a grid. Exact for
Lee and Radok's sphere (growing or fixed contact, any load history) and as accurate as the elastic macro
step for a field; it does not hold where a contact recedes (Ting's problem), which is reported.

Passing the memory as a known displacement sampled at the summits instead (Hertz's pressure of each
macro force fed to a grid memory) treats ``C_eff g`` as uniform over each contact, a Hertz contact at
``E_eff`` carrying the same force: under a constant load its radius hardly grows. Measured on the sphere
of the Lee and Radok test (standard linear solid, ``E_inf / E0 = 4``, 40 steps): radius 33 % and
approach 49 % off at the end (radius growth 1.06 for 1.59), against 0.05 % and 0.10 % here.

**Two scales.** The memory lives on the grid as in :func:`contactlib.solve_transient`: ``C_eff g`` (one
FFT convolution per step) is the known displacement of :func:`.micro.solve_micro`, seeded by the macro
step above with ``G_k`` the history pressure summed over each footprint and warm-started from the
last steps' pressures; its coarse correction takes each contact's stiffness from ``P_k + G_k``. The
micro scale converges to the full transient solver's step, up to its tolerance.
"""

from __future__ import annotations

import time as _time
import warnings

import numpy as np
import xarray as xr

from .._version import __version__
from ..errors import ConvergenceError
from ..invariants import verify_two_scale_series
from ..model.hereditary import PronyHistory
from ..core.inputs import load_history, time_values
from ..core.labels import attrs_for
from ..model.materials import contact_modulus, material_of
from ..model.operators import Compliance
from ..problems.transient import INITIAL_STATES, MODELS_KEPT
from .asperities import AsperityTable, asperity_forces
from .interaction import PointInteraction
from .laws import TabulatedLaw
from .macro import FiniteSize, HertzLaw, MacroState, solve_macro
from .micro import solve_micro
from .scene import SCALES, check_separate_contacts, solver_tolerances, table_with_grid

MACRO_TOL_TRANSIENT = 1e-10
"""Default ``macro_tol`` of ``scale="macro"`` steps: the macro forces are then the answer, and each step's
memory carries their error on."""
RECEDING_TOL = 1e-6
"""A macro force below ``-RECEDING_TOL`` times the largest is a receding contact (reported)."""


def solve_transient(
    asperities,
    *,
    times,
    material=None,
    E: float | None = None,
    nu: float | None = None,
    mean_pressure=None,
    penetration=None,
    scale: str = "two-scale",
    law=None,
    initial: str = "unloaded",
    periodic: bool | None = None,
    length: float | None = None,
    n: int | None = None,
    tol: float = 1e-6,
    force_tol: float | None = None,
    macro_tol: float | None = None,
    finite_size: bool = True,
    max_iter: int = 200,
    length_unit: str = "m",
    pressure_unit: str = "Pa",
    time_unit: str = "s",
) -> xr.Dataset:
    """Rigid spherical asperities on a viscoelastic (or elastic) half-space, stepped through ``times`` by
    the two-scale method.

    Parameters
    ----------
    asperities : xarray.DataArray or xarray.Dataset
        As :func:`contactlib.two_scale.solve`.
    times : sequence of float
        Strictly increasing instants [time], as :func:`contactlib.solve_transient`: the body is at rest
        before ``times[0]`` and the first load is applied at once (glassy), or with ``initial="relaxed"``
        has been carried for ever.
    material : contactlib.Viscoelastic or contactlib.Elastic
        The body (or the elastic shorthand ``E``, ``nu``).
    mean_pressure, penetration : float, sequence or callable
        Exactly one: total force over the window area [pressure], or the rigid approach from first
        contact of the highest point [length] (as :func:`contactlib.two_scale.solve`), as a constant, one
        value per time or a function of time.
    scale : {"two-scale", "macro"}
        ``"macro"``: Hertz's law and the point-load interaction only, the memory kept per asperity;
        ``"two-scale"``: each step refined by the local FFT solves, the memory kept on the grid.
    law : TabulatedLaw, optional
        The single-asperity law of every asperity, as :func:`contactlib.two_scale.solve`: default Hertz's,
        or a :func:`contactlib.two_scale.tabulated_law` for another shape. It may be tabulated at any
        modulus (its ``attrs['law_E_star']``): each step uses it at the step's effective modulus
        (:meth:`~contactlib.two_scale.TabulatedLaw.at_modulus`). Lee and Radok's argument behind the
        per-asperity memory holds for any axisymmetric shape whose contact does not recede.
    initial : {"unloaded", "relaxed"}
    periodic, length, n, tol, force_tol, finite_size, max_iter
        As :func:`contactlib.two_scale.solve`, for every step (``finite_size``: the macro step's finite-size
        term of the Hertz contacts, at the step's effective modulus; ``force_tol``: each step's sweeps stop on
        the asperity forces' estimated change, not on the pressure field's).
    macro_tol : float, optional
        The macro step's Newton tolerance: by default 1e-10 for ``scale="macro"``; under the two-scale method,
        where the macro forces only start each step's sweeps, as :func:`contactlib.two_scale.solve` (a hundredth
        of ``force_tol``, else of ``tol``, within [1e-8, 1e-4]).

    E, nu : float, optional
        The elastic shorthand for ``material=contactlib.Elastic(E, nu)``.
    length_unit, pressure_unit, time_unit : str
        udunits strings written to the output's ``units`` attributes.

    Returns
    -------
    xarray.Dataset
        On ``time``: ``mean_pressure``, ``penetration``, ``contact_area``, ``iterations`` (macro Newton
        plus outer two-scale iterations); on ``(time, asperity)``: ``force`` and ``contact_radius``.
        ``attrs``: the material, ``scale``, ``time_integration``, ``wall_time`` [s], the version.

    Raises
    ------
    ValueError
        Bad input, naming the parameter, or a load beyond separate spherical contacts at some step.
    ConvergenceError
        A step did not converge: ``err.dataset`` holds the steps before it.
    """
    material = material_of(material, E, nu)
    if scale not in SCALES:
        raise ValueError(f"scale must be one of {SCALES}, got {scale!r}")
    if initial not in INITIAL_STATES:
        raise ValueError(f"initial must be one of {INITIAL_STATES}, got {initial!r}")
    times = time_values(times, "times")
    if (mean_pressure is None) == (penetration is None):
        raise ValueError("give exactly one of mean_pressure or penetration")
    control = "mean_pressure" if mean_pressure is not None else "penetration"
    loads = load_history(mean_pressure if mean_pressure is not None else penetration, times, control)
    if control == "mean_pressure" and np.any(loads < 0):
        raise ValueError(f"mean_pressure must be >= 0 at every time, got {loads.min()!r}")
    macro_tol = solver_tolerances(scale, tol=tol, force_tol=force_tol, macro_tol=macro_tol, max_iter=max_iter,
                                  macro_default=MACRO_TOL_TRANSIENT)
    if law is not None:
        if not isinstance(law, TabulatedLaw):
            raise ValueError(f"law must be None (Hertz) or a contactlib.two_scale.tabulated_law(...), got {law!r}")
        law.at_modulus(contact_modulus(material.E0, material.nu))  # refuses a table without its modulus
    table = table_with_grid(asperities, length=length, periodic=periodic, n=n, scale=scale, law=law)
    if law is not None and scale == "two-scale" and table.grid is None:
        raise ValueError("law: the two-scale method with a tabulated law needs the heights on a grid (a DataArray)")
    stepper = _Stepper(table, material, scale, control, float(tol), float(macro_tol), int(max_iter), law,
                       finite_size=bool(finite_size), force_tol=None if force_tol is None else float(force_tol))
    record = _Record(table, times)
    start = _time.perf_counter()
    try:
        for k in range(times.size):
            if k == 0:
                step = stepper.first(loads[0], relaxed=initial == "relaxed")
            else:
                step = stepper.step(times[k] - times[k - 1], loads[k])
            record.add(step)
    except ConvergenceError as err:
        ds = record.dataset(stepper, start, (length_unit, pressure_unit, time_unit),
                            status=f"not converged at step {record.done} (t = {times[record.done]:g}): {err}")
        raise ConvergenceError(ds.attrs["status"], residual=err.residual, dataset=ds) from err
    ds = record.dataset(stepper, start, (length_unit, pressure_unit, time_unit), status="completed")
    verify_two_scale_series(ds, loads, control=control, scale=scale, tol=tol if force_tol is None else force_tol,
                            macro_tol=stepper.macro_tol)
    if stepper.receding:
        ds.attrs["receding_contacts"] = stepper.receding
        warnings.warn(f"two_scale.solve_transient: {stepper.receding}", stacklevel=2)
    return ds


class _Stepper:
    """One elastic two-scale problem per step at ``E_eff``, the Prony memory per asperity (macro) or on
    the grid (two-scale)."""

    def __init__(self, table: AsperityTable, material, scale: str, control: str, tol: float, macro_tol: float,
                 max_iter: int, law: TabulatedLaw | None = None, finite_size: bool = True,
                 force_tol: float | None = None):
        self.table, self.material, self.scale, self.control, self.law = table, material, scale, control, law
        self.finite_size = finite_size and law is None  # the term is Hertz's pressure's
        self.tol, self.macro_tol, self.max_iter, self.force_tol = tol, macro_tol, max_iter, force_tol
        self.z_top = float(table.heights.max()) if table.heights is not None else float(table.summit_height.max())
        self.area = table.length**2
        self.shape = (table.count,) if scale == "macro" else table.grid.shape
        self.history = PronyHistory(material, self.shape)
        self._models: dict[float, tuple] = {}
        self.receding = ""
        self.pressure = self.previous = None  # the two-scale pressure of the last two steps, for the warm start
        self.dt = self.last_dt = 0.0

    def predicted(self):
        """The micro scale's warm start: the last pressure extrapolated linearly over the step (the last one
        after the first step, whose own step is of zero length)."""
        if self.pressure is None:
            return None
        if self.previous is None or self.last_dt <= 0:
            return self.pressure
        return np.maximum(self.pressure + (self.pressure - self.previous) * (self.dt / self.last_dt), 0.0)

    def model(self, E_eff: float):
        """``(E*, interaction, law, compliance, finite_size)`` at modulus ``E_eff``; the last few kept (the Ewald
        setup is the costly part)."""
        if E_eff not in self._models:
            if len(self._models) >= MODELS_KEPT:
                self._models.pop(next(iter(self._models)))
            E_star = contact_modulus(E_eff, self.material.nu)
            compliance = None if self.scale == "macro" else \
                Compliance(self.table.grid, E_star=E_star, periodic=self.table.periodic)
            law = HertzLaw(self.table.radius, E_star) if self.law is None else self.law.at_modulus(E_star)
            finite_size = FiniteSize(self.table, E_star) if self.finite_size else None
            self._models[E_eff] = (E_star, PointInteraction(self.table, E_star), law, compliance, finite_size)
        return self._models[E_eff]

    def first(self, load: float, *, relaxed: bool) -> dict:
        if not relaxed:
            return self.step(0.0, load)
        step, carried = self._solve(self.material.E0, None, load)
        self.history = PronyHistory(self.material, self.shape, relaxed_pressure=carried)
        return step

    def step(self, dt: float, load: float) -> dict:
        self.last_dt, self.dt = self.dt, dt
        E_eff, _, _ = self.history.coefficients(dt)
        g = self.history.history_pressure(dt)
        step, carried = self._solve(E_eff, g, load)
        self.history.advance(dt, carried, g)
        return step

    def _solve(self, E_eff: float, g, load: float) -> tuple[dict, np.ndarray]:
        """The step's problem; returns the step's scalars and the field the memory carries on."""
        E_star, interaction, law, compliance, finite_size = self.model(E_eff)
        table = self.table
        if g is None:
            history_force = np.zeros(table.count)
        elif self.scale == "macro":
            history_force = g
        else:
            history_force = asperity_forces(g, table)
        total = None if self.control == "penetration" else float(load) * self.area + float(history_force.sum())
        carried = solve_macro(table, interaction, law, penetration=None if total is not None else float(load),
                              total_force=total, z_top=self.z_top, tol=self.macro_tol, max_iter=self.max_iter,
                              finite_size=finite_size)
        if not carried.converged:
            raise ConvergenceError(f"macro step: Newton did not converge in {carried.iterations} iterations: residual "
                                   f"{carried.residual:.3e} > macro_tol {self.macro_tol:.1e}",
                                   residual=carried.residual, dataset=None)
        check_separate_contacts(table, law, carried, self.z_top)
        if isinstance(law, TabulatedLaw) and np.any(carried.local_penetration > law.max_penetration):
            raise ValueError(f"law: the local penetration {float(carried.local_penetration.max()):.4g} exceeds the "
                             f"table's max_penetration {law.max_penetration:.4g}: tabulate further")
        force = carried.force - history_force
        macro = MacroState(np.maximum(force, 0.0), carried.local_penetration, carried.penetration, carried.iterations,
                           carried.residual, carried.converged)
        if self.scale == "macro":
            if np.any(force < -RECEDING_TOL * max(float(np.max(np.abs(force))), 1e-300)) and not self.receding:
                k = int(np.argmin(force))
                self.receding = (f"asperity {k} carries a negative force {force[k]:.4g} in the macro step: its contact "
                                 "recedes, where the per-asperity memory (Lee and Radok) does not hold")
            radius = law.contact_radius(carried.local_penetration)
            step = {"force": force, "contact_radius": radius, "penetration": carried.penetration,
                    "contact_area": float(np.sum(np.pi * radius**2)) / self.area, "iterations": carried.iterations}
            return step, force
        memory = None if g is None else compliance(g)
        micro = solve_micro(table, macro, law, E_star, interaction, z_top=self.z_top,
                            total_force=None if total is None else float(load) * self.area, tol=self.tol,
                            max_iter=self.max_iter, known_displacement=memory,
                            known_force=None if g is None else history_force, initial_pressure=self.predicted(),
                            force_tol=self.force_tol)
        if not micro.converged:
            measure = f"pressure change {micro.change:.3e} > tol {self.tol:.1e}" if self.force_tol is None else \
                f"asperity-force change {micro.force_change:.3e} > force_tol {self.force_tol:.1e}"
            raise ConvergenceError(f"micro step did not converge in {micro.iterations} outer iterations: {measure}",
                                   residual=micro.change if self.force_tol is None else micro.force_change,
                                   dataset=None)
        self.previous, self.pressure = self.pressure, micro.pressure
        node_area = table.grid.element_area
        step = {"force": micro.force, "contact_radius": np.sqrt(micro.contact_nodes * node_area / np.pi),
                "penetration": micro.penetration,
                "contact_area": float(np.count_nonzero(micro.pressure > 0)) / micro.pressure.size,
                "iterations": carried.iterations + micro.iterations}
        return step, micro.pressure


class _Record:
    """Every step's scalars and per-asperity values, labelled on demand."""

    def __init__(self, table: AsperityTable, times: np.ndarray):
        self.table, self.times = table, times
        self.rows: list[dict] = []

    @property
    def done(self) -> int:
        return len(self.rows)

    def add(self, step: dict) -> None:
        step["mean_pressure"] = float(np.sum(step["force"])) / self.table.length**2
        self.rows.append(step)

    def dataset(self, stepper: _Stepper, start: float, units, *, status: str) -> xr.Dataset:
        length_unit, pressure_unit, time_unit = units
        table, n = self.table, self.done

        def a(name):
            return attrs_for(name, length=length_unit, pressure=pressure_unit)

        coords = {"time": ("time", self.times[:n], {"units": time_unit, "long_name": "time"}),
                  "asperity": ("asperity", np.arange(table.count), a("asperity")),
                  "center_x": ("asperity", table.centers[:, 0], a("center_x")),
                  "center_y": ("asperity", table.centers[:, 1], a("center_y")),
                  "radius": ("asperity", table.radius, a("radius")),
                  "summit_height": ("asperity", table.summit_height, a("summit_height"))}
        data = {}
        for name in ("mean_pressure", "penetration", "contact_area", "iterations"):
            values = np.array([row[name] for row in self.rows], dtype=int if name == "iterations" else float)
            data[name] = ("time", values, a(name))
        for name in ("force", "contact_radius"):
            values = np.array([row[name] for row in self.rows]).reshape(n, table.count)
            data[name] = (("time", "asperity"), values, a(name))
        material = stepper.material
        ds = xr.Dataset(data, coords=coords)
        ds.attrs.update({
            "title": "two-scale asperity contact on a viscoelastic body (seed paper 1)",
            "source": f"contactlib {__version__}, contactlib.two_scale.solve_transient",
            "Conventions": "CF-1.10", "contactlib_version": __version__, "status": status, "steps": n,
            "wall_time": _time.perf_counter() - start, "scale": stepper.scale, "E0": float(material.E0),
            "E_inf": float(material.E_inf), "nu": float(material.nu),
            "prony": [v for branch in getattr(material, "prony", ()) for v in branch],
            "periodic": int(table.periodic), "window_lengths": [table.length, table.length],
            "load_control": stepper.control, "tol": stepper.tol, "macro_tol": stepper.macro_tol,
            **({"force_tol": stepper.force_tol} if stepper.force_tol is not None else {}),
            "finite_size_correction": int(stepper.finite_size),
            "max_iter": stepper.max_iter, "single_asperity_law": "hertz",
            **({} if stepper.law is None else {k: v for k, v in stepper.law.attrs.items() if k != "law_E_star"}),
            "time_integration": "displacement at a constant rate over each step, Prony branches integrated exactly "
                                "(second order; exact at fixed displacement): contactlib.model.hereditary; memory "
                                + ("per asperity (Lee and Radok: contacts that do not recede)"
                                   if stepper.scale == "macro" else "on the grid"),
        })
        return ds


__all__ = ["solve_transient"]
