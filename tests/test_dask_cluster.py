"""A real `dask scheduler` + two `dask worker` processes on 127.0.0.1; one worker is killed mid-sweep."""

import functools
import os
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import pytest
import xarray as xr

from contactlib import studies

from contactlib.pipeline import sweep
from contactlib.pipeline.cluster import open_client, shared_address

distributed = pytest.importorskip("distributed")

CONSTANTS = dict(q_low=1, q_roll=2, q_cutoff=32, rms_slope=0.1, E=1.0, nu=0.5, tol=1e-8, max_iter=10000,
                 kernel="spectral")
GRID = {"hurst": [0.5, 0.8], "n": [128], "seed": [0, 1, 2], "reduced_pressure": [0.02, 0.05, 0.1, 0.15]}
ROOT = Path(__file__).resolve().parents[1]


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def start(args, log):
    env = dict(os.environ, PYTHONPATH=f"{ROOT}{os.pathsep}{os.environ.get('PYTHONPATH', '')}")
    return subprocess.Popen([sys.executable, "-m", "distributed.cli." + args[0], *args[1:]], stdout=log,
                            stderr=subprocess.STDOUT, start_new_session=True, env=env, cwd=ROOT)


def stop(proc, sig=signal.SIGTERM):
    if proc.poll() is None:
        os.killpg(proc.pid, sig)
    try:
        proc.wait(timeout=15)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.wait(timeout=15)


@pytest.fixture
def cluster(tmp_path):
    port = free_port()
    address = f"tcp://127.0.0.1:{port}"
    procs = []
    with open(tmp_path / "cluster.log", "w") as log:
        try:
            procs.append(start(["dask_scheduler", "--host", "127.0.0.1", "--port", str(port), "--no-dashboard"], log))
            for _ in range(2):
                procs.append(start(["dask_worker", address, "--nthreads", "1", "--nworkers", "1", "--no-dashboard",
                                    "--host", "127.0.0.1", "--local-directory", str(tmp_path)], log))
            yield address, procs
        finally:
            for proc in reversed(procs):
                stop(proc)


def test_sweep_survives_a_killed_worker(cluster, tmp_path):
    address, procs = cluster
    serial = sweep.run_grid(functools.partial(studies.area_load_point, **CONSTANTS), GRID,
                            labels=studies.STUDY_VARIABLES, progress=False, fft_shapes=[(128, 128)])
    victim = procs[2]
    lines = []

    def progress(line):
        lines.append(line)
        if len(lines) == 4:  # a third of the way: kill one worker (its nanny and process)
            stop(victim, signal.SIGKILL)

    with open_client(scheduler_address=address, log=lines.append) as client:
        client.wait_for_workers(2, timeout=60)
        assert client.submit(sum, [1, 2]).result(timeout=60) == 3
        start_time = time.monotonic()
        ds = sweep.run_grid(functools.partial(studies.area_load_point, **CONSTANTS), GRID, client=client,
                            labels=studies.STUDY_VARIABLES, progress=progress, fft_shapes=[(128, 128)],
                            checkpoint_dir=tmp_path / "ckpt")
        assert time.monotonic() - start_time < 240
        deadline = time.monotonic() + 30
        while len(client.scheduler_info()["workers"]) != 1 and time.monotonic() < deadline:
            time.sleep(0.2)
        assert len(client.scheduler_info()["workers"]) == 1
    assert victim.poll() is not None
    assert "dashboard" in lines[0]
    assert (ds.status == 0).all() and int(ds.contact_area.notnull().sum()) == 24
    # the same bits as a run in this process: every worker uses the parent's FFT plans
    strip = lambda d: d.drop_vars("wall_time").drop_attrs()  # noqa: E731
    xr.testing.assert_identical(strip(ds), strip(serial))
    assert len(list((tmp_path / "ckpt").glob("*.pkl"))) == 24


def test_shared_cluster_serves_clients_and_leaves_nothing_behind(tmp_path):
    """`python -m contactlib.pipeline.cluster` (the workflow's shared cluster): its address reaches a client, a sweep runs
    on it, and SIGTERM stops it and removes its scheduler file; a client falls back when no server is alive."""
    scheduler_file = tmp_path / "dask.json"
    with open(tmp_path / "server.log", "w") as log:
        env = dict(os.environ, PYTHONPATH=f"{ROOT}{os.pathsep}{os.environ.get('PYTHONPATH', '')}")
        server = subprocess.Popen([sys.executable, "-m", "contactlib.pipeline.cluster", "--scheduler-file", str(scheduler_file),
                                   "--n-workers", "2"], stdout=log, stderr=subprocess.STDOUT, env=env,
                                  start_new_session=True)
    try:
        address = shared_address(scheduler_file, timeout=120)
        assert address and address.startswith("tcp://127.0.0.1:")
        lines = []
        with open_client(scheduler_file=scheduler_file, log=lines.append) as client:
            client.wait_for_workers(2, timeout=60)
            ds = sweep.run_grid(functools.partial(studies.area_load_point, **CONSTANTS),
                                {"hurst": [0.8], "n": [64], "seed": [0, 1], "reduced_pressure": [0.05]}, client=client,
                                labels=studies.STUDY_VARIABLES, progress=False)
        assert lines == [f"dask: scheduler {address}, dashboard {lines[0].split('dashboard ')[1]}"]
        assert (ds.status == 0).all()
        server.terminate()
        assert server.wait(timeout=30) == 0
        assert not scheduler_file.exists()
    finally:
        stop(server, signal.SIGKILL)
    # a record whose process is gone: no wait, the caller starts a cluster of its own
    scheduler_file.write_text('{"pid": %d, "address": "tcp://127.0.0.1:1"}' % server.pid)
    start_time = time.monotonic()
    assert shared_address(scheduler_file, timeout=60) is None and time.monotonic() - start_time < 5
    scheduler_file.unlink()
    assert shared_address(scheduler_file, timeout=0.3) is None  # none ever started
