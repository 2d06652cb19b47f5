"""Zhukovsky's lever: the velocity plan turned by 90 degrees, loaded with every force, as data.

Every external and inertia force of the mechanism (weights, inertia forces, the file's loads) is applied,
parallel to itself, at the image of its point on the velocity plan turned by 90 degrees counter-clockwise
about the pole; a couple (an inertia moment ``M_Phi2 = -J_S2 eps2``, an external moment) is first replaced
by two equal and opposite forces ``M / l`` at two points of its link, normal to the line between them (its two
points farthest apart; a slider block's one point and a point :data:`ARM` from it along the block's axis).
The plan is then a rigid lever pivoted at the pole: the moment of a force ``F`` at the turned image
``perp(v)`` of its point is ``perp(v) x F = -F . v``, minus its power.  The balancing force ``F_b`` at the
image of the crank pin, normal to the crank, holds the lever in equilibrium, and the balancing moment is
``M_b = F_b l_OA``: the principle of virtual power in the graphical method's form, a check of the
kinetostatic driving torque by a method that uses neither the reactions nor the accelerations of the
joints.

>>> import linkwork as lw
>>> from linkwork.kinetostatics.zhukovsky import lever
>>> f = lw.forces(lw.compile(lw.load("four-bar")), steps=12)
>>> bool(abs(lever(f).balancing - f.driving_torque).max() < 1e-9 * abs(f.driving_torque).max())
True
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from linkwork.errors import LinkworkError
from linkwork.kinetostatics.force_polygons import PlanForce, _cross, _Loads, _perp, _unit, point_names
from linkwork.kinetostatics.reaction_forces import Forces
from linkwork.motion.kinematic_analysis import Kinematics
from linkwork.structure.model import Mechanism, one_crank


@dataclass(frozen=True)
class LeverForce:
    """One force on the lever.

    Attributes
    ----------
    force : PlanForce
        The force, N; a couple's half: ``part`` ``"'"`` or ``"''"``, ``kind`` ``"inertia"`` for an inertia
        moment's, ``"load"`` for an external moment's.
    image : ndarray (V, A, 2)
        Where it acts on the lever: the velocity of its point turned by 90 degrees counter-clockwise, m/s.
    label : str
        The image point's letter: ``s2`` for a centre of mass, the point's name in lower case for the others.
    moment : ndarray (V, A)
        Its moment about the pole, ``image x force``, W.
    """

    force: PlanForce
    image: np.ndarray
    label: str
    moment: np.ndarray


@dataclass(frozen=True)
class Lever:
    """Zhukovsky's lever over the samples of a kinetostatic result.

    Attributes
    ----------
    forces : tuple of LeverForce
    pin : str
        The letter of the crank pin's image, where the balancing force acts.
    pin_image : ndarray (V, A, 2)
        Its place on the lever, m/s.
    balancing_force : ndarray (V, A, 2)
        The balancing force at the crank pin, normal to the crank, N.
    balancing : ndarray (V, A)
        The balancing moment on the crank, N m, counter-clockwise positive: the driving torque.
    crank : float
        The crank's length from its pivot to the pin, m (``(V,)``: of each variant).
    """

    forces: tuple[LeverForce, ...]
    pin: str
    pin_image: np.ndarray
    balancing_force: np.ndarray
    balancing: np.ndarray
    crank: np.ndarray


def _velocity(kin: Kinematics, link: int, at: np.ndarray) -> np.ndarray:
    """Velocity ``(V, A, 2)`` of the material point of ``link`` at ``at`` ``(V, A, 2)``."""
    q, v = kin.pose[..., link, :], kin.vel[..., link, :]
    return v[..., :2] + v[..., 2:3] * _perp(at - q[..., :2])


def _pair_of_forces(couple: PlanForce, a: np.ndarray, b: np.ndarray) -> tuple[PlanForce, PlanForce]:
    """A couple as two forces ``M / l`` at ``a`` and ``b`` of its link, normal to ``ab``, equal and opposite."""
    e, length = _unit(b - a)
    with np.errstate(invalid="ignore", divide="ignore"):
        f = (couple.moment / length)[..., None] * _perp(e)  # cross(b - a, f) = M
    zero = np.zeros(couple.moment.shape)
    kind = "inertia" if couple.symbol == "MPhi" else "load"
    return (
        PlanForce(couple.symbol, couple.index, "'", kind, couple.link, f, b, zero, couple.about),
        PlanForce(couple.symbol, couple.index, "''", kind, couple.link, -f, a, zero, couple.about),
    )


def _ends(m: Mechanism, link: int, points: np.ndarray) -> tuple[int, int]:
    """The two points of ``link`` farthest apart (a couple's forces go there)."""
    own = [int(p) for p in np.flatnonzero(m.point_link == link)]
    if len(own) < 2:
        return (own[0], own[0]) if own else (-1, -1)
    first = points[0, :, own]  # (K, A, 2) of the first variant
    best, pair = -1.0, (own[0], own[1])
    for i in range(len(own)):
        for j in range(i + 1, len(own)):
            d = float(np.nanmax(np.hypot(*(first[i] - first[j]).T), initial=0.0))
            if d > best:
                best, pair = d, (own[i], own[j])
    return pair


#: Where a link has one point, the second point of its couples' forces: this far along the link's x axis, m.
ARM = 0.1


def _couple_points(kin: Kinematics, link: int, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Two material points ``(V, A, 2)`` of ``link`` for a couple's two forces: its two points farthest apart, or,
    where it has one (a slider block), that point and the point :data:`ARM` from it along the link's x axis."""
    a, b = _ends(kin.mechanism, link, points)
    if a != b:
        return points[..., a, :], points[..., b, :]
    q = kin.pose[..., link, :]
    start = points[..., a, :] if a >= 0 else q[..., :2]
    return start, start + ARM * np.stack([np.cos(q[..., 2]), np.sin(q[..., 2])], -1)


def lever(f: Forces) -> Lever:
    """Zhukovsky's lever of ``f``'s mechanism at every sample (see the module's text).

    Raises
    ------
    LinkworkError
        Unless the mechanism has one revolute drive (a crank) with a pin.
    """
    kin, m = f.kinematics, f.mechanism
    if not one_crank(m):
        raise LinkworkError(f"{m.name}: Zhukovsky's lever needs one crank (a revolute drive)")
    k = int(m.drive_pair[0])
    crank = int(m.pair_links[k, 1]) if int(m.pair_links[k, 0]) == 0 else int(m.pair_links[k, 0])
    points = np.moveaxis(kin.point_positions(np.arange(len(m.point_names))), 0, -2)  # (V, A, P, 2)
    names = point_names(m)
    pivot = points[..., int(m.pair_points[k, 1]), :]
    pins = [int(m.pair_points[j, 1]) for j in range(m.n_pairs) if j != k and crank in m.pair_links[j]]
    if not pins:  # a crank alone (a pendulum): the balancing force at any other point of it
        pins = [p for p in range(len(m.point_names)) if int(m.point_link[p]) == crank and p != int(m.pair_points[k, 1])]
    if not pins:
        raise LinkworkError(f"{m.name}: the crank {m.link_names[crank]} has no point but its pivot")
    lengths = [float(np.nanmax(np.hypot(*(points[0, :, p] - pivot[0]).T), initial=0.0)) for p in pins]
    pin = pins[int(np.argmax(lengths))]
    loads = _Loads(f)
    out: list[LeverForce] = []
    for link in range(1, len(m.link_names)):
        applied = list(loads.forces[link])
        for couple in loads.couples[link]:
            applied += _pair_of_forces(couple, *_couple_points(kin, link, points))
        for force in applied:
            image = _perp(_velocity(kin, link, force.point))
            label = f"s{link}" if force.symbol in ("G", "Phi") else _letter(force, points, names, link, m)
            out.append(LeverForce(force, image, label, _cross(image, force.vector)))
    total = sum((lf.moment for lf in out), np.zeros(kin.valid_all.shape))
    omega = kin.vel[..., crank, 2]
    with np.errstate(invalid="ignore", divide="ignore"):
        balancing = total / omega  # sum perp(v) x F = -power; M_b omega = -power
    arm, length = _unit(points[..., pin, :] - pivot)
    with np.errstate(invalid="ignore", divide="ignore"):
        force = (balancing / length)[..., None] * _perp(arm)
    image = _perp(_velocity(kin, crank, points[..., pin, :]))
    return Lever(tuple(out), names[pin].lower(), image, force, balancing, np.nanmax(length, axis=-1))


def _letter(force: PlanForce, points: np.ndarray, names: list[str], link: int, m: Mechanism) -> str:
    """The letter of the point a force acts at: the nearest point of its link, in lower case."""
    own = np.flatnonzero(m.point_link == link)
    if not len(own):
        return "?"
    d = np.hypot(*np.moveaxis(points[0][:, own] - force.point[0][:, None], -1, 0))  # (A, K)
    nearest = int(own[int(np.nanargmin(np.nanmean(d, axis=0)))]) if np.isfinite(d).any() else int(own[0])
    return names[nearest].lower()
