"""The structural model of a description: arrays, structural analysis, assembly pose.

The first stage of :func:`linkwork.compile` (:mod:`linkwork.api`), the one compile, which adds the records
of the stages that build on it (:mod:`linkwork.structure.records`): the solve program, the external loads,
the friction in the pairs and the machine unit's motor and gear.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

from linkwork.errors import Problem, SpecError, StructureError, UnassemblableError
from linkwork.lang import t
from linkwork.spec.reader import description
from linkwork.spec.schema import ImpactSpec, Joint, Spec
from linkwork.structure.assemble import assemble, scaled, solve_group, unfixed_links
from linkwork.structure.assur import decompose, rank
from linkwork.structure.constraints import Rows, build_rows
from linkwork.structure.model import AssurGroup, Mechanism, PairType, Said, Structure, formula, frozen, global_points
from linkwork.structure.parameters import (
    COM_CENTROID,
    COM_GIVEN,
    INERTIA_GIVEN,
    INERTIA_NONE,
    INERTIA_ROD,
    mass_properties,
)
from linkwork.structure.records import ImpactRecord, ToolRecord


def structural_model(spec: Spec) -> Mechanism:
    """The structural model of a validated spec: a :class:`Mechanism` without the records of the later
    stages (its solve program, loads, friction, motor and gear: :func:`linkwork.compile` adds them).

    Builds the flat arrays, decomposes the mechanism into Assur groups,
    assembles it in the pose chosen by the drives' start values and the
    hints, and finds redundant constraints from the Jacobian's rank there.

    Raises
    ------
    SpecError
        A group lacks the hint that chooses its assembly mode, or a mass
        property is impossible.
    StructureError
        The mobility does not match the drives.
    UnassemblableError
        The assembly pose does not exist.
    """
    try:
        return _compile(spec)
    except (StructureError, UnassemblableError) as exc:
        file = spec.source.file if spec.source is not None else None
        if file and not str(exc).startswith(file):
            exc.args = (f"{file}: {exc}",)
        raise


@dataclass(frozen=True)
class _Count:
    """The Chebyshev count of a description: ``n`` moving links, ``p5`` lower and ``p4`` higher pairs;
    and its drives, as a message names them (``1 drive (crank) is given``)."""

    n: int
    p5: int
    p4: int
    drives: str

    @property
    def w(self) -> int:
        """The degrees of freedom W = 3n - 2p5 - p4."""
        return 3 * self.n - 2 * self.p5 - self.p4

    def text(self) -> str:
        """``W = 3n - 2p5 = 3*3 - 2*4 = 1``."""
        tail = f" - {self.p4}" if self.p4 else ""
        return f"W = 3n - 2p5{' - p4' if self.p4 else ''} = 3*{self.n} - 2*{self.p5}{tail} = {self.w}"

    def mismatch(self) -> str:
        """The message of a mechanism whose drives are not as many as its degrees of freedom."""
        w = self.w
        what = "the mechanism is a rigid structure" if w <= 0 else f"the mechanism has {w} degree(s) of freedom"
        return f"{self.text()}: {what}, but {self.drives}; the number of drives must equal W"


def _compile(spec: Spec) -> Mechanism:
    """The structural model: the arrays, the Assur groups, the assembly pose and the structural analysis."""
    mech, hints, count = _arrays(spec)
    rows = build_rows(mech.pair_type, mech.pair_links, mech.drive_pair)
    scale = _scale(mech)
    groups = _groups(mech, rows, scale, count)
    _require_hints(spec, mech, groups, hints)
    try:
        q0 = assemble(mech, rows, groups, hints, scale)
    except UnassemblableError:
        if count.w != mech.n_drives:
            raise StructureError(count.mismatch()) from None
        raise
    mech = dataclasses.replace(mech, pose0=q0)
    return dataclasses.replace(mech, structure=_structure(mech, rows, scale, groups, hints, count))


def _groups(mech: Mechanism, rows: Rows, scale: float, count: _Count) -> list[AssurGroup]:
    """The Assur groups in solving order, found from the constraint Jacobian at a random (generic) pose.

    Raises
    ------
    StructureError
        Naming the links the drives leave free.
    """
    n_total = mech.n_links_total
    rng = np.random.default_rng(20240607)
    qg = np.column_stack([rng.uniform(-scale, scale, (n_total, 2)), rng.uniform(-math.pi, math.pi, n_total)])
    jac_g = scaled(qg, mech, rows, scale)[1]
    moving = jac_g[:, 3:]
    if rank(moving) < moving.shape[1]:
        # the drives leave some links free: name them from the null space, without searching for groups
        groups: list[AssurGroup] = []
        free = _null_links(moving)
    else:
        groups, free = decompose(
            rows, jac_g, n_total, mech.pair_type, mech.pair_links, mech.pair_joint, mech.link_names
        )
    if free:
        raise StructureError(_free_message(mech, free, count))
    return groups


def _null_links(moving: np.ndarray) -> list[int]:
    """The links (numbered from 1) that move in the null space of the moving links' Jacobian ``(m, 3 n)``."""
    _, sv, vt = np.linalg.svd(moving)
    null = vt[np.sum(sv > 1e-8 * sv[0]) :] if len(sv) else vt
    weight = np.abs(null).reshape(len(null), -1, 3).max(axis=(0, 2))
    return [int(i) + 1 for i in np.flatnonzero(weight > 1e-8)]


