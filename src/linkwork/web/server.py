"""The viewer's local server: the page, its static files and a small JSON API.

Endpoints (all JSON except the page, its files, an edit's answer and a saved file):

* ``GET /`` the page; ``GET /static/NAME`` its script and style (:data:`STATIC`);
* ``GET /api/cycle``: the cycle of the mechanism as it was loaded
  (:func:`linkwork.web.payload.cycle_payload`, with ``parameters``); ``?labels=first``: its labels
  placed at the first sample only, the page's first answer (the page then asks for the labels of the
  cycle);
* ``GET /api/parameters``: the editable dimensions and masses;
* ``POST /api/solve`` ``{"overrides": {name: value}, "steps": n}``: the whole cycle of the edited
  mechanism (values in SI), its labels placed;
* ``POST /api/edit`` ``{"overrides": {...}, "steps": n, "whole_turn": bool, "client": id, "seq": n}``: what
  the edit changes, compact (:mod:`linkwork.web.update`: its JSON, then its arrays' bytes), in some
  milliseconds; its failures are JSON as any other's; with ``whole_turn`` a
  variant that does not assemble where the file's mechanism does is refused (a drag); an edit that
  waits for a slot while the same ``client`` sends a newer one (a higher ``seq``) is answered 409
  (superseded) unsolved: the latest wins;
* ``POST /api/pose`` ``{"angle_deg": a, "overrides": {...}}``: every point at one crank angle, solved on
  its own; it takes no solving slot, so a crank step never waits for an edit;
* ``POST /api/force-plans`` ``{"overrides": {...}, "steps": n, "index": i}``: the force plans of the groups and
  Zhukovsky's lever at sample ``i`` of the cycle (:mod:`linkwork.web.force_plans`: ``force_plans`` of the
  payload, with that one sample); it takes no solving slot;
* ``POST /api/save`` ``{"overrides": {...}}``: the mechanism's file with the values written in, its
  comments and layout kept (:func:`linkwork.structure.parameters.file_text`), as a download.

Bodies are JSON objects of at most :data:`MAX_BODY` bytes, validated by
pydantic (types, ranges, at most :data:`~linkwork.web.edits.MAX_OVERRIDES`
overrides); an edit that fails answers 422 with linkwork's message (the
file's line, the group and crank angles that do not assemble, and for a
variant out of its range the ``events``), a malformed request 400, 413 or
415, and the server goes on serving.  A client that goes away before its
request is read is let go quietly; one that goes while its request's work
runs is not waited for (:func:`answer`), nor is that work when the server
stops (:func:`serve`).  Requests must name the loopback host
(``127.0.0.1``, ``localhost``, ``[::1]``, with a port): a page elsewhere
cannot reach the server through a rebound DNS name.  Nothing from a
request is evaluated.
"""

from __future__ import annotations

import asyncio
import json
import re
import signal
import threading
import time
from collections.abc import AsyncIterator, Callable, Iterator
from contextlib import asynccontextmanager, contextmanager
from threading import BoundedSemaphore
from typing import TYPE_CHECKING, Annotated, Any, Literal

from fastapi import FastAPI, Request
from fastapi.exceptions import RequestValidationError
from fastapi.responses import HTMLResponse, JSONResponse, Response
from pydantic import BaseModel, ConfigDict, Field, StringConstraints, ValidationError
from starlette.concurrency import run_in_threadpool
from starlette.datastructures import MutableHeaders
from starlette.exceptions import HTTPException as StarletteHTTPException
from starlette.requests import ClientDisconnect
from starlette.types import ASGIApp, Message, Receive, Scope, Send

from linkwork import jit
from linkwork.errors import BusyError, LinkworkError
from linkwork.limits import digits
from linkwork.web.cycle import OutOfRange
from linkwork.web.edits import MAX_OVERRIDES
from linkwork.web.session import SCRIPTS, Viewer, dumps, page_html, static_text
from linkwork.web.update import EDIT_MEDIA

if TYPE_CHECKING:
    from pathlib import Path

    from linkwork.spec.schema import Spec
    from linkwork.structure.model import Mechanism

