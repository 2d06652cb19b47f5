"""Timing helper shared by the benchmarks."""

from __future__ import annotations

import time


def best(fn, repeat=7, budget=3.0, least=0.5):
    """Best wall time of ``fn()`` (after one warm-up) over at least ``repeat`` runs, and over as
    many more as fit in ``least`` seconds, stopping once ``budget`` seconds have passed.

    Short calls are thus timed many times: on a shared virtual machine a few runs in a row can all
    fall in a slow spell (the two threads of a call not running side by side), which says nothing
    of the code.  Every peer of a benchmark is timed the same way.
    """
    fn()
    times = []
    start = time.perf_counter()
    while True:
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
        spent = time.perf_counter() - start
        if spent > budget or (len(times) >= repeat and spent > least):
            break
    return min(times)
