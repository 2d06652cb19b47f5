"""The limit positions of the working member as a scene: the scheme at both extremes of its stroke (or swing)
and the angle theta between the crank's limit positions, marked at the crank's pivot.

At a limit position the output stands still; the crank turns by pi + theta from one to the other and by
pi - theta back, so the time ratio is K = (pi + theta) / (pi - theta).  Drawn: a ray from the pivot along the
crank at the low extreme and one against the crank at the high extreme (for a slider-crank, the lines O B1
and O B2 of the classical construction), the arc of theta between them and its value.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING

import numpy as np

from linkwork.lang import numbers, t
from linkwork.motion.analysis import Output, output_range, outputs, working
from linkwork.motion.kinematic_analysis import kinematics
from linkwork.scene.geometry import bounds, text_size
from linkwork.scene.labels import Obstacles, place_labels
from linkwork.scene.scheme import Label, SchemeScene, scheme_scene

if TYPE_CHECKING:
    from linkwork.motion.kinematic_analysis import Kinematics
    from linkwork.structure.model import Mechanism


@dataclass(frozen=True)
class Dimension:
    """A dimension of the drawing: its extension lines, then the dimension line (a straight one or an arc, an
    arrowhead at each of its ends), and its value.

    Attributes
    ----------
    lines : tuple of ndarray
        Polylines ``(K, 2)`` each (global, m), the dimension line last.
    label : Label
        The value (``ψ = 37.5°``) beside the dimension line's middle.
    """

    lines: tuple[np.ndarray, ...]
    label: Label


@dataclass(frozen=True)
class LimitsScene:
    """The two limit positions and theta.

    Attributes
    ----------
    scheme : SchemeScene
        The scheme at its two samples: the working member's low extreme (0) and high extreme (1).
    member : str
        The working member (a slider's joint, a rocker's link).
    rays : ndarray, shape (2, 2, 2)
        The two lines of theta from the crank's pivot (global, m).
    arc : ndarray, shape (K, 2)
        The arc of theta between them.
    theta : float
        The angle between the crank's limit positions, rad: |pi - the crank's turn between them|.
    turned : float
        The crank's turn from the low extreme to the high one (rad, in its direction).
    label : Label
        ``theta = ...°`` beside the arc (``centre`` of shape (1, 2)).
    letters : tuple of Label
        The crank pin and the working member's point lettered at both extremes: primed at the high one (position
        0 of the plan of positions, ``B′``), double-primed at the low one (``B″``).
    dimension : ndarray, shape (K, 2, 2)
        A slider's stroke H dimensioned: its two extension lines from the slider's point at the extremes, then
        the dimension line between them (arrowheads at its ends); none for a rocker.
    stroke : Label or None
        ``H = ... mm`` beside the dimension line.
    kind : str
        The working member's kind, ``"slider"`` or ``"rocker"`` (:class:`linkwork.motion.analysis.Output`).
    swings : tuple of Dimension
        Each rocker's swing ψ (a link pivoted on the frame that swings, the working member or not) dimensioned
        as an angle at its pivot: the extension lines along the rocker at its two extremes, the arc between them.
    """

    scheme: SchemeScene
    member: str
    rays: np.ndarray
    arc: np.ndarray
    theta: float
    turned: float
    label: Label
    letters: tuple[Label, ...] = ()
    dimension: np.ndarray = field(default_factory=lambda: np.zeros((0, 2, 2)))
    stroke: Label | None = None
    kind: str = "slider"
    swings: tuple[Dimension, ...] = ()

    def who(self, lang: str = "en") -> str:
        """The working member as the texts name it, in ``lang``: its kind in words and its name as the file
        writes it (``ползуна на направляющей guide_E``, ``коромысла rocker``)."""
        return t(f"limits.member.{self.kind}", lang, member=self.member)

    def extent(self) -> np.ndarray:
        """``[x0, y0, x1, y1]`` of everything drawn, m."""
        boxes = []
        for lab in self.texts():
            w, h = text_size(lab.text, self.scheme.em)
            c = lab.centre[0]
            boxes.append(np.array([c - [w / 2, h / 2], c + [w / 2, h / 2]]))
        return bounds(
            self.scheme.extent(paths=True)[None],
            self.rays.reshape(-1, 2),
            self.arc,
            self.dimension.reshape(-1, 2),
            *(line for d in self.swings for line in d.lines),
            *boxes,
        )

    def texts(self) -> list[Label]:
        """Every text of the drawing but the scheme's own: theta, the letters, H and the swings' ψ."""
        return [self.label, *self.letters, *([self.stroke] if self.stroke else []), *(d.label for d in self.swings)]


def limits_scene(kin: Kinematics, lang: str = "en") -> LimitsScene | None:
    """The limit positions of the first working member (:func:`linkwork.motion.analysis.working`) of a whole
    turn ``kin``, a slider's stroke dimensioned (its text in ``lang``); None where the mechanism has no such
    member with two extremes, or no crank pin."""
    from linkwork.scene.positions import _crank_pin

    mech = kin.mechanism
    members = working(mech)
    pin = _crank_pin(mech)
    if not members or pin < 0 or kin.angles.ndim != 1:
        return None
    r = output_range(kin, members[0])
    low, high = float(np.ravel(r.at_low)[0]), float(np.ravel(r.at_high)[0])
    if not (math.isfinite(low) and math.isfinite(high)) or bool(np.ravel(r.turns)[0]):
        return None
    both = kinematics(mech, np.array([low, high]))
    scheme = scheme_scene(both, at=[0], cycle=kin)
    names = [str(n).split(".", 1)[1] for n in mech.point_names]
    k = int(mech.drive_pair[0])
    pivot = next(int(p) for p in mech.pair_points[k] if p >= 0 and mech.point_link[p] == 0)
    pts = both.points()
    o = pts[0, pivot]
    u = [pts[i, pin] - o for i in (0, 1)]
    crank = float(np.hypot(*u[0]))
    a0, a1 = math.atan2(u[0][1], u[0][0]), math.atan2(-u[1][1], -u[1][0])
    sweep = (a1 - a0 + math.pi) % (2 * math.pi) - math.pi  # the shorter way round, signed
    reach = 2.2 * crank
    rays = np.array([[o, o + reach * np.array([math.cos(a), math.sin(a)])] for a in (a0, a1)])
    radius = 1.5 * crank
    t = a0 + sweep * np.linspace(0.0, 1.0, 33)
    arc = o + radius * np.column_stack([np.cos(t), np.sin(t)])
    theta = abs(sweep)
    text = f"θ = {_number(math.degrees(theta), 2, lang)}°"
    w, h = text_size(text, scheme.em)
    # beside the arc's end, outside the wedge (clear of both rays however narrow theta is)
    side = a1 + math.copysign(math.pi / 2, sweep if sweep else 1.0)
    out = np.array([math.cos(side), math.sin(side)])
    centre = arc[-1] + out * (0.5 * abs(out[0]) * w + 0.5 * abs(out[1]) * h + 0.5 * scheme.em)
    turned = float(np.ravel(r.rising)[0])
    label = Label(text, "position", 0, o, centre[None])
    scene = LimitsScene(scheme, members[0].name, rays, arc, theta, turned, label, kind=members[0].kind)
    if members[0].kind == "slider":
        scene = _dimensioned(scene, pts[:, members[0].point], float(np.ravel(r.stroke)[0]), lang)
    swings = [_swing(scene.scheme, kin, out, lang) for out in outputs(mech) if out.kind == "rocker"]
    scene = replace(scene, swings=tuple(d for d in swings if d is not None))
    return _lettered(scene, pts, [pin, _member_point(mech, members[0])], names)


def _member_point(mech: Mechanism, member: Output) -> int:
    """The working member's point lettered at its extremes: a slider's point on its guide, a rocker's joint
    farthest from its pivot (-1 where it names none)."""
    from linkwork.scene.positions import _farthest_from_pivot

    if member.kind == "slider":
        return member.point
    joints = [int(p) for pair in mech.pair_points for p in pair if p >= 0]
    far = _farthest_from_pivot(mech, member, joints)
    return -1 if far is None else far


def _swing(s: SchemeScene, kin: Kinematics, rocker: Output, lang: str) -> Dimension | None:
    """The swing ψ of ``rocker`` over the whole turn ``kin`` (:func:`~linkwork.motion.analysis.output_range`)
    dimensioned at its pivot as H is along a stroke: an extension line along the rocker at each extreme, from
    its joint farthest from the pivot out to the arc :data:`OFFSET` ems beyond that joint's block, the arc
    between them, and ``ψ = ...°`` beyond the arc's middle.  None for a rocker that turns fully, does not move,
    or names no point at its pivot."""
    from linkwork.scene.positions import _farthest_from_pivot

    mech = kin.mechanism
    r = output_range(kin, rocker)
    psi, at = float(np.ravel(r.stroke)[0]), [float(np.ravel(r.at_low)[0]), float(np.ravel(r.at_high)[0])]
    joints = [int(p) for pair in mech.pair_points for p in pair if p >= 0]
    far = _farthest_from_pivot(mech, rocker, joints)
    if bool(np.ravel(r.turns)[0]) or not (math.isfinite(psi) and psi > 1e-9) or far is None:
        return None
    pivot = next(int(p) for p in mech.pair_points[rocker.pair] if p >= 0 and mech.point_link[p] == rocker.link)
    pts = kinematics(mech, np.array(at)).points()
    o, ends = pts[0, pivot], pts[:, far]
    a0, a1 = (math.atan2(*(e - o)[::-1]) for e in ends)
    sweep = (a1 - a0 + math.pi) % (2 * math.pi) - math.pi  # the shorter way round, signed; ψ the other way if larger
    if abs(abs(sweep) - psi) > abs(2 * math.pi - abs(sweep) - psi):
        sweep -= math.copysign(2 * math.pi, sweep)
    radius = float(np.hypot(*(ends[0] - o))) + 3.0 * s.r + OFFSET * s.em
    u = [np.array([math.cos(a), math.sin(a)]) for a in (a0, a1)]
    lines = [np.array([e + 1.5 * s.r * d, o + (radius + 0.6 * s.em) * d]) for e, d in zip(ends, u, strict=True)]
    turn = a0 + sweep * np.linspace(0.0, 1.0, 49)
    lines.append(o + radius * np.column_stack([np.cos(turn), np.sin(turn)]))
    text = t("limits.swing", lang, value=_number(math.degrees(psi), 1, lang))
    w, h = text_size(text, s.em)
    n = np.array([math.cos(a0 + sweep / 2), math.sin(a0 + sweep / 2)])
    middle = o + radius * n
    centre = middle + n * (0.5 * abs(n[0]) * w + 0.5 * abs(n[1]) * h + 0.4 * s.em)
    return Dimension(tuple(lines), Label(text, "position", 0, middle, centre[None]))


def _dimensioned(scene: LimitsScene, ends: np.ndarray, stroke: float, lang: str) -> LimitsScene:
    """``scene`` with a slider's ``stroke`` (m) dimensioned between its point at the low and high extremes
    ``ends`` ``(2, 2)``: the extension lines and the dimension line beside the stroke, away from the drawing's
    middle, :data:`OFFSET` ems beyond the slider's block; the value above the line's middle."""
    s = scene.scheme
    d = ends[1] - ends[0]
    length = float(np.hypot(*d))
    if not length > 0:
        return scene
    u = d / length
    n = np.array([-u[1], u[0]])
    box = s.extent(paths=True)
    if (ends.mean(0) - (box[:2] + box[2:]) / 2) @ n < 0:
        n = -n
    off = 3.0 * s.r + OFFSET * s.em
    reach = off + 0.6 * s.em
    lines = [np.array([e + 1.5 * s.r * n, e + reach * n]) for e in ends] + [ends + off * n]
    text = t("limits.stroke", lang, value=_number(1000 * stroke, 1, lang))
    w, h = text_size(text, s.em)
    middle = ends.mean(0) + off * n
    centre = middle + n * (0.5 * abs(n[0]) * w + 0.5 * abs(n[1]) * h + 0.4 * s.em)
    return replace(scene, dimension=np.array(lines), stroke=Label(text, "position", 0, middle, centre[None]))


#: Ems from a slider's block to the dimension line of its stroke.
OFFSET = 2.0


def _number(value: float, decimals: int, lang: str) -> str:
    """``value`` to ``decimals`` places, with the decimal sign of ``lang``."""
    text = f"{value:.{decimals}f}"
    return numbers(text, lang)


def _segments(line: np.ndarray) -> np.ndarray:
    """The segments ``(K - 1, 2, 2)`` of a polyline ``(K, 2)``."""
    return np.stack([line[:-1], line[1:]], axis=1)


def _lettered(scene: LimitsScene, pts: np.ndarray, points: list[int], names: list[str]) -> LimitsScene:
    """``scene`` with ``points`` (the crank pin, the slider's point; ``names`` of every point) lettered at the
    high extreme (sample 1 of ``pts`` ``(2, P, 2)``: primed) and the low one (sample 0: double-primed), clear of
    both poses' lines and of the texts placed before."""
    from linkwork.scene.positions import FINE, _all_positions, _box

    s = scene.scheme
    wanted = [(f"{names[p]}{mark}", pts[k, p]) for p in points if p >= 0 for k, mark in ((1, "′"), (0, "″"))]
    if not wanted:
        return scene
    named = {names[p] for p in points if p >= 0}  # lettered here: their plain names go
    kept = tuple(lab for lab in s.labels if lab.text not in named)
    earlier = [*kept, *scene.texts()]
    taken = np.array([_box(lab, s.em) for lab in earlier]).reshape(1, -1, 4)
    anchors = np.array([a for _, a in wanted])[None]
    sizes = np.array([text_size(text, s.em) for text, _ in wanted])
    obstacles = _all_positions(s)
    drawn = [scene.dimension, *(_segments(line) for d in scene.swings for line in d.lines)]
    lines = np.concatenate([d for d in drawn if len(d)] or [np.zeros((0, 2, 2))])
    if len(lines):
        obstacles = Obstacles(np.concatenate([obstacles.segments, lines[None]], 1), obstacles.circles)
    gaps = np.full(len(wanted), 0.8 * s.r)
    placed = place_labels(anchors, sizes, gaps, obstacles, pad=0.15 * s.em, taken=taken, directions=FINE)[0]
    letters = tuple(Label(text, "position", 0, a, placed[j][None]) for j, (text, a) in enumerate(wanted))
    return replace(scene, letters=letters, scheme=replace(s, labels=kept))
