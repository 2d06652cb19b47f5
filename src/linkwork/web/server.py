"""The viewer's local server: the page, its static files and a small JSON API.

Endpoints (all JSON except the page and its files):

* ``GET /`` the page; ``GET /static/viewer.js``, ``/static/viewer.css``;
* ``GET /api/cycle``: the cycle of the mechanism as it was loaded
  (:func:`linkwork.web.payload.cycle_payload`, with ``parameters``);
* ``GET /api/parameters``: the editable dimensions and masses;
* ``POST /api/solve`` ``{"overrides": {name: value}, "steps": n}``: the
  cycle of the edited mechanism (values in SI);
* ``POST /api/pose`` ``{"angle_deg": a, "overrides": {...}}``: every
  point at one crank angle, solved on its own.

Bodies are JSON objects of at most :data:`MAX_BODY` bytes, validated by
pydantic (types, ranges, at most :data:`~linkwork.web.edits.MAX_OVERRIDES`
overrides); an edit that fails answers 422 with linkwork's message (the
file's line, the group and crank angle that do not assemble), a malformed
request 400, 413 or 415, and the server goes on serving.  Requests must
name the loopback host (``127.0.0.1``, ``localhost``, ``[::1]``, with a port): a page elsewhere
cannot reach the server through a rebound DNS name.  Nothing from a
request is evaluated.
"""

from __future__ import annotations

import json
import re
import time
from collections.abc import Callable
from typing import Annotated, Any

from fastapi import FastAPI, Request
from fastapi.exceptions import RequestValidationError
from fastapi.responses import HTMLResponse, JSONResponse, Response
from pydantic import BaseModel, ConfigDict, Field, StringConstraints, ValidationError
from starlette.concurrency import run_in_threadpool
from starlette.exceptions import HTTPException as StarletteHTTPException

from linkwork.errors import BusyError, LinkworkError
from linkwork.web.edits import MAX_OVERRIDES
from linkwork.web.session import Viewer, static_text

#: Largest request body, bytes.
MAX_BODY = 64 * 1024
#: Steps of the cycle an edit may ask for (1440: a quarter of a degree; the cache keeps 16 cycles).
MIN_STEPS, MAX_STEPS = 12, 1440
#: The Host headers the server answers to: a loopback name and an optional port, nothing else.
HOST = re.compile(r"(\[::1\]|127\.0\.0\.1|localhost)(:\d{1,5})?", re.IGNORECASE)

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


class SolveRequest(BaseModel):
    """``POST /api/solve``: overrides of named dimensions and masses (SI), and the steps of the cycle."""

    model_config = ConfigDict(extra="forbid", strict=True)

    overrides: Overrides = Field(default_factory=dict)
    steps: int | None = Field(None, ge=MIN_STEPS, le=MAX_STEPS)


class PoseRequest(BaseModel):
    """``POST /api/pose``: one crank angle (deg) of the mechanism with overrides."""

    model_config = ConfigDict(extra="forbid", strict=True)

    angle_deg: Value = Field(ge=-1e6, le=1e6)
    overrides: Overrides = Field(default_factory=dict)


class Rejected(Exception):
    """A request refused before any solving: its HTTP status and the reason, for the page."""

    def __init__(self, status: int, message: str) -> None:
        super().__init__(message)
        self.status = status
        self.message = message


async def read_body(request: Request, model: type[BaseModel]) -> Any:
    """The request's JSON body validated by ``model``; raises :class:`Rejected` with a plain message otherwise.

    The body is read in chunks up to :data:`MAX_BODY` bytes, parsed by :func:`json.loads` (no evaluation)
    and checked by pydantic in strict mode (no strings for numbers, no extra keys).
    """
    kind = request.headers.get("content-type", "").split(";")[0].strip().lower()
    if kind != "application/json":
        raise Rejected(415, f"send the body as application/json, not {kind[:100] or 'nothing'!r}")
    length = request.headers.get("content-length")
    if length is not None and not length.isdigit():
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


