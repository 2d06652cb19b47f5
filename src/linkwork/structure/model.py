"""The compiled mechanism: frozen arrays and its structural analysis."""

from __future__ import annotations

import functools
import math
import weakref
from collections.abc import Callable
from dataclasses import dataclass, field
from enum import IntEnum
from typing import TYPE_CHECKING, Any, TypeVar

import numpy as np
import numpy.typing as npt

from linkwork.structure.records import ExternalLoad, ImpactRecord, MotorGear, PairFriction, Step

if TYPE_CHECKING:  # the description below the model, which it keeps
    from linkwork.spec.yamlsource import Source


class PairType(IntEnum):
    """The kind of an elementary pair (``Mechanism.pair_type``)."""

    REVOLUTE = 0
    PRISMATIC = 1


T = TypeVar("T")


def per_mechanism(make: Callable[[Mechanism], T]) -> Callable[[Mechanism], T]:
    """``make`` called once per mechanism, its result kept until the mechanism is freed.

    A compiled :class:`Mechanism` is read-only, so what depends on it alone (its file's geometry, its
    parameters, the layout of its drawing) is found once and shared by every later call, the viewer's
    edits of its variants included; the result is shared, and callers must not change it.  Mechanisms
    are told apart by identity."""
    kept: dict[int, tuple[weakref.ref[Mechanism], T]] = {}

    @functools.wraps(make)
    def once(mech: Mechanism) -> T:
        key = id(mech)
        found = kept.get(key)
        if found is not None and found[0]() is mech:
            return found[1]
        value = make(mech)

        def forget(ref: weakref.ref[Mechanism]) -> None:
            if kept.get(key, (None,))[0] is ref:
                del kept[key]

        kept[key] = (weakref.ref(mech, forget), value)
        return value

    return once


ROMAN = ["0", "I", "II", "III", "IV", "V", "VI", "VII", "VIII", "IX", "X"]


def roman(n: int) -> str:
    return ROMAN[n] if 0 <= n < len(ROMAN) else str(n)


@dataclass(frozen=True)
class AssurGroup:
    """One step of the structural decomposition, in solving order (``Structure.groups``).

    Parameters
    ----------
    klass : int
        Class after Artobolevsky: 1 for a driving link (or a group that
        carries a drive), 2 for dyads, 3 for triads, 4 for four-link groups
        with a closed contour, ...; 0 for a link that only adds redundant
        constraints.
    order : int or None
        Number of external pairs (None for class 1).
    kind : str
        Pair letters: ``RRR``, ``RRP``, ``RPR``, ``PRP``, ``RPP`` for dyads;
        the letter of the driven pair for a driving link; for larger groups
        the letters of their pairs, external ones first.
    links : tuple of int
        Link numbers (frame = 0) of the group.
    link_names : tuple of str
        The file's names of those links.
    joints : tuple of str
        Names of the joints of the group (internal and external).
    internal : tuple of str
        Names of the joints between links of the group.
    pairs : tuple of int
        Indices of the pairs (rows of ``Mechanism.pair_*``) of the group.
    redundant : int, default 0
        Redundant constraints inside the group.
    driven : bool, default False
        The group carries a drive.
    """

    klass: int
    order: int | None
    kind: str
    links: tuple[int, ...]
    link_names: tuple[str, ...]
    joints: tuple[str, ...]
    internal: tuple[str, ...]
    pairs: tuple[int, ...]
    redundant: int = 0
    driven: bool = False

    @property
    def label(self) -> str:
        """``II(2,3) RRR``-style label."""
        nums = ",".join(str(i) for i in self.links)
        if self.klass == 1:
            return f"I(0,{nums}) {self.kind}"
        if self.klass == 0:
            return f"({nums}) redundant link"
        return f"{roman(self.klass)}({nums}) {self.kind}"

    def as_dict(self) -> dict[str, Any]:
        return {
            "class": self.klass,
            "order": self.order,
            "kind": self.kind,
            "links": list(self.links),
            "link_names": list(self.link_names),
            "joints": list(self.joints),
            "internal_joints": list(self.internal),
            "redundant": self.redundant,
            "driven": self.driven,
        }


