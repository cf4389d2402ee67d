"""The cohesive route on the JKR sphere: how far from JKR at a given Maugis parameter and grid, and the
limit lambda -> infinity by Richardson extrapolation in powers of 1 / lambda^2, along the whole branch
stable under load control (from pull-off at a_c far into compression).

Scene: a rigid paraboloid (R = 1) on a non-periodic half-space, ``E* = 1``, ``w = 2.83e-4`` (JKR pull-off
radius ``a_c = 0.1``), a cohesive law of peak stress ``sigma_0 = lambda / 2 (pi w K^2 / R)^(1/3)`` (Maugis'
parameter ``lambda``; for the exponential law the same peak stress), range ``w / sigma_0``. Penetration
control, unloading along JKR's approaches at the contact radii ``--radii`` (over ``a_c``), each state
warm-started from the previous lambda's state at the same approach (the first lambda: from the previous
state), solver tolerance ``--tol`` (the default 1e-6 left compressive tractions of up to 6 % of sigma_0 on
open points far outside a 2.4 a_c contact; 1e-8 leaves none). The contact radius is that of the disc of
closed points about the apex (:func:`contactlib.reference.adhesive.apex_disc_radius`), not
``sqrt(area / pi)``, whose lattice scatter is 0.6 % of ``|P_c|`` in the load at 2.4 a_c.

For each state: load against radius, error against JKR's closed form and (Maugis law) against Maugis' at
that lambda, over ``|P_c| = 3/2 pi w R``. The extrapolation is taken at a fixed ``a + 2/3 (c - a)``
(``--radius equivalent``, :func:`contactlib.reference.adhesive.jkr_equivalent_radius`; ``c`` the radius of
the disc of interacting points), where the terms of Maugis' series left after it are far smaller than at a
fixed contact radius ``a`` (``--radius contact``). Then, for each set of two or more lambdas, the load curves (cubic
splines in the radius) extrapolated to lambda -> infinity (:func:`contactlib.reference.adhesive.
jkr_extrapolation`) against JKR, next to the same extrapolation of Maugis' closed form (the extrapolation's
own error); and for all the lambdas a table by radius, with the radius error at each load beside the load
error at each radius.

    python -m benchmarks.bench_adhesion_sphere --lambdas 1.5 2 2.5 --n 256 --window 0.576

``--hard`` instead times issue 38's hard cases: the Maugis sphere ``paraboloid(n, length=0.25, radius=1)``, ``E = 1,
nu = 0.5``, work 1e-4, non-periodic, penetration 0.002, at each lambda of ``--lambdas``: the plain (non-adhesive)
solve and the adhesive one (wall and CPU seconds, medians of ``--repeat``), and the force and contact radius
against Maugis' closed form at the lambda asked.

    python -m benchmarks.bench_adhesion_sphere --hard --n 256 --lambdas 3.5 5 7 10 --repeat 3
"""

from __future__ import annotations

import argparse
import itertools
import math
import time
import warnings

import numpy as np
from scipy.interpolate import CubicSpline
from scipy.optimize import brentq

import contactlib
from contactlib.reference import adhesive as ref
from contactlib.reference import maugis

R, W, E_STAR = 1.0, 2.83e-4, 1.0
RADII = tuple(round(2.5 - 0.1 * k, 2) for k in range(17))  # JKR radii over a_c of the path, unloading


