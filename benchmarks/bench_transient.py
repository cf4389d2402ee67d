"""Viscoelastic time stepping: time per step against tamaas' MaxwellViscoelastic, against one elastic solve,
and peak memory against the number of steps.

Scene: a self-affine periodic surface (N x N, rms slope 0.1, H = 0.8, q_roll = 4, q_cutoff = N/8) under a
constant mean pressure giving about 10 % contact at the glassy modulus, on a two-branch generalised Maxwell
body (tamaas: long-term E = 1, shear moduli G = (2, 0.5), times (1, 0.1); contactlib: the same Prony series,
E_i = 2 G_i (1 + nu), nu = 0.3), stepped ``--steps`` times at ``dt = --dt`` from the instantaneous load.
Both codes at the same tolerance (``--tol``) and steps. Reported, from one run:

* time per step (median over the steps after the first) and its ratio contactlib / tamaas;
* the contact area at the last step of each (they part: tamaas relaxes below the long-term solution);
* one contactlib step over one cold elastic solve of the same scene at the same modulus as the step's
  (``contactlib.solve`` with ``E = E_eff(dt)``, the modulus each step solves with), medians of ``--repeats``;
* peak RSS of a fresh process running ``--memory-steps`` steps (fields kept at the last step only);
* the exact full-contact test for both codes: a sinusoid (32^2) pressed beyond full contact under a constant
  load, one branch, the pressure amplitude at 20 tau over its long-term value (exactly 1).

Run: ``python -m benchmarks.bench_transient`` (needs the ``bench`` extra for tamaas).
"""

from __future__ import annotations

import argparse
import json
import resource
import subprocess
import time

import numpy as np

import contactlib
from contactlib import surfaces
from contactlib.model.hereditary import PronyHistory

from .common import REPO, child_command

NU = 0.3
SHEAR, TAUS = (2.0, 0.5), (1.0, 0.1)


def material():
    return contactlib.Viscoelastic(E0=1.0, prony=[(2 * g * (1 + NU), t) for g, t in zip(SHEAR, TAUS)], nu=NU)


def scene(n: int):
    h = surfaces.self_affine(n, hurst=0.8, q_roll=4, q_cutoff=n / 8, rms_slope=0.1, seed=1)
    return h, 0.02 * material().E_inf  # about 10 % contact at the glassy modulus


def ours(n, steps, dt, tol):
    h, pm = scene(n)
    times = np.arange(steps) * dt
    stamps = []
    out = contactlib.solve_transient(h, material=material(), times=times, mean_pressure=pm, tol=tol,
                                     progress=lambda *a: stamps.append(time.perf_counter()))
    per_step = float(np.median(np.diff(stamps)))
    return per_step, out


def theirs(n, steps, dt, tol):
    import tamaas as tm
    tm.set_log_level(tm.LogLevel.error)
    h, pm = scene(n)
    heights = np.ascontiguousarray(h.transpose("x", "y").values)  # [ix, iy], as tamaas indexes it
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [1.0, 1.0], [n, n])
    model.E, model.nu = 1.0, NU
    solver = tm.MaxwellViscoelastic(model, heights, tol, dt, list(SHEAR), list(TAUS))
    times = []
    for _ in range(steps - 1):  # tamaas' first solve is at t = dt; ours has steps - 1 steps of dt after t = 0
        start = time.perf_counter()
        solver.solve(pm)
        times.append(time.perf_counter() - start)
    area = float(np.mean(np.array(model.traction) > 0))  # exactly 0 off contact in this solver
    return float(np.median(times[1:])), area


def elastic(n, tol, repeats, dt):
    h, pm = scene(n)
    E_eff = PronyHistory(material(), (1,)).coefficients(dt)[0]
    contactlib.solve(h, E=E_eff, nu=NU, mean_pressure=pm, tol=tol)  # plans
    walls = []
    for _ in range(repeats):
        start = time.perf_counter()
        contactlib.solve(h, E=E_eff, nu=NU, mean_pressure=pm, tol=tol)
        walls.append(time.perf_counter() - start)
    return float(np.median(walls))


