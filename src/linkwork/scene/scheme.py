"""The kinematic scheme of a mechanism as a scene: what is drawn, where, over every sample of a result.

A :class:`SchemeScene` is built once from a kinematics result and drawn by every renderer (the figures'
matplotlib, the viewer's SVG, DXF).  Each :class:`Item` is an outline, a line or a circle fixed in the
axes of one link (the frame's are the global axes), so a renderer places it at the link's pose of the
sample it draws: the links as bars (two points, or more in a line) or plates (the convex outline of
their points), pivots, supports on the frame, slider blocks on hatched guides, the tools and knives
with their working edges, the workpiece, markers.  :class:`Label` s carry the centre of their text at
every sample, placed clear of each other and of the lines (:mod:`linkwork.scene.labels`).

Sizes follow the drawing's size ``size`` (the larger side of the box of every point over the cycle):
pivots of radius ``r = 0.012 size``, text ``em = 0.032 size`` high.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from linkwork.motion.analysis import guide
from linkwork.motion.kinematics import kinematics
from linkwork.scene import symbols
from linkwork.scene.geometry import bounds, collinear, hull, place, text_size, to_local
from linkwork.scene.labels import Obstacles, place_labels, segments_hit
from linkwork.structure.constraints import perp
from linkwork.structure.model import PairType, per_mechanism, point_labels

if TYPE_CHECKING:
    from linkwork.motion.kinematics import Kinematics
    from linkwork.spec.schema import ImpactSpec
    from linkwork.structure.model import Mechanism

#: The kinds of item, in drawing order (later on top).
KINDS = ("path", "hatch", "support", "guide", "bar", "plate", "tool", "edge", "block", "pivot", "marker")

#: Radius of a pivot and size of the text, as fractions of the drawing's size.
PIVOT, FONT = 0.012, 0.032

#: Samples of the whole turn the fixed symbols are chosen from, where the drawing is given fewer.
CYCLE = 72

#: A support stands down unless another side is crossed at fewer samples by this fraction of them.
DOWN = 0.15


@dataclass(frozen=True)
class Item:
    """One thing drawn, fixed in the axes of one link.

    Attributes
    ----------
    kind : str
        One of :data:`KINDS`.
    link : int
        The link whose axes ``xy`` is in (0: the frame, whose axes are the global ones).
    xy : ndarray, shape (K, 2)
        The vertices (m); a circle's centre ``(1, 2)``.
    closed : bool
        An outline (the last vertex joins the first) rather than a line.
    radius : float
        A circle's radius (m); 0 for outlines and lines.
    name : str
        The link, joint or point it draws.
    """

    kind: str
    link: int
    xy: np.ndarray
    closed: bool = False
    radius: float = 0.0
    name: str = ""


@dataclass(frozen=True)
class Label:
    """A text of the drawing: a point's name, a link's number.

    Attributes
    ----------
    text : str
    kind : str
        ``"point"`` (a joint or marker), ``"link"`` (a link's number).
    link : int
        The link that carries the labelled point.
    at : ndarray, shape (2,)
        The labelled point in the link's axes, m.
    centre : ndarray, shape (A, 2)
        The centre of the text at every sample (global, m); NaN where not drawn.
    """

    text: str
    kind: str
    link: int
    at: np.ndarray
    centre: np.ndarray


@dataclass(frozen=True)
class SchemeScene:
    """The kinematic scheme of one mechanism over the samples of a kinematics result.

    Attributes
    ----------
    name : str
        The mechanism's name.
    angles : ndarray, shape (A,)
        Drive angle of every sample, rad.
    valid : ndarray, shape (A,)
        Where the mechanism assembles.
    poses : ndarray, shape (A, N, 3)
        Every link's pose (the frame's is zero); NaN where it does not assemble.
    items : tuple of Item
        In drawing order.
    labels : tuple of Label
    paths : ndarray, shape (A, Q, 2)
        Trajectories of the moving points drawn, ``path_names`` naming them.
    path_names : tuple of str
    size, r, em : float
        The drawing's size, a pivot's radius and the text's size, m.
    """

    name: str
    angles: np.ndarray
    valid: np.ndarray
    poses: np.ndarray
    items: tuple[Item, ...]
    labels: tuple[Label, ...]
    paths: np.ndarray
    path_names: tuple[str, ...]
    size: float
    r: float
    em: float

    def placed(self, item: Item, index: int | None = None) -> np.ndarray:
        """The item's vertices in the global axes: ``(A, K, 2)``, or ``(K, 2)`` at sample ``index``."""
        poses = self.poses[:, item.link] if index is None else self.poses[index : index + 1, item.link]
        xy = place(poses, np.asarray(item.xy, dtype=float))
        return xy if index is None else xy[0]

    def extent(self, index: int | list[int] | None = None, paths: bool = False) -> np.ndarray:
        """``[x0, y0, x1, y1]`` of everything drawn (at sample ``index``, at the samples of a list, or over all),
        labels' text included."""
        at = slice(None) if index is None else np.atleast_1d(np.asarray(index, dtype=int))
        parts: list[np.ndarray] = []
        for it in self.items:
            if it.kind != "path":
                xy = place(self.poses[at, it.link], np.asarray(it.xy, dtype=float))
                parts += [xy - it.radius, xy + it.radius] if it.radius else [xy]
        for lab in self.labels:
            w, h = text_size(lab.text, self.em)
            c = lab.centre[at]
            parts += [c - [w / 2, h / 2], c + [w / 2, h / 2]]
        if paths:
            parts.append(self.paths)
        return bounds(*parts)


