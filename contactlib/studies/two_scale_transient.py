"""The ``two_scale_transient`` study: creep of a field of separate spherical asperities on a standard linear
solid, by the two-scale method's time stepping (macro step alone, and macro + micro) against contactlib's
full transient solver (issue 17, the seed's viscoelastic extension).

One point: a :func:`contactlib.two_scale.random_asperity_field` of ``count`` asperities at ``coverage``, on
the grid of ``nodes_per_radius`` nodes per Hertz contact radius (the same grid for all methods: matched
resolution), on a standard linear solid of relaxed modulus ``E`` and ``E_inf = glassy_ratio E``,
relaxation time ``tau``. The load is the mean pressure that the glassy body carries at the approach
``approach`` times the mean summit height (macro step), applied at ``t = 0`` and held; ``steps`` equal
steps to ``end_time``. The contacts grow as the body creeps, and the forces move between asperities.

Against the full transient solver at ``tol`` (the reference): each step's per-asperity forces (the
largest difference over the step's largest force), penetration and contact area. Wall times: one run of
each method after a one-step warm-up (FFT plans), the full solver at ``full_tol``, the two-scale method
at ``two_scale_tol`` (its outer tolerance on the pressure change).
"""

from __future__ import annotations

import time

import numpy as np
import xarray as xr

from .. import two_scale
from ..problems.transient import solve_transient as full_transient
from ._viscoelastic_scene import SCENE_VARIABLES, material
from .two_scale import VARIABLES as TWO_SCALE_VARIABLES
from .two_scale import grid_points, nodes_per_spacing, two_scale_shapes

METHODS = ("full", "two_scale", "macro")
LABELS = {"full": "full transient solver", "two_scale": "two-scale method", "macro": "macro step",
          "reference": "reference (full solver at tol)"}

VARIABLES: dict[str, dict[str, str]] = {
    **{name: TWO_SCALE_VARIABLES[name] for name in ("count", "coverage", "seed", "n")},
    **{name: SCENE_VARIABLES[name] for name in ("glassy_ratio", "step_mean_pressure")},
    "time": {"units": "s", "long_name": "time since the step"},
    **{f"{m}_creep_penetration": {"units": "m", "long_name": f"penetration under the step load, {LABELS[m]}"}
       for m in ("reference",) + METHODS},
    **{f"{m}_creep_contact_area": {"units": "1", "long_name": f"contact area fraction, {LABELS[m]}"}
       for m in ("reference",) + METHODS},
    **{f"{m}_creep_force_error": {"units": "1", "long_name": f"{LABELS[m]}: largest asperity-force error over the "
                                  "step's largest force"} for m in METHODS},
    **{f"{m}_creep_time": {"units": "s", "long_name": f"wall time of the whole history, {LABELS[m]}"}
       for m in METHODS},
    **{f"{m}_creep_speedup": {"units": "1", "long_name": f"full solver time / {LABELS[m]} time"}
       for m in ("two_scale", "macro")},
    "in_contact_first": {"units": "1", "long_name": "asperities in contact at t = 0 (reference)"},
    "in_contact_last": {"units": "1", "long_name": "asperities in contact at the last time (reference)"},
}
"""Labels of the study's own names (the shared ones are in :data:`contactlib.studies._common.COMMON_VARIABLES`)."""


def creep_point(*, count: int, coverage: float, glassy_ratio: float, seed: int, nodes_per_radius: float,
                approach: float, tau: float, end_time: float, steps: int, full_tol: float, two_scale_tol: float,
                E: float, nu: float, tol: float, max_iter: int = 10_000, kernel: str = "spectral") -> dict:
    """One point of the study (see the module docstring); ``tol``, ``max_iter``: the reference solve's."""
    if kernel != "spectral":
        raise ValueError(f"kernel: the two_scale_transient study compares with the spectral kernel, got {kernel!r}")
    m = material(E0=E, glassy_ratio=glassy_ratio, tau=tau, nu=nu)
    field = two_scale.random_asperity_field(int(count), coverage=coverage,
                                            nodes_per_spacing=nodes_per_spacing(coverage, nodes_per_radius),
                                            seed=int(seed), n=grid_points(count, coverage, nodes_per_radius))
    table = two_scale.asperity_table(field)
    summit = float(np.mean(table.summit_height))
    load = float(two_scale.solve(field, E=m.E_inf, nu=nu, penetration=approach * summit, scale="macro",
                                 fields=False).mean_pressure)
    times = np.linspace(0.0, end_time, int(steps) + 1)
    reference = full_transient(field, material=m, times=times, mean_pressure=load, tol=tol, max_iter=max_iter,
                               save_fields=True)
    ref_forces = np.array([two_scale.asperity_forces(p, table) for p in reference.pressure])
    runs = {
        "full": lambda t: full_transient(field, material=m, times=t, mean_pressure=load, tol=full_tol,
                                         max_iter=max_iter, save_fields=True),
        "two_scale": lambda t: two_scale.solve_transient(field, material=m, times=t, mean_pressure=load,
                                                         tol=two_scale_tol, max_iter=max_iter),
        "macro": lambda t: two_scale.solve_transient(field, material=m, times=t, mean_pressure=load, scale="macro"),
    }
    out, wall = {}, {}
    for name, run in runs.items():
        run(times[:1])  # warm-up: FFT plans
        start = time.perf_counter()
        out[name] = run(times)
        wall[name] = time.perf_counter() - start
    forces = {"full": np.array([two_scale.asperity_forces(p, table) for p in out["full"].pressure]),
              "two_scale": out["two_scale"].force.values, "macro": out["macro"].force.values}

    def series(values, name):
        return xr.DataArray(np.asarray(values, dtype=float), dims=("time",), coords={"time": times},
                            attrs=VARIABLES[name])

    largest = ref_forces.max(axis=1)
    row = {"n": float(field.shape[0]), "step_mean_pressure": load,
           "residual": float(reference.residual.max()),  # the reference's largest: errors are measured against it
           "in_contact_first": float(np.count_nonzero(ref_forces[0])),
           "in_contact_last": float(np.count_nonzero(ref_forces[-1])),
           "reference_creep_penetration": series(reference.penetration, "reference_creep_penetration"),
           "reference_creep_contact_area": series(reference.contact_area, "reference_creep_contact_area")}
    for name in METHODS:
        row[f"{name}_creep_penetration"] = series(out[name].penetration, f"{name}_creep_penetration")
        row[f"{name}_creep_contact_area"] = series(out[name].contact_area, f"{name}_creep_contact_area")
        error = np.abs(forces[name] - ref_forces).max(axis=1) / largest
        row[f"{name}_creep_force_error"] = series(error, f"{name}_creep_force_error")
        row[f"{name}_creep_time"] = wall[name]
    for name in ("two_scale", "macro"):
        row[f"{name}_creep_speedup"] = wall["full"] / wall[name]
    return row


STUDY = {"point": creep_point, "fft_shapes": two_scale_shapes}
"""This study's entry of :data:`contactlib.studies.STUDIES`."""
