"""The tiered kernels (:mod:`linkwork.jit`): a long-lived process, a one-shot command and the viewer's edits, each
on the default settings beside ``LINKWORK_NUMBA=1`` (compiled always) and ``LINKWORK_NUMBA=0`` (NumPy always), in
one run.

Run with ``python benchmarks/bench_tiers.py [--cache DIR] [--calls 60] [--edits 100]`` (after
``pip install ".[web]"``).  ``--cache`` is a kernels' cache filled by ``linkwork warm`` (default: a new folder,
filled here first, which takes minutes); every run gets its own ``LINKWORK_CACHE_DIR``: the warm one, or an
empty one for the cold rows.

* A long-lived process: ``--calls`` (and ``--long``) calls each of ``lw.forces(m, steps=360)`` and
  ``lw.kinematics(m, steps=360)`` of the double-cut shears, in turn, in a fresh process; the median of the last 20
  of each, the time of all the calls and of those in the NumPy kernels, and the call at which the default switched
  to the compiled kernels (with the processor time the load took).  The loads measured on this machine
  (:func:`linkwork.jit.measured_cost`) are printed first: the default switches once the NumPy kernels took that.
  Bars: the default's time of all the calls within 1.5 times ``LINKWORK_NUMBA=1``'s (its load included); the
  median of the last 20 of ``--long`` calls within 1.5 times ``LINKWORK_NUMBA=1``'s.
* A one-shot command: ``linkwork forces double-cut-shears`` in a fresh process, the median of ``--repeat``;
  the default with the warm cache and with an empty one (a fresh install's first command: the compile starts
  in the background, stopped after each run).  Bar: cold within 1.5 times ``LINKWORK_NUMBA=0``.
* The viewer: ``linkwork view double-cut-shears`` in its own process; its first edit's round trip, and the
  median of the last half of ``--edits`` edits (``bench_viewer.py``'s round trip), against ``lw.forces`` at 360
  angles with the compiled kernels; the default also with an empty cache.  Bars: the first edit on an empty
  cache under 1 s; the edits within 10 times ``lw.forces`` compiled.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from bench_first_run import stop_compiles
from bench_viewer import crank_length, round_trips, start_server

import linkwork as lw

MODES = {"default": None, "=1": "1", "=0": "0"}

LOOP = """
import json, sys, time, statistics
import linkwork as lw
from linkwork import jit
m = lw.compile("double-cut-shears")
calls, forces, kinematics, switched = int(sys.argv[1]), [], [], None
for i in range(calls):
    t = time.perf_counter(); lw.forces(m, steps=360); forces.append(time.perf_counter() - t)
    t = time.perf_counter(); lw.kinematics(m, steps=360); kinematics.append(time.perf_counter() - t)
    if switched is None and jit.loaded():
        switched = i + 1
print(json.dumps({"forces": statistics.median(forces[-20:]), "kinematics": statistics.median(kinematics[-20:]),
                  "total": sum(forces) + sum(kinematics), "switched": switched, "load": jit.load_seconds(),
                  "ready": jit.ready(), "spent": jit._state.spent}))
"""


def environment(mode: str | None, cache: Path) -> dict[str, str]:
    """This process's environment with ``LINKWORK_NUMBA`` as ``mode`` (unset: None) and the cache ``cache``."""
    env = {k: v for k, v in os.environ.items() if k not in ("LINKWORK_NUMBA", "NUMBA_CACHE_DIR")}
    env["LINKWORK_CACHE_DIR"] = str(cache)
    if mode is not None:
        env["LINKWORK_NUMBA"] = mode
    return env


def long_lived(mode: str | None, cache: Path, calls: int) -> dict[str, float | None]:
    """The medians of the last 20 of ``calls`` calls in a fresh process, and when it switched."""
    out = subprocess.run(
        [sys.executable, "-c", LOOP, str(calls)], env=environment(mode, cache), capture_output=True, text=True
    )
    if out.returncode:
        raise SystemExit(out.stderr)
    return json.loads(out.stdout)


def one_shot(mode: str | None, cache: Path, repeat: int, cold: bool = False) -> float:
    """Median wall time (s) of ``linkwork forces double-cut-shears`` in a fresh process."""
    times = []
    for _ in range(repeat):
        if cold:
            stop_compiles(cache)
        t = time.perf_counter()
        subprocess.run(
            [sys.executable, "-m", "linkwork.cli", "forces", "double-cut-shears"],
            env=environment(mode, cache),
            check=True,
            capture_output=True,
        )
        times.append(time.perf_counter() - t)
    if cold:
        stop_compiles(cache)
    return statistics.median(times)


