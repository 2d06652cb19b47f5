"""The Dask cluster a sweep runs on: its scheduler checked before connecting, an embedded local cluster.

:func:`scheduler_problems` says what is wrong with a ``--scheduler`` (an address or a scheduler file) before
anything connects; :func:`connect` gives a Dask client of that scheduler (probed first: :func:`probe_scheduler`)
or of an embedded local cluster serving no pages (:func:`_local_cluster`).  The chunks themselves are run by
:mod:`linkwork.design.sweeps`.
"""

from __future__ import annotations

import json
import math
import os
import re
import sys
import time
from pathlib import Path
from typing import Any

from linkwork.errors import LinkworkError
from linkwork.limits import MAX_TIMEOUT, QUOTE_PATH, excerpt, quote
from linkwork.optional import require

_ADDRESS = re.compile(r"^([a-z]+://)?[^\s/:]+:\d+$|^[a-z]+://\[[0-9a-fA-F:]+\]:\d+$")


def scheduler_problems(scheduler: str, connect_timeout: float) -> list[str]:
    """What is wrong with a ``--scheduler`` (an address or a scheduler file) before connecting, and with the
    time to wait for it."""
    out = []
    shown = excerpt(scheduler, QUOTE_PATH)
    try:
        is_file = Path(scheduler).is_file()
    except OSError as exc:
        is_file = False
        out.append(f'--scheduler "{shown}": {exc.strerror or exc}')
    if is_file:
        why = _not_a_scheduler_file(Path(scheduler))
        if why is not None:
            out.append(f'--scheduler "{shown}": not a Dask scheduler file ({why})')
    elif not _ADDRESS.match(scheduler) and not out:
        if scheduler.endswith(".json") or "/" in scheduler.split("://")[-1]:
            out.append(f'--scheduler "{shown}": no such scheduler file')
        else:
            out.append(f'--scheduler "{shown}": expected an address tcp://HOST:PORT or a scheduler file')
    ok = isinstance(connect_timeout, int | float) and math.isfinite(connect_timeout)
    if not (ok and 0 < connect_timeout <= MAX_TIMEOUT):
        out.append(
            f"connect timeout: expected a positive number of seconds, at most {MAX_TIMEOUT:g}, got {connect_timeout!r}"
        )
    return out


#: Bytes of a scheduler file read (Dask writes a few hundred).
_SCHEDULER_FILE_BYTES = 1 << 16


def _not_a_scheduler_file(path: Path) -> str | None:
    """Why ``path`` is not a Dask scheduler file (a JSON object whose ``address`` is a scheduler's address),
    or None."""
    try:
        with open(path, "rb") as fh:
            data = fh.read(_SCHEDULER_FILE_BYTES + 1)
    except OSError as exc:
        return str(exc.strerror or exc)
    if len(data) > _SCHEDULER_FILE_BYTES:
        return f"larger than {_SCHEDULER_FILE_BYTES:,} bytes"
    try:
        info = json.loads(data)
    except (ValueError, RecursionError):
        return "not JSON"
    address = info.get("address") if isinstance(info, dict) else None
    if not isinstance(address, str) or not _ADDRESS.match(address):
        return f'no "address" of a scheduler in it, got {quote(address) if isinstance(address, str) else "none"}'
    return None


def connect(workers: int | None, scheduler: str | None, connect_timeout: float, dashboard: bool) -> tuple[Any, Any]:
    """A Dask client of the scheduler at ``scheduler`` (an address or a scheduler file), or of an embedded
    local cluster of ``workers`` processes of one thread each (:func:`_local_cluster`):
    ``(client, cluster or None)``.

    Raises
    ------
    LinkworkError
        The scheduler cannot be reached within ``connect_timeout`` seconds.
    """
    require("distributed", purpose="a sweep on Dask (--workers, --scheduler, or more than 20,000 variants)")
    from distributed import Client

    if scheduler is None:
        cluster = _local_cluster(workers or os.cpu_count() or 1, dashboard)
        return Client(cluster), cluster
    deadline = time.monotonic() + connect_timeout
    try:
        is_file = Path(scheduler).is_file()
        address = json.loads(Path(scheduler).read_bytes())["address"] if is_file else scheduler
        probe_scheduler(address, connect_timeout)
        left = max(deadline - time.monotonic(), 0.1)
        if is_file:
            return Client(scheduler_file=scheduler, timeout=left), None
        return Client(scheduler, timeout=left), None
    except (OSError, ValueError, KeyError, TypeError) as exc:
        why = str(exc) or type(exc).__name__
        within = f"within {connect_timeout:g} s"
        raise LinkworkError(f"cannot reach a Dask scheduler at {scheduler} {within}: {why}") from None


