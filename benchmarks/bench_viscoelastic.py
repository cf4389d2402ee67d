"""What steady viscoelastic sliding costs over the elastic solve of the same scene.

Two measurements, printed as markdown tables (machine and versions in the header) and written with every
number to ``--json``:

1. **steady**: a 2D self-affine surface (``--sizes``, q_cutoff = n/8, rms slope 0.1) on a standard linear
   solid (``--ratio`` E_inf/E0 = 10, nu = 0.5), sliding along x at ``zeta = V tau q0`` (``--zetas``, the
   middle of the band by default), over the elastic solve of the same surface at the relaxed modulus E0,
   each at the mean pressure that gives ``--contact`` (10 % and 50 %) elastically. Interleaved repeats,
   medians; iterations and outer iterations reported.
2. **sweep**: ``--sweep-speeds`` speeds log-spaced over ``zeta`` 1e-3..1e3, walked upwards (``--walks``): each
   solve warm-started from the last (``warm``), from :func:`contactlib.solve_speeds`' prediction without
   (``path``) and with (``recycle``) the GMRES vectors carried across solves (:mod:`contactlib.solvers.recycle`),
   and each cold (as the ``friction_speed`` study does), over one elastic solve; GMRES iterations and
   contact-set updates in all.
3. **floor** (``--floor``, with the ``path`` walk): what the elastic solver itself would take from starts as far
   off as the path's. At each speed after the first, the elastic solve (E0) starts from its own answer moved by
   the path's start error there (the prediction minus that speed's answer, scaled to the elastic pressure's
   norm, clipped at zero; the clipped start's own distance is reported beside the walk's); the first speed counts
   one cold elastic solve. Their total time (medians of ``--repeats``) over one cold elastic solve is the sweep
   ratio an elastic-speed solver would reach from starts as good as this walk's.

Run ``python -m benchmarks.bench_viscoelastic --help``.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import time
from pathlib import Path

import numpy as np

import contactlib

from .common import host_info
from .common import load_for_contact as load_for
from .common import sliding_surface as surface
from .common import timed


def elastic_floor(h, p: float, zetas, answers: list, tol: float, elastic_s: float, repeats: int) -> dict:
    """The elastic solver (E0) from starts as far off as the path walk's (see the module docstring, 3.), its
    iterations and time per speed (median of ``repeats``); printed as a table, returned for ``--json``."""
    cold = contactlib.solve(h, E=1.0, nu=0.5, mean_pressure=p, tol=tol)
    elastic = cold.pressure.transpose("x", ...).values  # [ix, iy]: the starts below are bare warm starts
    scale = np.linalg.norm(elastic)
    rows, total_s, total_its = [], elastic_s, int(cold.iterations)  # the first speed: one cold solve
    print("\n| zeta | path start error (relative L2) | elastic start error (after clipping) | elastic iterations "
          f"from as far off (cold: {int(cold.iterations)}) | elastic time [s] |\n|---|---|---|---|---|")
    for k in range(1, len(answers)):
        error = contactlib.predict_pressure(list(zetas[:k]), answers[:k], zetas[k]) - answers[k]
        norm = np.linalg.norm(answers[k])
        start = np.clip(elastic + error * (scale / norm), 0.0, None)
        t, out = timed(lambda: contactlib.solve(h, E=1.0, nu=0.5, mean_pressure=p, tol=tol, initial_pressure=start),
                       repeats)
        rows.append({"zeta": float(zetas[k]), "start_error": float(np.linalg.norm(error) / norm),
                     "elastic_start_error": float(np.linalg.norm(start - elastic) / scale),
                     "iterations": int(out.iterations), "elastic_s": t})
        total_s += t
        total_its += int(out.iterations)
        print(f"| {zetas[k]:.3g} | {rows[-1]['start_error']:.3f} | {rows[-1]['elastic_start_error']:.3f} | "
              f"{rows[-1]['iterations']} | {t:.3f} |")
    print(f"\n# elastic floor: {total_its} elastic iterations over the sweep ({int(cold.iterations)} cold), "
          f"{total_s:.2f} s = {total_s / elastic_s:.1f}x one elastic solve ({elastic_s:.3f} s)")
    return {"speeds": rows, "iterations": total_its, "cold_iterations": int(cold.iterations), "s": total_s,
            "ratio": total_s / elastic_s}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[512, 1024])
    ap.add_argument("--contact", type=float, nargs="+", default=[0.1, 0.5])
    ap.add_argument("--zetas", type=float, nargs="+", default=[1.0])
    ap.add_argument("--ratio", type=float, default=10.0)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--sweep-speeds", type=int, default=30)
    ap.add_argument("--sweep-size", type=int, default=512)
    ap.add_argument("--tol", type=float, default=1e-8)
    ap.add_argument("--walks", nargs="+", default=["warm", "path", "recycle", "cold"],
                    choices=["warm", "path", "recycle", "cold"],
                    help="sweep walks: from the last speed's pressure, from contactlib.solve_speeds' prediction "
                         "(without, with the carried Krylov vectors), from scratch")
    ap.add_argument("--floor", action="store_true",
                    help="with the path walk: the elastic solver from starts as far off as the path's")
    ap.add_argument("--json", type=Path)
    args = ap.parse_args(argv)
    if args.floor and "path" not in args.walks:
        ap.error("--floor needs the path walk (--walks path)")
    material = contactlib.Viscoelastic.standard_linear_solid(E0=1.0, E_inf=args.ratio, tau=1.0, nu=0.5)
    info = host_info()
    print(f"# steady viscoelastic sliding against elastic ({info.get('cpu', '?')}, contactlib {contactlib.__version__})")
    print("\n| n | contact | zeta | elastic [s] | viscoelastic [s] | ratio | iterations (outer) | area elastic -> sliding |")
    print("|---|---|---|---|---|---|---|---|")
    rows = []
    for n in args.sizes:
        h = surface(n)
        q0 = 2 * np.pi / 1.0
        for target in args.contact:
            p = load_for(h, target)
            for zeta in args.zetas:
                V = (zeta / q0, 0.0)

                def elastic():
                    return contactlib.solve(h, E=1.0, nu=0.5, mean_pressure=p, tol=args.tol)

                def sliding():
                    return contactlib.solve(h, material=material, mean_pressure=p, sliding_velocity=V, tol=args.tol)

                elastic(), sliding()  # warm-up: FFTW plans
                te, oe, tv, ov = [], None, [], None
                for _ in range(args.repeats):  # interleaved: the machine's load hits both alike
                    t, oe = timed(elastic, 1)
                    te.append(t)
                    t, ov = timed(sliding, 1)
                    tv.append(t)
                row = {"n": n, "contact": target, "zeta": zeta, "elastic_s": statistics.median(te),
                       "viscoelastic_s": statistics.median(tv), "iterations": int(ov.iterations),
                       "outer_iterations": int(ov.get("outer_iterations", 0)), "elastic_iterations": int(oe.iterations),
                       "area_elastic": float(oe.contact_area), "area_sliding": float(ov.contact_area)}
                row["ratio"] = row["viscoelastic_s"] / row["elastic_s"]
                rows.append(row)
                print(f"| {n} | {target:.0%} | {zeta:g} | {row['elastic_s']:.3f} | {row['viscoelastic_s']:.3f} | "
                      f"{row['ratio']:.1f}x | {row['iterations']} ({row['outer_iterations']}) vs "
                      f"{row['elastic_iterations']} | {row['area_elastic']:.3f} -> {row['area_sliding']:.3f} |",
                      flush=True)
    h = surface(args.sweep_size)
    p = load_for(h, 0.1)
    zetas = np.logspace(-3, 3, args.sweep_speeds)
    elastic_times, elastic_cpu = [], []

    def time_elastic():  # before and after every walk: the machine's load moves during a sweep
        for _ in range(args.repeats):
            c0 = time.process_time()
            elastic_times.append(timed(lambda: contactlib.solve(h, E=1.0, nu=0.5, mean_pressure=p, tol=args.tol), 1)[0])
            elastic_cpu.append(time.process_time() - c0)

    time_elastic()
    walks, cpu, paths = {}, {}, {}
    velocities = [(zeta / (2 * np.pi), 0.0) for zeta in zetas]
    for walk in args.walks:  # warm: from the last speed's pressure; path: predicted; cold: each from scratch
        t0, c0, warm, outs = time.perf_counter(), time.process_time(), None, []
        if walk in ("path", "recycle"):
            outs = contactlib.solve_speeds(h, velocities, material=material, mean_pressure=p, tol=args.tol,
                                           recycle=walk == "recycle")
        for velocity in velocities if walk not in ("path", "recycle") else ():
            out = contactlib.solve(h, material=material, mean_pressure=p, sliding_velocity=velocity,
                                   tol=args.tol, initial_pressure=warm)
            warm = out.pressure if walk == "warm" else None
            outs.append(out)
        paths[walk] = outs
        walks[walk] = (time.perf_counter() - t0, sum(int(out.iterations) for out in outs),
                       sum(int(out.get("outer_iterations", 0)) for out in outs))
        cpu[walk] = time.process_time() - c0
        time_elastic()
    t_el, c_el = statistics.median(elastic_times), statistics.median(elastic_cpu)
    sweep = {"n": args.sweep_size, "speeds": args.sweep_speeds, "elastic_s": t_el, "load": os.getloadavg(),
             "elastic_times": elastic_times, "elastic_cpu_s": c_el, **{f"{w}_cpu_s": c for w, c in cpu.items()},
             **{f"{w}_s": t for w, (t, _, _) in walks.items()},
             **{f"{w}_iterations": i for w, (_, i, _) in walks.items()},
             **{f"{w}_set_updates": u for w, (_, _, u) in walks.items()},
             **{f"{w}_ratio": t / t_el for w, (t, _, _) in walks.items()}}
    for walk, (t, its, updates) in walks.items():
        print(f"\n# speed sweep ({walk}): {args.sweep_speeds} speeds, zeta 1e-3..1e3, {args.sweep_size}^2 at 10 % "
              f"contact: {t:.2f} s = {t / t_el:.1f}x one elastic solve ({t_el:.3f} s), {its} iterations, "
              f"{updates} set updates; CPU time {cpu[walk]:.2f} s = {cpu[walk] / c_el:.1f}x ({c_el:.3f} s) "
              f"(load {os.getloadavg()[0]:.1f})")
    if args.floor:
        answers = [out.pressure.transpose("x", ...).values for out in paths["path"]]  # [ix, iy]: bare warm starts
        sweep["floor"] = elastic_floor(h, p, zetas, answers, args.tol, t_el, args.repeats)
    if args.json:
        args.json.write_text(json.dumps({"host": info, "steady": rows, "sweep": sweep}, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
