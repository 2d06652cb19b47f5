"""The kinematic scheme and the plan of positions, drawn with matplotlib from their scenes.

The scene (:mod:`linkwork.scene`) says what is drawn and where; this module only draws it: links as
bars and plates, pivots, supports and guides with their hatching, slider blocks, tools with their
working edges, markers, the labels where the scene placed them (their text as high as the scene says,
in the drawing's units), and a scale bar.  Every item's artist has the ``gid`` ``"kind:name"``
(``"pivot:B"``, ``"bar:rod"``), so that tests can read the drawing back.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

from linkwork.figures.sheet import (
    Sheet,
    add_line,
    add_patch,
    dashes,
    mathtext,
    numbers,
    round_length,
    sheet,
    text_width,
    where,
)
from linkwork.lang import t
from linkwork.motion.kinematic_analysis import kinematics
from linkwork.scene.positions import COUNT, PositionsScene, position_angles, positions_scene
from linkwork.scene.scheme import KINDS, Item, SchemeScene, scheme_scene
from linkwork.scene.style import SCHEME, TEXT
from linkwork.units import turn_deg

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from linkwork.motion.kinematic_analysis import Kinematics


def draw_scheme(
    kin: Kinematics,
    index: int = 0,
    ax: Axes | None = None,
    trajectories: bool = False,
    position: int | None = None,
    cycle: Kinematics | None = None,
    lang: str = "en",
) -> Figure:
    """The scheme at sample ``index`` of a kinematics result; returns the matplotlib Figure.

    With ``trajectories``, the paths of the points over the whole turn are drawn too; ``position`` (the
    number of the position the sample is) goes into the title; ``cycle``: a whole turn of the mechanism
    (see :func:`~linkwork.scene.scheme_scene`); ``lang``: the language of the texts (:mod:`linkwork.lang`).

    Parameters
    ----------
    kin : Kinematics
        A kinematics result (:func:`linkwork.kinematics`).
    index : int
        The sample drawn, an index of ``kin``'s angles.
    ax : matplotlib.axes.Axes, optional
        The axes to draw on; default a figure of its own.
    trajectories : bool, default False
        Also draw the paths of the points over the whole turn.
    position : int or str, optional
        The number of the position the sample is, for the title.
    cycle : Kinematics, optional
        A whole turn of the mechanism, for the trajectories and the drawing's extent.
    lang : str, default "en"
        The language of the texts, ``"en"`` or ``"ru"`` (:mod:`linkwork.lang`).
    """
    index = int(index) % len(kin.angles)
    scene = scheme_scene(kin, at=[index], cycle=cycle)
    title = f"{t('scheme.title', lang, name=scene.name)}\n{where(float(kin.angles[index]), position, lang)}"
    return render_scheme(scene, index, ax=ax, trajectories=trajectories, title=title, lang=lang)


def render_scheme(
    scene: SchemeScene,
    index: int,
    ax: Axes | None = None,
    trajectories: bool = False,
    title: str = "",
    lang: str = "en",
) -> Figure:
    """Draw sample ``index`` of a scheme's scene (with the trajectories of its points), a scale bar under it
    (its length in the units of ``lang``)."""
    box = scene.extent(index, paths=trajectories)
    bar = round_length(box[2] - box[0])
    box[1] -= 3.0 * scene.em  # room for the scale bar
    sh = sheet(box, ax=ax, top=0.7)
    if trajectories:
        draw_paths(sh, scene.paths)
    draw_items(sh, scene, index)
    draw_elements(sh, scene, index)
    draw_labels(sh, scene, index)
    scale_bar(sh, (box[0] + scene.em, box[1] + 1.2 * scene.em), bar, scene.em, lang)
    if title:
        sh.ax.set_title(title, fontsize=11)
    return sh.fig


def draw_paths(sh: Sheet, paths: np.ndarray) -> None:
    """Trajectories ``(A, Q, 2)`` as thin dashed lines."""
    style = SCHEME["path"]
    for q in range(paths.shape[1]):
        add_line(
            sh.ax,
            paths[:, q, 0],
            paths[:, q, 1],
            color=style.colour,
            lw=style.width,
            ls=dashes(style),
            zorder=KINDS.index("path"),
        )


def draw_items(
    sh: Sheet, scene: SchemeScene, index: int, frame: bool = True, kinds: tuple[str, ...] = KINDS, thin: float = 1.0
) -> None:
    """The items of ``kinds`` at sample ``index``, the frame's too if ``frame``; line widths and circles times
    ``thin``."""
    for it in scene.items:
        if it.kind == "path" or it.kind not in kinds or (it.link == 0 and not frame):
            continue
        xy = scene.placed(it, index)
        if np.isfinite(xy).all():
            draw_item(sh.ax, it, xy, thin)


def draw_elements(sh: Sheet, scene: SchemeScene, index: int) -> None:
    """The springs and dampers at sample ``index``, between their two points, under the links; each stroke's
    artist has the gid ``kind:name``."""
    z = 2 + KINDS.index("bar") * 0.1 - 0.05
    for element in scene.elements:
        style = SCHEME[element.kind]
        for xy in scene.element_strokes(element, index):
            if np.isfinite(xy).all():
                line = add_line(
                    sh.ax, xy[:, 0], xy[:, 1], color=style.colour, lw=style.width, zorder=z, solid_joinstyle="miter"
                )
                line.set_gid(f"{element.kind}:{element.name}")


def draw_item(ax: Axes, it: Item, xy: np.ndarray, thin: float = 1.0) -> Any:
    """One item at its global vertices ``xy`` ``(K, 2)``; returns its artist."""
    from matplotlib.colors import to_rgba
    from matplotlib.patches import Circle, Polygon

    style = SCHEME[it.kind]
    z = 2 + KINDS.index(it.kind) * 0.1
    face = to_rgba(style.fill, style.alpha) if style.fill and (thin == 1.0 or style.alpha == 1.0) else "none"
    artist: Any
    if it.radius:
        artist = add_patch(
            ax,
            Circle(
                tuple(xy[0]),
                it.radius * min(1.0, 0.3 + thin),
                fc=face,
                ec=style.colour,
                lw=style.width * thin,
                zorder=z,
            ),
        )
    elif it.closed:
        artist = add_patch(
            ax, Polygon(xy, closed=True, fc=face, ec=style.colour, lw=style.width * thin, zorder=z, joinstyle="round")
        )
    else:
        artist = add_line(
            ax,
            xy[:, 0],
            xy[:, 1],
            color=style.colour,
            lw=style.width * thin,
            ls=dashes(style),
            zorder=z,
            solid_capstyle="round",
        )
    artist.set_gid(f"{it.kind}:{it.name}")
    return artist


def draw_labels(sh: Sheet, scene: SchemeScene, index: int) -> None:
    """The labels of sample ``index`` where the scene placed them."""
    for lab in scene.labels:
        c = lab.centre[index]
        if np.isfinite(c).all():
            sh.ax.text(
                c[0],
                c[1],
                mathtext(lab.text),
                ha="center",
                va="center",
                fontsize=sh.font(scene.em),
                color=TEXT[lab.kind],
                zorder=5,
                gid=f"label:{lab.text}",
            )


def scale_bar(sh: Sheet, at: tuple[float, float], length: float, em: float, lang: str = "en") -> None:
    """A bar ``length`` (m) long from ``at``, with ticks at its ends and its length in mm beside it."""
    x, y = at
    ax = sh.ax
    ax.plot([x, x + length], [y, y], color="black", lw=1.0, zorder=5)
    for end in (x, x + length):
        ax.plot([end, end], [y - 0.25 * em, y + 0.25 * em], color="black", lw=1.0, zorder=5)
    ax.text(
        x + length + 0.5 * em,
        y,
        f"{1000 * length:g} {t('unit.mm', lang)}",
        ha="left",
        va="center",
        fontsize=0.8 * sh.font(em),
        zorder=5,
    )


def draw_positions(kin: Kinematics, count: int = COUNT, ax: Axes | None = None, lang: str = "en") -> Figure:
    """The plan of positions: the mechanism at ``count`` positions from position 0 (the working slider
    at the high end of its stroke), every ``360 / count`` degrees in the direction of rotation, overlaid
    thin, with the trajectories of its points over ``kin``'s samples and the position numbers at the
    crank pin and at the working point; the second extreme of the working member dashed where it is none of
    the positions, both extremes lettered, the crank's turns over the working and idle strokes marked at its
    pivot; the texts in ``lang``.

    Parameters
    ----------
    kin : Kinematics
        A kinematics result (:func:`linkwork.kinematics`).
    count : int, default 12
        Positions over the turn, from position 0.
    ax : matplotlib.axes.Axes, optional
        The axes to draw on; default a figure of its own.
    lang : str, default "en"
        The language of the texts, ``"en"`` or ``"ru"`` (:mod:`linkwork.lang`).
    """
    mech = kin.mechanism
    angles = position_angles(mech, count)
    scene = positions_scene(kinematics(mech, angles), cycle=kin, lang=lang)
    s = scene.scheme
    start = f"{turn_deg(angles[0]):.1f}"
    turn = t("positions.ccw" if mech.drive_speed[0] >= 0 else "positions.cw", lang, angle=numbers(start, lang))
    title = f"{t('positions.title', lang, name=mech.name, count=count)}\n{turn}"
    sh, box, bar = _overlay_sheet(scene, ax, title)
    for k in range(1, len(angles)):
        draw_items(sh, s, k, frame=False, kinds=("bar", "plate", "pivot"), thin=0.45)
    draw_labels(sh, s, 0)
    if len(scene.marks):
        sh.ax.plot(scene.marks[:, 0], scene.marks[:, 1], "o", color=TEXT["position"], ms=2.0, zorder=4)
    for leader in scene.leaders:
        sh.ax.plot(leader[:, 0], leader[:, 1], color=TEXT["position"], lw=0.4, zorder=4)
    _draw_extremes(sh, scene)
    for lab in (*scene.numbers, *scene.letters, *scene.strokes):
        c = lab.centre[0]
        sh.ax.text(
            c[0],
            c[1],
            mathtext(lab.text),
            ha="center",
            va="center",
            fontsize=0.85 * sh.font(s.em),
            color=TEXT["position"],
            zorder=5,
            gid=f"position:{lab.text}",
        )
    scale_bar(sh, (box[0] + s.em, box[1] + 1.2 * s.em), bar, s.em, lang)
    sh.ax.set_title(title, fontsize=TITLE)
    return sh.fig


#: The dashes of the second extreme's links where it is none of the positions, and of the idle stroke's arc.
EXTREME_DASH = (0, (5, 2))


def _draw_extremes(sh: Sheet, scene: PositionsScene) -> None:
    """The second extreme's links dashed (where it is a pose of its own) and the arcs of the working stroke (solid)
    and the idle one (dashed); gids ``extreme:kind:name`` and ``stroke:working``, ``stroke:idle``."""
    s = scene.scheme
    if scene.extreme >= scene.positions:
        for it in s.items:
            if it.link and it.kind in ("bar", "plate", "pivot"):
                xy = s.placed(it, scene.extreme)
                if np.isfinite(xy).all():
                    artist = draw_item(sh.ax, it, xy, thin=0.6)
                    artist.set_linestyle(EXTREME_DASH)
                    artist.set_gid(f"extreme:{it.kind}:{it.name}")
    for arc, kind, ls in zip(scene.arcs, ("working", "idle"), ("solid", EXTREME_DASH), strict=False):
        add_line(sh.ax, arc[:, 0], arc[:, 1], color=TEXT["position"], lw=1.0, ls=ls, zorder=4, gid=f"stroke:{kind}")


#: The size of a drawing's title, points.
TITLE = 11.0


def _overlay_sheet(scene: Any, ax: Axes | None, title: str = "") -> tuple[Any, np.ndarray, float]:
    """The sheet of a drawing of overlaid poses (the plan of positions, the limit positions), room for its scale
    bar below, with the trajectories and the first pose drawn: the sheet (wide enough for the lines of its
    ``title``), its box and the scale bar's length."""
    s = scene.scheme
    box = scene.extent()
    bar = round_length(box[2] - box[0])
    box[1] -= 3.0 * s.em
    least = max([5.0] + [text_width(line, TITLE) / 72 + 0.3 for line in title.split("\n")])
    sh = sheet(box, ax=ax, top=0.7, least=least)
    draw_paths(sh, s.paths)
    draw_items(sh, s, 0)
    return sh, box, bar


