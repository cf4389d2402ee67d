"""The two-scale method on an elastic half-space: :func:`solve`, macro-scale forces per asperity with their
elastic interaction, then (``scale="both"``) the micro-scale local FFT solves around each contact."""

from __future__ import annotations

import time

import numpy as np
import xarray as xr

from .._version import __version__
from ..errors import ConvergenceError
from ..invariants import verify_two_scale
from ..core.inputs import number
from ..core.labels import SOLVER_AXES, attrs_for, dataset, field_dims, field_values
from ..model.materials import contact_modulus
from ..model.operators import Compliance
from ..resolution import guard_asperities
from .asperities import AsperityTable
from .interaction import ACCURACY, PointInteraction
from .laws import TabulatedLaw
from .macro import FiniteSize, HertzLaw, MacroState, solve_macro
from .micro import MicroState, hertz_pressure_field, solve_micro, window_size
from .scene import MACRO_TOL, SCALES, check_separate_contacts, solver_tolerances, table_with_grid

INTERACTION_ACCURACY_FACTOR = 0.1
"""Two-scale: the Ewald products' accuracy (:class:`.PointInteraction`) as a fraction of ``macro_tol``, between
:data:`.interaction.ACCURACY` (1e-7) and :data:`INTERACTION_ACCURACY_MAX` (``scale="macro"``:
:data:`MACRO_ACCURACY`): the Newton residual is measured with the same products, so their error moves the forces by
at most about as much, a tenth of the tolerance. The two-scale sweeps use them only in the coarse correction,
which changes a sweep's contraction, not its fixed point (``micro.COARSE_RTOL``, 1e-2 to 1e-4); they get the same
accuracy (1e-5 at ``force_tol`` 1e-2, 1e-7 at ``tol`` 1e-6)."""
INTERACTION_ACCURACY_MAX = 1e-5
"""The loosest Ewald products of the two-scale method (7 x 7 Gaussian nodes at 1e-4 against 9 x 9 at 1e-5)."""
UNRESOLVED_CONTACT = 2.0
"""A micro step that does not converge while the largest macro contact radius is below this many grid spacings says
the contacts are not resolved: on fields of 10-300 asperities pressed by a hundredth of their height (contact radii
a seventh of the grid spacing, 2-45 nodes in contact in all) the outer iteration under load control did not settle
in 200 iterations, where penetration control converged in 4-5."""
MACRO_ACCURACY = 1e-4
"""``scale="macro"``: the Ewald products' accuracy at the default ``macro_tol`` (1e-4) and looser; ``macro_tol``
itself below it (no less than :data:`.interaction.ACCURACY`). The Newton residual is measured with these
products, yet at 10^3 asperities (coverage 0.05 / 0.2 / 0.4) their error at 1e-4 moved the forces from the
converged ones only by 0.8 / 2.1 / 10.4e-5 of the largest, against 0.4 / 1.0 / 8.7e-5 at 1e-5, and from the full
solver's by the same 3.4 / 4.5 / 3.7e-3 to two digits (the point-load model's error, 35x larger); a residual
product 0.14 -> 0.10 ms (7 x 7 nodes on an 80^2 mesh instead of 9 x 9 on 100^2)."""



def _material(material, E, nu) -> tuple[float, float]:
    """``(E, nu)`` from a material object with attributes ``E`` and ``nu``, or from the keywords."""
    if material is not None:
        if E is not None or nu is not None:
            raise ValueError("material: give material=... or E= and nu=, not both")
        if not (hasattr(material, "E") and hasattr(material, "nu")):
            raise ValueError(f"material must have attributes E and nu (an elastic material), got {material!r}")
        E, nu = material.E, material.nu
    if E is None or nu is None:
        raise ValueError("material: give material=contactlib.Elastic(E, nu) or both E= and nu=")
    return E, nu


