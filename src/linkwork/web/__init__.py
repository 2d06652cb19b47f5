"""The interactive browser viewer: a local server and a page in plain JavaScript and SVG.

:func:`create_app` builds the FastAPI application (``linkwork view``),
:func:`cycle_payload` the precomputed cycle both the server and the
exported page use, :func:`export_page` one self-contained HTML file.
FastAPI and uvicorn are imported only by the server (extra ``web``).
"""

from __future__ import annotations

from typing import Any

__all__ = ["create_app", "cycle_payload", "export_page", "serve"]


def __getattr__(name: str) -> Any:
    import importlib

    where = {
        "create_app": "linkwork.web.server",
        "serve": "linkwork.web.server",
        "cycle_payload": "linkwork.web.payload",
        "export_page": "linkwork.web.export",
    }
    if name in where:
        if where[name].endswith("server"):
            from linkwork.optional import require

            require("fastapi", "uvicorn", purpose="the viewer's server (linkwork view)")
        return getattr(importlib.import_module(where[name]), name)
    raise AttributeError(f"module 'linkwork.web' has no attribute {name!r}")