def path(h, lam: float, model: str, approaches, warm, length: float, tol: float):
    """The states along ``approaches``: (disc radii, pixel radii, loads, pressures, zone radii)."""
    K = 4 * E_STAR / 3
    sigma0 = lam / 2 * (math.pi * W * K**2 / R) ** (1 / 3)
    law = contactlib.Adhesion(work=W, range=W / sigma0, model=model)
    a_c = ref.jkr_pull_off_radius(radius=R, E_star=E_STAR, work=W)
    scale = abs(ref.jkr_pull_off(radius=R, work=W))
    size = h.size
    ds, disc, pixel, loads, states, zone = None, [], [], [], [], []
    for k, d in enumerate(approaches):
        first = warm[k] if warm is not None else (None if ds is None else ds.pressure.transpose("x", ...).values)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            try:
                ds = contactlib.solve(h, E=1.0, nu=0.0, penetration=d, adhesion=law, periodic=False, tol=tol,
                                      initial_pressure=first)
            except contactlib.ConvergenceError as error:  # said, and left out of the curve
                print(f"  {model} lambda {lam:g} d {d:+.5f}: {error}", flush=True)
                states.append(first)
                continue
        count = int(round(float(ds.contact_area) * size))
        a = ref.apex_disc_radius(h.values, count, radius=R)
        c = ref.apex_disc_radius(h.values, int(round(float(ds.interaction_area) * size)), radius=R)
        load = float(ds.mean_pressure) * length**2
        jkr = float(ref.jkr_load(a, radius=R, E_star=E_STAR, work=W))
        md = (float(maugis.maugis_load(a, radius=R, E_star=E_STAR, work=W, peak_stress=sigma0)[0])
              if model == "maugis" else math.nan)
        disc.append(a)
        zone.append(c)
        pixel.append(math.sqrt(float(ds.contact_area) * length**2 / math.pi))
        loads.append(load)
        states.append(ds.pressure.transpose("x", ...).values)  # [ix, iy]: a bare warm start
        print(f"  {model} lambda {lam:g} d {d:+.5f}: a/a_c {a / a_c:.4f} (sqrt(area/pi) {pixel[-1] / a_c:.4f}) "
              f"c/a_c {c / a_c:.4f} P/|P_c| {load / scale:+.4f} err JKR {(load - jkr) / scale:+.4f} "
              f"err MD {(load - md) / scale:+.5f} "
              f"zone {ds.attrs['process_zone_elements']:.1f} el {ds.attrs['solver']}", flush=True)
    return np.array(disc), np.array(pixel), np.array(loads), states, np.array(zone)


def limit(curves, lams, radii):
    """The extrapolated load at ``radii`` from the load curves of ``lams``."""
    values = [CubicSpline(*_increasing(curves[lam][0], curves[lam][2]))(radii) for lam in lams]
    return ref.jkr_extrapolation(values, lams)


def _own(A, lams, equivalent: bool):
    """The extrapolation's own error over ``|P_c|`` at Maugis radii ``A``: Maugis' closed form at ``lams``
    (at the same contact radius, or the same ``a + 2/3 (c - a)``), extrapolated, less JKR's."""
    values = []
    for lam in lams:
        if equivalent:  # the contact radius whose a + 2/3 (c - a) is A
            inner = [brentq(lambda x: float(ref.jkr_equivalent_radius(x, x * maugis.maugis_zone_ratio(x, lam))) - t,
                            0.3 * t, t) for t in A]
            values.append(maugis.maugis_load_penetration(np.array(inner), lam)[0])
        else:
            values.append(maugis.maugis_load_penetration(A, lam)[0])
    return (ref.jkr_extrapolation(values, lams) - A**3 + np.sqrt(6 * A**3)) / 1.5


def floor(jkr, scale: float):
    """The denominator of the floored relative load error ``|P - P_JKR| / max(|P_JKR|, |P_c|)``: the load
    itself where it is larger than the pull-off force, ``|P_c|`` where the load crosses zero (1.59 a_c)."""
    return np.maximum(np.abs(jkr), scale)


def _increasing(x, y):
    order = np.argsort(x)
    return x[order], y[order]