#: A text to be said in any language: its key in :mod:`linkwork.lang`'s catalogues and its fields (name, value).
Said = tuple[str, tuple[tuple[str, str], ...]]


@dataclass(frozen=True)
class Structure:
    """Structural analysis of a mechanism (``Mechanism.structure``; :func:`linkwork.compile` finds it).

    Parameters
    ----------
    n_links : int
        Moving links n (the frame and slot blocks not counted).
    p5, p4 : int
        Lower pairs (a compound hinge of k links counts k - 1) and higher
        (pin-in-slot) pairs.
    dof : int
        W = 3 n - 2 p5 - p4 by the Chebyshev formula.
    redundant : int
        Redundant (passive) constraints q, from the rank of the constraint
        Jacobian in the assembly pose and a neighbouring pose.
    mobility : int
        Actual degrees of freedom, W + q.
    groups : tuple of AssurGroup
        The decomposition, in solving order.
    formula : str
        The structural formula, e.g. ``I(0,1) -> II(2,3) -> II(4,5)``.
    warnings : tuple of str, default ()
        Singular assembly pose, hints far from the assembled points, ... (in English).
    said : tuple of Said, default ()
        The same warnings as keys of :mod:`linkwork.lang`'s catalogues with their fields, to be said in any language.
    """

    n_links: int
    p5: int
    p4: int
    dof: int
    redundant: int
    mobility: int
    groups: tuple[AssurGroup, ...]
    formula: str
    warnings: tuple[str, ...] = ()
    said: tuple[Said, ...] = ()

    def as_dict(self) -> dict[str, Any]:
        return {
            "n_links": self.n_links,
            "p5": self.p5,
            "p4": self.p4,
            "dof": self.dof,
            "redundant": self.redundant,
            "mobility": self.mobility,
            "groups": [g.as_dict() for g in self.groups],
            "formula": self.formula,
            "warnings": list(self.warnings),
        }


def formula(groups: tuple[AssurGroup, ...] | list[AssurGroup]) -> str:
    """The structural formula of a decomposition."""
    parts = []
    for g in groups:
        nums = ",".join(str(i) for i in g.links)
        if g.klass == 1:
            parts.append(f"I(0,{nums})")
        elif g.klass == 0:
            parts.append(f"q({nums})")
        else:
            parts.append(f"{roman(g.klass)}({nums})")
    return " -> ".join(parts)