def scheme_scene(kin: Kinematics, variant: int = 0, at: list[int] | None = None,
                 cycle: Kinematics | None = None) -> SchemeScene:  # fmt: skip
    """The scheme of every sample of ``kin`` (of design variant ``variant``).

    What does not move (the sides the supports stand on and the guides are hatched on, the guides'
    lengths, the size of the drawing) and the trajectories come from ``cycle``, a whole turn, so that
    every drawing of the mechanism, whichever samples it shows, has the same symbols and sizes.

    Parameters
    ----------
    kin : Kinematics
        Any samples: a whole cycle (the viewer), twelve positions, one position.
    variant : int
        Which design variant of a sweep.
    at : list of int, optional
        The samples whose labels are placed (the others' are NaN); default every sample.
    cycle : Kinematics, optional
        A whole turn of the same mechanism (and variant); default ``kin`` where it has at least
        :data:`CYCLE` samples, else the mechanism solved at :data:`CYCLE` steps.

    Returns
    -------
    SchemeScene
    """
    if cycle is None:
        cycle = kin if len(kin.angles) >= CYCLE else kinematics(kin.mechanism, steps=CYCLE)
    b = _Builder(kin, variant, cycle)
    items = b.items()
    return SchemeScene(
        name=str(b.mech.name),
        angles=np.asarray(kin.angles, dtype=float),
        valid=np.asarray(kin.valid_all[variant], dtype=bool),
        poses=b.poses,
        items=items,
        labels=b.labels(items, list(range(len(b.poses))) if at is None else [int(i) % len(b.poses) for i in at]),
        paths=b.cycle[:, list(b.path_points)],
        path_names=tuple(b.mech.point_names[p] for p in b.path_points),
        size=b.size,
        r=b.r,
        em=b.em,
    )


