"""A viewer application on a real uvicorn server in a background thread, for the web tests."""

from __future__ import annotations

import socket
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any


@contextmanager
def serving(app: Any, **config: Any) -> Iterator[tuple[str, int]]:
    """Serve ``app`` on 127.0.0.1 at a free port while the block runs, configured as `linkwork view` serves it
    (``config``: :func:`linkwork.web.server.server_config`'s options): yields (host, port)."""
    import uvicorn

    from linkwork.web.server import server_config

    sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM, socket.IPPROTO_TCP)  # as linkwork view: no Nagle
    sock.bind(("127.0.0.1", 0))
    srv = uvicorn.Server(server_config(app, **config))
    thread = threading.Thread(target=srv.run, kwargs={"sockets": [sock]}, daemon=True)
    thread.start()
    deadline = time.monotonic() + 30
    while not srv.started:
        assert time.monotonic() < deadline and thread.is_alive(), "the server did not start"
        time.sleep(0.05)
    try:
        yield "127.0.0.1", sock.getsockname()[1]
    finally:
        srv.should_exit = True
        thread.join(timeout=10)
        sock.close()
