"""Two-scale asperity method in viscoelastic time stepping against contactlib's full transient solver: per-asperity
force error and wall time of creep under a constant load (issue 17, viscoelastic extension).

A sparse field of :func:`contactlib.two_scale.random_asperity_field` (periodic unit window, ``--count``
asperities at ``--coverage``, grid for ``--nodes-per-radius`` nodes per mean Hertz contact radius at the
approach of :mod:`contactlib.studies.two_scale`) on a standard linear solid (``E_inf / E0 = --ratio``,
``tau = 1``), loaded at once at ``t = 0`` with the glassy load of ``--approach`` times the mean summit height
(macro estimate) and held over ``--steps`` steps to ``--t-end``:

* **reference**: ``contactlib.solve_transient(..., tol=--ref-tol)`` (1e-8), fields kept, forces summed over
  each footprint;
* **full**: ``contactlib.solve_transient(..., tol=--full-tol)`` (1e-4), timed (fields kept at every step for
  its error: three array copies a step);
* **two-scale**: ``contactlib.two_scale.solve_transient(..., tol=--two-scale-tol)`` (1e-3), or with
  ``--two-scale-force-tol``, ``force_tol=`` (each step's sweeps stop on the asperity forces' estimated change),
  timed;
* **macro**: ``scale="macro"``, timed.

Errors: max over steps and asperities of ``|P_k - P_k^ref|`` over the step's largest ``P_k^ref``. One timed
run each, after one warm-up step of each (FFT plans); ratios are full / method from the same run.

Run ``python -m benchmarks.bench_two_scale_transient --help``; ``--json`` writes every number.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np

import contactlib
from contactlib import two_scale
from contactlib.studies.two_scale import nodes_per_spacing

from .common import host_info, timed

NU = 0.5


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--count", type=int, default=100)
    parser.add_argument("--coverage", type=float, default=0.05)
    parser.add_argument("--nodes-per-radius", type=float, default=3.0)
    parser.add_argument("--ratio", type=float, default=2.0, help="E_inf / E0")
    parser.add_argument("--approach", type=float, default=0.3, help="glassy approach over the mean summit height")
    parser.add_argument("--steps", type=int, default=10)
    parser.add_argument("--t-end", type=float, default=5.0)
    parser.add_argument("--ref-tol", type=float, default=1e-8)
    parser.add_argument("--full-tol", type=float, default=1e-4)
    parser.add_argument("--two-scale-tol", type=float, default=1e-3)
    parser.add_argument("--two-scale-force-tol", type=float, default=None,
                        help="run the two-scale method with force_tol= instead of tol=--two-scale-tol")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--json", type=Path)
    args = parser.parse_args(argv)

    m = contactlib.Viscoelastic.standard_linear_solid(E0=1.0, E_inf=args.ratio, tau=1.0, nu=NU)
    nps = nodes_per_spacing(args.coverage, args.nodes_per_radius)
    field = two_scale.random_asperity_field(args.count, coverage=args.coverage, nodes_per_spacing=nps, seed=args.seed)
    table = two_scale.asperity_table(field)
    summit = float(table.summit_height.mean())
    load = float(two_scale.solve(field, E=m.E_inf, nu=NU, penetration=args.approach * summit, scale="macro",
                                 fields=False).mean_pressure)
    times = np.linspace(0.0, args.t_end, args.steps + 1)
    common = {"material": m, "times": times, "mean_pressure": load}
    stop = {"tol": args.two_scale_tol} if args.two_scale_force_tol is None else {"force_tol": args.two_scale_force_tol}

    reference = contactlib.solve_transient(field, tol=args.ref_tol, save_fields=True, **common)
    ref_forces = np.array([two_scale.asperity_forces(p, table) for p in reference.pressure])
    for fn, kw in ((contactlib.solve_transient, {"tol": args.full_tol}),
                   (two_scale.solve_transient, stop),
                   (two_scale.solve_transient, {"scale": "macro"})):  # warm-up: one step of each
        fn(field, material=m, times=times[:1], mean_pressure=load, **kw)
    full_time, full = timed(lambda: contactlib.solve_transient(field, tol=args.full_tol, save_fields=True, **common), 1)
    two_time, two = timed(lambda: two_scale.solve_transient(field, **stop, **common), 1)
    macro_time, macro = timed(lambda: two_scale.solve_transient(field, scale="macro", **common), 1)

    def error(forces):
        return float(np.max(np.abs(forces - ref_forces).max(axis=1) / ref_forces.max(axis=1)))

    full_forces = np.array([two_scale.asperity_forces(p, table) for p in full.pressure])
    row = {"count": args.count, "coverage": args.coverage, "n": int(field.shape[0]), "steps": args.steps + 1,
           "in_contact_first": int(np.count_nonzero(ref_forces[0] > 0)),
           "in_contact_last": int(np.count_nonzero(ref_forces[-1] > 0)),
           "approach_growth": float(reference.penetration[-1] / reference.penetration[0]),
           "full_time": full_time, "two_scale_time": two_time, "macro_time": macro_time,
           "two_scale_speedup": full_time / two_time, "macro_speedup": full_time / macro_time,
           "full_error": error(full_forces), "two_scale_error": error(two.force.values),
           "macro_error": error(macro.force.values), "two_scale_iterations": int(two.iterations.sum())}
    print(f"# bench_two_scale_transient ({host_info()})\n")
    print("| N | coverage | n | steps | in contact (first, last) | approach growth | full s | two-scale s | macro s | "
          "full/two-scale | full/macro | full err | two-scale err | macro err |")
    print("|" + "---|" * 14)
    print(f"| {row['count']} | {row['coverage']} | {row['n']} | {row['steps']} | {row['in_contact_first']}, "
          f"{row['in_contact_last']} | {row['approach_growth']:.2f} | {full_time:.3g} | {two_time:.3g} | "
          f"{macro_time:.3g} | {row['two_scale_speedup']:.2f} | {row['macro_speedup']:.1f} | {row['full_error']:.1e} | "
          f"{row['two_scale_error']:.1e} | {row['macro_error']:.1e} |")
    if args.json:
        args.json.write_text(json.dumps({"host": host_info(), "args": {k: str(v) for k, v in vars(args).items()},
                                         "rows": [row]}, indent=1))


if __name__ == "__main__":
    main()