def _free_message(mech: Mechanism, free: list[int], count: _Count) -> str:
    """What is wrong with a mechanism whose drives leave the links ``free`` undetermined."""
    names = ", ".join(f"{i} ({mech.link_names[i]})" for i in free)
    if set(free) <= set(_spinning_links(mech)):
        return (
            f"{count.text()}, but {count.drives}: the links {names} only turn about their one joint "
            "point (a passive degree of freedom, such as a roller on its pin), which W counts; join each to "
            "the link it turns on, or give it a point fixed by another pair"
        )
    return f"{count.text()}, but {count.drives}: the links {names} are not determined by the drives" + (
        f"; add {count.w - mech.n_drives} more drive(s)" if count.w > mech.n_drives else ""
    )


def _structure(
    mech: Mechanism, rows: Rows, scale: float, groups: list[AssurGroup], hints: dict[int, np.ndarray], count: _Count
) -> Structure:
    """The structural analysis of the assembled ``mech``: redundant constraints and the actual mobility from the
    rank of the Jacobian in the assembly pose and beside it, and the warnings of the assembly.

    Raises
    ------
    StructureError
        The mobility does not match the drives.
    """
    q0 = mech.pose0
    pair_rows = [i for i in range(rows.n) if rows.drive[i] < 0]
    r0, rd0 = _ranks(mech, rows, q0, scale, pair_rows)
    near = [_ranks(mech, rows, q1, scale, pair_rows, v) for q1, v in _neighbours(mech, rows, q0, scale)]
    r = max([r0] + [n[0] for n in near])
    rd = max([rd0] + [n[1] for n in near])
    mobility = 3 * (mech.n_links_total - 1) - r
    redundant = len(pair_rows) - r
    if mobility != mech.n_drives:
        msg = count.mismatch()
        if redundant:
            msg += (
                f"; {redundant} constraint(s) are redundant in the assembly pose, so the actual mobility is {mobility}"
            )
        raise StructureError(msg)
    said: list[Said] = []
    if rd0 < rd:
        said.append(("structure.warning.singular_pose", (("rank", str(rd - rd0)),)))
    said += _hint_warnings(mech, hints, scale)
    warnings = tuple(t(key, "en", **dict(fields)) for key, fields in said)
    return Structure(
        count.n, count.p5, count.p4, count.w, redundant, mobility, tuple(groups), formula(groups), warnings, tuple(said)
    )


_EMPTY = Structure(0, 0, 0, 0, 0, 0, (), "")


