"""Velocity and acceleration plans drawn with matplotlib from their scenes (:mod:`linkwork.scene.plans`).

The drawing is in millimetres of the sheet: a vector ``u`` of the plan is drawn ``u / scale`` mm long
(``scale`` in units per mm, written under the plan as mu_v or mu_a).  The pole ``p`` is at the origin;
every point's absolute vector ends at its lower-case letter; the relative vectors of the construction
(rotation, normal and tangential, transport, Coriolis, sliding) are drawn between plan points in their
own styles, named in a legend.  Each drawn vector is a line whose ``gid`` is ``"kind:start->end"``
(tests read them back).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from linkwork.figures.sheet import Sheet, add_line, add_patch, dashes, mathtext, room, sheet, text_width, where
from linkwork.lang import t
from linkwork.motion.kinematic_analysis import kinematics
from linkwork.motion.plans import plan_series
from linkwork.scene.plans import KINDS, PlanScene, kind_name, plan_scene
from linkwork.scene.positions import COUNT, position_angles
from linkwork.scene.style import TEXT, VECTORS
from linkwork.units import turn_deg

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from linkwork.motion.kinematic_analysis import Kinematics
    from linkwork.motion.plans import Plan


def velocity_plan(
    kin: Kinematics, index: int, ax: Axes | None = None, position: int | str | None = None, lang: str = "en"
) -> Figure:
    """The velocity plan of sample ``index`` of a kinematics result (``position``: its number, for the title;
    ``lang``: the language of its texts, :mod:`linkwork.lang`).

    Parameters
    ----------
    kin : Kinematics
        A kinematics result (:func:`linkwork.kinematics`).
    index : int
        The sample drawn, an index of ``kin``'s angles.
    ax : matplotlib.axes.Axes, optional
        The axes to draw on; default a figure of its own.
    position : int or str, optional
        The number of the position the sample is, for the title.
    lang : str, default "en"
        The language of the texts, ``"en"`` or ``"ru"`` (:mod:`linkwork.lang`).
    """
    return _one(kin, index, "velocity", ax, position, lang)


def acceleration_plan(
    kin: Kinematics, index: int, ax: Axes | None = None, position: int | str | None = None, lang: str = "en"
) -> Figure:
    """The acceleration plan of sample ``index`` of a kinematics result (``position``: its number, for the
    title; ``lang``: the language of its texts, :mod:`linkwork.lang`).

    Parameters
    ----------
    kin : Kinematics
        A kinematics result (:func:`linkwork.kinematics`).
    index : int
        The sample drawn, an index of ``kin``'s angles.
    ax : matplotlib.axes.Axes, optional
        The axes to draw on; default a figure of its own.
    position : int or str, optional
        The number of the position the sample is, for the title.
    lang : str, default "en"
        The language of the texts, ``"en"`` or ``"ru"`` (:mod:`linkwork.lang`).
    """
    return _one(kin, index, "acceleration", ax, position, lang)


def _one(kin: Kinematics, index: int, kind: str, ax: Axes | None, position: int | str | None, lang: str) -> Figure:
    i = int(index) % len(kin.angles)
    series = plan_series(kin)[0 if kind == "velocity" else 1]
    scene = plan_scene(series, [i], valid=np.asarray(kin.valid_all[0]), lang=lang)
    return render_plan(scene, 0, ax=ax, title=_title(scene, 0, kin.mechanism.name, position, lang), lang=lang)


def draw_plan(plan: Plan, ax: Axes | None = None, lang: str = "en") -> Figure:
    """Draw a :class:`~linkwork.motion.plans.Plan` (one position's plan as data), its texts in ``lang``;
    returns the matplotlib Figure.

    Parameters
    ----------
    plan : Plan
        One position's plan as data (:mod:`linkwork.motion.plans`).
    ax : matplotlib.axes.Axes, optional
        The axes to draw on; default a figure of its own.
    lang : str, default "en"
        The language of the texts, ``"en"`` or ``"ru"`` (:mod:`linkwork.lang`).
    """
    from linkwork.motion.plans import PlanEdge, PlanSeries

    labels = list(plan.points)
    for v in plan.vectors:
        labels += [lab for lab in (v.start, v.end) if lab not in labels]
    values = np.full((1, 1, len(labels), 2), np.nan)
    known = {lab: np.asarray(v, dtype=float) for lab, v in plan.points.items()}
    known.setdefault("p", np.zeros(2))
    for v in plan.vectors:
        if v.start in known and v.end not in known:
            known[v.end] = known[v.start] + np.asarray(v.vector)
    for j, lab in enumerate(labels):
        values[0, 0, j] = known.get(lab, np.nan)
    edges = tuple(PlanEdge(v.start, v.end, v.kind, v.group, v.about) for v in plan.vectors)
    vectors = np.array([[[v.vector for v in plan.vectors]]], dtype=float).reshape(1, 1, len(edges), 2)
    points = tuple(plan.points) if "p" in plan.points else ("p", *plan.points)
    series = PlanSeries(plan.kind, np.array([plan.angle]), points, tuple(labels), edges, values, vectors)
    scene = plan_scene(series, [0], scale=plan.scale, lang=lang)
    return render_plan(scene, 0, ax=ax, title=_title(scene, 0, "", None, lang), lang=lang)


def _title(scene: PlanScene, index: int, name: str, position: int | str | None, lang: str) -> str:
    head = f"{name}: " if name else ""
    return f"{head}{t(f'plan.{scene.kind}', lang)}\n{where(float(scene.angles[index]), position, lang)}"


def render_plan(
    scene: PlanScene, index: int, ax: Axes | None = None, title: str = "", legend: bool = True, lang: str = "en"
) -> Figure:
    """Draw position ``index`` of a plan's scene with its scale and (``legend``) the legend of its vectors' kinds,
    the texts in ``lang``."""
    kinds = scene.kinds(index)
    names = [kind_name(k, scene.kind, lang) for k in kinds]
    columns = _columns(names, WIDE * 72)
    rows = -(-len(kinds) // columns) if legend else 0
    width, height = _room(scene, index)
    sh = sheet(scene.extent(index), top=0.8, bottom=0.25 + 0.24 * rows, width=width, height=height, ax=ax, least=WIDE)
    draw_vectors(sh, scene, index)
    note = scene.scale_note(lang)
    if title:
        last = f"{title.rsplit(chr(10), 1)[-1]};  {note}"
        fits = text_width(last, 10) <= 0.95 * sh.fig.get_figwidth() * 72
        sh.ax.set_title(f"{title}{';  ' if fits else chr(10)}{note}", fontsize=10)  # the note on a line of its own
    else:
        sh.ax.set_title(note, fontsize=9)
    if legend and kinds and ax is None:
        _legend(sh, kinds, names, columns)
    return sh.fig


#: The height of a plan's drawing, inches (larger for a thin plan: :func:`~linkwork.figures.sheet.room`).
HIGH = 6.0


def _room(scene: PlanScene, index: int) -> tuple[float, float]:
    """The widest and tallest (inches) the drawing of the plan of position ``index`` may take
    (:func:`~linkwork.figures.sheet.room` of the ends of its vectors)."""
    return room(scene.extent(index), scene.ends[index].reshape(-1, 2), (WIDE, HIGH))


def draw_vectors(sh: Sheet, scene: PlanScene, index: int) -> None:
    """The arrows, dots and labels of position ``index``."""
    names = scene.names
    head = 0.55 * scene.em
    shown = set(scene.drawn(index))
    for e, arrow in enumerate(scene.arrows):
        start, end = scene.ends[index, e]
        if not np.isfinite(scene.ends[index, e]).all():
            continue
        style = VECTORS.get(arrow.kind, VECTORS["rotation"])
        line = add_line(
            sh.ax,
            [start[0], end[0]],
            [start[1], end[1]],
            color=style.colour,
            lw=style.width,
            ls=dashes(style),
            zorder=3,
        )
        line.set_gid(f"{arrow.kind}:{names[arrow.start]}->{names[arrow.end]}")  # of no length too: read back
        if e in shown:
            _head(sh, start, end, head, style.colour)
    pts = scene.points[index]
    shown = np.isfinite(pts).all(-1)
    sh.ax.plot(pts[shown, 0], pts[shown, 1], "o", color="black", ms=2.2, zorder=4)
    for j, text in enumerate(scene.text[index]):
        c = scene.centres[index, j]
        if text and np.isfinite(c).all():
            main = bool(scene.main[j])
            sh.ax.text(
                c[0],
                c[1],
                mathtext(text),
                ha="center",
                va="center",
                zorder=5,
                fontsize=sh.font(scene.em) * (1.0 if main else 0.8),
                color=TEXT["point" if main else "minor"],
                style="normal" if main else "italic",
            )


def _head(sh: Sheet, start: np.ndarray, end: np.ndarray, size: float, colour: str) -> None:
    """A filled arrowhead of ``size`` (mm of the sheet, at most 0.35 of the vector) at ``end``."""
    from matplotlib.patches import Polygon

    d = end - start
    length = float(np.hypot(*d))
    size = min(size, 0.35 * length)
    u = d / length
    w = np.array([-u[1], u[0]])
    tip = np.array([end, end - size * u + 0.3 * size * w, end - size * u - 0.3 * size * w])
    add_patch(sh.ax, Polygon(tip, closed=True, fc=colour, ec="none", lw=0, zorder=3))


#: Width of a plan's figure, inches; the size of the legend's text, points.
WIDE, LEGEND = 5.6, 8.5

#: Height of the points' letters on a sheet of the twelve plans, points (as large as a figure's legend: readable
#: on a printed A4 sheet).
SHEET_LETTERS = 9.0


def _columns(names: list[str], width: float) -> int:
    """The most columns, three at most, in which a legend of ``names`` is at most ``width`` points wide (its
    columns filled as matplotlib fills them: the first ones one longer)."""
    for columns in (3, 2):
        parts = np.array_split(np.array([text_width(n, LEGEND) for n in names] or [0.0]), columns)
        used = sum(float(p.max()) + 3.0 * LEGEND for p in parts if len(p)) + 1.2 * LEGEND * (len(parts) - 1)
        if used + 0.8 * LEGEND <= width:
            return columns
    return 1


def _legend(sh: Sheet, kinds: list[str], names: list[str], columns: int) -> None:
    """The kinds of vector under the figure, by their ``names``, in ``columns`` columns."""
    from matplotlib.lines import Line2D

    handles = [Line2D([], [], color=VECTORS[k].colour, lw=VECTORS[k].width, ls=dashes(VECTORS[k])) for k in kinds]
    sh.fig.legend(
        handles,
        names,
        loc="lower center",
        ncol=min(columns, len(kinds)),
        fontsize=LEGEND,
        frameon=False,
        handlelength=2.2,
        columnspacing=1.2,
    )


def plan_sheet(kin: Kinematics, kind: str = "velocity", count: int = COUNT, lang: str = "en") -> Figure:
    """The ``kind`` plans of all ``count`` positions on one sheet, to one scale (position 0 first), the texts in
    ``lang``.

    Parameters
    ----------
    kin : Kinematics
        A kinematics result (:func:`linkwork.kinematics`).
    kind : str, default "velocity"
        ``"velocity"`` or ``"acceleration"``.
    count : int, default 12
        Positions over the turn, from position 0.
    lang : str, default "en"
        The language of the texts, ``"en"`` or ``"ru"`` (:mod:`linkwork.lang`).
    """
    from matplotlib.figure import Figure

    mech = kin.mechanism
    positions = kinematics(mech, position_angles(mech, count))
    series = plan_series(positions)[0 if kind == "velocity" else 1]
    valid = np.asarray(positions.valid_all[0])
    cols, rows = 4, -(-count // 4)
    cell = 2.6  # inches of each plan's drawing
    rough = plan_scene(series, list(range(count)), valid=valid)
    ends = rough.ends.reshape(count, -1, 2)
    span = np.nanmax(np.nanmax(ends, axis=1) - np.nanmin(ends, axis=1))
    em = SHEET_LETTERS / (cell * 72 / (1.4 * span))  # letters of SHEET_LETTERS points on the plans drawn that large
    scene = plan_scene(series, list(range(count)), scale=rough.scale, valid=valid, em=em, lang=lang)
    fig = Figure(figsize=(11.0, 2.9 * rows + 0.9))
    grid = fig.add_gridspec(
        rows,
        cols,
        left=0.02,
        right=0.98,
        top=1 - 0.55 / fig.get_figheight(),
        bottom=0.5 / fig.get_figheight(),
        hspace=0.3,
        wspace=0.08,
    )
    boxes = np.array([scene.extent(k) for k in range(count)])
    half = np.max(boxes[:, 2:] - boxes[:, :2], axis=0) / 2  # one size for all: one scale on the sheet
    for k in range(count):
        ax = fig.add_subplot(grid[k // cols, k % cols])
        centre = (boxes[k, :2] + boxes[k, 2:]) / 2
        sh = sheet(np.concatenate([centre - half, centre + half]), ax=ax)
        draw_vectors(sh, scene, k)
        ax.set_title(t("plans.cell", lang, position=k, angle=f"{turn_deg(scene.angles[k], 0):.0f}"), fontsize=8)
    fig.suptitle(f"{t(f'plans.{kind}', lang, name=mech.name, count=count)};  {scene.scale_note(lang)}", fontsize=11)
    kinds = [k for k in KINDS if any(k in scene.kinds(i) for i in range(count))]
    names = [kind_name(k, kind, lang) for k in kinds]
    _legend(Sheet(fig, fig.axes[0], 1.0), kinds, names, _columns(names, fig.get_figwidth() * 72))
    return fig
