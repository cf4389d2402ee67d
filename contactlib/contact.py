"""Public entry point for normal contact, elastic or viscoelastic, at rest or sliding: :func:`solve`."""

from __future__ import annotations

import dataclasses
import math
import time

import numpy as np
import xarray as xr

from . import accuracy, adhesive_contact, area_target, fft, resolution
from .analysis.friction import interlocking_friction
from ._version import __version__
from .labels import attrs_for, to_dataset, window_variables
from .analysis.viscoelastic import traction_power
from .materials import Elastic, Viscoelastic, contact_modulus, material_of
from .bodies import BodyModel, Layer, body_model
from .grid import Grid
from .nonsymmetric import NonSymmetricSolve
from .inputs import EDGE_TENSION, check_below_full_contact, check_friction, check_iterations, check_loads, \
    check_tolerance, check_velocity, edge_tension, grid_of, periodic_of, real_values, round_off_floor, touches_edge
from .operators import KERNELS
from .solvers.coarse import PLATE_SET_FLOOR
from .solvers import (ContactState, solve_active_set, solve_periodic_displacement, solve_polonsky_keer,
                      solve_semismooth)

METHODS = ("cg", "active-set")


class ConvergenceError(RuntimeError):
    """A solve did not reach its tolerance within ``max_iter``, or stalled before it (the CG
    residual stopped falling, e.g. at the round-off floor of a tolerance set too tight).


    Parameters
    ----------
    message : str
        What did not converge, with the residual and the tolerance.
    residual : float
        The residual reached.
    dataset : xarray.Dataset
        The partial state.

    Attributes
    ----------
    residual : float
        The residual reached.
    dataset : xarray.Dataset
        The partial (unconverged) state, labelled like a converged one, ``attrs['converged'] = 0``.
    datasets : list of xarray.Dataset or None
        From :func:`solve_tolerances`: the answer at every tolerance asked, reached or not.
    """

    def __init__(self, message: str, *, residual: float, dataset: xr.Dataset):
        super().__init__(message)
        self.residual = residual
        self.dataset = dataset
        self.datasets = None


