"""The ``fig5_friction_area`` study: how Coulomb friction changes the contact area of a rough profile on
a thin confined layer through the layer's normal-tangential ("geometric") coupling (seed 2, Fig. 5).

Each point solves the same scene twice, frictionless (``a0``) and with friction ``mu_c`` (``a``), so
``area_ratio = a / a0`` needs no other point. Swept: ``friction``, ``scaled_layer_thickness`` (q0 h),
``scaled_pressure`` and ``seed``; Fig. 5a is the ratio against the pressure at one thin layer, Fig. 5b
against the thickness at ``mu_c`` near 1.
"""

from __future__ import annotations

import math

from ..problems.contact import solve
from ._sliding_layer import SCENE_VARIABLES, coupling_flag, profile_shapes, sliding_layer_scene

VARIABLES: dict[str, dict[str, str]] = {
    **SCENE_VARIABLES,
    "frictionless_contact_area": {"units": "1", "long_name": "contact area fraction a0 without friction"},
    "area_ratio": {"units": "1", "long_name": "contact area with friction over without, a / a0"},
}
"""Labels of the study's own names and of the scene's (the ones of every study are in
:data:`contactlib.studies._common.COMMON_VARIABLES`)."""


def friction_area_point(*, friction: float, scaled_layer_thickness: float, scaled_pressure: float, seed: int,
                        n: int, hurst: float, q_low: float, q_roll: float, q_cutoff: float, rms_slope: float,
                        layer_base: str, E: float, nu: float, tol: float, max_iter: int, kernel: str) -> dict:
    """Contact area ``a`` at friction ``mu_c`` and ``a0`` without, on the same profile, layer and load.

    A solve that does not converge raises :class:`contactlib.ConvergenceError` (the sweep records
    status 1, its residual and NaN); ``friction = 0`` gives ``a = a0`` from one solve.
    """
    h, layer, p, measures = sliding_layer_scene(
        n=n, hurst=hurst, seed=seed, q_low=q_low, q_roll=q_roll, q_cutoff=q_cutoff, rms_slope=rms_slope,
        scaled_layer_thickness=scaled_layer_thickness, scaled_pressure=scaled_pressure, layer_base=layer_base,
        E=E, nu=nu)
    scene = dict(E=E, nu=nu, mean_pressure=p, layer=layer, tol=tol, max_iter=max_iter, kernel=kernel)
    free = solve(h, **scene)
    out = solve(h, friction=friction, sliding_direction=0.0, **scene) if friction > 0 else free
    area, area0 = float(out.contact_area), float(free.contact_area)
    return {
        "contact_area": area,
        "frictionless_contact_area": area0,
        "area_ratio": area / area0 if area0 > 0 else math.nan,
        "friction_coefficient_interlocking": float(out.get("friction_coefficient_interlocking", 0.0)),
        "mean_pressure": float(out.mean_pressure),
        **measures,
        "coupled": coupling_flag(out),
        "iterations": float(free.iterations) + (float(out.iterations) if out is not free else 0.0),
        "outer_iterations": float(out.get("outer_iterations", 0)),
        "residual": max(float(free.residual), float(out.residual)),
    }


STUDY = {"point": friction_area_point, "fft_shapes": profile_shapes}
"""This study's entry of :data:`contactlib.studies.STUDIES`."""
