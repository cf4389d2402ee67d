"""Two-scale asperity method against contactlib's full FFT solver: error and wall time against the number
of asperities and their density (issue 17).

Fields of :func:`contactlib.two_scale.random_asperity_field` (periodic unit window, random sequential
addition at ``--coverages``: the fraction under footprints, 0.05 sparse to 0.4 nearly touching), with the
grid chosen for ``--nodes-per-radius`` nodes per Hertz contact radius at the approach ``0.4 z``
(``z``: mean summit height), the same grid for the full solver and the micro scale ("matched
resolution"). Displacement control at that approach for all three, so the total force is an output:

* **reference**: ``contactlib.solve(..., tol=--ref-tol)`` (1e-8);
* **full**: ``contactlib.solve(..., tol=--full-tol)`` (1e-4, far below 1 % force error), timed;
* **two-scale**: ``contactlib.two_scale.solve(..., tol=--two-scale-tol)`` (1e-3 on the pressure change), timed;
* **macro**: ``scale="macro", fields=False``, timed.

Errors against the reference: total force, per-asperity force (max over asperities of ``|P_k - P_k^ref|``
over the largest ``P_k^ref``), contact area, pressure field (relative L2; the macro field is Hertz's
pressure of each macro force). Times: one warm-up solve of each (FFT plans, JIT), then ``--repeats``
solves interleaved (macro, two-scale, full in turn) and the median; ratios are full / method from the
same run. Grids above ``--max-nodes`` points per side are skipped (the full solver's memory and time on a
small machine), and said so.

Run ``python benchmarks/bench_two_scale.py --help``; ``--json`` writes every number.
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse
import json
import math
import statistics
import sys
import time
from pathlib import Path

import numpy as np

import contactlib
import contactlib.two_scale as ts
from contactlib.two_scale.fields import SUMMIT_OVER_FOOTPRINT

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_solver import host_info  # noqa: E402

E, NU = 1.0, 0.5
APPROACH = 0.4
"""Approach in mean summit heights."""


def nodes_per_spacing(coverage: float, nodes_per_radius: float) -> int:
    """Grid nodes per mean spacing giving ``nodes_per_radius`` nodes per Hertz radius ``sqrt(R 0.4 z)``."""
    s = SUMMIT_OVER_FOOTPRINT
    radius_over_footprint = (1 + s * s) / (2 * s)
    contact_over_footprint = math.sqrt(radius_over_footprint * APPROACH * s)
    footprint_over_spacing = math.sqrt(coverage / math.pi)
    return int(math.ceil(nodes_per_radius / (contact_over_footprint * footprint_over_spacing)))


def errors(out, reference, reference_forces) -> dict:
    forces = out.force.values
    total = float(reference_forces.sum())
    row = {"force_error": abs(float(forces.sum()) / total - 1),
           "asperity_force_error": float(np.max(np.abs(forces - reference_forces)) / reference_forces.max()),
           "contact_area_error": abs(float(out.contact_area) / float(reference.contact_area) - 1)}
    if "pressure" in out:
        p, q = out.pressure.values, reference.pressure.values
        row["pressure_error"] = float(np.linalg.norm(p - q) / np.linalg.norm(q))
    return row


def run_case(count: int, coverage: float, args) -> dict:
    nps = nodes_per_spacing(coverage, args.nodes_per_radius)
    n = int(round(nps * math.sqrt(count)))
    case = {"count": count, "coverage": coverage, "n": n}
    if n > args.max_nodes:
        case["skipped"] = f"grid {n}^2 above --max-nodes {args.max_nodes}"
        return case
    field = ts.random_asperity_field(count, coverage=coverage, nodes_per_spacing=nps, seed=args.seed)
    table = ts.asperity_table(field)
    # an asperity of mean height indents by 0.4 z; the approach counts from the highest node
    approach = float(field.max()) - (1 - APPROACH) * float(np.mean(table.summit_height))
    reference = contactlib.solve(field, E=E, nu=NU, penetration=approach, tol=args.ref_tol)
    reference_forces = ts.asperity_forces(reference.pressure.values, table)
    solvers = {
        "macro": lambda: ts.solve(field, E=E, nu=NU, penetration=approach, scale="macro", fields=False),
        "two_scale": lambda: ts.solve(field, E=E, nu=NU, penetration=approach, tol=args.two_scale_tol),
        "full": lambda: contactlib.solve(field, E=E, nu=NU, penetration=approach, tol=args.full_tol),
    }
    times = {name: [] for name in solvers}
    outputs = {name: solve() for name, solve in solvers.items()}  # warm-up
    for _ in range(args.repeats):
        for name, solve in solvers.items():
            start = time.perf_counter()
            solve()
            times[name].append(time.perf_counter() - start)
    outputs["macro"] = ts.solve(field, E=E, nu=NU, penetration=approach, scale="macro")  # its fields, untimed
    case.update(in_contact=int(np.count_nonzero(reference_forces)), contact_area=float(reference.contact_area),
                full_iterations=int(outputs["full"].iterations),
                two_scale_iterations=int(outputs["two_scale"].attrs["micro_iterations"]))
    for name in solvers:
        case[f"{name}_time"] = statistics.median(times[name])
        full_row = errors(outputs[name], reference, reference_forces) if name != "full" else \
            errors(_with_forces(outputs[name], table), reference, reference_forces)
        case.update({f"{name}_{k}": v for k, v in full_row.items()})
    case["two_scale_speedup"] = case["full_time"] / case["two_scale_time"]
    case["macro_speedup"] = case["full_time"] / case["macro_time"]
    return case


def _with_forces(out, table):
    """The full solver's Dataset with per-asperity forces, for the same error measures."""
    return out.assign(force=("asperity", ts.asperity_forces(out.pressure.values, table)))


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--counts", type=int, nargs="+", default=[10, 100, 1000, 10000])
    parser.add_argument("--coverages", type=float, nargs="+", default=[0.05, 0.2, 0.4])
    parser.add_argument("--nodes-per-radius", type=float, default=3.0)
    parser.add_argument("--ref-tol", type=float, default=1e-8)
    parser.add_argument("--full-tol", type=float, default=1e-4)
    parser.add_argument("--two-scale-tol", type=float, default=1e-3)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--max-nodes", type=int, default=4096)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--json", type=Path)
    args = parser.parse_args(argv)
    rows = []
    print(f"# bench_two_scale ({host_info()})\n")
    print("| N | coverage | n | in contact | full s | two-scale s | macro s | full/two-scale | full/macro | "
          "two-scale force err | two-scale max asperity err | macro force err | macro max asperity err | "
          "full force err | outer its |")
    print("|" + "---|" * 15)
    for count in args.counts:
        for coverage in args.coverages:
            case = run_case(count, coverage, args)
            rows.append(case)
            if "skipped" in case:
                print(f"| {count} | {coverage} | {case['n']} | skipped: {case['skipped']} |" + " |" * 11)
            else:
                print(f"| {count} | {coverage} | {case['n']} | {case['in_contact']} | {case['full_time']:.3g} | "
                      f"{case['two_scale_time']:.3g} | {case['macro_time']:.3g} | {case['two_scale_speedup']:.2f} | "
                      f"{case['macro_speedup']:.1f} | {case['two_scale_force_error']:.1e} | "
                      f"{case['two_scale_asperity_force_error']:.1e} | {case['macro_force_error']:.1e} | "
                      f"{case['macro_asperity_force_error']:.1e} | {case['full_force_error']:.1e} | "
                      f"{case['two_scale_iterations']} |", flush=True)
    if args.json:
        args.json.write_text(json.dumps({"host": host_info(), "args": {k: str(v) for k, v in vars(args).items()},
                                         "rows": rows}, indent=1))


if __name__ == "__main__":
    main()