def _spinning_links(mech: Mechanism) -> list[int]:
    """Links whose every pair is a revolute at one and the same point of theirs (they spin about it)."""
    out = []
    for i in range(1, mech.n_links_total):
        pts: list[np.ndarray] = []
        for k in range(mech.n_pairs):
            a, b = (int(x) for x in mech.pair_links[k])
            if i not in (a, b):
                continue
            if mech.pair_type[k] != PairType.REVOLUTE:
                pts = []  # a link with a prismatic pair does not spin about a point
                break
            pts.append(mech.point_local[mech.pair_points[k, 0 if a == i else 1]])
        if pts and np.ptp(np.array(pts), axis=0).max() < 1e-12:
            out.append(i)
    return out


def _drives_text(spec: Spec) -> str:
    """The drives as a message names them: ``1 drive (crank) is given``."""
    names = ", ".join(d.joint for d in spec.drives)
    if len(spec.drives) == 1:
        return f"1 drive ({names}) is given"
    return f"{len(spec.drives)} drives ({names}) are given"


def _scale(mech: Mechanism) -> float:
    """The size of the mechanism (m), by which angles are made commensurate with lengths."""
    frame_pts = mech.point_local[mech.point_link == 0]
    spans = [np.abs(frame_pts).max() if len(frame_pts) else 0.0]
    spans.append(float(np.abs(mech.point_local).max()) if len(mech.point_local) else 0.0)
    return max(max(spans), 1e-3)


def _ranks(
    mech: Mechanism, rows: Rows, q: np.ndarray, scale: float, pair_rows: list[int], values: np.ndarray | None = None
) -> tuple[int, int]:
    """Rank of the pair constraints, and of pairs and drives together, at pose ``q``."""
    jac = scaled(q, mech, rows, scale, values)[1][:, 3:]
    return rank(jac[pair_rows]), rank(jac)


def _neighbours(mech: Mechanism, rows: Rows, q0: np.ndarray, scale: float) -> list[tuple[np.ndarray, np.ndarray]]:
    """Poses a little way either side along the motion (singular poses are isolated)."""
    step = np.where(mech.pair_type[mech.drive_pair] == PairType.REVOLUTE, 0.02, 0.002 * scale)
    links = tuple(range(1, mech.n_links_total))
    out = []
    for sign in (1.0, -1.0):
        values = mech.drive_start + sign * step
        q1, worst = solve_group(mech, rows, q0, links, list(range(rows.n)), scale, values)
        if worst <= 1e-9 * scale:
            out.append((q1, values))
    return out


def _require_hints(spec: Spec, mech: Mechanism, groups: list[AssurGroup], hints: dict[int, np.ndarray]) -> None:
    """Every group needs hints that fix its assembly mode: its inner joints,
    and enough points of each link to give a starting pose."""
    src = spec.source
    in_file = src is not None and isinstance(src.data, dict) and "hints" in src.data
    problems = []

    def add(path: tuple[str, ...], msg: str) -> None:
        problems.append(src.problem(path, msg) if src is not None else Problem(".".join(path), msg))

    placed = {0}
    for group in groups:
        inner = [k for k in group.pairs if set(map(int, mech.pair_links[k])) <= set(group.links)]
        for k in inner:
            if int(mech.pair_points[k, 1]) not in hints:
                joint = mech.pair_joint[k]
                add(
                    ("hints",) if in_file else ("joints", joint),
                    f"group {group.label} (links {', '.join(group.link_names)}) needs a hint for its inner "
                    f'joint "{joint}" to choose its assembly mode: add "{joint}: [x, y]" under hints, '
                    "near where it is in the assembly pose",
                )
        asked = any(int(mech.pair_points[k, 1]) not in hints for k in inner)
        for i in [] if asked else unfixed_links(mech, group, placed, hints):
            names = [n.split(".", 1)[1] for n, li in zip(mech.point_names, mech.point_link, strict=True) if li == i]
            add(
                ("hints",) if in_file else ("links", mech.link_names[i]),
                f'group {group.label}: the position of link "{mech.link_names[i]}" is not fixed by the joints '
                f"already placed and the hints; add a hint for one more of its points ({', '.join(names)}) "
                "to choose the assembly mode",
            )
        placed |= set(group.links)
    if problems:
        raise SpecError(list(dict.fromkeys(problems)))


