"""The twelve positions of the graphical method: their crank angles, which of them the plans are drawn
for, and the plan of positions as a scene.

Position 0 is where the working slider is at the high end of its stroke (the knives open:
:func:`linkwork.motion.analysis.zero_angle`); the others follow every 30 degrees in the direction of
rotation.  The plans are drawn for the positions the file names (``drawing: {positions: [9]}``), else
for the one position of the working stroke where the working point moves fastest with every dyad
transmitting well and every vector of the plan visible (:func:`best_position`): never a dead point, where
the plans collapse onto the pole.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from linkwork.lang import numbers, t
from linkwork.motion.analysis import Output, coordinate, output_range, position_angles, transmission, working
from linkwork.motion.kinematic_analysis import kinematics
from linkwork.motion.plans import plan_series
from linkwork.scene.geometry import place, text_size
from linkwork.scene.labels import Obstacles, place_labels
from linkwork.scene.scheme import Label, SchemeScene, scheme_scene
from linkwork.spec.reader import described

if TYPE_CHECKING:
    from linkwork.motion.kinematic_analysis import Kinematics
    from linkwork.structure.model import Mechanism

#: The positions of the graphical method over one turn.
COUNT = 12


def working_point(mech: Mechanism) -> int:
    """The point whose motion is the machine's work: the first tool of a process load, else the striking
    point of the blow, else the point of the first working member (:func:`linkwork.motion.analysis.working`,
    the member whose extreme is position 0): a slider's point on its guide, a rocker's joint farthest from
    its pivot; else the last joint of a moving link."""
    for load in mech.loads:
        if load.kind == "process" and load.points:
            return int(load.points[0])
    if mech.blow is not None:
        return mech.point_index(mech.blow.at)
    joints = [int(p) for pair in mech.pair_points for p in pair if p >= 0]
    members = working(mech)
    if members and members[0].kind == "slider":
        return members[0].point
    far = _farthest_from_pivot(mech, members[0], joints) if members else None
    if far is not None:
        return far
    moving = [p for p in joints if mech.point_link[p] != 0]
    return moving[-1] if moving else 0


def _farthest_from_pivot(mech: Mechanism, rocker: Output, joints: list[int]) -> int | None:
    """Of the joints on ``rocker``'s link, the one farthest from its pivot on the frame (index of a point);
    None if the link names no point at its pivot."""
    own = [p for p in joints if mech.point_link[p] == rocker.link]
    pivot = next((int(p) for p in mech.pair_points[rocker.pair] if p >= 0 and mech.point_link[p] == rocker.link), None)
    if pivot is None or not own:
        return None
    local = np.asarray(mech.point_local)
    return own[int(np.argmax(np.hypot(*(local[own] - local[pivot]).T)))]


def best_position(kin: Kinematics, point: int | None = None) -> int:
    """Of the samples of ``kin`` (e.g. the twelve positions), the one the plans are best drawn at: on the working
    stroke (:func:`working_stroke`), with every vector of the velocity plan visible (:func:`plans_clear`), the
    one where the working point moves fastest relative to how badly the mechanism transmits there: the largest
    ``|v| sin(mu)``, ``mu`` the least transmission angle of the dyads (0 at a dead point).  The first of equal
    ones; where no sample is both on the working stroke and clear, a clear one, else one on the stroke."""
    mech = kin.mechanism
    p = working_point(mech) if point is None else point
    v = np.asarray(kin.velocity(mech.point_names[p]))
    speed = np.hypot(v[..., 0], v[..., 1]).reshape(-1, len(kin.angles))[0]
    mu = [np.asarray(m).reshape(-1, len(kin.angles))[0] for m in transmission(kin).values()]
    quality = np.sin(np.min(mu, axis=0)) if mu else np.ones_like(speed)
    score = np.nan_to_num(np.where(np.asarray(kin.valid_all[0]), speed * quality, -np.inf), nan=-np.inf)
    stroke, clear = working_stroke(kin), plans_clear(kin)
    for allowed in (stroke & clear, clear, stroke):
        if np.any(allowed & (score > -np.inf)):
            return int(np.argmax(np.where(allowed, score, -np.inf)))
    return int(np.argmax(score))


#: The time ratio above which the slower stroke is the working one (a quick return).
QUICK_RETURN = 1.05


class StrokeAngles(NamedTuple):
    """The crank's turns over the two strokes of the first working member (:func:`stroke_angles`).

    Attributes
    ----------
    high, low : float
        Drive angles (rad) at the high extreme (position 0) and at the low one.
    working, idle : float
        The crank's turn over the working stroke and over the idle one (rad, in the drive's direction; they
        make a whole turn).
    rising : bool
        The working stroke runs from the low extreme to the high one (the slower stroke of a quick return that
        rises); else from the high one (position 0) to the low one.
    """

    high: float
    low: float
    working: float
    idle: float
    rising: bool


def stroke_angles(mech: Mechanism) -> StrokeAngles | None:
    """The working and idle strokes of ``mech``'s first working member (:func:`~linkwork.motion.analysis.working`)
    over a turn of 360 steps, its extremes refined between them: the slower stroke of a quick return (time ratio
    above :data:`QUICK_RETURN`), else the stroke from position 0 (the high end: the knives closing, the ram going
    down).  None where there is no working member with two extremes (a rocker that turns fully)."""
    members = working(mech)
    if not members:
        return None
    turn = output_range(kinematics(mech, steps=360), members[0])
    rising, falling = float(turn.rising[0]), float(turn.falling[0])
    if not (np.isfinite(rising) and np.isfinite(falling)):
        return None
    up = max(rising, falling) > QUICK_RETURN * min(rising, falling) and rising > falling
    work, idle = (rising, falling) if up else (falling, rising)
    return StrokeAngles(float(turn.at_high[0]), float(turn.at_low[0]), work, idle, up)


def working_stroke(kin: Kinematics) -> np.ndarray:
    """Which samples of ``kin`` ``(A,)`` are on the working stroke of the first working member
    (:func:`stroke_angles`; the falling one of a member without two extremes); every sample where the mechanism
    has no working member."""
    mech = kin.mechanism
    members = working(mech)
    if not members:
        return np.ones(len(kin.angles), dtype=bool)
    strokes = stroke_angles(mech)
    rate = np.asarray(coordinate(kin, members[0])[1]).reshape(-1, len(kin.angles))[0]
    return np.asarray(rate > 0 if strokes is not None and strokes.rising else rate < 0)


#: Where a vector of the velocity plan that moves at all is shorter than this part of the plan's longest, the
#: plan degenerates (two letters on one point: "a = b").
VISIBLE = 0.05


def plans_clear(kin: Kinematics) -> np.ndarray:
    """Which samples of ``kin`` ``(A,)`` have a velocity plan whose every vector shows: each absolute and
    relative vector that is not zero over all the samples at least :data:`VISIBLE` of the longest."""
    vel = plan_series(kin)[0]
    absolute = vel.values[0][:, [j for j, lab in enumerate(vel.points) if lab != "p"]]
    size = np.hypot(*np.moveaxis(np.concatenate([absolute, vel.vectors[0]], 1), -1, 0))  # (A, K)
    size = np.where(np.isfinite(size), size, 0.0)
    moving = size.max(0) > 1e-9 * max(float(size.max()), 1e-300)
    longest = size.max(1, keepdims=True)
    return np.asarray(np.all((size >= VISIBLE * longest) | ~moving, axis=1) & (longest[:, 0] > 0))


def plan_positions(mech: Mechanism, kin: Kinematics | None = None) -> list[int]:
    """The positions (of :data:`COUNT`) the plans are drawn for: the file's ``drawing.positions``, else
    :func:`best_position` of the twelve (``kin``: their kinematics, solved here if not given)."""
    spec = described(mech.description)
    drawing = spec.drawing if spec is not None else None
    if drawing is not None and drawing.positions:
        return [int(k) for k in drawing.positions]
    if kin is None:
        kin = kinematics(mech, position_angles(mech))
    return [best_position(kin)]


@dataclass(frozen=True)
class PositionsScene:
    """The plan of positions: the scheme at every position, thin, with the position numbers; the two extremes of
    the working member lettered, and the crank's turns over its working and idle strokes marked at its pivot.

    Attributes
    ----------
    scheme : SchemeScene
        The scheme at the positions (its samples), its labels the names of the frame's points, its paths
        the trajectories over the whole turn; a last sample the second extreme where it is none of the positions.
    numbers : tuple of Label
        The position numbers at the crank pin and at the working point (``centre`` of shape (1, 2));
        positions whose points coincide share a label ("5, 7").  Along a straight stroke they stand in a
        column beside it in the order of the points, each joined to its point by a leader.
    marks : ndarray, shape (M, 2)
        The numbered points at every position (a dot each), m.
    leaders : ndarray, shape (K, 2, 2)
        Thin lines from a point to its number (or to the value of a stroke's angle), m.
    count : int
        The numbered positions (the scheme's first samples); 0: all of the scheme's samples.
    extreme : int
        The scheme's sample at the second extreme of the working member (position 0 is the first); -1 where the
        mechanism has no working member with two extremes.
    letters : tuple of Label
        The crank pin and the working member's point lettered at both extremes: primed at position 0 (``A′``),
        double-primed at the other (``A″``).
    arcs : tuple of ndarray, shape (K, 2)
        The working stroke's arc and the idle stroke's, about the crank's pivot between its two extreme
        positions, in the drive's direction, m.
    strokes : tuple of Label
        Their values beside them: ``φ_w = 186.4°`` and ``φ_i = 173.6°`` (``φ_р.х``, ``φ_х.х`` in Russian).
    """

    scheme: SchemeScene
    numbers: tuple[Label, ...]
    marks: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros((0, 2)))
    leaders: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros((0, 2, 2)))
    count: int = 0
    extreme: int = -1
    letters: tuple[Label, ...] = ()
    arcs: tuple[np.ndarray, ...] = ()
    strokes: tuple[Label, ...] = ()

    @property
    def positions(self) -> int:
        """How many positions are numbered."""
        return self.count or len(self.scheme.angles)

    def extent(self) -> np.ndarray:
        """``[x0, y0, x1, y1]`` of everything drawn, m."""
        boxes = [self.scheme.extent(paths=True)]
        for lab in (*self.numbers, *self.letters, *self.strokes):
            w, h = text_size(lab.text, self.scheme.em)
            boxes.append(np.concatenate([lab.centre[0] - [w / 2, h / 2], lab.centre[0] + [w / 2, h / 2]]))
        boxes += [np.concatenate([arc.min(0), arc.max(0)]) for arc in self.arcs]
        arr = np.array(boxes)
        return np.concatenate([arr[:, :2].min(0), arr[:, 2:].max(0)])


def positions_scene(kin: Kinematics, cycle: Kinematics | None = None, lang: str = "en") -> PositionsScene:
    """The plan of the positions of ``kin`` (its samples, numbered 0, 1, ...), with the trajectories over
    ``cycle`` (a whole turn; see :func:`~linkwork.scene.scheme_scene`), the extremes of the working member and
    its strokes' angles (:func:`stroke_angles`) marked, their texts in ``lang``."""
    mech = kin.mechanism
    count = len(kin.angles)
    strokes = stroke_angles(mech)
    extreme = -1 if strokes is None else _sample_at(kin.angles, strokes.low)
    if extreme == count:
        kin = kinematics(mech, np.append(np.asarray(kin.angles, dtype=float), strokes.low))  # type: ignore[union-attr]
    scheme = scheme_scene(kin, at=[0], cycle=cycle)
    fixed = {name.split(".", 1)[1] for p, name in enumerate(mech.point_names) if mech.point_link[p] == 0}
    frame = tuple(lab for lab in scheme.labels if lab.kind == "point" and lab.text in fixed)
    scheme = dataclasses.replace(scheme, labels=_clear_of_every_position(scheme, frame))
    crank = _crank_pin(mech)
    points = [p for p in dict.fromkeys([crank, working_point(mech)]) if p >= 0]
    pts = kin.points()
    marks = pts[:count, points].reshape(-1, 2)
    numbers, leaders = _numbers(scheme, pts[:count], points)
    out = PositionsScene(scheme, numbers, marks[np.isfinite(marks).all(-1)], leaders, count)
    if strokes is None or crank < 0:
        return out
    return _extremes(out, mech, pts, extreme, strokes, lang)


def _sample_at(angles: np.ndarray, angle: float) -> int:
    """The sample of ``angles`` (drive angles, rad) within :data:`SAME` of ``angle``; their count if none is."""
    off = np.abs((np.asarray(angles, dtype=float) - angle + np.pi) % (2 * np.pi) - np.pi)
    return int(np.argmin(off)) if len(off) and off.min() < SAME else len(off)


#: Drive angles closer than this (rad; a quarter of a degree) are one position.
SAME = np.radians(0.25)


def _member_point(mech: Mechanism) -> int:
    """The point lettered at the working member's extremes: a slider's point on its guide, a rocker's joint
    farthest from its pivot; -1 if none."""
    members = working(mech)
    if not members:
        return -1
    if members[0].kind == "slider":
        return members[0].point
    joints = [int(p) for pair in mech.pair_points for p in pair if p >= 0]
    far = _farthest_from_pivot(mech, members[0], joints)
    return -1 if far is None else far


def _extremes(
    scene: PositionsScene, mech: Mechanism, pts: np.ndarray, extreme: int, strokes: StrokeAngles, lang: str
) -> PositionsScene:
    """``scene`` with the crank pin and the working member's point lettered at both extremes (samples 0 and
    ``extreme`` of ``pts`` ``(A, P, 2)``) and the arcs of the strokes' angles at the crank's pivot."""
    scheme, em = scene.scheme, scene.scheme.em
    lettered = [p for p in dict.fromkeys([_crank_pin(mech), _member_point(mech)]) if p >= 0]
    short = [str(name).split(".", 1)[1] for name in mech.point_names]
    wanted = [(f"{short[p]}{mark}", pts[k, p]) for p in lettered for k, mark in ((0, "′"), (extreme, "″"))]
    arcs, values, middles = _stroke_arcs(mech, pts, extreme, strokes, lang)
    taken = np.array([_box(lab, em) for lab in (*scheme.labels, *scene.numbers)]).reshape(1, -1, 4)
    anchors = np.array([a for _, a in wanted] + middles)[None]
    texts = [text for text, _ in wanted] + values
    sizes = np.array([text_size(text, em) for text in texts])
    centre = (scene.extent()[:2] + scene.extent()[2:]) / 2
    away = anchors[0] - centre
    prefer = away / np.maximum(np.hypot(*away.T), 1e-12)[:, None]
    gaps = np.array([0.8 * scheme.r] * len(wanted) + [0.5 * em] * len(values))
    placed = place_labels(
        anchors, sizes, gaps, _all_positions(scheme), prefer[None], pad=0.15 * em, taken=taken, directions=FINE
    )[0]
    labels = [Label(text, "position", 0, anchors[0, j], placed[j][None]) for j, text in enumerate(texts)]
    leaders = [
        _leader(anchors[0, j], placed[j], sizes[j], scheme.r, em)
        for j in range(len(texts))
        if np.hypot(*(placed[j] - anchors[0, j])) > np.hypot(*sizes[j]) / 2 + scheme.r + 1.5 * em
    ]
    return dataclasses.replace(
        scene,
        extreme=extreme,
        letters=tuple(labels[: len(wanted)]),
        arcs=arcs,
        strokes=tuple(labels[len(wanted) :]),
        leaders=np.concatenate([scene.leaders, np.array(leaders).reshape(-1, 2, 2)]),
    )


#: Radius of the strokes' arcs about the crank's pivot, in crank lengths.
ARC = 0.6


def _stroke_arcs(
    mech: Mechanism, pts: np.ndarray, extreme: int, strokes: StrokeAngles, lang: str
) -> tuple[tuple[np.ndarray, ...], list[str], list[np.ndarray]]:
    """The arcs of the working stroke and of the idle one about the crank's pivot, from the crank at one extreme
    to the crank at the other in the drive's direction (the working one from position 0 unless it rises); their
    values' texts in ``lang`` and the middles of the arcs."""
    k = int(mech.drive_pair[0])
    pivot = next(int(p) for p in mech.pair_points[k] if p >= 0 and mech.point_link[p] == 0)
    o = pts[0, pivot]
    arm = pts[0, _crank_pin(mech)] - o
    radius = ARC * float(np.hypot(*arm))
    sign = 1.0 if mech.drive_speed[0] >= 0 else -1.0
    at_high = float(np.arctan2(arm[1], arm[0]))
    first = at_high if not strokes.rising else at_high + sign * strokes.idle  # where the working stroke starts
    arcs, middles = [], []
    for start, turn in ((first, strokes.working), (first + sign * strokes.working, strokes.idle)):
        t_ = start + sign * turn * np.linspace(0.0, 1.0, 1 + max(8, int(np.degrees(turn) // 4)))
        arcs.append(o + radius * np.column_stack([np.cos(t_), np.sin(t_)]))
        middles.append(arcs[-1][len(t_) // 2])
    values = [
        t(f"positions.{kind}", lang, angle=_degrees(turn, lang))
        for kind, turn in (("working", strokes.working), ("idle", strokes.idle))
    ]
    return tuple(arcs), values, middles


def _degrees(angle: float, lang: str) -> str:
    """An angle (rad) in degrees to 0.1, with the decimal sign of ``lang``."""
    text = f"{np.degrees(angle):.1f}"
    return numbers(text, lang)


def _clear_of_every_position(scheme: SchemeScene, labels: tuple[Label, ...]) -> tuple[Label, ...]:
    """The frame's ``labels`` placed again, clear of the lines of every position (not of position 0 alone)."""
    if not labels:
        return labels
    anchors = np.array(
        [place(scheme.poses[:1, lab.link], np.asarray(lab.at, dtype=float)[None])[0, 0] for lab in labels]
    )[None]
    sizes = np.array([text_size(lab.text, scheme.em) for lab in labels])
    gaps = np.full(len(labels), max(0.8 * scheme.r, 0.5 * scheme.em))  # out of a small crank's circle if need be
    centres = place_labels(anchors, sizes, gaps, _all_positions(scheme), pad=0.15 * scheme.em, directions=FINE)
    return tuple(dataclasses.replace(lab, centre=centres[:, j]) for j, lab in enumerate(labels))


def _crank_pin(mech: Mechanism) -> int:
    """The crank's joint farthest from its pivot; -1 if none."""
    k = int(mech.drive_pair[0])
    link = int(mech.pair_links[k, 1] if mech.pair_links[k, 0] == 0 else mech.pair_links[k, 0])
    joints = [int(p) for pair in mech.pair_points for p in pair if p >= 0 and mech.point_link[p] == link]
    if not joints:
        return -1
    local = np.asarray(mech.point_local)[joints]
    far = int(np.argmax(np.hypot(*local.T)))
    return joints[far] if np.hypot(*local[far]) > 0 else -1


#: The directions the plan of positions tries for its labels (one drawing crowded with twelve positions' links:
#: every 7.5 degrees).
FINE = np.radians(np.arange(0.0, 360.0, 7.5))

#: Positions whose points are closer than this (ems) share one number; the least distance between two
#: numbers in a column (ems; more where the numbers are wider than that along it).
TOGETHER, SPACING = 0.2, 1.35


def _numbers(scheme: SchemeScene, pts: np.ndarray, points: list[int]) -> tuple[tuple[Label, ...], np.ndarray]:
    """Position numbers at ``points`` ``(A, P, 2)`` (those of coinciding positions together) and the leaders to
    them: along a straight stroke in a column beside it, in order (:func:`_column`); elsewhere (the crank
    pin's circle) placed clear of every position's lines and of each other."""
    em = scheme.em
    wanted: list[tuple[str, np.ndarray]] = []
    fixed: list[tuple[str, np.ndarray, np.ndarray]] = []
    leaders: list[np.ndarray] = []
    centre = scheme.extent()[:2] / 2 + scheme.extent()[2:] / 2
    for p in points:
        groups = _coincident(pts[:, p], TOGETHER * em)
        anchors = np.array([a for _, a in groups]).reshape(-1, 2)
        column = _column(anchors, [text for text, _ in groups], centre, scheme.r, em) if len(groups) > 2 else None
        if column is None:
            wanted += groups
            continue
        for (text, anchor), (box_centre, leader) in zip(groups, column, strict=True):
            fixed.append((text, anchor, box_centre))
            leaders.append(leader)
    numbers = [Label(text, "position", 0, a, c[None]) for text, a, c in fixed]
    taken = np.array([_box(lab, em) for lab in (*scheme.labels, *numbers)]).reshape(1, -1, 4)
    if wanted:
        anchors = np.array([a for _, a in wanted])[None]
        sizes = np.array([text_size(t, em) for t, _ in wanted])
        away = anchors[0] - centre
        prefer = away / np.maximum(np.hypot(*away.T), 1e-12)[:, None]
        gaps = np.full(len(wanted), 0.8 * scheme.r)
        centres = place_labels(
            anchors, sizes, gaps, _all_positions(scheme), prefer[None], pad=0.15 * em, taken=taken, directions=FINE
        )
        numbers += [Label(t, "position", 0, a, centres[:, j]) for j, (t, a) in enumerate(wanted)]
        leaders += [
            _leader(a, centres[0, j], sizes[j], scheme.r, em)
            for j, (_, a) in enumerate(wanted)
            if np.hypot(*(centres[0, j] - a)) > np.hypot(*sizes[j]) / 2 + scheme.r + 1.5 * em
        ]
    return tuple(numbers), np.array(leaders).reshape(-1, 2, 2)


def _leader(anchor: np.ndarray, centre: np.ndarray, size: np.ndarray, r: float, em: float) -> np.ndarray:
    """A line from a point (clear of its dot of radius ``r``) to the edge of its number's box of ``size``."""
    d = centre - anchor
    u = d / np.hypot(*d)
    inside = float(np.min(size / 2 / np.maximum(np.abs(u), 1e-12))) + 0.2 * em  # centre to the box's edge
    return np.array([anchor + 0.5 * r * u, centre - inside * u])


def _coincident(xy: np.ndarray, within: float) -> list[tuple[str, np.ndarray]]:
    """The positions ``(A, 2)`` grouped where their points coincide (closer than ``within``): each group's
    numbers, in order, and its first point."""
    taken = ~np.isfinite(xy).all(-1)
    out = []
    for k in range(len(xy)):
        if not taken[k]:
            close = ~taken & (np.hypot(*(xy - xy[k]).T) < within)
            taken |= close
            out.append((", ".join(str(i) for i in np.flatnonzero(close)), xy[k]))
    return out


def _column(
    anchors: np.ndarray, texts: list[str], centre: np.ndarray, r: float, em: float
) -> list[tuple[np.ndarray, np.ndarray]] | None:
    """Where the numbers of points along a straight line go: in a column beside the line, on the side away from
    the drawing's ``centre``, in the order of the points along it, each as near its point as the numbers'
    :data:`SPACING` lets it be (the least squares spread: pool adjacent violators); with each number, its
    leader from the point.  None where the points are not on a line."""
    mean = anchors.mean(0)
    _, spread, axes = np.linalg.svd(anchors - mean, full_matrices=False)
    if spread[0] <= 0 or spread[-1] > 0.02 * spread[0]:
        return None
    u = axes[0]
    n = np.array([-u[1], u[0]])
    if (mean - centre) @ n < 0:
        n = -n
    along = (anchors - mean) @ u
    order = np.argsort(along)
    sizes = np.array([text_size(t, em) for t in texts])
    slots = _spread(along[order], max(SPACING * em, float(np.max(sizes @ np.abs(u))) + 0.4 * em))
    reach = sizes @ np.abs(n) / 2  # half of each box across the line
    side = float(np.max((anchors - mean) @ n)) + r + 2.0 * em
    out: dict[int, tuple[np.ndarray, np.ndarray]] = {}
    for slot, i in zip(slots, order, strict=True):
        box_centre = mean + slot * u + (side + reach[i]) * n
        out[int(i)] = (box_centre, np.array([anchors[i] + 0.5 * r * n, box_centre - (reach[i] + 0.2 * em) * n]))
    return [out[i] for i in range(len(texts))]


def _spread(targets: np.ndarray, step: float) -> np.ndarray:
    """Values nearest ``targets`` (ascending) in least squares with each at least ``step`` above the one before."""
    shifted = targets - step * np.arange(len(targets))
    blocks: list[list[float]] = []  # [mean, count] of pooled runs, non-decreasing
    for value in shifted:
        blocks.append([float(value), 1.0])
        while len(blocks) > 1 and blocks[-2][0] > blocks[-1][0]:
            (m2, c2), (m1, c1) = blocks.pop(), blocks.pop()
            blocks.append([(m1 * c1 + m2 * c2) / (c1 + c2), c1 + c2])
    fitted = np.concatenate([np.full(int(c), m) for m, c in blocks])
    return fitted + step * np.arange(len(targets))


def _box(label: Label, em: float) -> np.ndarray:
    """``[x0, y0, x1, y1]`` of a label's text at its first sample."""
    half = np.array(text_size(label.text, em)) / 2
    return np.concatenate([label.centre[0] - half, label.centre[0] + half])


def _all_positions(scheme: SchemeScene) -> Obstacles:
    """The lines and circles of every position, as obstacles of one drawing."""
    segs, circles = [], []
    for it in scheme.items:
        xy = scheme.placed(it)  # (A, K, 2)
        if it.radius:
            circles.append(np.concatenate([xy[:, 0], np.full((len(xy), 1), it.radius)], -1))
        elif it.kind != "hatch":
            ring = np.concatenate([xy, xy[:, :1]], 1) if it.closed else xy
            segs.append(np.stack([ring[:, :-1], ring[:, 1:]], 2).reshape(-1, 2, 2))
    return Obstacles(
        np.concatenate(segs)[None] if segs else np.zeros((1, 0, 2, 2)),
        np.concatenate(circles)[None] if circles else np.zeros((1, 0, 3)),
    )