#: Largest request body, bytes.
MAX_BODY = 64 * 1024
#: Steps of the cycle an edit may ask for (1440: a quarter of a degree; the cache keeps 16 cycles).
MIN_STEPS, MAX_STEPS = 12, 1440
#: The Host headers the server answers to: a loopback name and an optional port, nothing else.
HOST = re.compile(r"(\[::1\]|127\.0\.0\.1|localhost)(:\d{1,5})?", re.IGNORECASE)
#: The page's files and their types.
STATIC = {name: "text/javascript" for name in SCRIPTS} | {"viewer.css": "text/css"}

SECURITY_HEADERS = {
    "Content-Security-Policy": "default-src 'none'; script-src 'self'; style-src 'self'; img-src 'self' data:; "
    "connect-src 'self'; base-uri 'none'; form-action 'none'; frame-ancestors 'none'",
    "X-Content-Type-Options": "nosniff",
    "Referrer-Policy": "no-referrer",
    "Cache-Control": "no-store",
}


Name = Annotated[str, StringConstraints(min_length=1, max_length=200)]
Value = Annotated[float, Field(allow_inf_nan=False)]
Overrides = Annotated[dict[Name, Value], Field(max_length=MAX_OVERRIDES)]
Client = Annotated[str, StringConstraints(pattern=r"^[A-Za-z0-9_-]{1,64}$")]


class _Body(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True)


class SolveRequest(_Body):
    """``POST /api/solve``: overrides of named dimensions and masses (SI), and the steps of the cycle."""

    overrides: Overrides = Field(default_factory=dict)
    steps: int | None = Field(None, ge=MIN_STEPS, le=MAX_STEPS)


class EditRequest(SolveRequest):
    """``POST /api/edit``: as :class:`SolveRequest`; ``whole_turn``: refuse a variant that does not assemble
    where the file's mechanism does; ``client`` and ``seq``: the page and the number of its edit (latest wins)."""

    whole_turn: bool = False
    client: Client | None = None
    seq: int | None = Field(None, ge=0, le=2**53)


class PoseRequest(_Body):
    """``POST /api/pose``: one crank angle (deg) of the mechanism with overrides."""

    angle_deg: Value = Field(ge=-1e6, le=1e6)
    overrides: Overrides = Field(default_factory=dict)


class ForcePlansRequest(SolveRequest):
    """``POST /api/force-plans``: as :class:`SolveRequest`, and the ``index`` of the sample drawn."""

    index: int = Field(ge=0, le=MAX_STEPS)


class SaveRequest(_Body):
    """``POST /api/save``: the values (SI) to write into the mechanism's file."""

    overrides: Overrides = Field(default_factory=dict)


class Rejected(Exception):
    """A request refused before any solving: its HTTP status and the reason, for the page."""

    def __init__(self, status: int, message: str) -> None:
        super().__init__(message)
        self.status = status
        self.message = message


class Superseded(Exception):
    """An edit a newer one of the same page has replaced while it waited for a slot."""


async def read_body(request: Request, model: type[BaseModel]) -> Any:
    """The request's JSON body validated by ``model``; raises :class:`Rejected` with a plain message otherwise.

    The body is read in chunks up to :data:`MAX_BODY` bytes, parsed by :func:`json.loads` (no evaluation)
    and checked by pydantic in strict mode (no strings for numbers, no extra keys).
    """
    kind = request.headers.get("content-type", "").split(";")[0].strip().lower()
    if kind != "application/json":
        raise Rejected(415, f"send the body as application/json, not {kind[:100] or 'nothing'!r}")
    length = request.headers.get("content-length")
    if length is not None and not digits(length):
        raise Rejected(400, "the Content-Length header is not a number")
    if length is not None and int(length) > MAX_BODY:
        raise Rejected(413, f"the body is limited to {MAX_BODY} bytes")
    raw = bytearray()
    async for chunk in request.stream():
        raw += chunk
        if len(raw) > MAX_BODY:
            raise Rejected(413, f"the body is limited to {MAX_BODY} bytes")
    try:
        data = json.loads(bytes(raw).decode("utf-8"))
    except (UnicodeDecodeError, ValueError, RecursionError) as exc:
        raise Rejected(400, f"the body is not valid JSON: {str(exc)[:200]}") from None
    if not isinstance(data, dict):
        raise Rejected(422, "the body must be a JSON object")
    try:
        return model.model_validate(data)
    except ValidationError as exc:
        raise Rejected(422, _validation_message(exc)) from None


