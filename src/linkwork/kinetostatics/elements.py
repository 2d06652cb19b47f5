"""Force elements: linear springs and dampers between two points, torsion springs in revolute joints.

They are loads like the others of :mod:`linkwork.kinetostatics.external`: compiled from the file's
``loads:`` into :class:`~linkwork.structure.records.ExternalLoad` records and evaluated over a
kinematics result into forces at points and moments on links, so every analysis that reads the loads
(reactions, the reduced load moment, the flywheel, the runs in time, sweeps, the viewer, the report)
has them.  A spring's or damper's force acts along the line of its two points, tension positive (it
pulls them together): ``T = k (L - L0)`` and ``T = c dL/dt``; a torsion spring's moment on the joint's
second link is ``-k (theta_b - theta_a - theta_0)`` and its opposite on the first.

Potential energy (J) of the springs: :func:`potential`; the power of every load is what
:func:`linkwork.kinetostatics.external.power` gives.
"""

from __future__ import annotations

import math
from typing import NamedTuple, Protocol

import numpy as np

from linkwork.motion.kinematic_analysis import Kinematics

#: Kinds of the force elements among the loads.
ELEMENTS = ("spring", "damper", "torsion_spring")


class ForceElement(Protocol):
    """What a compiled force element holds (:class:`~linkwork.structure.records.ExternalLoad`)."""

    @property
    def kind(self) -> str: ...
    @property
    def points(self) -> tuple[int, ...]: ...
    @property
    def value(self) -> float: ...
    @property
    def pair(self) -> int: ...
    @property
    def free(self) -> float: ...


class Action(NamedTuple):
    """What a force element does over (V, A): ``forces`` ``(link, position, velocity, force)`` at points,
    ``moments`` ``(link, moment)`` on links, and its ``size`` (N, N m)."""

    forces: list[tuple[int, np.ndarray, np.ndarray, np.ndarray]]
    moments: list[tuple[int, np.ndarray]]
    size: np.ndarray


def _state(kin: Kinematics, p: int) -> tuple[np.ndarray, np.ndarray]:
    """Position and velocity ``(V, A, 2)`` of point ``p``."""
    pos, vel, _ = kin.motion_of(kin.mechanism.point_names[p])
    return pos, vel


def evaluate_element(kin: Kinematics, load: ForceElement) -> Action:
    """The forces (spring, damper) or moments (torsion spring) of one force element over ``kin`` and its size;
    NaN where a spring's two points coincide (its line has no direction)."""
    if load.kind == "torsion_spring":
        turn = relative_turn(kin, load)
        m = -load.value * (turn - load.free)
        a, b = (int(x) for x in kin.mechanism.pair_members[load.pair])
        return Action([], [(b, m), (a, -m)], m)
    (p1, v1), (p2, v2) = (_state(kin, p) for p in load.points)
    d = p2 - p1
    length = np.sqrt(np.sum(d * d, -1))
    with np.errstate(invalid="ignore", divide="ignore"):
        u = np.where((length > 0)[..., None], d / length[..., None], np.nan)
    if load.kind == "spring":
        tension = load.value * (length - load.free)
    else:
        tension = load.value * np.sum((v2 - v1) * u, -1)
    f = tension[..., None] * u
    links = [int(kin.mechanism.point_link[p]) for p in load.points]
    return Action([(links[0], p1, v1, f), (links[1], p2, v2, -f)], [], np.where(length > 0, tension, np.nan))


def relative_turn(kin: Kinematics, load: ForceElement) -> np.ndarray:
    """The turn (rad) of a torsion spring's joint, its second link's angle less its first's ``(V, A)``; in the
    drive's own joint the drive coordinate counts whole turns, elsewhere it is taken within half a turn of
    the free angle."""
    mech = kin.mechanism
    a, b = (int(x) for x in mech.pair_members[load.pair])
    q = kin.pose
    turn = q[..., b, 2] - q[..., a, 2]
    if load.pair in mech.drive_pair:
        return turn
    return load.free + np.mod(turn - load.free + math.pi, 2 * math.pi) - math.pi


def potential(kin: Kinematics) -> np.ndarray:
    """Potential energy (J) of the springs of ``kin.mechanism`` ``(V, A)``: ``k (L - L0)^2 / 2`` and
    ``k (theta - theta_0)^2 / 2``."""
    total = np.zeros(kin.valid_all.shape)
    for load in kin.mechanism.loads:
        if load.kind == "spring":
            (p1, _), (p2, _) = (_state(kin, p) for p in load.points)
            stretch = np.sqrt(np.sum((p2 - p1) ** 2, -1)) - load.free
        elif load.kind == "torsion_spring":
            stretch = relative_turn(kin, load) - load.free
        else:
            continue
        total = total + 0.5 * load.value * stretch**2
    return total
