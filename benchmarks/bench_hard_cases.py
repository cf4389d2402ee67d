"""Iterations, time and memory of the hard-case scenes, plus the ones too large for the test suite.

The scenes are :data:`contactlib.testing.HARD_CASES`, those of ``tests/test_hard_cases.py`` (so a scene added to
the suite is reported here too) and, with ``--large``, a 2D self-affine surface at N = 4096
(10 % contact, load control): time, iterations, residual and the process' peak resident memory. With
``--cohesive N``, issue 38's hard cohesive case on N^2 (a Maugis sphere at lambda = 5, ``paraboloid(N, length=0.25,
radius=1)``, ``E = 1, nu = 0.5``, ``work = 1e-4, range = 4e-4``, non-periodic, penetration 0.002: at N = 512 the
issue's scene, its process zone 3.4 N / 512 elements) beside the plain solve of the same scene, bounded by
``--cohesive-timeout`` seconds (the solve is run in a child process and stopped there).

    python -m benchmarks.bench_hard_cases [--large 4096] [--cohesive 512] [--json results/bench_hard_cases.json]
"""

from __future__ import annotations

import argparse
import json
import resource
import sys
import time
from pathlib import Path

import numpy as np

import contactlib
from contactlib.testing import HARD_CASE_E as E
from contactlib.testing import HARD_CASE_NU as NU
from contactlib.testing import HARD_CASES


def peak_rss_mib() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024  # Linux: KiB


def run(name, heights, solve_kwargs) -> dict:
    kwargs = {"tol": 1e-8, **solve_kwargs}
    t0 = time.perf_counter()
    try:
        out = contactlib.solve(heights, E=E, nu=NU, **kwargs)
        status = "converged"
    except contactlib.ConvergenceError as err:
        out, status = err.dataset, f"not converged (residual {err.residual:.1e})"
    seconds = time.perf_counter() - t0
    p, g = out.pressure.values, out.gap.values
    return {"scene": name, "shape": list(heights.shape), "status": status, "seconds": seconds,
            "iterations": int(out.iterations), "residual": float(out.residual),
            "contact_area": float(out.contact_area), "min_pressure": float(p.min()),
            "max_interpenetration": float(np.maximum(-g, 0).max()), "peak_rss_mib": peak_rss_mib()}


def _cohesive_child(n, queue) -> None:
    heights = contactlib.surfaces.paraboloid(n, length=0.25, radius=1.0)
    law = contactlib.Adhesion(work=1e-4, range=4.0e-4, model="maugis")
    queue.put(run(f"Maugis sphere lambda = 5, {n} x {n}", heights,
                  {"penetration": 0.002, "periodic": False, "adhesion": law, "tol": 1e-6}))


def cohesive_sphere(n, timeout) -> list[dict]:
    """The plain and the cohesive solve of the hard cohesive sphere on ``n^2`` (the cohesive one in a child process
    stopped after ``timeout`` seconds)."""
    import multiprocessing

    heights = contactlib.surfaces.paraboloid(n, length=0.25, radius=1.0)
    rows = [run(f"plain sphere, {n} x {n}", heights, {"penetration": 0.002, "periodic": False})]
    queue = multiprocessing.get_context("fork").Queue()
    child = multiprocessing.get_context("fork").Process(target=_cohesive_child, args=(n, queue))
    t0 = time.perf_counter()
    child.start()
    child.join(timeout)
    if child.is_alive():
        child.terminate()
        child.join()
        rows.append({"scene": f"Maugis sphere lambda = 5, {n} x {n}", "shape": [n, n],
                     "status": f"stopped after {timeout:g} s", "seconds": time.perf_counter() - t0, "iterations": -1,
                     "residual": float("nan"), "contact_area": float("nan"), "min_pressure": float("nan"),
                     "max_interpenetration": float("nan"), "peak_rss_mib": peak_rss_mib()})
    else:
        rows.append(queue.get())
    return rows


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--large", type=int, nargs="*", default=[4096], help="2D grid sizes of the large scene")
    parser.add_argument("--cohesive", type=int, nargs="*", default=[], help="grid sizes of the cohesive sphere")
    parser.add_argument("--cohesive-timeout", type=float, default=600.0)
    parser.add_argument("--json", type=Path)
    args = parser.parse_args(argv)

    # load the compiled sweeps
    contactlib.solve(np.ones((8, 8)) - np.eye(8), length=1.0, E=E, nu=NU, mean_pressure=0.01)
    rows = []
    for scene in HARD_CASES:
        rows.append(run(scene.name, scene.surface(), scene.solve))
        print(f"{rows[-1]['scene']}: {rows[-1]['seconds']:.2f} s", file=sys.stderr, flush=True)
    for n in args.large:
        heights = contactlib.surfaces.self_affine(n, hurst=0.8, q_roll=4, q_cutoff=n // 8, rms_slope=0.1, seed=1)
        # mean pressure for ~10 % contact: kappa ~ 2 in A = kappa p / (E* rms_slope)
        rows.append(run(f"self-affine {n} x {n}, ~10 % contact", heights,
                        {"mean_pressure": 0.1 / 2.0 * (E / (1 - NU**2)) * 0.1}))
        print(f"{rows[-1]['scene']}: {rows[-1]['seconds']:.2f} s", file=sys.stderr, flush=True)

    for n in args.cohesive:
        for row in cohesive_sphere(n, args.cohesive_timeout):
            rows.append(row)
            print(f"{row['scene']}: {row['seconds']:.2f} s", file=sys.stderr, flush=True)

    print(f"contactlib {contactlib.__version__}, tol 1e-8, 1 FFTW thread; peak RSS is the whole process' so far\n")
    print("| scene | shape | status | time [s] | iterations | residual | contact area | min p | max overlap | "
          "peak RSS [MiB] |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['scene']} | {'x'.join(map(str, r['shape']))} | {r['status']} | {r['seconds']:.2f} | "
              f"{r['iterations']} | {r['residual']:.1e} | {r['contact_area']:.4g} | {r['min_pressure']:.1e} | "
              f"{r['max_interpenetration']:.1e} | {r['peak_rss_mib']:.0f} |")
    if args.json:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