class Hold:
    """One of a set of slots, held by a request and by the work it hands to a worker thread (:func:`answer`):
    freed when the last of them lets go, so that work whose client has gone still counts until it ends."""

    def __init__(self, slots: BoundedSemaphore) -> None:
        self.slots, self.holders = slots, 1

    def take(self) -> None:
        self.holders += 1

    def let_go(self) -> None:
        self.holders -= 1
        if self.holders == 0:
            self.slots.release()


@asynccontextmanager
async def holding(
    slots: BoundedSemaphore, wait_s: float, request: Request, superseded: Callable[[], bool] = bool
) -> AsyncIterator[Hold]:
    """Hold one of ``slots`` while the block runs (and while the work it hands to :func:`answer` runs), waiting
    for it without holding a thread.

    The work of a client that has gone (its connection closed while it waited) is not started.

    Raises
    ------
    Superseded
        Where ``superseded()`` turns true while waiting.
    ClientDisconnect
        Where the client has gone before a slot was had.
    BusyError
        Where none frees within ``wait_s`` seconds.
    """
    deadline = time.monotonic() + wait_s
    delay = 0.002
    while True:
        if superseded():
            raise Superseded
        if await request.is_disconnected():
            raise ClientDisconnect
        if slots.acquire(blocking=False):
            break
        if time.monotonic() >= deadline:
            raise BusyError("the server is busy solving other edits; try again")
        await asyncio.sleep(delay)
        delay = min(2 * delay, 0.02)
    hold = Hold(slots)
    try:
        yield hold
    finally:
        hold.let_go()


#: Seconds between two looks at whether the client of a request whose work runs in a worker thread is still there.
LOOK_S = 0.05
#: The work handed to worker threads and not ended (kept referenced while no request waits for it).
_RUNNING: set[asyncio.Future[Any]] = set()


async def answer(request: Request, work: Callable[..., Any], *args: Any, hold: Hold | None = None) -> Any:
    """``work(*args)`` run in a worker thread, while the request waits for it and looks every :data:`LOOK_S`
    seconds at whether its client is still there.

    A thread's work cannot be stopped: where the client goes first, the request ends at once and the work runs
    on to its end unread, holding ``hold`` (its slot) until then.  So neither the request nor the server's
    shutdown waits for the work of a client that has gone.

    Raises
    ------
    ClientDisconnect
        Where the client goes before the work ends.
    """
    job = asyncio.ensure_future(run_in_threadpool(work, *args))
    _RUNNING.add(job)
    job.add_done_callback(_ended)
    if hold is not None:
        hold.take()
        job.add_done_callback(lambda _: hold.let_go())
    while not job.done():
        await asyncio.wait({job}, timeout=LOOK_S)
        if not job.done() and await request.is_disconnected():
            raise ClientDisconnect
    return job.result()


def _ended(job: asyncio.Future[Any]) -> None:
    _RUNNING.discard(job)
    if not job.cancelled():
        job.exception()  # read: the failure of work nobody waits for any more is not reported as unread


class Guard:
    """Answers only requests for the loopback host, and puts the security headers on every answer."""

    def __init__(self, app: ASGIApp) -> None:
        self.app = app

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        hosts = [value.decode("latin-1") for key, value in scope["headers"] if key.lower() == b"host"]
        if len(hosts) != 1 or not HOST.fullmatch(hosts[0]):
            shown = hosts[0][:100] if hosts else ""
            message = f"this server answers only to the loopback host (127.0.0.1), not {shown!r}"
            await _error(400, message)(scope, receive, send)
            return

        async def secured(message: Message) -> None:
            if message["type"] == "http.response.start":
                headers = MutableHeaders(scope=message)
                for key, value in SECURITY_HEADERS.items():
                    headers.setdefault(key, value)
            await send(message)

        await self.app(scope, receive, secured)


def _error(status: int, message: str, **extra: Any) -> JSONResponse:
    return JSONResponse({"error": message, **extra}, status_code=status, headers=SECURITY_HEADERS)


