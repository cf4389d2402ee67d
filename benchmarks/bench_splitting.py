"""Douglas-Rachford on the complex multiplier against the fixed point on the skew part, same scenes.

For each scene the body model's operators are built once (as :func:`contactlib.solve` builds them) and both
solvers run on them, interleaved, medians of ``--repeats`` (a solver that does not converge runs once):
:func:`contactlib.solvers.solve_coupled` (Anderson on the skew part around the symmetric constrained CG) and
:func:`contactlib.solvers.nonsymmetric.splitting.solve_splitting`. Printed as a markdown table: the skew ratio
``max |Im M| / Re M``, iterations, residual, seconds, the time ratio and the pressures' relative difference.

``--try-first``: the dispatch of a loss-dominated body (E_inf/E0 = ``--ratio``, nu = 0.5, the 2D surface of
``bench_viscoelastic.py`` at the load of 10 % elastic contact, ``--sizes``, ``--zetas``), before (Douglas-Rachford
alone) and after (the bounded GMRES first try, Douglas-Rachford if it fails: the dispatch of ``solve``), interleaved with
an elastic solve of the same scene, the unit of cost; medians of ``--repeats``, load average before and after.

Run ``python -m benchmarks.bench_splitting --help``.
"""

from __future__ import annotations

import argparse
import os
import statistics
import time

import numpy as np

import contactlib
from contactlib import Elastic, Layer, Viscoelastic

from .common import complex_multiplier, host_info, load_for_contact, nonsymmetric_solve, prepared_problem
from .common import sliding_surface as surface


