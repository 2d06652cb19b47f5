"""Force plans and Zhukovsky's lever drawn with matplotlib from their scenes (:mod:`linkwork.scene.force_plans`).

:func:`force_plans_figure`: the force plan of every group at one position, a panel each (the groups in the
order the graphical method takes them, the driving link last), each to its scale μF.  :func:`lever_figure`:
the lever at the same position.  Each arrow is a line whose ``gid`` is ``"kind:name"`` (tests read them
back); a reaction read off a plan is dashed.
"""

from __future__ import annotations

import textwrap
from typing import TYPE_CHECKING

import numpy as np

from linkwork.figures.plans import LEGEND, _columns, _head
from linkwork.figures.sheet import Sheet, add_line, mathtext, numbers, room, sheet, where
from linkwork.lang import group_label, t
from linkwork.scene.force_plans import FORCE_KINDS, SMALL, ForceScene, force_plan_scene, lever_scene, short_note
from linkwork.scene.style import FORCES, TEXT

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from linkwork.kinetostatics.force_polygons import ForcePlans
    from linkwork.kinetostatics.reaction_forces import Forces
    from linkwork.kinetostatics.zhukovsky import Lever
    from linkwork.motion.kinematic_analysis import Kinematics


def draw_forces(sh: Sheet, scene: ForceScene) -> None:
    """The lines, arrows, dots and names of a force scene."""
    lever = FORCES["lever"]
    for s, e in scene.lines:
        add_line(sh.ax, [s[0], e[0]], [s[1], e[1]], color=lever.colour, lw=lever.width, zorder=2)
    for a in scene.arrows:
        style = FORCES.get(a.kind, FORCES["reaction"])
        dash = SECOND if a.second else (0, (4.0, 2.0)) if a.resultant or style.dash else "solid"
        line = add_line(
            sh.ax,
            [a.start[0], a.end[0]],
            [a.start[1], a.end[1]],
            color=style.colour,
            lw=style.width * (0.8 if a.resultant else 1.0),
            ls=dash,
            zorder=3,
        )
        line.set_gid(f"{a.kind}:{a.text}")
        _head(sh, a.start, a.end, 0.55 * scene.em, style.colour)
        if a.text and np.isfinite(a.centre).all():
            sh.ax.text(
                a.centre[0],
                a.centre[1],
                a.tex,
                ha="center",
                va="center",
                zorder=5,
                fontsize=sh.font(scene.em),
                color=style.colour,
            )
    if len(scene.dots):
        sh.ax.plot(scene.dots[:, 0], scene.dots[:, 1], "o", color="black", ms=2.0, zorder=4)
    for text, c in zip(scene.dot_text, scene.dot_centres, strict=True):
        if text and np.isfinite(c).all():
            sh.ax.text(
                c[0], c[1], text, ha="center", va="center", zorder=5, fontsize=sh.font(scene.em), color=TEXT["point"]
            )


#: The line of an arrow drawn to a lever's second scale μF2: dash-dotted.
SECOND = (0, (6.0, 2.0, 1.0, 2.0))


def _legend(fig: Figure, kinds: list[str], lang: str, seconds: dict[str, str] | None = None) -> None:
    """The kinds of arrow under the figure; a kind drawn to a lever's scale of its own (``seconds``: the kind's
    scale, or the words for each cell's) dash-dotted, with it."""
    from matplotlib.lines import Line2D

    if not kinds:
        return
    names = [t(f"force.{k}", lang) for k in kinds]
    handles = [Line2D([], [], color=FORCES[k].colour, lw=FORCES[k].width) for k in kinds]
    for kind, scale in (seconds or {}).items():
        names.append(f"{t(f'force.{kind}', lang)}, {scale}")
        handles.append(Line2D([], [], color=FORCES[kind].colour, lw=FORCES[kind].width, ls=SECOND))
    columns = _columns(names, 0.9 * fig.get_figwidth() * 72)
    fig.legend(
        handles,
        names,
        loc="lower center",
        ncol=min(columns, len(kinds)),
        fontsize=LEGEND,
        frameon=False,
        handlelength=2.2,
        columnspacing=1.2,
    )