def solve(
    asperities,
    *,
    material=None,
    E: float | None = None,
    nu: float | None = None,
    mean_pressure: float | None = None,
    penetration: float | None = None,
    scale: str = "two-scale",
    law: TabulatedLaw | None = None,
    periodic: bool | None = None,
    length: float | None = None,
    n: int | None = None,
    tol: float = 1e-6,
    force_tol: float | None = None,
    macro_tol: float | None = None,
    finite_size: bool = True,
    max_iter: int = 200,
    fields: bool = True,
    length_unit: str = "m",
    pressure_unit: str = "Pa",
) -> xr.Dataset:
    """Normal contact of a rigid field of spherical asperities on an elastic half-space, by the
    two-scale method.

    Parameters
    ----------
    asperities : xarray.DataArray or xarray.Dataset
        The heights from :func:`contactlib.surfaces.spheres` (they carry their asperity table, and
        their grid is the micro scale's), or a Dataset with ``center_x``, ``center_y``, ``radius``,
        ``summit_height`` [length] on an ``asperity`` dimension (window in ``attrs['length']`` or
        ``length``; the micro scale then builds the caps on an ``n x n`` grid).
    material : object with attributes ``E`` [pressure] and ``nu`` [1], optional
        E.g. ``contactlib.Elastic(E, nu)``; or give ``E`` and ``nu``.
    E, nu : float, optional
        Young's modulus [pressure] and Poisson ratio.
    mean_pressure : float
        Load control: total force over the window area [pressure].
    penetration : float
        Displacement control: rigid approach from first contact of the highest point [length] (the
        highest grid node when there is a grid, as :func:`contactlib.solve`, else the highest summit).
        Periodic: measured against the mean deformed plane, as in :func:`contactlib.solve`.
    scale : {"two-scale", "macro"}
        ``"macro"``: forces from Hertz's law with the point-load interaction only (seed eq. 3);
        ``"two-scale"``: then the local FFT solves to the full solver's answer.
    law : TabulatedLaw, optional
        The single-asperity law of every asperity: default Hertz's with each one's ``radius``; a
        :func:`tabulated_law` for asperities of another shape (all of that shape, each at its own
        ``summit_height``): the footprints are then the law's ``footprint_radius`` and ``radius`` is
        not used. It must be tabulated with the same material.
    periodic : bool, optional
        Default: the input's ``attrs['periodic']``, else True.
    length : float, optional
        Window size [length] for a Dataset.
    n : int, optional
        Grid points per side for the micro scale of a Dataset.
    tol : float
        Two-scale: largest relative change of the pressure field between outer iterations [1].
    force_tol : float, optional
        Two-scale: stop instead when no asperity force changes between outer iterations by more than
        ``force_tol`` times the largest force (and, under load control, the total force is within
        ``force_tol``) [1]; ``tol`` is then unused. The sweep contracts the force error by about 10x
        on every field measured (``benchmarks/RESULTS.md``), so the forces are then well within
        ``force_tol`` of the full solver's: the choice for a target error in the forces. Local solves
        run at 0.1 of ``force_tol`` (or of ``tol``), in single precision when that is 1e-4 or more
        (their rounding, about 1e-6 of the displacement, is then far below it;
        ``micro.SINGLE_PRECISION_TOL``).
    macro_tol : float, optional
        Macro: Newton residual, relative to the largest local penetration [1]. Default for
        ``scale="macro"``: 1e-4 (:data:`MACRO_TOL`), which leaves the forces within about 1e-4 of the
        largest of the converged ones, 30-60x below the point-load model's own error (0.3-0.6 % of
        the largest force against the full solver). Default for ``"two-scale"``: 1e-2 of ``force_tol``
        (else of ``tol``), between 1e-8 and 1e-4 (:data:`START_TOL_FACTOR`): the macro forces only start the
        sweeps, whose answer does not depend on them.
    finite_size : bool
        Macro: add the finite size of the Hertz contacts to the point-load interaction
        (:class:`.macro.FiniteSize`; with the default Hertz law only): at 10^3 asperities it takes the macro
        step's error at coverage 0.4 from 1.1e-2 to 3.7e-3 of the largest force (the total force's from 1.3e-2 to
        1.1e-3) at no extra product.
        :func:`solve_transient` applies it at each step's effective modulus.
    max_iter : int
        Newton iterations (macro) and outer iterations (two-scale) at most.
    fields : bool
        Also return ``pressure``, ``gap`` and ``displacement`` on the grid (for ``"macro"``: Hertz's
        pressure of each force, and its displacement by one FFT).
    length_unit, pressure_unit : str
        udunits strings for the labels.

    Returns
    -------
    xarray.Dataset
        ``force`` [force], ``contact_radius`` [length], ``local_penetration`` [length] and
        ``macro_force`` on the ``asperity`` dimension (coords ``center_x``, ``center_y``, ``radius``,
        ``summit_height``); scalars ``contact_area``, ``mean_pressure``, ``penetration``,
        ``iterations``, ``residual``; with a grid and ``fields``, ``pressure``, ``gap``,
        ``displacement`` on ``x``, ``y``. ``attrs`` hold the parameters, the interaction method, the
        iterations of both scales, ``wall_time`` [s] and the version.

    Raises
    ------
    ValueError
        Bad input, naming the parameter (see :func:`.asperity_table`), or a load beyond what separate
        spherical contacts carry (a cap pressed down to its base, the body reaching the base plane): under
        load control the message names the largest mean pressure the separate caps carry on the field, and
        where they stop (found by bisecting displacement-controlled macro solves, only on refusal).
    ConvergenceError
        When the Newton iteration or the outer iteration does not reach its tolerance; it holds the
        residual and the partial Dataset.

    Examples
    --------
    >>> import contactlib
    >>> h = contactlib.surfaces.spheres(256, radius=0.5, lattice=4, summit_height=0.01, height_std=0.001)
    >>> out = contactlib.two_scale.solve(h, E=1.0, nu=0.5, mean_pressure=1e-4)
    >>> out.force.dims
    ('asperity',)
    """
    E, nu = _material(material, E, nu)
    E_star = contact_modulus(E, nu)
    if scale not in SCALES:
        raise ValueError(f"scale must be one of {SCALES}, got {scale!r}")
    if (mean_pressure is None) == (penetration is None):
        raise ValueError("give exactly one of mean_pressure or penetration")
    if mean_pressure is not None:
        mean_pressure = number("mean_pressure", mean_pressure, lower=0.0)
    if penetration is not None:
        penetration = number("penetration", penetration)
    macro_tol = solver_tolerances(scale, tol=tol, force_tol=force_tol, macro_tol=macro_tol, max_iter=max_iter,
                                  macro_default=MACRO_TOL)
    if law is not None:
        if not isinstance(law, TabulatedLaw):
            raise ValueError(f"law must be None (Hertz) or a contactlib.two_scale.tabulated_law(...), got {law!r}")
        law_E_star = law.attrs.get("law_E_star", E_star)
        if abs(law_E_star / E_star - 1) > 1e-12:
            raise ValueError(f"law: tabulated with E* = {law_E_star!r}, the material has E* = {E_star!r}")
    table = table_with_grid(asperities, length=length, periodic=periodic, n=n, scale=scale, law=law)
    if law is not None and scale == "two-scale" and table.grid is None:
        raise ValueError("law: the two-scale method with a tabulated law needs the heights on a grid (a DataArray)")
    z_top = float(table.summit_height.max()) if table.heights is None else \
        table.highest if table.highest is not None else float(table.heights.max())
    total_force = None if mean_pressure is None else float(mean_pressure) * table.length**2

    start = time.perf_counter()
    accuracy = min(max(macro_tol, ACCURACY), MACRO_ACCURACY) if scale == "macro" else \
        min(max(INTERACTION_ACCURACY_FACTOR * macro_tol, ACCURACY), INTERACTION_ACCURACY_MAX)
    interaction = PointInteraction(table, E_star, accuracy=accuracy)
    law = HertzLaw(table.radius, E_star) if law is None else law
    correction = FiniteSize(table, E_star) if finite_size and isinstance(law, HertzLaw) else None  # Hertz's pressure
    try:
        macro = solve_macro(table, interaction, law, penetration=penetration, total_force=total_force, z_top=z_top,
                            tol=macro_tol, max_iter=int(max_iter), finite_size=correction)
    except ValueError as err:  # Newton lost every contact: the load presses the body past the separate caps
        if total_force is None or "no asperity in contact" not in str(err):
            raise
        limit = _separate_caps_limit(table, interaction, law, correction, z_top, macro_tol, int(max_iter))
        raise ValueError(_beyond_separate_caps(mean_pressure, *limit)) from None
    macro_wall = time.perf_counter() - start
    params = {"scale": scale, "E": float(E), "nu": float(nu), "E_star": E_star, "periodic": int(table.periodic),
              "load_control": "mean_pressure" if mean_pressure is not None else "penetration", "tol": tol,
              "force_tol": float("nan") if force_tol is None else force_tol,
              "macro_tol": macro_tol, "max_iter": int(max_iter), "single_asperity_law": "hertz",
              **(law.attrs if isinstance(law, TabulatedLaw) else {}),
              "finite_size_correction": int(correction is not None), "macro_iterations": macro.iterations,
              "macro_residual": macro.residual, "macro_wall_time": macro_wall,
              "contactlib_version": __version__, "window_lengths": [table.length, table.length],
              "Conventions": "CF-1.10", **interaction.attrs}
    if not macro.converged:
        ds = _label(table, macro, None, params, law, E_star, z_top, length_unit, pressure_unit, fields=False)
        ds.attrs["converged"] = 0
        try:  # an iteration that wandered past the method's assumption: say so (the likelier cause)
            check_separate_contacts(table, law, macro, z_top)
            why = ""
        except ValueError as err:
            why = f"; its last iterate is past the method's assumption ({err})"
        ds.attrs["convergence_message"] = (f"two_scale macro step: Newton did not converge in {macro.iterations} "
                                           f"iterations: residual {macro.residual:.3e} > macro_tol {macro_tol:.1e}{why}")
        raise ConvergenceError(ds.attrs["convergence_message"], residual=macro.residual, dataset=ds)
    try:
        check_separate_contacts(table, law, macro, z_top)
    except ValueError:
        if total_force is None:
            raise
        limit = _separate_caps_limit(table, interaction, law, correction, z_top, macro_tol, int(max_iter))
        raise ValueError(_beyond_separate_caps(mean_pressure, *limit)) from None
    if isinstance(law, TabulatedLaw) and np.any(macro.local_penetration > law.max_penetration):
        raise ValueError(f"law: the local penetration {float(macro.local_penetration.max()):.4g} exceeds the "
                         f"table's max_penetration {law.max_penetration:.4g}: tabulate further")
    micro = None
    if scale == "two-scale":
        micro = solve_micro(table, macro, law, E_star, interaction, z_top=z_top, total_force=total_force, tol=tol,
                            max_iter=int(max_iter), force_tol=force_tol)
        params.update(micro_iterations=micro.iterations, local_iterations=micro.local_iterations,
                      micro_change=micro.change, micro_force_change=micro.force_change, micro_window=micro.window)
    params["wall_time"] = time.perf_counter() - start
    ds = _label(table, macro, micro, params, law, E_star, z_top, length_unit, pressure_unit, fields=fields)
    if micro is not None and not micro.converged:
        message = (f"two_scale micro step did not converge in {micro.iterations} outer iterations: pressure change "
                   f"{micro.change:.3e} > tol {tol:.1e}" if force_tol is None else
                   f"two_scale micro step did not converge in {micro.iterations} outer iterations: force change "
                   f"{micro.force_change:.3e} > force_tol {force_tol:.1e}")
        spacing, radius = min(table.grid.spacing), float(np.max(law.contact_radius(macro.local_penetration)))
        if radius < UNRESOLVED_CONTACT * spacing:
            message += (f"; the largest contact (macro radius {radius:.3g}) spans less than {UNRESOLVED_CONTACT:g} grid "
                        f"spacings ({spacing:.3g}): the micro scale does not resolve the contacts (refine the grid, or "
                        "use scale='macro')")
        ds.attrs["converged"] = 0
        ds.attrs["convergence_message"] = message
        raise ConvergenceError(message, residual=micro.change if force_tol is None else micro.force_change, dataset=ds)
    verify_two_scale(ds, table.heights, scale=scale, tol=tol if force_tol is None else force_tol, macro_tol=macro_tol,
                     mean_pressure=mean_pressure, penetration=penetration)
    if micro is not None:  # the macro step is Hertz's law itself: only the micro solves have a grid to resolve
        guard_asperities(ds, ds["contact_radius"].values, min(table.grid.spacing), max(table.grid.shape))
    return ds


