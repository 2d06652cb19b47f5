"""Sweeps on a real Dask cluster of separate processes on loopback: a scheduler and two workers.

The results equal those computed in this process; a worker killed in the middle of a sweep has its
chunk computed again by the other, and every variant ends in the table exactly once; a sweep stopped
part way resumes on the cluster without computing again what is on disk.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import linkwork as lw

pytestmark = pytest.mark.dask

pytest.importorskip("distributed")
pytest.importorskip("pyarrow")

VARY = ["links.crank.length=95mm:105mm:6", "links.rod.mass=50:70:4"]
METRICS = ["peak_driving_torque", "peak_foundation_force", "knife_overlap", "knife_clearance", "stroke"]


def _start(args: list[str], log: Path) -> subprocess.Popen:
    env = dict(os.environ, PYTHONUNBUFFERED="1")
    with open(log, "w") as fh:
        return subprocess.Popen([sys.executable, "-m", *args], stdout=fh, stderr=subprocess.STDOUT, env=env)


@pytest.fixture(scope="module")
def cluster(tmp_path_factory):
    """A scheduler and two single-threaded workers (no nanny: a killed worker stays dead)."""
    from distributed import Client

    tmp = tmp_path_factory.mktemp("dask")
    sched_file = tmp / "scheduler.json"
    procs: list[subprocess.Popen] = []
    try:
        procs.append(
            _start(
                [
                    "distributed.cli.dask_scheduler",
                    "--host",
                    "127.0.0.1",
                    "--port",
                    "0",
                    "--no-dashboard",
                    "--dashboard-address",  # its other pages (/json, /metrics) off Dask's port 8787, which
                    "127.0.0.1:0",  # the test of a sweep's own cluster probes
                    "--scheduler-file",
                    str(sched_file),
                ],
                tmp / "scheduler.log",
            )
        )
        deadline = time.monotonic() + 60
        while not sched_file.exists():
            if time.monotonic() > deadline or procs[0].poll() is not None:
                pytest.fail("the Dask scheduler did not start: " + (tmp / "scheduler.log").read_text())
            time.sleep(0.1)
        for i in range(2):
            procs.append(
                _start(
                    [
                        "distributed.cli.dask_worker",
                        "--scheduler-file",
                        str(sched_file),
                        "--nthreads",
                        "1",
                        "--nworkers",
                        "1",
                        "--no-nanny",
                        "--no-dashboard",
                        "--host",
                        "127.0.0.1",
                        "--name",
                        f"w{i}",
                    ],
                    tmp / f"worker{i}.log",
                )
            )
        with Client(scheduler_file=str(sched_file), timeout=60) as client:
            client.wait_for_workers(2, timeout=60)
        yield {"file": str(sched_file), "workers": procs[1:], "procs": procs}
    finally:
        for p in reversed(procs):
            if p.poll() is None:
                p.terminate()
        for p in procs:
            try:
                p.wait(timeout=15)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait()


def _attempts(path: Path) -> list[tuple[int, int]]:
    return [
        (int(c), int(pid))
        for f in sorted(path.glob("attempts-*.txt"))
        for c, pid in (line.split() for line in f.read_text().splitlines())
    ]


def _equal(a, b):
    assert set(a.columns) == set(b.columns)
    for name in a.columns:
        np.testing.assert_array_equal(a[name], b[name])


def test_an_embedded_local_cluster_gives_the_results_of_this_process(tmp_path):
    """--workers 2: a LocalCluster of two worker processes started by the sweep itself."""
    vary = ["links.crank.length=95mm:105mm:3", "links.rod.mass=50:70:2"]
    here = lw.sweep("double-cut-shears", vary, METRICS, steps=60, chunk_size=1, workers=0)
    there = lw.sweep("double-cut-shears", vary, METRICS, steps=60, chunk_size=1, workers=2, attempts=tmp_path)
    _equal(here, there)
    log = _attempts(tmp_path)
    assert sorted(c for c, _ in log) == list(range(6))
    assert os.getpid() not in {pid for _, pid in log}  # computed in the workers, not here


def test_the_cluster_gives_the_results_of_this_process(cluster, tmp_path):
    here = lw.sweep("double-cut-shears", VARY, METRICS, steps=120, chunk_size=5, workers=0)
    there = lw.sweep(
        "double-cut-shears",
        VARY,
        METRICS,
        steps=120,
        chunk_size=5,
        scheduler=cluster["file"],
        out=tmp_path / "s.parquet",
        attempts=tmp_path,
    )
    _equal(here, there)
    pids = {pid for _, pid in _attempts(tmp_path)}
    assert len(pids) == 2  # both workers took part
    assert sorted(c for c, _ in _attempts(tmp_path)) == list(range(5))


def test_a_sweep_stopped_part_way_resumes_on_the_cluster(cluster, tmp_path):
    out = tmp_path / "s.parquet"
    first: list[int] = []
    second: list[int] = []

    class Stop(Exception):
        pass

    def stop(chunk, done, total):
        first.append(chunk)
        if done == 3:
            raise Stop

    logs = tmp_path / "first", tmp_path / "second"
    for d in logs:
        d.mkdir()
    kw = dict(steps=120, chunk_size=3, scheduler=cluster["file"], out=out)
    with pytest.raises(Stop):
        lw.sweep("double-cut-shears", VARY, METRICS, on_chunk=stop, attempts=logs[0], **kw)
    assert len(first) == 3 and not out.exists()
    t = lw.sweep(
        "double-cut-shears",
        VARY,
        METRICS,
        on_chunk=lambda c, d, n: second.append(c),
        resume=True,
        attempts=logs[1],
        **kw,
    )
    assert sorted(first + second) == list(range(8))  # 24 variants in 8 chunks, each stored once
    redone = [c for c, _ in _attempts(logs[1])]
    assert sorted(redone) == sorted(second)  # the chunks on disk were not computed again
    np.testing.assert_array_equal(t["variant"], np.arange(24))
    _equal(t, lw.sweep("double-cut-shears", VARY, METRICS, steps=120, chunk_size=3, workers=0))


def test_a_worker_killed_mid_sweep_has_its_chunk_retried_and_every_variant_is_computed_once(cluster, tmp_path):
    """Runs last: it kills one of the two workers."""
    from distributed import Client

    with Client(scheduler_file=cluster["file"], timeout=30) as client:
        info = client.scheduler_info()["workers"]
    assert len(info) == 2
    victim = cluster["workers"][0]
    killed: list[int] = []

    stored: list[int] = []

    def kill_after_two(chunk, done, total):
        stored.append(chunk)
        if done == 2 and not killed:
            # wait until the victim has started a chunk whose result is not stored (this loop holds the
            # results back meanwhile), then kill it: that computation is lost
            log = tmp_path / f"attempts-{victim.pid}.txt"
            deadline = time.monotonic() + 20
            while time.monotonic() < deadline:
                started = {int(line.split()[0]) for line in log.read_text().splitlines()} if log.exists() else set()
                if started - set(stored):
                    break
                time.sleep(0.01)
            os.kill(victim.pid, signal.SIGKILL)
            killed.append(victim.pid)

    out = tmp_path / "s.parquet"
    t = lw.sweep(
        "double-cut-shears",
        VARY,
        METRICS,
        steps=360,
        chunk_size=2,
        scheduler=cluster["file"],
        out=out,
        attempts=tmp_path,
        on_chunk=kill_after_two,
        keep_parts=True,
    )
    assert killed and victim.wait(timeout=10) == -signal.SIGKILL
    np.testing.assert_array_equal(t["variant"], np.arange(24))
    parts = sorted(p.name for p in (tmp_path / "s.parquet.parts").glob("chunk-*.parquet"))
    assert parts == [f"chunk-{c:05d}.parquet" for c in range(12)]
    log = _attempts(tmp_path)
    chunks = [c for c, _ in log]
    assert set(chunks) == set(range(12))
    assert sorted(stored) == list(range(12))  # each chunk stored once
    twice = {c for c in chunks if chunks.count(c) > 1}
    # computed again: only chunks the victim had in hand when it died (the one it was computing, and
    # any it had finished whose result had not been fetched yet), each once more, by the survivor
    assert twice
    for c in twice:
        pids = [p for cc, p in log if cc == c]
        assert len(pids) == 2 and pids[0] == victim.pid and pids[1] != victim.pid
    _equal(t, lw.sweep("double-cut-shears", VARY, METRICS, steps=360, chunk_size=2, workers=0))


def _pages(host: str) -> dict[str, int]:
    """The HTTP status of a few of Dask's pages on the web servers of the cluster this process is a client of
    (its scheduler's and its workers'), asked for with the Host header ``host``; 8787 is Dask's own port."""
    import urllib.error
    import urllib.request

    from distributed import default_client

    client = default_client()
    ports = {client.run_on_scheduler(lambda dask_scheduler: dask_scheduler.http_server.port)}
    ports |= set(client.run(lambda dask_worker: dask_worker.http_server.port).values())
    status = {}
    for port in sorted(ports | {8787}):
        for page in ("/status", "/json/identity.json", "/info/main/workers.html", "/metrics"):
            request = urllib.request.Request(f"http://127.0.0.1:{port}{page}", headers={"Host": host})
            try:
                with urllib.request.urlopen(request, timeout=5) as reply:
                    status[f"{port}{page}"] = reply.status
            except urllib.error.HTTPError as exc:
                status[f"{port}{page}"] = exc.code
            except OSError:
                status[f"{port}{page}"] = 0  # nothing listens
    return status


def test_a_local_cluster_serves_no_page_unless_asked_for(tmp_path):
    """Dask's pages answer whatever host a request names, so that a page in a browser on this machine could
    read them through a name of its own for 127.0.0.1: a sweep's local cluster serves none."""
    seen: list[dict[str, int]] = []

    def probe(chunk: int, done: int, total: int) -> None:
        if not seen:
            seen.append(_pages("attacker.example"))

    lw.sweep(
        "four-bar", ["links.crank.length=95mm:105mm:2"], ["swing"], steps=12, chunk_size=1, workers=1, on_chunk=probe
    )
    assert seen and len(seen[0]) >= 8  # the scheduler's, a worker's and 8787
    served = {page: code for page, code in seen[0].items() if 200 <= code < 400}
    assert served == {}
