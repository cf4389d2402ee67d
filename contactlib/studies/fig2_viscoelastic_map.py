"""The ``fig2_viscoelastic_map`` study: the pressure map of an isotropic self-affine surface sliding on
a viscoelastic half-space (seed 2, Fig. 2): the patches shrink at their trailing edges and stretch
across the sliding direction. One point per seed; the pressure field is kept.

Parameters of the seed: 64 scales, ``lambda = L = 0.01 m``, ``E_inf = 1e8 Pa``, ``E_inf / E0 = 11``,
``tau = 0.1 s``, ``nu = 0.5``, ``p = 32 kPa``, ``V tau / lambda = 0.13`` (read as in
:mod:`._viscoelastic_scene`). The same surface at rest (relaxed) is solved beside it for comparison.
"""

from __future__ import annotations

from .. import analysis, surfaces
from ..problems.contact import solve
from ._viscoelastic_scene import SCENE_VARIABLES, material, model_flag

VARIABLES: dict[str, dict[str, str]] = {
    **SCENE_VARIABLES,
    "speed_ratio": {"units": "1", "long_name": "V tau / lambda (lambda: the window)"},
    "pressure": {"units": "Pa", "long_name": "contact pressure (compressive positive)"},
    "pressure_at_rest": {"units": "Pa", "long_name": "contact pressure at rest, relaxed (compressive positive)"},
    "contact_area_at_rest": {"units": "1", "long_name": "contact area fraction at rest (relaxed)"},
}


def viscoelastic_map_point(*, seed: int, n: int, length: float, hurst: float, scales: int, rms_slope: float,
                           E: float, glassy_ratio: float, tau: float, nu: float, mean_pressure: float,
                           speed_ratio: float, tol: float, max_iter: int, kernel: str) -> dict:
    """Pressure maps sliding (velocity along +x) and at rest, contact areas, ``mu_a``."""
    h = surfaces.self_affine(n, length=length, hurst=hurst, q_low=1, q_roll=1, q_cutoff=scales,
                             rms_slope=rms_slope, seed=seed, synthesis="random-phase")
    m = material(E0=E, glassy_ratio=glassy_ratio, tau=tau, nu=nu)
    V = speed_ratio * length / tau
    out = solve(h, material=m, mean_pressure=mean_pressure, sliding_velocity=(V, 0.0), tol=tol, max_iter=max_iter,
                kernel=kernel)
    rest = solve(h, material=m, mean_pressure=mean_pressure, tol=tol, max_iter=max_iter, kernel=kernel)
    fields = {}
    for name, ds in (("pressure", out), ("pressure_at_rest", rest)):
        p = ds.pressure.reset_coords(drop=True)
        p.attrs = {}
        fields[name] = p
    return {"contact_area": float(out.contact_area), "contact_area_at_rest": float(rest.contact_area),
            "friction_coefficient_interlocking": float(out.friction_coefficient_interlocking),
            "dissipated_power": float(out.dissipated_power), "rms_slope": analysis.rms_slope(h),
            "viscoelastic_model": model_flag(out), "iterations": float(out.iterations),
            "outer_iterations": float(out.get("outer_iterations", 0)), "residual": float(out.residual), **fields}


def map_shapes(grid: dict, constants: dict) -> list[tuple[int, ...]]:
    return [(constants["n"], constants["n"])]


STUDY = {"point": viscoelastic_map_point, "fft_shapes": map_shapes}