LIMIT_RTOL = 1e-3
"""The approach at which separate caps end, found to this fraction of the highest point's height (a refusal's
bisection: about 10 displacement-controlled macro solves)."""


def _separate_caps_limit(table: AsperityTable, interaction, law, correction, z_top: float, macro_tol: float,
                         max_iter: int) -> tuple[float, float, str]:
    """``(mean_pressure, approach, why)``: the largest mean pressure [pressure] that separate spherical caps carry on
    this field, the approach [length] where it is reached, and what breaks just beyond it (a cap pressed to its
    base, or the body on the base plane): displacement-controlled macro solves bisected on the approach between
    first contact and the base plane (where the body always meets the base), to :data:`LIMIT_RTOL` of ``z_top``."""
    def broken(delta):
        state = solve_macro(table, interaction, law, penetration=delta, z_top=z_top, tol=macro_tol, max_iter=max_iter,
                            finite_size=correction)
        try:
            check_separate_contacts(table, law, state, z_top)
        except ValueError as err:
            message = str(err)  # without its "mean_pressure/penetration: ... carry:" preamble
            return message.split("carry: ", 1)[-1] if "carry: " in message else message.split(": ", 1)[-1], state
        return ("" if state.converged else "the macro Newton iteration does not converge"), state

    lo, hi = 0.0, z_top
    why, _ = broken(hi)
    carried = 0.0
    while hi - lo > LIMIT_RTOL * z_top:
        mid = 0.5 * (lo + hi)
        reason, state = broken(mid)
        if reason:
            hi, why = mid, reason
        else:
            lo, carried = mid, float(np.sum(state.force))
    return carried / table.length**2, lo, why


