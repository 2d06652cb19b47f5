"""The forces drawn on the viewer's scheme: the joints' reactions and the external loads, as arrows to one scale.

Every joint gets one arrow, at its point: the force the joint puts on its link of the highest number
(:meth:`linkwork.kinetostatics.reaction_forces.Forces.reaction` with ``on=`` that link), labelled ``R`` with the
numbers of the links, e.g. ``R12``, the force of link 1 on link 2 (``R03``: of the frame on link 3).  For a
prismatic pair it acts at the slider's point, normal to the guide.  The external forces of the file's
loads (a process load on each of its tools, given forces at their points, springs and dampers at their
moving ends) get an arrow each, labelled with the load's name.  One scale for the whole cycle, from the
1-2-5 series: the largest arrow of nearly every position (:data:`PERCENTILE`) about :data:`LENGTH` of the
drawing's size.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from linkwork.motion.plans import drawing_scale, percentile
from linkwork.structure.model import Mechanism, PairType, per_mechanism
from linkwork.web.cycle import Cycle

#: Percentile of the positions' largest arrows that sets the scale.
PERCENTILE = 95.0

#: The largest arrow of nearly every position, as a fraction of the drawing's size.
LENGTH = 0.3


@dataclass(frozen=True)
class SchemeForce:
    """One force arrow the viewer draws on the scheme (a reaction at a joint or a load): what it is and where it acts.

    Attributes
    ----------
    kind : str
        ``"reaction"`` or ``"load"``.
    name : str
        The joint, or the load.
    label : str
        ``R12``, or the load's name.
    on : str
        The link the force acts on.
    by : tuple of str
        The links that exert it (a reaction), or none (a load).
    point : int
        The point it acts at.
    """

    kind: str
    name: str
    label: str
    on: str
    by: tuple[str, ...]
    point: int

    def as_dict(self) -> dict[str, Any]:
        return {
            "kind": self.kind,
            "name": self.name,
            "label": self.label,
            "on": self.on,
            "by": list(self.by),
            "point": self.point,
        }


@dataclass(frozen=True)
class Arrows:
    """The arrows of a cycle and their forces.

    Attributes
    ----------
    arrows : tuple of SchemeForce
    values : ndarray, shape (A, K, 2)
        Each arrow's force at each sample, N (NaN where the mechanism does not assemble).
    scale : float
        N per mm of the mechanism drawn full size (an arrow of force F is ``F / scale`` mm long).
    torque_point : int
        The frame's point of the crank's pivot, where the driving torque is drawn.
    """

    arrows: tuple[SchemeForce, ...]
    values: np.ndarray
    scale: float
    torque_point: int


def force_arrows(cycle: Cycle, size: float) -> Arrows | None:
    """The arrows of ``cycle`` (None where it has no forces), scaled for a drawing of ``size`` m."""
    if cycle.forces is None:
        return None
    mech = cycle.mech
    reactions = _reaction_arrows(mech)
    loads, load_values = _loads(cycle)
    values = np.concatenate([_reactions(cycle, reactions), load_values], 1)  # (A, arrows, 2)
    values = np.where(cycle.valid[:, None, None], values, np.nan)
    size_of = np.hypot(values[..., 0], values[..., 1])
    largest = np.max(size_of, axis=1, initial=0.0, where=np.isfinite(size_of))
    top = percentile(largest[cycle.valid], PERCENTILE) if cycle.valid.any() else 0.0
    scale = drawing_scale(top * 100.0 / (LENGTH * 1000.0 * size)) if top > 0 else 1.0
    return Arrows(reactions + loads, values, scale, _torque_point(mech))


@per_mechanism
def _reaction_arrows(mech: Mechanism) -> tuple[SchemeForce, ...]:
    """One arrow a joint: the force on its member of the highest number, at its point."""
    arrows = []
    for joint in dict.fromkeys(mech.pair_joint):
        pairs = [k for k, j in enumerate(mech.pair_joint) if j == joint]
        members = sorted({int(i) for k in pairs for i in mech.pair_links[k] if not mech.link_virtual[int(i)]})
        if len(members) < 2:
            continue
        on = members[-1]
        by = members[:-1]
        k = next(k for k in pairs if on in map(int, mech.pair_links[k]))
        point = _point_of(mech, k, on)
        label = "R" + (",".join if max(members) >= 10 else "".join)([*(str(b) for b in by), str(on)])
        arrows.append(
            SchemeForce(
                "reaction", str(joint), label, mech.link_names[on], tuple(mech.link_names[b] for b in by), point
            )
        )
    return tuple(arrows)


def _reactions(cycle: Cycle, arrows: tuple[SchemeForce, ...]) -> np.ndarray:
    """The forces of the reactions' ``arrows``, ``(A, R, 2)``."""
    forces = cycle.forces
    assert forces is not None
    return cycle.one(forces.reactions([a.name for a in arrows], [a.on for a in arrows]))


def _point_of(mech: Mechanism, k: int, link: int) -> int:
    """The point at which pair ``k``'s force on ``link`` acts: its point of ``link``, the slider's for a guide."""
    if mech.pair_type[k] != PairType.REVOLUTE:
        return int(mech.pair_points[k, 1])
    return int(mech.pair_points[k, 0 if int(mech.pair_links[k, 0]) == link else 1])


@per_mechanism
def _load_arrows(mech: Mechanism) -> tuple[SchemeForce, ...]:
    """An arrow for each point of the file's forces, process loads, springs and dampers on a moving link (a
    force's, each tool of a process load, each moving end of a spring or damper)."""
    return tuple(
        SchemeForce("load", load.name, load.name, mech.link_names[int(mech.point_link[p])], (), int(p))
        for load in mech.loads
        if load.kind in ("force", "process", "spring", "damper")
        for p in load.points
        if mech.point_link[p] != 0
    )


def _loads(cycle: Cycle) -> tuple[tuple[SchemeForce, ...], np.ndarray]:
    """An arrow for each force of the file's loads on a moving link (a process load's on each tool), and their
    forces ``(A, L, 2)``: the elementary force of the external loads on its point's link at its point."""
    mech, kin, forces = cycle.mech, cycle.kin, cycle.forces
    candidates = _load_arrows(mech)
    if not candidates:
        return (), np.zeros((len(cycle.valid), 0, 2))
    assert forces is not None
    applied = forces.external.forces
    arrows, values, used = [], [], set()
    for arrow in candidates:
        link = int(mech.point_link[arrow.point])
        position = cycle.one(kin.position(mech.point_names[arrow.point]))
        for i, force in enumerate(applied):
            same = force.link == link and np.array_equal(force.position[0], position, equal_nan=True)
            if i not in used and same:
                used.add(i)
                arrows.append(arrow)
                values.append(force.force[0])  # (V, A, 2), as evaluate gives every array
                break
    return tuple(arrows), np.stack(values, 1) if values else np.zeros((len(cycle.valid), 0, 2))


def _torque_point(mech: Mechanism) -> int:
    """The frame's point of the crank's pivot."""
    k = int(mech.drive_pair[0])
    a = int(mech.pair_links[k, 0])
    return int(mech.pair_points[k, 0 if a == 0 else 1])