def _hint_warnings(mech: Mechanism, hints: dict[int, np.ndarray], scale: float) -> list[Said]:
    """A warning for each hint far (more than a tenth of ``scale``) from where its point assembled."""
    pts = global_points(mech.pose0, mech.point_link, mech.point_local)
    out: dict[tuple[str, float, float], Said] = {}
    for p, h in hints.items():
        gap = float(np.hypot(*(pts[p] - h)))
        name = mech.point_names[p].split(".", 1)[1]
        key = (name, float(h[0]), float(h[1]))
        if gap > 0.1 * scale and key not in out:
            at, found = f"({h[0]:.4g}, {h[1]:.4g})", f"({pts[p][0]:.4g}, {pts[p][1]:.4g})"
            out[key] = ("structure.warning.hint", (("name", name), ("at", at), ("gap", f"{gap:.3g}"), ("found", found)))
    return list(out.values())


# --- the arrays of a description ---------------------------------------------------------------------


class _Draft(NamedTuple):
    """The arrays of a description before its analysis: the model (its assembly pose zero, its structure
    empty), the hints by point index and the Chebyshev count."""

    mechanism: Mechanism
    hints: dict[int, np.ndarray]
    chebyshev: _Count


def _arrays(spec: Spec) -> _Draft:
    """The flat arrays of a validated description, in the steps that build them: the links and their points,
    the mass rules, the elementary pairs, the drives and the hints."""
    slots = [j for j, joint in spec.joints.items() if joint.type == "pin-in-slot"]
    link_names = ("frame", *spec.links, *(f"{j}:block" for j in slots))
    index = {name: i for i, name in enumerate(link_names)}
    points = _points(spec, link_names, index)
    rules = _mass_rules(spec, index, points.index)
    pairs = _pairs(spec, index, points)
    drives = _drives(spec, pairs)
    mech = _model(spec, points, rules, pairs, drives)
    count = _Count(len(spec.links), pairs.p5, pairs.p4, _drives_text(spec))
    return _Draft(mech, _hints(spec, index, points.index), count)


@dataclass
class _Points:
    """The points of the model as they are added: ``link.point`` names, owner links, local coordinates (m),
    the index of each ``(link, point name)``; and the point indices of the ends of each link given by ends
    and length (-1 for the others)."""

    link_names: tuple[str, ...]
    ends: np.ndarray
    names: list[str] = field(default_factory=list)
    link: list[int] = field(default_factory=list)
    local: list[tuple[float, float]] = field(default_factory=list)
    index: dict[tuple[int, str], int] = field(default_factory=dict)

    def add(self, link: int, name: str, xy: tuple[float, float]) -> None:
        self.index[(link, name)] = len(self.names)
        self.names.append(f"{self.link_names[link]}.{name}")
        self.link.append(link)
        self.local.append(xy)


def _points(spec: Spec, link_names: tuple[str, ...], index: dict[str, int]) -> _Points:
    """The frame's points, then each link's: its two ends (for a link given by ends and length, on its
    local x axis) and its named points.  The slot blocks' points come with their pairs."""
    points = _Points(link_names, np.full((len(link_names), 2), -1))
    for name, xy in spec.frame.points.items():
        points.add(0, name, xy)
    for name, link in spec.links.items():
        i = index[name]
        if link.ends is not None and link.length is not None:
            points.add(i, link.ends[0], (0.0, 0.0))
            points.add(i, link.ends[1], (link.length, 0.0))
            points.ends[i] = (points.index[(i, link.ends[0])], points.index[(i, link.ends[1])])
        for pname, xy in link.points.items():
            points.add(i, pname, xy)
    return points


class _MassRules(NamedTuple):
    """What the file gives of each link's mass properties, ``(N,)`` or ``(N, 2)``: masses (kg), the rule of
    the centre of mass and the given centres (m), the rule of the moment of inertia and the given moments
    (kg m^2) (:mod:`linkwork.structure.parameters`)."""

    mass: np.ndarray
    com_rule: np.ndarray
    com_given: np.ndarray
    inertia_rule: np.ndarray
    inertia_given: np.ndarray