@dataclass(frozen=True)
class Mechanism:
    """A compiled mechanism: flat read-only arrays, no state.

    Link 0 is the frame; links ``1..n_links`` are the moving links in the
    order of the file (the paper's numbering); pin-in-slot pairs add a
    massless slot block link each after them (``link_virtual``).  Pairs are
    the elementary kinematic pairs: a compound hinge of k links becomes
    k - 1 revolute pairs, each between the member nearest the frame (which
    carries the pin) and one of the others in the file's order; a
    pin-in-slot a revolute and a prismatic pair of its block.

    Shapes: ``N = n_links_total`` links, ``P`` points, ``M`` pairs, ``D``
    drives (``drive_*``: the joints the file drives, each by a speed or a law; the motor that turns the
    machine is ``motor_gear``).  Lengths in m, angles in rad, SI throughout.

    :func:`linkwork.compile` makes it from a description; nobody writes these arrays by hand.

    Parameters
    ----------
    name : str
        The mechanism's name: the file's ``name:``, else the file's name, else ``"mechanism"``.
    source : str or None
        The file it was read from, or None.
    link_names : tuple of str
        ``(N,)``: ``"frame"``, the moving links in the file's order, then the slot blocks.
    link_virtual : ndarray of bool, shape (N,)
        True for a pin-in-slot's massless block.
    link_mass : ndarray, shape (N,)
        Mass of each link, kg.
    link_com : ndarray, shape (N, 2)
        Centre of mass in the link's local frame, m.
    link_inertia : ndarray, shape (N,)
        Moment of inertia about the centre of mass, kg m^2.
    link_com_rule : ndarray of int, shape (N,)
        How the file gives the centre of mass: ``COM_GIVEN`` (-2), ``COM_CENTROID`` (-1), or the index of the
        point it is at (:mod:`linkwork.structure.parameters`; the mass rule of the variants).
    link_inertia_rule : ndarray of int, shape (N,)
        How the file gives the inertia: ``INERTIA_GIVEN`` (-3), ``INERTIA_ROD`` (-2), ``INERTIA_NONE`` (-1),
        or the index of the point it is given about.
    link_inertia_given : ndarray, shape (N,)
        The file's inertia about the rule's point, kg m^2; 0 where the file gives none.
    point_names : tuple of str
        ``(P,)``: ``"link.point"`` of every point.
    point_link : ndarray of int, shape (P,)
        The link each point is on.
    point_local : ndarray, shape (P, 2)
        Each point in its link's local frame, m.
    pair_type : ndarray of int, shape (M,)
        ``PairType`` of each pair: 0 revolute, 1 prismatic.
    pair_links : ndarray of int, shape (M, 2)
        The two links of each pair ``[a, b]``; a prismatic pair's ``[guide, slider]``.
    pair_points : ndarray of int, shape (M, 2)
        The point of each link at the pair; -1 where there is none.
    pair_origin : ndarray, shape (M, 2)
        A prismatic pair's point of the guide line, local to its guide, m.
    pair_axis : ndarray, shape (M, 2)
        A prismatic pair's guide direction (a unit vector), local to its guide.
    pair_joint : tuple of str
        ``(M,)``: the file's joint each pair comes from.
    drive_pair : ndarray of int, shape (D,)
        The pair each drive turns or pushes.
    drive_speed : ndarray, shape (D,)
        Each drive's speed, rad/s or m/s, signed; NaN where the file gives a law.
    drive_start : ndarray, shape (D,)
        Each drive's coordinate in the assembly pose, rad or m.
    gravity : float
        The size of gravity's acceleration, m/s^2 (0: none), along ``gravity_direction``.
    pose0 : ndarray, shape (N, 3)
        The assembly pose ``(x, y, theta)`` of every link, m and rad.
    structure : Structure
        The structural analysis: Chebyshev's formula and the Assur groups.
    link_ends : ndarray of int, shape (N, 2)
        The end points of a link the file gives by its ends and length; -1 otherwise.
    pair_origin_point : ndarray of int, shape (M,)
        The point whose local coordinates are a guide's origin; -1 where none is.
    pair_members : ndarray of int, shape (M, 2)
        The links of each pair in the order its joint names them in the file (see ``pair_sign``).
    joint_names : tuple of str, default ()
        The file's joints, in its order.
    program : tuple of Step, default ()
        The solve program, one step per group, in solving order.
    program_table : tuple of (ndarray, ndarray) or None, default None
        The program as the compiled kernels read it (operations, branches), where every step has a compiled
        kernel.
    loads : tuple of ExternalLoad, default ()
        The file's external loads.
    friction : tuple of PairFriction, default ()
        The friction in proportion to the pairs' forces.
    motor_gear : MotorGear or None, default None
        The machine unit's motor, gear and flywheel, if the file gives them.
    delta : float or None, default None
        The coefficient of speed fluctuation the file asks a flywheel for.
    blow : ImpactRecord or None, default None
        The file's ``impact:`` section in SI.
    description : Source or None, default None
        The document it was compiled from, as plain data with the line of each element
        (:class:`~linkwork.spec.yamlsource.Source`; a description changed in code: its values in SI);
        :func:`linkwork.spec.reader.described` reads it back into the description.  The model keeps no
        object of the file format.
    gravity_direction : float, default -pi/2
        The direction gravity acts in, rad, global, counter-clockwise from +x (-y by default).
    """

    name: str
    source: str | None
    link_names: tuple[str, ...]
    link_virtual: np.ndarray  # (N,) bool
    link_mass: np.ndarray  # (N,) kg
    link_com: np.ndarray  # (N, 2) local m
    link_inertia: np.ndarray  # (N,) kg m^2 about the centre of mass
    # how the file gives them (linkwork.structure.parameters: the mass rule for variants)
    link_com_rule: np.ndarray  # (N,) COM_GIVEN, COM_CENTROID, or the point it is at
    link_inertia_rule: np.ndarray  # (N,) INERTIA_GIVEN, INERTIA_ROD, INERTIA_NONE, or the point it is about
    link_inertia_given: np.ndarray  # (N,) kg m^2: the file's value (about the rule's point), else 0
    point_names: tuple[str, ...]  # "link.point"
    point_link: np.ndarray  # (P,) int
    point_local: np.ndarray  # (P, 2)
    pair_type: np.ndarray  # (M,) PairType: 0 revolute, 1 prismatic
    pair_links: np.ndarray  # (M, 2) [a, b]; prismatic: [guide, slider]
    pair_points: np.ndarray  # (M, 2) point indices; -1 where none
    pair_origin: np.ndarray  # (M, 2) prismatic: guide line point, local to a
    pair_axis: np.ndarray  # (M, 2) prismatic: guide unit direction, local to a
    pair_joint: tuple[str, ...]  # spec joint name of each pair
    drive_pair: np.ndarray  # (D,) int
    drive_speed: np.ndarray  # (D,) rad/s or m/s, signed; NaN where a law is given
    drive_start: np.ndarray  # (D,) drive coordinate of the assembly pose
    gravity: float  # m/s^2, the size of gravity (0: none), acting along gravity_direction
    pose0: np.ndarray  # (N, 3) assembly pose
    structure: Structure
    link_ends: np.ndarray  # (N, 2) point indices of links given by ends and length; -1 otherwise
    pair_origin_point: np.ndarray  # (M,) point whose local coordinates are the guide origin; -1
    pair_members: np.ndarray  # (M, 2) the links of each pair in the order its joint names them
    joint_names: tuple[str, ...] = field(default=())
    # the records the stages above compile into the model (linkwork.structure.records), by linkwork.compile:
    program: tuple[Step, ...] = ()  # the solve program, in solving order
    # the program as the compiled kernels read it (linkwork.motion.compiled_program.encode: ops, branches), if
    # every step has a compiled kernel
    program_table: tuple[np.ndarray, np.ndarray] | None = None
    loads: tuple[ExternalLoad, ...] = ()  # the external loads
    friction: tuple[PairFriction, ...] = ()  # friction in proportion to the pairs' forces
    motor_gear: MotorGear | None = None  # the machine unit's motor, gear and flywheel, if the file gives them
    delta: float | None = None  # the coefficient of speed fluctuation the file asks a flywheel for
    blow: ImpactRecord | None = None  # the file's impact: section, SI, as a record
    description: Source | None = field(default=None, repr=False, compare=False)  # the document, plain data
    gravity_direction: float = -math.pi / 2  # rad, global, counter-clockwise from +x: -y by default

    @property
    def gravity_vector(self) -> np.ndarray:
        """Gravity's acceleration ``(2,)``, m/s^2: ``gravity`` along ``gravity_direction``; a component a
        quarter-turn direction leaves at rounding size (cos 270 deg) is exactly zero."""
        u = np.array([math.cos(self.gravity_direction), math.sin(self.gravity_direction)])
        u[np.abs(u) < 1e-12] = 0.0
        return self.gravity * u

    @property
    def n_links(self) -> int:
        """Number of moving links n of the Chebyshev formula."""
        return self.structure.n_links

    @property
    def n_links_total(self) -> int:
        return len(self.link_names)

    @property
    def n_pairs(self) -> int:
        return len(self.pair_type)

    @property
    def n_drives(self) -> int:
        return len(self.drive_pair)

    @property
    def pair_sign(self) -> np.ndarray:
        """``(M,)``: +1 where ``pair_links`` lists a pair's links in the order its joint names them in
        the file (``pair_members``), -1 where the model reverses them (a drive written ``[crank, frame]``,
        which the model measures from the frame; the member of a compound hinge that carries the pin
        named after the other; a pin's pair with its slot's block, the block standing for the slot).
        It turns the force of ``pair_links[k, 0]`` on ``pair_links[k, 1]`` into the force of
        ``pair_members[k, 0]`` on ``pair_members[k, 1]``."""
        return np.where(self.pair_links[:, 0] == self.pair_members[:, 0], 1.0, -1.0)

    def first_pairs(self) -> dict[str, int]:
        """The first pair of every joint, by the joint's name (a compound hinge makes several)."""
        out: dict[str, int] = {}
        for k, joint in enumerate(self.pair_joint):
            out.setdefault(joint, k)
        return out

    def point_index(self, name: str) -> int:
        """Index of a point given as ``link.point`` or a joint name."""
        if name in self.point_names:
            return self.point_names.index(name)
        for k, joint in enumerate(self.pair_joint):
            if joint == name:
                return int(self.pair_points[k, 1])
        raise KeyError(f'no point "{name}"')

    def points0(self) -> np.ndarray:
        """Global positions of all points in the assembly pose, (P, 2)."""
        return global_points(self.pose0, self.point_link, self.point_local)


