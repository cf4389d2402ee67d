"""When to restart the conjugacy: Polonsky & Keer's rule (every re-entry) against contactlib's default
(re-entries of more than ``RESTART_FRACTION`` of the contact set), on rough and smooth scenes.

Each scene is solved under load control at ``--tol`` with both rules, and once tightly (tol 1e-12,
Polonsky & Keer's rule, or the default where that stalls) as the reference of the pressure error.
Prints a markdown table: contact fraction, iterations, time, error and status per rule.
Run ``python -m benchmarks.bench_restart --help``.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

import contactlib
from contactlib.core.grid import Grid
from contactlib.model.operators import Compliance
from contactlib.solvers import solve_polonsky_keer
from contactlib.solvers.symmetric.ccg import RESTART_FRACTION

RULES = {"every re-entry": 0.0, f"default ({RESTART_FRACTION:g})": RESTART_FRACTION}


def scenes(args):
    """(name, heights, periodic, mean pressure) of every scene."""
    n = args.n2d
    for hurst in (0.3, 0.8, 0.95):
        h = contactlib.surfaces.self_affine(n, hurst=hurst, q_roll=4, q_cutoff=n // 4, rms_slope=0.2, seed=3).values
        for mean_pressure in (1e-4, 1e-3, 1e-2, 0.05, 0.2):
            yield f"2D {n}^2, H = {hurst}", h, True, mean_pressure
    for n in args.large:
        h = contactlib.surfaces.self_affine(n, hurst=0.8, q_roll=4, q_cutoff=n // 8, rms_slope=0.1, seed=1).values
        for mean_pressure in (0.003, 0.03):
            yield f"2D {n}^2, H = 0.8", h, True, mean_pressure
    n = args.n1d
    h = contactlib.surfaces.self_affine(n, hurst=0.8, q_roll=4, q_cutoff=n // 4, rms_slope=0.1, seed=1, dim=1).values
    for mean_pressure in (1e-3, 1e-2, 0.05):
        yield f"1D {n}, H = 0.8", h, True, mean_pressure
    x = (np.arange(256) - 128) / 256
    yield "Hertz 256^2, non-periodic", -(x[:, None] ** 2 + x[None, :] ** 2) / 2, False, 1e-3
    h = contactlib.surfaces.self_affine(512, hurst=0.8, q_roll=4, q_cutoff=128, rms_slope=0.1, seed=4).values
    yield "2D 512^2, H = 0.8, non-periodic", h, False, 0.01


def run_scene(name, heights, periodic, mean_pressure, args) -> dict:
    op = Compliance(Grid(heights.shape, (1.0,) * heights.ndim), E_star=1.0, periodic=periodic)
    ref = solve_polonsky_keer(op, heights, mean_pressure=mean_pressure, tol=1e-12, max_iter=args.max_iter,
                              restart_fraction=0.0)
    if not ref.converged:
        ref = solve_polonsky_keer(op, heights, mean_pressure=mean_pressure, tol=1e-12, max_iter=args.max_iter)
    row = {"scene": name, "mean_pressure": mean_pressure, "contact": float(np.mean(ref.pressure > 0)),
           "reference_residual": ref.residual, "rules": {}}
    for rule, fraction in RULES.items():
        times = []
        for _ in range(args.repeats):
            t0 = time.perf_counter()
            s = solve_polonsky_keer(op, heights, mean_pressure=mean_pressure, tol=args.tol, max_iter=args.max_iter,
                                    restart_fraction=fraction)
            times.append(time.perf_counter() - t0)
        error = float(np.linalg.norm(s.pressure - ref.pressure) / np.linalg.norm(ref.pressure))
        row["rules"][rule] = {"iterations": s.iterations, "seconds": float(np.median(times)), "error": error,
                              "converged": s.converged, "residual": s.residual}
    return row


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--n2d", type=int, default=512)
    ap.add_argument("--large", type=int, nargs="*", default=[1024, 2048], help="2D sizes at 10 and 50 %% contact")
    ap.add_argument("--n1d", type=int, default=65536)
    ap.add_argument("--tol", type=float, default=1e-8)
    ap.add_argument("--repeats", type=int, default=1)
    ap.add_argument("--max-iter", type=int, default=20000)
    ap.add_argument("--json", type=Path)
    args = ap.parse_args(argv)
    rows = []
    names = list(RULES)
    print(f"contactlib {contactlib.__version__}, load control, spectral kernel, preconditioned, tol {args.tol:g}, "
          "1 FFTW thread; error = rel. L2 pressure error against tol 1e-12\n")
    print(f"| scene | mean pressure / E* | contact | {' | '.join(f'{r}: iterations, time [s], error' for r in names)} "
          "| iterations ratio |")
    print("|---|---|---|" + "---|" * len(names) + "---|")
    for scene in scenes(args):
        row = run_scene(*scene, args)
        rows.append(row)
        cells = []
        for r in names:
            v = row["rules"][r]
            status = "" if v["converged"] else f" (stalled at {v['residual']:.0e})"
            cells.append(f"{v['iterations']}, {v['seconds']:.3g}, {v['error']:.1e}{status}")
        ratio = row["rules"][names[0]]["iterations"] / max(row["rules"][names[1]]["iterations"], 1)
        print(f"| {row['scene']} | {row['mean_pressure']:g} | {row['contact']:.3f} | {' | '.join(cells)} "
              f"| {ratio:.2f} |", flush=True)
    if args.json:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps(rows, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
