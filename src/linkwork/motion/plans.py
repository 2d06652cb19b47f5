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
"""

from __future__ import annotations

from dataclasses import dataclass, field
from types import SimpleNamespace
from typing import Any

import numpy as np


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


def plans(kin: Any, index: int, variant: int = 0) -> tuple[Plan, Plan]:
    """The velocity and acceleration plans of sample ``index``."""
    mech = kin.mechanism
    q, v, a = (x[:, :, variant, index] for x in (kin.q, kin.v, kin.a))  # (N, 3)
    loc = kin.local[:, :, variant, 0]
    axis = kin.axis[:, :, variant, 0]
    names = [n.split(".", 1)[1] for n in mech.point_names]

    def state_at(link: int, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        r = x - q[link, :2]
        w, e = v[link, 2], a[link, 2]
        return v[link, :2] + w * np.array([-r[1], r[0]]), a[link, :2] + e * np.array([-r[1], r[0]]) - w * w * r

    def glob(p: int) -> np.ndarray:
        i = mech.point_link[p]
        c, s = np.cos(q[i, 2]), np.sin(q[i, 2])
        return q[i, :2] + np.array([c * loc[p, 0] - s * loc[p, 1], s * loc[p, 0] + c * loc[p, 1]])

    grounded = {
        int(mech.pair_points[k, 1])
        for k in range(mech.n_pairs)
        if mech.pair_type[k] == 0 and mech.pair_links[k, 0] == 0
    }
    from linkwork.io.motion_tables import point_labels

    labels = {p: label.lower() for label, p in point_labels(mech, with_all=True)}

    def label_of(p: int) -> str:
        """Plan label: the point's name in lower case; p for the frame and points pinned to it."""
        if mech.point_link[p] == 0 or p in grounded:
            return "p"
        return labels[p]

    vel_pts: dict[str, tuple[float, float]] = {}
    acc_pts: dict[str, tuple[float, float]] = {}
    for p in range(len(names)):
        vx, ax = state_at(int(mech.point_link[p]), glob(p))
        vel_pts.setdefault(label_of(p), tuple(map(float, vx)))
        acc_pts.setdefault(label_of(p), tuple(map(float, ax)))
    vvec: list[PlanVector] = []
    avec: list[PlanVector] = []

    def turn(group: str, arm: Any, x: np.ndarray, lab: str) -> None:
        """X of the arm's link turning about the arm's outer joint."""
        _rotation(
            vvec, avec, group, label_of(arm.src), lab, x - glob(arm.src), v[arm.link, 2], a[arm.link, 2], names[arm.src]
        )

    for step in mech.program:
        g = step.label
        arms = step.arms
        if step.kind == "crank":
            arm = arms[0]
            for p in np.flatnonzero(mech.point_link == arm.link):
                if p != arm.own:
                    turn(g, arm, glob(p), label_of(p))
        elif step.kind in ("RRR", "RRP", "PRP"):
            xp = step.x_local[0]
            x = glob(xp)
            lab = label_of(xp)
            for arm in arms:
                if arm.kind == "R":
                    turn(g, arm, x, lab)
                else:
                    primes = "'" * (1 + sum(1 for other in arms[: arms.index(arm)] if other.kind == "P"))
                    _sliding(vvec, avec, g, lab, x, arm, mech, q, v, a, state_at, axis, primes)
        elif step.kind == "RPR":
            # the slider turns about its pivot; the guide's coincident point turns about the guide's pivot,
            # and the slider slides along the guide relative to it (with the Coriolis component)
            arm_g, arm_s = arms
            sp = arm_s.slider_point
            x, lab = glob(sp), label_of(sp)
            turn(g, arm_s, x, lab)
            on_guide = SimpleNamespace(carrier=arm_g.link, pair=step.inner, link=arm_s.link)
            _sliding(vvec, avec, g, lab, x, on_guide, mech, q, v, a, state_at, axis)
    longest_v = max((np.hypot(*pv) for pv in vel_pts.values()), default=0.0)
    longest_a = max((np.hypot(*pa) for pa in acc_pts.values()), default=0.0)
    angle = float(kin.angles[index])
    return (
        Plan("velocity", angle, vel_pts, vvec, _round_scale(longest_v)),
        Plan("acceleration", angle, acc_pts, avec, _round_scale(longest_a)),
    )


def _rotation(
    vvec: list, avec: list, group: str, start: str, end: str, r: np.ndarray, w: float, e: float, about: str
) -> None:
    """X turning with a link about P (r = X - P): v = w perp(r); a = -w^2 r + e perp(r)."""
    pr = np.array([-r[1], r[0]])
    vvec.append(PlanVector(start, end, tuple(map(float, w * pr)), "rotation", group, about))
    mid = f"n_{end}{start}"
    avec.append(PlanVector(start, mid, tuple(map(float, -w * w * r)), "normal", group, about))
    avec.append(PlanVector(mid, end, tuple(map(float, e * pr)), "tangential", group, about))


def _sliding(
    vvec: list,
    avec: list,
    group: str,
    lab: str,
    x: np.ndarray,
    arm: Any,
    mech: Any,
    q: np.ndarray,
    v: np.ndarray,
    a: np.ndarray,
    state_at: Any,
    axis: np.ndarray,
    prime: str = "'",
) -> None:
    """X on a link sliding along a guide of the carrier: transport + (Coriolis) + sliding."""
    c = arm.carrier
    th = q[c, 2]
    k = arm.pair
    ax_loc = axis[k]
    cs, sn = np.cos(th), np.sin(th)
    u = np.array([cs * ax_loc[0] - sn * ax_loc[1], sn * ax_loc[0] + cs * ax_loc[1]])
    v_tr, a_tr = state_at(c, x)
    v_x, a_x = state_at(arm.link, x)
    sdot = float((v_x - v_tr) @ u)
    cor = 2 * v[c, 2] * sdot * np.array([-u[1], u[0]])
    sddot = float((a_x - a_tr - cor) @ u)
    carrier = "p" if c == 0 else f"{lab}{prime}"
    vvec.append(PlanVector("p", carrier, tuple(map(float, v_tr)), "transport", group, mech.link_names[c]))
    vvec.append(PlanVector(carrier, lab, tuple(map(float, sdot * u)), "sliding", group, mech.link_names[c]))
    avec.append(PlanVector("p", carrier, tuple(map(float, a_tr)), "transport", group, mech.link_names[c]))
    mid = f"k{prime}_{lab}"
    avec.append(PlanVector(carrier, mid, tuple(map(float, cor)), "coriolis", group, mech.link_names[c]))
    avec.append(PlanVector(mid, lab, tuple(map(float, sddot * u)), "sliding", group, mech.link_names[c]))
