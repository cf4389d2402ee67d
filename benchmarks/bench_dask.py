"""Dask fan-out benchmark: a 16-point area-load sweep at N = 256 with 1 and with 2 workers, in one run.

Reports the median sweep wall time per worker count, the speed-up, and two overheads per task against the
median solve time: ``gap`` is the scheduling overhead proper (from Dask's task stream: idle time between
consecutive tasks on a worker plus task time outside the point function), ``idle`` is every second a worker
slot is not solving (wall x workers / points - mean solve; includes the load imbalance of the last tasks).
Targets: speed-up >= 1.8, scheduling overhead < 5 % of the median solve.

    python -m benchmarks.bench_dask [--repeats 3] [--n 256]
"""

from __future__ import annotations

import argparse
import functools
import statistics
import time

from distributed import Client, LocalCluster, get_task_stream

from contactlib import studies

from contactlib.pipeline import sweep

CONSTANTS = dict(q_low=1, q_roll=2, q_cutoff=64, rms_slope=0.1, E=1.0, nu=0.5, tol=1e-8, max_iter=10000,
                 kernel="spectral", hurst=0.5)


def measure(n_workers: int, n: int, repeats: int) -> dict:
    grid = {"n": [n], "seed": [0, 1, 2, 3], "reduced_pressure": [0.02, 0.04, 0.07, 0.1]}  # 16 points
    point = functools.partial(studies.area_load_point, **CONSTANTS)
    walls, solves, overheads, gaps = [], [], [], []
    with LocalCluster(n_workers=n_workers, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        # warm-up: imports and FFT plans on every worker, not timed
        sweep.run_grid(point, {**grid, "seed": [100 + i for i in range(n_workers)]}, client=client, progress=False,
                       labels=studies.STUDY_VARIABLES, fft_shapes=[(n, n)])
        for _ in range(repeats):
            start = time.perf_counter()
            with get_task_stream(client) as stream:
                ds = sweep.run_grid(point, grid, client=client, progress=False, labels=studies.STUDY_VARIABLES,
                                    fft_shapes=[(n, n)])
            wall = time.perf_counter() - start
            gaps.append(scheduling_gap(stream.data, float(ds.wall_time.sum())))
            tasks = ds.wall_time.values.ravel()
            walls.append(wall)
            solves.append(float(statistics.median(tasks)))
            overheads.append(wall * n_workers / tasks.size - float(tasks.mean()))
    return {"workers": n_workers, "wall": statistics.median(walls), "solve": statistics.median(solves),
            "overhead": statistics.median(overheads), "gap": statistics.median(gaps), "points": 16}


def scheduling_gap(records: list[dict], solve_total: float) -> float:
    """Per task: idle time between consecutive tasks on each worker + task time outside the point function."""
    by_worker: dict[str, list[tuple[float, float]]] = {}
    for rec in records:
        spans = [(s["start"], s["stop"]) for s in rec["startstops"] if s["action"] == "compute"]
        by_worker.setdefault(rec["worker"], []).extend(spans)
    idle, busy = 0.0, 0.0
    for spans in by_worker.values():
        spans.sort()
        busy += sum(stop - start for start, stop in spans)
        idle += sum(max(0.0, b[0] - a[1]) for a, b in zip(spans, spans[1:]))
    return (idle + busy - solve_total) / len(records)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--n", type=int, default=256)
    args = parser.parse_args()
    rows = [measure(w, args.n, args.repeats) for w in (1, 2)]
    base = rows[0]["wall"]
    print(f"16-point sweep, N = {args.n}, median of {args.repeats} repeats")
    print(f"{'workers':>7} {'wall [s]':>9} {'speed-up':>9} {'median solve [s]':>17} {'gap/task [ms]':>14} "
          f"{'gap/solve':>10} {'idle/task [ms]':>15} {'idle/solve':>11}")
    for r in rows:
        print(f"{r['workers']:>7} {r['wall']:>9.2f} {base / r['wall']:>9.2f} {r['solve']:>17.3f} "
              f"{1e3 * r['gap']:>14.1f} {r['gap'] / r['solve']:>10.1%} {1e3 * r['overhead']:>15.1f} "
              f"{r['overhead'] / r['solve']:>11.1%}")
    print("targets: speed-up >= 1.8 with 2 workers; overhead < 5 % of the median solve")


if __name__ == "__main__":
    main()
