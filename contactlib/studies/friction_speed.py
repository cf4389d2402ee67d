"""The ``friction_speed`` study: the hysteretic friction coefficient and the contact area of a 2D rough
surface sliding on a standard linear solid, against ``zeta = V tau q0`` (the bell-shaped curve), for
several ``E_inf / E0`` and seeds. The load is fixed as a fraction of the relaxed contact modulus times
the rms slope. Each speed is solved cold, so the points spread over the workers (72 tasks at the quick
scale instead of one walk per seed and ratio). Warm starts from the next slower speed did not pay at the
quick scale: 128^2, seed 0, zeta 1e-3..0.1, 1.3 s cold against 1.5 s warm at E_inf/E0 = 10, 3.0 s against
4.1 s at 100. At 512^2 (benchmarks/bench_viscoelastic.py, 30 speeds, E_inf/E0 = 10) the cold walk took
fewer iterations (5361 against 7643) but more time (246 s against 185 s, one run on a loaded machine).
"""

from __future__ import annotations

from .. import analysis
from ..problems.contact import solve
from ._common import rough_surface
from ._viscoelastic_scene import SCENE_VARIABLES, material, model_flag, relaxed_contact_modulus, speed


VARIABLES: dict[str, dict[str, str]] = dict(SCENE_VARIABLES)


def friction_speed_point(*, zeta: float, glassy_ratio: float, seed: int, n: int, hurst: float, q_low: float,
                         q_roll: float, q_cutoff: float, rms_slope: float, reduced_pressure: float, E: float,
                         tau: float, nu: float, tol: float, max_iter: int, kernel: str, initial_pressure=None) -> dict:
    """``mu_a``, contact area and dissipated power at ``zeta``, sliding along +x at mean pressure
    ``reduced_pressure * E0* * rms slope``."""
    h = rough_surface(n=n, hurst=hurst, seed=seed, q_low=q_low, q_roll=q_roll, q_cutoff=q_cutoff, rms_slope=rms_slope)
    m = material(E0=E, glassy_ratio=glassy_ratio, tau=tau, nu=nu)
    slope = analysis.rms_slope(h)
    out = solve(h, material=m, mean_pressure=reduced_pressure * relaxed_contact_modulus(m) * slope,
                sliding_velocity=(speed(zeta, tau=tau, length=1.0), 0.0), tol=tol, max_iter=max_iter,
                kernel=kernel, initial_pressure=initial_pressure)
    return {"friction_coefficient_interlocking": float(out.friction_coefficient_interlocking),
            "contact_area": float(out.contact_area), "mean_pressure": float(out.mean_pressure),
            "dissipated_power": float(out.dissipated_power), "rms_slope": slope, "viscoelastic_model": model_flag(out),
            "iterations": float(out.iterations), "outer_iterations": float(out.get("outer_iterations", 0)),
            "residual": float(out.residual), "_warm_start": out.pressure}


def speed_shapes(grid: dict, constants: dict) -> list[tuple[int, ...]]:
    return [(constants["n"], constants["n"])]


STUDY = {"point": friction_speed_point, "fft_shapes": speed_shapes, "surface_keys": ("seed",)}
