"""Two-scale asperity method against contactlib's full FFT solver: error and wall time against the number
of asperities and their density (issue 17).

Fields of :func:`contactlib.two_scale.random_asperity_field` (periodic unit window, random sequential
addition at ``--coverages``: the fraction under footprints, 0.05 sparse to 0.4 nearly touching), with the
grid chosen for ``--nodes-per-radius`` nodes per Hertz contact radius at the approach ``0.4 z``
(``z``: mean summit height), rounded up to a 7-smooth size (a fast FFT size; never fewer nodes), the same
grid for the full solver and the micro scale ("matched resolution": both get the fast size). Displacement control at that approach for all three, so the total force is an output:

* **reference**: ``contactlib.solve(..., tol=--ref-tol)`` (1e-8);
* **full**: ``contactlib.solve(..., tol=--full-tol)`` (1e-4, far below 1 % force error), timed;
* **two-scale**: ``contactlib.two_scale.solve(..., tol=--two-scale-tol)`` (1e-3 on the pressure change), or
  with ``--two-scale-force-tol``, ``force_tol=`` (the stop on the change of the asperity forces), timed;
* **macro**: ``scale="macro", fields=False``, timed.

Errors against the reference: total force, per-asperity force (max over asperities of ``|P_k - P_k^ref|``
over the largest ``P_k^ref``), contact area, pressure field (relative L2; the macro field is Hertz's
pressure of each macro force). Times: one warm-up solve of each (FFT plans, JIT), then ``--repeats``
solves interleaved (macro, two-scale, full in turn) and the median; ratios are full / method from the
same run. With ``--block k`` each round runs each method ``k`` times in a row (all timed, the median over all):
the macro step then mostly runs after its own solves, as a sweep of it does, instead of after a full solve whose
700^2 arrays have emptied the caches (2.3 against 3.0 ms at 10^3 asperities); the rounds still alternate. Each
field runs in a fresh interpreter (``--same-process`` to opt out; :func:`run_isolated` says why);
``--allocator keep`` runs them with glibc keeping freed memory mapped (no page faults on reuse). Grids above
``--max-nodes`` points per side are skipped (the full solver's memory and time on a small machine), and said so.

Run ``python -m benchmarks.bench_two_scale --help``; ``--json`` writes every number.
"""

from __future__ import annotations

import argparse
import json
import multiprocessing
import os
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

from contactlib.studies.two_scale import compare_methods, grid_points

from .common import host_info

E, NU = 1.0, 0.5


def run_case(count: int, coverage: float, args) -> dict:
    """One field: :func:`contactlib.studies.two_scale.compare_methods` (the study's own point), or the reason
    it was skipped."""
    n = grid_points(count, coverage, args.nodes_per_radius)
    case = {"count": count, "coverage": coverage, "n": n, "block": args.block, "load_average": os.getloadavg()[0]}
    if n > args.max_nodes:
        case["skipped"] = f"grid {n}^2 above --max-nodes {args.max_nodes}"
        return case
    try:
        case.update(compare_methods(count=count, coverage=coverage, seed=args.seed,
                                    nodes_per_radius=args.nodes_per_radius, full_tol=args.full_tol,
                                    two_scale_tol=args.two_scale_tol, repeats=args.repeats, E=E, nu=NU,
                                    tol=args.ref_tol, two_scale_force_tol=args.two_scale_force_tol,
                                    block=args.block))
    except (ValueError, RuntimeError) as err:  # a refused scene or a non-convergence is a result too
        case["skipped"] = f"{type(err).__name__}: {err}"
    case["load_average"] = os.getloadavg()[0]  # the 1-minute load when the field's runs ended
    return case


KEEP_MAPPED = {"MALLOC_MMAP_THRESHOLD_": str(256 << 20), "MALLOC_TRIM_THRESHOLD_": str(512 << 20)}
"""glibc settings under which freed memory stays mapped (``--allocator keep``)."""