def solve(
    heights,
    *,
    E: float | None = None,
    nu: float | None = None,
    mean_pressure: float | None = None,
    penetration: float | None = None,
    periodic: bool | None = None,
    tol: float | None = None,
    max_iter: int = 10_000,
    kernel: str = "spectral",
    method: str = "cg",
    length=None,
    initial_pressure=None,
    length_unit: str = "m",
    pressure_unit: str = "Pa",
    target_error: float | None = None,
    layer: Layer | None = None,
    friction: float = 0.0,
    sliding_direction: float | None = None,
    material: Elastic | Viscoelastic | None = None,
    sliding_velocity=None,
    adhesion=None,
    contact_area: float | None = None,
) -> xr.Dataset:
    """Normal contact of a rigid rough surface on an elastic or viscoelastic half-space or layer, with
    Coulomb friction and steady sliding.

    Parameters
    ----------
    heights : xarray.DataArray or ndarray
        Rigid surface heights [length], 1D (plane strain, per unit width) or 2D. Higher points
        touch first. A DataArray's coordinates give the physical size; an ndarray needs ``length``.
    E, nu : float
        Young's modulus [pressure] and Poisson ratio of the body, ``E > 0``, ``-1 < nu <= 0.5``: the
        shorthand for ``material=contactlib.Elastic(E, nu)``.
    material : contactlib.Elastic or contactlib.Viscoelastic, optional
        The body's material (give it or ``E, nu``). A viscoelastic body at rest is relaxed (``E0``).
    sliding_velocity : float or sequence of float, optional
        Steady sliding: the velocity ``(Vx, Vy)`` (1D: ``Vx``) of the rigid surface relative to the body
        [length/time]. A viscoelastic body then responds with its complex modulus at ``q . V`` at each
        wavevector (:mod:`contactlib.kernels.viscoelastic`; periodic only), and the result adds
        ``dissipated_power`` and the interlocking friction. Where the complex modulus is within
        ``0.1 tol`` of ``E0`` (or ``E_inf``) over the grid, the elastic problem with that modulus is
        solved (``attrs['material_model']``). It sets the sliding direction.
    mean_pressure : float
        Load control: mean pressure over the window [pressure] (1D: line load per unit width over
        the window length). Non-periodic: total load divided by the window area.
    penetration : float
        Displacement control: rigid approach from first contact of the highest point [length].
        Periodic displacements are zero-mean (the q = 0 mode of a half-space is infinite), so the
        approach is measured against the mean deformed plane; beyond full contact it does not fix
        the load and is refused. A non-periodic profile (1D): a half-plane's displacement is defined up
        to a constant, fixed at zero one window length from a line load
        (:func:`contactlib.kernels.elastic.halfspace_love_influence`), so the load that a penetration
        gives depends on the window (a cylinder pressed by 1e-3: 23 % apart on windows of one and four
        radii); load control does not.
    periodic : bool, optional
        Periodic window or an isolated footprint (zero padding, free boundary). Default: the heights'
        ``attrs['periodic']`` where a DataArray has it (a measured surface from
        :func:`contactlib.surfaces.read` is non-periodic unless its file says otherwise), else periodic.
    tol : float, optional
        Target of the scale-free residual (:func:`contactlib.solvers.contact_residual`); default
        1e-8 (1e-6 with ``adhesion``), or the rule of ``target_error``.
    max_iter : int
        Iteration bound; beyond it :class:`ConvergenceError` is raised with the partial state.
    kernel : {"spectral", "love"}
        Continuous multiplier ``2/(E*|q|)`` or Love's uniform-element kernel.
    method : {"cg", "active-set"}
        Polonsky-Keer constrained conjugate gradients, or the seed paper's active-set +
        Gauss-Seidel scheme (small grids; a cross-check).
    length : float or tuple, optional
        Window size [length], one number or one per axis: required for bare-array heights (there is no
        default window; ``ValueError`` naming ``length`` without it); for a DataArray it may only repeat the
        window its coordinates give.
    initial_pressure : ndarray, optional
        Warm start for ``method="cg"``.
    length_unit, pressure_unit : str
        udunits strings written to the output's ``units`` attributes.
    target_error : float, optional
        Relative error in (0, 1) wanted on the contact area (the slowest quantity to converge):
        picks ``tol`` by :func:`contactlib.accuracy.tolerance_for` (give ``tol`` or ``target_error``,
        not both), tightened by :func:`contactlib.accuracy.tolerance_for_scene` where the approach is far
        below the rms height (a small contact in a wide window: the solve goes on from its state to the
        tighter ``tol``, which ``attrs['tol']`` then holds) and, for a periodic surface, warns with
        :class:`contactlib.accuracy.AccuracyWarning`
        when the grid has fewer points per shortest wavelength than
        :func:`contactlib.accuracy.points_per_wavelength` asks (the grid is the caller's: refine
        the surface with :func:`contactlib.surfaces.resample` or generate it at
        :func:`contactlib.accuracy.settings_for`'s ``n``). Recorded in ``attrs``.
    layer : contactlib.Layer, optional
        A layer of finite thickness on a rigid base (``"confined"``) or with a free back face loaded by
        the balancing pressure (``"remote_pressure"``) instead of a half-space; ``kernel="spectral"``,
        ``0 <= nu <= 0.5``. A confined compressible layer has a finite uniaxial stiffness, so its
        penetration is measured from the undeformed surface; the others' mean displacement is
        undetermined (zero-mean, as for the half-space). ``periodic=False`` takes a confined layer,
        zero-padded, on a window of at least :data:`contactlib.bodies.LAYER_WINDOW` (6) thicknesses.
    friction : float
        Coulomb coefficient ``mu_c >= 0``: on the contact the body carries the tangential traction
        ``mu_c p`` along ``sliding_direction``. Through the normal-tangential terms of the Green's
        tensor it moves the surface normally (material coupling, ``nu < 0.5``; geometric, a finite
        layer), which makes the pressure asymmetric (:mod:`contactlib.solvers.coupled`).
    sliding_direction : float, optional
        Direction [rad, in the x-y plane] in which the rigid surface moves relative to the body;
        a profile slides along ``+x`` (give 0, or pi to slide along ``-x``). Default: the direction
        of ``sliding_velocity``, else 0; a direction that contradicts the velocity is refused.
    adhesion : contactlib.Adhesion, optional
        An adhesive interface (:mod:`contactlib.adhesion`): a cohesive law inside the contact solve, or
        ``"jkr"``, the energy balance (a profile symmetric about its highest point, or a surface of
        revolution). Frictionless and at rest (``friction`` and a nonzero ``sliding_velocity`` are
        refused; a viscoelastic body at rest is its relaxed elastic body);
        ``mean_pressure`` (the applied traction, adhesive part included) and ``penetration`` may then be
        negative. Adds ``adhesive_pressure`` (the tensile part of ``pressure``) and ``interaction_area``;
        ``contact_area`` is the repulsive (closed) area (:mod:`contactlib.adhesive_contact`).
    contact_area : float, optional
        Solve to this contact area fraction in (0, 1) instead of a load: the state whose area is nearest it on the
        grid (the area rises in whole elements), with the ``mean_pressure`` that gives it, found by bracketing the
        load over solves of one scene (:mod:`contactlib.area_target`); ``attrs['target_contact_area']``. Not with
        ``mean_pressure``, ``penetration`` or ``adhesion``.

    Returns
    -------
    xarray.Dataset
        ``pressure``, ``gap``, ``displacement`` fields and scalars ``contact_area``,
        ``mean_pressure``, ``penetration``, ``mean_gap``, ``iterations``, ``residual``; non-periodic, the load as
        a force and the contact's size (:func:`contactlib.labels.window_variables`): ``normal_force``
        (``mean_pressure`` times the window area) and ``contact_radius`` (``sqrt(A / pi)``), or on a profile
        ``line_load`` and ``contact_half_width``; with friction, also the
        tangential traction and (periodic) the tangential displacement fields, and
        ``friction_coefficient_interlocking`` (``mu_a``, :func:`interlocking_friction`) and
        ``friction_coefficient`` (``mu_c + mu_a``); sliding (``sliding_velocity``), also those two and
        ``dissipated_power`` (:func:`contactlib.analysis.traction_power`). ``attrs['model']`` says which model ran
        (:mod:`contactlib.bodies`: the half-space where a layer is within tolerance of it, no
        coupling where it vanishes); ``attrs['full_contact']`` is 1, with a message, when the
        contact is complete (the load no longer changes the area).

    Raises
    ------
    ValueError
        Naming the argument: a bad value, a missing or doubled load, an option the scene does not support, or a
        non-periodic contact cut by the window's edge.
    ConvergenceError
        When the solver does not reach ``tol`` in ``max_iter`` (or stalls), with its residual and partial state.
    contactlib.invariants.InvariantError
        When a converged state breaks a physical invariant (load balance, sign, complementarity, ...).

    Warns
    -----
    ResolutionWarning
        When the grid resolves the scene worse than the measured rule asks for 1 % (:mod:`contactlib.resolution`).
    contactlib.accuracy.AccuracyWarning
        With ``target_error``, when the grid is too coarse for it.

    Examples
    --------
    >>> import contactlib
    >>> h = contactlib.surfaces.self_affine(64, hurst=0.8, q_roll=2, q_cutoff=16, rms_slope=0.1, seed=1)
    >>> out = contactlib.solve(h, E=1.0, nu=0.5, mean_pressure=0.01)
    >>> 0 < float(out.contact_area) < 1
    True
    """
    periodic = periodic_of(heights, periodic)
    if contact_area is not None:  # the load is what is sought: the scene is built at a provisional one
        mean_pressure = area_target.check(contact_area, mean_pressure=mean_pressure, penetration=penetration,
                                          adhesion=adhesion)
    setup = _setup(heights, material=material_of(material, E, nu), mean_pressure=mean_pressure,
                   penetration=penetration, periodic=periodic, tol=tol, max_iter=max_iter, kernel=kernel,
                   method=method, length=length, initial_pressure=initial_pressure, target_error=target_error,
                   layer=layer, friction=friction, sliding_direction=sliding_direction,
                   sliding_velocity=sliding_velocity, adhesion=adhesion)
    start = time.perf_counter()
    state = setup.run() if contact_area is None else area_target.run(setup, contact_area)
    if target_error is not None and adhesion is None:
        state = accuracy.solve_on_for_scene(setup, state)
    wall = time.perf_counter() - start
    ds = setup.label(state, wall, length_unit=length_unit, pressure_unit=pressure_unit)
    setup.check(state, ds)
    resolution.guard_setup(setup, state, ds, where="solve", guarantee=target_error is not None)
    return ds


