"""Force plans and Zhukovsky's lever for CAD: their scenes (:mod:`linkwork.scene.force_plans`) written as DXF.

As the other drawings (:mod:`linkwork.io.dxf`): millimetres of the sheet, every kind of arrow on a layer of
its own (``WEIGHTS``, ``INERTIA``, ``LOADS``, ``KNOWN_REACTIONS``, ``TANGENTIAL_R``, ``NORMAL_R``,
``REACTIONS``, ``INNER_REACTIONS``, ``BALANCING``; the lever's turned velocity plan on ``LEVER``), each
arrow a LINE with the extended data ``LINKWORK: "kind:name"`` and a SOLID arrowhead, the reactions read off
a plan dashed, the names in ``LABELS``, the notes (group, scale μF) in ``NOTES`` in the report's language.
``force_plans.dxf`` holds every group's plan side by side, each at its own scale (in its note);
``lever.dxf`` the lever.  Files are written atomically.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from linkwork.io.dxf import APPID, PURPOSE, THIN, _document, _head, _note, _save, _text
from linkwork.lang import group_label, t
from linkwork.optional import require
from linkwork.scene.force_plans import ForceScene, force_plan_scene, lever_scene, short_note
from linkwork.scene.style import FORCES
from linkwork.units import turn_deg

if TYPE_CHECKING:
    from linkwork.kinetostatics.force_polygons import ForcePlans
    from linkwork.kinetostatics.zhukovsky import Lever
    from linkwork.motion.kinematic_analysis import Kinematics

#: AutoCAD colour index of each layer (7: black on white paper, white on black).
COLOURS = {
    "WEIGHTS": 34,
    "INERTIA": 1,
    "LOADS": 7,
    "KNOWN_REACTIONS": 6,
    "TANGENTIAL_R": 5,
    "NORMAL_R": 3,
    "REACTIONS": 30,
    "INNER_REACTIONS": 4,
    "BALANCING": 211,
    "LEVER": 8,
}


def _forces_document() -> tuple[Any, Any]:
    doc, msp = _document(FORCES, extra={"POINTS": 7})
    for name, colour in COLOURS.items():
        doc.layers.get(name).color = colour
    doc.layers.get("INNER_REACTIONS").dxf.linetype = "DASHED"
    return doc, msp


def _draw(msp: Any, scene: ForceScene, offset: np.ndarray) -> None:
    """The scene's lines, arrows and names, shifted by ``offset`` (mm)."""
    for s, e in scene.lines:
        msp.add_line(tuple(s + offset), tuple(e + offset), dxfattribs={"layer": FORCES["lever"].layer})
    for a in scene.arrows:
        layer = FORCES.get(a.kind, FORCES["reaction"]).layer
        attrs = {"layer": layer, **({"linetype": "DASHED", "lineweight": THIN} if a.resultant else {})}  # thin
        line = msp.add_line(tuple(a.start + offset), tuple(a.end + offset), dxfattribs=attrs)
        line.set_xdata(APPID, [(1000, f"{a.kind}:{a.text}")])
        _head(msp, a.start + offset, a.end + offset, 0.55 * scene.em, layer)
        if a.text:
            _text(msp, a.text, a.centre + offset, scene.em)
    for p in scene.dots:
        msp.add_circle(tuple(p + offset), 0.2 * scene.em, dxfattribs={"layer": "POINTS"})
    for text, c in zip(scene.dot_text, scene.dot_centres, strict=True):
        if text:
            _text(msp, text, c + offset, scene.em)


def _short(
    msp: Any, scene: ForceScene, offset: np.ndarray, lang: str, width: float | None = None, em: float | None = None
) -> None:
    """Under a force plan, the names and values of its arrows too short to carry their names
    (:func:`~linkwork.scene.force_plans.short_note`), in ``NOTES``, in lines no wider than ``width`` mm (default
    the plan's, at least 60 mm), ``em`` mm high (default the scene's)."""
    from linkwork.scene.geometry import text_size

    note = short_note(scene, lang)
    if not note:
        return
    em = scene.em if em is None else em
    box = scene.extent() + np.r_[offset, offset]
    width = max(60.0, float(box[2] - box[0])) if width is None else width
    lines = [""]
    for part in note.split(", "):
        joined = f"{lines[-1]}, {part}" if lines[-1] else part
        if lines[-1] and text_size(joined, em)[0] > width:
            lines.append(part)
        else:
            lines[-1] = joined
    for k, line in enumerate(lines):
        at = np.array([box[0], box[1] - (1.2 * scene.em + 1.5 * k * em)])
        _text(msp, line, at, em, layer="NOTES", left=True)


def write_force_plans(plans: ForcePlans, index: int, path: str | Path, lang: str = "en") -> Path:
    """Every group's force plan at sample ``index`` side by side, each with its note (group, μF) in ``lang``."""
    require("ezdxf", purpose=PURPOSE)
    doc, msp = _forces_document()
    angle = float(plans.forces.angles[index])
    x = 0.0
    top = 0.0
    for g in plans.groups:
        scene = force_plan_scene(g, index, lang=lang, angle=angle)
        box = scene.extent()
        offset = np.array([x - box[0], 0.0])
        _draw(msp, scene, offset)
        _short(msp, scene, offset, lang)
        label = group_label(g.label, lang)
        if g.balancing is not None:
            label = t("forceplans.driving", lang, group=label)
        note = t("forceplans.cell", lang, group=label, scale=f"{scene.scale:g}").replace("\n", ";  ")
        _note(doc, msp, note, box + np.r_[offset, offset], scene.em, lang)
        x += box[2] - box[0] + 20.0
        top = max(top, float(box[3]) + 6 * scene.em)
    crank = t("drawing.crank", lang, angle=f"{turn_deg(angle):.1f}")
    note = f"{t('forceplans.title', lang, name=plans.forces.mechanism.name)}, {crank}"
    _note(doc, msp, note, np.array([0.0, 0.0, x, top]), 1.4 * 3.5, lang)
    return _save(doc, path)


def write_lever(lv: Lever, kin: Kinematics, index: int, path: str | Path, lang: str = "en") -> Path:
    """Zhukovsky's lever at sample ``index`` of ``kin`` (the samples of ``lv``), its note in ``lang``."""
    from linkwork.motion.plans import plan_series

    require("ezdxf", purpose=PURPOSE)
    doc, msp = _forces_document()
    scene = lever_scene(lv, plan_series(kin)[0], index, lang=lang)
    _draw(msp, scene, np.zeros(2))
    _short(msp, scene, np.zeros(2), lang)
    doc.header.custom_vars.append("LINKWORK_SCALE", repr(scene.scale))
    crank = t("drawing.crank", lang, angle=f"{turn_deg(float(kin.angles[index])):.1f}")
    note = (
        f"{t('lever.title', lang, name=kin.mechanism.name)}, {crank}; "
        f"{t('lever.scale', lang, plan=f'{scene.plan_scale:g}', scale=f'{scene.scale:g}')}; "
        f"{t('lever.moment', lang, moment=f'{float(lv.balancing[0, index]):.6g}')}"
    )
    _note(doc, msp, note, scene.extent(), scene.em, lang)
    return _save(doc, path)
