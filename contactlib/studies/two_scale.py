"""The ``two_scale`` study: error and wall time of the two-scale asperity method (macro step alone, and
macro + micro) against contactlib's full FFT solver, over the number of asperities and their density
(issue 17; the seed's claim of "the same answer, much faster").

One point: a :func:`contactlib.two_scale.random_asperity_field` of ``count`` asperities at ``coverage``
(fraction of the window under the footprints), on the grid that gives ``nodes_per_radius`` nodes per
Hertz contact radius (the same grid for the full solver and the micro scale: matched resolution), at
the approach that indents an asperity of mean height by ``APPROACH`` of its height. Displacement
control, so the total force is an output of every method. Errors against the full solver at
``tol`` (the reference); times of the full solver at ``full_tol``, the two-scale method at
``two_scale_tol`` and the macro step, each the median of ``repeats`` interleaved rounds of ``block``
solves in a row (the study: one) after a warm-up (FFT plans, JIT).
"""

from __future__ import annotations

import math
import statistics
import time

import numpy as np

from .. import two_scale
from ..problems.contact import solve
from ..two_scale.fields import SCATTER_CLIP, SUMMIT_OVER_FOOTPRINT

APPROACH = 0.4
"""Indentation of an asperity of mean summit height, in summit heights [1]."""
METHODS = ("macro", "two_scale", "full")

VARIABLES: dict[str, dict[str, str]] = {
    "count": {"units": "1", "long_name": "number of asperities"},
    "coverage": {"units": "1", "long_name": "fraction of the window under the asperities' exclusion discs"},
    "seed": {"units": "1", "long_name": "random seed of the asperity field"},
    "n": {"units": "1", "long_name": "grid points per side"},
    "in_contact": {"units": "1", "long_name": "asperities in contact (reference)"},
    **{f"{m}_time": {"units": "s", "long_name": f"wall time, {label} (median)"}
       for m, label in zip(METHODS, ("macro step", "two-scale method", "full FFT solver"))},
    **{f"{m}_cpu_time": {"units": "s", "long_name": f"CPU time of the process, {label} (median)"}
       for m, label in zip(METHODS, ("macro step", "two-scale method", "full FFT solver"))},
    **{f"{m}_{q}_error": {"units": "1", "long_name": f"{label}: relative error of the {what}"}
       for m, label in zip(METHODS, ("macro step", "two-scale method", "full FFT solver"))
       for q, what in (("force", "total force"), ("asperity_force", "asperity forces (max over the largest)"),
                       ("contact_area", "contact area"), ("pressure", "pressure field (L2)"))},
    "two_scale_speedup": {"units": "1", "long_name": "full solver time / two-scale time"},
    "macro_speedup": {"units": "1", "long_name": "full solver time / macro step time"},
    "two_scale_cpu_speedup": {"units": "1", "long_name": "full solver CPU time / two-scale CPU time"},
    "macro_cpu_speedup": {"units": "1", "long_name": "full solver CPU time / macro step CPU time"},
    "two_scale_iterations": {"units": "1", "long_name": "outer iterations of the two-scale micro step"},
}
"""Labels of the study's own names (the shared ones are in :data:`contactlib.studies._common.COMMON_VARIABLES`)."""


def nodes_per_spacing(coverage: float, nodes_per_radius: float) -> int:
    """Grid nodes per mean asperity spacing giving ``nodes_per_radius`` nodes per Hertz contact radius
    ``sqrt(R APPROACH z)`` of a mean asperity of :func:`contactlib.two_scale.random_asperity_field`."""
    s = SUMMIT_OVER_FOOTPRINT  # of the tallest cap, whose footprint sets the coverage
    radius_over_footprint = (1 + s * s) / (2 * s)
    mean_summit_over_footprint = s / (1 + SCATTER_CLIP * 0.1)  # random_asperity_field's default scatter 0.1
    contact_over_footprint = math.sqrt(radius_over_footprint * APPROACH * mean_summit_over_footprint)
    return int(math.ceil(nodes_per_radius / (contact_over_footprint * math.sqrt(coverage / math.pi))))


def smooth_size(n: int) -> int:
    """The smallest 7-smooth integer (only factors 2, 3, 5, 7: sizes FFTW transforms fast) ``>= n``."""
    m = max(int(n), 1)
    while True:
        k = m
        for p in (2, 3, 5, 7):
            while k % p == 0:
                k //= p
        if k == 1:
            return m
        m += 1


def grid_points(count: int, coverage: float, nodes_per_radius: float) -> int:
    """Grid points per side of a study field: ``nodes_per_spacing sqrt(N)`` rounded, then up to a 7-smooth size
    (:func:`smooth_size`), so at least ``nodes_per_radius`` nodes per Hertz radius. The full solver and the
    two-scale method share this grid, so both get the fast FFT size (a size like 696 = 2^3 3 29 cost the
    two-scale method's global convolutions, and the full solver's, up to 2x)."""
    return smooth_size(int(round(nodes_per_spacing(coverage, nodes_per_radius) * math.sqrt(count))))


def _errors(forces, contact_area, pressure, reference, reference_forces) -> dict:
    out = {"force_error": abs(float(np.sum(forces)) / float(reference_forces.sum()) - 1),
           "asperity_force_error": float(np.max(np.abs(forces - reference_forces)) / reference_forces.max()),
           "contact_area_error": abs(contact_area / float(reference.contact_area) - 1)}
    q = reference.pressure.values
    out["pressure_error"] = float(np.linalg.norm(pressure - q) / np.linalg.norm(q))
    return out


