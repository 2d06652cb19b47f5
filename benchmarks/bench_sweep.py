"""Design sweep benchmark: one million four-bar variants x 360 crank angles on a local Dask cluster.

Run with ``python benchmarks/bench_sweep.py`` (``--variants 100000`` for a
shorter run).  Every variant of the bundled four-bar (crank and rocker
lengths from a Latin-hypercube sample) is solved over a whole turn through
:func:`linkwork.sweep`: positions, velocities and accelerations of every
link, then the smallest transmission angle and the rocker's swing.  The
sweep runs in this process, and on an embedded local Dask cluster of one
and of two worker processes (one thread each), each cluster started and its
workers' compiled kernels loaded before the timed sweep (the start is shown
apart).  The three tables are checked to be equal before the times are
reported.  Prints variants/s and the speed-up from one to two workers.
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

import linkwork as lw

VARY = ["links.crank.length=90mm:110mm", "links.rocker.length=240mm:260mm"]
METRICS = ["min_transmission_angle", "swing"]


def run(n: int, steps: int, workers: int, chunk: int | None):
    """Time one sweep; on a local cluster of ``workers`` processes (started and warmed up first, timed apart)
    or, for 0, in this process.  Returns (startup, sweep time, table)."""
    kw = dict(sampling="lhs", samples=n, seed=1, steps=steps, chunk_size=chunk)
    if workers == 0:
        lw.sweep("four-bar", VARY, METRICS, sampling="lhs", samples=10, steps=steps, workers=0)  # compile
        t = time.perf_counter()
        table = lw.sweep("four-bar", VARY, METRICS, workers=0, **kw)
        return 0.0, time.perf_counter() - t, table
    from distributed import Client, LocalCluster

    t = time.perf_counter()
    with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with Client(cluster) as client:
            client.wait_for_workers(workers)
        # load the compiled kernels in every worker
        lw.sweep(
            "four-bar",
            VARY,
            METRICS,
            sampling="lhs",
            samples=20 * workers,
            steps=steps,
            chunk_size=10,
            scheduler=cluster.scheduler_address,
        )
        startup = time.perf_counter() - t
        t = time.perf_counter()
        table = lw.sweep("four-bar", VARY, METRICS, scheduler=cluster.scheduler_address, **kw)
        return startup, time.perf_counter() - t, table


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--variants", type=int, default=1_000_000)
    parser.add_argument("--steps", type=int, default=360)
    parser.add_argument("--chunk-size", type=int, default=None, help="variants per chunk (default: linkwork's)")
    parser.add_argument("--skip-in-process", action="store_true", help="only the Dask runs")
    args = parser.parse_args()
    n, steps = args.variants, args.steps
    print(f"four-bar, {n} variants x {steps} angles (positions, velocities, accelerations; {', '.join(METRICS)})")
    print(f"machine: {os.cpu_count()} cores")
    print(f"{'':28s} {'start, s':>9s} {'sweep, s':>9s} {'variants/s':>12s} {'M configurations/s':>19s}")
    rows = []
    runs = [(1, "local Dask, 1 worker"), (2, "local Dask, 2 workers")]
    if not args.skip_in_process:
        runs.append((0, "in this process"))
    tables = []
    for workers, label in runs:
        startup, t, table = run(n, steps, workers, args.chunk_size)
        tables.append(table)
        rows.append((label, t))
        print(f"{label:28s} {startup:9.2f} {t:9.2f} {n / t:12.0f} {n * steps / t / 1e6:19.2f}")
    for table in tables[1:]:
        for name in METRICS:
            assert np.array_equal(table[name], tables[0][name], equal_nan=True), name
    print(f"speed-up from one to two workers: {rows[0][1] / rows[1][1]:.2f}x (tables equal)")


if __name__ == "__main__":
    main()
