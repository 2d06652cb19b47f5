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

from linkwork.lang import russian_numbers, t
from linkwork.motion.analysis import output_range, working
from linkwork.motion.kinematic_analysis import kinematics
from linkwork.scene.geometry import bounds, text_size
from linkwork.scene.labels import Obstacles, place_labels
from linkwork.scene.scheme import Label, SchemeScene, scheme_scene

if TYPE_CHECKING:
    from linkwork.motion.kinematic_analysis import Kinematics


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

    def who(self, lang: str = "en") -> str:
        """The working member as the texts name it, in ``lang``: its kind in words and its name as the file
        writes it (``ползуна на направляющей guide_E``, ``коромысла rocker``)."""
        return t(f"limits.member.{self.kind}", lang, member=self.member)

    def extent(self) -> np.ndarray:
        """``[x0, y0, x1, y1]`` of everything drawn, m."""
        boxes = []
        for lab in (self.label, *self.letters, *([self.stroke] if self.stroke else [])):
            w, h = text_size(lab.text, self.scheme.em)
            c = lab.centre[0]
            boxes.append(np.array([c - [w / 2, h / 2], c + [w / 2, h / 2]]))
        return bounds(
            self.scheme.extent(paths=True)[None],
            self.rays.reshape(-1, 2),
            self.arc,
            self.dimension.reshape(-1, 2),
            *boxes,
        )


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
    return _lettered(scene, pts, [pin, members[0].point], names)


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
    return russian_numbers(text) if lang == "ru" else text


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
    earlier = [*kept, scene.label, *([scene.stroke] if scene.stroke else [])]
    taken = np.array([_box(lab, s.em) for lab in earlier]).reshape(1, -1, 4)
    anchors = np.array([a for _, a in wanted])[None]
    sizes = np.array([text_size(text, s.em) for text, _ in wanted])
    obstacles = _all_positions(s)
    if len(scene.dimension):
        obstacles = Obstacles(np.concatenate([obstacles.segments, scene.dimension[None]], 1), obstacles.circles)
    gaps = np.full(len(wanted), 0.8 * s.r)
    placed = place_labels(anchors, sizes, gaps, obstacles, pad=0.15 * s.em, taken=taken, directions=FINE)[0]
    letters = tuple(Label(text, "position", 0, a, placed[j][None]) for j, (text, a) in enumerate(wanted))
    return replace(scene, letters=letters, scheme=replace(s, labels=kept))