def run(lams, n: int, length: float, model: str, radii_over, tol: float, equivalent: bool) -> None:
    K = 4 * E_STAR / 3
    h = contactlib.surfaces.paraboloid(n, length=length, radius=R)
    a_c = ref.jkr_pull_off_radius(radius=R, E_star=E_STAR, work=W)
    scale = abs(ref.jkr_pull_off(radius=R, work=W))
    approaches = [float(ref.jkr_penetration(r * a_c, radius=R, E_star=E_STAR, work=W)) for r in radii_over]
    curves, warm = {}, None
    for lam in lams:
        start = time.perf_counter()
        disc, pixel, loads, warm, zone = path(h, lam, model, approaches, warm, length, tol)
        # the comparison radius: the contact radius itself, or a + 2/3 (c - a) (ref.jkr_equivalent_radius)
        curves[lam] = (ref.jkr_equivalent_radius(disc, zone) if equivalent else disc, pixel, loads)
        print(f"{model} lambda {lam:g} n {n} L {length:g}: pull-off {loads.min() / scale:+.4f} |P_c| "
              f"(JKR -1, Maugis {maugis.maugis_pull_off(lam) / 1.5:+.4f}), {time.perf_counter() - start:.0f} s",
              flush=True)
    A_scale = (K / (math.pi * W * R**2)) ** (1 / 3)
    lo = max(curves[lam][0].min() for lam in lams)
    hi = min(curves[lam][0].max() for lam in lams)
    radii = np.linspace(lo, hi, 1501)  # every 0.001 a_c or so
    jkr = ref.jkr_load(radii, radius=R, E_star=E_STAR, work=W)
    bands = [(0.0, 1.0), (1.0, 1.6), (1.6, 1.8), (1.8, 2.0), (2.0, 2.2), (2.2, 2.5)]
    for k in range(2, len(lams) + 1):
        for subset in itertools.combinations(lams, k):
            difference = limit(curves, subset, radii) - jkr
            error, relative = difference / scale, difference / floor(jkr, scale)
            coarse = np.linspace(lo, hi, 61)  # the closed form's own error is smooth: sampled coarser
            own = np.interp(radii, coarse, _own(coarse * A_scale, subset, equivalent))
            parts = []
            for b0, b1 in bands:
                sel = (radii / a_c >= b0) & (radii / a_c < b1)
                if sel.any():
                    parts.append(f"{max(b0, lo / a_c):.2f}-{min(b1, hi / a_c):.2f} a_c: "
                                 f"{np.abs(error[sel]).max():.4f} (own {np.abs(own[sel]).max():.4f}; "
                                 f"floored relative {np.abs(relative[sel]).max():.4f})")
            weights = ref.jkr_weights(subset)
            print(f"{model} limit from lambda {', '.join(f'{x:g}' for x in subset)} (sum |weights| "
                  f"{np.abs(weights).sum():.1f}): largest |error| vs JKR / |P_c| by band, " + "; ".join(parts),
                  flush=True)
            fails = radii[np.abs(error) >= 0.03]  # where the |P_c| measure first reaches 3 %
            print(f"  |P_c| measure < 3 % from {lo / a_c:.2f} a_c up to {(fails.min() if fails.size else hi) / a_c:.3f}"
                  f" a_c; floored relative measure at most {np.abs(relative).max():.4f} over "
                  f"{lo / a_c:.2f}-{hi / a_c:.2f} a_c", flush=True)
    # the table for all the lambdas: the load error at each radius and the radius error at each load
    rows = np.unique(np.concatenate([np.round(np.array(radii_over), 2), [1.0, 1.59]]))
    rows = rows[(rows * a_c >= lo) & (rows * a_c <= hi)]
    P = limit(curves, lams, rows * a_c)
    own = _own(rows * a_c * A_scale, lams, equivalent)
    jkr_rows = ref.jkr_load(rows * a_c, radius=R, E_star=E_STAR, work=W)
    # radius at each JKR load: splines of the radius in the load on the branch a >= a_c of each lambda
    branch = {lam: (curves[lam][2][curves[lam][0] >= a_c], curves[lam][0][curves[lam][0] >= a_c]) for lam in lams}
    print(f"\nall lambdas {', '.join(f'{x:g}' for x in lams)}, n {n}, L {length:g}, tol {tol:g}, radius "
          + ("a + 2/3 (c - a)" if equivalent else "a"))
    print("a/a_c  P_JKR/|P_c|  (P_lim - P_JKR)/|P_c|  (P_lim - P_JKR)/max(|P_JKR|, |P_c|)  own  lambda="
          + f"{lams[-1]:g}" + " alone  |  at P_JKR: (a_lim - a_JKR)/a_JKR")
    top = lams[-1]
    for r, p, pj, o in zip(rows, P, jkr_rows, own):
        alone = (CubicSpline(*_increasing(curves[top][0], curves[top][2]))(r * a_c) - pj) / scale
        radius_error = math.nan
        lows = [branch[lam][0].min() for lam in lams]
        highs = [branch[lam][0].max() for lam in lams]
        if r >= 1.0 and max(lows) <= pj <= min(highs) and all(len(branch[lam][0]) > 3 for lam in lams):
            a_lim = ref.jkr_extrapolation([CubicSpline(*_increasing(*branch[lam]))(pj) for lam in lams], lams)
            radius_error = (a_lim - r * a_c) / (r * a_c)
        print(f"{r:5.2f}  {pj / scale:+8.4f}  {(p - pj) / scale:+8.4f}  {(p - pj) / floor(pj, scale):+8.4f}  "
              f"{o:+8.4f}  {alone:+8.4f}  |  "
              f"{radius_error:+.5f}")


