"""Velocity and acceleration plans of the graphical method, as data.

For one position, a plan has the pole ``p`` (zero velocity or
acceleration), the end point of every point's absolute vector (labelled
with the point's name in lower case: ``a``, ``b``, ...), and the relative
vectors of the construction, group by group in solving order, exactly as
the graphical method draws them:

* a link turning about a known point P carries X with ``v_XP`` normal to PX,
  and ``a_XP = a^n_XP + a^t_XP`` (normal component along XP towards P,
  tangential component normal to PX);
* a link sliding on a guide carries X with the velocity of the guide's
  coincident point ``x'`` plus the relative velocity along the guide, and
  the acceleration of ``x'`` plus the Coriolis component ``2 omega v_rel``
  plus the relative acceleration along the guide.

The constructions cover cranks and RRR, RRP, PRP and RPR dyads (the RPR
with its Coriolis component, as for the slotted rocker of a shaper); the
points of other groups (RPP, Newton-solved groups) appear by their absolute
vectors only.

For the double-cut shears the velocity plan of E is ``v_E = v_D + v_ED``
(``v_ED`` normal to DE) ``= v_E'`` (zero: the guide is fixed) ``+ v_EE'``
(vertical), as in equations (3)-(5) of the paper.

:func:`plan_series` builds the plans of every position of every variant at
once (arrays over variants x angles, one construction); :func:`plans` is the
view of one position.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, NamedTuple

import numpy as np

from linkwork.motion import groups
from linkwork.motion.analysis import guide_lines
from linkwork.motion.kinematic_analysis import Kinematics
from linkwork.structure.model import Mechanism, PairType, per_mechanism, point_labels
from linkwork.structure.records import Arm, Step


@dataclass(frozen=True)
class PlanVector:
    """One vector of the construction, from plan point ``start`` to plan point ``end``.

    ``kind``: ``absolute`` (from the pole), ``rotation`` (velocity of X about P),
    ``normal`` and ``tangential`` (acceleration of X about P), ``transport``
    (velocity or acceleration of the guide's coincident point), ``coriolis``,
    ``sliding`` (relative motion along the guide).
    """

    start: str
    end: str
    vector: tuple[float, float]
    kind: str
    group: str
    about: str = ""

    def as_dict(self) -> dict[str, Any]:
        return {
            "from": self.start,
            "to": self.end,
            "vector": list(self.vector),
            "kind": self.kind,
            "group": self.group,
            "about": self.about,
        }


@dataclass(frozen=True)
class Plan:
    """A velocity or acceleration plan of one position.

    Attributes
    ----------
    kind : str
        ``"velocity"`` (vectors in m/s) or ``"acceleration"`` (m/s^2).
    angle : float
        Drive coordinate of the position (rad).
    points : dict
        Plan point label -> vector from the pole (the point's absolute velocity or acceleration).
    vectors : list of PlanVector
        The relative vectors of the construction.
    scale : float
        Units per millimetre of drawing, a round number that makes the
        longest vector at most 100 mm long (e.g. 0.02 means (m/s)/mm).
    """

    kind: str
    angle: float
    points: dict[str, tuple[float, float]]
    vectors: list[PlanVector] = field(default_factory=list)
    scale: float = 1.0

    def as_dict(self) -> dict[str, Any]:
        return {
            "kind": self.kind,
            "angle_deg": float(np.degrees(self.angle)),
            "pole": [0.0, 0.0],
            "points": {k: list(v) for k, v in self.points.items()},
            "vectors": [v.as_dict() for v in self.vectors],
            "scale_per_mm": self.scale,
            "unit": "m/s" if self.kind == "velocity" else "m/s^2",
        }


def drawing_scale(longest: float) -> float:
    """A drawing scale from the 1-2-5 series that draws ``longest`` at most 100 mm long.

    Parameters
    ----------
    longest : float
        The longest vector to draw, in its own unit (m/s, m/s^2, N...).

    Returns
    -------
    float
        Units per millimetre of drawing: the least of 1, 2, 2.5, 5 times a power of ten at least ``longest`` / 100;
        1.0 where ``longest`` is not positive (or NaN).
    """
    if not longest > 0:
        return 1.0
    raw = longest / 100.0
    exp = np.floor(np.log10(raw))
    for m in (1, 2, 2.5, 5, 10):
        if m * 10**exp >= raw:
            return float(m * 10**exp)
    return float(10 ** (exp + 1))


def percentile(x: np.ndarray, q: float) -> float:
    """``np.percentile(x, q)`` of a non-empty 1-D array without NaN: the same interpolation between the same two
    values of ``x`` in order, found by a partition (without the general function's checks and copies)."""
    n = len(x)
    at = (n - 1) * (q / 100)
    if at >= n - 1:
        return float(np.max(x))
    lo = math.floor(at)
    below, above = np.partition(x, (lo, lo + 1))[lo : lo + 2]
    t = at - lo
    step = above - below
    return float(above - step * (1 - t) if t >= 0.5 else below + step * t)


@dataclass(frozen=True)
class PlanEdge:
    """One vector of the construction, without its values: see :class:`PlanVector`."""

    start: str
    end: str
    kind: str
    group: str
    about: str = ""


@dataclass(frozen=True)
class PlanSeries:
    """The velocity or acceleration plan of every position of every variant: one construction.

    Attributes
    ----------
    kind : str
        ``"velocity"`` (m/s) or ``"acceleration"`` (m/s^2).
    angles : ndarray, shape (A,)
        Drive coordinates of the positions (rad).
    points : tuple of str
        Labels of the plan points that are the points' absolute vectors, ``p`` (the pole) first among them.
    labels : tuple of str
        Every plan point: ``points``, then the construction's intermediate points in order.
    edges : tuple of PlanEdge
        The relative vectors of the construction, group by group in solving order.
    values : ndarray, shape (V, A, L, 2)
        Each plan point (``labels``) from the pole; NaN where the mechanism does not assemble.
    vectors : ndarray, shape (V, A, E, 2)
        Each vector of the construction (``edges``).
    """

    kind: str
    angles: np.ndarray
    points: tuple[str, ...]
    labels: tuple[str, ...]
    edges: tuple[PlanEdge, ...]
    values: np.ndarray
    vectors: np.ndarray

    def at(self, index: int, variant: int = 0) -> Plan:
        """The plan of one position."""
        values, vectors = self.values[variant, index], self.vectors[variant, index]
        points = {lab: (float(values[j, 0]), float(values[j, 1])) for j, lab in enumerate(self.points)}
        vecs = [
            PlanVector(e.start, e.end, (float(vectors[j, 0]), float(vectors[j, 1])), e.kind, e.group, e.about)
            for j, e in enumerate(self.edges)
        ]
        longest = float(longest_length(values[: len(self.points)]))
        return Plan(self.kind, float(self.angles[index]), points, vecs, drawing_scale(longest))


def longest_length(vectors: np.ndarray) -> np.ndarray:
    """Length of the longest finite vector of each set.

    Parameters
    ----------
    vectors : ndarray
        ``(..., K, 2)``: sets of ``K`` vectors.

    Returns
    -------
    ndarray
        ``(...)``: the length of the longest finite vector of each set; 0 where none is finite.
    """
    size = np.hypot(vectors[..., 0], vectors[..., 1])
    return np.max(size, axis=-1, initial=0.0, where=np.isfinite(size))


def plans(kin: Kinematics, index: int, variant: int = 0) -> tuple[Plan, Plan]:
    """The velocity and acceleration plans of sample ``index`` (of design variant ``variant``)."""
    n = len(kin.angles)
    if not -n <= index < n:
        raise IndexError(f"sample {index} is out of range: the result has {n} angles")
    i = index % n
    vel, acc = plan_series(kin.samples(slice(i, i + 1)))
    return vel.at(0, variant), acc.at(0, variant)


def plan_series(kin: Kinematics) -> tuple[PlanSeries, PlanSeries]:
    """The velocity and acceleration plans of every sample and variant of a kinematics result, at once.

    The construction of the mechanism (its plan points, its edges, the arrays each edge is read from) is
    found once per mechanism (:func:`_layout`); a call computes each kind of vector for all the points,
    turns or slides together, a few NumPy operations in all, on arrays ``(K, 2, V, A)`` (each vector's
    components, then the variants and the samples; the samples last, so that each operation runs along
    them).  The arithmetic is the construction's, in its order.

    Returns
    -------
    velocity, acceleration : PlanSeries
        Values ``(V, A, L, 2)`` in m/s and m/s^2.
    """
    lay = _layout(kin.mechanism)
    links = _Links(*(np.ascontiguousarray(x) for x in (kin.q, kin.v, kin.a)))
    pts = np.ascontiguousarray(kin.point_positions(lay.placed).transpose(0, 3, 1, 2))  # (P, 2, V, A)
    rotation, normal, tangential = _turns(links, lay, pts)
    (v_abs, v_tr, v_x), (a_abs, a_tr, a_x) = _material(links, lay, pts)
    u = guide_lines(kin, lay.slide_pair)[1]
    sdot = np.sum((v_x - v_tr) * u, 1, keepdims=True)
    cor = 2 * links.v.take(lay.slide_carrier, 0)[:, 2:3] * sdot * _perp(u)
    sddot = np.sum((a_x - a_tr - cor) * u, 1, keepdims=True)
    vel = np.concatenate([rotation, v_tr, sdot * u])
    acc = np.concatenate([normal, tangential, a_tr, cor, sddot * u])
    return _series(kin, lay, lay.velocity, v_abs, vel), _series(kin, lay, lay.acceleration, a_abs, acc)


class _Links(NamedTuple):
    """Poses, velocities and accelerations of the links ``(N, 3, V, A)``, C-contiguous (of :class:`Kinematics`)."""

    q: np.ndarray
    v: np.ndarray
    a: np.ndarray


#: The quarter turn of :func:`_perp`.
_QUARTER = np.array([-1.0, 1.0])[:, None, None]


def _perp(u: np.ndarray) -> np.ndarray:
    """Vectors ``(K, 2, V, A)`` turned a quarter counter-clockwise: :func:`~linkwork.structure.constraints.perp`
    with the components on the second axis."""
    return u[:, ::-1] * _QUARTER


def _material(links: _Links, lay: _Layout, pts: np.ndarray) -> tuple[list[np.ndarray], list[np.ndarray]]:
    """Velocities and accelerations ``(K, 2, V, A)`` of the material points read: the point of each
    absolute plan point on its link, then each sliding point on its link's carrier, then on its link.

    Of a link ``(x, y, theta)`` at ``X``: ``v + w perp(r)`` and ``a + e perp(r) - w^2 r``, ``r = X - (x, y)``.
    """
    q, v, a = (x.take(lay.at_link, 0) for x in links)
    r = pts.take(lay.at_point, 0) - q[:, :2]
    w, e, pr = v[:, 2:3], a[:, 2:3], _perp(r)
    vel, acc = v[:, :2] + w * pr, a[:, :2] + e * pr - w * w * r
    n, s = len(lay.points), len(lay.slide_pair)
    return [vel[:n], vel[n : n + s], vel[n + s :]], [acc[:n], acc[n : n + s], acc[n + s :]]


def _turns(links: _Links, lay: _Layout, pts: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Each turning point X with its link about the link's outer joint P, ``(T, 2, V, A)`` each:
    v = w perp(r); a = a^n + a^t, a^n = -w^2 r, a^t = e perp(r); r = X - P."""
    r = pts.take(lay.turn_point, 0) - pts.take(lay.turn_about, 0)
    w, e = links.v.take(lay.turn_link, 0)[:, 2:3], links.a.take(lay.turn_link, 0)[:, 2:3]
    pr = _perp(r)
    return w * pr, -w * w * r, e * pr


def _series(kin: Kinematics, lay: _Layout, plot: _Plot, absolute: np.ndarray, vectors: np.ndarray) -> PlanSeries:
    """The plan of a kind from the absolute plan points ``(len(lay.points), 2, V, A)`` and the kind's
    vectors ``(K, 2, V, A)`` (its arrays of vectors concatenated, see :func:`plan_series`): the edges'
    vectors, the intermediate points reached along the construction, NaN the others."""
    vectors = vectors.take(plot.order, 0)
    values = np.empty((len(plot.labels),) + absolute.shape[1:])
    values[: len(absolute)], values[len(absolute) :] = absolute, np.nan
    for end, start, edge in plot.reached:
        values[end] = values.take(start, 0) + vectors.take(edge, 0)
    values, vectors = _samples_first(values), _samples_first(vectors)
    return PlanSeries(plot.kind, kin.angles, lay.points, plot.labels, plot.edges, values, vectors)


def _samples_first(x: np.ndarray) -> np.ndarray:
    """``(K, 2, V, A) -> (V, A, K, 2)``, C-contiguous."""
    return np.ascontiguousarray(x.transpose(2, 3, 0, 1))


class _Plot(NamedTuple):
    """The plan of one kind of a mechanism, without its values.

    ``order``: where each edge's vector is in the kind's arrays of vectors as :func:`plan_series`
    concatenates them (:data:`_VECTORS`); ``reached``: the intermediate plan points, each the point an
    edge starts from plus the edge's vector, in rounds (a round's points start from points known before
    it), each round index arrays ``(labels reached, labels they start from, edges)``.
    """

    kind: str
    labels: tuple[str, ...]
    edges: tuple[PlanEdge, ...]
    order: np.ndarray
    reached: tuple[tuple[np.ndarray, ...], ...]


#: The kinds of vectors of each plan, in the order :func:`plan_series` concatenates their arrays.
_VECTORS = {
    "velocity": ("rotation", "transport", "sliding"),
    "acceleration": ("normal", "tangential", "transport", "coriolis", "sliding"),
}


class _Layout(NamedTuple):
    """The graphical construction of a mechanism, without its values (:func:`_layout`).

    ``placed``: the points whose positions are read; ``points``: the
    absolute plan points' labels; ``turn_*``: each point X turning with a link about a point P
    (:func:`_turns`); ``slide_*``: each point X on a link sliding along a guide of its carrier, the
    guide's prismatic pair; ``at_link``, ``at_point``: the material points whose velocities and
    accelerations are read (:func:`_material`).  Points (but ``placed``) are numbered among ``placed``.
    """

    placed: np.ndarray
    points: tuple[str, ...]
    turn_point: np.ndarray
    turn_about: np.ndarray
    turn_link: np.ndarray
    slide_carrier: np.ndarray
    slide_pair: np.ndarray
    at_link: np.ndarray
    at_point: np.ndarray
    velocity: _Plot
    acceleration: _Plot


@per_mechanism
def _layout(mech: Mechanism) -> _Layout:
    """The graphical construction of ``mech`` (found once per mechanism: its structure alone decides it;
    shared, not to be changed)."""
    c = Construction(mech)
    for step in mech.program:
        c.step(step)
    turn = np.array(c.turns, dtype=int).reshape(-1, 3).T
    slide = np.array(c.slides, dtype=int).reshape(-1, 4).T
    points = tuple(dict.fromkeys(c.label))
    first = np.array([c.label.index(lab) for lab in points], dtype=int)
    at_point = np.concatenate([first, slide[0], slide[0]])
    placed, among = np.unique(np.concatenate([at_point, turn[0], turn[1]]), return_inverse=True)
    at_point, turn_point, turn_about = np.split(among, np.cumsum([len(at_point), len(turn[0])]))
    t, s = len(c.turns), len(c.slides)
    size = {"rotation": t, "normal": t, "tangential": t, "transport": s, "coriolis": s, "sliding": s}
    return _Layout(
        placed=placed,
        points=points,
        turn_point=turn_point,
        turn_about=turn_about,
        turn_link=turn[2],
        slide_carrier=slide[2],
        slide_pair=slide[3],
        at_link=np.concatenate([mech.point_link[first], slide[2], slide[1]]).astype(int),
        at_point=at_point,
        velocity=_plot("velocity", points, c.vel, size),
        acceleration=_plot("acceleration", points, c.acc, size),
    )


def _plot(kind: str, points: tuple[str, ...], edges: list[tuple[PlanEdge, int]], size: dict[str, int]) -> _Plot:
    """The plan of a kind from its edges, each with its number among the vectors of its kind (``size``
    of them)."""
    kinds = _VECTORS[kind]
    offset = dict(zip(kinds, np.cumsum([0] + [size[k] for k in kinds[:-1]]).tolist(), strict=True))
    labels = list(points)
    for edge, _ in edges:
        for lab in (edge.start, edge.end):
            if lab not in labels:
                labels.append(lab)
    plan = tuple(e for e, _ in edges)
    order = np.array([offset[e.kind] + i for e, i in edges], dtype=int)
    return _Plot(kind, tuple(labels), plan, order, _reached(labels, points, plan))


def _reached(
    labels: list[str], points: tuple[str, ...], edges: tuple[PlanEdge, ...]
) -> tuple[tuple[np.ndarray, ...], ...]:
    """The intermediate plan points along the construction, each reached by the first edge to it from a
    known point (that point plus the edge's vector), in rounds: index arrays ``(labels reached, labels
    they start from, edges)`` of each round."""
    round_of = dict.fromkeys(points, 0)
    rounds: list[list[tuple[int, int, int]]] = []
    for j, edge in enumerate(edges):
        if edge.start in round_of and edge.end not in round_of:
            n = round_of[edge.end] = round_of[edge.start] + 1
            if n > len(rounds):
                rounds.append([])
            rounds[n - 1].append((labels.index(edge.end), labels.index(edge.start), j))
    return tuple(tuple(np.array(column, dtype=int) for column in zip(*found, strict=True)) for found in rounds)


class Construction:
    """The graphical construction of a mechanism, step by step in solving order, without its values:
    the turning and sliding points it draws, and the edges of its velocity and acceleration plans (each
    with its number among the vectors of its kind)."""

    def __init__(self, mech: Mechanism) -> None:
        self.mech = mech
        self.names = [n.split(".", 1)[1] for n in mech.point_names]
        grounded = {
            int(mech.pair_points[k, 1])
            for k in range(mech.n_pairs)
            if mech.pair_type[k] == PairType.REVOLUTE and mech.pair_links[k, 0] == 0
        }
        labels = {p: label.lower() for label, p in point_labels(mech, with_all=True)}
        self.label = [
            "p" if mech.point_link[p] == 0 or p in grounded else labels[p] for p in range(len(mech.point_names))
        ]
        self.turns: list[tuple[int, int, int]] = []  # point, the point it turns about, link
        self.slides: list[tuple[int, int, int, int]] = []  # point, link, carrier, pair
        self.vel: list[tuple[PlanEdge, int]] = []
        self.acc: list[tuple[PlanEdge, int]] = []

    def step(self, step: Step) -> None:
        """Draw a step by its kind's construction (:mod:`linkwork.motion.plan_steps`), where it has one."""
        plan = groups.KINDS[step.kind].plan
        if plan is not None:
            plan(self, step)

    def pivot(self, link: int, p: int) -> int:
        """A point of the placed ``link`` that the coincident point of ``p`` on it turns about in the plans: one
        at rest if the link has one (its pivot), else its first other point; -1 for the frame."""
        if link == 0:
            return -1
        own = [int(q) for q in np.flatnonzero(self.mech.point_link == link) if q != p]
        return min(own, key=lambda q: self.label[q] != "p", default=-1)

    def turn(self, group: str, arm: Arm, p: int) -> None:
        """Point ``p`` turning with the arm's link about the arm's outer joint: v = w perp(r);
        a = -w^2 r + e perp(r), r = X - P."""
        self._turn_with(group, p, arm.src, arm.link, self.label[p])

    def _turn_with(self, group: str, p: int, src: int, link: int, end: str) -> None:
        """The plan point ``end`` of the point of ``link`` at ``p``, turning with it about its point ``src``."""
        start, about = self.label[src], self.names[src]
        i = len(self.turns)
        self.turns.append((p, src, link))
        self.vel.append((PlanEdge(start, end, "rotation", group, about), i))
        mid = f"n_{end}{start if start != 'p' else about.lower()}"  # named by the pivot's letter, not the pole's
        self.acc.append((PlanEdge(start, mid, "normal", group, about), i))
        self.acc.append((PlanEdge(mid, end, "tangential", group, about), i))

    def sliding(self, group: str, p: int, arm: Arm, pivot: int, prime: str = "'") -> None:
        """Point ``p`` on a link sliding along a guide of the carrier: the carrier's coincident point ``x'``, then
        (Coriolis and) sliding.  ``x'`` turns with the carrier about its point ``pivot`` (rotation; normal and
        tangential, as the construction draws it); on the frame (``pivot`` -1) it is the pole."""
        c, lab = arm.carrier, self.label[p]
        i = len(self.slides)
        self.slides.append((p, arm.link, c, arm.pair))
        carrier = "p" if c == 0 or pivot < 0 else f"{lab}{prime}"
        about = self.mech.link_names[c]
        if carrier != "p":
            self._turn_with(group, p, pivot, c, carrier)
        mid = f"k{prime}_{lab}"
        self.vel.append((PlanEdge(carrier, lab, "sliding", group, about), i))
        self.acc.append((PlanEdge(carrier, mid, "coriolis", group, about), i))
        self.acc.append((PlanEdge(mid, lab, "sliding", group, about), i))
