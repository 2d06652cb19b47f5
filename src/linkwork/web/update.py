"""An edit's answer: only what an edit of dimensions or masses changes, its arrays in a compact form.

The page holds the payload of the mechanism as loaded (:func:`linkwork.web.payload.cycle_payload`);
an edit changes the positions, the plans, the series, the forces, the strokes and events, the scheme's
items and sizes, but not the names, the structure, the labels' texts or the series' keys.  So the
answer (``format: linkwork-edit/1``) holds, under the payload's own keys, only these: ``valid``,
``local`` (the points in their links' axes, from which the page places the points: positions are not
sent), ``plans`` (each plan's ``scale_per_mm`` and ``values``), ``scene`` (``size``, ``r``, ``em``,
``items``, ``poses``, the labels' anchors ``label_at`` (Lb, 2), each plan's ``frame`` and ``em``, but
while a value is dragged),
``series`` (``keys`` and ``values`` (S, A) in that order), ``forces`` (as in the payload, ``values``
compact, without the checks of the whole solution), ``parameters`` (the variant's values),
``extremes`` (None in a drag's answers), ``events``, ``warnings``, ``overrides`` and ``steps``.  The
labels' places and the drawing's extent are the page's to keep: it moves each label with the point it
names until the cycle is placed again whole.

A compact array is ``{"dtype": "f4", "shape": [...], "b64": ...}``: the little-endian values, base64.
Link poses go as float32 with their angles in (-pi, pi] (0.1 micrometre at a metre); the plans, series
and forces as float32 (7 significant digits); NaN where the mechanism does not assemble.
"""

from __future__ import annotations

import base64
from typing import Any

import numpy as np

from linkwork.motion.analysis import extremes
from linkwork.motion.plans import plan_series
from linkwork.scene.scheme import scheme_scene
from linkwork.structure.parameters import Parameter
from linkwork.web.cycle import Cycle
from linkwork.web.edits import variant_parameters
from linkwork.web.payload import (
    _finite,
    _json,
    cycle_scale,
    forces_part,
    plan_shape,
    plan_values,
    scheme_shape,
    series_values,
)

EDIT_FORMAT = "linkwork-edit/1"


def compact(a: np.ndarray, dtype: str = "f4") -> dict[str, Any]:
    """``a`` as ``{"dtype", "shape", "b64"}``: its values as little-endian ``dtype`` (``f4``, ``f8``, ``u1``),
    base64."""
    data = np.ascontiguousarray(a, dtype=np.dtype(dtype).newbyteorder("<"))
    return {"dtype": dtype, "shape": list(data.shape), "b64": base64.b64encode(data.tobytes()).decode("ascii")}


def edit_payload(cycle: Cycle, editable: list[Parameter] | None = None, dragged: bool = False) -> dict[str, Any]:
    """The answer to an edit: what differs from the payload of the mechanism as loaded (module docstring).

    ``editable``: the editable parameters of the mechanism, where the caller has them.  The answers to a
    ``dragged`` value leave out the strokes (``extremes`` None) and the frames of the plans, which the page
    keeps from the last whole cycle until the drag ends.
    """
    kin = cycle.kin
    series = plan_series(kin)
    # the scheme's items and the labels' anchors do not depend on the samples drawn: those of the symbols
    scheme = scheme_scene(cycle.symbols, at=[], cycle=cycle.symbols)
    poses = np.array(kin.pose[0])
    poses[..., 2] = np.pi - np.mod(np.pi - poses[..., 2], 2 * np.pi)  # angles in (-pi, pi]
    scene = scheme_shape(scheme)
    shapes: dict[str, tuple[dict[str, Any], float]]
    if dragged:  # each plan's scale for the cycle, its frame kept
        shapes = {one.kind: ({}, cycle_scale(one, cycle.valid)) for one in series}
    else:  # each plan's frame and labels' size, and its scale
        shapes = {one.kind: plan_shape(cycle, one) for one in series}
    scene.update({
        "poses": compact(poses),
        "label_at": _json(np.array([lab.at for lab in scheme.labels]).reshape(-1, 2), 12),
        "plans": {kind: shape for kind, (shape, _) in shapes.items()},
    })  # fmt: skip
    quantities = series_values(cycle)
    out: dict[str, Any] = {
        "format": EDIT_FORMAT,
        "steps": len(kin.angles),
        "overrides": dict(cycle.overrides),
        "valid": compact(cycle.valid, "u1"),
        "local": _json(cycle.local, 12),
        "plans": {one.kind: {"scale_per_mm": shapes[one.kind][1], "values": compact(plan_values(one, cycle.valid))}
                  for one in series},  # fmt: skip
        "scene": scene,
        "series": {"keys": [q[0] for q in quantities],
                   "values": compact(np.array([q[4] for q in quantities]).reshape(len(quantities), -1))},  # fmt: skip
        "forces": forces_part(cycle, scheme.size, compact),
        "parameters": variant_parameters(cycle.mech, cycle.overrides, kin.mass_properties, editable),
        "extremes": None if dragged else [_finite(e.as_dict()) for e in extremes(kin)],
        "events": [_finite(e.as_dict()) for e in kin.events],
        "warnings": list(cycle.notes),
    }
    return out