class _Builder:
    """The scheme's items and labels from one variant of a kinematics result."""

    def __init__(self, kin: Kinematics, variant: int, cycle: Kinematics) -> None:
        self.kin, self.mech, self.variant = kin, kin.mechanism, variant
        self.poses = np.array(kin.pose[variant])  # (A, N, 3)
        self.local = np.asarray(kin.local[:, :, variant, 0], dtype=float)  # (P, 2)
        pts = kin.points()
        turn = pts if cycle is kin else cycle.points()
        self.pts = np.asarray(pts[variant] if kin.variants else pts)  # (A, P, 2)
        self.cycle = np.asarray(turn[min(variant, len(turn) - 1)] if cycle.variants else turn)  # (S, P, 2)
        mech = self.mech
        self.layout = layout = _layout(mech)
        self.joint, self.moving, self.outline = layout.joint, layout.moving, layout.outline
        self.path_points = layout.path_points
        self._segments: np.ndarray | None = None
        box = bounds(self.cycle[:, self.moving], self.local[np.asarray(mech.point_link) == 0])
        self.size = float(max(box[2] - box[0], box[3] - box[1], 1e-9))
        self.r, self.em = PIVOT * self.size, FONT * self.size
        self.first = int(np.argmax(np.asarray(kin.valid_all[variant]))) if len(self.pts) else 0

    # ------------------------------------------------------------ items

    def items(self) -> tuple[Item, ...]:
        found: list[Item] = []
        found += self._bodies()
        found += self._pivots()
        found += self._supports()
        found += self._sliders()
        found += self._tools()
        found += self._markers()
        return tuple(sorted(found, key=lambda it: KINDS.index(it.kind)))

    def _bodies(self) -> list[Item]:
        """Each moving link as a bar (its points in one line) or a plate (their convex outline)."""
        out = []
        for link in range(1, self.mech.n_links_total):
            draw = self.outline[link]
            if not draw:
                continue
            xy = self.local[draw]
            name = str(self.mech.link_names[link])
            if collinear(xy):
                ends = hull(xy)
                out.append(Item("bar", link, xy[ends][:2], name=name))
            else:
                out.append(Item("plate", link, xy[hull(xy)], closed=True, name=name))
        return out

    def _pivots(self) -> list[Item]:
        """A circle at every revolute joint, one for the links a compound hinge joins."""
        return [Item("pivot", link, self.local[p][None], radius=self.r, name=joint)
                for joint, p, link in self.layout.pivots]  # fmt: skip

    def _supports(self) -> list[Item]:
        """A hinge symbol under every revolute joint on the frame, turned towards the freest side."""
        found = self.layout.supports
        apexes = self.local[list(found)].reshape(-1, 2)
        out = []
        for apex, down, joint in zip(apexes, self._free_sides(apexes), found.values(), strict=True):
            triangle, base, hatch = symbols.support(apex, down, self.r)
            out += [Item("support", 0, triangle, closed=True, name=joint), Item("support", 0, base, name=joint)]
            out += [Item("hatch", 0, h, name=joint) for h in hatch]
        return out

    def _free_sides(self, apexes: np.ndarray) -> np.ndarray:
        """For each of ``apexes`` ``(K, 2)``, of down, left, right and up, the direction from it in which a support's
        symbol is crossed by the lines of the moving links at the fewest samples of the cycle, down preferred (by
        :data:`DOWN` of the samples over the sides, twice that over up): ``(K, 2)``."""
        sides = np.array([[0.0, -1.0], [-1.0, 0.0], [1.0, 0.0], [0.0, 1.0]])
        segs = self._link_segments()[None] - apexes[:, None, None, None]  # (K, n, S, 2, 2): sides of links, samples
        box = np.array([1.2 * self.r, -2.6 * self.r, 3.6 * self.r, 2.6 * self.r])
        # in the axes of each side: along it, across it; (K, 4, n S, 2, 2), one support and side a row
        turned = np.stack([segs @ sides.T, segs @ perp(sides).T], -1)  # (K, n, S, 2, 4, 2)
        turned = np.moveaxis(turned, 4, 1).reshape(len(apexes) * len(sides), segs.shape[1] * segs.shape[2], 2, 2)
        hits = segments_hit(np.broadcast_to(box, (len(turned), 1, 4)), turned)[:, 0].reshape(-1, len(sides))
        score = hits / max(segs.shape[2], 1) + DOWN * np.array([0.0, 1.0, 1.0, 2.0])
        return sides[np.argmin(score, axis=1)]

    def _link_segments(self) -> np.ndarray:
        """The sides of every drawn link at every sample of the cycle, ``(n, S, 2, 2)`` (NaN where it does not
        assemble)."""
        if self._segments is None:
            self._segments = np.moveaxis(self.cycle[:, self.layout.sides], 0, 1)  # (S, n, 2, 2) -> (n, S, 2, 2)
        return self._segments

    def _sliders(self) -> list[Item]:
        """A block at every slider, and a hatched guide under those that slide on the frame."""
        out = []
        for k in range(self.mech.n_pairs):
            if self.mech.pair_type[k] != PairType.PRISMATIC:
                continue
            a, b = (int(x) for x in self.mech.pair_links[k])
            p = int(self.mech.pair_points[k, 1])
            origin, u = (x[self.variant] for x in guide(self.kin, k))  # (A, 2)
            joint = str(self.mech.pair_joint[k])
            u_local = to_local(np.array([0.0, 0.0, self.poses[self.first, b, 2]]), u[self.first])
            out.append(Item("block", b, symbols.block(self.local[p], u_local, self.r), closed=True, name=joint))
            if a == 0:
                out += self._guide(joint, p, origin[self.first], u[self.first])
        return out

    def _guide(self, joint: str, p: int, origin: np.ndarray, u: np.ndarray) -> list[Item]:
        """A frame guide along its slider's stroke (3 r beyond each end), hatched on the side with fewer links."""
        s = (self.cycle[:, p] - origin) @ u
        s = s[np.isfinite(s)]
        span = (float(s.min()) - 3 * self.r, float(s.max()) + 3 * self.r) if len(s) else (-3 * self.r, 3 * self.r)
        segs = (self._link_segments() - origin).reshape(-1, 2, 2)
        turned = np.stack([segs @ u, segs @ perp(u)], -1)  # along the guide, across it (left +)
        left = [span[0], 1.5 * self.r, span[1], 8 * self.r]
        right = [span[0], -8 * self.r, span[1], -1.5 * self.r]
        hits = segments_hit(np.array([[left, right]]), turned[None])[0]
        side = 1.0 if hits[0] <= hits[1] else -1.0
        line, hatch = symbols.guide(origin, u, span, side, self.r)
        return [Item("guide", 0, line, name=joint)] + [Item("hatch", 0, h, name=joint) for h in hatch]

    def _tools(self) -> list[Item]:
        """The knives and tools of process loads with their working edges, and the body a striker hits."""
        out = []
        for load in self.mech.loads:
            if load.kind != "process":
                continue
            for p in load.points:
                out += self._blade(int(p), str(load.name))
        if self.mech.blow is not None:
            out += self._anvil(self.mech.blow)
        return out

    def _blade(self, p: int, name: str) -> list[Item]:
        link = int(self.mech.point_link[p])
        joints = [q for q in range(len(self.mech.point_names)) if self.mech.point_link[q] == link and q in self.joint]
        root = self.local[joints].mean(0) if joints else self.local[p]
        d = self.local[p] - root
        if not np.hypot(*d) > 0:
            return []
        body, edge = symbols.blade(self.local[p], d / np.hypot(*d), self.r)
        pname = str(self.mech.point_names[p])
        return [Item("tool", link, body, closed=True, name=pname), Item("edge", link, edge, name=pname)]

    def _anvil(self, blow: ImpactSpec) -> list[Item]:
        p = self.mech.point_index(blow.at)
        face = self.mech.points0()[p]
        n = np.array([np.cos(blow.normal), np.sin(blow.normal)])
        return [Item("tool", 0, symbols.anvil(face, n, self.r), closed=True, name="tool")]

    def _markers(self) -> list[Item]:
        """A dot at every point of a moving link that no pair uses."""
        return [
            Item("marker", int(self.mech.point_link[p]), self.local[p][None], radius=0.45 * self.r,
                 name=str(self.mech.point_names[p]))
            for p in self.moving
            if p not in self.joint
        ]  # fmt: skip

    # ------------------------------------------------------------ labels

    def labels(self, items: tuple[Item, ...], at: list[int]) -> tuple[Label, ...]:
        """Point names, then link numbers, each placed clear of the others and of the lines, at the samples ``at``."""
        wanted = self._point_labels() + self._link_numbers(items)
        if not wanted:
            return ()
        centres = np.full((len(self.poses), len(wanted), 2), np.nan)
        if at:  # none: the labels' texts and anchors only (the viewer's edits move the labels it has)
            centres[at] = self._placed(items, wanted, at)
        return tuple(Label(text, kind, link, local, centres[:, j])
                     for j, (text, kind, link, local, _, _) in enumerate(wanted))  # fmt: skip

    def _placed(self, items: tuple[Item, ...], wanted: list[tuple[str, str, int, np.ndarray, np.ndarray, float]],
                at: list[int]) -> np.ndarray:  # fmt: skip
        """The centres ``(len(at), L, 2)`` of the texts of ``wanted`` at the samples ``at``."""
        # a point's anchor at every sample (A, 2); a link's number's alternatives (M, 2) in its axes, placed
        found = [a if kind == "point" else place(self.poses[:, link], a) for _, kind, link, _, a, _ in wanted]
        count = max(a.shape[1] if a.ndim == 3 else 1 for a in found)
        anchors = np.stack([_alternatives(a, count) for a in found], 1)  # (A, L, M, 2)
        sizes = np.array([text_size(text, self.em) for text, *_ in wanted])
        gaps = np.array([g for *_, g in wanted])
        prefer = np.stack([self._prefer(link, local, kind, anchors[:, j, 0]) for j, (_, kind, link, local, _, _)
                           in enumerate(wanted)], 1)  # fmt: skip
        obstacles = self._obstacles(items)
        return place_labels(anchors[at], sizes, gaps, Obstacles(obstacles.segments[at], obstacles.circles[at]),
                            prefer[at], pad=0.15 * self.em)  # fmt: skip

    def _point_labels(self) -> list[tuple[str, str, int, np.ndarray, np.ndarray, float]]:
        """(text, kind, link, local anchor, anchors (A, 2), gap) of every named point, each name once:
        the joints (a slider's beyond its block), the markers, the frame's points away from any joint."""
        return [(text, "point", link, self.local[p], self.pts[:, p], gap * self.r)
                for text, p, link, gap in self.layout.point_labels]  # fmt: skip

    def _link_numbers(self, items: tuple[Item, ...]) -> list[tuple[str, str, int, np.ndarray, np.ndarray, float]]:
        """(text, kind, link, local anchor, alternatives (M, 2) in the link's axes, gap) of a link's number beside
        the middle of its longest side."""
        out = []
        for it in items:
            if it.kind not in ("bar", "plate"):
                continue
            xy = np.asarray(it.xy)
            ring = np.vstack([xy, xy[:1]]) if it.closed else xy
            sides = np.hypot(*np.diff(ring, axis=0).T)
            i = int(np.argmax(sides))
            along = np.array([0.5, 0.32, 0.68, 0.2, 0.8])[:, None]
            at = ring[i] + along * (ring[i + 1] - ring[i])  # the middle first, then towards the ends
            out.append((str(it.link), "link", it.link, at[0], at, 0.5 * self.r))
        return out

    def _prefer(self, link: int, at: np.ndarray, kind: str, anchors: np.ndarray) -> np.ndarray:
        """Unit directions ``(A, 2)`` away from the drawn points nearest the anchor (for a link's number:
        across its side, to the left going from the side's first point to its last)."""
        if kind == "link":
            poses = self.poses[:, link]
            mid = place(poses, at[None])[:, 0]
            centre = place(poses, self.local[self.outline[link]].mean(0)[None])[:, 0]
            away = mid - centre
        else:
            rel = self.pts[:, self.moving] - anchors[:, None, :]  # (A, Q, 2)
            dist = np.hypot(rel[..., 0], rel[..., 1])
            near = (dist > 1e-9 * self.size) & (dist < 0.35 * self.size)
            unit = np.where(near[..., None], rel / np.where(dist > 0, dist, 1)[..., None], 0.0)
            away = -unit.sum(1)
        size = np.hypot(away[:, 0], away[:, 1])[:, None]
        default = np.array([np.sqrt(0.5), np.sqrt(0.5)])
        return np.where(size > 1e-9, away / np.where(size > 0, size, 1), default)

    def _obstacles(self, items: tuple[Item, ...]) -> Obstacles:
        """The lines and circles of ``items`` at every sample."""
        segs, circles = [], []
        bands: dict[str, list[np.ndarray]] = {}
        for it in items:
            if it.kind == "hatch":  # a band of strokes: the line through their outer ends stands for them
                bands.setdefault(it.name, []).append(np.asarray(it.xy[1], dtype=float))
                continue
            xy = place(self.poses[:, it.link], np.asarray(it.xy, dtype=float))  # (A, K, 2)
            if it.radius:
                circles.append(np.concatenate([xy[:, 0], np.full((len(xy), 1), it.radius)], -1))
                continue
            ring = np.concatenate([xy, xy[:, :1]], 1) if it.closed else xy
            segs.append(np.stack([ring[:, :-1], ring[:, 1:]], 2))
        n = len(self.poses)
        for ends in bands.values():
            segs.append(np.broadcast_to(np.array([ends[0], ends[-1]]), (n, 1, 2, 2)))
        return Obstacles(
            np.concatenate(segs, 1) if segs else np.zeros((n, 0, 2, 2)),
            np.stack(circles, 1) if circles else np.zeros((n, 0, 3)),
        )


