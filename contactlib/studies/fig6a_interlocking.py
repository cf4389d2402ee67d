"""The ``fig6a_interlocking`` study: the interlocking friction ``mu_a`` that the pressure's asymmetry
adds to Coulomb friction on a thin confined layer, normalised by ``mu_c g``, against the load for
several Poisson ratios (seed 2, Fig. 6a).

At ``nu = 0.5`` only the layer's finite thickness couples normal and tangential displacements
("geometric" coupling); below it the material couples them too. ``mu_a > 0`` when the asymmetry
resists sliding (:func:`contactlib.analysis.interlocking_friction`).
"""

from __future__ import annotations

from ..problems.contact import solve
from ._sliding_layer import SCENE_VARIABLES, coupling_flag, profile_shapes, sliding_layer_scene

VARIABLES: dict[str, dict[str, str]] = {
    **SCENE_VARIABLES,
    "interlocking_ratio": {"units": "1", "long_name": "normalised interlocking friction mu_a / (mu_c g)"},
}
"""Labels of the study's own names and of the scene's (the ones of every study are in
:data:`contactlib.studies._common.COMMON_VARIABLES`)."""


def interlocking_point(*, nu: float, scaled_pressure: float, seed: int, n: int, hurst: float, q_low: float,
                       q_roll: float, q_cutoff: float, rms_slope: float, scaled_layer_thickness: float,
                       layer_base: str, friction: float, E: float, tol: float, max_iter: int, kernel: str) -> dict:
    """``mu_a / (mu_c g)`` of one profile sliding with friction ``mu_c > 0`` on the layer, ``g`` its
    measured rms slope. A solve that does not converge raises :class:`contactlib.ConvergenceError`."""
    if not friction > 0:
        raise ValueError(f"friction (Coulomb coefficient mu_c) must be > 0 to normalise mu_a, got {friction!r}")
    h, layer, p, measures = sliding_layer_scene(
        n=n, hurst=hurst, seed=seed, q_low=q_low, q_roll=q_roll, q_cutoff=q_cutoff, rms_slope=rms_slope,
        scaled_layer_thickness=scaled_layer_thickness, scaled_pressure=scaled_pressure, layer_base=layer_base,
        E=E, nu=nu)
    out = solve(h, E=E, nu=nu, mean_pressure=p, layer=layer, friction=friction, sliding_direction=0.0, tol=tol,
                max_iter=max_iter, kernel=kernel)
    mu_a = float(out.friction_coefficient_interlocking)
    return {
        "friction_coefficient_interlocking": mu_a,
        "interlocking_ratio": mu_a / (friction * measures["rms_slope"]),
        "contact_area": float(out.contact_area),
        "mean_pressure": float(out.mean_pressure),
        **measures,
        "coupled": coupling_flag(out),
        "iterations": float(out.iterations),
        "outer_iterations": float(out.get("outer_iterations", 0)),
        "residual": float(out.residual),
    }


STUDY = {"point": interlocking_point, "fft_shapes": profile_shapes}
"""This study's entry of :data:`contactlib.studies.STUDIES`."""