def create_app(spec_or_mech: Spec | Mechanism | str | Path, steps: int = 360, lang: str = "en") -> Any:
    """The viewer's FastAPI application for a spec, a compiled mechanism, or a file or example name.

    With a :class:`~linkwork.spec.schema.Spec` (or a name) the page can edit
    dimensions and masses; with a compiled :class:`~linkwork.structure.model.Mechanism`
    it edits the description it was compiled from, and shows one without a description.
    The cycle of the mechanism as given is solved here, so a mechanism that fails
    raises its LinkworkError before any server starts.

    Parameters
    ----------
    spec_or_mech : Spec, Mechanism, str or Path
        The mechanism: a description, a compiled mechanism, a file's path or an example's name.
    steps : int
        Crank angles of the cycle the page plays; default 360.
    lang : str
        The language of the page (``en`` or ``ru``, :data:`linkwork.lang.LANGUAGES`).

    Returns
    -------
    fastapi.FastAPI
        The application, to pass to :func:`serve` (``pip install "linkwork[web]"``).

    Raises
    ------
    LinkworkError
        The mechanism does not compile or assemble over its cycle, or ``lang`` is not a language of the texts.

    Examples
    --------
    >>> from linkwork.web import create_app, serve
    >>> serve(create_app("four-bar"), port=0, ready=print)  # doctest: +SKIP
    http://127.0.0.1:...
    """
    jit.prefer()  # many solves to come: the compiled kernels as soon as they are ready (loaded in the background)
    viewer = Viewer(spec_or_mech, steps, lang=lang)
    viewer.cycle(first=True)  # fails here, not on the first request

    app = FastAPI(title="linkwork viewer", docs_url=None, redoc_url=None, openapi_url=None)
    app.state.viewer = viewer
    app.add_middleware(Guard)
    _handlers(app)
    _pages(app, viewer.lang)
    _api(app, viewer)
    return app


def _handlers(app: FastAPI) -> None:
    """Every failure answers JSON with a message; a client that went away is let go without a trace."""

    @app.exception_handler(Rejected)
    async def rejected(request: Request, exc: Rejected) -> JSONResponse:
        return _error(exc.status, exc.message)

    @app.exception_handler(OutOfRange)
    async def out_of_range(request: Request, exc: OutOfRange) -> JSONResponse:
        return _error(422, str(exc), events=exc.events)

    @app.exception_handler(LinkworkError)
    async def failed(request: Request, exc: LinkworkError) -> JSONResponse:
        return _error(422, str(exc))

    @app.exception_handler(BusyError)
    async def busy(request: Request, exc: BusyError) -> JSONResponse:
        return _error(503, str(exc))

    @app.exception_handler(Superseded)
    async def superseded(request: Request, exc: Superseded) -> JSONResponse:
        return _error(409, "superseded by a newer edit of the same page")

    @app.exception_handler(ClientDisconnect)
    async def gone(request: Request, exc: ClientDisconnect) -> Response:
        return Response(status_code=400)  # nobody reads it

    @app.exception_handler(RequestValidationError)
    async def invalid(request: Request, exc: RequestValidationError) -> JSONResponse:
        return _error(422, "; ".join(str(e.get("msg", e)) for e in exc.errors())[:500])

    @app.exception_handler(StarletteHTTPException)
    async def http_error(request: Request, exc: StarletteHTTPException) -> JSONResponse:
        return _error(exc.status_code, str(exc.detail))

    @app.exception_handler(Exception)
    async def crashed(request: Request, exc: Exception) -> JSONResponse:
        return _error(500, f"internal error: {type(exc).__name__}: {str(exc)[:300]}")


def _pages(app: FastAPI, lang: str = "en") -> None:
    @app.get("/", response_class=HTMLResponse)
    def index() -> HTMLResponse:
        return HTMLResponse(page_html(lang))

    @app.get("/static/{name}")
    def static(name: str) -> Response:
        if name not in STATIC:
            return _error(404, "no such file")
        return Response(static_text(name), media_type=STATIC[name] + "; charset=utf-8")


