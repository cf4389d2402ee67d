"""Public entry points for normal contact, elastic or viscoelastic, at rest or sliding: :func:`solve` (one load) and
:func:`solve_tolerances` (one load, several tolerances), both on a prepared :class:`contactlib.Problem`."""

from __future__ import annotations

import dataclasses
import time

import numpy as np
import xarray as xr

from .. import resolution
from ..model.bodies import Layer
from ..core.inputs import check_tolerance, real_values
from ..model.materials import Elastic, Viscoelastic
from ..errors import ConvergenceError
from .problem import prepare
from ..solvers import ContactState

__all__ = ["solve", "solve_tolerances", "ConvergenceError"]


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
    comm=None,
) -> xr.Dataset:
    """Normal contact of a rigid rough surface on an elastic or viscoelastic half-space or layer, with
    Coulomb friction and steady sliding: ``prepare(heights, **scene).solve(mean_pressure=..., penetration=...,
    initial_pressure=...)`` (:func:`contactlib.prepare`), the scene being every argument but the load and the warm
    start.

    Parameters
    ----------
    heights : xarray.DataArray or ndarray
        Rigid surface heights [length], 1D (plane strain, per unit width) or 2D. Higher points
        touch first. A DataArray's coordinates give the physical size, and its ``x`` and ``y`` dimensions are read
        by name (either order); an ndarray needs ``length`` and is indexed ``[ix, iy]`` (rows along x; a
        DataArray surface's is ``surface.transpose("x", "y").values``).
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
    initial_pressure : xarray.DataArray or ndarray, optional
        Warm start for ``method="cg"``: a solve's ``pressure`` (read by name), or an ndarray indexed ``[ix, iy]``.
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
        zero-padded, on a window of at least :data:`contactlib.model.bodies.LAYER_WINDOW` (6) thicknesses.
    friction : float
        Coulomb coefficient ``mu_c >= 0``: on the contact the body carries the tangential traction
        ``mu_c p`` along ``sliding_direction``. Through the normal-tangential terms of the Green's
        tensor it moves the surface normally (material coupling, ``nu < 0.5``; geometric, a finite
        layer), which makes the pressure asymmetric (:mod:`contactlib.solvers.nonsymmetric.coupled`).
    sliding_direction : float, optional
        Direction [rad, in the x-y plane] in which the rigid surface moves relative to the body;
        a profile slides along ``+x`` (give 0, or pi to slide along ``-x``). Default: the direction
        of ``sliding_velocity``, else 0; a direction that contradicts the velocity is refused.
    adhesion : contactlib.Adhesion, optional
        An adhesive interface (:mod:`contactlib.model.adhesion`): a cohesive law inside the contact solve, or
        ``"jkr"``, the energy balance (a profile symmetric about its highest point, or a surface of
        revolution). Frictionless and at rest (``friction`` and a nonzero ``sliding_velocity`` are
        refused; a viscoelastic body at rest is its relaxed elastic body);
        ``mean_pressure`` (the applied traction, adhesive part included) and ``penetration`` may then be
        negative. Adds ``adhesive_pressure`` (the tensile part of ``pressure``) and ``interaction_area``;
        ``contact_area`` is the repulsive (closed) area (:mod:`contactlib.problems.adhesive`).
    contact_area : float, optional
        Solve to this contact area fraction in (0, 1) instead of a load: the state whose area is nearest it on the
        grid (the area rises in whole elements), with the ``mean_pressure`` that gives it, found by bracketing the
        load over solves of one scene (:mod:`contactlib.problems.area_target`); ``attrs['target_contact_area']``. Not
        with ``mean_pressure``, ``penetration`` or ``adhesion``.
    comm : mpi4py.MPI.Comm, optional
        Solve one scene over the ranks of ``comm`` (the ``mpi`` extra): each rank passes its own rows of the heights
        (:func:`contactlib.distributed.slabs.slab_of`) or the generator's arguments, and gets its rows of the answer
        (:mod:`contactlib.distributed.dataset`: a 2D elastic half-space or periodic layer, frictionless, at rest;
        the other options are refused by name).

    Returns
    -------
    xarray.Dataset
        ``pressure``, ``gap``, ``displacement`` fields (2D: on dims ``("y", "x")``, so that ``.plot()`` draws x
        horizontally; select by name, ``.sel(x=..., y=...)``) and scalars ``contact_area``,
        ``mean_pressure``, ``penetration``, ``mean_gap``, ``iterations``, ``residual``; non-periodic, the load as
        a force and the contact's size (:func:`contactlib.core.labels.window_variables`): ``normal_force``
        (``mean_pressure`` times the window area) and ``contact_radius`` (``sqrt(A / pi)``), or on a profile
        ``line_load`` and ``contact_half_width``; with friction, also the
        tangential traction and (periodic) the tangential displacement fields, and
        ``friction_coefficient_interlocking`` (``mu_a``, :func:`interlocking_friction`) and
        ``friction_coefficient`` (``mu_c + mu_a``); sliding (``sliding_velocity``), also those two and
        ``dissipated_power`` (:func:`contactlib.analysis.traction_power`). ``attrs['model']`` says which model ran
        (:mod:`contactlib.model.bodies`: the half-space where a layer is within tolerance of it, no
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
    if comm is not None:  # one scene over MPI ranks, each with its rows (imports mpi4py only here)
        from ..distributed.dataset import solve as solve_distributed

        return solve_distributed(heights, comm=comm, E=E, nu=nu, material=material, layer=layer, periodic=periodic,
                                 length=length, tol=tol, max_iter=max_iter, mean_pressure=mean_pressure,
                                 penetration=penetration, length_unit=length_unit, pressure_unit=pressure_unit,
                                 friction=friction, sliding_direction=sliding_direction,
                                 sliding_velocity=sliding_velocity, adhesion=adhesion, kernel=kernel, method=method,
                                 initial_pressure=initial_pressure, target_error=target_error,
                                 contact_area=contact_area)
    problem = prepare(heights, E=E, nu=nu, material=material, layer=layer, friction=friction,
                      sliding_direction=sliding_direction, sliding_velocity=sliding_velocity, adhesion=adhesion,
                      periodic=periodic, length=length, tol=tol, max_iter=max_iter, kernel=kernel, method=method,
                      target_error=target_error, length_unit=length_unit, pressure_unit=pressure_unit)
    return problem.solve(mean_pressure=mean_pressure, penetration=penetration, initial_pressure=initial_pressure,
                         contact_area=contact_area)


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
    problem = prepare(heights, E=E, nu=nu, periodic=periodic, tol=min(tols), max_iter=max_iter, kernel=kernel,
                      length=length, length_unit=length_unit, pressure_unit=pressure_unit)
    setup = problem.loaded(mean_pressure=mean_pressure, penetration=penetration, initial_pressure=initial_pressure)
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
        ds = setup.label(state, 0.0, tol=t)
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
