"""The mechanism a viewer shows, its edits and what they are solved in; shared by the server and the exported page.

An edit is solved as a variant of the compiled mechanism (:mod:`linkwork.web.cycle`).  Two kinds of
answer: the whole cycle with its labels placed (:func:`linkwork.web.payload.full_payload`, 0.04 s for
the double-cut shears with its labels placed at the first sample, the page's first answer, and 0.12 s at
the :data:`~linkwork.web.payload.LIVE_PLACED` samples that follow it), and an edit's compact
answer (:func:`linkwork.web.update.edit_payload`, 3 to 4 milliseconds), which the page shows while a
value is dragged.  Each kind has its own solving slots (:attr:`Viewer.full_slots`,
:attr:`Viewer.edit_slots`), so that placing labels never holds up an edit; a crank step (a pose)
takes no slot.  Answers are kept in small caches (an undo returns at once).
"""

from __future__ import annotations

import json
import math
import re
import threading
import unicodedata
from collections import OrderedDict
from collections.abc import Callable
from importlib import resources
from typing import TYPE_CHECKING, Any

import numpy as np

from linkwork.api import mechanism_of
from linkwork.errors import ParameterError
from linkwork.lang import check_lang
from linkwork.scene.scheme import CYCLE
from linkwork.spec.reader import described
from linkwork.structure.model import Mechanism
from linkwork.structure.parameters import file_text
from linkwork.web.cycle import DRAGGED, Cycle, check_assembly, solve_cycle
from linkwork.web.edits import editable, validated, variant_parameters
from linkwork.web.force_plans import drawn_of, force_plans_part
from linkwork.web.payload import LIVE_PLACED, full_payload, pose_payload
from linkwork.web.update import edit_payload, encode_edit

if TYPE_CHECKING:
    from pathlib import Path

    from linkwork.spec.schema import Spec

#: The page's scripts, in the order it loads them.
SCRIPTS = ("viewer.js", "forces.js", "forceplans.js", "editing.js")

#: Edits' answers kept (encoded), and clients whose newest edit is remembered.
EDIT_CACHE, CLIENTS = 64, 256


def static_text(name: str) -> str:
    """One of the page's files: ``index.html``, ``viewer.css`` or one of :data:`SCRIPTS`."""
    return (resources.files("linkwork.web") / "static" / name).read_text(encoding="utf-8")


def page_html(lang: str = "en") -> str:
    """The page (``index.html``) with its texts in ``lang``: an element's ``data-t="KEY"`` gives its text, a
    ``data-t-ATTR="KEY"`` its attribute ``ATTR``, from the catalogues (:func:`linkwork.lang.t`)."""
    from html import escape

    from linkwork.lang import t

    def attributes(m: re.Match[str]) -> str:
        tag = m.group(0)
        for attr, key in re.findall(r'\sdata-t-([a-z-]+)="([^"]+)"', tag):
            start = tag.index(f' {attr}="') + len(attr) + 3
            tag = tag[:start] + escape(t(key, lang), quote=True) + tag[tag.index('"', start) :]
        return tag

    page = re.sub(r"<[^>]*\sdata-t-[^>]*>", attributes, static_text("index.html"))
    page = re.sub(
        r'(<[^>]*\sdata-t="([^"]+)"[^>]*>)[^<]*', lambda m: m.group(1) + escape(t(m.group(2), lang), False), page
    )
    return page.replace('<html lang="en">', f'<html lang="{lang}">', 1)


def dumps(data: Any) -> bytes:
    """Strict JSON (no NaN or infinities), compact."""
    return json.dumps(data, allow_nan=False, separators=(",", ":")).encode("utf-8")


class _Cache:
    """A small least-recently-used cache, safe across threads."""

    def __init__(self, size: int) -> None:
        self._items: OrderedDict[Any, Any] = OrderedDict()
        self._size = size
        self._lock = threading.Lock()
        self._pending: dict[Any, Any] = {}  # the computations under way (:meth:`once`), by key

    def get(self, key: Any) -> Any:
        with self._lock:
            if key in self._items:
                self._items.move_to_end(key)
            return self._items.get(key)

    def put(self, key: Any, value: Any) -> None:
        with self._lock:
            self._items[key] = value
            self._items.move_to_end(key)
            while len(self._items) > self._size:
                self._items.popitem(last=False)

    def once(self, key: Any, compute: Callable[[], Any]) -> Any:
        """The value of ``key``, computed by ``compute()`` where it is not kept: the first call computes it and
        calls for the same key meanwhile wait for that one computation (a failure is theirs too, and not kept)."""
        from concurrent.futures import Future

        with self._lock:
            if key in self._items:
                self._items.move_to_end(key)
                return self._items[key]
            pending = self._pending.get(key)
            if pending is None:
                pending = self._pending[key] = Future()
                mine = True
            else:
                mine = False
        if not mine:
            return pending.result()
        try:
            value = compute()
        except BaseException as exc:
            pending.set_exception(exc)
            raise
        else:
            self.put(key, value)
            pending.set_result(value)
            return value
        finally:
            with self._lock:
                self._pending.pop(key, None)