def profile(n, dim=1, cutoff=None):
    cutoff = min(64, n // 4) if cutoff is None else cutoff
    return contactlib.surfaces.self_affine(n, hurst=0.8, q_roll=1, q_cutoff=cutoff, rms_slope=0.1, seed=3, dim=dim)


def q0_of(h):
    return 2 * np.pi / (float(h.x[1] - h.x[0]) * h.sizes["x"])


def scene(h, material, load, velocity=None, friction=0.0, layer=None, tol=1e-8):
    return prepared_problem(h, material=material, mean_pressure=load, tol=tol, max_iter=3000, layer=layer,
                            friction=friction, sliding_velocity=velocity)


def scenes(n1, n2):
    h, h2 = profile(n1), profile(n2, dim=2, cutoff=n2 // 8)
    q0, q02 = q0_of(h), q0_of(h2)
    sls = lambda r: Viscoelastic.standard_linear_solid(E0=1.0, E_inf=r, tau=1.0, nu=0.5)  # noqa: E731
    for ratio, zeta in [(1000, 1e-4), (1000, 1e-3), (1000, 1e-2), (1000, 1.0), (10, 0.1), (10, 1.0)]:
        yield f"1D {n1}, SLS E_inf/E0 = {ratio}, zeta = {zeta:g}, p = 0.5", scene(h, sls(ratio), 0.5, (zeta / q0,))
    yield f"1D {n1}, SLS E_inf/E0 = 10, zeta = 1, p = 0.05", scene(h, sls(10), 0.05, (1 / q0,))
    yield f"1D {n1}, Coulomb mu = 0.5, nu = 0.3, p = 0.05", scene(h, Elastic(1.0, 0.3), 0.05, friction=0.5)
    yield f"2D {n2}^2, Coulomb mu = 0.5, nu = 0.3, p = 0.05", scene(h2, Elastic(1.0, 0.3), 0.05, friction=0.5)
    yield f"2D {n2}^2, SLS E_inf/E0 = 10, zeta = 1, p = 0.05", scene(h2, sls(10), 0.05, (1 / q02, 0.0))
    yield (f"1D {n1}, confined layer q0 h = 1.5, mu = 0.8, SLS 11, zeta = 1",
           scene(h, sls(11), 0.05, (1 / q0,), friction=0.8, layer=Layer(1.5 / q0)))
    yield (f"1D {n1}, confined layer q0 h = 0.1, mu = 1, elastic nu = 0.5",
           scene(h, Elastic(1.0, 0.5), 0.05, friction=1.0, layer=Layer(0.1 / q0)))


def try_first(sizes, zetas, ratio, repeats, tol=1e-8) -> None:
    """Print the before/after table of the loss-dominated dispatch (see the module docstring)."""
    material = Viscoelastic.standard_linear_solid(E0=1.0, E_inf=ratio, tau=1.0, nu=0.5)
    print(f"\nload average {os.getloadavg()[0]:.2f}; E_inf/E0 = {ratio:g}, tol {tol:g}, medians of {repeats}")
    print("\n| n | zeta | elastic s (it) | before: DR s (ratio), it | try: it (sets), residual, s (ratio) | after: solver, "
          "s (ratio), it | after / before | \\|p_after - p_before\\| / \\|p_before\\| |")
    print("|---|---|---|---|---|---|---|---|")
    ratios = []
    for n in sizes:
        h = surface(n)
        load = load_for_contact(h, 0.1)
        for zeta in zetas:
            s = prepared_problem(h, material=material, mean_pressure=load, tol=tol, max_iter=10_000,
                                 sliding_velocity=(zeta / (2 * np.pi), 0.0))
            te, tb, ta, tt = [], [], [], []
            for _ in range(repeats):  # interleaved: the machine's load hits all alike
                t0 = time.perf_counter()
                e = contactlib.solve(h, E=1.0, nu=0.5, mean_pressure=load, tol=tol)
                te.append(time.perf_counter() - t0)
                t0 = time.perf_counter()
                attempt = nonsymmetric_solve(s, "krylov", first_try=True)  # the try alone: what a failed one adds
                tt.append(time.perf_counter() - t0)
                t0 = time.perf_counter()
                before = nonsymmetric_solve(s, "splitting")
                tb.append(time.perf_counter() - t0)
                t0 = time.perf_counter()
                after = nonsymmetric_solve(s, "dispatch")
                ta.append(time.perf_counter() - t0)
            e_s, b_s, a_s, t_s = (statistics.median(t) for t in (te, tb, ta, tt))
            ratios.append(a_s / b_s)
            diff = np.linalg.norm(after.pressure - before.pressure) / np.linalg.norm(before.pressure)
            flag = lambda st: "" if st.converged else " **not converged**"  # noqa: E731
            print(f"| {n} | {zeta:g} | {e_s:.3f} ({int(e.iterations)}) | {b_s:.3f} ({b_s / e_s:.0f}x), "
                  f"{before.iterations}{flag(before)} | {attempt.iterations} ({attempt.outer_iterations}), "
                  f"{attempt.residual:.1e}{'' if attempt.converged else ' failed'}, {t_s:.3f} ({t_s / e_s:.1f}x) "
                  f"| {after.solver}, {a_s:.3f} "
                  f"({a_s / e_s:.0f}x), {after.iterations}{flag(after)} | {a_s / b_s:.2f} | {diff:.1e} |", flush=True)
    print(f"\nafter / before: median {statistics.median(ratios):.2f}, max {max(ratios):.2f}; "
          f"load average {os.getloadavg()[0]:.2f}")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--n1", type=int, default=1024, help="1D profile points")
    ap.add_argument("--n2", type=int, default=256, help="2D surface side")
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--try-first", action="store_true",
                    help="only the loss-dominated dispatch, before (Douglas-Rachford) and after (GMRES first try)")
    ap.add_argument("--sizes", type=int, nargs="+", default=[128, 256], help="--try-first: 2D surface sides")
    ap.add_argument("--zetas", type=float, nargs="+", default=[1e-4, 1e-3, 1e-2], help="--try-first: V tau q0")
    ap.add_argument("--ratio", type=float, default=1000.0, help="--try-first: E_inf / E0")
    args = ap.parse_args(argv)
    info = host_info()
    if args.try_first:
        print(f"# loss-dominated dispatch: GMRES first try then Douglas-Rachford, against Douglas-Rachford alone "
              f"({info.get('cpu', '?')}, contactlib {contactlib.__version__})")
        try_first(args.sizes, args.zetas, args.ratio, args.repeats)
        return 0
    print(f"# Douglas-Rachford vs coupled fixed point ({info.get('cpu', '?')}, contactlib {contactlib.__version__}), "
          f"tol 1e-8, medians of {args.repeats}")
    print("\n| scene | max\\|Im M\\|/Re M | coupled: it (outer), residual, s | DR: it, residual, s | t_DR / t_coupled "
          "| \\|p_DR - p_c\\| / \\|p_DR\\| |")
    print("|---|---|---|---|---|---|")
    for name, s in scenes(args.n1, args.n2):
        multiplier = complex_multiplier(s)
        nonzero = np.ones(multiplier.shape, dtype=bool)
        nonzero.flat[0] = False
        skew = float(np.max(np.abs(multiplier[nonzero].imag) / multiplier[nonzero].real))
        tc, ts = [], []
        for _ in range(args.repeats):
            t0 = time.perf_counter()
            c = nonsymmetric_solve(s, "coupled")
            tc.append(time.perf_counter() - t0)
            t0 = time.perf_counter()
            d = nonsymmetric_solve(s, "douglas-rachford", multiplier=multiplier)
            ts.append(time.perf_counter() - t0)
            if not c.converged:
                break
        diff = np.linalg.norm(c.pressure - d.pressure) / np.linalg.norm(d.pressure)
        tcm, tsm = statistics.median(tc), statistics.median(ts)
        cflag = "" if c.converged else " **not converged**"
        dflag = "" if d.converged else " **not converged**"
        print(f"| {name} | {skew:.3g} | {c.iterations} ({c.outer_iterations}), {c.residual:.1e}{cflag}, {tcm:.3f} | "
              f"{d.iterations}, {d.residual:.1e}{dflag}, {tsm:.3f} | {tsm / tcm:.2f} | {diff:.1e} |", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
