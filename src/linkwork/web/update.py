"""An edit's answer: only what an edit of dimensions or masses changes, its arrays in a compact form.

The page holds the payload of the mechanism as loaded (:func:`linkwork.web.payload.cycle_payload`);
an edit changes the positions, the plans, the series, the forces, the strokes and events, the scheme's
items and sizes, but not the names, the structure, the labels' texts or the series' keys.  So the
answer (``format: linkwork-edit/2``) holds, under the payload's own keys, only these: ``valid``,
``local`` (the points in their links' axes, from which the page places the points: positions are not
sent), ``plans`` (each plan's ``scale_per_mm`` and ``values``), ``scene`` (``size``, ``r``, ``em``, the
items as a table ``item_table`` (:func:`item_table`) in place of ``items``, ``poses``, the labels'
anchors ``label_at`` (Lb, 2), each plan's ``frame`` and ``em``, but while a value is dragged),
``series`` (``keys`` and ``values`` (S, A) in that order), ``forces`` (as in the payload, ``values``
compact, without the checks of the whole solution), ``parameters`` (the variant's values),
``extremes`` (None in a drag's answers), ``events``, ``warnings``, ``overrides`` and ``steps``.  The
labels' places and the drawing's extent are the page's to keep: it moves each label with the point it
names until the cycle is placed again whole.

The answer is sent as its JSON followed by the bytes of its arrays (:func:`encode_edit`): an array is
``{"dtype": "f4", "shape": [...], "offset": ...}`` in the JSON, its little-endian values where the offset
says, which the page reads in place (no text to parse or decode).  Link poses go as float32 with their
angles in (-pi, pi] (0.1 micrometre at a metre); the plans, series and forces as float32 (7 significant
digits); NaN where the mechanism does not assemble.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from typing import Any

import numpy as np

from linkwork.angles import wrap
from linkwork.motion.analysis import extremes
from linkwork.motion.plans import plan_series
from linkwork.scene.scheme import SchemeScene, scheme_scene
from linkwork.structure.parameters import Parameter
from linkwork.web.cycle import Cycle
from linkwork.web.edits import variant_parameters
from linkwork.web.payload import (
    _finite,
    _json,
    cycle_scale,
    element_list,
    events_part,
    forces_part,
    peaks,
    plan_shape,
    plan_values,
    series_values,
)

EDIT_FORMAT = "linkwork-edit/2"

#: The media type of an edit's answer (:func:`encode_edit`).
EDIT_MEDIA = "application/vnd.linkwork.edit"

#: The arrays of an edit's answer start at multiples of this many bytes (a float64's).
ALIGN = 8


@dataclass(frozen=True)
class Compact:
    """An array of an edit's answer (:func:`compact`): written by :func:`encode_edit` as
    ``{"dtype", "shape", "offset"}`` in the answer's JSON, its bytes after it."""

    dtype: str
    shape: list[int]
    data: bytes


def compact(a: np.ndarray, dtype: str = "f4") -> Compact:
    """``a`` as little-endian ``dtype`` values (``f4``, ``f8``, ``u1``)."""
    data = np.ascontiguousarray(a, dtype=np.dtype(dtype).newbyteorder("<"))
    return Compact(dtype, list(data.shape), data.tobytes())


