"""The drawings of the course project's sheets (:mod:`linkwork.io.dxf_sheet`): the scheme at a reduction of ГОСТ
2.302, the plans and force plans at scales of the 1-2-2.5-5 series, Zhukovsky's lever, the legend of the arrows, and
the drawings of the kinematics and kinetostatics sheets; each a :class:`~linkwork.io.dxf_sheet.SheetDrawing` that
the sheet places in a cell of its field.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from linkwork.io.dxf import CAP, PURPOSE, draw_plan, draw_positions, draw_scheme
from linkwork.io.dxf_sheet import (
    CAPACITY,
    LABEL,
    SMALLEST,
    THIN,
    GostSheet,
    SheetDrawing,
    TitleBlock,
    add_text,
    nice_up,
    number,
    reduction,
)
from linkwork.lang import t
from linkwork.optional import require
from linkwork.scene.geometry import text_size
from linkwork.scene.style import FORCES
from linkwork.spec.reader import described

if TYPE_CHECKING:
    from linkwork.kinetostatics.force_polygons import ForcePlans
    from linkwork.kinetostatics.zhukovsky import Lever
    from linkwork.machine.steady_cycle import Dynamics
    from linkwork.motion.kinematic_analysis import Kinematics


def _metres(lang: str) -> str:
    return t("sheet.m_per_mm", lang)


def scheme_drawing(
    title: str, draw: Callable[..., np.ndarray], extent: np.ndarray, lang: str, em: float
) -> SheetDrawing:
    """A drawing of a scheme of ``extent`` (m, ``[x0, y0, x1, y1]``) drawn by ``draw(layout, mm=, em=)`` at the
    largest reduction of ГОСТ 2.302 that fits; its labels :data:`LABEL` mm high, or lower, down to
    :data:`SMALLEST`, where the reduction draws the font size ``em`` (m) their places were found for smaller."""
    span = np.asarray(extent[2:] - extent[:2], dtype=float)
    drawing = SheetDrawing(title, lambda layout, w, h: (np.zeros(4), ""), big=True)

    def fit(layout: Any, w: float, h: float) -> tuple[np.ndarray, str]:
        n = reduction(max(span[0] / w, span[1] / h) * 1.08)
        size = min(LABEL, max(SMALLEST, CAP * em * 1000.0 / n))  # the labels as large as their places allow
        box = draw(layout, mm=1000.0 / n, em=size / CAP)
        drawing.scale = f"1:{number(n, lang)}"
        return box, f"μl = {number(n / 1000, lang)} {_metres(lang)}"

    drawing.draw = fit
    return drawing


def _fitted(
    build: Callable[[float], Any], extent: Callable[[Any], np.ndarray], start: float, w: float, h: float
) -> Any:
    """The scene ``build(scale)`` at the least scale of the 1-2-2.5-5 series (the largest drawing) whose
    ``extent`` fits ``w`` x ``h`` mm, searched from ``start``."""
    scale = nice_up(start)
    scene = build(scale)
    best = None
    for _ in range(12):
        ratio = _ratio(extent(scene), w, h)
        if ratio <= 1:
            best = scene
            smaller = nice_up(scale * ratio * 1.01)
            if smaller >= scale:
                return scene
            scale = smaller
        else:
            if best is not None:
                return best
            scale = nice_up(scale * ratio * 1.01)
        scene = build(scale)
    return best if best is not None else scene


def _ratio(box: np.ndarray, w: float, h: float) -> float:
    return float(max((box[2] - box[0]) / w, (box[3] - box[1]) / h))


def plan_drawing(kin: Kinematics, index: int, kind: str, title: str, lang: str) -> SheetDrawing:
    """The velocity (``kind`` ``"velocity"``) or acceleration plan of sample ``index`` of ``kin``."""
    from linkwork.motion.plans import plan_series
    from linkwork.scene.plans import plan_scale, plan_scene

    series = plan_series(kin)[0 if kind == "velocity" else 1]
    valid = np.asarray(kin.valid_all[0])

    def fit(layout: Any, w: float, h: float) -> tuple[np.ndarray, str]:
        def build(scale: float) -> Any:
            return plan_scene(series, [index], scale=scale, em=LABEL / CAP, valid=valid, lang=lang)

        scene = _fitted(build, lambda s: s.extent(0), plan_scale(series, [index]), w, h)
        box = draw_plan(layout, scene, 0)
        unit = t(f"plan.unit.{kind}", lang)
        return box, f"{scene.symbol} = {number(scene.scale, lang)} {unit}"

    return SheetDrawing(title, fit)


def force_plan_drawing(plans: ForcePlans, group: int, index: int, title: str, lang: str) -> SheetDrawing:
    """The force plan of the ``group``-th group of ``plans`` at sample ``index``."""
    from linkwork.io.dxf_forces import _draw, _short
    from linkwork.scene.force_plans import force_plan_scene

    g = plans.groups[group]
    angle = float(plans.forces.angles[index])

    def fit(layout: Any, w: float, h: float) -> tuple[np.ndarray, str]:
        def build(scale: float) -> Any:
            return force_plan_scene(g, index, lang=lang, scale=scale, em=LABEL / CAP, angle=angle)

        scene = _fitted(build, lambda s: s.extent(), g.scale(index), w, h - 2 * LABEL)
        _draw(layout, scene, np.zeros(2))
        _short(layout, scene, np.zeros(2), lang, width=0.85 * (w - 2.0), em=SMALLEST / CAP)  # room for the font
        return scene.extent(), f"μF = {number(scene.scale, lang)} {t('sheet.n_per_mm', lang)}"

    return SheetDrawing(title, fit)


def lever_drawing(lv: Lever, kin: Kinematics, index: int, title: str, lang: str) -> SheetDrawing:
    """Zhukovsky's lever at sample ``index`` of ``kin``: the turned velocity plan at a scale μv that fits."""
    from linkwork.io.dxf_forces import _draw, _short
    from linkwork.motion.plans import plan_series
    from linkwork.scene.force_plans import lever_scene
    from linkwork.scene.plans import plan_scale

    series = plan_series(kin)[0]

    def fit(layout: Any, w: float, h: float) -> tuple[np.ndarray, str]:
        first = lever_scene(lv, series, index, lang=lang, em=LABEL / CAP)
        ratio = first.scale / first.plan_scale  # the forces shrink with the plan: (N/mm) / ((m/s)/mm)

        def build(scale: float) -> Any:
            return lever_scene(
                lv, series, index, lang=lang, em=LABEL / CAP, plan_scale=scale, scale=nice_up(ratio * scale)
            )

        scene = _fitted(build, lambda s: s.extent(), plan_scale(series, [index]), w, h - 2 * LABEL)
        _draw(layout, scene, np.zeros(2))
        _short(layout, scene, np.zeros(2), lang, width=0.85 * (w - 2.0), em=SMALLEST / CAP)  # room for the font
        unit = t("plan.unit.velocity", lang)
        scales = f"μv = {number(scene.plan_scale, lang)} {unit};  μF = {number(scene.scale, lang)} "
        return scene.extent(), scales + t("sheet.n_per_mm", lang)

    return SheetDrawing(title, fit)