def force_plans_figure(plans: ForcePlans, index: int, position: int | str | None = None, lang: str = "en") -> Figure:
    """The force plan of every group of ``plans`` at sample ``index`` (``position``: its number, for the title),
    a panel each, the texts in ``lang``."""
    from matplotlib.figure import Figure

    angle = float(plans.forces.angles[index])
    cell = 3.6  # inches of each panel
    scenes = []
    for g in plans.groups:  # the names 8 points high whatever the plan's size
        rough = force_plan_scene(g, index, lang=lang, angle=angle)
        span = float(np.max(rough.extent()[2:] - rough.extent()[:2]))
        scenes.append(force_plan_scene(g, index, lang=lang, angle=angle, em=8.0 * span / (0.8 * cell * 72)))
    cols = 2 if len(scenes) > 1 else 1
    rows = -(-len(scenes) // cols)
    kinds = [k for k in FORCE_KINDS if any(k in s.kinds() for s in scenes)]
    legend = -(-len(kinds) // 2) * 0.22 + 0.2
    titles = []
    for g, scene in zip(plans.groups, scenes, strict=True):
        label = group_label(g.label, lang)
        if g.balancing is not None:
            label = t("forceplans.driving", lang, group=label)
        title = t("forceplans.cell", lang, group=label, scale=f"{scene.scale:g}")
        title += "" if g.solved else "\n" + t("forceplans.not_solved", lang)
        if not scene.arrows:  # nothing finite to draw
            title += "\n" + t("forceplans.singular", lang)
        note = short_note(scene, lang)
        if note:  # the names of the arrows too short to carry them, under the group's title
            title += "\n" + "\n".join(mathtext(line) for line in textwrap.wrap(note, 44))  # Φ₆ as the labels
        titles.append(title)
    lines = max(title.count("\n") + 1 for title in titles)
    gap = 0.18 * lines  # inches of a panel's title
    fig = Figure(figsize=(cols * cell + 0.4, rows * (cell + gap + 0.3) + 0.7 + legend))
    height = fig.get_figheight()
    grid = fig.add_gridspec(
        rows,
        cols,
        left=0.03,
        right=0.97,
        top=1 - (0.7 + gap) / height,
        bottom=(legend + 0.1) / height,
        hspace=(gap + 0.3) / cell,
        wspace=0.1,
    )
    for j, (scene, title) in enumerate(zip(scenes, titles, strict=True)):
        ax = fig.add_subplot(grid[j // cols, j % cols])
        sh = sheet(scene.extent(), ax=ax)
        draw_forces(sh, scene)
        ax.set_title(title, fontsize=9)
    name = plans.forces.mechanism.name
    fig.suptitle(f"{t('forceplans.title', lang, name=name)}\n{where(angle, position, lang)}", fontsize=11)
    _legend(fig, kinds, lang)
    return fig


def lever_figure(lv: Lever, kin: Kinematics, index: int, position: int | str | None = None, lang: str = "en") -> Figure:
    """Zhukovsky's lever ``lv`` of the kinematics ``kin`` (the same samples) at sample ``index``, the texts in
    ``lang``."""
    from linkwork.motion.plans import plan_series

    scene = lever_scene(lv, plan_series(kin)[0], index, lang=lang)
    kinds = [k for k in scene.kinds() if any(a.kind == k and not a.second for a in scene.arrows)]  # solid ones
    rows = -(-(len(kinds) + len(scene.second_scales)) // 2)
    moment = float(lv.balancing[0, index])
    name = kin.mechanism.name
    note = "\n".join(textwrap.wrap(t("lever.scale", lang, plan=f"{scene.plan_scale:g}", scale=f"{scene.scale:g}"), 64))
    if scene.second_scales:
        size = f"{SMALL * scene.em:.1f}"
        second = t("lever.second_note", lang, size=size, scales=scene.second_note(lang))
        note += "\n" + "\n".join(textwrap.wrap(second, 64))
    note += "\n" + t("lever.moment", lang, moment=f"{moment:.6g}")
    left = short_note(scene, lang)
    if left:  # the forces too short to draw at this scale, with their values
        note += "\n" + "\n".join(mathtext(line) for line in textwrap.wrap(left, 64))  # Φ₆, G₁ as the labels
    angle = float(kin.angles[index])
    title = f"{t('lever.title', lang, name=name)}\n{where(angle, position, lang)}\n{note}"
    top = max(1.1, 0.3 + 0.17 * (title.count("\n") + 1))  # inches: the title's lines
    width, height = room(scene.extent(), scene.lines.reshape(-1, 2), (5.6, 6.0))
    sh = sheet(scene.extent(), top=top, bottom=0.3 + 0.24 * rows, width=width, height=height + top - 1.1, least=5.6)
    draw_forces(sh, scene)
    sh.ax.set_title(numbers(title, lang), fontsize=9)
    _legend(sh.fig, kinds, lang, scene.kind_scales(lang))
    return sh.fig


def force_figures(f: Forces, index: int, position: int | None = None, lang: str = "en") -> tuple[Figure, Figure]:
    """The force plans and the lever of the kinetostatic result ``f`` at sample ``index``."""
    from linkwork.kinetostatics.force_polygons import force_plans
    from linkwork.kinetostatics.zhukovsky import lever

    return (
        force_plans_figure(force_plans(f), index, position, lang),
        lever_figure(lever(f), f.kinematics, index, position, lang),
    )


def lever_sheet(lv: Lever, kin: Kinematics, lang: str = "en") -> Figure:
    """Zhukovsky's lever ``lv`` at every sample of ``kin`` (the twelve positions, position 0 first) on one sheet, to
    one velocity scale, each with its force scale and its balancing moment; the texts in ``lang``."""
    from matplotlib.figure import Figure

    from linkwork.motion.plans import plan_series

    velocity = plan_series(kin)[0]
    count = len(kin.angles)
    first = [lever_scene(lv, velocity, k, lang=lang) for k in range(count)]
    plan_scale = max(s.plan_scale for s in first)
    cols, rows, cell = 4, -(-count // 4), 2.6
    rough = [lever_scene(lv, velocity, k, lang=lang, plan_scale=plan_scale) for k in range(count)]
    span = max(float(np.max(s.extent()[2:] - s.extent()[:2])) for s in rough)
    em = 7.0 * span / (cell * 72 / 1.2)
    scenes = [lever_scene(lv, velocity, k, lang=lang, plan_scale=plan_scale, em=em) for k in range(count)]
    top = 0.75 + (0.15 if any(s.second_scales for s in scenes) else 0.0)  # inches: a cell's title of two lines
    fig = Figure(figsize=(11.0, 2.9 * rows + 0.55 + top))
    height = fig.get_figheight()
    grid = fig.add_gridspec(
        rows, cols, left=0.02, right=0.98, top=1 - top / height, bottom=0.75 / height, hspace=0.3, wspace=0.08
    )
    boxes = np.array([s.extent() for s in scenes])
    half = np.max(boxes[:, 2:] - boxes[:, :2], axis=0) / 2
    for k, scene in enumerate(scenes):
        ax = fig.add_subplot(grid[k // cols, k % cols])
        centre = (boxes[k, :2] + boxes[k, 2:]) / 2
        draw_forces(sheet(np.concatenate([centre - half, centre + half]), ax=ax), scene)
        moment, scale = f"{float(lv.balancing[0, k]):.4g}", f"{scene.scale:g}"
        title = t("levers.cell", lang, position=k, moment=moment, scale=scale)
        title += f"\n{scene.second_note(lang)}" if scene.second_scales else ""
        ax.set_title(numbers(title, lang), fontsize=8)
    note = t("levers.scale", lang, plan=f"{plan_scale:g}")
    fig.suptitle(numbers(f"{t('levers.title', lang, name=kin.mechanism.name, count=count)}\n{note}", lang), fontsize=10)
    kinds = [k for k in FORCE_KINDS if any(k in s.kinds() for s in scenes)]
    seconds = {k: t("levers.second", lang) for s in scenes for k, _ in s.second_scales}
    _legend(fig, kinds, lang, seconds)
    return fig


def force_plan_sheet(plans: ForcePlans, group: int, lang: str = "en") -> Figure:
    """The force plan of group ``group`` (its place in ``plans.groups``) at every sample of ``plans`` (the twelve
    positions, position 0 first) on one sheet, each to its own scale μF, stated above it; the texts in ``lang``."""
    from matplotlib.figure import Figure

    from linkwork.units import turn_deg

    g = plans.groups[group]
    angles = plans.forces.angles
    count = len(angles)
    cols, rows, cell = 4, -(-count // 4), 2.6
    scenes = []
    for k in range(count):  # the names 7 points high whatever each plan's size
        rough = force_plan_scene(g, k, lang=lang, angle=float(angles[k]))
        span = float(np.max(rough.extent()[2:] - rough.extent()[:2]))
        scenes.append(force_plan_scene(g, k, lang=lang, angle=float(angles[k]), em=7.0 * span / (0.8 * cell * 72)))
    fig = Figure(figsize=(11.0, 3.1 * rows + 1.4))
    height = fig.get_figheight()
    grid = fig.add_gridspec(
        rows, cols, left=0.02, right=0.98, top=1 - 0.8 / height, bottom=0.75 / height, hspace=0.45, wspace=0.08
    )
    for k, scene in enumerate(scenes):
        ax = fig.add_subplot(grid[k // cols, k % cols])
        draw_forces(sheet(scene.extent(), ax=ax), scene)
        title = t("plans.cell", lang, position=k, angle=f"{turn_deg(angles[k], 0):.0f}")
        title += f"\nμF = {scene.scale:g} {t('forceplans.unit', lang)}" if scene.arrows else ""
        title += "" if scene.arrows else "\n" + t("forceplans.singular", lang)  # nothing finite to draw
        ax.set_title(title, fontsize=8)
    label = group_label(g.label, lang)
    if g.balancing is not None:
        label = t("forceplans.driving", lang, group=label)
    name = plans.forces.mechanism.name
    fig.suptitle(t("forceplans.sheet", lang, name=name, group=label, count=count), fontsize=10)
    kinds = [k for k in FORCE_KINDS if any(k in s.kinds() for s in scenes)]
    _legend(fig, kinds, lang)
    return fig
