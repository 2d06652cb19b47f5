"""The force plans of the Assur groups and Zhukovsky's lever at a crank angle, as the viewer draws them.

The drawings are the scenes of :mod:`linkwork.scene.force_plans`, the ones the figures and DXF draw, written as
plain JSON-able data (``force_plans`` of the payload, ``format: linkwork-view/1``):

* ``available`` (and the ``reason`` where not), ``groups``: each drawing's ``key`` (``group:0``..., ``lever``),
  ``title`` (the group's label; the driving link's said so) and whether its plan is ``solved`` by the
  graphical method (else closed by the analytic reactions); ``kinds``: the name of each kind of arrow, for a
  legend; ``styles``: each kind's colour and dashes (:data:`linkwork.scene.style.FORCES`);
* ``samples``: the samples drawn, and ``at``: for each, ``index``, ``turn_deg`` and its ``drawings`` (one a
  group, then the lever), each (:func:`scene_dict`) with ``kind``, ``scale`` μF (N/mm), ``plan_scale`` μv
  ((m/s)/mm, the lever's: the velocity plan's scale for the cycle), ``em`` (the labels' height), ``extent``,
  the ``arrows`` (``kind``, ``text``, its ``runs`` as the figures set the name (:func:`tex_runs`), ``start``,
  ``end``, ``centre`` of its name, ``value`` N,
  ``resultant``: a reaction read off the plan, drawn dashed), the lever's ``lines``, the ``dots`` with their
  ``dot_text`` and ``dot_centres``; all in mm of the sheet, y up; the lever's ``balancing`` moment (N m,
  counter-clockwise +) and ``crank`` length (m).

Drawing a sample takes some tens of milliseconds (its labels are placed clear of each other), so the live page
asks the server for the sample it shows (:func:`force_plans_at`) and an exported page carries
:data:`EXPORTED` samples, evenly spread, and shows the one nearest the crank.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import Any

import numpy as np

from linkwork.errors import LinkworkError
from linkwork.kinetostatics.force_polygons import ForcePlans, force_plans
from linkwork.kinetostatics.zhukovsky import Lever, lever
from linkwork.lang import group_label, t
from linkwork.motion.plans import PlanSeries, plan_series
from linkwork.scene.force_plans import FORCE_KINDS, ForceScene, force_plan_scene, lever_scene
from linkwork.scene.style import FORCES
from linkwork.web.cycle import Cycle
from linkwork.web.payload import PLAN_FONT, _json, plan_shape

#: Samples of a turn an exported page carries its force plans and lever at (every 10 degrees of 360).
EXPORTED = 36


@dataclass(frozen=True)
class Drawn:
    """What the force drawings of a cycle are made from: the plans of its groups, its lever (None where it has
    none), its velocity plan with the scale and labels' size the page's velocity plan has."""

    cycle: Cycle
    plans: ForcePlans
    lever: Lever | None
    velocity: PlanSeries
    plan_scale: float
    plan_em: float


def drawn_of(cycle: Cycle) -> Drawn | None:
    """The force plans and the lever of ``cycle``, or None where it has no forces."""
    if cycle.forces is None:
        return None
    try:
        lv: Lever | None = lever(cycle.forces)
    except LinkworkError:  # no crank pin: the plans without the lever
        lv = None
    velocity = plan_series(cycle.kin)[0]
    shape, scale = plan_shape(cycle, velocity)
    return Drawn(cycle, force_plans(cycle.forces), lv, velocity, scale, float(shape["em"]))


def force_plans_part(
    cycle: Cycle, samples: list[int] | np.ndarray, drawn: Drawn | None = None, lang: str = "en"
) -> dict[str, Any]:
    """The force plans and the lever of ``cycle`` at ``samples`` (see the module's text), their names in ``lang``."""
    drawn = drawn_of(cycle) if drawn is None else drawn
    if drawn is None:
        return {"available": False, "reason": cycle.reason or "no forces", "groups": [], "samples": [], "at": []}
    groups = [_group(g, k, lang) for k, g in enumerate(drawn.plans.groups)]
    if drawn.lever is not None:
        groups.append({"key": "lever", "title": t("caption.lever", lang), "solved": True})
    at = [sample_drawings(drawn, int(i), lang) for i in samples]
    return {
        "available": True,
        "reason": "",
        "groups": groups,
        "kinds": {k: t(f"force.{k}", lang) for k in FORCE_KINDS},
        "styles": {k: {"colour": FORCES[k].colour, "dash": list(FORCES[k].dash)} for k in (*FORCE_KINDS, "lever")},
        "samples": [int(i) for i in samples],
        "at": at,
    }


def _group(g: Any, k: int, lang: str = "en") -> dict[str, Any]:
    title = group_label(g.label, lang)
    if g.balancing is not None:
        title = t("forceplans.driving", lang, group=title)
    return {"key": f"group:{k}", "title": title, "solved": bool(g.solved)}


def sample_drawings(drawn: Drawn, index: int, lang: str = "en") -> dict[str, Any]:
    """The drawings of every group and the lever at sample ``index`` of the cycle (none where it does not
    assemble), the forces named in ``lang``."""
    cycle = drawn.cycle
    angles = cycle.kin.angles
    turn = abs(math.degrees(float(angles[index] - angles[0])))
    out: dict[str, Any] = {"index": index, "turn_deg": turn, "drawings": []}
    if not cycle.valid[index]:
        return out
    angle = float(angles[index])
    for g in drawn.plans.groups:
        scale = g.scale(index)
        vertices = g.vertices(index) / scale
        finite = vertices[np.isfinite(vertices).all(-1)]
        span = float(np.max(finite.max(0) - finite.min(0))) if len(finite) else 100.0
        em = PLAN_FONT * max(span, 10.0)  # as high on the panel as the plans' labels
        scene = force_plan_scene(g, index, scale=scale, em=em, angle=angle, lang=lang)
        out["drawings"].append(scene_dict(scene))
    if drawn.lever is not None:
        lv = drawn.lever
        lever_drawn = lever_scene(lv, drawn.velocity, index, em=drawn.plan_em, plan_scale=drawn.plan_scale, lang=lang)
        one = scene_dict(lever_drawn)
        one["balancing"] = _number(lv.balancing[0, index])
        one["crank"] = _number(np.asarray(lv.crank).reshape(-1)[0])
        out["drawings"].append(one)
    return out


def _number(x: Any) -> float | None:
    x = float(x)
    return x if math.isfinite(x) else None


def scene_dict(scene: ForceScene) -> dict[str, Any]:
    """A force scene as the page draws it: mm of the sheet, y up (see the module's text)."""
    d = None  # unrounded: a force read back off its arrow and the scale is the force
    return {
        "kind": scene.kind,
        "scale": scene.scale,
        "plan_scale": _number(scene.plan_scale),
        "em": scene.em,
        "extent": _json(scene.extent(), d),
        "arrows": [
            {
                "kind": a.kind,
                "text": a.text,
                "runs": tex_runs(a.tex),
                "start": _json(a.start, d),
                "end": _json(a.end, d),
                "centre": _json(a.centre, d),
                "value": _number(a.value),
                "resultant": a.resultant,
            }
            for a in scene.arrows
        ],
        "lines": _json(scene.lines, d),
        "dots": _json(scene.dots, d),
        "dot_text": list(scene.dot_text),
        "dot_centres": _json(scene.dot_centres, d),
    }


#: A force's name as mathtext writes it (:meth:`~linkwork.kinetostatics.force_polygons.PlanForce.tex`): a base,
#: its subscript and its superscript, each in braces.
_TEX = re.compile(r"^\$(?P<base>[^_^$]+)(?:_\{(?P<sub>[^}]*)\})?(?:\^\{(?P<sup>[^}]*)\})?\$$")

#: The mathtext commands of the forces' names and their letters.
_TEX_LETTERS = {r"\Phi ": "Φ", r"\Phi": "Φ", r"\tau": "τ", r"\prime": "′"}


def tex_runs(tex: str) -> list[list[str]]:
    """A force's name as the figures write it (``$R_{12}^{n}$``, ``$\\Phi_{2}$``) in runs the page sets: ``[text,
    ""]`` on the line, ``[text, "sub"]`` lowered, ``[text, "sup"]`` raised (``[["R", ""], ["12", "sub"], ["n",
    "sup"]]``); a name of another form as one run of its text."""
    for command, letter in _TEX_LETTERS.items():
        tex = tex.replace(command, letter)
    m = _TEX.match(tex)
    if m is None:
        return [[tex.strip("$"), ""]]
    runs = [[m["base"], ""], [m["sub"] or "", "sub"], [m["sup"] or "", "sup"]]
    return [run for run in runs if run[0]]


def exported_samples(n: int) -> np.ndarray:
    """The samples (of ``n``) an exported page carries its force drawings at: :data:`EXPORTED`, evenly spread."""
    return np.unique(np.round(np.arange(min(n, EXPORTED)) * (n / min(n, EXPORTED))).astype(int))