def solve_tolerances(
    heights,
    tols,
    *,
    E: float,
    nu: float,
    mean_pressure: float | None = None,
    penetration: float | None = None,
    periodic: bool | None = None,
    max_iter: int = 10_000,
    kernel: str = "spectral",
    length=None,
    initial_pressure=None,
    length_unit: str = "m",
    pressure_unit: str = "Pa",
) -> list[xr.Dataset]:
    """The answers of :func:`solve` at several tolerances, for the cost of the tightest one.

    The conjugate-gradient iterates do not depend on ``tol`` (it only stops them), so one solve at
    ``min(tols)`` passes through the state each looser solve would return: it is recorded at the
    first iteration whose residual reaches that tolerance, bit for bit the same pressure, gap,
    iterations and residual as ``solve(..., tol=t)``. Each Dataset's ``attrs['wall_time']`` is the
    time from the first iteration to reaching it [s], its own labelling included and the recording
    of the others not: the separate solve's time (argument checks and operator set-up excluded).
    Holds one copy of the fields per tolerance. Arguments as :func:`solve` (``method="cg"`` only).
    Periodic displacement control (the dual solver) checks the primal residual, one convolution,
    at every iteration whose own residual is below the loosest tolerance, not only the tightest:
    its times there include those checks, which a separate looser solve partly skips.


    Parameters
    ----------
    heights : xarray.DataArray or ndarray
        As :func:`solve`.
    tols : sequence of float
        The tolerances, each in (0, 1).
    E, nu : float
        Young's modulus [pressure] and Poisson ratio.
    mean_pressure, penetration : float
        The load, as :func:`solve` (one of them).
    periodic : bool, optional
        As :func:`solve`.
    max_iter : int
        Iteration bound of the one solve.
    kernel : {"spectral", "love"}
        As :func:`solve`.
    length : float or tuple, optional
        Window size [length], required for bare-array heights.
    initial_pressure : ndarray, optional
        Warm start.
    length_unit, pressure_unit : str
        udunits strings written to the outputs' ``units`` attributes.

    Returns
    -------
    list of xarray.Dataset
        One per tolerance, in the order of ``tols``, ``attrs['tol']`` set to it.

    Raises
    ------
    ConvergenceError
        When a tolerance is not reached (``max_iter`` or a stall): ``err.datasets`` holds the whole
        list, the unreached tolerances carrying the final state with ``attrs['converged'] = 0``.
    """
    tols = [float(t) for t in np.atleast_1d(real_values(tols, "tols"))]
    if not tols:
        raise ValueError("tols must hold at least one tolerance")
    for t in tols:
        check_tolerance(t, "tols")
    periodic = periodic_of(heights, periodic)
    setup = _setup(heights, material=material_of(None, E, nu), mean_pressure=mean_pressure,
                   penetration=penetration, periodic=periodic, tol=min(tols), max_iter=max_iter, kernel=kernel,
                   method="cg", length=length, initial_pressure=initial_pressure, target_error=None, layer=None,
                   friction=0.0, sliding_direction=None, sliding_velocity=None)
    pending = sorted(set(tols), reverse=True)
    found: dict[float, tuple[ContactState, float]] = {}
    paused = 0.0

    def monitor(it, residual, snapshot):
        nonlocal paused
        if not pending or residual > pending[0]:
            return
        reached = time.perf_counter() - start - paused
        t0 = time.perf_counter()
        state = snapshot()
        paused += time.perf_counter() - t0
        while pending and residual <= pending[0]:
            found[pending.pop(0)] = (state, reached)

    start = time.perf_counter()
    final = setup.run(monitor=monitor, verify_below=max(tols))
    total = time.perf_counter() - start - paused
    out, failed = [], None
    for t in tols:
        state, wall = found.get(t, (final, total))
        state = dataclasses.replace(state, converged=bool(state.residual <= t))
        t0 = time.perf_counter()
        ds = setup.label(state, 0.0, length_unit=length_unit, pressure_unit=pressure_unit, tol=t)
        ds.attrs["wall_time"] = wall + (time.perf_counter() - t0)
        try:
            setup.check(state, ds)
        except ConvergenceError as err:
            failed = failed or err
        resolution.guard_setup(setup, state, ds, where="solve_tolerances", quiet=bool(out))  # one warning a call
        out.append(ds)
    if failed is not None:
        failed.datasets = out
        raise failed
    return out


