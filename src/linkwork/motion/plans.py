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

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from linkwork.motion.analysis import guide
from linkwork.motion.kinematics import Kinematics
from linkwork.motion.program import Arm, Step
from linkwork.structure.constraints import perp
from linkwork.structure.model import PairType, point_labels


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


def _round_scale(longest: float) -> float:
    """A drawing scale (units per mm) from the 1-2-5 series, making ``longest`` at most 100 mm."""
    if not longest > 0:
        return 1.0
    raw = longest / 100.0
    exp = np.floor(np.log10(raw))
    for m in (1, 2, 2.5, 5, 10):
        if m * 10**exp >= raw:
            return float(m * 10**exp)
    return float(10 ** (exp + 1))


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
        longest = float(_longest(values[: len(self.points)]))
        return Plan(self.kind, float(self.angles[index]), points, vecs, _round_scale(longest))


def _longest(vectors: np.ndarray) -> np.ndarray:
    """Length of the longest finite vector ``(..., K, 2) -> (...)``; 0 where none is finite."""
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

    Returns
    -------
    velocity, acceleration : PlanSeries
        Values ``(V, A, L, 2)`` in m/s and m/s^2.
    """
    c = _Construction(kin)
    c.build()
    return c.series("velocity", c.vel_pts, c.vvec), c.series("acceleration", c.acc_pts, c.avec)


class _Construction:
    """The graphical construction over ``(V, A)``: every vector an array ``(V, A, 2)``."""

    def __init__(self, kin: Kinematics) -> None:
        mech = self.mech = kin.mechanism
        self.kin = kin
        self.q, self.v, self.a = kin.pose, kin.vel, kin.acc  # (V, A, N, 3)
        pts = kin.points()
        self.pts = pts if kin.variants else pts[None]  # (V, A, P, 2)
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
        self.vel_pts: dict[str, np.ndarray] = {}
        self.acc_pts: dict[str, np.ndarray] = {}
        self.vvec: list[tuple[PlanEdge, np.ndarray]] = []
        self.avec: list[tuple[PlanEdge, np.ndarray]] = []

    def state_at(self, link: int | np.ndarray, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Velocity and acceleration of the material point of ``link`` at ``x`` (V, A, 2); of each of the links
        ``(P,)`` at its point ``x`` (V, A, P, 2)."""
        q, v, a = self.q[..., link, :], self.v[..., link, :], self.a[..., link, :]
        r = x - q[..., :2]
        w, e = v[..., 2:3], a[..., 2:3]
        return v[..., :2] + w * perp(r), a[..., :2] + e * perp(r) - w * w * r

    def build(self) -> None:
        vx, ax = self.state_at(np.asarray(self.mech.point_link, dtype=int), self.pts)  # every point at once
        for p, label in enumerate(self.label):
            self.vel_pts.setdefault(label, vx[..., p, :])
            self.acc_pts.setdefault(label, ax[..., p, :])
        for step in self.mech.program:
            self.step(step)

    def step(self, step: Step) -> None:
        g, arms = step.label, step.arms
        if step.kind == "crank":
            arm = arms[0]
            for p in np.flatnonzero(self.mech.point_link == arm.link):
                if p != arm.own:
                    self.turn(g, arm, int(p))
        elif step.kind in ("RRR", "RRP", "PRP"):
            xp = step.x_local[0]
            for arm in arms:
                if arm.kind == "R":
                    self.turn(g, arm, xp)
                else:
                    primes = "'" * (1 + sum(1 for other in arms[: arms.index(arm)] if other.kind == "P"))
                    self.sliding(g, xp, arm, primes)
        elif step.kind == "RPR":
            # the slider turns about its pivot; the guide's coincident point turns about the guide's pivot,
            # and the slider slides along the guide relative to it (with the Coriolis component)
            arm_g, arm_s = arms
            sp = arm_s.slider_point
            self.turn(g, arm_s, sp)
            self.sliding(g, sp, Arm("P", arm_s.link, step.inner, carrier=arm_g.link))

    def turn(self, group: str, arm: Arm, p: int) -> None:
        """Point ``p`` turning with the arm's link about the arm's outer joint: v = w perp(r);
        a = -w^2 r + e perp(r), r = X - P."""
        start, end, about = self.label[arm.src], self.label[p], self.names[arm.src]
        r = self.pts[..., p, :] - self.pts[..., arm.src, :]
        w, e = self.v[..., arm.link, 2:3], self.a[..., arm.link, 2:3]
        pr = perp(r)
        self.vvec.append((PlanEdge(start, end, "rotation", group, about), w * pr))
        mid = f"n_{end}{start}"
        self.avec.append((PlanEdge(start, mid, "normal", group, about), -w * w * r))
        self.avec.append((PlanEdge(mid, end, "tangential", group, about), e * pr))

    def sliding(self, group: str, p: int, arm: Arm, prime: str = "'") -> None:
        """Point ``p`` on a link sliding along a guide of the carrier: transport + (Coriolis) + sliding."""
        c, lab, x = arm.carrier, self.label[p], self.pts[..., p, :]
        u = guide(self.kin, arm.pair)[1]
        v_tr, a_tr = self.state_at(c, x)
        v_x, a_x = self.state_at(arm.link, x)
        sdot = np.sum((v_x - v_tr) * u, -1)[..., None]
        cor = 2 * self.v[..., c, 2:3] * sdot * perp(u)
        sddot = np.sum((a_x - a_tr - cor) * u, -1)[..., None]
        carrier = "p" if c == 0 else f"{lab}{prime}"
        about = self.mech.link_names[c]
        mid = f"k{prime}_{lab}"
        self.vvec.append((PlanEdge("p", carrier, "transport", group, about), v_tr))
        self.vvec.append((PlanEdge(carrier, lab, "sliding", group, about), sdot * u))
        self.avec.append((PlanEdge("p", carrier, "transport", group, about), a_tr))
        self.avec.append((PlanEdge(carrier, mid, "coriolis", group, about), cor))
        self.avec.append((PlanEdge(mid, lab, "sliding", group, about), sddot * u))

    def series(self, kind: str, pts: dict[str, np.ndarray], vecs: list[tuple[PlanEdge, np.ndarray]]) -> PlanSeries:
        """The plan points (absolute, then each intermediate point reached along the construction)."""
        known = dict(pts)
        labels = list(pts)
        for edge, vec in vecs:
            for lab in (edge.start, edge.end):
                if lab not in labels:
                    labels.append(lab)
            if edge.start in known and edge.end not in known:
                known[edge.end] = known[edge.start] + vec
        shape = self.pts.shape[:2] + (2,)
        nan = np.full(shape, np.nan)
        values = np.stack([known.get(lab, nan) for lab in labels], axis=2)
        vectors = np.stack([vec for _, vec in vecs], axis=2) if vecs else np.zeros(shape[:2] + (0, 2))
        return PlanSeries(
            kind, self.kin.angles, tuple(pts), tuple(labels), tuple(e for e, _ in vecs), values, vectors
        )