def create_app(spec_or_mech: Any, steps: int = 360) -> Any:
    """The viewer's FastAPI application for a spec, a compiled mechanism, or a file or example name.

    With a :class:`~linkwork.spec.schema.Spec` (or a name) the page can edit
    dimensions and masses; with a compiled :class:`~linkwork.structure.model.Mechanism`
    it only shows it.  The cycle of the mechanism as given is solved here, so
    a mechanism that fails raises its LinkworkError before any server starts.
    """
    viewer = Viewer(spec_or_mech, steps)
    viewer.cycle()  # fails here, not on the first request

    app = FastAPI(title="linkwork viewer", docs_url=None, redoc_url=None, openapi_url=None)
    app.state.viewer = viewer

    def error(status: int, message: str) -> JSONResponse:
        return JSONResponse({"error": message}, status_code=status, headers=SECURITY_HEADERS)

    @app.middleware("http")
    async def guard(request: Request, call_next: Any) -> Any:
        host = request.headers.get("host") or ""
        if not HOST.fullmatch(host):
            return error(400, f"this server answers only to the loopback host (127.0.0.1), not {host[:100]!r}")
        response = await call_next(request)
        for key, value in SECURITY_HEADERS.items():
            response.headers.setdefault(key, value)
        return response

    @app.exception_handler(Rejected)
    async def rejected(request: Request, exc: Rejected) -> JSONResponse:
        return error(exc.status, exc.message)

    @app.exception_handler(LinkworkError)
    async def failed(request: Request, exc: LinkworkError) -> JSONResponse:
        return error(422, str(exc))

    @app.exception_handler(BusyError)
    async def busy(request: Request, exc: BusyError) -> JSONResponse:
        return error(503, str(exc))

    @app.exception_handler(RequestValidationError)
    async def invalid(request: Request, exc: RequestValidationError) -> JSONResponse:
        return error(422, "; ".join(str(e.get("msg", e)) for e in exc.errors())[:500])

    @app.exception_handler(StarletteHTTPException)
    async def http_error(request: Request, exc: StarletteHTTPException) -> JSONResponse:
        return error(exc.status_code, str(exc.detail))

    @app.exception_handler(Exception)
    async def crashed(request: Request, exc: Exception) -> JSONResponse:
        return error(500, f"internal error: {type(exc).__name__}: {str(exc)[:300]}")

    @app.get("/", response_class=HTMLResponse)
    def index() -> HTMLResponse:
        return HTMLResponse(static_text("index.html"))

    @app.get("/static/{name}")
    def static(name: str) -> Response:
        kinds = {"viewer.js": "text/javascript", "viewer.css": "text/css"}
        if name not in kinds:
            return error(404, "no such file")
        return Response(static_text(name), media_type=kinds[name] + "; charset=utf-8")

    @app.get("/api/cycle")
    async def cycle() -> Response:
        return _json(await run_in_threadpool(viewer.cycle))

    @app.get("/api/parameters")
    def parameters() -> Response:
        return _json({"editable": viewer.spec is not None, "parameters": viewer.parameters()})

    @app.post("/api/solve")
    async def solve(request: Request) -> Response:
        req = await read_body(request, SolveRequest)
        return _json(await run_in_threadpool(viewer.cycle, req.overrides, req.steps))

    @app.post("/api/pose")
    async def pose(request: Request) -> Response:
        from linkwork.web.payload import pose_payload

        req = await read_body(request, PoseRequest)

        def solve_pose() -> dict[str, Any]:
            with viewer.solving():
                return pose_payload(viewer.compile(req.overrides), req.angle_deg)

        return _json(await run_in_threadpool(solve_pose))

    return app


def _json(data: Any) -> Response:
    return Response(json.dumps(data, allow_nan=False, separators=(",", ":")), media_type="application/json")


def _validation_message(exc: Any) -> str:
    """One line per problem of a request body: where and what was expected."""
    lines = []
    for err in exc.errors(include_url=False)[:10]:
        where = ".".join(str(x) for x in err.get("loc", ())) or "body"
        lines.append(f"{where}: {err.get('msg', 'invalid')}")
    return "\n".join(lines)


def serve(app: Any, port: int = 8765, ready: Callable[[str], None] | None = None) -> None:
    """Serve ``app`` on 127.0.0.1 (``port`` 0: a free port) until interrupted.

    ``ready(url)`` is called (from another thread) once the server listens.

    Raises
    ------
    LinkworkError
        When the port cannot be had (in use, or privileged).
    """
    import socket
    import threading

    import uvicorn

    sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    try:
        sock.bind(("127.0.0.1", port))
    except OSError as exc:
        sock.close()
        raise LinkworkError(f"cannot listen on 127.0.0.1:{port}: {exc.strerror or exc}; try --port 0") from None
    url = f"http://127.0.0.1:{sock.getsockname()[1]}/"
    server = uvicorn.Server(uvicorn.Config(app, log_level="warning", access_log=False, lifespan="off"))

    def announce() -> None:
        while not server.started and not server.should_exit:
            time.sleep(0.02)
        if server.started and ready is not None:
            ready(url)

    watcher = threading.Thread(target=announce, daemon=True)
    watcher.start()
    try:
        server.run(sockets=[sock])
    finally:
        server.should_exit = True
        sock.close()
