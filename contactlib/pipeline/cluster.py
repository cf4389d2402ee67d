"""The Dask cluster a sweep runs on: its own ``LocalCluster``, an existing scheduler, or one ``LocalCluster``
shared by every sweep of a workflow run.

A study started on its own pays for a cluster of its own: worker processes spawned, contactlib imported in
each and FFTW plans made, then all of it torn down, about 5 s per study on two cores. A workflow run that
holds many studies starts one cluster instead (``python -m contactlib.pipeline.cluster``, from the Snakefile's
``onstart``) and each study connects to it through a scheduler file:

* the serving process writes ``{"pid": ...}`` to the file at once, then ``{"pid": ..., "address": ...}`` when
  the scheduler listens (each write atomic), and removes the file when it stops;
* a client (:func:`open_client` with ``scheduler_file=``) waits for the address while that process is alive,
  and falls back to a cluster of its own if the process is gone or the wait times out, so a sweep never
  depends on the shared cluster to finish.

The serving process ends with its parent (:func:`contactlib.pipeline.lifeline.exit_with_parent`), and its nanny-started
workers end with it: a killed workflow leaves no cluster behind.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import signal
import sys
import threading
import time
from collections.abc import Callable
from pathlib import Path

from . import lifeline

SHARED_WAIT_SECONDS = 120.0
"""How long a client waits for a shared cluster that is starting [s] (its process must stay alive)."""


def _write_json(path: Path, record: dict) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    tmp.write_text(json.dumps(record))
    os.replace(tmp, path)  # a reader sees the old record or the new one, never half of one


def _read_json(path: Path) -> dict | None:
    try:
        return json.loads(Path(path).read_text())
    except (OSError, ValueError):
        return None


def shared_address(scheduler_file: str | os.PathLike, *, timeout: float = SHARED_WAIT_SECONDS,
                   poll: float = 0.1) -> str | None:
    """The scheduler address a serving process wrote to ``scheduler_file``; None when no such process is
    alive (or none has written its pid within ``timeout``) or the address does not come within ``timeout`` [s]."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        record = _read_json(Path(scheduler_file))
        if record is not None:
            if not lifeline.running(int(record.get("pid", -1)), "contactlib.pipeline.cluster"):
                return None
            if record.get("address"):
                return record["address"]
        time.sleep(poll)
    return None


@contextlib.contextmanager
def open_client(*, scheduler_address: str | None = None, scheduler_file: str | os.PathLike | None = None,
                n_workers: int = 2, threads_per_worker: int = 1, log: Callable[[str], None] | None = None):
    """A ``distributed.Client`` on an existing scheduler (``scheduler_address``), on the shared cluster of
    ``scheduler_file`` (:func:`serve`), or else on a new ``LocalCluster`` of ``n_workers`` processes.

    The dashboard address is logged; it is served where ``bokeh`` is installed (the ``workflow`` extra brings
    it), on Dask's usual port 8787 when that is free, another port otherwise.
    """
    from distributed import Client, LocalCluster

    log = log or (lambda line: print(line, file=sys.stderr, flush=True))
    if not scheduler_address and scheduler_file is not None:
        scheduler_address = shared_address(scheduler_file)
        if scheduler_address is None:
            log(f"dask: no shared cluster behind {scheduler_file}; starting one for this sweep")
    if scheduler_address:
        with Client(scheduler_address, timeout="60s") as client:
            log(f"dask: scheduler {scheduler_address}, dashboard {client.dashboard_link}")
            yield client
        return
    with LocalCluster(n_workers=n_workers, threads_per_worker=threads_per_worker, processes=True,
                      dashboard_address=":8787") as cluster, Client(cluster) as client:
        log(f"dask: LocalCluster {n_workers} workers x {threads_per_worker} threads, "
            f"dashboard {client.dashboard_link}")
        yield client


def serve(scheduler_file: str | os.PathLike, *, n_workers: int = 2, threads_per_worker: int = 1,
          log: Callable[[str], None] | None = None) -> None:
    """Run a ``LocalCluster`` of ``n_workers`` processes until SIGTERM or SIGINT, with its address in
    ``scheduler_file`` (Dask's scheduler-file format, plus this process's pid) while it runs."""
    from distributed import LocalCluster

    log = log or (lambda line: print(line, file=sys.stderr, flush=True))
    path = Path(scheduler_file)
    stop = threading.Event()
    for sig in (signal.SIGTERM, signal.SIGINT):
        signal.signal(sig, lambda *_: stop.set())
    _write_json(path, {"pid": os.getpid()})
    try:
        with LocalCluster(n_workers=n_workers, threads_per_worker=threads_per_worker, processes=True,
                          dashboard_address=":8787") as cluster:
            _write_json(path, {"pid": os.getpid(), "address": cluster.scheduler_address})
            log(f"dask: shared LocalCluster {n_workers} workers x {threads_per_worker} threads at "
                f"{cluster.scheduler_address}, dashboard {cluster.dashboard_link}")
            while not stop.wait(0.5):
                pass
            log("dask: shared cluster stopping")
    finally:
        with contextlib.suppress(FileNotFoundError):
            path.unlink()


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m contactlib.pipeline.cluster",
                                     description="Serve one Dask LocalCluster for every sweep of a workflow run.")
    parser.add_argument("--scheduler-file", required=True, help="where the scheduler's address is written")
    parser.add_argument("--n-workers", type=int, default=2)
    parser.add_argument("--threads-per-worker", type=int, default=1)
    args = parser.parse_args(argv)
    if args.n_workers < 1 or args.threads_per_worker < 1:
        parser.error("--n-workers and --threads-per-worker must be >= 1")
    tie = lifeline.exit_with_parent()  # a killed workflow must not leave its cluster running
    print(f"dask: cluster process {os.getpid()} exits with its parent {os.getppid()} ({tie})", file=sys.stderr,
          flush=True)
    serve(args.scheduler_file, n_workers=args.n_workers, threads_per_worker=args.threads_per_worker)
    return 0


if __name__ == "__main__":  # spawned workers re-import this module as __mp_main__: serve only when run
    sys.exit(main())