def legend_drawing(plans: ForcePlans, index: int, lang: str) -> SheetDrawing:
    """The legend of the force plans at sample ``index``: for each kind of arrow drawn, a stroke on its layer (the
    reactions read off a plan dashed, as drawn), its name and the names of the arrows of that kind (a process
    load also by the file's name of it), so that no meaning rests on colour alone."""
    from linkwork.io.dxf import _head
    from linkwork.lang import t as text
    from linkwork.scene.force_plans import FORCE_KINDS, force_plan_scene

    names: dict[tuple[str, bool], list[str]] = {}  # (kind, dashed): the arrows' names
    for g in plans.groups:
        for a in force_plan_scene(g, index, lang=lang).arrows:
            key = (a.kind, a.resultant or a.kind == "internal")
            if a.text and a.text not in names.setdefault(key, []):
                names[key].append(a.text)
    loads = [ld.name for ld in plans.forces.mechanism.loads if ld.kind == "process"]

    def fit(layout: Any, w: float, h: float) -> tuple[np.ndarray, str]:
        rows = [k for kind in FORCE_KINDS for k in ((kind, False), (kind, True)) if k in names]
        lines = []
        for row, (kind, dashed) in enumerate(rows):
            y = -row * 2.2 * LABEL
            layer = FORCES[kind].layer
            layout.add_line(
                (0.0, y),
                (15.0, y),
                dxfattribs={"layer": layer, **({"linetype": "DASHED", "lineweight": THIN} if dashed else {})},
            )
            _head(layout, np.array([0.0, y]), np.array([15.0, y]), 3.0, layer)
            what = text(f"force.{kind}", lang) + (f" ({', '.join(loads)})" if kind == "load" and loads else "")
            if dashed and kind != "internal":
                what += text("sheet.read_off", lang)
            lines.append(f"{what}: {', '.join(names[(kind, dashed)])}")
            add_text(layout, lines[-1], (20.0, y), LABEL, "LABELS", left=True)
        wide = max((text_size(line, LABEL / CAP)[0] for line in lines), default=0.0)
        return np.array([0.0, -(len(rows) - 1) * 2.2 * LABEL - LABEL, 20.0 + wide, LABEL]), ""

    return SheetDrawing(t("sheet.legend", lang), fit)