@dataclasses.dataclass
class _Setup(NonSymmetricSolve):
    """A validated contact problem: its operator and solver arguments, and how to label the answer."""

    values: np.ndarray
    grid: Grid
    dims: tuple
    coords: dict
    body: BodyModel
    solver_args: dict
    attrs: dict
    method: str
    adhesion: object = None

    @property
    def operator(self):
        return self.body.compliance

    def run(self, monitor=None, verify_below=None) -> ContactState:
        """Solve; ``verify_below``: see :func:`contactlib.solvers.solve_periodic_displacement`."""
        if self.adhesion is not None:
            return adhesive_contact.run(self, self.adhesion)
        if self.body.coupling is not None:
            return self._run_nonsymmetric()
        if self.method == "cg":
            return self._symmetric(self.values, monitor=monitor, verify_below=verify_below, **self.solver_args)
        args = {k: v for k, v in self.solver_args.items() if k != "initial_pressure"}
        return solve_active_set(self.operator, self.values, **args)

    def _symmetric(self, heights, *, monitor=None, verify_below=None, **args) -> ContactState:
        """The constrained CG of the symmetric compliance (the whole problem, or a coupled solve's inner one)."""
        return constrained_solve(self.operator, heights, monitor=monitor, verify_below=verify_below, **args)

    def label(self, state: ContactState, wall: float, *, length_unit: str, pressure_unit: str,
              tol: float | None = None) -> xr.Dataset:
        extra = {}  # built with the fields: one Dataset construction, no merge per addition
        if state.outer_iterations:
            extra["outer_iterations"] = xr.Variable((), state.outer_iterations, attrs_for("outer_iterations"))
        if self.attrs["friction"] > 0 or "sliding_velocity" in self.attrs:
            extra.update(self._friction_variables(state, length_unit, pressure_unit))
        extra.update(window_variables(state, self.grid.lengths, periodic=self.operator.periodic,
                                      length_unit=length_unit, pressure_unit=pressure_unit))
        ds = to_dataset(state, dims=self.dims, coords=self.coords, length_unit=length_unit,
                        pressure_unit=pressure_unit, extra=extra)
        ds.attrs.update({"solver": state.solver, **self.attrs, "converged": int(state.converged), "wall_time": wall,
                         "contactlib_version": __version__, "window_lengths": list(self.grid.lengths)})
        if tol is not None:
            ds.attrs["tol"] = tol
        if np.all(state.pressure > 0):
            ds.attrs["full_contact"] = 1
            ds.attrs["full_contact_message"] = ("full contact: every element carries pressure, so the contact area "
                                                "cannot grow with the load (a thin remote-pressure layer wraps the "
                                                "surface at a lower load than a thick one)")
        else:
            ds.attrs["full_contact"] = 0
        if self.adhesion is not None:
            adhesive_contact.label(ds, state, self.adhesion, self, length_unit=length_unit,
                                   pressure_unit=pressure_unit)
        return ds

    def _friction_variables(self, state: ContactState, length_unit: str, pressure_unit: str) -> dict:
        """The tangential traction ``mu_c p s`` and (periodic) the tangential displacement it and the
        pressure cause; ``mu_a`` and ``mu = mu_c + mu_a``; sliding, the dissipated power (name: variable)."""
        mu, direction = self.attrs["friction"], self.attrs["sliding_direction"]
        axes = ("x", "y")[: self.grid.dim]
        components = (np.cos(direction), np.sin(direction))[: self.grid.dim]
        tractions = [mu * c * state.pressure for c in components] if mu > 0 else []
        variables = {}
        for axis, traction in zip(axes, tractions):
            name = f"tangential_traction_{axis}"
            variables[name] = xr.Variable(self.dims, traction, attrs_for(name, length=length_unit,
                                                                        pressure=pressure_unit))
        if self.body.tensor is not None and mu > 0:
            spectra = self.body.tensor.tangential_displacement(self.grid, fft.rfftn(state.pressure),
                                                               [fft.rfftn(t) for t in tractions])
            for axis, spectrum in zip(axes, spectra):
                name = f"tangential_displacement_{axis}"
                variables[name] = xr.Variable(self.dims, fft.irfftn(spectrum, self.grid.shape),
                                              attrs_for(name, length=length_unit, pressure=pressure_unit))
        # from the deformed surface: exactly zero on a decoupled elastic body, the dissipated power when sliding
        mu_a = interlocking_friction(state.pressure, state.displacement, lengths=self.grid.lengths,
                                     direction=direction, periodic=self.operator.periodic)
        variables["friction_coefficient_interlocking"] = xr.Variable((), mu_a,
                                                                     attrs_for("friction_coefficient_interlocking"))
        variables["friction_coefficient"] = xr.Variable((), mu + mu_a, attrs_for("friction_coefficient"))
        if "sliding_velocity" in self.attrs:  # elastic models dissipate nothing: their tensor is real
            velocity = self.attrs["sliding_velocity"]
            power = 0.0 if self.body.factor is None else traction_power(
                self.grid, state.pressure, self.body.tensor, velocity, friction=mu, direction=direction)
            variables["dissipated_power"] = xr.Variable((), power, attrs_for("dissipated_power", length=length_unit,
                                                                             pressure=pressure_unit))
        return variables

    def check_window(self, pressure: np.ndarray) -> None:
        """Refuse a non-periodic state that the window cuts: compression on its edge (the surface outside would carry
        load too) or, adhesive, its cohesive zone reaching the edge (tension above :data:`EDGE_TENSION` of the law's
        peak stress there; JKR, with no stress of its own, any tension: its contact edge is there)."""
        if self.operator.periodic:
            return
        jkr = self.adhesion is not None and not self.adhesion.cohesive
        if touches_edge(pressure) or (jkr and edge_tension(pressure, round_off_floor(pressure))):
            raise ValueError(
                "periodic=False: the contact reaches the edge of the window, so the surface outside it would "
                "carry load too; enlarge the window (or use periodic=True for a periodic surface)"
            )
        if self.adhesion is not None and not jkr and edge_tension(pressure, EDGE_TENSION * self.adhesion.peak_stress):
            raise ValueError(
                "periodic=False: the adhesive zone reaches the edge of the window (tension above "
                f"{EDGE_TENSION:g} of the law's peak stress there), so adhesion beyond it is cut off; enlarge the "
                "window (or use periodic=True for a periodic surface)"
            )

    def check(self, state: ContactState, ds: xr.Dataset) -> None:
        """Refuse a footprint cut by the window edge; raise :class:`ConvergenceError` if unconverged (first,
        for an adhesive solve: a diverged cohesive iterate can touch the edge, which would hide why), and
        :class:`contactlib.invariants.InvariantError` where a converged state breaks an invariant
        (:func:`contactlib.invariants.verify_solve`; ``ds.attrs['invariants_checked']`` names them)."""
        if state.converged or self.adhesion is None:
            self.check_window(state.pressure)
        if not state.converged:
            tol, max_iter = ds.attrs["tol"], self.solver_args["max_iter"]
            stalled = state.solver.startswith(("polonsky-keer", "coupled")) and state.iterations < max_iter
            outer = f" ({state.outer_iterations} outer)" if state.outer_iterations else ""
            message = (f"{state.solver} did not converge in {state.iterations} iterations{outer}: residual "
                       f"{state.residual:.3e} > tol {tol:.1e}"
                       + (" (stalled: no progress over the last iterations; round-off floor or an ill-posed scene)"
                          if stalled else "")
                       + (f"; {self.attrs['monotone_message']}" if self.attrs.get("monotone") == 0 else "")
                       + ("; if this tension is beyond the pull-off, no equilibrium exists under load control "
                          "(contactlib.adhesion_curve finds the pull-off; penetration control follows the branch "
                          "past it)"
                          if self.adhesion is not None and (self.solver_args["mean_pressure"] or 0.0) < 0 else ""))
            ds.attrs["convergence_message"] = message  # the partial state says why it is partial
            raise ConvergenceError(message, residual=state.residual, dataset=ds)
        from .invariants import verify_solve  # imported here: invariants subclasses this module's ConvergenceError
        verify_solve(self, state, ds)


