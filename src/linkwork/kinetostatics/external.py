"""External loads of a mechanism file: forces at points, moments on links, process loads.

:func:`linkwork.stage_records.compile_loads` turns the ``loads:`` of a spec into :class:`ExternalLoad`
records (SI, indices); :func:`evaluate` gives, over a kinematics result, every
elementary force (its link, point of application, the point's velocity) and
moment, from which the reactions, the power balance and the momentum check
are all built.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from linkwork.kinetostatics.elements import ELEMENTS, evaluate_element
from linkwork.kinetostatics.geometry import guide_direction
from linkwork.motion.kinematic_analysis import Kinematics
from linkwork.structure.constraints import perp
from linkwork.structure.model import Mechanism, PairType
from linkwork.structure.records import ExternalLoad


class PointForce(NamedTuple):
    """A force ``force`` (N) on ``link`` at a point whose ``position`` (m) and ``velocity`` (m/s) are given;
    each ``(V, A, 2)``."""

    link: int
    position: np.ndarray
    velocity: np.ndarray
    force: np.ndarray


class LinkMoment(NamedTuple):
    """A moment ``moment`` (N m) ``(V, A)`` on ``link``."""

    link: int
    moment: np.ndarray


@dataclass(frozen=True)
class Applied:
    """The elementary external loads over (V, A).

    Attributes
    ----------
    forces : list of PointForce
    moments : list of LinkMoment
    magnitude : dict
        Each load's magnitude (V, A): N for forces and process loads, N m for moments; friction N m in a
        revolute joint, N along a guide (:func:`magnitude_units`).
    penetration : dict
        Relative penetration (V, A) of each process load.
    """

    forces: list[PointForce]
    moments: list[LinkMoment]
    magnitude: dict[str, np.ndarray]
    penetration: dict[str, np.ndarray]


def magnitude_units(mech: Mechanism) -> dict[str, str]:
    """The unit of each external load's magnitude (:attr:`Applied.magnitude`), by its name: ``N m`` for
    a moment and for friction in a revolute joint, ``N`` for a force, a process load and friction along
    a guide."""
    out: dict[str, str] = {}
    for load in mech.loads:
        turning = load.kind in ("moment", "torsion_spring") or (
            load.kind == "friction" and mech.pair_type[load.pair] == PairType.REVOLUTE
        )
        out[load.name] = "N m" if turning else "N"
    return out


def _interp(x: np.ndarray, table: tuple[np.ndarray, np.ndarray]) -> np.ndarray:
    """Linear in the table, zero outside it; NaN stays NaN."""
    xp, fp = table
    y = np.interp(x, xp, fp, left=0.0, right=0.0)
    return np.where(np.isnan(x), np.nan, y)


def _along(x: np.ndarray, u: np.ndarray) -> np.ndarray:
    """Component of vectors (..., 2) along ``u`` (written out: ``@`` would wake BLAS threads that spin)."""
    return x[..., 0] * u[0] + x[..., 1] * u[1]


def evaluate(kin: Kinematics, kinds: tuple[str, ...] | None = None) -> Applied:
    """The external loads of ``kin.mechanism`` (those of the ``kinds`` given, default all) over a kinematics
    result."""
    out = Applied([], [], {}, {})
    for load in kin.mechanism.loads:
        if kinds is None or load.kind in kinds:
            _add(kin, load, out)
    return out


def _add(kin: Kinematics, load: ExternalLoad, out: Applied) -> None:
    """The forces and moments of one load over ``kin``, added to ``out``."""
    if load.kind == "friction":
        _friction(kin, load, out)
    elif load.kind in ("force", "moment"):
        _given_load(kin, load, out)
    elif load.kind in ELEMENTS:
        _element(kin, load, out)
    else:
        _process_load(kin, load, out)


def power_of_loads(
    kin: Kinematics,
    kinds: tuple[str, ...] | None = None,
    *,
    at: slice = slice(None),
    moving: slice = slice(None),
) -> np.ndarray:
    """Power (W) of the external loads of ``kin.mechanism`` (those of the ``kinds`` given, default all), ``(V, A)``:
    :func:`power` of :func:`evaluate`, each load evaluated and its power added before the next is evaluated, so
    the memory taken is the sum ``(V, A)`` and one load's arrays (about 13 floats a sample for a spring: its two
    points' positions and velocities and its two forces), whatever the number of loads.  ``at`` and ``moving``:
    the loads of the samples ``at`` with the velocities of the samples ``moving`` (:func:`power`)."""
    total = np.zeros(kin.valid_all[:, moving].shape)
    for load in kin.mechanism.loads:
        if kinds is None or load.kind in kinds:
            one = Applied([], [], {}, {})
            _add(kin, load, one)
            total += power(kin, one, at=at, moving=moving)
    return total


def _element(kin: Kinematics, load: ExternalLoad, out: Applied) -> None:
    """A force element's forces or moments (:mod:`linkwork.kinetostatics.elements`)."""
    action = evaluate_element(kin, load)
    out.forces.extend(PointForce(*f) for f in action.forces)
    out.moments.extend(LinkMoment(*m) for m in action.moments)
    out.magnitude[load.name] = action.size