def run_isolated(count: int, coverage: float, args) -> dict:
    """:func:`run_case` in a fresh interpreter, so that every field starts from the same state of the memory
    allocator. In one process a larger field run before leaves glibc's thresholds raised, and the full solver then
    reuses mapped memory instead of faulting in about 29 MB of fresh pages a solve (10^3 asperities, 700^2:
    0.27-0.30 s against 0.31-0.35 s), so a row's ratios depended on the rows before it."""
    with ProcessPoolExecutor(max_workers=1, mp_context=multiprocessing.get_context("spawn")) as pool:
        return pool.submit(run_case, count, coverage, args).result()


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--counts", type=int, nargs="+", default=[10, 100, 1000, 10000])
    parser.add_argument("--coverages", type=float, nargs="+", default=[0.05, 0.2, 0.4])
    parser.add_argument("--nodes-per-radius", type=float, default=3.0)
    parser.add_argument("--ref-tol", type=float, default=1e-8)
    parser.add_argument("--full-tol", type=float, default=1e-4)
    parser.add_argument("--two-scale-tol", type=float, default=1e-3)
    parser.add_argument("--two-scale-force-tol", type=float, default=None,
                        help="run the two-scale method with force_tol= (stop on the asperity forces' change) "
                             "instead of tol=--two-scale-tol")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--block", type=int, default=1,
                        help="solves of each method in a row per round, all timed (1: interleaved solve by solve; "
                             "5: each mostly after its own solves, as in a sweep of it)")
    parser.add_argument("--max-nodes", type=int, default=4096)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--json", type=Path)
    parser.add_argument("--same-process", action="store_true",
                        help="run every field in this process (default: each in a fresh one, see run_isolated)")
    parser.add_argument("--allocator", choices=("default", "keep"), default="default",
                        help="'keep': the fields' processes keep freed memory mapped (glibc's trim and mmap "
                             "thresholds raised), so no solver pays page faults for memory it frees and reallocates")
    args = parser.parse_args(argv)
    if args.allocator == "keep":
        if args.same_process:
            parser.error("--allocator keep needs fresh processes: drop --same-process")
        os.environ.update(KEEP_MAPPED)  # read by glibc when each field's interpreter starts
    rows = []
    print(f"# bench_two_scale ({host_info()})\n")
    print("| N | coverage | n | in contact | full s | two-scale s | macro s | full/two-scale | full/macro | "
          "two-scale force err | two-scale max asperity err | macro force err | macro max asperity err | "
          "full force err | outer its | CPU full/two-scale | CPU full/macro | load |")
    print("|" + "---|" * 18)
    for count in args.counts:
        for coverage in args.coverages:
            case = (run_case if args.same_process else run_isolated)(count, coverage, args)
            case["allocator"] = args.allocator
            rows.append(case)
            if "skipped" in case:
                print(f"| {count} | {coverage} | {case['n']} | {case['skipped']} |" + " |" * 13
                      + f" {case['load_average']:.1f} |", flush=True)
            else:
                print(f"| {count} | {coverage} | {case['n']} | {case['in_contact']} | {case['full_time']:.3g} | "
                      f"{case['two_scale_time']:.3g} | {case['macro_time']:.3g} | {case['two_scale_speedup']:.2f} | "
                      f"{case['macro_speedup']:.1f} | {case['two_scale_force_error']:.1e} | "
                      f"{case['two_scale_asperity_force_error']:.1e} | {case['macro_force_error']:.1e} | "
                      f"{case['macro_asperity_force_error']:.1e} | {case['full_force_error']:.1e} | "
                      f"{case['two_scale_iterations']} | {case['two_scale_cpu_speedup']:.2f} | "
                      f"{case['macro_cpu_speedup']:.1f} | {case['load_average']:.1f} |", flush=True)
    if args.json:
        args.json.write_text(json.dumps({"host": host_info(), "args": {k: str(v) for k, v in vars(args).items()},
                                         "rows": rows}, indent=1))


if __name__ == "__main__":
    main()
