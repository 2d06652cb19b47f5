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

from linkwork.motion.analysis import guide_lines
from linkwork.motion.kinematic_analysis import kinematics
from linkwork.scene import symbols
from linkwork.scene.geometry import bounds, collinear, hull, place, text_size
from linkwork.scene.labels import Obstacles, ends_hit, place_labels
from linkwork.scene.layout import scheme_layout
from linkwork.structure.constraints import perp

if TYPE_CHECKING:
    from linkwork.motion.kinematic_analysis import Kinematics
    from linkwork.structure.records import ImpactRecord

#: The kinds of item, in drawing order (later on top).
KINDS = ("path", "hatch", "support", "guide", "bar", "plate", "tool", "edge", "block", "pivot", "marker")

#: Radius of a pivot and size of the text, as fractions of the drawing's size.
PIVOT, FONT = 0.012, 0.032

#: Samples of the whole turn the fixed symbols are chosen from, where the drawing is given fewer.
CYCLE = 72

#: A support stands down unless another side is crossed at fewer samples by this fraction of them.
DOWN = 0.15

#: The sides a support may stand towards: down, left, right, up.
SIDES = np.array([[0.0, -1.0], [-1.0, 0.0], [1.0, 0.0], [0.0, 1.0]])

#: The box ``[x0, y0, x1, y1]`` a support's symbol takes about its apex standing towards each of :data:`SIDES`, in
#: pivot radii: from 1.2 to 3.6 along the side, 2.6 either side across it (exact: the sides are the axes).
_NEAR, _FAR = 1.2 * SIDES - 2.6 * perp(SIDES), 3.6 * SIDES + 2.6 * perp(SIDES)  # opposite corners of each
SUPPORT_BOXES = np.concatenate([np.minimum(_NEAR, _FAR), np.maximum(_NEAR, _FAR)], 1)

#: What a support's standing towards each of :data:`SIDES` costs beyond the fraction of the samples it is crossed at.
_STANDING = DOWN * np.array([0.0, 1.0, 1.0, 2.0])

#: Where along its longest side a link's number may stand, as fractions of the side: the middle first.
_ALONG = np.array([0.5, 0.32, 0.68, 0.2, 0.8])[:, None]


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
class Element:
    """A spring or a damper between two points of (usually) two links, drawn between them at every pose.

    Attributes
    ----------
    kind : str
        ``"spring"`` (a zigzag) or ``"damper"`` (a dashpot).
    name : str
        The load's name in the file.
    links : tuple of int
        The links of its two points (0: the frame).
    at : ndarray, shape (2, 2)
        The two points, each in its link's axes, m.
    strokes : tuple of ndarray, shape (K, 3)
        The symbol's lines as rows ``(f, s, c)`` (:func:`linkwork.scene.symbols.force_element`).
    """

    kind: str
    name: str
    links: tuple[int, int]
    at: np.ndarray
    strokes: tuple[np.ndarray, ...]


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
    elements: tuple[Element, ...] = ()

    def element_ends(self, element: Element, index: int | None = None) -> np.ndarray:
        """The element's two points in the global axes: ``(A, 2, 2)``, or ``(2, 2)`` at sample ``index``."""
        at = slice(None) if index is None else slice(index, index + 1)
        ends = np.stack(
            [place(self.poses[at, link], element.at[j : j + 1])[:, 0] for j, link in enumerate(element.links)], 1
        )
        return ends if index is None else ends[0]

    def element_strokes(self, element: Element, index: int | None = None) -> list[np.ndarray]:
        """The element's lines in the global axes, each ``(A, K, 2)``, or ``(K, 2)`` at sample ``index``: its
        symbol's rows ``(f, s, c)`` laid between its two points (NaN where they meet)."""
        ends = self.element_ends(element, index)
        a, b = ends[..., 0, :], ends[..., 1, :]
        d = b - a
        with np.errstate(divide="ignore", invalid="ignore"):
            u = d / np.linalg.norm(d, axis=-1, keepdims=True)
        n = perp(u)
        a, d, u, n = (v[..., None, :] for v in (a, d, u, n))
        return [a + f[:, None] * d + s[:, None] * u + c[:, None] * n for f, s, c in (x.T for x in element.strokes)]

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


def scheme_scene(
    kin: Kinematics, variant: int = 0, at: list[int] | None = None, cycle: Kinematics | None = None
) -> SchemeScene:
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
        elements=b.elements(),
    )