def viewer(mode: str | None, cache: Path, edits: int, cold: bool = False) -> tuple[float, float]:
    """The first edit's round trip (s) and the median of the last half of ``edits`` more, of a viewer started
    with ``mode`` and ``cache``."""
    mech = lw.compile("double-cut-shears")
    name = crank_length(mech)
    start = lw.parameters(mech)[name]
    if cold:
        stop_compiles(cache)
    saved, env = dict(os.environ), environment(mode, cache)
    os.environ.clear()
    os.environ.update(env)  # the server's (bench_viewer.start_server starts it with this process's)
    try:
        proc, port = start_server("double-cut-shears")
    finally:
        os.environ.clear()
        os.environ.update(saved)
    try:
        first = round_trips(port, name, start * 1.01, 1, warm=0)[0]
        trips = round_trips(port, name, start, edits)
    finally:
        proc.terminate()
        proc.wait(timeout=10)
        if cold:
            stop_compiles(cache)
    return first, statistics.median(trips[len(trips) // 2 :])


def forces_compiled(cache: Path) -> float:
    """Median of ``lw.forces`` at 360 angles with the compiled kernels (a fresh process, 50 calls after 10)."""
    code = (
        "import time, statistics, linkwork as lw; m = lw.compile('double-cut-shears'); ts = []\n"
        "for i in range(60):\n"
        "    t = time.perf_counter(); lw.forces(m, steps=360); ts.append(time.perf_counter() - t)\n"
        "print(statistics.median(ts[10:]))"
    )
    out = subprocess.run([sys.executable, "-c", code], env=environment("1", cache), capture_output=True, text=True)
    return float(out.stdout)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--cache", type=Path, help="a kernels' cache filled by linkwork warm")
    parser.add_argument("--calls", type=int, default=60)
    parser.add_argument("--long", type=int, default=200, help="the calls of a longer process")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--edits", type=int, default=100)
    args = parser.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        warm = args.cache or Path(tmp) / "warm"
        empty = Path(tmp) / "empty"
        if args.cache is None:
            subprocess.run([sys.executable, "-m", "linkwork.cli", "warm"], env=environment(None, warm), check=True)
        measured = [float(v) for record in warm.glob("loads-*") for v in record.read_text().split()]
        print(f"loads measured on this machine (jit.measured_cost): {', '.join(f'{v:.2f}' for v in measured)} s")
        for calls in (args.calls, args.long):
            print(f"long-lived process, double-cut shears, 360 angles, median of the last 20 of {calls} calls")
            for label, mode in MODES.items():
                r = long_lived(mode, warm, calls)
                switched = f", switched after call {r['switched']} (load {r['load']:.2f} s)" if r["load"] else ""
                print(
                    f"  {label:8s} lw.forces {1e3 * r['forces']:7.2f} ms   lw.kinematics {1e3 * r['kinematics']:6.2f}"
                    f" ms   all calls {r['total']:6.2f} s   in the NumPy kernels {r['spent']:5.2f} s{switched}"
                )
        print(f"one-shot: linkwork forces double-cut-shears, median of {args.repeat}")
        for label, mode in MODES.items():
            print(f"  {label:8s} {one_shot(mode, warm, args.repeat):6.2f} s")
        print(f"  {'cold':8s} {one_shot(None, empty, args.repeat, cold=True):6.2f} s (default, empty cache)")
        compiled = forces_compiled(warm)
        print(f"the viewer's edits (lw.forces compiled: {1e3 * compiled:.2f} ms): first, the median of the last half")
        for label, mode in MODES.items():
            first, median = viewer(mode, warm, args.edits)
            ratio = median / compiled
            print(f"  {label:8s} first {1e3 * first:7.1f} ms   median {1e3 * median:6.1f} ms ({ratio:.1f}x)")
        first, median = viewer(None, empty, args.edits, cold=True)
        print(f"  {'cold':8s} first {1e3 * first:7.1f} ms   median {1e3 * median:6.1f} ms (default, empty cache)")


if __name__ == "__main__":
    main()