def kinematics_drawings(twelve: Kinematics, position: int, cycle: Kinematics, lang: str) -> list[SheetDrawing]:
    """The drawings of the kinematic analysis: the plan of the twelve positions, the velocity and acceleration
    plans of ``position`` and the kinematic scheme there (on a landscape sheet under the plan of positions)."""
    from linkwork.scene.positions import positions_scene
    from linkwork.scene.scheme import scheme_scene

    scene = positions_scene(twelve, cycle=cycle, lang=lang)
    at = scheme_scene(twelve, at=[position], cycle=cycle)
    where = t("at_position", lang, position=position)
    drawings = [
        scheme_drawing(
            t("sheet.positions", lang, count=len(twelve.angles)),
            lambda layout, mm, em: draw_positions(layout, scene, mm=mm, em=em),
            scene.extent(),
            lang,
            scene.scheme.em,
        ),
        plan_drawing(twelve, position, "velocity", t("sheet.velocity", lang) + where, lang),
        plan_drawing(twelve, position, "acceleration", t("sheet.acceleration", lang) + where, lang),
        scheme_drawing(
            t("sheet.scheme", lang) + where,
            lambda layout, mm, em: draw_scheme(layout, at, position, trajectories=False, mm=mm, em=em),
            at.extent(position),
            lang,
            at.em,
        ),
    ]
    return drawings


def kinetostatics_drawings(
    plans: ForcePlans, lv: Lever, index: int, named: str, cycle: Kinematics, lang: str
) -> list[SheetDrawing]:
    """The drawings of the kinetostatic analysis at sample ``index`` of ``plans`` (``named``: its position, for
    the titles): the scheme there, each group's force plan, Zhukovsky's lever, the legend of the arrows."""
    from linkwork.lang import group_label
    from linkwork.scene.scheme import scheme_scene

    kin = plans.forces.kinematics
    scene = scheme_scene(kin, at=[index], cycle=cycle)
    where = t("at_position", lang, position=named)
    drawings = [
        scheme_drawing(
            t("sheet.scheme", lang) + where,
            lambda layout, mm, em: draw_scheme(layout, scene, index, trajectories=False, mm=mm, em=em),
            scene.extent(index),
            lang,
            scene.em,
        )
    ]
    for j, g in enumerate(plans.groups):
        label = group_label(g.label, lang)
        title = t("forceplans.driving", lang, group=label) if g.balancing is not None else label
        drawings.append(force_plan_drawing(plans, j, index, t("sheet.force_plan", lang, group=title), lang))
    drawings.append(lever_drawing(lv, kin, index, t("sheet.lever", lang), lang))
    drawings.append(legend_drawing(plans, index, lang))
    return drawings