def _state(kin: Kinematics, p: int) -> tuple[np.ndarray, np.ndarray]:
    """Position and velocity ``(V, A, 2)`` of point ``p``."""
    pos, vel, _ = kin.motion_of(kin.mechanism.point_names[p])
    return pos, vel


def _given_load(kin: Kinematics, load: ExternalLoad, out: Applied) -> None:
    """A force at a point or a moment on a link, constant or from its table over the drive angle."""
    shape = kin.valid_all.shape
    if load.table is None:
        size = np.full(shape, load.value)
    else:
        drive = kin.angles_all
        x0 = load.table[0][0]
        size = _interp(x0 + np.mod(drive - x0, 2 * np.pi), load.table)
    out.magnitude[load.name] = size
    if load.kind == "moment":
        out.moments.append(LinkMoment(load.link, size))
        return
    pos, vel = _state(kin, load.points[0])
    f = size[..., None] * np.asarray(load.vector)
    out.forces.append(PointForce(load.link, pos, vel, f))


def _process_load(kin: Kinematics, load: ExternalLoad, out: Applied) -> None:
    """A process load: the table's force at the tools' relative penetration into the workpiece while they
    close on it, on the first tool and back on the second (or on the frame, where the workpiece rests)."""
    assert load.table is not None  # a process load has its table
    u = np.asarray(load.vector)
    lo, hi = load.workpiece
    tools = [_state(kin, p) for p in load.points]
    (p1, v1) = tools[0]
    depth = np.maximum(hi - _along(p1, u), 0.0)
    closing = -_along(v1, u)
    if len(tools) == 2:
        p2, v2 = tools[1]
        depth = depth + np.maximum(_along(p2, u) - lo, 0.0)
        closing = closing + _along(v2, u)
    eps = depth / (hi - lo)
    # the table's value at zero penetration (a constant cutting force) acts from the touch on, not before
    size = np.where((closing > 0) & (eps > 0), _interp(eps, load.table), 0.0)
    size = np.where(np.isnan(closing) | np.isnan(eps), np.nan, size)
    out.magnitude[load.name] = size
    out.penetration[load.name] = eps
    f = size[..., None] * u
    out.forces.append(PointForce(load.link, p1, v1, f))
    if len(tools) == 2:
        link2 = int(kin.mechanism.point_link[load.points[1]])
        out.forces.append(PointForce(link2, tools[1][0], tools[1][1], -f))
    else:  # the workpiece rests on the frame
        out.forces.append(PointForce(0, p1, np.zeros_like(v1), -f))


def _friction(kin: Kinematics, load: ExternalLoad, out: Applied) -> None:
    """Coulomb friction of constant size in one pair, against the relative motion (none at rest)."""
    size = np.full(kin.valid_all.shape, load.value)
    pair_friction(kin, load.pair, size, out)
    out.magnitude[load.name] = size


