"""Tie a process's life to its parent's: a study process must not outlive the workflow that started it.

Snakemake runs each study as a child process, which starts its Dask workers. When Snakemake dies by
a signal it cannot catch (``kill -9``, the OOM killer, a closed terminal), the child would run on,
finish, and write a dataset that the next run then distrusts. :func:`exit_with_parent` ends it:

* Linux: ``prctl(PR_SET_PDEATHSIG, SIGTERM)``. The kernel signals the child the moment its parent
  dies, with no polling and no thread; SIGTERM's default action ends it at once.
* everywhere (and on Linux as a backstop, e.g. should ``prctl`` be refused): a daemon thread that
  checks every :data:`POLL_SECONDS` whether the parent process id changed (the child was re-parented
  to init or a subreaper) and then terminates the process.

The Dask workers need nothing: a nanny-started worker exits when the process holding its nanny ends
(``distributed.process.AsyncProcess`` watches a pipe to its parent). Checkpoints are written under a
temporary name and renamed (:mod:`contactlib.pipeline.sweep`), so a process ended mid-write leaves at most a
``.*.tmp`` file, never a truncated file under a final name.
"""

from __future__ import annotations

import ctypes
import os
import signal
import sys
import threading
import time

POLL_SECONDS = 1.0
"""Period of the watchdog on the parent process id [s]."""

_PR_SET_PDEATHSIG = 1


def _parent_death_signal(sig: int) -> bool:
    """Ask the Linux kernel for ``sig`` when the parent dies; False where that is not available."""
    if not sys.platform.startswith("linux"):
        return False
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        return libc.prctl(_PR_SET_PDEATHSIG, int(sig), 0, 0, 0) == 0
    except (OSError, AttributeError):
        return False


def _terminate() -> None:
    os.kill(os.getpid(), signal.SIGTERM)
    time.sleep(5 * POLL_SECONDS)  # a SIGTERM handler that does not exit gets this long
    os._exit(1)


def _watch(parent: int) -> None:
    while os.getppid() == parent:
        time.sleep(POLL_SECONDS)
    _terminate()


def running(pid: int, command: str | None = None) -> bool:
    """Whether process ``pid`` is alive and, where the system shows it (``/proc``), its command line
    contains ``command`` (a recycled pid running something else is not the process once recorded)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    cmdline = f"/proc/{pid}/cmdline"
    if command is None or not os.path.exists(cmdline):
        return True
    with open(cmdline, "rb") as f:
        return command.encode() in f.read()


def exit_with_parent() -> str:
    """End this process (SIGTERM) when its parent dies; returns how (``"prctl+watchdog"`` or
    ``"watchdog"``). Call it first thing in a process that must not be orphaned."""
    parent = os.getppid()
    how = "prctl+watchdog" if _parent_death_signal(signal.SIGTERM) else "watchdog"
    if os.getppid() != parent:  # the parent died before we asked: nobody will signal us
        _terminate()
    threading.Thread(target=_watch, args=(parent,), name="contactlib-lifeline", daemon=True).start()
    return how