def draw_limits(kin: Kinematics, ax: Axes | None = None, lang: str = "en") -> Figure | None:
    """The working member's two limit positions over a whole turn ``kin`` (the low extreme whole, the high one
    thin), with the trajectories, the two lines of theta from the crank's pivot, its arc and value
    (:func:`~linkwork.scene.limits.limits_scene`); None where there are none.

    Parameters
    ----------
    kin : Kinematics
        A kinematics result (:func:`linkwork.kinematics`).
    ax : matplotlib.axes.Axes, optional
        The axes to draw on; default a figure of its own.
    lang : str, default "en"
        The language of the texts, ``"en"`` or ``"ru"`` (:mod:`linkwork.lang`).
    """
    from linkwork.scene.limits import limits_scene

    scene = limits_scene(kin, lang)
    if scene is None:
        return None
    s = scene.scheme
    k = (math.pi + scene.theta) / (math.pi - scene.theta)
    theta = numbers(f"{math.degrees(scene.theta):.2f}", lang)
    title = t("limits.title", lang, name=s.name, member=scene.who(lang), theta=theta, k=numbers(f"{k:.4f}", lang))
    sh, box, bar = _overlay_sheet(scene, ax, title)
    draw_items(sh, s, 1, frame=False, kinds=("bar", "plate", "pivot", "block", "tool"), thin=0.45)
    draw_labels(sh, s, 0)
    for ray in scene.rays:
        add_line(
            sh.ax,
            ray[:, 0],
            ray[:, 1],
            color=TEXT["position"],
            lw=0.8,
            ls=(0, (6, 2, 1, 2)),
            zorder=4,
            gid="limits:ray",
        )
    add_line(sh.ax, scene.arc[:, 0], scene.arc[:, 1], color=TEXT["position"], lw=1.0, zorder=4, gid="limits:arc")
    _draw_dimension(sh, list(scene.dimension), s.em)
    for swing in scene.swings:
        _draw_dimension(sh, list(swing.lines), s.em, gid="limits:swing")
    texts = [(scene.label, "limits:theta"), *((lab, f"limits:{lab.text}") for lab in scene.letters)]
    texts += [(scene.stroke, "limits:stroke")] if scene.stroke is not None else []
    texts += [(swing.label, "limits:swing") for swing in scene.swings]
    for lab, gid in texts:
        c = lab.centre[0]
        sh.ax.text(
            c[0],
            c[1],
            mathtext(lab.text),
            ha="center",
            va="center",
            fontsize=sh.font(s.em),
            color=TEXT["position"],
            zorder=5,
            gid=gid,
        )
    scale_bar(sh, (box[0] + s.em, box[1] + 1.2 * s.em), bar, s.em, lang)
    sh.ax.set_title(title, fontsize=TITLE)
    return sh.fig


def _draw_dimension(sh: Sheet, lines: list[np.ndarray], em: float, gid: str = "limits:dimension") -> None:
    """A dimension's extension lines and its dimension line (the last of ``lines``, polylines ``(K, 2)``: a
    straight line or an arc) with an arrowhead at each end along it, thin (gid ``gid``)."""
    from matplotlib.patches import Polygon

    for line in lines:
        add_line(sh.ax, line[:, 0], line[:, 1], color="black", lw=0.6, zorder=4, gid=gid)
    if len(lines):
        line = lines[-1]
        length = float(np.sum(np.hypot(*np.diff(line, axis=0).T)))
        size = min(0.8 * em, 0.3 * length)
        for tip, toward in ((line[0], line[1]), (line[-1], line[-2])):
            u = (toward - tip) / max(float(np.hypot(*(toward - tip))), 1e-300)
            w = np.array([-u[1], u[0]])
            head = np.array([tip, tip + size * u + 0.25 * size * w, tip + size * u - 0.25 * size * w])
            add_patch(sh.ax, Polygon(head, closed=True, fc="black", ec="none", zorder=4))
