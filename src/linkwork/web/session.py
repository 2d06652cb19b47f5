"""The mechanism a viewer shows and the cycles of its edits, shared by the server and the exported page."""

from __future__ import annotations

import threading
from collections import OrderedDict
from collections.abc import Iterator
from contextlib import contextmanager
from importlib import resources
from typing import Any

from linkwork.errors import BusyError


def static_text(name: str) -> str:
    """One of the page's files: ``index.html``, ``viewer.js`` or ``viewer.css``."""
    return (resources.files("linkwork.web") / "static" / name).read_text(encoding="utf-8")


class Viewer:
    """The mechanism a server shows, and the cycles of its edits (a small cache)."""

    def __init__(self, spec_or_mech: Any, steps: int = 360, cache: int = 16) -> None:
        from linkwork.api import mechanism_of

        self.mech = mechanism_of(spec_or_mech, "viewer")
        self.spec = self.mech.spec
        self.steps = steps
        self._cache: OrderedDict[tuple[Any, ...], dict[str, Any]] = OrderedDict()
        self._size = cache
        self._lock = threading.Lock()
        self._busy = threading.BoundedSemaphore(2)
        #: Seconds a request waits for one of the two solving slots before it is answered busy.
        self.wait_s = 30.0

    @contextmanager
    def solving(self) -> Iterator[None]:
        """Hold one of the two slots every solve (a cycle, a pose) shares; :class:`BusyError` if none frees."""
        if not self._busy.acquire(timeout=self.wait_s):
            raise BusyError("the server is busy solving other edits; try again")
        try:
            yield
        finally:
            self._busy.release()

    def parameters(self, mech: Any = None) -> list[dict[str, Any]]:
        """The editable values of ``mech`` (by default the mechanism as loaded)."""
        from linkwork.web.edits import editable

        return [p.as_dict() for p in editable(mech if mech is not None else self.mech)]

    def edit(self, overrides: dict[str, float]) -> tuple[Any, Any]:
        """The description and the mechanism with ``overrides`` (SI) applied; a LinkworkError when it fails."""
        from linkwork.api import compile
        from linkwork.web.edits import apply

        if not overrides:
            return self.spec, self.mech
        spec = apply(self.mech, overrides)
        return spec, compile(spec)

    def compile(self, overrides: dict[str, float]) -> Any:
        """The mechanism with ``overrides`` (SI) applied; raises a LinkworkError when it fails."""
        return self.edit(overrides)[1]

    def cycle(self, overrides: dict[str, float] | None = None, steps: int | None = None) -> dict[str, Any]:
        """The cycle payload of the mechanism with ``overrides``, with ``parameters`` and ``editable``."""
        from linkwork.web.payload import cycle_payload

        overrides = overrides or {}
        steps = steps or self.steps
        key = (steps, *sorted(overrides.items()))
        with self._lock:
            if key in self._cache:
                self._cache.move_to_end(key)
                return self._cache[key]
        with self.solving():
            spec, mech = self.edit(overrides)
            out = cycle_payload(mech, steps)
        out["editable"] = self.spec is not None
        out["overrides"] = dict(overrides)
        out["parameters"] = self.parameters(mech)
        with self._lock:
            self._cache[key] = out
            while len(self._cache) > self._size:
                self._cache.popitem(last=False)
        return out
