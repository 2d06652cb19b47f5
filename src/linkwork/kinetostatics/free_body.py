"""Free bodies of the Assur groups: the forces of every pair on the group's links, and their balance.

The solution by Lagrange multipliers gives the reactions of all pairs at
once; this module reads them back pair by pair as forces acting at points
(Newton's third law: the first link on the second, and the opposite back),
and adds them up, with the applied and inertia loads, for each group of the
structural decomposition, as the graphical method of kinetostatics does.  The
sum (the ``residual``) vanishes when the reactions are right; it is computed
from the pair forces and the points, not from the constraint Jacobian.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from linkwork.kinetostatics.geometry import guide_direction
from linkwork.structure.model import PairType

if TYPE_CHECKING:  # the forces module makes the free bodies of its results
    from linkwork.kinetostatics.reaction_forces import Forces


@dataclass(frozen=True)
class Contact:
    """The force of link ``other`` on link ``on`` in joint ``joint``.

    ``force`` (V, A, 2) acts at ``point`` (V, A, 2); ``moment`` (V, A) is the couple of a prismatic
    pair or of a revolute drive; for a drive, ``joint`` is the driven joint and ``drive`` is True.
    """

    joint: str
    on: int
    other: int
    force: np.ndarray
    point: np.ndarray
    moment: np.ndarray
    drive: bool = False
    pair: int = -1  # the elementary pair (drives: the driven pair)


@dataclass(frozen=True)
class FreeBody:
    """One Assur group (or the driving link) cut free.

    Attributes
    ----------
    label : str
        ``II(2,3) RRR``-style label of the group.
    links : tuple of int
    external : list of Contact
        The forces of the links outside the group (frame and drive included) on its links.
    internal : list of Contact
        The group's internal pairs: the force of the link the file names first on the other.
    loads : ndarray (V, A, 3)
        Applied and inertia loads of the group's links: force and moment about the global origin.
    residual : ndarray (V, A, 3)
        Sum of the external contacts and the loads: zero for a correct solution.
    """

    label: str
    links: tuple[int, ...]
    external: list[Contact]
    internal: list[Contact]
    loads: np.ndarray
    residual: np.ndarray


def _cross(r: np.ndarray, f: np.ndarray) -> np.ndarray:
    return r[..., 0] * f[..., 1] - r[..., 1] * f[..., 0]


def contacts(forces: Forces) -> list[Contact]:
    """Every pair and drive, each side: the force on ``on`` from ``other``."""
    m = forces.mechanism
    kin = forces.kinematics
    shape = kin.valid_all.shape
    zero = np.zeros(shape)
    lam = forces.multipliers
    out: list[Contact] = []
    for k in range(m.n_pairs):
        a, b = (int(x) for x in m.pair_links[k])
        point = kin.motion_of(m.point_names[int(m.pair_points[k, 1])])[0]
        f = forces.pair_force(k)
        couple = zero if m.pair_type[k] == PairType.REVOLUTE else lam[..., 2 * k]
        out.append(Contact(m.pair_joint[k], b, a, f, point, couple, pair=k))
        out.append(Contact(m.pair_joint[k], a, b, -f, point, -couple, pair=k))
    for d, k in enumerate(m.drive_pair):
        a, b = (int(x) for x in m.pair_links[k])
        value = lam[..., 2 * m.n_pairs + d]
        point = kin.motion_of(m.point_names[int(m.pair_points[k, 1])])[0]
        if m.pair_type[k] == PairType.REVOLUTE:
            f, couple = np.zeros(shape + (2,)), value
        else:
            f, couple = value[..., None] * guide_direction(kin, k), zero
        out.append(Contact(m.pair_joint[k], b, a, f, point, couple, drive=True, pair=int(k)))
        out.append(Contact(m.pair_joint[k], a, b, -f, point, -couple, drive=True, pair=int(k)))
    return out


def free_bodies(forces: Forces) -> list[FreeBody]:
    """The free body of every group of the structural decomposition, in solving order."""
    m = forces.mechanism
    q = forces.kinematics.pose
    total = forces.loads.total  # about each link's origin
    about_origin = total.copy()
    about_origin[..., 2] += _cross(q[..., :2], total[..., :2])
    every = contacts(forces)
    second = np.where(m.pair_sign > 0, m.pair_links[:, 1], m.pair_links[:, 0])  # the later named of each pair
    out = []
    for group in m.structure.groups:
        links = set(group.links)
        external = [c for c in every if c.on in links and c.other not in links]
        internal = [c for c in every if c.on in links and c.other in links and c.on == second[c.pair]]
        loads = np.sum(about_origin[..., sorted(links), :], axis=-2)
        residual = loads.copy()
        for c in external:
            residual[..., :2] += c.force
            residual[..., 2] += _cross(c.point, c.force) + c.moment
        out.append(FreeBody(group.label, tuple(group.links), external, internal, loads, residual))
    return out
