"""A prepared problem: :func:`prepare` validates a scene once and builds its body; :class:`Problem` solves it at
any load, and :meth:`Problem.at_speed` moves it along a path of sliding speeds.

:func:`contactlib.solve` is ``prepare(heights, **scene).solve(**load)``. A problem is reused explicitly: a load sweep
calls :meth:`Problem.solve` at each load (the operator is built once), a speed sweep calls :meth:`Problem.at_speed`
at each speed (a new body, as the complex modulus at ``q . V`` changes with the speed, sharing the problem's caches:
the half-space Green's tensor, :class:`contactlib.model.bodies.KernelCache`, and, on request, the GMRES set solves'
Krylov vectors, :class:`contactlib.solvers.recycle.RecycledSpace`). The caches are fields of the problem, so they
live exactly as long as it does, and two problems never share them unless one was made from the other.

Which solver runs is chosen in one module per operator class: :mod:`contactlib.solvers.symmetric.choice`,
:mod:`contactlib.solvers.nonsymmetric.choice` and :mod:`contactlib.problems.adhesive_choice`.
"""

from __future__ import annotations

import dataclasses
import sys
import time

import numpy as np
import xarray as xr

from .. import accuracy, resolution
from . import adhesive_choice, adhesive, area_target
from ..core import fft
from .._version import __version__
from ..errors import ConvergenceError
from ..analysis.friction import interlocking_friction
from ..analysis.viscoelastic import traction_power
from ..model.bodies import BodyModel, KernelCache, body_model
from ..invariants import verify_solve
from ..core.inputs import (EDGE_TENSION, check_below_full_contact, check_loads, edge_tension, round_off_floor,
    solver_values, touches_edge)
from ..core.labels import attrs_for, field_variable, to_dataset, window_variables
from ..model.materials import Viscoelastic, contact_modulus
from .scene import Scene, scene_of
from ..solvers import ContactState
from ..solvers.nonsymmetric import choice as nonsymmetric_choice
from ..solvers.symmetric import choice as symmetric_choice
from ..solvers.recycle import RecycledSpace


