"""Time per iteration of load-controlled solves cut at a fixed iteration count: for comparing two
revisions of the solver on the same machine.

Run it alternately on two checkouts' contactlib (``PYTHONPATH=<checkout>:. python -P -m benchmarks.bench_periter
--label <name> ...`` from this repository's root: ``-P`` keeps the working directory's contactlib off the path),
several rounds, and compare the medians: one process per size and thread
count, a warm-up solve, then ``--repeats`` timed solves of ``--iterations`` iterations each at two
loads (about 10 % and 74 % contact on the default surface). Prints one line per size and thread
count: label, N, threads, milliseconds per iteration at each load.
"""

from __future__ import annotations

import argparse
import sys
import time

import numpy as np

from contactlib.core import fft
from contactlib.core.grid import Grid
from contactlib.model.operators import Compliance
from contactlib.solvers import solve_polonsky_keer
from contactlib.surfaces import self_affine


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--label", default="contactlib")
    ap.add_argument("--sizes", type=int, nargs="+", default=[512, 1024, 2048])
    ap.add_argument("--threads", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--mean-pressures", type=float, nargs="+", default=[0.005, 0.05], help="E* = 1/(1-0.0^2) = 1")
    ap.add_argument("--iterations", type=int, default=40)
    ap.add_argument("--repeats", type=int, default=7)
    args = ap.parse_args(argv)
    for n in args.sizes:
        heights = self_affine(n, hurst=0.8, rms_slope=0.1, q_roll=4, q_cutoff=n / 8, seed=1).values
        op = Compliance(Grid(heights.shape, (1.0, 1.0)), E_star=1.0)
        for threads in args.threads:
            fft.set_fft_options(threads=threads)
            per_iteration = []
            for mean_pressure in args.mean_pressures:
                solve_polonsky_keer(op, heights, mean_pressure=mean_pressure, tol=1e-8, max_iter=3)  # plans, compiles
                times = []
                for _ in range(args.repeats):
                    t0 = time.perf_counter()
                    state = solve_polonsky_keer(op, heights, mean_pressure=mean_pressure, tol=1e-8,
                                                max_iter=args.iterations)
                    times.append(time.perf_counter() - t0)
                per_iteration.append(1e3 * float(np.median(times)) / max(state.iterations, 1))
            print(args.label, n, threads, " ".join(f"{t:.2f}" for t in per_iteration), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