def _mass_rules(spec: Spec, index: dict[str, int], pindex: dict[tuple[int, str], int]) -> _MassRules:
    """How the file gives each link's mass, centre of mass and moment of inertia (the mass rule of
    :mod:`linkwork.structure.parameters`)."""
    n = len(index)
    mass = np.zeros(n)
    com_rule = np.full(n, COM_CENTROID)
    com_given = np.zeros((n, 2))
    inertia_rule = np.full(n, INERTIA_NONE)
    inertia_given = np.zeros(n)
    for name, link in spec.links.items():
        mass[index[name]] = link.mass or 0.0
    if spec.frame.mass is not None:
        mass[0] = spec.frame.mass
    owners = [(0, spec.frame.com, None, None, None)] + [
        (index[name], link.com, link.inertia, link.inertia_about, link.length) for name, link in spec.links.items()
    ]
    for i, com, inertia, about, length in owners:
        if isinstance(com, str):
            com_rule[i] = pindex[(i, com)]
        elif com is not None:
            com_rule[i], com_given[i] = COM_GIVEN, com
        elif i == 0:
            com_rule[i] = COM_GIVEN  # the frame's centre of mass, where the file gives none: its origin
        if inertia is not None:
            inertia_given[i] = inertia
            inertia_rule[i] = pindex[(i, about)] if about is not None else INERTIA_GIVEN
        elif length is not None:
            inertia_rule[i] = INERTIA_ROD
    return _MassRules(mass, com_rule, com_given, inertia_rule, inertia_given)


#: A guide line: its origin and unit direction, local to the guide, and the guide's point the origin is at (or -1).
_Line = tuple[tuple[float, float], tuple[float, float], int]


@dataclass
class _Pairs:
    """The elementary pairs as they are added (the rows of ``Mechanism.pair_*``), the first pair of each
    revolute and prismatic joint, and the counts of lower (``p5``) and higher (``p4``) pairs."""

    type: list[int] = field(default_factory=list)
    links: list[tuple[int, int]] = field(default_factory=list)
    points: list[tuple[int, int]] = field(default_factory=list)
    origin: list[tuple[float, float]] = field(default_factory=list)
    axis: list[tuple[float, float]] = field(default_factory=list)
    origin_point: list[int] = field(default_factory=list)
    joint: list[str] = field(default_factory=list)
    members: list[tuple[int, int]] = field(default_factory=list)
    first: dict[str, int] = field(default_factory=dict)
    p5: int = 0
    p4: int = 0

    def add(
        self,
        kind: PairType,
        links: tuple[int, int],
        points: tuple[int, int],
        joint: str,
        named: list[int],
        line: _Line = ((0.0, 0.0), (1.0, 0.0), -1),
    ) -> None:
        """One pair of ``kind`` between ``links`` at ``points`` (-1 where none), of the joint that names the
        links ``named``; a prismatic pair's guide ``line``: its origin and direction, local to the guide, and
        the point the origin is at (-1: given by coordinates)."""
        a, b = links
        self.type.append(kind)
        self.links.append(links)
        if a in named and b in named:
            self.members.append((a, b) if named.index(a) < named.index(b) else (b, a))
        else:  # a pin in a slot: its block stands for the other member
            self.members.append((named[0], named[1]))
        self.points.append(points)
        self.origin.append(line[0])
        self.axis.append(line[1])
        self.origin_point.append(line[2])
        self.joint.append(joint)