class _Builder:
    """The scheme's items and labels from one variant of a kinematics result."""

    def __init__(self, kin: Kinematics, variant: int, cycle: Kinematics) -> None:
        self.kin, self.mech, self.variant = kin, kin.mechanism, variant
        self.layout = layout = scheme_layout(self.mech)
        self.joint, self.moving, self.outline = layout.joint, layout.moving, layout.outline
        self.path_points = layout.path_points
        self.poses = np.array(kin.pose[variant])  # (A, N, 3)
        self.local = np.asarray(kin.local[:, :, variant, 0], dtype=float)  # (P, 2)
        self.pts = _points(kin, variant)  # (A, P, 2)
        self.cycle = self.pts if cycle is kin else _points(cycle, min(variant, cycle.q.shape[2] - 1))  # (S, P, 2)
        self._segments: np.ndarray | None = None
        box = bounds(self.cycle[:, self.moving], self.local[layout.frame_points])
        self.size = float(max(box[2] - box[0], box[3] - box[1], 1e-9))
        self.r, self.em = PIVOT * self.size, FONT * self.size
        self.first = int(np.argmax(np.asarray(kin.valid_all[variant]))) if len(self.pts) else 0

    # ------------------------------------------------------------ items

    def elements(self) -> tuple[Element, ...]:
        """The springs and dampers between two points, in the order of the file's loads."""
        out = []
        for load in self.mech.loads:
            if load.kind in ("spring", "damper"):
                links = (int(self.mech.point_link[load.points[0]]), int(self.mech.point_link[load.points[1]]))
                strokes = symbols.force_element(load.kind, self.r)
                out.append(Element(load.kind, load.name, links, self.local[list(load.points)], strokes))
        return tuple(out)

    def items(self) -> tuple[Item, ...]:
        """Every item, in drawing order."""
        apexes = self.local[list(self.layout.supports)].reshape(-1, 2)
        origins, directions = self._guide_lines()
        on = self.layout.sliders.on_frame  # the guides drawn: those on the frame
        spans = [
            self._stroke(p, origin, u)
            for p, origin, u in zip(self.layout.sliders.guided, origins[on], directions[on], strict=True)
        ]
        downs, sides = self._free_sides(apexes, origins[on], directions[on], spans)
        supports, bases = self._supports(apexes, downs)
        guides, lines = self._guides(origins[on], directions[on], spans, sides)
        found = self._bodies() + self._pivots() + supports + self._blocks(directions) + guides
        found += self._tools() + self._markers()
        found += self._hatches(bases + lines, [*self.layout.supports.values(), *self.layout.sliders.guide_joints])
        return tuple(sorted(found, key=_drawn_before))

    def _bodies(self) -> list[Item]:
        """Each moving link as a bar (its points in one line) or a plate (their convex outline)."""
        out = []
        at = self.local.tolist()  # a bar of two points: its ends in the order of the hull's (x, then y)
        pairs = [
            draw[::-1] if at[draw[1]] < at[draw[0]] else draw for _, draw, _ in self.layout.bodies if len(draw) == 2
        ]
        ends = iter(self.local[pairs] if pairs else ())
        for link, draw, name in self.layout.bodies:
            if len(draw) == 2:
                out.append(_item("bar", link, next(ends), name=name))
                continue
            xy = self.local[draw]
            if collinear(xy):
                out.append(_item("bar", link, xy[hull(xy)][:2], name=name))
            else:
                out.append(_item("plate", link, xy[hull(xy)], closed=True, name=name))
        return out

    def _pivots(self) -> list[Item]:
        """A circle at every revolute joint, one for the links a compound hinge joins."""
        return [
            _item("pivot", link, self.local[p][None], radius=self.r, name=joint)
            for joint, p, link in self.layout.pivots
        ]

    def _supports(self, apexes: np.ndarray, downs: np.ndarray) -> tuple[list[Item], list[symbols.Hatch]]:
        """A hinge symbol under every revolute joint on the frame at ``apexes``, turned towards ``downs``, and
        their bases to hatch."""
        out, bases = [], []
        for apex, down, joint in zip(apexes.tolist(), downs.tolist(), self.layout.supports.values(), strict=True):
            triangle, base = symbols.support(apex, down, self.r)
            out += [
                _item("support", 0, triangle, closed=True, name=joint),
                _item("support", 0, np.array(base[:2]), name=joint),
            ]
            bases.append(base)
        return out, bases

    def _hatches(self, lines: list[symbols.Hatch], joints: list[str]) -> list[Item]:
        """The strokes hatching ``lines``, each named for its joint of ``joints``."""
        out = []
        for strokes, joint in zip(symbols.hatches(lines, self.r), joints, strict=True):
            out += _lines("hatch", strokes, joint)
        return out

    def _free_sides(
        self, apexes: np.ndarray, origins: np.ndarray, directions: np.ndarray, spans: list[tuple[float, float]]
    ) -> tuple[np.ndarray, list[float]]:
        """The sides the supports stand on and the guides are hatched on, from one count of the crossings of the
        lines of the moving links over the cycle (:func:`~linkwork.scene.labels.ends_hit`).

        For each of ``apexes`` ``(K, 2)``, of :data:`SIDES`, the direction from it in which a support's symbol is
        crossed at the fewest samples, down preferred (by :data:`DOWN` of the samples over the sides, twice that over
        up): ``(K, 2)``; for each guide on the frame through ``origins`` along ``directions`` ``(G, 2)`` over its
        stroke ``spans``, the side it is hatched on (+1 left of its direction, -1 right): the one with fewer
        crossings.  The links' sides are taken about each apex (each side's box there, :data:`SUPPORT_BOXES`), and in
        each guide's axes (a box along it on either side; two boxes that nothing meets make as many as a support's).
        """
        segs = self._link_segments()  # (n, S, 2, 2)
        count, r = len(apexes), self.r
        ends = np.empty((4, count + len(spans), segs.shape[0] * segs.shape[1]))  # x0, y0, x1, y1 of the sides
        boxes = np.full((count + len(spans), len(SIDES), 4), np.nan)  # where each support or guide is drawn
        np.subtract(segs.reshape(-1, 4).T[:, None], apexes[:, [0, 1, 0, 1]].T[..., None], out=ends[:, :count])
        boxes[:count] = SUPPORT_BOXES * r
        for row, (origin, u, (lo, hi)) in enumerate(zip(origins, directions, spans, strict=True), count):
            ends[0::2, row], ends[1::2, row] = (x.T for x in self._along(origin, u))
            boxes[row, :2] = [[lo, 1.5 * r, hi, 8 * r], [lo, -8 * r, hi, -1.5 * r]]  # left of the guide, right
        hits = ends_hit(boxes, ends)
        score = hits[:count] / max(segs.shape[1], 1) + _STANDING
        return SIDES[np.argmin(score, axis=1)], [
            1.0 if left <= right else -1.0 for left, right in hits[count:, :2].tolist()
        ]

    def _along(self, origin: np.ndarray, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The ends of the sides of the links in the axes of the guide through ``origin`` along ``u``: along it and
        across it (left +), ``(n S, 2)`` each."""
        segs = (self._link_segments() - origin).reshape(-1, 2, 2)
        return segs @ u, segs @ perp(u)

    def _link_segments(self) -> np.ndarray:
        """The sides of every drawn link at every sample of the cycle, ``(n, S, 2, 2)`` (NaN where it does not
        assemble)."""
        if self._segments is None:  # (S, n, 2, 2) -> (n, S, 2, 2)
            self._segments = np.ascontiguousarray(self.cycle[:, self.layout.sides].swapaxes(0, 1))
        return self._segments

    def _guide_lines(self) -> tuple[np.ndarray, np.ndarray]:
        """A point of every slider's guide line and its unit direction, ``(B, 2)`` each (global, m), at the first
        sample that assembles (:func:`~linkwork.motion.analysis.guide_lines`)."""
        origin, direction = guide_lines(self.kin, self.layout.sliders.pairs)  # (B, 2, V, A)
        return origin[..., self.variant, self.first], direction[..., self.variant, self.first]

    def _blocks(self, directions: np.ndarray) -> list[Item]:
        """A block at every slider along its guide's direction of ``directions`` ``(B, 2)``, in its link's axes."""
        sliders, out = self.layout.sliders, []
        angles = self.poses[self.first, sliders.links, 2]
        turns = np.cos(angles).tolist(), np.sin(angles).tolist()
        centres = self.local[sliders.points].tolist()
        for link, centre, (ux, uy), c, s, joint in zip(
            sliders.links, centres, directions.tolist(), *turns, sliders.joints, strict=True
        ):
            u = (c * ux + s * uy, -s * ux + c * uy)  # in the link's axes
            out.append(_item("block", link, symbols.block(centre, u, self.r), closed=True, name=joint))
        return out

    def _stroke(self, p: int, origin: np.ndarray, u: np.ndarray) -> tuple[float, float]:
        """Where a guide through ``origin`` along ``u`` runs: the stroke of its slider's point ``p`` over the cycle,
        3 r beyond each end."""
        x = (self.cycle[:, p] - origin) @ u
        x = x[np.isfinite(x)]
        return (float(x.min()) - 3 * self.r, float(x.max()) + 3 * self.r) if len(x) else (-3 * self.r, 3 * self.r)

    def _guides(
        self, origins: np.ndarray, directions: np.ndarray, spans: list[tuple[float, float]], sides: list[float]
    ) -> tuple[list[Item], list[symbols.Hatch]]:
        """The guides on the frame through ``origins`` along ``directions`` over ``spans``, and their lines to hatch
        on ``sides``."""
        lines = [
            symbols.guide(origin, u, span, side, self.r)
            for origin, u, span, side in zip(origins.tolist(), directions.tolist(), spans, sides, strict=True)
        ]
        joints = self.layout.sliders.guide_joints
        return [
            _item("guide", 0, np.array(line[:2]), name=joint) for line, joint in zip(lines, joints, strict=True)
        ], lines

    def _tools(self) -> list[Item]:
        """The knives and tools of process loads with their working edges, and the body a striker hits."""
        out = []
        for p, name, link, joints in self.layout.blades:
            out += self._blade(p, name, link, joints)
        if self.mech.blow is not None:
            out += self._anvil(self.mech.blow)
        return out

    def _blade(self, p: int, name: str, link: int, joints: list[int]) -> list[Item]:
        """A knife at point ``p`` of a process load, facing away from the mean of ``joints``, those of its link
        (none where it is at their mean)."""
        root = self.local[joints].sum(0) / len(joints) if joints else self.local[p]  # their mean
        (ex, ey), (rx, ry) = self.local[p].tolist(), root.tolist()
        dx, dy = ex - rx, ey - ry
        length = float(np.hypot(dx, dy))
        if not length > 0:
            return []
        body, line = symbols.blade((ex, ey), (dx / length, dy / length), self.r)
        return [_item("tool", link, body, closed=True, name=name), _item("edge", link, line, name=name)]

    def _anvil(self, blow: ImpactRecord) -> list[Item]:
        p = self.mech.point_index(blow.at)
        face = self.mech.points0()[p]
        n = np.array([np.cos(blow.normal), np.sin(blow.normal)])
        return [_item("tool", 0, symbols.anvil(face, n, self.r), closed=True, name="tool")]

    def _markers(self) -> list[Item]:
        """A dot at every point of a moving link that no pair uses."""
        return [
            _item("marker", link, self.local[p][None], radius=0.45 * self.r, name=name)
            for p, link, name in self.layout.markers
        ]

    # ------------------------------------------------------------ labels

    def labels(self, items: tuple[Item, ...], at: list[int]) -> tuple[Label, ...]:
        """Point names, then link numbers, each placed clear of the others and of the lines, at the samples ``at``."""
        wanted = self._point_labels() + self._link_numbers(items)
        if not wanted:
            return ()
        centres = np.full((len(self.poses), len(wanted), 2), np.nan)
        if at:  # none: the labels' texts and anchors only (the viewer's edits move the labels it has)
            centres[at] = self._placed(items, wanted, at)
        return tuple(
            _label(text, kind, link, local, centres[:, j]) for j, (text, kind, link, local, _, _) in enumerate(wanted)
        )

    def _placed(
        self, items: tuple[Item, ...], wanted: list[tuple[str, str, int, np.ndarray, np.ndarray, float]], at: list[int]
    ) -> np.ndarray:
        """The centres ``(len(at), L, 2)`` of the texts of ``wanted`` at the samples ``at``."""
        # a point's anchor at every sample (A, 2); a link's number's alternatives (M, 2) in its axes, placed
        found = [a if kind == "point" else place(self.poses[:, link], a) for _, kind, link, _, a, _ in wanted]
        count = max(a.shape[1] if a.ndim == 3 else 1 for a in found)
        anchors = np.stack([_alternatives(a, count) for a in found], 1)  # (A, L, M, 2)
        sizes = np.array([text_size(text, self.em) for text, *_ in wanted])
        gaps = np.array([g for *_, g in wanted])
        prefer = np.stack(
            [
                self._prefer(link, local, kind, anchors[:, j, 0])
                for j, (_, kind, link, local, _, _) in enumerate(wanted)
            ],
            1,
        )
        obstacles = self._obstacles(items)
        return place_labels(
            anchors[at],
            sizes,
            gaps,
            Obstacles(obstacles.segments[at], obstacles.circles[at]),
            prefer[at],
            pad=0.15 * self.em,
        )

    def _point_labels(self) -> list[tuple[str, str, int, np.ndarray, np.ndarray, float]]:
        """(text, kind, link, local anchor, anchors (A, 2), gap) of every named point, each name once:
        the joints (a slider's beyond its block), the markers, the frame's points away from any joint."""
        return [
            (text, "point", link, self.local[p], self.pts[:, p], gap * self.r)
            for text, p, link, gap in self.layout.point_labels
        ]

    def _link_numbers(self, items: tuple[Item, ...]) -> list[tuple[str, str, int, np.ndarray, np.ndarray, float]]:
        """(text, kind, link, local anchor, alternatives (M, 2) in the link's axes, gap) of a link's number beside
        the middle of its longest side."""
        bars = [it for it in items if it.kind == "bar"]  # two ends each, before the plates
        out = []
        if bars:
            ends = np.array([it.xy for it in bars])  # (B, 2, 2)
            at = ends[:, None, 0] + _ALONG * (ends[:, None, 1] - ends[:, None, 0])  # the middle first, then the ends
            out += [
                (str(it.link), "link", it.link, each[0], each, 0.5 * self.r) for it, each in zip(bars, at, strict=True)
            ]
        for it in items:
            if it.kind != "plate":
                continue
            xy = np.asarray(it.xy)
            ring = np.vstack([xy, xy[:1]]) if it.closed else xy
            i = int(np.argmax(np.hypot(*np.diff(ring, axis=0).T)))
            at = ring[i] + _ALONG * (ring[i + 1] - ring[i])  # the middle first, then towards the ends
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


def _item(kind: str, link: int, xy: np.ndarray, closed: bool = False, radius: float = 0.0, name: str = "") -> Item:
    """An :class:`Item`, made without the dataclass's ``__init__``, which sets the fields of a frozen dataclass one
    at a time (a scheme has some ninety items, and the viewer makes one on every edit)."""
    out = object.__new__(Item)
    out.__dict__.update(kind=kind, link=link, xy=xy, closed=closed, radius=radius, name=name)
    return out


def _lines(kind: str, shapes: np.ndarray, name: str) -> list[Item]:
    """Open lines in the frame's axes, of one ``kind`` and ``name``, an item each of ``shapes`` ``(H, K, 2)`` (a
    support's or a guide's hatching, some twenty strokes), made as :func:`_item` makes one."""
    fields = {"kind": kind, "link": 0, "xy": None, "closed": False, "radius": 0.0, "name": name}
    out = []
    for xy in shapes:
        item = object.__new__(Item)
        item.__dict__.update(fields)
        item.__dict__["xy"] = xy
        out.append(item)
    return out


def _label(text: str, kind: str, link: int, at: np.ndarray, centre: np.ndarray) -> Label:
    """A :class:`Label`, made as :func:`_item` makes an item."""
    out = object.__new__(Label)
    out.__dict__.update(text=text, kind=kind, link=link, at=at, centre=centre)
    return out


#: The place of each kind of item in the drawing order.
_DEPTH = {kind: i for i, kind in enumerate(KINDS)}


def _drawn_before(item: Item) -> int:
    """The key that sorts items in drawing order."""
    return _DEPTH[item.kind]


def _points(kin: Kinematics, variant: int) -> np.ndarray:
    """Every point of design variant ``variant`` at every sample, ``(A, P, 2)``."""
    every = kin.point_positions(np.arange(len(kin.mechanism.point_names)), variant)  # (P, 1, A, 2)
    return np.ascontiguousarray(every[:, 0].swapaxes(0, 1))


def _alternatives(anchors: np.ndarray, count: int) -> np.ndarray:
    """``(A, 2)`` or ``(A, M, 2)`` anchors as ``(A, count, 2)``, the missing alternatives NaN."""
    a = anchors if anchors.ndim == 3 else anchors[:, None, :]
    return np.concatenate([a, np.full((len(a), count - a.shape[1], 2), np.nan)], 1)