#: The most bytes of the greeting a Dask scheduler sends on a new connection (its handshake: some hundred).
_GREETING_BYTES = 1 << 16


def probe_scheduler(address: str, timeout: float) -> None:
    """Check that a Dask scheduler answers at the ``tcp://`` ``address`` within ``timeout`` seconds, before
    Dask's client trusts it: a scheduler greets each new connection with its handshake, one message of
    Dask's frames (its length, the count of its frames and their lengths, each a little-endian 64-bit
    number).  A service that sends something else (an HTTP server answering Dask's greeting, which Dask
    would read as a length of exbibytes) or nothing (which Dask would wait for without end) is refused.
    Addresses of other protocols are left to Dask.

    Raises
    ------
    OSError
        Nothing listens there, or what answers is no Dask scheduler (why, in words).
    """
    import socket
    import struct
    from urllib.parse import urlsplit

    if not address.startswith("tcp://"):
        return
    where = urlsplit(address)
    deadline = time.monotonic() + timeout
    with socket.create_connection((where.hostname, where.port), timeout=timeout) as sock:
        try:
            head = _receive(sock, 8, deadline)
            (size,) = struct.unpack("<Q", head)
            if not 16 <= size <= _GREETING_BYTES:
                raise OSError(f"the service there is no Dask scheduler: it began its answer with {head!r}")
            body = _receive(sock, size, deadline)
        except TimeoutError:
            raise OSError("the service there accepted the connection but sent no Dask handshake") from None
    (frames,) = struct.unpack_from("<Q", body)
    if not 1 <= frames <= 64 or 8 * (frames + 1) > size:
        raise OSError("the service there is no Dask scheduler: its greeting is not a message of Dask's frames")


def _receive(sock: Any, n: int, deadline: float) -> bytes:
    """``n`` bytes from ``sock`` by ``deadline`` (time.monotonic); TimeoutError past it, OSError if it closes."""
    data = b""
    while len(data) < n:
        sock.settimeout(max(deadline - time.monotonic(), 1e-3))
        chunk = sock.recv(n - len(data))
        if not chunk:
            raise OSError("the service there closed the connection without a Dask handshake")
        data += chunk
    return data


#: Dask's settings of the web servers of its scheduler and workers: no pages at all.
NO_PAGES: dict[str, list[str]] = {"distributed.scheduler.http.routes": [], "distributed.worker.http.routes": []}


def _local_cluster(n: int, dashboard: bool) -> Any:
    """A local Dask cluster of ``n`` worker processes of one thread each, on 127.0.0.1.

    Dask's scheduler and workers always run a web server; its pages (the dashboard, and the JSON and
    Prometheus pages of the cluster's state) answer a request whatever host it names, so a web page in a
    browser on this machine could read them through a host name of its own that points to 127.0.0.1.
    Unless ``dashboard`` is asked for, they serve no page, on a free port (every request gets 404, but for
    Dask's list of the pages, ``/sitemap.json``, which is then empty).  With
    ``dashboard``, Dask's dashboard is served on 127.0.0.1:8787 and its link written on stderr.
    """
    import dask
    from distributed import LocalCluster

    if dashboard:
        cluster = LocalCluster(
            n_workers=n, threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address="127.0.0.1:8787"
        )
        sys.stderr.write(f"Dask's dashboard (while the sweep runs): {cluster.dashboard_link}\n")
        return cluster
    with dask.config.set(NO_PAGES):
        return LocalCluster(
            n_workers=n,
            threads_per_worker=1,
            processes=True,
            host="127.0.0.1",
            dashboard_address=None,
            scheduler_kwargs={"dashboard": False, "dashboard_address": "127.0.0.1:0"},
        )
