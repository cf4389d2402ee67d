"""Recovery from a hard kill: no orphaned study process, and the plain `snakemake --cores 2` finishes the run.

Two kills. (1) A study of 24 points at 512^2 (about 15 s) is started under Snakemake, which is SIGKILLed once two
paths are checkpointed. Every process of that run is tracked by process id (the descendants of the
snakemake process, read from /proc before the kill), not by name. (2) Snakemake dies after a study wrote its
dataset but before Snakemake recorded the job's end, so the dataset exists and is marked incomplete: the plain
command rebuilds it only if the default profile (profiles/default, rerun-incomplete) is read.
"""

import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml

from test_lifeline import process_alive

ROOT = Path(__file__).resolve().parents[1]
TARGET = "results/area_load.nc"

pytestmark = [pytest.mark.slow,
              pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="tracks processes through /proc")]


def _clone(root: Path) -> Path:
    """The workflow's files as a fresh clone has them: the Snakefile, workflow/ and the default profile."""
    root.mkdir()
    shutil.copy(ROOT / "Snakefile", root / "Snakefile")
    for folder in ("workflow", "profiles"):
        if (ROOT / folder).is_dir():  # a checkout without profiles/ must fail the recovery, not the copy
            shutil.copytree(ROOT / folder, root / folder)
    return root


def _workdir(root: Path) -> Path:
    _clone(root)
    config = yaml.safe_load((ROOT / "tests" / "data" / "tiny_config.yaml").read_text())
    study = config["studies"]["area_load"]
    study["quick"] = {"constants": {"q_cutoff": 32},
                      "grid": {"hurst": [0.5, 0.8], "n": [512], "seed": [0, 1, 2], "reduced_pressure": [0.02, 0.1]}}
    (root / "kill.yaml").write_text(yaml.safe_dump({**config, "studies": {"area_load": study}}))
    return root


def _command(**kwargs):
    # the README's command, on one target and the test's config
    return subprocess.Popen([sys.executable, "-m", "snakemake", TARGET, "--cores", "2", "--configfile", "kill.yaml"],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, **kwargs)


def _parents() -> dict[int, list[int]]:
    children: dict[int, list[int]] = {}
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                ppid = int((entry / "stat").read_text().rsplit(")", 1)[1].split()[1])
            except (OSError, IndexError, ValueError):
                continue
            children.setdefault(ppid, []).append(int(entry.name))
    return children


def _descendants(pid: int) -> list[int]:
    children, found, todo = _parents(), [], [pid]
    while todo:
        kids = children.get(todo.pop(), [])
        found += kids
        todo += kids
    return found


def _finish(work: Path) -> str:
    proc = _command(cwd=work)
    out, _ = proc.communicate(timeout=300)
    assert proc.returncode == 0, out[-3000:]
    return out


def test_sigkill_of_snakemake_leaves_no_process_and_one_command_finishes(tmp_path):
    clean, killed = _workdir(tmp_path / "clean"), _workdir(tmp_path / "killed")
    proc = _command(cwd=killed, start_new_session=True)
    checkpoints = killed / "results" / "checkpoints" / "area_load"
    try:
        start = time.monotonic()
        while len(list(checkpoints.glob("[!.]*"))) < 2:
            assert proc.poll() is None, proc.stdout.read()[-3000:]
            assert time.monotonic() - start < 120, "no checkpoint within 2 minutes"
            time.sleep(0.05)
        run = _descendants(proc.pid)
        assert run, "snakemake had no child process to track"
        os.kill(proc.pid, signal.SIGKILL)
        proc.wait()
        start = time.monotonic()
        while any(process_alive(pid) for pid in run) and time.monotonic() - start < 10:
            time.sleep(0.1)
        left = [pid for pid in run if process_alive(pid)]
        assert not left, f"processes of the killed run still alive after 10 s: {left}"
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
    assert not (killed / TARGET).exists()  # killed before the dataset: no orphan wrote it
    assert list((killed / ".snakemake" / "locks").glob("*.lock")), "the kill should have left Snakemake's lock"

    resumed = _finish(killed)
    assert "released the lock of snakemake run" in resumed
    assert resumed.count(" cached ") >= 2  # finished points came back from the checkpoints
    _finish(clean)
    a, b = xr.load_dataset(killed / TARGET), xr.load_dataset(clean / TARGET)
    assert set(a.data_vars) == set(b.data_vars)
    for name in a.data_vars:
        if name != "wall_time":
            np.testing.assert_array_equal(a[name].values, b[name].values, err_msg=name)
    assert int((a.status != 0).sum()) == 0


INCOMPLETE_TARGET = "results/reciprocating.nc"  # 3 points at 32^2 in the tiny config: about a second


def _wait_for(condition, what: str, proc: subprocess.Popen, output: Path, within: float = 300.0) -> None:
    start = time.monotonic()
    while not condition():
        assert proc.poll() is None, output.read_text()[-3000:]
        assert time.monotonic() - start < within, f"no {what} within {within:.0f} s"
        time.sleep(0.01)


def test_dataset_left_marked_incomplete_by_a_kill_is_rebuilt_by_the_plain_command(tmp_path):
    work = _clone(tmp_path / "work")
    shutil.copy(ROOT / "tests" / "data" / "tiny_config.yaml", work / "tiny.yaml")
    command = [sys.executable, "-m", "snakemake", INCOMPLETE_TARGET, "--cores", "2", "--configfile", "tiny.yaml"]
    output, log = tmp_path / "killed_run.txt", work / "logs" / "run_study" / "reciprocating.log"
    with open(output, "w") as sink:  # a file, not a pipe: nobody reads while Snakemake is stopped
        proc = subprocess.Popen(command, cwd=work, stdout=sink, stderr=subprocess.STDOUT, start_new_session=True)
    try:
        # The study's log is opened by the running job, so Snakemake has marked the dataset incomplete by now.
        # Frozen from here, Snakemake cannot record the job's end; killed once the dataset is written, it leaves
        # the dataset and its incomplete mark behind: the state of a kill just as a study finishes (issue 38).
        _wait_for(log.exists, "study process", proc, output)
        os.kill(proc.pid, signal.SIGSTOP)
        _wait_for(lambda: "wrote " + INCOMPLETE_TARGET in log.read_text(), "dataset", proc, output)
        os.kill(proc.pid, signal.SIGKILL)
        proc.wait()
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
    written = xr.load_dataset(work / INCOMPLETE_TARGET)

    # the state the issue met: without the profile, Snakemake stops and asks for --rerun-incomplete
    bare = subprocess.run([*command, "-n", "--workflow-profile", "none"], cwd=work, capture_output=True, text=True,
                          timeout=300)
    refused = bare.stdout + bare.stderr
    assert bare.returncode != 0 and "IncompleteFilesException" in refused, refused[-3000:]
    assert INCOMPLETE_TARGET in refused.split("Incomplete files:")[-1]

    resumed = subprocess.run(command, cwd=work, capture_output=True, text=True, timeout=300)
    out = resumed.stdout + resumed.stderr
    assert resumed.returncode == 0, out[-3000:]
    assert "Using workflow specific profile profiles/default" in out
    assert out.count(" cached ") == written.status.size  # rebuilt, every point from its checkpoint
    rebuilt = xr.load_dataset(work / INCOMPLETE_TARGET)
    assert set(rebuilt.data_vars) == set(written.data_vars)
    for name in written.data_vars:
        if name != "wall_time":
            np.testing.assert_array_equal(rebuilt[name].values, written[name].values, err_msg=name)
    assert int((rebuilt.status != 0).sum()) == 0