def hard(n: int, lams, repeat: int, penetration: float = 0.002) -> None:
    """Issue 38's hard cases (module docstring, ``--hard``)."""
    w, length, E, nu = 1e-4, 0.25, 1.0, 0.5
    e_star = E / (1 - nu**2)
    K = 4 * e_star / 3
    h = contactlib.surfaces.paraboloid(n, length=length, radius=R)

    def timed(**kwargs):
        walls, cpus, ds = [], [], None
        for _ in range(repeat):
            wall, cpu = time.perf_counter(), time.process_time()
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                try:
                    ds = contactlib.solve(h, E=E, nu=nu, penetration=penetration, periodic=False, **kwargs)
                except contactlib.ConvergenceError as error:
                    ds = error.dataset
            walls.append(time.perf_counter() - wall)
            cpus.append(time.process_time() - cpu)
        return float(np.median(walls)), float(np.median(cpus)), ds

    plain_wall, plain_cpu, _ = timed()
    print(f"n {n}: plain solve {plain_wall:.2f} s wall, {plain_cpu:.2f} s CPU (median of {repeat})", flush=True)
    for lam in lams:
        sigma0 = lam / 2 * (math.pi * w * K**2 / R) ** (1 / 3)
        law = contactlib.Adhesion(work=w, range=w / sigma0, model="maugis")
        wall, cpu, ds = timed(adhesion=law)
        force, radius = maugis.maugis_at_penetration(penetration, lam=lam, radius=R, E_star=e_star, work=w)
        got = float(ds.mean_pressure) * length**2
        a = ref.apex_disc_radius(h.values, int(round(float(ds.contact_area) * h.size)), radius=R)
        print(f"n {n} lambda {lam:g} (zone {ds.attrs['process_zone_elements']:.2f} el): {wall:.2f} s wall "
              f"({wall / plain_wall:.1f}x), {cpu:.2f} s CPU ({cpu / plain_cpu:.1f}x), converged "
              f"{ds.attrs['converged']}, {ds.attrs['solver']}; force {got / force - 1:+.4f}, radius "
              f"{a / radius - 1:+.4f} vs Maugis", flush=True)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--lambdas", type=float, nargs="+", default=[1.5, 2.0, 2.5])
    parser.add_argument("--n", type=int, default=256)
    parser.add_argument("--window", type=float, default=0.576)
    parser.add_argument("--model", default="maugis", choices=["maugis", "exponential"])
    parser.add_argument("--radii", type=float, nargs="+", default=list(RADII),
                        help="JKR contact radii over a_c of the approaches of the path, unloading")
    parser.add_argument("--tol", type=float, default=1e-8)
    parser.add_argument("--radius", default="equivalent", choices=["equivalent", "contact"],
                        help="extrapolate at a fixed a + 2/3 (c - a) (default) or at a fixed contact radius a")
    parser.add_argument("--hard", action="store_true", help="time issue 38's hard cases instead (docstring)")
    parser.add_argument("--repeat", type=int, default=1, help="--hard: runs per timing (the median)")
    args = parser.parse_args(argv)
    if args.hard:
        hard(args.n, args.lambdas, args.repeat)
        return
    run(args.lambdas, args.n, args.window, args.model, args.radii, args.tol, args.radius == "equivalent")


if __name__ == "__main__":
    main()
