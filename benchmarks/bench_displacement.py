"""Periodic displacement control: the dual solver against the plain primal iteration.

For each N one self-affine surface is pressed by penetrations that are fractions of its mean
separation ``mean(max h - h)`` (the full-contact limit). Each is solved by
:func:`contactlib.solvers.solve_periodic_displacement` (what :func:`contactlib.solve` runs) and by
the unpreconditioned primal :func:`contactlib.solvers.solve_polonsky_keer`, at ``--tol``; the
pressure fields are compared with a tighter dual solve. Times are medians of ``--repeats`` after a
warm-up; both solvers use the same planned FFTs.

    python -m benchmarks.bench_displacement --sizes 256 512 1024 --json results/bench_displacement.json
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

import contactlib
from contactlib.core.grid import Grid
from contactlib.model.operators import Compliance
from contactlib.solvers import solve_periodic_displacement, solve_polonsky_keer

from .common import timed


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[256, 512, 1024])
    ap.add_argument("--fractions", type=float, nargs="+", default=[0.6, 0.9, 0.97, 0.999],
                    help="penetration / mean separation")
    ap.add_argument("--tol", type=float, default=1e-8)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--max-iter", type=int, default=5000)
    ap.add_argument("--json", type=Path)
    args = ap.parse_args(argv)
    rows = []
    print(f"contactlib {contactlib.__version__}, tol {args.tol:g}, 1 FFTW thread, spectral kernel; "
          "surface self_affine(N, hurst=0.8, q_roll=4, q_cutoff=N/8, rms_slope=0.1, seed=1), E* = 1\n")
    print("| N | penetration / mean separation | contact | dual it | dual [s] | primal it | primal [s] | "
          "primal status | time primal / dual | dual error | primal error |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for n in args.sizes:
        h = contactlib.surfaces.self_affine(n, hurst=0.8, q_roll=4, q_cutoff=n / 8, rms_slope=0.1, seed=1).values
        op = Compliance(Grid(h.shape, (1.0, 1.0)), E_star=1.0)
        depth = float(np.mean(h.max() - h))
        for fraction in args.fractions:
            d = fraction * depth
            ref = solve_periodic_displacement(op, h, penetration=d, tol=args.tol * 1e-3, max_iter=args.max_iter)
            t_dual, dual = timed(lambda d=d, op=op, h=h: solve_periodic_displacement(op, h, penetration=d, tol=args.tol,
                                                                          max_iter=args.max_iter), args.repeats, warm=True)
            t_primal, primal = timed(lambda d=d, op=op, h=h: solve_polonsky_keer(op, h, penetration=d, tol=args.tol,
                                                                      max_iter=args.max_iter), args.repeats, warm=True)
            norm = np.linalg.norm(ref.pressure)
            row = {"n": n, "fraction": fraction, "contact_area": float(np.mean(dual.pressure > 0)),
                   "dual_iterations": dual.iterations, "dual_s": t_dual, "dual_residual": dual.residual,
                   "primal_iterations": primal.iterations, "primal_s": t_primal, "primal_residual": primal.residual,
                   "primal_converged": primal.converged, "reference_residual": ref.residual,
                   "dual_error": float(np.linalg.norm(dual.pressure - ref.pressure) / norm),
                   "primal_error": float(np.linalg.norm(primal.pressure - ref.pressure) / norm)}
            rows.append(row)
            status = "converged" if primal.converged else f"stopped, residual {primal.residual:.1e}"
            print(f"| {n} | {fraction:g} | {row['contact_area']:.3f} | {dual.iterations} | {t_dual:.3f} | "
                  f"{primal.iterations} | {t_primal:.3f} | {status} | {t_primal / t_dual:.1f} | "
                  f"{row['dual_error']:.1e} | {row['primal_error']:.1e} |", flush=True)
    if args.json:
        args.json.write_text(json.dumps(rows, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
