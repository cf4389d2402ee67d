"""Time to solution of contactlib's elastic contact solver, side by side with its peers.

For each grid size N one self-affine surface is generated, a mean pressure is chosen that gives
the target contact fraction (10 % by default), and the surface is solved by contactlib at
``--tol`` and by every installed peer (tamaas' PolonskyKeerRey, optionally ContactMechanics) *at
equal accuracy*:

* accuracy = relative L2 error of the pressure field against a reference solved by contactlib at
  ``--ref-tol`` (1e-12) on the same surface. contactlib's own error at ``--tol`` is the target;
  each peer's tolerance (which measures something else than our residual) is tightened over a
  half-decade ladder until its pressure error is no larger than ours. The ladder is reported.
* time = median of ``--repeats`` solves after one warm-up solve of the same shape (FFTW planning
  excluded: plans are cached per shape and wisdom on disk); one solve when it takes longer than
  ``--single-above`` seconds. With ``--peer-budget`` a peer is capped at the iterations that fit
  the budget, and a capped solve still short of contactlib's accuracy is reported as a lower
  bound on its time.
* FFT pair = median time of one planned pyfftw forward + inverse real FFT of the same grid
  (``contactlib.core.fft.get_fft(shape)``), measured in the same run. A Polonsky-Keer iteration needs
  two convolutions, contactlib's preconditioned one two and a half (``K p``, the preconditioner,
  the forward transform of ``t``; ``Peer.fft_pairs_per_iteration``), so
  ``non-FFT share = (t_iter - k t_pair) / t_iter`` with that k.
* peak memory = peak RSS of a fresh subprocess during one solve, minus its RSS after imports and
  after loading the surface (Linux: VmHWM reset through /proc/self/clear_refs; otherwise psutil
  sampled every 1 ms). It includes FFTW plans/buffers and the returned fields.

Peers are adapters (:class:`Peer`) sharing one interface, so adding one is a class and a line
in :data:`benchmarks.common.PEERS`. Run ``python -m benchmarks.bench_solver --help``.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import threading
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np

from contactlib.core import fft as cfft

from .common import (REPO, child_command, host_info, ladder, pressure_for_area, rel_l2, self_affine_array,
                     write_json as write_payload)
from .peers import PEERS, Contactlib, Peer, Solution
from .common import contact_fraction as area


# ------------------------------------------------------------------------------------- measures

def fft_pair_seconds(shape, *, min_total=0.3, min_reps=20) -> float:
    """Median time of one planned pyfftw forward + inverse real FFT of ``shape``."""
    plan = cfft.get_fft(shape)
    plan.real[...] = np.random.default_rng(0).standard_normal(shape)
    plan.forward(), plan.inverse()
    times, start = [], time.perf_counter()
    while len(times) < min_reps or time.perf_counter() - start < min_total:
        t0 = time.perf_counter()
        plan.forward()
        plan.inverse()
        times.append(time.perf_counter() - t0)
    return float(np.median(times))


# -------------------------------------------------------------------------------- peak memory

def _rss_kib(key: str) -> int:
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith(key + ":"):
                return int(line.split()[1])
    raise KeyError(key)


def memory_probe(args) -> None:
    """Child process: peak RSS increase during one solve (printed as JSON on the last line)."""
    heights = np.load(args.probe_surface)
    peer = PEERS[args.probe_peer](args.E, args.nu, args.probe_threads)
    # one-off costs that are not the solve's memory: numba's JIT cache / LLVM, lazy imports
    small = np.ascontiguousarray(heights[:32, :32])
    peer.solve(small, args.probe_pressure, 1e-4)
    method = "VmHWM"
    try:
        with open("/proc/self/clear_refs", "w") as f:
            f.write("5")  # reset the high-water mark to the current RSS
        base = _rss_kib("VmRSS")
        sol = peer.solve(heights, args.probe_pressure, args.probe_tol, max_iter=args.probe_max_iter)
        peak = _rss_kib("VmHWM")
    except OSError:
        import psutil

        method = "psutil 1 ms sampling"
        proc, stop, samples = psutil.Process(), threading.Event(), []
        base = proc.memory_info().rss // 1024

        def sample():
            while not stop.is_set():
                samples.append(proc.memory_info().rss // 1024)
                time.sleep(0.001)

        th = threading.Thread(target=sample, daemon=True)
        th.start()
        sol = peer.solve(heights, args.probe_pressure, args.probe_tol, max_iter=args.probe_max_iter)
        stop.set()
        th.join()
        peak = max(samples + [proc.memory_info().rss // 1024])
    print(json.dumps({"peak_mib": (peak - base) / 1024, "method": method, "iterations": sol.iterations}))


def peak_memory(peer: str, heights: np.ndarray, p: float, tol: float, threads: int, args) -> dict:
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "h.npy"
        np.save(path, heights)
        cmd = child_command("bench_solver", "--_probe", "--probe-peer", peer, "--probe-surface", str(path),
                            "--probe-pressure", repr(p), "--probe-tol", repr(tol), "--probe-threads", str(threads),
                            "--probe-max-iter", str(args.memory_max_iter), "--E", repr(args.E), "--nu", repr(args.nu))
        out = subprocess.run(cmd, capture_output=True, text=True, cwd=REPO)
    lines = [ln for ln in out.stdout.splitlines() if ln.startswith("{")]
    if out.returncode or not lines:
        return {"peak_mib": float("nan"), "method": f"probe failed: {out.stderr[-300:]}"}
    return json.loads(lines[-1])


# ------------------------------------------------------------------------------------- driver

@dataclass
class Row:
    solver: str
    n: int
    threads: int
    target_area: float
    mean_pressure: float
    tol: float
    time_s: float
    times_s: list
    iterations: int
    fft_pair_s: float
    iter_over_fft_pair: float
    non_fft_share: float
    contact_area: float
    pressure_error: float  # rel L2 vs the tight contactlib reference
    reference_residual: float
    peak_mib: float = float("nan")
    memory_method: str = ""
    area_rel_diff_vs_contactlib: float = 0.0
    pressure_rel_l2_vs_contactlib: float = 0.0
    time_ratio_contactlib_over_this: float = float("nan")
    ladder: list = field(default_factory=list)
    converged: bool = True
    time_is_lower_bound: bool = False  # stopped by the time budget with an error above contactlib's


def timed_solves(peer: Peer, heights, p, tol, repeats) -> tuple[list[float], Solution]:
    sols = [peer.solve(heights, p, tol) for _ in range(repeats)]
    return [s.seconds for s in sols], sols[-1]


def iteration_cap(peer: Peer, heights, p, budget: float | None) -> int:
    """Most iterations that fit ``budget`` seconds: time per iteration from two short capped solves
    (5 and 15 iterations; their difference removes the set-up cost)."""
    if not budget:
        return 100_000
    short, longer = (peer.solve(heights, p, 1e-30, max_iter=k) for k in (5, 15))
    per_iter = max(longer.seconds - short.seconds, 1e-9) / max(longer.iterations - short.iterations, 1)
    return max(20, int(budget / per_iter))


def bench_case(n, heights, target, threads, args, log, shared: dict) -> list[Row]:
    """One (N, contact fraction, threads) case. ``shared`` keeps the calibrated load and the reference
    of each (N, contact fraction) across thread passes: every pass is measured against the same ones."""
    ours = Contactlib(args.E, args.nu, threads)
    pair = fft_pair_seconds(heights.shape)
    if (n, target) not in shared:
        p, a_cal = pressure_for_area(ours, heights, target, args)
        shared[n, target] = (p, a_cal) + ours.reference(heights, p, args.ref_tol)
    p, a_cal, ref, ref_residual = shared[n, target]
    log(f"  N={n} threads={threads} target A={target}: mean pressure {p:.6g} (A={a_cal:.4f}), FFT pair {pair*1e3:.3f} ms")
    if args.warmup:
        warm = ours.solve(heights, p, args.tol)  # warm-up (planning is cached anyway)
        times, sol = timed_solves(ours, heights, p, args.tol, 1 if warm.seconds > args.single_above else args.repeats)
    else:  # the calibration and the reference solves have planned this shape already
        times, sol = timed_solves(ours, heights, p, args.tol, 1)
    err_ours = rel_l2(sol.pressure, ref.pressure)
    t_iter = float(np.median(times)) / max(sol.iterations, 1)
    base = Row("contactlib", n, threads, target, p, args.tol, float(np.median(times)), times, sol.iterations, pair,
               t_iter / pair, (t_iter - ours.fft_pairs_per_iteration * pair) / t_iter, area(sol.pressure), err_ours, ref_residual,
               ladder=[{"tol": args.tol, "pressure_error": err_ours, "iterations": sol.iterations}],
               time_ratio_contactlib_over_this=1.0)
    log(f"    contactlib: {base.time_s:.3f} s, {sol.iterations} it, error {err_ours:.2e} (ref: {ref.iterations} it, residual {ref_residual:.1e})")
    rows = [base]
    for name in args.peers:
        if name == "contactlib" or not PEERS[name].available():
            continue
        if args.peer_threads and threads not in args.peer_threads:
            continue
        peer = PEERS[name](args.E, args.nu, threads)
        cap = iteration_cap(peer, heights, p, args.peer_budget)
        steps, chosen, last = [], None, None
        for tol in ladder(max(err_ours, 1e-14)):
            last = peer.solve(heights, p, tol, max_iter=cap)
            e = rel_l2(last.pressure, ref.pressure)
            steps.append({"tol": tol, "pressure_error": e, "iterations": last.iterations, "time_s": last.seconds,
                          "converged": last.converged})
            log(f"    {name} tol {tol:.2e}: error {e:.2e}, {last.iterations} it, {last.seconds:.2f} s"
                + ("" if last.converged else f" (stopped by the {cap}-iteration cap of the time budget)"))
            if e <= err_ours:
                chosen = tol
                break
            if not last.converged or len(steps) >= args.max_ladder:
                break
        lower_bound = chosen is None and not last.converged
        if chosen is None:
            log(f"    {name}: no tolerance on the ladder reached error {err_ours:.2e}; "
                + ("its time is a lower bound" if lower_bound else "using the tightest tried"))
            chosen = steps[-1]["tol"]
        if lower_bound or last.seconds > args.single_above:
            times, s = [last.seconds], last  # one long solve: the ladder's own run is the measurement
        else:
            times, s = timed_solves(peer, heights, p, chosen, args.repeats)
        t_iter = float(np.median(times)) / max(s.iterations, 1)
        rows.append(Row(name, n, threads, target, p, chosen, float(np.median(times)), times, s.iterations, pair,
                        t_iter / pair, (t_iter - peer.fft_pairs_per_iteration * pair) / t_iter, area(s.pressure),
                        rel_l2(s.pressure, ref.pressure), ref_residual, ladder=steps, converged=s.converged,
                        time_is_lower_bound=lower_bound,
                        area_rel_diff_vs_contactlib=(base.contact_area - area(s.pressure)) / area(s.pressure),
                        pressure_rel_l2_vs_contactlib=rel_l2(sol.pressure, s.pressure),
                        time_ratio_contactlib_over_this=base.time_s / float(np.median(times))))
        log(f"    {name}: {rows[-1].time_s:.3f} s at tol {chosen:.2e}, ratio contactlib/{name} "
            f"{'<= ' if lower_bound else ''}{rows[-1].time_ratio_contactlib_over_this:.3f}")
    if args.memory:
        for row in rows:
            mem = peak_memory(row.solver, heights, p, row.tol, threads, args)
            row.peak_mib, row.memory_method = mem["peak_mib"], mem["method"]
    return rows


def machine_info() -> dict:
    info = host_info()
    for name, peer in PEERS.items():
        if name != "contactlib":
            info[name] = peer.version() if peer.available() else "not installed"
    return info


def markdown(rows: list[Row], info: dict, args) -> str:
    out = ["# contactlib solver benchmark", ""]
    out += [f"- {k}: {v}" for k, v in info.items()]
    out += [f"- surface: self_affine(N, hurst={args.hurst}, q_roll={args.q_roll}, q_cutoff={args.cutoff_fraction}*N, "
            f"rms_slope={args.rms_slope}, seed={args.seed}); E={args.E}, nu={args.nu}; periodic unit square",
            f"- accuracy: pressure error = rel. L2 vs contactlib at tol {args.ref_tol:g} (or the smallest residual it "
            "reaches in 3000 iterations: column ref res); peers' tolerance tightened "
            f"(half decades) until their error <= contactlib's at tol {args.tol:g}",
            f"- time: median of {args.repeats} after a warm-up (one run when a solve takes over {args.single_above:g} s)"
            + (f"; peers capped at the iterations that fit {args.peer_budget:g} s: '>' marks a peer stopped by the cap "
               "with its pressure error still above contactlib's, so its time is a lower bound and the ratio an upper one"
               if args.peer_budget else "") + "; FFT pair = planned pyfftw rfft+irfft of the grid; "
            "non-FFT share = (t_iter - k pairs)/t_iter, k = 2.5 for contactlib (K p, preconditioner, forward FFT of t), 2 for the peers",
            "- peak memory: fresh subprocess, peak RSS during one solve"
            + (f" (its first {args.memory_max_iter} iterations)" if args.memory_max_iter < 100_000 else "")
            + f" minus RSS after imports and surface load ({rows[0].memory_method or 'not measured'})", ""]
    out.append("| solver | N | thr | A target | A | tol | error | ref res | time [s] | iter | t_iter/FFT pair | non-FFT | "
               "peak [MiB] | t_ours/t_peer | dA rel | dp L2 |")
    out.append("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        peer = r.solver != "contactlib"
        out.append(
            f"| {r.solver} | {r.n} | {r.threads} | {r.target_area:g} | {r.contact_area:.4f} | {r.tol:.1e} | "
            f"{r.pressure_error:.1e} | {r.reference_residual:.0e} | {'> ' if r.time_is_lower_bound else ''}{r.time_s:.3f} | "
            f"{'> ' if r.time_is_lower_bound else ''}{r.iterations} | {r.iter_over_fft_pair:.1f} | "
            f"{100 * r.non_fft_share:.0f} % | {r.peak_mib:.1f} | "
            f"{(('< ' if r.time_is_lower_bound else '') + f'{r.time_ratio_contactlib_over_this:.3f}') if peer else ''} | "
            f"{f'{r.area_rel_diff_vs_contactlib:.1e}' if peer else ''} | "
            f"{f'{r.pressure_rel_l2_vs_contactlib:.1e}' if peer else ''} |")
    out += ["", "error: pressure rel. L2 vs the tight reference; t_ours/t_peer: contactlib time over this solver's "
            "time (< 1: contactlib faster); dA rel: (A_contactlib - A_peer)/A_peer; dp L2: |p_contactlib - p_peer| / "
            "|p_peer|."]
    return "\n".join(out)


def parse(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[256, 512, 1024, 2048])
    ap.add_argument("--contact", type=float, nargs="+", default=[0.1], help="target contact fractions")
    ap.add_argument("--threads", type=int, nargs="+", default=[1], help="FFTW threads (each value one pass)")
    ap.add_argument("--peer-threads", type=int, nargs="+",
                    help="thread counts at which the peers run too (default: every --threads value); the PyPI "
                         "tamaas wheel is sequential, so more threads only repeat its runs")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--peers", nargs="+", default=["tamaas"], choices=sorted(PEERS),
                    help="peers to compare with (skipped when not installed); contactmechanics is slow")
    ap.add_argument("--tol", type=float, default=1e-8)
    ap.add_argument("--ref-tol", type=float, default=1e-12)
    ap.add_argument("--max-ladder", type=int, default=8, help="most tolerances tried per peer")
    ap.add_argument("--calibration-tol", type=float, default=1e-6,
                    help="tolerance of the solves that find the mean pressure of each contact fraction")
    ap.add_argument("--no-warmup", dest="warmup", action="store_false",
                    help="time contactlib's first solve at --tol, once (for N = 4096: the calibration and "
                         "reference solves have planned the FFTs already)")
    ap.add_argument("--no-memory", dest="memory", action="store_false", help="skip the peak-memory subprocesses")
    ap.add_argument("--memory-max-iter", type=int, default=100_000,
                    help="iterations of the peak-memory solve (every solver allocates its arrays before iterating)")
    ap.add_argument("--peer-budget", type=float, default=None,
                    help="seconds a peer solve may take: it is capped at the iterations that fit, and when the cap "
                         "stops it short of contactlib's accuracy its time is reported as a lower bound")
    ap.add_argument("--single-above", type=float, default=60.0,
                    help="a solve longer than this many seconds is timed once, not --repeats times")
    ap.add_argument("--hurst", type=float, default=0.8)
    ap.add_argument("--q-roll", type=float, default=4.0)
    ap.add_argument("--cutoff-fraction", type=float, default=1 / 8, help="q_cutoff = fraction * N")
    ap.add_argument("--rms-slope", type=float, default=0.1)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--E", type=float, default=1.0)
    ap.add_argument("--nu", type=float, default=0.3)
    ap.add_argument("--json", type=Path, help="also write rows and machine info here")
    ap.add_argument("--quiet", action="store_true", help="no progress on stderr")
    for hidden in ("--probe-peer", "--probe-surface"):
        ap.add_argument(hidden, help=argparse.SUPPRESS)
    ap.add_argument("--probe-pressure", type=float, help=argparse.SUPPRESS)
    ap.add_argument("--probe-tol", type=float, help=argparse.SUPPRESS)
    ap.add_argument("--probe-threads", type=int, default=1, help=argparse.SUPPRESS)
    ap.add_argument("--probe-max-iter", type=int, default=100_000, help=argparse.SUPPRESS)
    ap.add_argument("--_probe", action="store_true", help=argparse.SUPPRESS)
    return ap.parse_args(argv)


def main(argv=None) -> int:
    args = parse(argv)
    if args._probe:
        memory_probe(args)
        return 0

    def log(msg):
        if not args.quiet:
            print(msg, file=sys.stderr, flush=True)

    info = machine_info()
    rows, shared = [], {}
    for n in args.sizes:
        heights = self_affine_array(n, args)
        for threads in args.threads:
            for target in args.contact:
                rows += bench_case(n, heights, target, threads, args, log, shared)
                if args.json:  # after every case: a killed run keeps what it measured
                    write_json(args.json, info, args, rows)
    text = markdown(rows, info, args)
    print(text)
    if args.json:
        write_json(args.json, info, args, rows)
    return 0


def write_json(path: Path, info: dict, args, rows: list[Row]) -> None:
    write_payload(path, {"machine": info, "args": {k: (str(v) if isinstance(v, Path) else v)
                                                   for k, v in vars(args).items() if not k.startswith(("probe", "_"))},
                         "rows": [asdict(r) for r in rows]})


if __name__ == "__main__":
    sys.exit(main())
