"""contactlib.pipeline.lifeline: a process ends when its parent is SIGKILLed, by prctl (Linux) or by the watchdog alone."""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

CHILD = """
import sys, time
import contactlib.pipeline.lifeline as lifeline
if sys.argv[1] == "watchdog":
    lifeline._parent_death_signal = lambda sig: False  # as on a platform without prctl
print(lifeline.exit_with_parent(), flush=True)
time.sleep(120)
"""
PARENT = """
import subprocess, sys, time
child = subprocess.Popen([sys.executable, "-c", sys.argv[1], sys.argv[2]], stdout=subprocess.PIPE, text=True)
print(child.pid, child.stdout.readline().strip(), flush=True)
time.sleep(120)
"""


def process_alive(pid: int) -> bool:
    """Whether ``pid`` runs (a zombie, dead but not yet reaped, does not)."""
    stat = Path(f"/proc/{pid}/stat")
    try:
        return stat.read_text().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads process states from /proc")
@pytest.mark.parametrize("mode, how, within", [("prctl", "prctl+watchdog", 2.0), ("watchdog", "watchdog", 4.0)])
def test_child_exits_when_parent_is_killed(mode, how, within):
    parent = subprocess.Popen([sys.executable, "-c", PARENT, CHILD, mode], stdout=subprocess.PIPE, text=True)
    try:
        pid, reported = parent.stdout.readline().split()
        pid = int(pid)
        assert reported == how and process_alive(pid)
        os.kill(parent.pid, signal.SIGKILL)
        parent.wait()
        start = time.monotonic()
        while process_alive(pid) and time.monotonic() - start < 10:
            time.sleep(0.05)
        assert not process_alive(pid), "the child outlived its parent by 10 s"
        assert time.monotonic() - start < within
    finally:
        parent.kill()
