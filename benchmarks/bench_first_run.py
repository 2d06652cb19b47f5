"""A new user's first runs: each command cold (an empty cache of compiled kernels) and warm, against the
NumPy kernels (``LINKWORK_NUMBA=0``), each in a fresh process.

Run with ``python benchmarks/bench_first_run.py`` (after ``pip install ".[plot,data]"``); for a fresh
install, make a fresh virtual environment, install linkwork into it and pass its interpreter with
``--python .venv-fresh/bin/python``.  The kernels' cache is a new temporary folder (``LINKWORK_CACHE_DIR``).

- *numpy*: ``LINKWORK_NUMBA=0``, the reference.
- *cold*: the default with the cache empty: the command answers with the NumPy kernels while the compile
  starts in a process of its own at the lowest priority; the compile is stopped after each cold run, so
  every cold run finds the cache empty (as a first run does).
- *warm*: the default after ``linkwork warm`` filled the cache (timed too: what the compile costs).

Target: cold within 1.5 times numpy for every command (issue "the first ten minutes").
"""

from __future__ import annotations

import argparse
import os
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

COMMANDS = [
    ("check", ["check", "double-cut-shears"]),
    ("kinematics", ["kinematics", "double-cut-shears"]),
    ("forces", ["forces", "double-cut-shears"]),
    ("dynamics", ["dynamics", "double-cut-shears"]),
    ("analyze", ["analyze", "double-cut-shears", "--out", "{tmp}/report"]),
]


def run(python: str, args: list[str], env: dict[str, str]) -> float:
    """Wall time (s) of ``linkwork ARGS`` in a fresh process."""
    t = time.perf_counter()
    subprocess.run([python, "-m", "linkwork.cli", *args], check=True, capture_output=True, env=env)
    return time.perf_counter() - t


def stop_compiles(cache: Path) -> None:
    """Stop a compile a cold run started, and empty the cache again."""
    for lock in cache.glob("compiling-*"):
        try:
            os.kill(int(lock.read_text().split()[0]), signal.SIGKILL)
        except (OSError, ValueError):
            pass
    shutil.rmtree(cache, ignore_errors=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--python", default=sys.executable, help="the interpreter of the install to measure")
    parser.add_argument("--repeat", type=int, default=3)
    opts = parser.parse_args()
    base = {k: v for k, v in os.environ.items() if k not in ("LINKWORK_NUMBA", "NUMBA_CACHE_DIR")}
    with tempfile.TemporaryDirectory() as tmp:
        cache = Path(tmp) / "kernels"
        env = {**base, "LINKWORK_CACHE_DIR": str(cache)}
        rows = []
        for label, args in COMMANDS:
            args = [a.format(tmp=tmp) for a in args]
            numpy = [run(opts.python, args, {**env, "LINKWORK_NUMBA": "0"}) for _ in range(opts.repeat)]
            cold = []
            for _ in range(opts.repeat):
                stop_compiles(cache)
                cold.append(run(opts.python, args, env))
            stop_compiles(cache)
            rows.append((label, args, statistics.median(numpy), statistics.median(cold)))
        compile_s = run(opts.python, ["warm"], env)
        print(f"{'command':12s} {'numpy':>8s} {'cold':>8s} {'cold/numpy':>10s} {'warm':>8s}")
        for label, args, numpy_s, cold_s in rows:
            warm_s = statistics.median(run(opts.python, args, env) for _ in range(opts.repeat))
            print(f"{label:12s} {numpy_s:7.2f}s {cold_s:7.2f}s {cold_s / numpy_s:10.2f} {warm_s:7.2f}s")
        print(f"linkwork warm (the compile, once): {compile_s:.1f} s")


if __name__ == "__main__":
    main()