def _api(app: FastAPI, viewer: Viewer) -> None:
    @app.get("/api/cycle")
    async def cycle(request: Request, labels: Literal["cycle", "first"] = "cycle") -> Response:
        async with holding(viewer.full_slots, viewer.wait_s, request) as hold:
            return _json(await answer(request, viewer.cycle, None, None, labels == "first", hold=hold))

    @app.get("/api/parameters")
    def parameters() -> Response:
        return _json({"editable": viewer.spec is not None, "parameters": viewer.parameters()})

    @app.get("/api/family")
    def family() -> Response:
        """The family the file's requirements leave (a synthesised slider-crank), as edits; none otherwise."""
        return _json(viewer.family())

    @app.post("/api/solve")
    async def solve(request: Request) -> Response:
        req = await read_body(request, SolveRequest)
        async with holding(viewer.full_slots, viewer.wait_s, request) as hold:
            return _json(await answer(request, viewer.cycle, req.overrides, req.steps, hold=hold))

    @app.post("/api/edit")
    async def edit(request: Request) -> Response:
        req = await read_body(request, EditRequest)
        viewer.newest(req.client, req.seq)
        found = viewer.cached_edit(req.overrides, req.steps, req.whole_turn)
        if found is None:
            newer = lambda: viewer.superseded(req.client, req.seq)  # noqa: E731
            async with holding(viewer.edit_slots, viewer.wait_s, request, newer) as hold:
                # in a worker thread, never on the event loop: a pose (or any request) is read and answered while
                # edits are solved, sharing the interpreter with at most the edits' slots
                found = await answer(request, viewer.edit, req.overrides, req.steps, req.whole_turn, hold=hold)
        return Response(found, media_type=EDIT_MEDIA)

    @app.post("/api/pose")
    async def pose(request: Request) -> Response:
        req = await read_body(request, PoseRequest)
        return _json(await answer(request, viewer.pose, req.angle_deg, req.overrides))

    @app.post("/api/force-plans")
    async def force_plans(request: Request) -> Response:
        req = await read_body(request, ForcePlansRequest)
        return _json(await answer(request, viewer.force_plans, req.overrides, req.steps, req.index))

    @app.post("/api/save")
    async def save(request: Request) -> Response:
        req = await read_body(request, SaveRequest)
        text = await answer(request, viewer.file_text, req.overrides)
        headers = {"Content-Disposition": attachment(viewer.saved_name())}
        return Response(text, media_type="application/yaml; charset=utf-8", headers=headers)


def attachment(name: str) -> str:
    """The ``Content-Disposition`` of a file offered under ``name`` (any script): its UTF-8 name in
    ``filename*`` (RFC 6266, which browsers read), an ASCII stand-in in ``filename`` for the rest."""
    from urllib.parse import quote as percent

    plain = "".join(c if c.isascii() and c.isprintable() and c not in '"\\' else "_" for c in name)
    return f"attachment; filename=\"{plain}\"; filename*=UTF-8''{percent(name, safe='')}"


def _json(data: Any) -> Response:
    return Response(dumps(data), media_type="application/json")


def _validation_message(exc: Any) -> str:
    """One line per problem of a request body: where and what was expected."""
    lines = []
    for err in exc.errors(include_url=False)[:10]:
        where = ".".join(str(x) for x in err.get("loc", ())) or "body"
        lines.append(f"{where}: {err.get('msg', 'invalid')}")
    return "\n".join(lines)


#: Seconds the viewer's shutdown (Ctrl+C, SIGTERM) waits for the answers in progress before it ends: work whose
#: client has gone is not waited for longer than this.
SHUTDOWN_WAIT_S = 5

#: Seconds a client has to send the head of a request (its line and headers) once connected, or once the
#: previous answer on its connection is sent; a connection that does not is closed (a slow client holding
#: connections open, byte by byte, cannot hold the server's file descriptors).
HEAD_TIMEOUT_S = 10.0


def server_config(app: Any, head_timeout: float = HEAD_TIMEOUT_S) -> Any:
    """The uvicorn configuration the viewer is served with: on a warning level, no access log, and
    connections whose request's head does not arrive within ``head_timeout`` seconds closed."""
    import uvicorn
    from uvicorn.protocols.http.auto import AutoHTTPProtocol

    http = _head_timed(AutoHTTPProtocol, head_timeout)
    return uvicorn.Config(
        app, log_level="warning", access_log=False, lifespan="off", http=http, timeout_graceful_shutdown=SHUTDOWN_WAIT_S
    )