def constrained_solve(operator, heights, *, monitor=None, verify_below=None, restart_fraction=None,
                      **args) -> ContactState:
    """Frictionless contact on a symmetric compliance: Polonsky-Keer, or its dual under periodic displacement
    control, where the primal iteration cannot be preconditioned (:mod:`contactlib.solvers.dual`), or, on a
    plate-like body (not :attr:`~contactlib.operators.Compliance.preconditionable`), the semismooth Newton
    method with a coarse space under either control (:mod:`contactlib.solvers.semismooth`).
    ``args``: ``mean_pressure``, ``penetration`` (one of them None), ``tol``, ``max_iter``, ``initial_pressure``;
    ``restart_fraction``: Polonsky-Keer's (default :data:`contactlib.solvers.ccg.RESTART_FRACTION`; the dual
    restarts on every re-entry)."""
    if not operator.preconditionable:
        # a plate-like body (a thin remote-pressure layer): its soft long waves need a coarse space, under
        # either control (the dual iteration stalled there beyond about 5 % contact at q0 h = 0.1)
        return solve_semismooth(operator, heights, monitor=monitor, set_floor=PLATE_SET_FLOOR, **args)
    if not operator.definite and args["penetration"] is not None:
        args = {k: v for k, v in args.items() if k != "mean_pressure"}
        return solve_periodic_displacement(operator, heights, monitor=monitor, verify_below=verify_below, **args)
    if restart_fraction is not None:
        args["restart_fraction"] = restart_fraction
    return solve_polonsky_keer(operator, heights, monitor=monitor, **args)


