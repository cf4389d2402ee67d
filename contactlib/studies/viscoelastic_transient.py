"""The ``viscoelastic_transient`` study: creep and relaxation of a 2D rough contact on a standard linear solid.

Creep: a step mean pressure ``reduced_pressure * E0* * rms slope`` from ``t = 0`` (glassy response at once),
held; the contact area and the penetration against time. Relaxation: a step penetration, the relaxed elastic
penetration of that load, held; the mean pressure (which relaxes as ``E(t)`` while the contact stays put, by
the correspondence principle) and the contact area. The elastic levels with ``E0`` and ``E_inf`` are solved
beside them. Times: ``t = 0`` and ``steps`` log-spaced times from ``first_time`` to ``end_time`` [s].
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from .. import analysis
from ..problems.contact import solve
from ..model.materials import Elastic
from ..problems.transient import solve_transient
from ._common import rough_surface
from ._viscoelastic_scene import SCENE_VARIABLES, material, relaxed_contact_modulus

VARIABLES: dict[str, dict[str, str]] = {
    **{name: SCENE_VARIABLES[name] for name in ("glassy_ratio", "step_mean_pressure")},
    "creep_contact_area": {"units": "1", "long_name": "contact area fraction under the step load"},
    "creep_penetration": {"units": "m", "long_name": "penetration under the step load"},
    "relaxation_mean_pressure": {"units": "Pa", "long_name": "mean pressure at the step penetration"},
    "relaxation_contact_area": {"units": "1", "long_name": "contact area fraction at the step penetration"},
    "relaxed_contact_area": {"units": "1", "long_name": "elastic contact area with E0 (relaxed level)"},
    "glassy_contact_area": {"units": "1", "long_name": "elastic contact area with E_inf (glassy level)"},
    "relaxed_penetration": {"units": "m", "long_name": "elastic penetration with E0 (relaxed level)"},
    "glassy_penetration": {"units": "m", "long_name": "elastic penetration with E_inf (glassy level)"},
    "time": {"units": "s", "long_name": "time since the step"},
}


def transient_times(*, first_time: float, end_time: float, steps: int) -> np.ndarray:
    return np.concatenate([[0.0], np.geomspace(first_time, end_time, steps)])


def transient_point(*, glassy_ratio: float, seed: int, n: int, hurst: float, q_low: float, q_roll: float,
                    q_cutoff: float, rms_slope: float, reduced_pressure: float, E: float, tau: float, nu: float,
                    first_time: float, end_time: float, steps: int, tol: float, max_iter: int, kernel: str) -> dict:
    """Creep and relaxation histories (on ``time``) and the elastic E0 / E_inf levels of one surface."""
    h = rough_surface(n=n, hurst=hurst, seed=seed, q_low=q_low, q_roll=q_roll, q_cutoff=q_cutoff, rms_slope=rms_slope)
    m = material(E0=E, glassy_ratio=glassy_ratio, tau=tau, nu=nu)
    load = reduced_pressure * relaxed_contact_modulus(m) * analysis.rms_slope(h)
    times = transient_times(first_time=first_time, end_time=end_time, steps=steps)
    relaxed = solve(h, material=Elastic(m.E0, nu), mean_pressure=load, tol=tol, max_iter=max_iter, kernel=kernel)
    glassy = solve(h, material=Elastic(m.E_inf, nu), mean_pressure=load, tol=tol, max_iter=max_iter, kernel=kernel)
    creep = solve_transient(h, material=m, times=times, mean_pressure=load, tol=tol, max_iter=max_iter)
    relaxation = solve_transient(h, material=m, times=times, penetration=float(relaxed.penetration), tol=tol,
                                 max_iter=max_iter)

    def series(values, name):
        return xr.DataArray(np.asarray(values, dtype=float), dims=("time",), coords={"time": times},
                            attrs=VARIABLES[name])

    return {"creep_contact_area": series(creep.contact_area, "creep_contact_area"),
            "creep_penetration": series(creep.penetration, "creep_penetration"),
            "relaxation_mean_pressure": series(relaxation.mean_pressure, "relaxation_mean_pressure"),
            "relaxation_contact_area": series(relaxation.contact_area, "relaxation_contact_area"),
            "relaxed_contact_area": float(relaxed.contact_area), "glassy_contact_area": float(glassy.contact_area),
            "relaxed_penetration": float(relaxed.penetration), "glassy_penetration": float(glassy.penetration),
            "step_mean_pressure": load,
            "iterations": float(creep.iterations.sum() + relaxation.iterations.sum()),
            "residual": float(max(creep.residual.max(), relaxation.residual.max()))}


def transient_shapes(grid: dict, constants: dict) -> list[tuple[int, ...]]:
    return [(constants["n"], constants["n"])]


STUDY = {"point": transient_point, "fft_shapes": transient_shapes, "surface_keys": ("seed",)}