def encode_edit(answer: Any) -> bytes:
    """An edit's answer as it is sent (:data:`EDIT_MEDIA`): the length ``n`` of its JSON (little-endian
    ``uint32``), ``n`` bytes of strict, compact JSON (UTF-8), zero bytes up to a multiple of :data:`ALIGN`,
    then the bytes of its :class:`Compact` arrays, each written in the JSON as ``{"dtype", "shape", "offset"}``
    (bytes from the end of that padding, a multiple of :data:`ALIGN`, so that the page reads each array where
    it lies)."""
    blobs: list[bytes] = []
    end = 0

    def written(value: Any) -> dict[str, Any]:  # called in the order the text is written
        nonlocal end
        if not isinstance(value, Compact):
            raise TypeError(f"{type(value).__name__} is not JSON serializable")
        at, end = end, end + -(-len(value.data) // ALIGN) * ALIGN
        blobs.append(value.data.ljust(end - at, b"\0"))
        return {"dtype": value.dtype, "shape": value.shape, "offset": at}

    head = json.dumps(answer, allow_nan=False, separators=(",", ":"), default=written).encode("utf-8")
    pad = -(4 + len(head)) % ALIGN
    return b"".join([len(head).to_bytes(4, "little"), head, bytes(pad), *blobs])


def decode_edit(body: bytes) -> Any:
    """The answer :func:`encode_edit` wrote, its arrays as read-only NumPy arrays (as the page reads it)."""
    n = int.from_bytes(body[:4], "little")
    base = 4 + n + -(4 + n) % ALIGN

    def array(d: dict[str, Any]) -> Any:
        if set(d) != {"dtype", "shape", "offset"}:
            return d
        dtype = np.dtype(d["dtype"]).newbyteorder("<")
        count = int(np.prod(d["shape"], dtype=np.int64))
        return np.frombuffer(body, dtype, count, base + d["offset"]).reshape(d["shape"])

    return json.loads(body[4 : 4 + n], object_hook=array)


def item_table(scheme: SchemeScene) -> dict[str, Any]:
    """The scheme's items as the page rebuilds them (the whole payload's ``items``, one dict an item): a list
    of each field, ``ends`` (where each item's vertices end among all of them) and ``xy``, every vertex
    ``(V, 2)`` in its link's axes, float64 (a table writes and reads in a tenth of the time of ninety dicts)."""
    items = scheme.items
    xy = [np.asarray(it.xy, dtype=float).reshape(-1, 2) for it in items]
    return {
        "kind": [it.kind for it in items],
        "link": [it.link for it in items],
        "name": [it.name for it in items],
        "closed": [it.closed for it in items],
        "radius": [it.radius for it in items],
        "ends": np.cumsum([len(a) for a in xy], dtype=int).tolist(),
        "xy": compact(np.concatenate(xy) if xy else np.zeros((0, 2)), "f8"),
    }


def edit_payload(
    cycle: Cycle, editable: list[Parameter] | None = None, dragged: bool = False, lang: str = "en"
) -> dict[str, Any]:
    """The answer to an edit: what differs from the payload of the mechanism as loaded (module docstring).

    ``editable``: the editable parameters of the mechanism, where the caller has them.  The answers to a
    ``dragged`` value leave out the strokes (``extremes`` None) and the frames of the plans, which the page
    keeps from the last whole cycle until the drag ends.  The parameters' notes in ``lang``.
    """
    kin = cycle.kin
    series = plan_series(kin)
    # the scheme's items and the labels' anchors do not depend on the samples drawn: those of the symbols
    scheme = scheme_scene(cycle.symbols, at=[], cycle=cycle.symbols)
    poses = np.array(kin.pose[0])
    poses[..., 2] = wrap(poses[..., 2])  # angles in (-pi, pi]
    scene: dict[str, Any] = {
        "size": scheme.size,
        "r": scheme.r,
        "em": scheme.em,
        "item_table": item_table(scheme),
        "elements": element_list(scheme),
    }
    shapes: dict[str, tuple[dict[str, Any], float]]
    if dragged:  # each plan's scale for the cycle, its frame kept
        shapes = {one.kind: ({}, cycle_scale(one, cycle.valid)) for one in series}
    else:  # each plan's frame and labels' size, and its scale
        shapes = {one.kind: plan_shape(cycle, one) for one in series}
    scene.update(
        {
            "poses": compact(poses),
            "label_at": _json(np.array([lab.at for lab in scheme.labels]).reshape(-1, 2), 12),
            "plans": {kind: shape for kind, (shape, _) in shapes.items()},
        }
    )
    quantities = series_values(cycle)
    out: dict[str, Any] = {
        "format": EDIT_FORMAT,
        "steps": len(kin.angles),
        "overrides": dict(cycle.overrides),
        "valid": compact(cycle.valid, "u1"),
        "local": _json(cycle.local, 12),
        "plans": {
            one.kind: {"scale_per_mm": shapes[one.kind][1], "values": compact(plan_values(one, cycle.valid))}
            for one in series
        },
        "scene": scene,
        "series": {
            "keys": [q[0] for q in quantities],
            "values": compact(np.array([q[4] for q in quantities]).reshape(len(quantities), -1)),
        },
        "forces": forces_part(cycle, scheme.size, compact),
        "parameters": variant_parameters(cycle.mech, cycle.overrides, kin.mass_properties, editable, lang),
        "extremes": None if dragged else [_finite(e.as_dict()) for e in extremes(kin)],
        "peaks": None if dragged else peaks(cycle),
        "events": events_part(cycle, lang),
        "warnings": list(cycle.notes),
    }
    return out
