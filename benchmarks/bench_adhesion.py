"""Adhesive solves: contactlib against tamaas 2.9 on the same scene and tolerance, and adhesive against
non-adhesive contactlib solves.

Scene (:func:`contactlib.testing.adhesive_rough_scene`, that of the tamaas test): a periodic self-affine surface
(Hurst 0.8, rolloff 4, cutoff 32 wavelengths, rms slope 0.1) on ``N x N``, ``E = 1``, ``nu = 0``, mean
pressure 0.01, work 1e-5, range 1e-3 (process zone 5 elements at N = 256). Both laws. Tolerances: tamaas 1e-10 on its own residual, contactlib 1e-8 on its scale-free one
(the tamaas test agrees within 1e-3 in area and mean gap at these). Prints medians over ``--repeats``
runs (a warm-up first; tamaas' from ``--peer-warm-up-below`` on is not warmed up: minutes a solve), the ratio
contactlib / tamaas measured in the same run, the adhesive / non-adhesive ratio (the two interleaved, medians),
the adhesive solve's CG iterations and frozen-traction rounds against the plain solve's iterations, its method,
and the differences in area and mean gap. ``adh/plain cpu`` is the same ratio in process time (medians of the
same pairs): on a machine shared with other jobs it moves less than the wall-clock one.

    python -m benchmarks.bench_adhesion --sizes 256 512 1024 --repeats 3
"""

from __future__ import annotations

import argparse
import statistics
import time

import contactlib
from contactlib.testing import adhesive_rough_scene
from contactlib.testing import solve_tamaas_adhesive as solve_tamaas

from .common import timed


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[256, 512, 1024])
    parser.add_argument("--models", nargs="+", default=["exponential", "maugis"])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--peer-repeats", type=int, default=None,
                        help="tamaas' repeats (default --repeats; 0: tamaas is not run, its columns are NaN)")
    parser.add_argument("--peer-warm-up-below", type=int, default=1024,
                        help="warm tamaas up only below this N (its solves at 1024^2 take minutes)")
    args = parser.parse_args(argv)
    print(f"{'N':>5} {'law':>12} {'tamaas s':>9} {'contactlib s':>12} {'ratio':>6} {'plain s':>8} {'adh/plain':>9} "
          f"{'adh/plain cpu':>13} "
          f"{'its':>4} {'rounds':>6} {'plain its':>9} {'method':>15} {'d area':>8} {'d gap/gap':>9}")
    for n in args.sizes:
        for model in args.models:
            h, scene = adhesive_rough_scene(n, model=model)
            law = scene["adhesion"]
            work, range_, load = law.work, law.range, scene["mean_pressure"]
            if args.peer_repeats == 0:
                t_peer, peer = float("nan"), {"contact_area": float("nan"), "mean_gap": float("nan")}
            else:
                bare = h.transpose("x", "y").values  # [ix, iy], as tamaas indexes it
                t_peer, peer = timed(lambda: solve_tamaas(bare, E=1.0, nu=0.0, work=work, range_=range_,
                                                          model=model, mean_pressure=load, tol=1e-10),
                                     args.repeats if args.peer_repeats is None else args.peer_repeats,
                                     warm=n < args.peer_warm_up_below)
            # the adhesive and the plain solve interleaved, so that both see the same load on the machine
            times, plain_times, cpu, plain_cpu = [], [], [], []
            for k in range(args.repeats + 1):
                start, start_cpu = time.perf_counter(), time.process_time()
                ds = contactlib.solve(h, E=1.0, nu=0.0, mean_pressure=load, tol=1e-8, adhesion=law)
                middle, middle_cpu = time.perf_counter(), time.process_time()
                plain = contactlib.solve(h, E=1.0, nu=0.0, mean_pressure=load, tol=1e-8)
                if k:  # the first pair is the warm-up
                    times.append(middle - start)
                    plain_times.append(time.perf_counter() - middle)
                    cpu.append(middle_cpu - start_cpu)
                    plain_cpu.append(time.process_time() - middle_cpu)
            t_ours, t_plain = statistics.median(times), statistics.median(plain_times)
            cpu_ratio = statistics.median(cpu) / statistics.median(plain_cpu)
            gap = float(ds.gap.mean() - ds.gap.min())
            print(f"{n:>5} {model:>12} {t_peer:>9.3f} {t_ours:>12.3f} {t_ours / t_peer:>6.2f} {t_plain:>8.3f} "
                  f"{t_ours / t_plain:>9.2f} {cpu_ratio:>13.2f} {int(ds.iterations):>4} {int(ds.outer_iterations):>6} "
                  f"{int(plain.iterations):>9} "
                  f"{ds.attrs['solver'].split()[0]:>15} {float(ds.contact_area) - peer['contact_area']:>+8.1e} "
                  f"{(gap - peer['mean_gap']) / peer['mean_gap']:>+9.1e}", flush=True)


if __name__ == "__main__":
    main()
