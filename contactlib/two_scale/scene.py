"""What :func:`contactlib.two_scale.solve` and :func:`contactlib.two_scale.solve_transient` share: the checks of
their options, the asperity table on its grid, and the limit of separate spherical contacts; one path for both, so
that a driver adds its own path (the times and loads of a series) and no copy of these."""

from __future__ import annotations

import math
import numbers

import numpy as np

from .. import surfaces
from ..core.inputs import check_iterations, check_tolerance, check_whole
from .asperities import AsperityTable, asperity_table
from .macro import HertzLaw, MacroState

SCALES = ("macro", "two-scale")
"""The methods: the macro step alone (per-asperity forces with their interaction) or with the local FFT solves."""

MACRO_TOL = 1e-4
"""Default ``macro_tol`` of ``scale="macro"``: the forces within about 1e-4 of the largest of the converged ones
(0.1-1.04e-4 measured at 300 and 10^3 asperities; the residual is measured with Ewald products of about the same
accuracy, :data:`MACRO_ACCURACY`, so the bound holds to that accuracy for the exact sum), 30-60x below the
point-load model's own error (0.3-0.6 % of the largest force against the full solver), and one Newton step (10 of
25 interaction products at 10^3 asperities) fewer than 1e-8."""
START_TOL_FACTOR = 1e-2
"""Two-scale: the macro step only starts the sweeps (their fixed point does not depend on it), so by default
it runs at this fraction of the outer tolerance (``force_tol``, else ``tol``), between :data:`START_TOL_MIN` and
:data:`MACRO_TOL`."""
START_TOL_MIN = 1e-8
"""The tightest default start: tighter gains the sweeps nothing, and Newton's residual has a floor near 1e-15."""


def solver_tolerances(scale: str, *, tol, force_tol, macro_tol, max_iter, macro_default: float) -> float:
    """``macro_tol`` (its default where None: ``macro_default`` for ``scale="macro"``, else
    :data:`START_TOL_FACTOR` of the outer tolerance between :data:`START_TOL_MIN` and :data:`MACRO_TOL`), with
    ``tol``, ``force_tol`` and ``max_iter`` refused naming the parameter where they are not tolerances in (0, 1) or a
    whole number >= 1."""
    if macro_tol is None:
        outer = force_tol if force_tol is not None else tol
        valid = isinstance(outer, numbers.Real) and math.isfinite(outer) and outer > 0  # else refused below
        macro_tol = (min(max(START_TOL_FACTOR * outer, START_TOL_MIN), MACRO_TOL) if scale == "two-scale" and valid
                     else macro_default)
    for name, value in (("tol", tol), ("macro_tol", macro_tol)) + ((("force_tol", force_tol),) if force_tol is not None
                                                                    else ()):
        check_tolerance(value, name)  # relative changes and residuals: in (0, 1)
    check_iterations(max_iter)
    return macro_tol


def table_with_grid(asperities, *, length, periodic, n, scale: str, law=None) -> AsperityTable:
    """The validated table, with the caps built on an ``n x n`` grid when a Dataset feeds the two-scale
    method (or ``n`` is given)."""
    if n is not None:
        check_whole(n, "n", 2)  # grid points per side
    table = asperity_table(asperities, length=length, periodic=periodic,
                           footprint_radius=None if law is None else law.footprint_radius)
    if law is not None:
        return table
    if table.grid is None and (scale == "two-scale" or n is not None):
        if n is None:
            raise ValueError("n: the two-scale method needs a grid; give n= (points per side) with a Dataset")
        built = surfaces.spheres(int(n), length=table.length, radius=table.radius, summit_height=table.summit_height,
                                 centers=table.centers)
        table = AsperityTable(table.centers, table.radius, table.summit_height, table.length, table.periodic,
                              np.asarray(built.values, dtype=float), asperity_table(built).grid)
    return table


def check_separate_contacts(table: AsperityTable, law: HertzLaw, macro: MacroState, z_top: float) -> None:
    """Refuse a load beyond what separate spherical contacts carry, saying where the assumption breaks:
    a cap pressed down to the base (local penetration >= summit height; its contact then fills the
    footprint and meets the flat between asperities), or the body reaching the base plane."""
    ratio = macro.local_penetration / table.summit_height
    worst = int(np.argmax(ratio))
    if ratio[worst] >= 1.0:
        a = float(law.contact_radius(macro.local_penetration[worst : worst + 1])[0])
        raise ValueError(
            f"mean_pressure/penetration: the load is beyond what separate spherical contacts carry: asperity {worst} "
            f"is pressed by {macro.local_penetration[worst]:.4g}, beyond its summit height "
            f"{table.summit_height[worst]:.4g} (contact radius {a:.4g} by the single-asperity law, footprint radius "
            f"{table.footprint_radius[worst]:.4g}), at approach {macro.penetration:.4g}: the body meets the base "
            "around it and the contacts are no longer separate caps")
    if macro.penetration >= z_top:
        raise ValueError(f"mean_pressure/penetration: the approach {macro.penetration:.4g} reaches the base plane "
                         f"(highest point {z_top:.4g}): the body touches between the asperities, so the contacts are "
                         "no longer separate caps")
