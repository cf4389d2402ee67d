"""How many steps a reciprocating cycle needs: the energy per cycle against the slide of a step, and the energy
balance at the default steps over a grid of scenes (the figures behind ``transient.SLIDE_PER_STEP`` and
``reciprocating.ENERGY_BALANCE``).

1. **convergence** (``--convergence``): one scene (``--dim``, ``--n``, ``--ratio`` E_inf/E0, ``--frequency`` f tau,
   ``--amplitude`` over the window, ``--load`` mean pressure over E0) at ``--steps`` steps a cycle: the
   slide of a step in grid spacings, the energy dissipated per cycle, the loop's work, their balance, time.
2. **scan** (``--scan``): 72 scenes (1D 256 points, 2D 32^2 and 64^2; E_inf/E0 10 and 1000; f tau 1e-3, 0.1,
   10; amplitudes 0.01 and 0.3 of the window; mean pressure 0.005 and 0.5 E0) at the default steps and at twice
   as many: status, ``energy_balance`` and how far the energy moved on doubling.

Self-affine surfaces (Hurst 0.8, q_roll 1, rms slope 0.1, seed 0; q_cutoff 32 for profiles, n/8 for maps) on a
standard linear solid (tau = 1, nu = 0.5), window 1. Run ``python -m benchmarks.bench_reciprocating_steps --help``.
"""

from __future__ import annotations

import argparse
import itertools
import math
import time
import warnings

import contactlib


def surface(dim: int, n: int):
    return contactlib.surfaces.self_affine(n, hurst=0.8, q_roll=1, q_cutoff=min(32, n // 4) if dim == 1 else n // 8,
                                           rms_slope=0.1, seed=0, dim=dim)


def run(h, *, ratio: float, frequency: float, amplitude: float, load: float, steps: int | None):
    material = contactlib.Viscoelastic.standard_linear_solid(E0=1.0, E_inf=ratio, tau=1.0, nu=0.5)
    start = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", contactlib.TimeStepWarning)  # the table reports what they would say
        out = contactlib.solve_reciprocating(h, material=material, amplitude=amplitude, frequency=frequency,
                                             mean_pressure=load, length=1.0, steps_per_cycle=steps)
    return out, time.perf_counter() - start


def convergence(args) -> None:
    h = surface(args.dim, args.n)
    print(f"\n{args.dim}D, n = {args.n}, E_inf/E0 = {args.ratio:g}, f tau = {args.frequency:g}, amplitude "
          f"{args.amplitude:g}, load {args.load:g}\n")
    print("| steps a cycle | slide a step [spacings] | energy per cycle | loop work | energy balance | status | s |")
    print("|---|---|---|---|---|---|---|")
    for steps in args.steps:
        out, seconds = run(h, ratio=args.ratio, frequency=args.frequency, amplitude=args.amplitude, load=args.load,
                           steps=steps)
        print(f"| {out.attrs['steps_per_cycle']} | {out.attrs['slide_per_step']:.3g} | "
              f"{float(out.dissipated_energy_per_cycle):.5e} | {float(out.friction_work_per_cycle):.5e} | "
              f"{float(out.energy_balance):+.4f} | {out.attrs['status'][:11]} | {seconds:.2f} |", flush=True)


def scan() -> None:
    print("\n| dim | n | E_inf/E0 | f tau | amplitude | load | default steps | status | energy balance | "
          "energy change on doubling | balance at twice the steps | s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    rows = []
    for dim, n in ((1, 256), (2, 32), (2, 64)):
        h = surface(dim, n)
        for ratio, frequency, amplitude, load in itertools.product((10.0, 1000.0), (1e-3, 0.1, 10.0), (0.01, 0.3),
                                                                (0.005, 0.5)):
            scene = dict(ratio=ratio, frequency=frequency, amplitude=amplitude, load=load)
            out, seconds = run(h, steps=None, **scene)
            twice, more = run(h, steps=2 * out.attrs["steps_per_cycle"], **scene)
            energy, energy2 = float(out.dissipated_energy_per_cycle), float(twice.dissipated_energy_per_cycle)
            change = abs(energy2 - energy) / abs(energy2) if energy2 else math.nan
            settled = out.attrs["status"] == "settled"
            rows.append((settled, float(out.energy_balance), change))
            print(f"| {dim} | {n} | {ratio:g} | {frequency:g} | {amplitude:g} | {load:g} | "
                  f"{out.attrs['steps_per_cycle']} | {'settled' if settled else 'not settled'} | {float(out.energy_balance):+.4f} | {change:.4f} | "
                  f"{float(twice.energy_balance):+.4f} | {seconds + more:.1f} |", flush=True)
    settled = [r for r in rows if r[0]]
    above = [r for r in settled if abs(r[1]) > contactlib.problems.reciprocating.ENERGY_BALANCE]
    below = [r for r in settled if abs(r[1]) <= contactlib.problems.reciprocating.ENERGY_BALANCE]
    print(f"\n# {len(rows)} scenes, {len(settled)} settled; {len(above)} past the balance bound (energy moved "
          f"{', '.join(f'{r[2]:.3f}' for r in above)} on doubling); below it at most {max(r[2] for r in below):.4f}, "
          f"under 1 % in {sum(r[2] < 0.01 for r in below)} of {len(below)}")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--convergence", action="store_true")
    ap.add_argument("--scan", action="store_true")
    ap.add_argument("--dim", type=int, default=1)
    ap.add_argument("--n", type=int, default=256)
    ap.add_argument("--ratio", type=float, default=10.0)
    ap.add_argument("--frequency", type=float, default=1e-3)
    ap.add_argument("--amplitude", type=float, default=0.3)
    ap.add_argument("--load", type=float, default=0.5)
    ap.add_argument("--steps", type=lambda s: None if s == "default" else int(s), nargs="+",
                    default=[64, 128, 256, 512, 1024, 2048], help="steps a cycle ('default': the library's choice)")
    args = ap.parse_args(argv)
    if not (args.convergence or args.scan):
        ap.error("ask for --convergence, --scan or both")
    if args.convergence:
        convergence(args)
    if args.scan:
        scan()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
