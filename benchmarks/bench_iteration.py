"""Where one iteration of contactlib's Polonsky-Keer solver spends its time, against what the
machine's memory bandwidth allows.

For each N, a self-affine surface is solved under load control for ``--iterations`` iterations
(a realistic contact set and pressure), and then every part of one iteration is timed alone on
that state, ``--repeats`` times (median):

* the transforms: forward and inverse planned FFTs of the solver's buffers
  (``Compliance.iteration_transforms``);
* the three passes over a spectrum: ``K p`` minus the heights, the preconditioner with its Parseval
  sum, and the Parseval sum ``<t, K t>``;
* the five fused element-wise sweeps of the solver (``contactlib.solvers``), in the order the loop
  calls them (the contact sum twice).

Each part is also given in *array transfers*: how many times it must move an n-element float64
array through memory (a read is 1; a write is 2, since the cache line is read before it is written,
or 1 where the sweep read that element already; an rfft half-spectrum of complex numbers counts as
one array, its real multiplier as half, the byte mask of the contact set as an eighth). Times one transfer, measured by
a streaming read of a grid-sized array, this is the floor that memory bandwidth sets under each
sweep, whatever the code. ``--threads 1 2`` repeats everything with FFTW and the sweeps on two threads
(the streaming read too), from the same mid-solve state.

Run ``python -m benchmarks.bench_iteration --help``; the sum of the parts is checked against the
time per iteration of a whole solve measured in the same run.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numba
import numpy as np

import contactlib
from contactlib.core import fft as cfft
from contactlib.core.grid import Grid
from contactlib.model.operators import Compliance, weighted_power_sum
from contactlib.solvers import solve_polonsky_keer

from .common import iteration_internals, pressure_for_area, self_affine_array, timed
from .peers import Contactlib


@numba.njit(cache=True, nogil=True, fastmath={"reassoc", "contract", "nsz"})
def _stream_read(a):
    s = 0.0
    for i in range(a.size):
        s += a[i]
    return s


@numba.njit(cache=True, nogil=True, parallel=True, fastmath={"reassoc", "contract", "nsz"})
def _stream_read_parallel(a):
    s = 0.0
    for i in numba.prange(a.size):
        s += a[i]
    return s


def median_time(fn, repeats: int, setup=None) -> float:
    return float(timed(fn, repeats, setup=setup)[0])


def measure(n: int, args) -> list[dict]:
    heights = self_affine_array(n, args)
    cfft.set_fft_options(threads=1)
    mean_pressure, contact = pressure_for_area(Contactlib(args.E, args.nu, 1), heights, args.contact, args)
    E_star = args.E / (1 - args.nu**2)
    op = Compliance(Grid(heights.shape, (1.0, 1.0)), E_star=E_star, kernel="spectral", periodic=True)
    # a mid-solve state: its contact set is what the sweeps branch on
    mid = solve_polonsky_keer(op, heights, mean_pressure=mean_pressure, tol=0.0, max_iter=args.iterations)
    return [measure_threads(threads, heights, op, mean_pressure, contact, mid, args) for threads in args.threads]


def measure_threads(threads: int, heights, op, mean_pressure, contact, mid, args) -> dict:
    """Every part, the FFT pair and a whole solve with FFTW and the sweeps on ``threads`` threads."""
    n = heights.shape[0]
    cfft.set_fft_options(threads=threads)
    solve_polonsky_keer(op, heights, mean_pressure=mean_pressure, tol=0.0, max_iter=2)  # plans, compiles
    # a whole solve: the time per iteration the parts must add up to
    t0 = time.perf_counter()
    full = solve_polonsky_keer(op, heights, mean_pressure=mean_pressure, tol=args.tol)
    t_iteration = (time.perf_counter() - t0) / max(full.iterations, 1)
    in_loop = _fft_time_in_loop(lambda: solve_polonsky_keer(op, heights, mean_pressure=mean_pressure, tol=args.tol))

    hp = heights - heights.max()
    p = np.ascontiguousarray(mid.pressure)
    contact = p > 0
    approach = mid.penetration
    t = np.where(contact, mid.gap, 0.0)
    r = args.repeats
    parts = {}
    with op.iteration_transforms(offset=hp) as tr:
        parts_of = iteration_internals(tr, heights.shape)
        ws, sweeps = parts_of.workspace, parts_of.sweeps
        numba_threads = numba.get_num_threads() if parts_of.threaded else 1
        tr.pressure[...] = p
        parts["forward FFT"] = (median_time(lambda: ws.forward("pressure"), r), 0)
        spectrum_copy = ws.spectrum.copy()

        def fresh_spectrum():
            np.copyto(ws.spectrum, spectrum_copy)

        parts["inverse FFT"] = (median_time(lambda: ws.inverse("displacement"), r, fresh_spectrum), 0)
        rows = ws.spectrum.reshape(-1, ws.spectrum.shape[-1])
        multiplier, inverse = (m.reshape(-1, m.shape[-1]) for m in (op.multiplier, op.inverse_multiplier))
        affine, scale_power = parts_of.affine_pass(rows), parts_of.scale_power_pass(rows)
        even = heights.shape[-1] % 2 == 0
        parts["K p - hp (multiply, subtract)"] = (
            median_time(lambda: affine(rows, multiplier, parts_of.offset, 1.0), r, fresh_spectrum), 3.5)
        parts["preconditioner (multiply, Parseval)"] = (
            median_time(lambda: scale_power(rows, inverse, even), r, fresh_spectrum), 2.5)
        parts["Parseval <t, K t>"] = (median_time(lambda: _parseval(ws.spectrum, op.multiplier, even), r), 1.5)
        w = tr.displacement(1.0)  # K p - hp: the gap plus the approach
        masked = tr.residual
        parts["A contact_sum (approach)"] = (median_time(lambda: sweeps.contact_sum(w, contact), r), 1.125)
        parts["B measure (+ masked gap)"] = (
            median_time(lambda: sweeps.measure(w, 1.0, approach, p, masked, True), r), 4)
        z = np.where(contact, mid.displacement, 0.0)  # stands for the preconditioned gap
        parts["C contact_sum (z)"] = (median_time(lambda: sweeps.contact_sum(z, contact), r), 1.125)
        t_work = tr.direction  # as in the loop, t lives in the FFT input buffer and is updated in place
        parts["D conjugate_direction"] = (
            median_time(lambda: sweeps.conjugate_direction(z, 1.0, 0.0, w, 1.0, approach, contact, 0.5, t_work), r,
                        lambda: np.copyto(t_work, t)), 4.125)
        p_work, contact_work = tr.pressure, contact.copy()
        parts["E step_project_reenter"] = (
            median_time(lambda: sweeps.step_project_reenter(p_work, 1.0, t, w, approach, 1e-3, 1e-3, contact_work),
                        r, lambda: np.copyto(p_work, p)), 4.25)
        pair = median_time(lambda: (ws.forward("pressure"), ws.inverse("displacement")), max(r, 9))

    flat = np.ascontiguousarray(heights).ravel()
    read = _stream_read if numba_threads == 1 else _stream_read_parallel
    read(flat)
    transfer = median_time(lambda: read(flat), max(r, 9))
    return {"n": n, "threads": threads, "sweep_threads": numba_threads, "contact_fraction": float(np.mean(p > 0)),
            "calibrated_contact": contact, "mean_pressure": mean_pressure, "iterations_full_solve": full.iterations,
            "t_iteration": t_iteration, "in_loop": in_loop, "t_fft_pair": pair, "t_transfer": transfer,
            "read_bandwidth_gb_s": flat.nbytes / transfer / 1e9,
            "parts": {k: {"seconds": v[0], "transfers": v[1]} for k, v in parts.items()}}


def _fft_time_in_loop(solve) -> dict:
    """Run ``solve`` with the solver's transforms timed where they run: inside the loop they find
    their inputs out of cache, as the sweeps do, which parts timed alone do not show."""
    spent = [0.0]
    originals = cfft.SharedSpectrum.forward, cfft.SharedSpectrum.inverse

    def timed(method):
        def call(self, name):
            t0 = time.perf_counter()
            out = method(self, name)
            spent[0] += time.perf_counter() - t0
            return out
        return call

    cfft.SharedSpectrum.forward, cfft.SharedSpectrum.inverse = (timed(m) for m in originals)
    try:
        t0 = time.perf_counter()
        state = solve()
        total = time.perf_counter() - t0
    finally:
        cfft.SharedSpectrum.forward, cfft.SharedSpectrum.inverse = originals
    return {"seconds": total, "fft_seconds": spent[0], "iterations": state.iterations}


def _parseval(spectrum, multiplier, even):
    return weighted_power_sum(spectrum.reshape(-1, spectrum.shape[-1]),
                              multiplier.reshape(-1, multiplier.shape[-1]), even)


def report(res: dict) -> str:
    pair, tr = res["t_fft_pair"], res["t_transfer"]
    lines = [f"### N = {res['n']}, {res['threads']} FFTW thread(s), sweeps on {res['sweep_threads']}, "
             f"contact fraction {res['contact_fraction']:.3f}",
             "",
             f"FFT pair {pair * 1e3:.2f} ms; one array transfer (streaming read of {res['n']}^2 float64 on "
             f"{res['sweep_threads']} thread(s)) {tr * 1e3:.3f} ms = {res['read_bandwidth_gb_s']:.1f} GB/s",
             "",
             "| part | time [ms] | FFT pairs | transfers | bandwidth floor [ms] | time / floor |",
             "|---|---|---|---|---|---|"]
    fft_parts = ("forward FFT", "inverse FFT")
    total = non_fft = floor_non_fft = 0.0
    for name, v in res["parts"].items():
        s, k = v["seconds"], v["transfers"]
        count = 2 if name in fft_parts else 1
        if name == "forward FFT":
            count = 3  # K p, the preconditioner, and t for <t, K t>
        total += count * s
        floor = k * tr if name not in fft_parts else float("nan")
        if name not in fft_parts:
            non_fft += s
            floor_non_fft += floor
        lines.append(f"| {name}{f' (x{count} per iteration)' if count > 1 else ''} | {s * 1e3:.3f} | "
                     f"{s / pair:.3f} | {k if name not in fft_parts else '-'} | "
                     f"{'' if name in fft_parts else f'{floor * 1e3:.3f}'} | "
                     f"{'' if name in fft_parts else f'{s / floor:.2f}'} |")
    fft_time = total - non_fft
    whole = res["t_iteration"]
    lines += [
        "",
        (f"- parts summed: {total * 1e3:.2f} ms per iteration ({total / pair:.2f} FFT pairs); whole solve: "
         f"{whole * 1e3:.2f} ms per iteration over {res['iterations_full_solve']} iterations ({whole / pair:.2f} pairs)"),
        (f"- transforms {fft_time / pair:.2f} pairs; everything else {non_fft / pair:.2f} pairs: non-FFT share "
         f"{100 * non_fft / total:.0f} % of the parts, {100 * (1 - fft_time / whole):.0f} % of the whole solve's "
         "iteration (Python and the residual's bookkeeping included)"),
        (f"- the same non-FFT work at the bandwidth floor: {floor_non_fft / pair:.2f} pairs, share "
         f"{100 * floor_non_fft / (fft_time + floor_non_fft):.0f} %"),
    ]
    loop = res.get("in_loop")
    if loop:
        per = loop["seconds"] / max(loop["iterations"], 1)
        lines.append(f"- inside a whole solve, transforms timed where they run: {per * 1e3:.2f} ms per iteration, of which "
                     f"FFTs {loop['fft_seconds'] / loop['seconds'] * per * 1e3:.2f} ms: non-FFT share "
                     f"{100 * (1 - loop['fft_seconds'] / loop['seconds']):.0f} % of the whole solve (setup included)")
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[512, 1024, 2048])
    ap.add_argument("--contact", type=float, default=0.1, help="target contact fraction")
    ap.add_argument("--iterations", type=int, default=20, help="iterations before the state is frozen")
    ap.add_argument("--repeats", type=int, default=15)
    ap.add_argument("--threads", type=int, nargs="+", default=[1],
                    help="FFTW and sweep threads, one pass each (the sweeps thread above 1 on large grids)")
    ap.add_argument("--tol", type=float, default=1e-8)
    ap.add_argument("--calibration-tol", type=float, default=1e-6, help="of the solves that find the load")
    ap.add_argument("--json", type=Path)
    for name, default in (("hurst", 0.8), ("q-roll", 4.0), ("cutoff-fraction", 1 / 8), ("rms-slope", 0.1),
                          ("E", 1.0), ("nu", 0.3)):
        ap.add_argument(f"--{name}", type=float, default=default)
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args(argv)
    results = [res for n in args.sizes for res in measure(n, args)]
    try:
        layer = f"{numba.threading_layer()} threads"
    except ValueError:  # no threaded sweep ran
        layer = "serial sweeps"
    print(f"contactlib {contactlib.__version__}, numba {numba.__version__} ({layer}), load control, spectral kernel, "
          "preconditioned\n")
    print("\n\n".join(report(res) for res in results))
    if args.json:
        args.json.write_text(json.dumps(results, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
