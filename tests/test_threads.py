"""The one way a batch is split over the threads of the compiled kernels (:func:`linkwork.threads.in_parts`)."""

from __future__ import annotations

import threading

import pytest

from linkwork import threads


def _calls(monkeypatch, count, samples, n_threads=3, per_thread=100):
    monkeypatch.setattr(threads, "THREADS", n_threads)
    monkeypatch.setattr(threads, "PER_THREAD", per_thread)
    seen: list[tuple[int, int, bool]] = []
    lock = threading.Lock()

    def part(lo: int, hi: int) -> None:
        with lock:
            seen.append((lo, hi, threading.current_thread() is threading.main_thread()))

    threads.in_parts(part, count, samples)
    return sorted(seen)


def test_a_long_batch_is_cut_into_slices_that_cover_each_angle_once(monkeypatch):
    seen = _calls(monkeypatch, count=10, samples=1000)  # 1000 samples at 100 a thread: all 3 threads
    assert [(lo, hi) for lo, hi, _ in seen] == [(0, 3), (3, 6), (6, 10)]  # floor(10 k / 3)
    assert [on_main for _, _, on_main in seen] == [True, False, False]  # the calling thread takes the first


def test_a_short_batch_runs_in_one_call_on_the_calling_thread(monkeypatch):
    assert _calls(monkeypatch, count=10, samples=150) == [(0, 10, True)]  # one part's worth of samples
    assert _calls(monkeypatch, count=2, samples=1000) == [(0, 2, True)]  # fewer angles than parts
    assert _calls(monkeypatch, count=10, samples=1000, n_threads=1) == [(0, 10, True)]


def test_what_a_part_raises_reaches_the_caller(monkeypatch):
    monkeypatch.setattr(threads, "THREADS", 2)
    monkeypatch.setattr(threads, "PER_THREAD", 1)

    def part(lo: int, hi: int) -> None:
        if lo > 0:
            raise ValueError(f"part {lo}:{hi}")

    with pytest.raises(ValueError, match="part 2:4"):
        threads.in_parts(part, 4, 4)
