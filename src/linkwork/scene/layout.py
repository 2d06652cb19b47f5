"""What of a kinematic scheme the structure of its mechanism fixes, whatever its dimensions: which points are
joints, which links are drawn through which points, the pivots, the supports on the frame, the slider pairs and
their guides, the knives of process loads, the markers and the names written beside the points.

:func:`scheme_layout` finds it once a mechanism (:func:`~linkwork.structure.model.per_mechanism`), so that the viewer's
edits, which draw one mechanism's variants, and every drawing of a report share it; :mod:`linkwork.scene.scheme`
places it at the poses of a kinematics result.
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import compress
from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from linkwork.structure.model import PairType, per_mechanism, point_labels

if TYPE_CHECKING:
    from linkwork.structure.model import Mechanism


@dataclass(frozen=True)
class Layout:
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
    point_link : ndarray of int, shape (P,)
        The link of every point.
    frame_points : ndarray of int
        The frame's points.
    bodies : list of (int, list of int, str)
        Link, the points it is drawn through and name of every drawn link.
    sliders : SliderLayout
        The prismatic pairs.
    blades : list of (int, str, int, list of int)
        Point, its name, its link and the link's joints of every point of a process load (a knife's edge).
    markers : list of (int, int, str)
        Point, link and name of every point of a moving link that no pair uses.
    """

    joint: set[int]
    moving: list[int]
    outline: dict[int, list[int]]
    sides: np.ndarray
    path_points: list[int]
    pivots: list[tuple[str, int, int]]
    supports: dict[int, str]
    point_labels: list[tuple[str, int, int, float]]
    point_link: np.ndarray
    frame_points: np.ndarray
    bodies: list[tuple[int, list[int], str]]
    sliders: SliderLayout
    blades: list[tuple[int, str, int, list[int]]]
    markers: list[tuple[int, int, str]]


@per_mechanism
def scheme_layout(mech: Mechanism) -> Layout:
    """The :class:`Layout` of ``mech``, found once a mechanism (the viewer's edits draw one mechanism's variants)."""
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
    point_link = np.array(mech.point_link, dtype=int)
    return Layout(
        joint,
        moving,
        outline,
        np.array(sides, dtype=int).reshape(-1, 2),
        [p for p in moving if outline[int(point_link[p])]],
        list(pivots.values()),
        supports,
        _named_points(mech, joint, revolute),
        point_link,
        np.flatnonzero(point_link == 0),
        [(i, draw, str(mech.link_names[i])) for i, draw in outline.items() if i and draw],
        _sliders(mech, [k for k in range(mech.n_pairs) if not revolute[k]]),
        _blades(mech, joint),
        [(p, int(point_link[p]), str(mech.point_names[p])) for p in moving if p not in joint],
    )


def _blades(mech: Mechanism, joint: set[int]) -> list[tuple[int, str, int, list[int]]]:
    """:attr:`Layout.blades` of ``mech``, whose pairs' points are ``joint``."""
    out = []
    for load in mech.loads:
        if load.kind != "process":
            continue
        for p in load.points:
            link = int(mech.point_link[p])
            joints = [q for q in range(len(mech.point_names)) if mech.point_link[q] == link and q in joint]
            out.append((int(p), str(mech.point_names[p]), link, joints))
    return out


class SliderLayout(NamedTuple):
    """The prismatic pairs of a mechanism: the pairs, the sliders' links, points and joints, whether each guide is
    on the frame; the points and joints of the guides on the frame."""

    pairs: np.ndarray
    links: list[int]
    points: list[int]
    joints: list[str]
    on_frame: np.ndarray
    guided: list[int]
    guide_joints: list[str]


def _sliders(mech: Mechanism, pairs: list[int]) -> SliderLayout:
    """:attr:`Layout.sliders` of the prismatic pairs ``pairs`` of ``mech``."""
    points = [int(mech.pair_points[k, 1]) for k in pairs]
    joints = [str(mech.pair_joint[k]) for k in pairs]
    on = np.array([int(mech.pair_links[k, 0]) == 0 for k in pairs], dtype=bool)  # the guide is the frame's
    return SliderLayout(
        np.array(pairs, dtype=int),
        [int(mech.pair_links[k, 1]) for k in pairs],
        points,
        joints,
        on,
        list(compress(points, on)),
        list(compress(joints, on)),
    )


def _named_points(mech: Mechanism, joint: set[int], revolute: list[bool]) -> list[tuple[str, int, int, float]]:
    """:attr:`Layout.point_labels` of ``mech``."""
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
