"""The threads the compiled kernels split a long batch over.

The numba kernels (:mod:`linkwork.motion.kernels_numba`, :mod:`linkwork.kinetostatics.reactions_numba`)
release the GIL, so a long batch runs in parts of at least :data:`PER_THREAD` samples on up to
:data:`THREADS` threads of one pool shared by both (:func:`pool`).  The NumPy kernels run on the calling
thread alone.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor

import numpy as np

#: Threads a long batch is split over (a process of a cluster of one-thread workers sets 1: :func:`set_threads`).
THREADS = min(os.cpu_count() or 1, 8)
#: The least samples (variants times angles) a thread takes.
PER_THREAD = 5_000
_POOL: list[ThreadPoolExecutor] = []


def pool() -> ThreadPoolExecutor:
    """The pool of the compiled kernels' threads (made on first use, of :data:`THREADS` threads)."""
    if not _POOL:
        _POOL.append(ThreadPoolExecutor(THREADS, thread_name_prefix="linkwork"))
    return _POOL[0]


def parts(samples: int) -> int:
    """How many threads a batch of ``samples`` samples runs on: one per :data:`PER_THREAD` samples, at most
    :data:`THREADS`, at least one."""
    return min(THREADS, max(1, samples // PER_THREAD))


def in_parts(part: Callable[[int, int], None], count: int, samples: int) -> None:
    """Run ``part(lo, hi)`` over the slices ``lo:hi`` of ``range(count)`` (the angles of a batch of ``samples``
    samples, variants times angles): :func:`parts` slices of about equal length, the calling thread taking the
    first and the threads of :func:`pool` the others; one call ``part(0, count)`` where there is one part or
    fewer angles than parts.  Returns when every part has run (raising what a part raised)."""
    n_threads = parts(samples)
    if n_threads == 1 or count < n_threads:
        part(0, count)
        return
    bounds = np.linspace(0, count, n_threads + 1).astype(int).tolist()
    rest = [pool().submit(part, lo, hi) for lo, hi in zip(bounds[1:-1], bounds[2:], strict=True)]
    part(bounds[0], bounds[1])
    for job in rest:
        job.result()


def set_threads(threads: int) -> None:
    """Split the batches of this process over at most ``threads`` threads (at least one)."""
    global THREADS
    THREADS = max(1, int(threads))
