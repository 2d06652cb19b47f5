"""Timing helper shared by the benchmarks."""

from __future__ import annotations

import time


def best(fn, repeat=7, budget=3.0):
    """Best wall time of ``fn()`` over a few runs (after one warm-up)."""
    fn()
    times = []
    start = time.perf_counter()
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
        if time.perf_counter() - start > budget:
            break
    return min(times)
