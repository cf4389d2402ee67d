"""Cohesive spheres at large Maugis lambda: the time of a solve and of a path against the plain solve, and the answer
against Maugis' closed form (issue 38, "Hard cases converge").

Scene (issue 38's): ``paraboloid(N, length=0.25, radius=1)``, ``E = 1, nu = 0.5``, work ``1e-4``, the Maugis law of
parameter lambda, non-periodic, penetration 0.002 (Maugis' contact radius 0.073: 75 spacings at N = 256; other
approaches with ``--penetrations``). For each N, lambda and approach: the medians over ``--repeats`` of the plain
(non-adhesive) solve at that approach and of the adhesive one, interleaved so that both see the same load on the
machine, and their ratio; the force and the contact radius (the disc of the closed points' count about the apex)
against Maugis' at that lambda; the method. With ``--path K`` also an ``adhesion_curve`` along K penetrations from
-0.0005 to 0.002 and back (2K - 1 states): its time per state over the plain solve's (at the last approach).

    python -m benchmarks.bench_maugis --sizes 256 512 --lambdas 3.5 5 7 10 --repeats 3 --path 7
    python -m benchmarks.bench_maugis --sizes 256 384 512 --penetrations 0.001 0.002 --repeats 1
"""

from __future__ import annotations

import argparse
import math
import statistics
import time
import warnings

import numpy as np
import contactlib
from contactlib.reference import adhesive as ref
from contactlib.reference import maugis

E, NU, RADIUS, WORK, LENGTH, PENETRATION = 1.0, 0.5, 1.0, 1e-4, 0.25, 0.002
E_STAR = E / (1 - NU**2)
K = 4 * E_STAR / 3


def maugis_law(lam: float) -> contactlib.Adhesion:
    peak = lam / 2 * (math.pi * WORK * K**2 / RADIUS) ** (1 / 3)
    return contactlib.Adhesion(work=WORK, range=WORK / peak, model="maugis")


def interleaved(first, second, repeats: int) -> tuple[float, float, object]:
    """Median wall-clock times of ``first`` and ``second`` run alternately (after one warm-up of each) and the last
    answer of ``second``."""
    first(), second()
    a, b, out = [], [], None
    for _ in range(repeats):
        t = time.perf_counter()
        first()
        a.append(time.perf_counter() - t)
        t = time.perf_counter()
        out = second()
        b.append(time.perf_counter() - t)
    return statistics.median(a), statistics.median(b), out


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[256])
    parser.add_argument("--lambdas", type=float, nargs="+", default=[3.5, 5.0, 7.0, 10.0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--penetrations", type=float, nargs="+", default=[PENETRATION],
                        help="approaches of the single solves [length]")
    parser.add_argument("--path", type=int, default=0, help="penetrations of the path (0: no path)")
    args = parser.parse_args(argv)
    warnings.simplefilter("ignore")  # the zone warnings of an unresolved law are expected here
    print(f"{'N':>5} {'lambda':>6} {'approach':>8} {'plain s':>8} {'adhesive s':>10} {'ratio':>6} {'force err':>9} "
          f"{'radius err':>10} method")
    for n in args.sizes:
        h = contactlib.surfaces.paraboloid(n, length=LENGTH, radius=RADIUS)
        for lam in args.lambdas:
            law = maugis_law(lam)
            t_plain = None
            for approach in args.penetrations:
                t_plain = single(h, law, n, lam, approach, args.repeats)
            if args.path:
                penetrations = np.linspace(-0.0005, PENETRATION, args.path)
                t = time.perf_counter()
                curve = contactlib.adhesion_curve(h, E=E, nu=NU, adhesion=law, penetrations=penetrations,
                                                  periodic=False)
                elapsed = time.perf_counter() - t
                states = int(curve.converged.size)
                print(f"{'':>5} {'path':>6} {states} states, {int(curve.converged.sum())} converged: "
                      f"{elapsed:.1f} s, {elapsed / states / t_plain:.1f}x the plain solve per state", flush=True)


def single(h, law, n, lam, approach, repeats) -> float:
    """One row: the plain and the adhesive solve at ``approach``, timed interleaved; returns the plain time [s]."""

    def plain():
        return contactlib.solve(h, E=E, nu=NU, penetration=approach, periodic=False)

    def adhesive():
        try:
            return contactlib.solve(h, E=E, nu=NU, penetration=approach, adhesion=law, periodic=False)
        except contactlib.ConvergenceError as err:
            return err

    t_plain, t_adh, out = interleaved(plain, adhesive, repeats)
    row = f"{n:>5} {lam:>6.1f} {approach:>8.4f} {t_plain:>8.3f} {t_adh:>10.2f} {t_adh / t_plain:>6.1f}"
    if isinstance(out, Exception):
        print(f"{row} {'raised':>9} {'':>10} {str(out)[:80]}", flush=True)
        return t_plain
    force, radius = maugis.maugis_at_penetration(approach, lam=lam, radius=RADIUS, E_star=E_STAR, work=WORK)
    got_radius = ref.apex_disc_radius(h.values, int(round(float(out.contact_area) * h.size)), radius=RADIUS)
    print(f"{row} {float(out.normal_force) / force - 1:>+9.4f} {got_radius / radius - 1:>+10.4f} "
          f"{out.attrs['solver']}", flush=True)
    return t_plain


if __name__ == "__main__":
    main()