def _head_timed(base: type, head_timeout: float) -> type:
    """uvicorn's HTTP protocol ``base`` (h11's or httptools') closing a connection that has no request in
    progress ``head_timeout`` seconds after it was made or after its last answer: uvicorn itself closes an
    idle connection after its keep-alive time only once it has answered, and never one whose request's head
    stops half way."""

    class HeadTimed(base):
        head_timer: asyncio.TimerHandle | None = None

        def connection_made(self, transport: Any) -> None:
            super().connection_made(transport)
            self._wait_for_head()

        def on_response_complete(self) -> None:
            super().on_response_complete()
            if not self.transport.is_closing():
                self._wait_for_head()

        def connection_lost(self, exc: Exception | None) -> None:
            if self.head_timer is not None:
                self.head_timer.cancel()
            super().connection_lost(exc)

        def _wait_for_head(self) -> None:
            if self.head_timer is not None:
                self.head_timer.cancel()
            self.head_timer = self.loop.call_later(head_timeout, self._head_late, self.cycle)

        def _head_late(self, cycle: Any) -> None:
            self.head_timer = None
            waiting = self.cycle is cycle and (cycle is None or cycle.response_complete)
            if waiting and not self.transport.is_closing():
                self.transport.close()

    return HeadTimed


def serve(app: Any, port: int = 8765, ready: Callable[[str], None] | None = None) -> None:
    """Serve ``app`` on 127.0.0.1 (``port`` 0: a free port) until interrupted.

    ``ready(url)`` is called (from another thread) once the server listens.  Ctrl+C (SIGINT) or SIGTERM stops
    the server: the answers in progress get :data:`SHUTDOWN_WAIT_S` seconds, and then the signal ends the
    process (:func:`ended_by_signal`), whatever work is still running in its threads.

    Parameters
    ----------
    app : fastapi.FastAPI
        The viewer's application, from :func:`create_app`.
    port : int
        The port on 127.0.0.1; 0 takes a free one; default 8765.
    ready : callable, optional
        ``ready(url)``, called with the page's address once the server listens.

    Raises
    ------
    LinkworkError
        When the port cannot be had (in use, or privileged).

    Examples
    --------
    >>> from linkwork.web import create_app, serve
    >>> serve(create_app("four-bar"), port=0, ready=print)  # doctest: +SKIP
    http://127.0.0.1:...
    """
    import socket

    import uvicorn

    # IPPROTO_TCP named: asyncio then turns Nagle's algorithm off on the connections (it does so only for sockets
    # whose protocol says TCP), so that a small answer is not held back for the client's delayed ACK (40 ms)
    sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM, socket.IPPROTO_TCP)
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    try:
        sock.bind(("127.0.0.1", port))
    except OSError as exc:
        sock.close()
        raise LinkworkError(f"cannot listen on 127.0.0.1:{port}: {exc.strerror or exc}; try --port 0") from None
    url = f"http://127.0.0.1:{sock.getsockname()[1]}/"
    server = uvicorn.Server(server_config(app))

    def announce() -> None:
        while not server.started and not server.should_exit:
            time.sleep(0.02)
        if server.started and ready is not None:
            ready(url)

    watcher = threading.Thread(target=announce, daemon=True)
    watcher.start()
    try:
        with ended_by_signal():
            server.run(sockets=[sock])
    finally:
        server.should_exit = True
        sock.close()


@contextmanager
def ended_by_signal() -> Iterator[None]:
    """While the block runs, SIGINT (Ctrl+C) and SIGTERM take their default action, which ends the process:
    uvicorn catches either while it serves and raises it again once its shutdown is over.

    Work that a request left in a worker thread cannot be cancelled (a solve, or numba compiling the kernels
    for a new kind of batch: a minute).  Where Ctrl+C raised :class:`KeyboardInterrupt` instead, asyncio's
    runner waited for every request the shutdown had cancelled to get its thread's result, and the
    interpreter's exit joined every worker thread: the viewer ran on, for minutes, the work of clients long
    gone.  Outside the main thread, where no signal is handled, nothing changes.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = {sig: signal.signal(sig, signal.SIG_DFL) for sig in (signal.SIGINT, signal.SIGTERM)}
    try:
        yield
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)
