"""The semismooth Newton loop with GMRES on the complex multiplier against the fixed point on the skew part
(the dispatch before it) and the elastic/frictionless solve of the same scene, interleaved.

Scenes on a 2D self-affine surface (``--n``, q_cutoff = n/8, rms slope 0.1, seed 1), each at the mean pressure
giving ``--contact`` elastically (nu = 0.5 half-space, as ``bench_viscoelastic.py``): Coulomb friction mu = 1 on a
nu = 0.3 half-space, a confined incompressible layer at q0 h = 1 with mu = 1, and a standard linear solid
(E_inf/E0 = 10, nu = 0.5) at V tau q0 = 1. Each row: median CPU seconds (``time.process_time``: less sensitive to
a shared machine than the wall clock) of ``--repeats`` interleaved solves, iterations (outer), and the pressure
difference between the two non-symmetric solvers.

Run ``python -m benchmarks.bench_krylov --help``.
"""

from __future__ import annotations

import argparse
import os
import statistics
import time

import numpy as np

import contactlib

from .common import load_for_contact as load_for
from .common import nonsymmetric_solve, prepared_problem
from .common import sliding_surface as surface


def scene(h, name, P, tol):
    layer, friction, velocity = None, 0.0, None
    if name == "friction":
        material = contactlib.Elastic(1.0, 0.3)
        friction = 1.0
    elif name == "layer":
        material, layer, friction = contactlib.Elastic(1.0, 0.5), contactlib.Layer(1 / (2 * np.pi)), 1.0
    else:
        material = contactlib.Viscoelastic.standard_linear_solid(E0=1.0, E_inf=10.0, tau=1.0, nu=0.5)
        velocity = (1 / (2 * np.pi), 0.0)

    def make(material, friction, velocity):
        return prepared_problem(h, material=material, mean_pressure=P, tol=tol, max_iter=10_000, layer=layer,
                                friction=friction, sliding_velocity=velocity)
    elastic = make(contactlib.Elastic(1.0, material.nu), 0.0, None)
    return elastic, make(material, friction, velocity)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--n", type=int, default=512)
    ap.add_argument("--contact", type=float, nargs="+", default=[0.1, 0.5])
    ap.add_argument("--scenes", nargs="+", default=["friction", "layer", "viscoelastic"])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--tol", type=float, default=1e-8)
    args = ap.parse_args(argv)
    h = surface(args.n)
    print(f"# n = {args.n}, tol {args.tol:g}, load average {os.getloadavg()[0]:.2f} at start")
    print("\n| scene | contact (elastic) | elastic [s], it | coupled: [s], it (outer), ratio | semismooth-gmres: [s], "
          "it (sets), ratio | new / coupled | dp | load |")
    print("|---|---|---|---|---|---|---|---|")
    for target in args.contact:
        P = load_for(h, target)
        for name in args.scenes:
            elastic, body = scene(h, name, P, args.tol)
            runs = {"elastic": lambda: nonsymmetric_solve(elastic, "dispatch"),
                    "coupled": lambda: nonsymmetric_solve(body, "coupled"),  # the dispatch before the Newton loop
                    "new": lambda: nonsymmetric_solve(body, "krylov")}
            for fn in runs.values():
                fn()  # warm-up: plans
            times = {k: [] for k in runs}
            out = {}
            for _ in range(args.repeats):
                for k, fn in runs.items():
                    t0 = time.process_time()
                    out[k] = fn()
                    times[k].append(time.process_time() - t0)
            t = {k: statistics.median(v) for k, v in times.items()}
            e, c, s = out["elastic"], out["coupled"], out["new"]
            dp = np.linalg.norm(s.pressure - c.pressure) / np.linalg.norm(c.pressure)
            print(f"| {name} | {target:.0%} ({np.mean(e.pressure > 0):.3f} -> {np.mean(s.pressure > 0):.3f}) | "
                  f"{t['elastic']:.3f}, {e.iterations} | {t['coupled']:.3f}, {c.iterations} ({c.outer_iterations}), "
                  f"{t['coupled'] / t['elastic']:.2f}x{'' if c.converged else ' NC'} | {t['new']:.3f}, {s.iterations} "
                  f"({s.outer_iterations}), {t['new'] / t['elastic']:.2f}x{'' if s.converged else ' NC'} | "
                  f"{t['new'] / t['coupled']:.2f} | {dp:.1e} | {os.getloadavg()[0]:.1f} |", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
