"""Drawings for CAD: the scenes (:mod:`linkwork.scene`) written as DXF with ezdxf (``pip install "linkwork[cad]"``).

Every kind of item or vector goes on a layer of its own (``LINKS``, ``PIVOTS``, ``SUPPORTS``,
``HATCHING``, ``GUIDES``, ``BLOCKS``, ``TOOLS``, ``MARKERS``, ``SPRINGS``, ``DAMPERS``, ``TRAJECTORIES``,
``LABELS``; the plans' ``ABSOLUTE``, ``ROTATION``, ``NORMAL``, ``TANGENTIAL``, ``TRANSPORT``, ``CORIOLIS``, ``SLIDING``,
``POINTS``, ``NOTES``), so that an engineer can show, hide and restyle them.  Drawing units are
millimetres: the scheme and the plan of positions 1:1 (a point at x m is at 1000 x), the plans to their
stated scale (a vector u is u / scale mm long; the scale is in the ``NOTES`` layer's text and in the
header's custom property ``LINKWORK_SCALE``).  Each vector of a plan is a LINE with the extended data
``LINKWORK: "kind:start->end"`` and its arrowhead a SOLID on the same layer.  The notes are written in
the language of the report (``lang``, :mod:`linkwork.lang`; the layers keep their English names), every
text in the TrueType text style :data:`STYLE`, whose font has the Cyrillic and Greek letters.  Files are
written atomically.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from linkwork.atomic import write_atomic
from linkwork.lang import t
from linkwork.motion.kinematic_analysis import kinematics
from linkwork.motion.plans import plan_series
from linkwork.optional import require
from linkwork.scene.geometry import text_runs
from linkwork.scene.limits import LimitsScene, limits_scene
from linkwork.scene.plans import PlanScene, kind_name, plan_scene
from linkwork.scene.positions import PositionsScene, position_angles, positions_scene
from linkwork.scene.scheme import SchemeScene, scheme_scene
from linkwork.scene.style import SCHEME, VECTORS, Style
from linkwork.spec.reader import described
from linkwork.units import turn_deg

if TYPE_CHECKING:
    from linkwork.motion.kinematic_analysis import Kinematics

#: The application name of the extended data on the plans' vectors.
APPID = "LINKWORK"

#: Height of capital letters in ems of DejaVu Sans: a DXF text's height is that of its capitals.
CAP = 0.73

#: The least height of a text on paper, mm (ГОСТ 2.304): a plan's construction letters and its legend are no
#: smaller on a drawing in mm of the sheet.
SMALLEST = 2.5

#: The text style of every text: a TrueType font of ezdxf's standard styles with Cyrillic and Greek letters
#: (the default style's SHX font has neither).
STYLE = "OpenSans"

#: The size of the lettering the styles' dashes are drawn for (mm of the sheet): a dash of ``d`` points is
#: ``d`` mm long on a drawing lettered :data:`~linkwork.scene.plans.LETTERING` mm high ($LTSCALE scales it).
DASH_EM = 3.5

PURPOSE = "the drawings for CAD (linkwork analyze --dxf)"

#: Line weights (0.01 mm) of ГОСТ 2.303: the main line s = 0.7 mm (links, the absolute vectors, the forces), the
#: thin lines s / 2 and s / 3 (0.35 mm: pivots, guides, the plans' relative vectors; 0.25 mm: the trajectories,
#: the hatching).
MAIN, THIN, FINE = 70, 35, 25


def write_drawings(
    kin: Kinematics, index: int, folder: str | Path, cycle: Kinematics | None = None, lang: str = "en"
) -> list[Path]:
    """``scheme.dxf``, ``positions.dxf``, ``limits.dxf`` (a file that carries requirements: a synthesised one),
    ``velocity_plan.dxf`` and ``acceleration_plan.dxf`` of sample ``index``
    of ``kin`` into ``folder``, their notes in ``lang``; returns the paths.  ``cycle``: a whole turn (the
    scheme's trajectories and fixed symbols; see :func:`~linkwork.scene.scheme_scene`)."""
    require("ezdxf", purpose=PURPOSE)
    folder = Path(folder)
    mech = kin.mechanism
    full = cycle if cycle is not None else kinematics(mech, steps=360)
    out = [write_scheme(scheme_scene(kin, at=[index], cycle=full), index, folder / "scheme.dxf", lang=lang)]
    twelve = kinematics(mech, position_angles(mech))
    out.append(write_positions(positions_scene(twelve, cycle=full, lang=lang), folder / "positions.dxf", lang))
    spec = described(mech.description)
    limits = limits_scene(full, lang) if spec is not None and spec.requirements else None
    if limits is not None:
        out.append(write_limits(limits, folder / "limits.dxf", lang))
    valid = np.asarray(kin.valid_all[0])
    for series in plan_series(kin):
        scene = plan_scene(series, [index], valid=valid, lang=lang)
        out.append(write_plan(scene, 0, folder / f"{series.kind}_plan.dxf", lang))
    return out


def write_scheme(scene: SchemeScene, index: int, path: str | Path, trajectories: bool = True, lang: str = "en") -> Path:
    """The scheme of sample ``index`` of ``scene``, 1:1 in mm, with the trajectories of its points; its note
    in ``lang``."""
    doc, msp = _document(SCHEME, em=1000 * scene.em)
    draw_scheme(msp, scene, index, trajectories)
    crank = t("drawing.crank", lang, angle=f"{turn_deg(scene.angles[index]):.1f}")
    note = f"{t('scheme.title', lang, name=scene.name)}, {crank}; 1:1, {t('unit.mm', lang)}"
    _note(doc, msp, note, scene.extent(index, paths=trajectories) * 1000, 1000 * scene.em, lang)
    return _save(doc, path)


def draw_scheme(
    layout: Any, scene: SchemeScene, index: int, trajectories: bool = True, mm: float = 1000.0, em: float | None = None
) -> np.ndarray:
    """Draw the scheme of sample ``index`` into ``layout`` (a modelspace or a block), ``mm`` mm a metre, its
    labels ``em`` mm (default the scene's); returns its extent ``[x0, y0, x1, y1]``, mm."""
    if trajectories:
        _paths(layout, scene.paths, mm)
    _items(layout, scene, index, mm=mm)
    _elements(layout, scene, index, mm)
    for lab in scene.labels:
        _text(layout, lab.text, lab.centre[index] * mm, mm * scene.em if em is None else em)
    return np.asarray(scene.extent(index, paths=trajectories) * mm)


def write_positions(scene: PositionsScene, path: str | Path, lang: str = "en") -> Path:
    """The plan of positions, 1:1 in mm: position 0 whole, the others' links thin, the position numbers; its
    note in ``lang``."""
    s = scene.scheme
    doc, msp = _document(SCHEME, em=1000 * s.em)
    draw_positions(msp, scene)
    note = f"{t('positions.title', lang, name=s.name, count=scene.positions)}; 1:1, {t('unit.mm', lang)}"
    _note(doc, msp, note, scene.extent() * 1000, 1000 * s.em, lang)
    return _save(doc, path)


def draw_positions(layout: Any, scene: PositionsScene, mm: float = 1000.0, em: float | None = None) -> np.ndarray:
    """Draw the plan of positions into ``layout``, ``mm`` mm a metre, its labels ``em`` mm (default the
    scene's); returns its extent ``[x0, y0, x1, y1]``, mm."""
    s = scene.scheme
    em = mm * s.em if em is None else em
    _paths(layout, s.paths, mm)
    _items(layout, s, 0, mm=mm)
    for k in range(1, len(s.angles)):  # the other positions in thin lines (ГОСТ 2.303)
        _items(layout, s, k, kinds=("bar", "plate", "pivot"), frame=False, mm=mm, weight=THIN)
    for lab in (*s.labels, *scene.numbers, *scene.letters, *scene.strokes):
        _text(layout, lab.text, lab.centre[0] * mm, em)
    for arc in scene.arcs:
        layout.add_lwpolyline([tuple(v) for v in arc * mm], dxfattribs={"layer": "LABELS"})
    for mark in scene.marks * mm:
        layout.add_circle(tuple(mark), 0.15 * em, dxfattribs={"layer": "MARKERS"})
    for leader in scene.leaders * mm:
        layout.add_line(tuple(leader[0]), tuple(leader[1]), dxfattribs={"layer": "LABELS"})
    return np.asarray(scene.extent() * mm)


def write_limits(scene: LimitsScene, path: str | Path, lang: str = "en") -> Path:
    """The working member's limit positions, 1:1 in mm: the first whole, the second's links thin, the two lines
    of theta from the crank's pivot (layer ``LIMITS``), its arc and value, a slider's stroke H dimensioned (layer
    ``DIMENSIONS``); its note in ``lang``."""
    s = scene.scheme
    doc, msp = _document(SCHEME, extra={"LIMITS": 7, "DIMENSIONS": 7})
    _paths(msp, s.paths)
    _items(msp, s, 0)
    _items(msp, s, 1, kinds=("bar", "plate", "pivot", "block", "tool"), frame=False)
    for line in (*scene.rays, scene.arc):
        msp.add_lwpolyline([tuple(v) for v in line * 1000], dxfattribs={"layer": "LIMITS"})
    for lines in (list(scene.dimension), *(list(d.lines) for d in scene.swings)):  # H, each rocker's swing ψ
        _dimension(msp, lines, 1000 * s.em)
    for lab in (*s.labels, *scene.texts()):
        _text(msp, lab.text, lab.centre[0] * 1000, 1000 * s.em)
    k = (np.pi + scene.theta) / (np.pi - scene.theta)
    title = t(
        "limits.title", lang, name=s.name, member=scene.who(lang), theta=f"{np.degrees(scene.theta):.2f}", k=f"{k:.4f}"
    ).replace("\n", ", ")
    _note(doc, msp, f"{title}; 1:1, {t('unit.mm', lang)}", scene.extent() * 1000, 1000 * s.em, lang)
    return _save(doc, path)


def _dimension(msp: Any, lines: list[np.ndarray], em: float) -> None:
    """A dimension in the ``DIMENSIONS`` layer: its extension lines and its dimension line (the last of
    ``lines``, polylines ``(K, 2)`` in m: a straight line or an arc), an arrowhead (``em`` mm) at each of its
    ends along it."""
    for line in lines:
        msp.add_lwpolyline([tuple(v) for v in line * 1000], dxfattribs={"layer": "DIMENSIONS"})
    if lines:
        mm = lines[-1] * 1000
        length = float(np.sum(np.hypot(*np.diff(mm, axis=0).T)))
        for tip, toward in ((mm[0], mm[1]), (mm[-1], mm[-2])):
            u = (tip - toward) / max(float(np.hypot(*(tip - toward))), 1e-300)
            _head(msp, tip - length * u, tip, min(0.8 * em, 0.3 * length), "DIMENSIONS")


def write_plan(scene: PlanScene, index: int, path: str | Path, lang: str = "en") -> Path:
    """The plan of position ``index`` of ``scene``, in mm of the sheet at the plan's scale; its note in
    ``lang``."""
    doc, msp = _document(VECTORS, extra={"POINTS": 7, "NOTES": 7}, em=scene.em)
    doc.header.custom_vars.append("LINKWORK_SCALE", repr(scene.scale))
    draw_plan(msp, scene, index)
    crank = t("drawing.crank", lang, angle=f"{turn_deg(scene.angles[index]):.1f}")
    note = f"{t(f'plan.{scene.kind}', lang)}, {crank}; {scene.scale_note(lang)}"
    _note(doc, msp, note, scene.extent(index), scene.em, lang)
    _legend(msp, scene, index, lang)
    return _save(doc, path)


def draw_plan(msp: Any, scene: PlanScene, index: int) -> np.ndarray:
    """Draw the plan of position ``index`` of ``scene`` into ``msp`` (a modelspace or a block), in mm of the sheet;
    returns its extent ``[x0, y0, x1, y1]``, mm."""
    for e in scene.drawn(index):
        arrow = scene.arrows[e]
        start, end = scene.ends[index, e]
        layer = VECTORS.get(arrow.kind, VECTORS["rotation"]).layer
        line = msp.add_line(tuple(start), tuple(end), dxfattribs={"layer": layer})
        line.set_xdata(APPID, [(1000, f"{arrow.kind}:{scene.names[arrow.start]}->{scene.names[arrow.end]}")])
        _head(msp, start, end, 0.55 * scene.em, layer)
    for j, p in enumerate(scene.points[index]):
        if np.isfinite(p).all():
            msp.add_circle(tuple(p), 0.2 * scene.em, dxfattribs={"layer": "POINTS"})
        text, c = scene.text[index][j], scene.centres[index, j]
        if text and np.isfinite(c).all():
            _text(msp, text, c, scene.em if scene.main[j] else max(0.8 * scene.em, SMALLEST / CAP))
    return scene.extent(index)


def _legend(msp: Any, scene: PlanScene, index: int, lang: str) -> None:
    """Under the plan, a stroke of each kind of vector drawn, on its layer, and the kind's name in ``lang``."""
    x0, y0 = scene.extent(index)[:2]
    em = scene.em
    for row, kind in enumerate(scene.kinds(index)):
        y = y0 - (2.5 + 1.6 * row) * em
        layer = VECTORS[kind].layer
        line = msp.add_line((x0, y), (x0 + 5 * em, y), dxfattribs={"layer": layer})
        line.set_xdata(APPID, [(1000, f"legend:{kind}")])
        _head(msp, np.array([x0, y]), np.array([x0 + 5 * em, y]), 0.55 * em, layer)
        name = kind_name(kind, scene.kind, lang)
        _text(msp, name, np.array([x0 + 6 * em, y]), max(0.8 * em, SMALLEST / CAP), layer="NOTES", left=True)


def _document(styles: dict[str, Style], extra: dict[str, int] | None = None, em: float = DASH_EM) -> tuple[Any, Any]:
    """A new DXF document in mm with a layer for every style, in its colour and its line type (a dashed
    style's dashes, for lettering ``em`` mm high), and ``LABELS``, ``NOTES``, ``extra``."""
    ezdxf = require("ezdxf", purpose=PURPOSE)
    doc = ezdxf.new("R2010", setup=True)
    doc.units = ezdxf.units.MM
    doc.header["$MEASUREMENT"] = 1
    doc.header["$LTSCALE"] = em / DASH_EM
    doc.appids.add(APPID)
    for style in styles.values():
        if style.layer not in doc.layers:
            weight = MAIN if style.width >= 1.2 else THIN if style.width >= 0.9 else FINE
            linetype = _linetype(doc, style)
            doc.layers.add(style.layer, color=style.aci, lineweight=weight, linetype=linetype)
    for name, colour in {"LABELS": 7, "NOTES": 7, **(extra or {})}.items():
        if name not in doc.layers:
            doc.layers.add(name, color=colour)
    return doc, doc.modelspace()


def _linetype(doc: Any, style: Style) -> str:
    """The line type of ``style``: ``Continuous``, or its dashes (points, drawn as mm: :data:`DASH_EM`) as a line
    type ``LW_LAYER`` of the document."""
    if not style.dash:
        return "Continuous"
    name = f"LW_{style.layer}"
    if name not in doc.linetypes:
        pattern = [float(sum(style.dash))] + [d if k % 2 == 0 else -d for k, d in enumerate(style.dash)]
        doc.linetypes.add(name, pattern=pattern, description=f"linkwork {style.layer.lower()}")
    return name


def _items(
    msp: Any,
    scene: SchemeScene,
    index: int,
    kinds: tuple[str, ...] | None = None,
    frame: bool = True,
    mm: float = 1000.0,
    weight: int | None = None,
) -> None:
    """The scheme's items at sample ``index`` (of ``kinds``; the frame's only if ``frame``), ``mm`` mm a metre;
    ``weight`` (0.01 mm) instead of their layer's line weight."""
    for it in scene.items:
        if it.kind == "path" or (kinds is not None and it.kind not in kinds) or (it.link == 0 and not frame):
            continue
        xy = scene.placed(it, index) * mm
        if not np.isfinite(xy).all():
            continue
        attrs: dict[str, Any] = {"layer": SCHEME[it.kind].layer}
        if weight is not None:
            attrs["lineweight"] = weight
        if it.radius:
            msp.add_circle(tuple(xy[0]), mm * it.radius, dxfattribs=attrs)
        else:
            msp.add_lwpolyline([tuple(v) for v in xy], close=it.closed, dxfattribs=attrs)


def _elements(msp: Any, scene: SchemeScene, index: int, mm: float = 1000.0) -> None:
    """The springs and dampers at sample ``index``, a polyline for each stroke of their symbols, in mm, on their
    kind's layer (``SPRINGS``, ``DAMPERS``)."""
    for element in scene.elements:
        for xy in scene.element_strokes(element, index):
            if np.isfinite(xy).all():
                msp.add_lwpolyline([tuple(v) for v in xy * mm], dxfattribs={"layer": SCHEME[element.kind].layer})


def _paths(msp: Any, paths: np.ndarray, mm: float = 1000.0) -> None:
    """Trajectories ``(A, Q, 2)`` (m) as polylines, ``mm`` mm a metre, broken where the mechanism does not
    assemble."""
    for q in range(paths.shape[1]):
        xy = np.asarray(paths[:, q], dtype=float) * mm
        ok = np.asarray(np.isfinite(xy).all(-1))
        runs = np.split(np.arange(len(xy)), np.flatnonzero(np.diff(ok.astype(int))) + 1)
        for run in runs:
            if ok[run[0]] and len(run) > 1:
                msp.add_lwpolyline([tuple(v) for v in xy[run]], dxfattribs={"layer": SCHEME["path"].layer})


def _text(msp: Any, text: str, centre: np.ndarray, em: float, layer: str = "LABELS", left: bool = False) -> None:
    """A label ``text`` of font size ``em`` centred at ``centre`` (``left``: starting there): an MTEXT, its
    subscripts stacked under an empty numerator (:func:`mtext`)."""
    from ezdxf.enums import MTextEntityAlignment

    if np.isfinite(centre).all():
        entity = msp.add_mtext(mtext(text), dxfattribs={"layer": layer, "style": STYLE, "char_height": CAP * em})
        at = MTextEntityAlignment.MIDDLE_LEFT if left else MTextEntityAlignment.MIDDLE_CENTER
        entity.set_location(tuple(centre), attachment_point=at)


def mtext(text: str) -> str:
    """A label's text as MTEXT markup: each subscript (:func:`~linkwork.scene.geometry.text_runs`) a stack with
    an empty upper part (``n_ba`` -> ``n\\S^ ba;``), the markup's own characters escaped."""
    out = []
    for run, sub in text_runs(text):
        run = run.replace("\\", "\\\\").replace("{", "\\{").replace("}", "\\}")
        out.append(f"\\S^ {run.replace('^', '')};" if sub else run.replace("^", "^ "))
    return "".join(out)


def _note(doc: Any, msp: Any, text: str, extent: np.ndarray, em: float, lang: str = "en") -> None:
    """The drawing's title above it, in the ``NOTES`` layer (its numbers with decimal commas in Russian)."""
    from ezdxf.enums import TextEntityAlignment

    from linkwork.lang import russian_numbers

    text = russian_numbers(text) if lang == "ru" else text

    entity = msp.add_text(text, height=CAP * em, dxfattribs={"layer": "NOTES", "style": STYLE})
    entity.set_placement((float(extent[0]), float(extent[3]) + 1.5 * em), align=TextEntityAlignment.BOTTOM_LEFT)


def _head(msp: Any, start: np.ndarray, end: np.ndarray, size: float, layer: str) -> None:
    """A filled arrowhead at ``end`` of the vector from ``start``."""
    d = end - start
    length = float(np.hypot(*d))
    size = min(size, 0.35 * length)
    u = d / length
    w = np.array([-u[1], u[0]])
    a, b = end - size * u + 0.3 * size * w, end - size * u - 0.3 * size * w
    msp.add_solid([tuple(end), tuple(a), tuple(b)], dxfattribs={"layer": layer})


def _save(doc: Any, path: str | Path) -> Path:
    """Write ``doc`` to ``path`` atomically."""
    return write_atomic(path, lambda tmp: doc.saveas(tmp))
