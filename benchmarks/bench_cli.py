"""Command-line benchmark: ``linkwork --help`` and ``linkwork analyze double-cut-shears`` end to end.

Run with ``python benchmarks/bench_cli.py`` (after ``pip install ".[plot,fast]"``).  Each command is
started as a fresh process (interpreter start, imports and, for analyze, every analysis, figure,
the animation and the report); best of a few runs.  Targets: under 0.5 s and under 10 s.
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
import time


def timed(args: list[str], repeat: int) -> float:
    best = float("inf")
    for _ in range(repeat):
        t = time.perf_counter()
        subprocess.run([sys.executable, "-m", "linkwork.cli", *args], check=True, capture_output=True)
        best = min(best, time.perf_counter() - t)
    return best


def main() -> None:
    help_time = timed(["--help"], 5)
    with tempfile.TemporaryDirectory() as tmp:
        timed(["analyze", "double-cut-shears", "--out", f"{tmp}/warm"], 1)  # compiled kernels cached
        analyze_time = timed(["analyze", "double-cut-shears", "--out", f"{tmp}/report"], 3)
    print(f"linkwork --help                      {help_time:6.2f} s   (target 0.5 s)")
    print(f"linkwork analyze double-cut-shears   {analyze_time:6.2f} s   (target 10 s)")


if __name__ == "__main__":
    main()