def _beyond_separate_caps(mean_pressure: float, limit: float, approach: float, why: str) -> str:
    """The refusal of a load beyond :func:`_separate_caps_limit`'s: where the assumption breaks, and at what load."""
    return (f"mean_pressure {mean_pressure!r} is beyond what separate spherical caps carry on this field: they carry "
            f"at most a mean pressure of about {limit:.4g} (approach {approach:.4g}); just beyond it {why}. The "
            f"two-scale method assumes separate contacts: ask for less than {limit:.4g}, or solve the heights with "
            "contactlib.solve")


def _label(table: AsperityTable, macro: MacroState, micro: MicroState | None, params: dict, law, E_star: float,
           z_top: float, length_unit: str, pressure_unit: str, *, fields: bool) -> xr.Dataset:
    """The labelled Dataset: per-asperity variables, scalars, and fields on the grid when asked."""
    def a(name):
        return attrs_for(name, length=length_unit, pressure=pressure_unit)

    macro_radius = law.contact_radius(macro.local_penetration)
    area = table.length**2
    coords = {"asperity": ("asperity", np.arange(table.count), a("asperity")),
              "center_x": ("asperity", table.centers[:, 0], a("center_x")),
              "center_y": ("asperity", table.centers[:, 1], a("center_y")),
              "radius": ("asperity", table.radius, a("radius")),
              "summit_height": ("asperity", table.summit_height, a("summit_height"))}
    data = {"macro_force": ("asperity", macro.force, a("macro_force")),
            "local_penetration": ("asperity", macro.local_penetration, a("local_penetration"))}
    if micro is None:
        force, radius = macro.force, macro_radius
        contact_area = float(np.sum(np.pi * macro_radius**2)) / area
        penetration, iterations, residual = macro.penetration, macro.iterations, macro.residual
    else:
        node_area = table.grid.element_area
        force, radius = micro.force, np.sqrt(micro.contact_nodes * node_area / np.pi)
        contact_area = float(micro.contact_nodes.sum()) / micro.pressure.size  # all the pressure is on footprints
        penetration, iterations, residual = micro.penetration, micro.iterations, micro.residual
    data["force"] = ("asperity", force, a("force"))
    data["contact_radius"] = ("asperity", radius, a("contact_radius"))
    scalars = {"contact_area": contact_area, "mean_pressure": float(np.sum(force)) / area,
               "penetration": penetration, "iterations": iterations, "residual": residual}
    data.update({k: ((), v, a(k)) for k, v in scalars.items()})
    if fields and table.grid is not None:
        grid = table.grid
        if micro is not None:
            pressure, displacement, gap = micro.pressure, micro.displacement, micro.gap
        else:
            window = window_size(table, grid=grid, contact_radius=macro_radius)
            pressure = hertz_pressure_field(table, grid, macro.force, macro_radius, window)
            displacement = Compliance(grid, E_star=E_star, periodic=table.periodic)(pressure)
            gap = displacement + z_top - table.heights - macro.penetration
        xs = grid.coordinates()
        coords["x"] = ("x", xs[0], a("x"))
        coords["y"] = ("y", xs[1], a("y"))
        for name, value in (("pressure", pressure), ("displacement", displacement), ("gap", gap)):
            data[name] = (field_dims(SOLVER_AXES), field_values(SOLVER_AXES, value), a(name))  # [ix, iy] on (y, x)
    attrs = {**params, "converged": params.get("converged", 1), "title": "two-scale asperity contact (seed paper 1)",
             "source": f"contactlib {__version__}, contactlib.two_scale.solve"}
    return dataset(data, coords, attrs)