def _setup(heights, *, material, mean_pressure, penetration, periodic, tol, max_iter, kernel, method, length,
           initial_pressure, target_error, layer, friction, sliding_direction, sliding_velocity,
           adhesion=None) -> _Setup:
    """Validate every argument of :func:`solve` and build the body's operators."""
    values, grid, dims, coords = grid_of(heights, length)
    E, nu = material.E0, material.nu
    E_star = contact_modulus(E, nu)
    if adhesion is None:
        check_loads(mean_pressure, penetration)
    else:
        adhesive_contact.check(adhesion, values, spacing=grid.spacing, mean_pressure=mean_pressure,
                               penetration=penetration, friction=friction, method=method, periodic=periodic)
    if target_error is not None:
        if tol is not None:
            raise ValueError("give tol or target_error, not both")
        tol = accuracy.tolerance_for(target_error)
        if periodic:
            accuracy.check_resolution(values, target_error, length=grid.lengths)
    tol = (1e-8 if adhesion is None else adhesive_contact.DEFAULT_TOL) if tol is None else tol
    check_tolerance(tol, "tol")
    check_iterations(max_iter)
    if kernel not in KERNELS:
        raise ValueError(f"kernel must be one of {KERNELS}, got {kernel!r}")
    if method not in METHODS:
        raise ValueError(f"method must be one of {METHODS}, got {method!r}")
    check_friction(layer, friction, sliding_direction, nu, method, kernel, periodic)
    velocity, sliding_direction = check_velocity(sliding_velocity, sliding_direction, grid.dim, material, method,
                                                  periodic)
    if grid.dim == 1:
        if abs(math.sin(sliding_direction)) > 1e-4:  # pi to four decimals (3.1416) passes
            raise ValueError(f"sliding_direction must be 0 (+x) or pi (-x) for a profile (1D heights), got "
                             f"{sliding_direction!r}")
        sliding_direction = 0.0 if math.cos(sliding_direction) > 0 else math.pi  # 3.1416 from a command line: pi
    if adhesion is not None and velocity is not None and any(v != 0 for v in velocity):
        raise ValueError(f"sliding_velocity: adhesion is modelled at rest (a steady sliding adhesive contact is not "
                         f"supported), got sliding_velocity={sliding_velocity!r} with adhesion")
    warm = None
    if initial_pressure is not None:
        if method != "cg":
            raise ValueError(f"initial_pressure: a warm start is for method='cg', got method={method!r}")
        warm = real_values(initial_pressure, "initial_pressure")
        if warm.shape != values.shape:
            raise ValueError(f"initial_pressure has shape {warm.shape}, heights {values.shape}")
        if not np.all(np.isfinite(warm)):
            raise ValueError("initial_pressure contains NaN or infinite values")
    body = body_model(grid, material=material, layer=layer, friction=float(friction),
                      direction=float(sliding_direction), tol=tol, kernel=kernel, periodic=periodic, velocity=velocity)
    if not body.compliance.definite and penetration is not None:
        check_below_full_contact(penetration, values)
    attrs = {"kernel": kernel, "periodic": int(periodic), "tol": tol, "max_iter": int(max_iter), "E": float(E),
             "nu": float(nu), "E_star": E_star,
             "load_control": "mean_pressure" if mean_pressure is not None else "penetration", **body.attrs}
    if isinstance(material, Viscoelastic):
        attrs["prony"] = [v for branch in material.prony for v in branch]  # E_1, tau_1, E_2, tau_2, ...
    if velocity is not None:
        attrs["sliding_velocity"] = list(velocity)
    if target_error is not None:
        attrs["target_error"] = float(target_error)
    solver_args = {"mean_pressure": mean_pressure, "penetration": penetration, "tol": tol,
                   "max_iter": int(max_iter), "initial_pressure": warm}
    return _Setup(values, grid, dims, coords, body, solver_args, attrs, method, adhesion)
