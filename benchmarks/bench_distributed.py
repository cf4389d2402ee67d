"""Memory and time of the distributed (MPI) contact solve against the serial one, and a projection to 65536^2.

Usage::

    python -m benchmarks.bench_distributed --n 4096            # prepares the surface, runs serial, 1 rank, 2 ranks
    python -m benchmarks.bench_distributed --n 8192 --max-iter 20 --skip-one-rank   # memory only

Each run is its own process (``mpiexec -n P`` for the distributed ones) that reads the same prepared surface
file (the serial one with xarray, the ranks their rows with netCDF4), solves a periodic self-affine scene under
load control, and reports its wall time, iterations and peak resident memory (``VmHWM``, per rank); the
distributed runs also count their transposes and the bytes each rank sent in them. With ``--max-iter`` below
the iterations needed, the solves stop unconverged at the same iteration: a memory measurement (the peak is
reached by the first iteration and at the end), not a time to solution.

Communication per iteration (measured, and by construction): the loop runs five distributed transforms per
iteration (``K p`` forward and inverse, the preconditioner forward and inverse, ``<t, K t>`` forward), each one
``Alltoallw`` in which a rank sends ``(P - 1) / P`` of its share of the half-spectrum: ``16 (N/2 + 1) N / P``
bytes a rank, about ``8 N^2 (P - 1) / P^2``. So per iteration each rank sends about ``40 N^2 (P-1) / P^2`` bytes,
the whole job ``40 N^2 (P - 1) / P`` bytes (zero-padded: the padded rows are never sent, the work box's columns
are twice as many: twice that). The ``Allreduce`` of the sweeps' sums (six per iteration, at most four numbers)
cost latency, not volume.

Projection (see benchmarks/DISTRIBUTED.md for the numbers measured and the assumptions).
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
MPI_ENV = {"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1", "OMP_NUM_THREADS": "1",
           "OMPI_MCA_rmaps_base_oversubscribe": "1", "OMPI_MCA_mpi_yield_when_idle": "1"}


def _hwm_mib() -> float:
    for line in Path("/proc/self/status").read_text().splitlines():
        if line.startswith("VmHWM:"):
            return int(line.split()[1]) / 1024
    return float("nan")


def _rss_mib() -> float:
    for line in Path("/proc/self/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1]) / 1024
    return float("nan")


def run_serial(surface: str, mean_pressure: float, tol: float, max_iter: int) -> dict:
    import xarray as xr

    import contactlib

    with xr.open_dataset(surface) as ds:
        heights = ds["height"].load()
    before = _rss_mib()
    start = time.perf_counter()
    try:
        out = contactlib.solve(heights, E=1.0, nu=0.5, mean_pressure=mean_pressure, tol=tol, max_iter=max_iter)
    except contactlib.ConvergenceError as err:
        out = err.dataset
    wall = time.perf_counter() - start
    return {"mode": "serial", "ranks": 1, "wall_s": wall, "iterations": int(out.iterations),
            "residual": float(out.residual), "contact_area": float(out.contact_area), "rss_before_mib": before,
            "peak_mib": [_hwm_mib()]}


def run_distributed(surface: str, mean_pressure: float, tol: float, max_iter: int) -> dict | None:
    from mpi4py import MPI

    from contactlib.distributed.ccg import solve_polonsky_keer
    from contactlib.distributed.io import read_slab
    from contactlib.distributed.operator import DistributedCompliance
    from contactlib.distributed.slabs import Slabs

    comm = MPI.COMM_WORLD
    heights = read_slab(comm, surface)
    lengths = tuple(heights.attrs["length"])
    heights = heights.transpose("x", "y").values  # rows of x; the solve reuses this buffer (overwrite_heights)
    nx = comm.allreduce(heights.shape[0])
    shape = (nx, heights.shape[1])
    before = _rss_mib()
    comm.Barrier()
    start = time.perf_counter()
    op = DistributedCompliance(comm, shape, lengths, E_star=4 / 3, periodic=True)
    state = solve_polonsky_keer(op, heights, mean_pressure=mean_pressure, tol=tol, max_iter=max_iter,
                                row_start=int(Slabs(nx, comm.size).starts[comm.rank]), overwrite_heights=True)
    comm.Barrier()
    wall = time.perf_counter() - start
    peaks = comm.gather(_hwm_mib())
    befores = comm.gather(before)
    sent = comm.gather(op.plan.bytes_per_transpose * op.plan.transposes)
    if comm.rank:
        return None
    return {"mode": "distributed", "ranks": comm.size, "wall_s": wall, "iterations": state.iterations,
            "residual": state.residual, "contact_area": state.contact_area, "rss_before_mib": max(befores),
            "peak_mib": peaks, "transposes": op.plan.transposes,
            "bytes_sent_per_iteration_per_rank": [s / max(state.iterations, 1) for s in sent]}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--n", type=int, default=4096)
    ap.add_argument("--mean-pressure", type=float, default=0.01)
    ap.add_argument("--tol", type=float, default=1e-8)
    ap.add_argument("--max-iter", type=int, default=10_000)
    ap.add_argument("--skip-one-rank", action="store_true")
    ap.add_argument("--surface", help="prepared surface file (default: made in /tmp)")
    ap.add_argument("--effort", help="FFTW planner effort of every run (default: contactlib's, FFTW_MEASURE)")
    ap.add_argument("--_run", choices=("serial", "distributed"), help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    surface = args.surface or f"/tmp/bench_distributed_{args.n}.nc"
    if args.effort:
        from contactlib.core.fft import set_fft_options

        set_fft_options(effort=args.effort)
    if args._run:
        run = run_serial if args._run == "serial" else run_distributed
        result = run(surface, args.mean_pressure, args.tol, args.max_iter)
        if result is not None:
            print("RESULT " + json.dumps(result), flush=True)
        return 0
    env = {**os.environ, **MPI_ENV, "PYTHONPATH": os.pathsep.join(filter(None, [str(ROOT),
                                                                                  os.environ.get("PYTHONPATH")]))}
    if not Path(surface).exists():
        import contactlib

        h = contactlib.surfaces.self_affine(args.n, hurst=0.8, q_roll=2, q_cutoff=args.n // 4, rms_slope=0.1, seed=1)
        h.to_dataset().to_netcdf(surface)
        del h
    common = [__file__, "--n", str(args.n), "--mean-pressure", str(args.mean_pressure), "--tol", str(args.tol),
              "--max-iter", str(args.max_iter), "--surface", surface]
    common += ["--effort", args.effort] if args.effort else []
    runs = [[sys.executable, *common, "--_run", "serial"]]
    for ranks in ([] if args.skip_one_rank else [1]) + [2]:
        runs.append(["mpiexec", "-n", str(ranks), sys.executable, *common, "--_run", "distributed"])
    for command in runs:
        done = subprocess.run(command, env=env, capture_output=True, text=True)
        lines = [line for line in done.stdout.splitlines() if line.startswith("RESULT ")]
        if done.returncode or not lines:
            print(f"failed: {' '.join(command)}\n{done.stderr[-2000:]}", file=sys.stderr)
            continue
        result = json.loads(lines[0][7:])
        result["n"] = args.n
        print(json.dumps(result), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
