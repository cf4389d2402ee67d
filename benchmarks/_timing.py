"""The median wall time of repeated calls, shared by the benchmark scripts."""

from __future__ import annotations

import statistics
import time


def timed(fn, repeats: int, warm: bool = False, setup=None):
    """``(median seconds, last output)`` of ``repeats`` calls of ``fn()``. ``warm``: one untimed call first
    (numba compilation, FFT plans, a peer's own caches); ``setup``: called untimed before each call."""
    if warm:
        fn()
    times, out = [], None
    for _ in range(repeats):
        if setup is not None:
            setup()
        start = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - start)
    return statistics.median(times), out