def full_contact(dt=0.05, end=20.0, n=32):
    """The exact test beyond full contact: a sinusoid under a constant load, ``E_eff(t) = p_q / (|q| h_q / 2) (1 -
    nu^2)`` must follow ``E(t)`` to the long-term modulus. Rows ``(nu, G_1, code, E_eff(end) / E_inf)`` for tamaas'
    MaxwellViscoelastic and contactlib (one branch, tau = 1, long-term E = 1)."""
    import tamaas as tm
    tm.set_log_level(tm.LogLevel.error)
    q, h0 = 2 * np.pi, 1e-3
    x = np.arange(n) / n
    heights = h0 * np.cos(q * x)[:, None] * np.ones(n)[None, :]
    rows = []
    for nu in (0.0, 0.5):
        for shear in (0.1, 2.0):
            E1 = 2 * shear * (1 + nu)
            pm = 10 * q * h0 * (1 + E1) / (1 - nu**2)  # far beyond full contact
            model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [1.0, 1.0], [n, n])
            model.E, model.nu = 1.0, nu
            solver = tm.MaxwellViscoelastic(model, heights, 1e-12, dt, [shear], [1.0])
            for _ in range(int(round(end / dt))):
                solver.solve(pm)
            theirs = np.array(model.traction).reshape(n, n)
            times = np.arange(int(round(end / dt)) + 1) * dt
            out = contactlib.solve_transient(heights, material=contactlib.Viscoelastic(E0=1.0, prony=[(E1, 1.0)], nu=nu),
                                             times=times, mean_pressure=pm, length=1.0, tol=1e-12)
            ours = out.pressure.isel(saved_time=-1).transpose("x", "y").values  # [ix, iy], as theirs
            for code, p in (("tamaas", theirs), ("contactlib", ours)):
                amplitude = np.abs(np.fft.rfft(p[:, 0])[1]) * 2 / n
                rows.append((nu, shear, code, amplitude / (q * h0 / 2) * (1 - nu**2)))
    return rows


def memory_probe(n, steps, dt):
    """Peak RSS [MiB] of this process after ``steps`` steps (run in a fresh process)."""
    h, pm = scene(n)
    contactlib.solve_transient(h, material=material(), times=np.arange(steps) * dt, mean_pressure=pm)
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[256, 512, 1024])
    ap.add_argument("--steps", type=int, default=12)
    ap.add_argument("--dt", type=float, default=0.05)
    ap.add_argument("--tol", type=float, default=1e-8)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--memory-steps", type=int, nargs="+", default=[10, 40, 160])
    ap.add_argument("--memory-n", type=int, default=256)
    ap.add_argument("--no-peer", action="store_true")
    ap.add_argument("--json", help="also write the rows here")
    ap.add_argument("--_memory", nargs=2, type=int, help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args._memory:
        print(memory_probe(args._memory[0], args._memory[1], args.dt))
        return
    rows = []
    print("| N | steps | contactlib s/step | tamaas s/step | ratio | step / elastic solve | area ours | area tamaas |")
    print("|---|---|---|---|---|---|---|---|")
    for n in args.sizes:
        per_step, out = ours(n, args.steps, args.dt, args.tol)
        cold = elastic(n, args.tol, args.repeats, args.dt)
        row = {"n": n, "steps": args.steps, "ours": per_step, "elastic": cold,
               "area_ours": float(out.contact_area[-1])}
        if not args.no_peer:
            peer, area = theirs(n, args.steps, args.dt, args.tol)
            row.update(tamaas=peer, area_tamaas=area)
        rows.append(row)
        print(f"| {n} | {args.steps} | {per_step:.4f} | {row.get('tamaas', float('nan')):.4f} | "
              f"{per_step / row.get('tamaas', float('nan')):.3f} | {per_step / cold:.2f} | {row['area_ours']:.4f} | "
              f"{row.get('area_tamaas', float('nan')):.4f} |", flush=True)
    print("\n| steps | peak RSS [MiB] |\n|---|---|")
    for steps in args.memory_steps:
        peak = float(subprocess.run(child_command("bench_transient", "--_memory", str(args.memory_n), str(steps),
                                                  "--dt", str(args.dt)),
                                    capture_output=True, text=True, check=True, cwd=REPO).stdout)
        rows.append({"memory_steps": steps, "n": args.memory_n, "peak_rss_mib": peak})
        print(f"| {steps} | {peak:.0f} |", flush=True)
    if not args.no_peer:
        print("\n| nu | G_1 | code | E_eff(20 tau) / E_inf (exact: 1) |\n|---|---|---|---|")
        for nu, shear, code, ratio in full_contact():
            rows.append({"full_contact": code, "nu": nu, "G1": shear, "ratio": ratio})
            print(f"| {nu} | {shear} | {code} | {ratio:.6f} |", flush=True)
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(rows, fh, indent=1)


if __name__ == "__main__":
    main()
