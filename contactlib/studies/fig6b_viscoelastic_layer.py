"""The ``fig6b_viscoelastic_layer`` study: the interlocking friction ``mu_a / g`` of a 1D rough profile
sliding on a thin confined viscoelastic layer against ``zeta = V tau q0``, with Coulomb friction
``mu_c = 0.8`` and without (seed 2, Fig. 6b). With coupling, ``mu_a`` stays non-zero at both ends of the
speed range: the layer's geometric coupling does not depend on the speed.

The scene of :mod:`._sliding_layer` (dimensionless, ``L = 1``, ``nu = 0.5``), the layer a standard linear
solid. Below ``q0 h`` of 1.2-1.5 with ``mu_c = 0.8`` the lagged coupling makes the normal operator's
symmetric part negative at the longest waves: not monotone, but well posed on a grid that resolves the layer
(:mod:`contactlib.model.bodies`), and solved down to ``q0 h = 0.1``.
"""

from __future__ import annotations

from ..problems.contact import solve
from ._sliding_layer import SCENE_VARIABLES as LAYER_VARIABLES
from ._sliding_layer import profile_shapes, sliding_layer_scene
from ._viscoelastic_scene import SCENE_VARIABLES, material, model_flag, speed

VARIABLES: dict[str, dict[str, str]] = {
    **LAYER_VARIABLES, **SCENE_VARIABLES,
    "interlocking_over_slope": {"units": "1", "long_name": "normalised interlocking friction mu_a / g"},
}


def viscoelastic_layer_point(*, zeta: float, friction: float, seed: int, n: int, hurst: float, q_low: float,
                             q_roll: float, q_cutoff: float, rms_slope: float, scaled_layer_thickness: float,
                             layer_base: str, scaled_pressure: float, E: float, glassy_ratio: float, nu: float,
                             tau: float, tol: float, max_iter: int, kernel: str, initial_pressure=None) -> dict:
    """``mu_a / g`` at ``zeta`` (``E = E0`` [Pa], ``tau`` [s]; the load scaled with ``E0``)."""
    h, layer, p, measures = sliding_layer_scene(
        n=n, hurst=hurst, seed=seed, q_low=q_low, q_roll=q_roll, q_cutoff=q_cutoff, rms_slope=rms_slope,
        scaled_layer_thickness=scaled_layer_thickness, scaled_pressure=scaled_pressure, layer_base=layer_base,
        E=E, nu=nu)
    m = material(E0=E, glassy_ratio=glassy_ratio, tau=tau, nu=nu)
    out = solve(h, material=m, mean_pressure=p, layer=layer, friction=friction,
                sliding_velocity=speed(zeta, tau=tau, length=1.0), tol=tol, max_iter=max_iter,
                kernel=kernel, initial_pressure=initial_pressure)
    mu_a = float(out.friction_coefficient_interlocking)
    return {"friction_coefficient_interlocking": mu_a, "interlocking_over_slope": mu_a / measures["rms_slope"],
            "contact_area": float(out.contact_area), **measures, "viscoelastic_model": model_flag(out),
            "iterations": float(out.iterations), "outer_iterations": float(out.get("outer_iterations", 0)),
            "residual": float(out.residual), "_warm_start": out.pressure}


# each speed solved cold: walking the speeds with warm starts cost more (2048 points, 14 speeds: 1.3 s cold
# against 2.6 s warm at mu_c = 0, 1.8 s against 2.2 s at 0.8)
STUDY = {"point": viscoelastic_layer_point, "fft_shapes": profile_shapes}
