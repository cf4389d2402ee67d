"""The cohesive route on the JKR sphere: how far from JKR at a given Maugis parameter and grid, and the
limit lambda -> infinity by Richardson extrapolation in 1 / lambda^2.

Scene: a rigid paraboloid (R = 1) on a non-periodic half-space, ``E* = 1``, ``w = 2.83e-4`` (JKR pull-off
radius ``a_c = 0.1``), a cohesive law of peak stress ``sigma_0 = lambda / 2 (pi w K^2 / R)^(1/3)`` (Maugis'
parameter ``lambda``; for the exponential law the same peak stress), range ``w / sigma_0``. Penetration
control from ``+|d_c|`` down to ``-1.25 |d_c|`` in steps of ``|d_c| / 2`` (``d_c`` JKR's approach at
load-control pull-off), each state warm-started from the previous lambda's state at the same approach (the
first lambda: from the previous state). For each state: load against the repulsive contact radius, its
error against JKR's closed form and (Maugis law) against Maugis' at that lambda, over ``|P_c| = 3/2 pi w R``.
Then, for each pair of lambdas, the load curves (cubic splines in the radius) extrapolated to lambda ->
infinity (:func:`contactlib.reference.adhesive.jkr_limit`) against JKR, and the same extrapolation of
Maugis' closed form (the extrapolation's own error).

    python benchmarks/bench_adhesion_sphere.py --lambdas 2 2.5 3 --n 192 --window 0.36 --model maugis
"""

from __future__ import annotations

import argparse
import itertools
import math
import time
import warnings

import numpy as np
from scipy.interpolate import CubicSpline

import contactlib
from contactlib.reference import adhesive as ref

R, W, E_STAR = 1.0, 2.83e-4, 1.0
STEPS = (1.0, 0.5, 0.0, -0.5, -0.75, -1.0, -1.25)  # approach over |d_c|, unloading


def run(lams, n: int, length: float, model: str) -> None:
    K = 4 * E_STAR / 3
    h = contactlib.surfaces.paraboloid(n, length=length, radius=R)
    a_c = ref.jkr_pull_off_radius(radius=R, E_star=E_STAR, work=W)
    d_c = abs(ref.jkr_penetration(a_c, radius=R, E_star=E_STAR, work=W))
    scale = abs(ref.jkr_pull_off(radius=R, work=W))
    curves, warm = {}, None
    for lam in lams:
        sigma0 = lam / 2 * (math.pi * W * K**2 / R) ** (1 / 3)
        law = contactlib.Adhesion(work=W, range=W / sigma0, model=model)
        ds, radii, loads, states, start = None, [], [], [], time.perf_counter()
        for k, step in enumerate(STEPS):
            first = warm[k] if warm is not None else (None if ds is None else ds.pressure.values)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                ds = contactlib.solve(h, E=1.0, nu=0.0, penetration=step * d_c, adhesion=law, periodic=False,
                                      initial_pressure=first)
            load = float(ds.mean_pressure) * length**2
            a = math.sqrt(float(ds.contact_area) * length**2 / math.pi)
            jkr = float(ref.jkr_load(a, radius=R, E_star=E_STAR, work=W))
            md = (float(ref.maugis_load(a, radius=R, E_star=E_STAR, work=W, peak_stress=sigma0)[0])
                  if model == "maugis" else math.nan)
            radii.append(a)
            loads.append(load)
            states.append(ds.pressure.values)
            print(f"  {model} lambda {lam:g} n {n} d/|d_c| {step:+.2f}: a/a_c {a / a_c:.3f} "
                  f"P/|P_c| {load / scale:+.4f} "
                  f"err JKR {(load - jkr) / scale:+.4f} err MD {(load - md) / scale:+.4f} "
                  f"zone {ds.attrs['process_zone_elements']:.1f} el {ds.attrs['solver']}", flush=True)
        warm = states
        curves[lam] = (np.array(radii), np.array(loads))
        pull = min(loads) / scale
        maugis = ref.maugis_pull_off(lam) / 1.5
        print(f"{model} lambda {lam:g} n {n} L {length:g}: pull-off {pull:+.4f} |P_c| (JKR -1, Maugis {maugis:+.4f}), "
              f"{time.perf_counter() - start:.0f} s", flush=True)
    A_c = a_c * (K / (math.pi * W * R**2)) ** (1 / 3)
    for l1, l2 in itertools.combinations(lams, 2):
        (a1, P1), (a2, P2) = curves[l1], curves[l2]
        radii = np.linspace(max(a1.min(), a2.min()), min(a1.max(), a2.max()), 25)
        limit = ref.jkr_limit(CubicSpline(a1[::-1], P1[::-1])(radii), l1, CubicSpline(a2[::-1], P2[::-1])(radii), l2)
        error = (limit - ref.jkr_load(radii, radius=R, E_star=E_STAR, work=W)) / scale
        A = radii / a_c * A_c
        theory = (ref.jkr_limit(ref.maugis_load_penetration(A, l1)[0], l1, ref.maugis_load_penetration(A, l2)[0], l2)
                  - (A**3 - np.sqrt(6 * A**3))) / 1.5
        pull = ref.jkr_limit(P1.min(), l1, P2.min(), l2) / scale
        worst = radii[np.argmax(np.abs(error))] / a_c
        print(f"{model} limit from lambda {l1:g}, {l2:g} over {radii[0] / a_c:.2f}-{radii[-1] / a_c:.2f} a_c: "
              f"largest |error| vs JKR {np.abs(error).max():.4f} |P_c| (at {worst:.2f} a_c); "
              f"the extrapolation of Maugis' equations {np.abs(theory).max():.4f}; pull-off {pull:+.4f} |P_c|",
              flush=True)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--lambdas", type=float, nargs="+", default=[2.0, 2.5])
    parser.add_argument("--n", type=int, default=160)
    parser.add_argument("--window", type=float, default=0.36)
    parser.add_argument("--model", default="maugis", choices=["maugis", "exponential"])
    args = parser.parse_args(argv)
    run(args.lambdas, args.n, args.window, args.model)


if __name__ == "__main__":
    main()