@dataclass(frozen=True)
class _Layout:
    """What of a scheme the structure of its mechanism fixes, whatever its dimensions (the same for every variant).

    Attributes
    ----------
    joint : set of int
        The points of pairs.
    moving : list of int
        The points of the drawn moving links.
    outline : dict
        For each link, the points it is drawn through: its joints, then its markers (none for a link of one
        point, the frame and a virtual link).
    sides : ndarray of int, shape (n, 2)
        The points of every drawn link's sides.
    path_points : list of int
        The moving points whose trajectories are drawn.
    pivots : list of (str, int, int)
        Joint, point and link of a pivot's circle at every revolute joint (one a compound hinge).
    supports : dict
        The frame's point of every revolute joint on the frame, and the joint.
    point_labels : list of (str, int, int, float)
        Text, point, link and gap (in pivot radii) of every named point, each name once: the joints (a
        slider's beyond its block), the markers, the frame's points away from any joint.
    """

    joint: set[int]
    moving: list[int]
    outline: dict[int, list[int]]
    sides: np.ndarray
    path_points: list[int]
    pivots: list[tuple[str, int, int]]
    supports: dict[int, str]
    point_labels: list[tuple[str, int, int, float]]


@per_mechanism
def _layout(mech: Mechanism) -> _Layout:
    """The :class:`_Layout` of ``mech``, found once a mechanism (the viewer's edits draw one mechanism's variants)."""
    n_points = len(mech.point_names)
    joint = {int(p) for pair in mech.pair_points for p in pair if p >= 0}
    drawn = [link != 0 and not bool(mech.link_virtual[link]) for link in range(mech.n_links_total)]
    moving = [p for p in range(n_points) if drawn[int(mech.point_link[p])]]
    outline = {}
    for link in range(mech.n_links_total):
        own = [p for p in range(n_points) if mech.point_link[p] == link] if drawn[link] else []
        draw = [p for p in own if p in joint] + [p for p in own if p not in joint]
        outline[link] = draw if len(draw) >= 2 else []
    sides = [(i, j) for draw in outline.values() for i, j in zip(draw, draw[1:], strict=False)]
    revolute = [mech.pair_type[k] == PairType.REVOLUTE for k in range(mech.n_pairs)]
    pivots: dict[str, tuple[str, int, int]] = {}
    supports: dict[int, str] = {}
    for k in range(mech.n_pairs):
        a, b = (int(x) for x in mech.pair_links[k])
        joint_name, p = str(mech.pair_joint[k]), int(mech.pair_points[k, 1])
        if revolute[k]:
            pivots.setdefault(joint_name, (joint_name, p, int(mech.point_link[p])))
        if revolute[k] and 0 in (a, b):
            supports.setdefault(int(mech.pair_points[k, 0 if a == 0 else 1]), joint_name)
    return _Layout(joint, moving, outline, np.array(sides, dtype=int).reshape(-1, 2),
                   [p for p in moving if outline[int(mech.point_link[p])]], list(pivots.values()), supports,
                   _named_points(mech, joint, revolute))  # fmt: skip