def _titled(block: TitleBlock, name: str, what: str) -> TitleBlock:
    """``block`` with graph 1 filled: the file's title, else the mechanism's name, and the sheet's content."""
    import dataclasses

    return dataclasses.replace(block, title=f"{block.title or name}. {what}")


def sheet_options(mech: Any, given: Mapping[str, str] | None = None) -> tuple[str, TitleBlock]:
    """The format and the title block of the sheets of ``mech``: ``given``'s ``sheet`` and title block fields (those
    of ``linkwork analyze --sheet --title-block``) over its file's ``drawing.sheet`` and ``drawing.title_block``
    (A1 and empty fields where neither gives one)."""
    spec = described(mech.description)
    drawing = spec.drawing if spec is not None else None
    fields = {**(drawing.title_block.model_dump() if drawing is not None else {}), **(given or {})}
    sheet = fields.pop("sheet", drawing.sheet if drawing is not None else "A1")
    return sheet, TitleBlock(**fields)


@dataclass(frozen=True)
class SheetAnalyses:
    """What the sheets of a course project draw: the kinematics at the twelve positions ``twelve`` and at the
    ``position`` of the plans, the ``cycle`` (for the paths), the force ``plans`` and the ``lever`` at their sample
    ``index`` (``named`` in the titles: the position of the force analysis) and, for a machine, its steady
    cycle's ``dynamics`` (:func:`linkwork.dynamics`)."""

    twelve: Kinematics
    position: int
    cycle: Kinematics
    plans: ForcePlans
    lever: Lever
    index: int
    named: str
    dynamics: Dynamics | None = None


def write_sheets(
    analyses: SheetAnalyses,
    folder: str | Path,
    lang: str = "en",
    fmt: str = "A1",
    block: TitleBlock | None = None,
    pdf: bool = True,
) -> list[Path]:
    """The sheets of the ``analyses`` on format ``fmt`` with the title block ``block``: the kinematics, the
    kinetostatics and (a machine's) the dynamics, ``sheet_1.dxf``, ``sheet_2.dxf``... into ``folder`` (on A1 and
    A2 one sheet each, on A3 four drawings a sheet, on A4 two: :data:`CAPACITY`), numbered in their title blocks,
    and (``pdf``) the same sheets drawn as the pages of ``sheets.pdf`` (:func:`linkwork.io.sheet_pdf.write_pdf`);
    returns their paths."""
    require("ezdxf", purpose=PURPOSE)
    block = block or TitleBlock()
    a = analyses
    name = a.twelve.mechanism.name
    parts = [
        (t("sheet.kinematics", lang), kinematics_drawings(a.twelve, a.position, a.cycle, lang)),
        (t("sheet.kinetostatics", lang), kinetostatics_drawings(a.plans, a.lever, a.index, a.named, a.cycle, lang)),
    ]
    if a.dynamics is not None:
        from linkwork.io.dxf_dynamics import dynamics_drawings

        parts.append((t("sheet.dynamics", lang), dynamics_drawings(a.dynamics, lang)))
    pages = [(what, d[k : k + CAPACITY[fmt]]) for what, d in parts for k in range(0, len(d), CAPACITY[fmt])]
    sheets, out = [], []
    for number_, (what, drawings) in enumerate(pages, start=1):
        sheet = GostSheet(fmt, _titled(block, name, what), number_, len(pages), lang)
        sheet.place(drawings)
        sheets.append(sheet)
        out.append(sheet.save(Path(folder) / f"sheet_{number_}.dxf"))
    if pdf:
        from linkwork.io.sheet_pdf import write_pdf

        out.append(write_pdf(sheets, Path(folder) / "sheets.pdf"))
    return out