def compare_methods(*, count: int, coverage: float, seed: int, nodes_per_radius: float, full_tol: float,
                    two_scale_tol: float, repeats: int, E: float, nu: float, tol: float,
                    two_scale_force_tol: float | None = None, block: int = 1) -> dict:
    """Errors and median wall times of the macro step, the two-scale method and the full solver on one
    field (see the module docstring); ``tol``: the reference solve's. ``two_scale_force_tol``: run the
    two-scale method with ``force_tol=`` (the stop on the asperity forces) instead of ``tol=two_scale_tol``.
    ``block``: each method runs this many solves in a row in each of the ``repeats`` rounds, all timed (1: the
    three interleaved solve by solve; more: each method mostly in the steady state of a sweep of its own, after
    its own solves rather than the others', the rounds still alternating the methods under the same load)."""
    if int(block) < 1:
        raise ValueError(f"block must be >= 1 (solves of each method in a row), got {block!r}")
    nps = nodes_per_spacing(coverage, nodes_per_radius)
    field = two_scale.random_asperity_field(int(count), coverage=coverage, nodes_per_spacing=nps, seed=int(seed),
                                            n=grid_points(count, coverage, nodes_per_radius))
    table = two_scale.asperity_table(field)
    approach = float(field.max()) - (1 - APPROACH) * float(np.mean(table.summit_height))
    reference = solve(field, E=E, nu=nu, penetration=approach, tol=tol)
    reference_forces = two_scale.asperity_forces(reference.pressure, table)
    solvers = {
        "macro": lambda: two_scale.solve(field, E=E, nu=nu, penetration=approach, scale="macro", fields=False),
        "two_scale": lambda: two_scale.solve(field, E=E, nu=nu, penetration=approach, tol=two_scale_tol,
                                             force_tol=two_scale_force_tol),
        "full": lambda: solve(field, E=E, nu=nu, penetration=approach, tol=full_tol),
    }
    outputs = {name: run() for name, run in solvers.items()}  # warm-up: FFT plans, JIT
    times = {name: [] for name in solvers}
    cpu = {name: [] for name in solvers}  # CPU time beside wall time: less sensitive to other jobs' load
    for _ in range(int(repeats)):
        for name, run in solvers.items():  # interleaved: a change of the machine's load hits all alike
            for _ in range(int(block)):
                start, start_cpu = time.perf_counter(), time.process_time()
                run()
                times[name].append(time.perf_counter() - start)
                cpu[name].append(time.process_time() - start_cpu)
    macro_fields = two_scale.solve(field, E=E, nu=nu, penetration=approach, scale="macro")  # untimed
    row = {"n": field.shape[0], "in_contact": int(np.count_nonzero(reference_forces)),
           "residual": float(reference.residual),  # the reference's: the errors are measured against it
           "contact_area": float(reference.contact_area),
           "two_scale_iterations": int(outputs["two_scale"].attrs["micro_iterations"])}
    answers = {
        "macro": (outputs["macro"].force.values, float(outputs["macro"].contact_area), macro_fields.pressure.values),
        "two_scale": (outputs["two_scale"].force.values, float(outputs["two_scale"].contact_area),
                      outputs["two_scale"].pressure.values),
        "full": (two_scale.asperity_forces(outputs["full"].pressure, table),
                 float(outputs["full"].contact_area), outputs["full"].pressure.values),
    }
    for name in METHODS:
        row[f"{name}_time"] = statistics.median(times[name])
        row[f"{name}_cpu_time"] = statistics.median(cpu[name])
        row.update({f"{name}_{k}": v for k, v in _errors(*answers[name], reference, reference_forces).items()})
    row["two_scale_speedup"] = row["full_time"] / row["two_scale_time"]
    row["macro_speedup"] = row["full_time"] / row["macro_time"]
    row["two_scale_cpu_speedup"] = row["full_cpu_time"] / row["two_scale_cpu_time"]
    row["macro_cpu_speedup"] = row["full_cpu_time"] / row["macro_cpu_time"]
    return row


def two_scale_point(*, count: int, coverage: float, seed: int, nodes_per_radius: float, full_tol: float,
                    two_scale_tol: float, repeats: int, E: float, nu: float, tol: float, max_iter: int = 10_000,
                    kernel: str = "spectral") -> dict:
    """One point of the study: :func:`compare_methods` (``max_iter`` and ``kernel`` of the shared solver
    settings are the full solver's defaults here: spectral kernel)."""
    if kernel != "spectral":
        raise ValueError(f"kernel: the two_scale study compares with the spectral kernel, got {kernel!r}")
    return compare_methods(count=count, coverage=coverage, seed=seed, nodes_per_radius=nodes_per_radius,
                           full_tol=full_tol, two_scale_tol=two_scale_tol, repeats=repeats, E=E, nu=nu, tol=tol)


def two_scale_shapes(grid: dict, constants: dict) -> list[tuple[int, ...]]:
    """FFT shapes: each field's grid (the local windows are small and planned on first use)."""
    shapes = []
    for count in grid["count"]:
        for coverage in grid["coverage"]:
            n = grid_points(count, coverage, constants["nodes_per_radius"])
            shapes.append((n, n))
    return shapes


STUDY = {"point": two_scale_point, "fft_shapes": two_scale_shapes}
"""This study's entry of :data:`contactlib.studies.STUDIES`."""