def _pairs(spec: Spec, index: dict[str, int], points: _Points) -> _Pairs:
    """The elementary pairs of the joints, in the file's order: a revolute joint of k links makes k - 1
    revolute pairs, a prismatic joint one prismatic pair, a pin in a slot a revolute pair of the pin with
    the slot's block and a prismatic pair of the block in the slot (the block's point is added here)."""
    depth = _depths(spec, index)
    driven_joints = {drive.joint for drive in spec.drives}
    pairs = _Pairs()
    pin = points.index
    for jname, joint in spec.joints.items():
        pt = joint.point or jname
        named = [index[ln] for ln in joint.links]
        links = list(named)
        if joint.type == "revolute" and len(links) > 2:
            # a compound hinge: k - 1 pairs from the member nearest the frame (whatever the listed order)
            centre = min(links, key=lambda i: (depth[i], i))
            links = [centre] + [i for i in links if i != centre]
        if joint.type == "revolute" and len(links) == 2 and links[1] == 0 and jname in driven_joints:
            # a drive on the frame measures the driven link's angle from the frame, however the file orders them;
            # pair_members keeps the file's order, in which the reactions are given
            links = links[::-1]
        if joint.type == "revolute":
            pairs.first[jname] = len(pairs.type)
            for other in links[1:]:
                pairs.add(PairType.REVOLUTE, (links[0], other), (pin[(links[0], pt)], pin[(other, pt)]), jname, named)
                pairs.p5 += 1
        elif joint.type == "prismatic":
            pairs.first[jname] = len(pairs.type)
            line = _guide(points, links[0], joint)
            pairs.add(PairType.PRISMATIC, (links[0], links[1]), (-1, pin[(links[1], pt)]), jname, named, line)
            pairs.p5 += 1
        else:
            block = index[f"{jname}:block"]
            points.add(block, pt, (0.0, 0.0))
            pairs.add(PairType.REVOLUTE, (links[1], block), (pin[(links[1], pt)], pin[(block, pt)]), jname, named)
            line = _guide(points, links[0], joint)
            pairs.add(PairType.PRISMATIC, (links[0], block), (-1, pin[(block, pt)]), jname, named, line)
            pairs.p4 += 1
    return pairs


def _guide(points: _Points, guide: int, joint: Joint) -> _Line:
    """The line of a prismatic pair or a slot on the link ``guide``: its origin and unit direction, local to
    the guide, and the guide's point the origin is at (-1 where the file gives coordinates)."""
    through, angle = joint.through, joint.axis
    assert through is not None and angle is not None  # the checks of linkwork.spec ask for both
    axis = (math.cos(angle), math.sin(angle))
    if isinstance(through, str):
        p = points.index[(guide, through)]
        return points.local[p], axis, p
    return through, axis, -1


class _Drives(NamedTuple):
    """The drives: the pair each drives, its signed speed (rad/s or m/s; NaN where a law gives the motion)
    and its coordinate in the assembly pose."""

    pair: list[int]
    speed: list[float]
    start: list[float]


def _drives(spec: Spec, pairs: _Pairs) -> _Drives:
    """The drives of the file, on the first pair of their joints."""
    out = _Drives([], [], [])
    for drive in spec.drives:
        k = pairs.first[drive.joint]
        out.pair.append(k)
        sign = -1.0 if drive.direction in ("cw", "backward") else 1.0
        speed = drive.speed if isinstance(drive.speed, float) else (math.nan if drive.law else 0.0)
        out.speed.append(sign * speed)
        start = drive.angle if pairs.type[k] == PairType.REVOLUTE else drive.position
        out.start.append(start or 0.0)
    return out


def _hints(spec: Spec, index: dict[str, int], pindex: dict[tuple[int, str], int]) -> dict[int, np.ndarray]:
    """The hints by point index: a hint named by a joint is a hint for its point on each moving member (and on
    a pin-in-slot's block)."""
    hints: dict[int, np.ndarray] = {}
    for key, xy in spec.hints.items():
        if "." in key:
            ln, p = key.split(".", 1)
            hints[pindex[(index[ln], p)]] = np.array(xy)
        else:
            joint = spec.joints[key]
            pt = joint.point or key
            for ln in joint.links[1:] if joint.type != "revolute" else joint.links:
                if ln != "frame":
                    hints[pindex[(index[ln], pt)]] = np.array(xy)
            if joint.type == "pin-in-slot":
                hints[pindex[(index[f"{key}:block"], pt)]] = np.array(xy)
    return hints