class Viewer:
    """The mechanism a server shows, its edits' answers, and the slots they are solved in.

    Attributes
    ----------
    mech : Mechanism
    steps : int
        Crank angles of the cycle.
    full_slots, edit_slots : threading.BoundedSemaphore
        One whole cycle at a time; two edits at a time.
    wait_s : float
        Seconds a request may wait for a slot before it is answered busy.
    placed : int or None
        Samples the labels of a whole cycle are placed at (:func:`linkwork.web.payload.full_payload`): about
        :data:`~linkwork.web.payload.LIVE_PLACED` for the live page, every one (None) for an exported page.
    lang : str
        The language of the page's texts and drawings (:data:`linkwork.lang.LANGUAGES`).

    Raises
    ------
    LinkworkError
        For a language there is no catalogue of (:func:`linkwork.lang.check_lang`).
    """

    def __init__(
        self,
        spec_or_mech: Spec | Mechanism | str | Path,
        steps: int = 360,
        cache: int = 16,
        placed: int | None = LIVE_PLACED,
        lang: str = "en",
    ) -> None:
        check_lang(lang)
        self.lang = lang
        self.mech: Mechanism = mechanism_of(spec_or_mech, "viewer")
        self.spec = described(self.mech.description)
        self._editable = editable(self.mech)
        self.steps = steps
        self.placed = placed
        self._full = _Cache(cache)
        self._edits = _Cache(EDIT_CACHE)
        self._whole = _Cache(8)
        self._drawn = _Cache(4)  # the force plans of a variant, and their drawings at a sample
        self._drawings = _Cache(EDIT_CACHE)
        self._family = _Cache(1)
        self.full_slots = threading.BoundedSemaphore(1)
        self.edit_slots = threading.BoundedSemaphore(2)
        self.wait_s = 30.0
        self._newest: OrderedDict[str, int] = OrderedDict()
        self._lock = threading.Lock()

    def parameters(self) -> list[dict[str, Any]]:
        """The editable values of the mechanism as loaded."""
        return [p.as_dict() for p in self._editable]

    def family(self) -> dict[str, Any]:
        """The family the file's requirements leave (:func:`~linkwork.synthesis.achieved.family_members`), as
        edits; none otherwise.  Solved once (seconds for the shears): requests meanwhile wait for that answer."""
        from linkwork.synthesis.achieved import family_members

        return self._family.once("family", lambda: family_members(self.spec, self.lang) or {"overrides": []})

    def solve(self, overrides: dict[str, float] | None, steps: int | None = None, whole_turn: bool = False) -> Cycle:
        """The cycle of the variant ``overrides`` (SI).

        Raises
        ------
        ParameterError
            A bad name or value, or a mechanism without its description.
        OutOfRange
            A variant that does not assemble at the assembly pose, or (``whole_turn``) at a sample where the
            file's mechanism does.
        """
        steps = steps or self.steps
        checked = validated(self.mech, overrides) if overrides else {}
        cycle = solve_cycle(self.mech, steps, checked, DRAGGED if whole_turn else CYCLE)
        check_assembly(cycle, self.whole(steps) if whole_turn else None, self.lang)
        return cycle

    def whole(self, steps: int) -> np.ndarray:
        """Where the file's mechanism assembles at ``steps`` angles, ``(steps,)``."""
        found = self._whole.get(steps)
        if found is None:
            found = solve_cycle(self.mech, steps).valid
            self._whole.put(steps, found)
        return found

    def cycle(
        self, overrides: dict[str, float] | None = None, steps: int | None = None, first: bool = False
    ) -> dict[str, Any]:
        """The whole payload of the variant ``overrides``, with its ``parameters``, ``editable`` and
        ``overrides`` (kept: the caller must not change it).  ``first``: its labels placed at the first
        sample only (carried along the turn from there), to show a page at once."""
        steps = steps or self.steps
        key = (steps, first, *sorted((overrides or {}).items()))
        found = self._full.get(key)
        if found is not None:
            return found
        cycle = self.solve(overrides, steps)
        out = full_payload(cycle, 1 if first else self.placed, self.lang)
        out["force_plans"] = self.force_plans_at([], overrides, steps, cycle)  # which: the page asks for a sample's
        out["editable"] = self.spec is not None
        out["overrides"] = dict(cycle.overrides)
        masses = cycle.kin.mass_properties
        out["parameters"] = variant_parameters(cycle.mech, cycle.overrides, masses, self._editable, self.lang)
        self._full.put(key, out)
        return out

    def force_plans(self, overrides: dict[str, float] | None, steps: int | None, index: int) -> dict[str, Any]:
        """The force plans and the lever of the variant ``overrides`` at sample ``index`` of its cycle
        (:func:`linkwork.web.force_plans.force_plans_part`).

        Raises
        ------
        ParameterError
            A bad name or value, or ``index`` outside the cycle.
        """
        steps = steps or self.steps
        if not 0 <= index < steps:
            raise ParameterError(f"sample {index} is outside the cycle of {steps} samples")
        key = (steps, index, *sorted((overrides or {}).items()))
        found = self._drawings.get(key)
        if found is None:
            found = self.force_plans_at([index], overrides, steps)
            self._drawings.put(key, found)
        return found

    def force_plans_at(
        self,
        samples: Any,
        overrides: dict[str, float] | None = None,
        steps: int | None = None,
        cycle: Cycle | None = None,
    ) -> dict[str, Any]:
        """The force plans and the lever of the variant ``overrides`` (its ``cycle``, where the caller has solved
        it) at ``samples`` of its cycle (:func:`linkwork.web.force_plans.force_plans_part`)."""
        steps = steps or self.steps
        key = (steps, *sorted((overrides or {}).items()))
        found = self._drawn.get(key)
        if found is None:
            cycle = self.solve(overrides, steps) if cycle is None else cycle
            found = (cycle, drawn_of(cycle))
            self._drawn.put(key, found)
        return force_plans_part(found[0], samples, found[1], self.lang)

    def edit(self, overrides: dict[str, float], steps: int | None = None, whole_turn: bool = False) -> bytes:
        """The compact answer to the edit ``overrides`` (:func:`linkwork.web.update.edit_payload`), as it is
        sent (:func:`linkwork.web.update.encode_edit`)."""
        found = self.cached_edit(overrides, steps, whole_turn)
        if found is None:
            # a drag (whole_turn) is answered without the strokes and the plans' frames, the scheme's symbols of
            # DRAGGED angles, to answer in time
            cycle = self.solve(overrides, steps, whole_turn)
            found = encode_edit(edit_payload(cycle, self._editable, whole_turn, self.lang))
            self._edits.put(self._edit_key(overrides, steps, whole_turn), found)
        return found

    def cached_edit(self, overrides: dict[str, float], steps: int | None, whole_turn: bool) -> bytes | None:
        """The answer to an edit solved before, or None."""
        return self._edits.get(self._edit_key(overrides, steps, whole_turn))

    def _edit_key(self, overrides: dict[str, float], steps: int | None, whole_turn: bool) -> tuple[Any, ...]:
        return (steps or self.steps, whole_turn, *sorted(overrides.items()))

    def saved_name(self) -> str:
        """The name a saved file is offered under: the file's, ``-edited`` (letters of any script, their marks,
        digits and ``._-`` only; a run of anything else as ``-``)."""
        source = str(self.mech.source or self.mech.name or "mechanism")
        name = source.replace("\\", "/").rsplit("/", 1)[-1]
        stem = re.sub(
            r"-+", "-", "".join(c if c in "._-" or unicodedata.category(c)[0] in "LMN" else "-" for c in name)
        )
        stem = re.sub(r"\.ya?ml$", "", stem, flags=re.IGNORECASE).strip(".-") or "mechanism"
        return f"{stem[:80]}-edited.yaml"

    def pose(self, angle_deg: float, overrides: dict[str, float] | None = None) -> dict[str, Any]:
        """Every point at one crank angle (deg), of the variant ``overrides``; see :func:`pose_payload`."""
        checked = validated(self.mech, overrides) if overrides else {}
        return pose_payload(self.mech, angle_deg, checked)

    def file_text(self, overrides: dict[str, float]) -> str:
        """The file of the mechanism with ``overrides`` written in, its comments and layout kept."""
        return file_text(self.mech, validated(self.mech, overrides))

    def newest(self, client: str | None, seq: int | None) -> bool:
        """Note edit ``seq`` of ``client``; False where the client has sent a newer one (this one is superseded)."""
        if client is None or seq is None:
            return True
        with self._lock:
            known = self._newest.get(client, -math.inf)
            if seq >= known:
                self._newest[client] = seq
            self._newest.move_to_end(client)
            while len(self._newest) > CLIENTS:
                self._newest.popitem(last=False)
            return seq >= known

    def superseded(self, client: str | None, seq: int | None) -> bool:
        """Whether ``client`` has sent an edit newer than ``seq``."""
        if client is None or seq is None:
            return False
        with self._lock:
            return self._newest.get(client, -math.inf) > seq