def _named_points(mech: Mechanism, joint: set[int], revolute: list[bool]) -> list[tuple[str, int, int, float]]:
    """:attr:`_Layout.point_labels` of ``mech``."""
    short = [name.split(".", 1)[1] for name in mech.point_names]
    sliders = {short[int(mech.pair_points[k, 1])] for k in range(mech.n_pairs) if not revolute[k]}
    out, seen = [], set()
    named = [(lab, p) for lab, p in point_labels(mech) if not mech.link_virtual[mech.point_link[p]]]
    frame = [(short[p], p) for p in range(len(mech.point_names)) if mech.point_link[p] == 0]
    for label, p in named + frame:
        text = label.rsplit(".", 1)[-1] if p not in joint else label
        key = text if p in joint or mech.point_link[p] == 0 else p
        if key in seen:
            continue
        seen.add(key)
        out.append((text, p, int(mech.point_link[p]), 2.6 if p in joint and short[p] in sliders else 1.5))
    return out


def _alternatives(anchors: np.ndarray, count: int) -> np.ndarray:
    """``(A, 2)`` or ``(A, M, 2)`` anchors as ``(A, count, 2)``, the missing alternatives NaN."""
    a = anchors if anchors.ndim == 3 else anchors[:, None, :]
    return np.concatenate([a, np.full((len(a), count - a.shape[1], 2), np.nan)], 1)