def _model(spec: Spec, points: _Points, rules: _MassRules, pairs: _Pairs, drives: _Drives) -> Mechanism:
    """The frozen arrays: a :class:`Mechanism` with its assembly pose zero and its structure empty, its centres of
    mass and moments of inertia by the mass rule (:func:`~linkwork.structure.parameters.mass_properties`)."""
    n_total = len(points.link_names)
    source = spec.source
    mech = Mechanism(
        name=spec.name or (source.file if source and source.file else "mechanism"),
        source=source.file if source else None,
        link_names=points.link_names,
        link_virtual=frozen(np.arange(n_total) > len(spec.links), bool),  # the slot blocks come last
        link_mass=frozen(rules.mass),
        link_com=frozen(rules.com_given).reshape(-1, 2),  # the given ones; the rule fills in the others below
        link_inertia=frozen(rules.inertia_given),
        link_com_rule=frozen(rules.com_rule, int),
        link_inertia_rule=frozen(rules.inertia_rule, int),
        link_inertia_given=frozen(rules.inertia_given),
        point_names=tuple(points.names),
        point_link=frozen(points.link, int),
        point_local=frozen(points.local).reshape(-1, 2),
        pair_type=frozen(pairs.type, int),
        pair_links=frozen(pairs.links, int).reshape(-1, 2),
        pair_points=frozen(pairs.points, int).reshape(-1, 2),
        pair_origin=frozen(pairs.origin).reshape(-1, 2),
        pair_axis=frozen(pairs.axis).reshape(-1, 2),
        pair_joint=tuple(pairs.joint),
        pair_members=frozen(pairs.members, int).reshape(-1, 2),
        drive_pair=frozen(drives.pair, int),
        drive_speed=frozen(drives.speed),
        drive_start=frozen(drives.start),
        gravity=spec.gravity if isinstance(spec.gravity, float) else spec.gravity.value,
        gravity_direction=-math.pi / 2 if isinstance(spec.gravity, float) else spec.gravity.direction,
        pose0=np.zeros((n_total, 3)),
        structure=_EMPTY,
        joint_names=tuple(spec.joints),
        link_ends=frozen(points.ends, int).reshape(-1, 2),
        pair_origin_point=frozen(pairs.origin_point, int),
        delta=spec.machine.delta if spec.machine is not None else None,
        blow=impact_record(spec.impact),
        description=description(spec),
    )
    com, inertia = mass_properties(
        mech, np.array(points.local, dtype=float).reshape(1, -1, 2), rules.mass[None], rules.inertia_given[None]
    )
    return dataclasses.replace(mech, link_com=frozen(com[0]), link_inertia=frozen(inertia[0]))


def _depths(spec: Spec, index: dict[str, int]) -> dict[int, int]:
    """Number of joints between each link and the frame (breadth first)."""
    adj: dict[int, set[int]] = {i: set() for i in index.values()}
    for joint in spec.joints.values():
        members = [index[ln] for ln in joint.links]
        for i in members:
            adj[i] |= set(members) - {i}
    depth, frontier = {0: 0}, [0]
    while frontier:
        nxt = []
        for i in frontier:
            for j in adj[i]:
                if j not in depth:
                    depth[j] = depth[i] + 1
                    nxt.append(j)
        frontier = nxt
    return {i: depth.get(i, 1 << 30) for i in index.values()}


def impact_record(impact: ImpactSpec | None) -> ImpactRecord | None:
    """The :class:`~linkwork.structure.records.ImpactRecord` of a validated ``impact:`` section (SI already), or
    None: the compiled model carries numbers and names, not the file's objects."""
    if impact is None:
        return None
    tool = impact.tool
    return ImpactRecord(
        at=impact.at,
        normal=impact.normal,
        omega=impact.omega,
        link=impact.link,
        restitution=impact.restitution,
        friction=impact.friction,
        rod_joint=impact.rod_joint,
        tool=None if tool is None else ToolRecord(tool.mass, tool.feed, tool.resistance),
    )