@dataclasses.dataclass(eq=False, repr=False)
class Problem:
    """A validated contact scene, its body's operators and its caches (:func:`prepare`); solve it with
    :meth:`solve`.

    Public attributes (read them; a benchmark or a path driver may): :attr:`scene` (the validated inputs,
    :class:`contactlib.problems.scene.Scene`), :attr:`body` (:class:`contactlib.model.bodies.BodyModel`: the symmetric
    compliance, the skew part, the Green's tensor), :attr:`operator` (the compliance the solvers apply),
    :attr:`values` / :attr:`heights` (the heights on the grid), :attr:`grid`, :attr:`attrs` (what labels the
    answer), :attr:`solver_args` (``tol``, ``max_iter`` and, with a load, ``mean_pressure``, ``penetration``,
    ``initial_pressure``: the solvers' keyword arguments), :attr:`kernels` and :attr:`recycled` (the caches).

    Parameters
    ----------
    scene : contactlib.problems.scene.Scene
        The validated inputs.
    body : contactlib.model.bodies.BodyModel
        The body's operators.
    attrs : dict
        What labels the answer.
    solver_args : dict
        The solvers' keyword arguments (with a load once :meth:`loaded`).
    kernels : contactlib.model.bodies.KernelCache
        The Green's tensor cache, shared with the problems :meth:`at_speed` makes.
    recycled : contactlib.solvers.recycle.RecycledSpace, optional
        Krylov vectors carried between GMRES set solves (:meth:`recycling`).
    """

    scene: Scene
    body: BodyModel
    attrs: dict
    solver_args: dict
    kernels: KernelCache
    recycled: RecycledSpace | None = None

    values = property(lambda self: self.scene.values, doc="The heights [length] on the grid (an ndarray).")
    heights = values
    grid = property(lambda self: self.scene.grid, doc="The window's :class:`contactlib.Grid`.")
    dims = property(lambda self: self.scene.dims)
    coords = property(lambda self: self.scene.coords)
    method = property(lambda self: self.scene.method)
    adhesion = property(lambda self: self.scene.adhesion)

    def __repr__(self) -> str:
        load = {k: v for k, v in self.solver_args.items() if k in ("mean_pressure", "penetration") and v is not None}
        return (f"Problem(shape={self.grid.shape}, lengths={self.grid.lengths}, model={self.attrs['model']!r}, "
                f"tol={self.scene.tol!r}{''.join(f', {k}={v!r}' for k, v in load.items())})")

    @property
    def operator(self):
        """The symmetric compliance the solvers apply (:class:`contactlib.model.operators.Compliance`)."""
        return self.body.compliance

    def solve(self, *, mean_pressure: float | None = None, penetration: float | None = None,
              initial_pressure=None, contact_area: float | None = None) -> xr.Dataset:
        """The contact at one load: ``mean_pressure`` (load control) or ``penetration`` (displacement control), as
        :func:`contactlib.solve` documents them, from ``initial_pressure`` (a warm start, ``method="cg"``); or at
        the load whose contact area is ``contact_area`` (:mod:`contactlib.problems.area_target`).

        Parameters
        ----------
        mean_pressure, penetration : float, optional
            The load (one of them, or ``contact_area``).
        initial_pressure : xarray.DataArray or ndarray, optional
            Warm start: a solve's ``pressure`` (read by name) or a bare array indexed ``[ix, iy]``.
        contact_area : float, optional
            Target contact area fraction in (0, 1), instead of a load.

        Returns
        -------
        xarray.Dataset
            What :func:`contactlib.solve` returns. The problem itself is unchanged: solve it again at another load.

        Raises
        ------
        ValueError
            Naming a bad load or warm start.
        ConvergenceError
            As :func:`contactlib.solve`.
        """
        start = time.perf_counter()
        if contact_area is None:
            loaded = self.loaded(mean_pressure=mean_pressure, penetration=penetration,
                                 initial_pressure=initial_pressure)
            state = loaded.run()
        else:
            area_target.check(contact_area, mean_pressure=mean_pressure, penetration=penetration,
                              adhesion=self.adhesion)
            loaded, state = area_target.search(self, contact_area)
        if self.scene.target_error is not None and self.adhesion is None:
            state = accuracy.solve_on_for_scene(loaded, state)
        wall = time.perf_counter() - start
        ds = loaded.label(state, wall)
        loaded.check(state, ds)
        # the warning points at the caller: of this method, or of contactlib.solve, the facade that calls it
        facade = sys._getframe(1).f_globals.get("__name__") == "contactlib.problems.contact"
        resolution.guard_setup(loaded, state, ds, where="solve", guarantee=self.scene.target_error is not None,
                               stacklevel=5 + facade)
        return ds

    def loaded(self, *, mean_pressure=None, penetration=None, initial_pressure=None) -> Problem:
        """This problem with its load: a copy whose :attr:`solver_args` and ``attrs['load_control']`` hold it (the
        caches shared), refused with a ``ValueError`` naming a bad load or warm start. What the solvers run on."""
        scene = self.scene
        if self.adhesion is None:
            check_loads(mean_pressure, penetration)
        else:
            adhesive.check_load(self.adhesion, mean_pressure=mean_pressure, penetration=penetration)
        warm = None
        if initial_pressure is not None:
            if scene.method != "cg":
                raise ValueError(f"initial_pressure: a warm start is for method='cg', got method={scene.method!r}")
            warm = solver_values(initial_pressure, "initial_pressure")  # a DataArray by name, an ndarray [ix, iy]
            if warm.shape != scene.values.shape:
                raise ValueError(f"initial_pressure has shape {warm.shape}, heights {scene.values.shape}")
            if not np.all(np.isfinite(warm)):
                raise ValueError("initial_pressure contains NaN or infinite values")
        if not self.operator.definite and penetration is not None:
            check_below_full_contact(penetration, scene.values)
        items = [(k, list(v) if isinstance(v, list) else v) for k, v in self.attrs.items()]  # a Dataset's own lists
        at = [k for k, _ in items].index("E_star") + 1  # where solve has always put it
        control = "mean_pressure" if mean_pressure is not None else "penetration"
        attrs = dict(items[:at] + [("load_control", control)] + items[at:])
        args = {"mean_pressure": mean_pressure, "penetration": penetration, "tol": scene.tol,
                "max_iter": scene.max_iter, "initial_pressure": warm}
        return dataclasses.replace(self, attrs=attrs, solver_args=args)

    def at_speed(self, sliding_velocity) -> Problem:
        """The same scene sliding at ``sliding_velocity`` (validated as :func:`contactlib.solve`'s): a new body
        (the complex modulus at ``q.V`` is the speed's) built with this problem's caches, which the two then
        share. A method rather than a field, because the body, its reductions and its attrs follow from the
        speed: a problem is never left half-updated."""
        s = self.scene
        scene = scene_of(s.heights, material=s.material, periodic=s.periodic, tol=None if s.target_error else s.tol,
                         max_iter=s.max_iter, kernel=s.kernel, method=s.method, length=s.length,
                         target_error=s.target_error, layer=s.layer, friction=s.friction,
                         sliding_direction=s.sliding_direction_given,
                         sliding_velocity=sliding_velocity, adhesion=s.adhesion,
                         length_unit=s.length_unit, pressure_unit=s.pressure_unit)
        return _build(scene, self.kernels, self.recycled)

    def recycling(self, space: RecycledSpace | None = None) -> Problem:
        """This problem carrying Krylov vectors from GMRES set solve to set solve (:mod:`contactlib.solvers.recycle`)
        in ``space`` (a new one by default), across its solves and those of the problems :meth:`at_speed` makes."""
        return dataclasses.replace(self, recycled=RecycledSpace() if space is None else space)

    def run(self, monitor=None, verify_below=None) -> ContactState:
        """The state of a loaded problem (:meth:`loaded`), from the solver its operator class chooses;
        ``monitor``, ``verify_below``: see :func:`contactlib.solvers.symmetric.choice.constrained_solve`."""
        if self.adhesion is not None:
            return adhesive_choice.solve(self, self.adhesion)
        if self.body.coupling is not None:
            return nonsymmetric_choice.solve(self)
        return symmetric_choice.solve(self, monitor=monitor, verify_below=verify_below)

    def solve_symmetric(self, heights, *, monitor=None, verify_below=None, **args) -> ContactState:
        """The constrained solve of the symmetric compliance on ``heights`` (the whole problem, or an adhesive or
        coupled solve's inner one); ``args`` as :func:`contactlib.solvers.symmetric.choice.constrained_solve`."""
        return symmetric_choice.constrained_solve(self.operator, heights, monitor=monitor, verify_below=verify_below,
                                                  **args)

    def label(self, state: ContactState, wall: float, *, tol: float | None = None) -> xr.Dataset:
        """``state`` as :func:`contactlib.solve`'s Dataset, ``wall`` its ``attrs['wall_time']`` [s], ``tol`` (given)
        its ``attrs['tol']``."""
        length_unit, pressure_unit = self.scene.length_unit, self.scene.pressure_unit
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
            adhesive.label(ds, state, self.adhesion, self, length_unit=length_unit,
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
            variables[name] = field_variable(self.dims, traction, attrs_for(name, length=length_unit,
                                                                           pressure=pressure_unit))
        if self.body.tensor is not None and mu > 0:
            spectra = self.body.tensor.tangential_displacement(self.grid, fft.rfftn(state.pressure),
                                                               [fft.rfftn(t) for t in tractions])
            for axis, spectrum in zip(axes, spectra):
                name = f"tangential_displacement_{axis}"
                variables[name] = field_variable(self.dims, fft.irfftn(spectrum, self.grid.shape),
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
        verify_solve(self, state, ds)


def prepare(heights, *, E: float | None = None, nu: float | None = None, material=None, layer=None,
            friction: float = 0.0, sliding_direction: float | None = None, sliding_velocity=None, adhesion=None,
            periodic: bool | None = None, length=None, tol: float | None = None, max_iter: int = 10_000,
            kernel: str = "spectral", method: str = "cg", target_error: float | None = None,
            length_unit: str = "m", pressure_unit: str = "Pa") -> Problem:
    """Validate a scene and build its body, once: a :class:`Problem` to solve at one or many loads.

    The scene is every argument of :func:`contactlib.solve` but the load (``mean_pressure``, ``penetration``) and the
    warm start (``initial_pressure``), which :meth:`Problem.solve` takes, with the same meanings: the material
    (``E``, ``nu`` or ``material``), the body (``layer``), the interface (``friction``, ``sliding_direction``,
    ``sliding_velocity``, ``adhesion``), the window (``periodic``, ``length``) and the options (``tol``,
    ``max_iter``, ``kernel``, ``method``, ``target_error``, ``length_unit``, ``pressure_unit``). A bad one is refused
    here with the ``ValueError`` :func:`contactlib.solve` raises for it.

    Parameters
    ----------
    heights : xarray.DataArray or ndarray
        Rigid surface heights [length], as :func:`contactlib.solve`: a DataArray's ``x`` and ``y`` read by name, a
        bare array indexed ``[ix, iy]`` (``surface.transpose("x", "y").values``) with ``length``.
    E, nu : float
        Young's modulus [pressure] and Poisson ratio (or ``material``).
    material : contactlib.Elastic or contactlib.Viscoelastic, optional
        The body's material.
    layer : contactlib.Layer, optional
        A finite layer instead of the half-space.
    friction : float
        Coulomb coefficient ``mu_c >= 0``.
    sliding_direction : float, optional
        Direction of the rigid surface's motion [rad].
    sliding_velocity : float or sequence of float, optional
        Steady sliding velocity [length/time], one component per axis of the heights.
    adhesion : contactlib.Adhesion, optional
        An adhesive interface.
    periodic : bool, optional
        Periodic window or an isolated footprint.
    length : float or tuple, optional
        Window size [length], required for bare-array heights.
    tol : float, optional
        Target of the scale-free residual.
    max_iter : int
        Iteration bound of a solve.
    kernel : {"spectral", "love"}
        The half-space's kernel.
    method : {"cg", "active-set"}
        The symmetric solver.
    target_error : float, optional
        Relative error wanted on the contact area (picks ``tol``).
    length_unit, pressure_unit : str
        udunits strings written to the outputs' ``units`` attributes.

    Returns
    -------
    Problem
        The validated scene with its body's operators and caches.

    Raises
    ------
    ValueError
        Naming the argument, as :func:`contactlib.solve` does.

    Examples
    --------
    >>> import contactlib
    >>> h = contactlib.surfaces.self_affine(64, hurst=0.8, q_roll=2, q_cutoff=16, rms_slope=0.1, seed=1)
    >>> problem = contactlib.prepare(h, E=1.0, nu=0.5)
    >>> areas = [float(problem.solve(mean_pressure=p).contact_area) for p in (0.01, 0.02)]
    >>> areas[0] < areas[1]
    True
    """
    scene = scene_of(heights, E=E, nu=nu, material=material, periodic=periodic, tol=tol, max_iter=max_iter,
                     kernel=kernel, method=method, length=length, target_error=target_error, layer=layer,
                     friction=friction, sliding_direction=sliding_direction, sliding_velocity=sliding_velocity,
                     adhesion=adhesion, length_unit=length_unit, pressure_unit=pressure_unit)
    return _build(scene, KernelCache(), None)


def _build(scene: Scene, kernels: KernelCache, recycled: RecycledSpace | None) -> Problem:
    """The body of a validated scene and the attrs that label its answers."""
    material = scene.material
    body = body_model(scene.grid, material=material, layer=scene.layer, friction=scene.friction,
                      direction=scene.sliding_direction, tol=scene.tol, kernel=scene.kernel, periodic=scene.periodic,
                      velocity=scene.velocity, kernels=kernels)
    E, nu = material.E0, material.nu
    attrs = {"kernel": scene.kernel, "periodic": int(scene.periodic), "tol": scene.tol, "max_iter": scene.max_iter,
             "E": float(E), "nu": float(nu), "E_star": contact_modulus(E, nu), **body.attrs}
    if isinstance(material, Viscoelastic):
        attrs["prony"] = [v for branch in material.prony for v in branch]  # E_1, tau_1, E_2, tau_2, ...
    if scene.velocity is not None:
        attrs["sliding_velocity"] = list(scene.velocity)
    if scene.target_error is not None:
        attrs["target_error"] = scene.target_error
    args = {"mean_pressure": None, "penetration": None, "tol": scene.tol, "max_iter": scene.max_iter,
            "initial_pressure": None}
    return Problem(scene, body, attrs, args, kernels, recycled)
