"""Command-line benchmark: the commands a user runs often, end to end, each in a fresh process.

Run with ``python benchmarks/bench_cli.py`` (after ``pip install ".[plot,data]"``), on a machine as quiet
as you can find it.  Each command is started as a fresh process (interpreter start, imports, the work and
its output); the best of a few runs, and the median beside it.  ``linkwork analyze double-cut-shears``
writes every table, figure, the animation and ``report.html`` (its first run, not timed, fills numba's
cache of compiled kernels).  Targets: ``--help`` 0.5 s, ``check`` 0.5 s, ``analyze`` 3 s.
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import tempfile
import time


def timed(args: list[str], repeat: int) -> tuple[float, float]:
    """Best and median wall time (s) of ``repeat`` runs of ``linkwork ARGS``."""
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        subprocess.run([sys.executable, "-m", "linkwork.cli", *args], check=True, capture_output=True)
        times.append(time.perf_counter() - t)
    return min(times), statistics.median(times)


def main() -> None:
    rows = [
        ("linkwork --help", ["--help"], 7, 0.5),
        ("linkwork check double-cut-shears", ["check", "double-cut-shears"], 7, 0.5),
    ]
    results = [(label, *timed(args, n), target) for label, args, n, target in rows]
    with tempfile.TemporaryDirectory() as tmp:
        timed(["analyze", "double-cut-shears", "--out", f"{tmp}/warm"], 1)  # compiled kernels cached
        best, median = timed(["analyze", "double-cut-shears", "--out", f"{tmp}/report"], 5)
        results.append(("linkwork analyze double-cut-shears", best, median, 3.0))
    for label, best, median, target in results:
        print(f"{label:38s} {best:6.2f} s best, {median:6.2f} s median   (target {target:g} s)")


if __name__ == "__main__":
    main()