def relative_motion(kin: Kinematics, k: int) -> np.ndarray:
    """The relative motion of pair ``k``, ``(V, A)``: link ``b``'s angular speed less link ``a``'s (rad/s) in a
    revolute pair, the slider's speed along the guide relative to the guide's material point under it (m/s)
    in a prismatic one (``a, b = pair_links[k]``)."""
    mech = kin.mechanism
    a, b = (int(x) for x in mech.pair_links[k])
    if mech.pair_type[k] == PairType.REVOLUTE:
        return kin.vel[..., b, 2] - kin.vel[..., a, 2]
    _, va, vb, u = _sliding(kin, k)
    return np.sum((vb - va) * u, -1)


def _sliding(kin: Kinematics, k: int) -> tuple[np.ndarray, ...]:
    """Prismatic pair ``k``: the slider's point P, the velocities of the guide's material point at P and of
    the slider's, and the guide's direction, each ``(V, A, 2)``."""
    mech = kin.mechanism
    a = int(mech.pair_links[k, 0])
    pos, vb, _ = kin.motion_of(mech.point_names[int(mech.pair_points[k, 1])])
    q, v = kin.pose[..., a, :], kin.vel[..., a, :]
    va = v[..., :2] + kin.vel[..., a, 2, None] * perp(pos - q[..., :2])  # a's material point at P
    return pos, va, vb, guide_direction(kin, k)


def pair_friction(kin: Kinematics, k: int, size: np.ndarray, out: Applied) -> None:
    """Friction of size ``size`` ``(V, A)`` (N m in a revolute pair, N in a prismatic one) in pair ``k``, against
    its relative motion (:func:`relative_motion`; none at relative rest), added to ``out``: a moment on
    each link of a revolute pair, a force along the guide at the slider's point on each link of a prismatic
    one.  Their power is ``-size |relative motion|``."""
    mech = kin.mechanism
    a, b = (int(x) for x in mech.pair_links[k])
    if mech.pair_type[k] == PairType.REVOLUTE:
        turn = np.sign(kin.vel[..., b, 2] - kin.vel[..., a, 2])
        out.moments.append(LinkMoment(b, -size * turn))
        out.moments.append(LinkMoment(a, size * turn))
        return
    pos, va, vb, u = _sliding(kin, k)
    slide = np.sign(np.sum((vb - va) * u, -1))
    f = (-size * slide)[..., None] * u
    out.forces.append(PointForce(b, pos, vb, f))
    out.forces.append(PointForce(a, pos, va, -f))


def generalised(kin: Kinematics, applied: Applied) -> np.ndarray:
    """Generalised loads (V, A, N, 3): force and moment about each link's origin."""
    q = kin.pose
    out = np.zeros(q.shape)
    for link, pos, _, f in applied.forces:
        r = pos - q[..., link, :2]
        out[..., link, :2] += f
        out[..., link, 2] += r[..., 0] * f[..., 1] - r[..., 1] * f[..., 0]
    for link, m in applied.moments:
        out[..., link, 2] += m
    return out


def power(
    kin: Kinematics, applied: Applied | None, *, at: slice = slice(None), moving: slice = slice(None)
) -> np.ndarray:
    """Power (W) of the external loads ``applied`` (none: zero), (V, A): ``sum F . v_P + M omega``.  With ``at`` and
    ``moving`` the loads of the samples ``at`` with the velocities of the samples ``moving`` (the same poses in
    another motion, as many samples): the virtual power of the loads of one state in the motion of another, as the
    reduced moment takes them (:func:`linkwork.machine.reduction.load_moment`)."""
    w = kin.vel[:, moving, :, 2]
    total = np.zeros(kin.valid_all[:, moving].shape)
    for _, _, vel, f in applied.forces if applied is not None else ():
        total = total + np.sum(f[:, at] * vel[:, moving], -1)
    for link, m in applied.moments if applied is not None else ():
        total = total + m[:, at] * w[..., link]
    return total


def resultant(applied: Applied | None, shape: tuple[int, ...]) -> np.ndarray:
    """Total external force and moment about the global origin of the loads ``applied`` (none: zero), (V, A, 3)."""
    out = np.zeros(shape + (3,))
    for _, pos, _, f in applied.forces if applied is not None else ():
        out[..., :2] += f
        out[..., 2] += pos[..., 0] * f[..., 1] - pos[..., 1] * f[..., 0]
    for _, m in applied.moments if applied is not None else ():
        out[..., 2] += m
    return out