def point_labels(mech: Mechanism, with_all: bool = False) -> list[tuple[str, int]]:
    """One name per physical point: the joint's name for the points of a joint (given once), the
    point's own name for a marker whose name no other point has, ``link.point`` otherwise.  Frame
    points and slot blocks are left out, unless ``with_all`` (then every point, joints repeated)."""
    joint_of: dict[int, str] = {}
    for k in range(mech.n_pairs):
        for p in mech.pair_points[k]:
            if p >= 0:
                joint_of[int(p)] = mech.point_names[int(p)].split(".", 1)[1]
    short = [n.split(".", 1)[1] for n in mech.point_names]
    out: list[tuple[str, int]] = []
    seen: set[str] = set()
    for p, name in enumerate(short):
        link = mech.point_link[p]
        if not with_all and (link == 0 or mech.link_virtual[link]):
            continue
        label = name if p in joint_of or short.count(name) == 1 else mech.point_names[p]
        if with_all or label not in seen:
            seen.add(label)
            out.append((label, p))
    return out


def one_crank(mech: Mechanism) -> bool:
    """Whether the mechanism has exactly one drive and it is revolute (a crank turning whole cycles)."""
    return bool(mech.n_drives == 1 and mech.pair_type[mech.drive_pair[0]] == PairType.REVOLUTE)


def frozen(values: npt.ArrayLike, dtype: npt.DTypeLike = float) -> np.ndarray:
    """``values`` as a new read-only array of ``dtype``: the arrays of a :class:`Mechanism` are never written."""
    out: np.ndarray = np.array(values, dtype=dtype)
    out.flags.writeable = False
    return out


def global_points(q: np.ndarray, point_link: np.ndarray, point_local: np.ndarray) -> np.ndarray:
    """Global coordinates of points, shape ``(..., n_points, 2)``, of the poses ``q`` ``(..., N, 3)``."""
    ql = q[..., point_link, :]
    c, s = np.cos(ql[..., 2]), np.sin(ql[..., 2])
    x, y = point_local[..., 0], point_local[..., 1]
    return ql[..., :2] + np.stack([c * x - s * y, s * x + c * y], -1)
