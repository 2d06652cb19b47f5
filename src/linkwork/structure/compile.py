"""The structural model of a description: arrays, structural analysis, assembly pose.

:func:`linkwork.compile` (:mod:`linkwork.api`) composes it with the stages that build on it: the
solve program (:mod:`linkwork.motion.program`), the external loads
(:mod:`linkwork.kinetostatics.external`) and the machine's drive (:mod:`linkwork.machine.drive`).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from linkwork.errors import Problem, SpecError, StructureError, UnassemblableError
from linkwork.spec.schema import Spec
from linkwork.structure.assemble import assemble, scaled, solve_group, unfixed_links
from linkwork.structure.assur import decompose, rank
from linkwork.structure.constraints import build_rows
from linkwork.structure.model import AssurGroup, Mechanism, PairType, Structure, formula, global_points


def structural_model(spec: Spec) -> Mechanism:
    """The structural model of a validated spec: a :class:`Mechanism` without its solve program, its
    loads and its drive (those are added by :func:`linkwork.compile`).

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


def _compile(spec: Spec) -> Mechanism:
    arrays, hints, counts = _arrays(spec)
    mech = Mechanism(**arrays, pose0=np.zeros((len(arrays["link_names"]), 3)), structure=_EMPTY)
    rows = build_rows(mech.pair_type, mech.pair_links, mech.drive_pair)
    scale = _scale(mech)
    n_total = mech.n_links_total
    n, p5, p4 = counts
    w = 3 * n - 2 * p5 - p4

    rng = np.random.default_rng(20240607)
    qg = np.column_stack([rng.uniform(-scale, scale, (n_total, 2)), rng.uniform(-math.pi, math.pi, n_total)])
    jac_g = scaled(qg, mech, rows, scale)[1]
    drives_text = _drives_text(spec)
    moving = jac_g[:, 3:]
    if rank(moving) < moving.shape[1]:
        # the drives leave some links free: name them from the null space, without searching for groups
        _, sv, vt = np.linalg.svd(moving)
        null = vt[np.sum(sv > 1e-8 * sv[0]) :] if len(sv) else vt
        weight = np.abs(null).reshape(len(null), -1, 3).max(axis=(0, 2))
        free = [i + 1 for i in np.flatnonzero(weight > 1e-8)]
    else:
        groups, free = decompose(
            rows, jac_g, n_total, mech.pair_type, mech.pair_links, mech.pair_joint, mech.link_names
        )
    if free:
        names = ", ".join(f"{i} ({mech.link_names[i]})" for i in free)
        spinning = _spinning_links(mech)
        if set(free) <= set(spinning):
            raise StructureError(
                f"{_w_text(n, p5, p4, w)}, but {drives_text}: the links {names} only turn about their one joint "
                "point (a passive degree of freedom, such as a roller on its pin), which W counts; join each to "
                "the link it turns on, or give it a point fixed by another pair"
            )
        raise StructureError(
            f"{_w_text(n, p5, p4, w)}, but {drives_text}: the links {names} are not determined by the drives"
            + (f"; add {w - mech.n_drives} more drive(s)" if w > mech.n_drives else "")
        )
    _require_hints(spec, mech, groups, hints)
    try:
        q0 = assemble(mech, rows, groups, hints, scale)
    except UnassemblableError:
        if w != mech.n_drives:
            raise StructureError(_mismatch(n, p5, p4, w, drives_text)) from None
        raise
    mech = dataclasses.replace(mech, pose0=q0)

    pair_rows = [i for i in range(rows.n) if rows.drive[i] < 0]
    r0, rd0 = _ranks(mech, rows, q0, scale, pair_rows)
    near = [_ranks(mech, rows, q1, scale, pair_rows, v) for q1, v in _neighbours(mech, rows, q0, scale)]
    r = max([r0] + [n[0] for n in near])
    rd = max([rd0] + [n[1] for n in near])
    mobility = 3 * (n_total - 1) - r
    redundant = len(pair_rows) - r
    if mobility != mech.n_drives:
        msg = _mismatch(n, p5, p4, w, drives_text)
        if redundant:
            msg += (
                f"; {redundant} constraint(s) are redundant in the assembly pose, so the actual mobility is {mobility}"
            )
        raise StructureError(msg)
    warnings = []
    if rd0 < rd:
        warnings.append(
            "the assembly pose is a singular position (dead point): the constraint Jacobian loses "
            f"rank {rd - rd0} there; choose another drive angle for the assembly"
        )
    warnings += _hint_warnings(mech, hints, scale)
    structure = Structure(n, p5, p4, w, redundant, mobility, tuple(groups), formula(groups), tuple(warnings))
    return dataclasses.replace(mech, structure=structure)


_EMPTY = Structure(0, 0, 0, 0, 0, 0, (), "")


def _spinning_links(mech: Mechanism) -> list[int]:
    """Links whose every pair is a revolute at one and the same point of theirs (they spin about it)."""
    out = []
    for i in range(1, mech.n_links_total):
        pts = []
        for k in range(mech.n_pairs):
            a, b = (int(x) for x in mech.pair_links[k])
            if i not in (a, b):
                continue
            if mech.pair_type[k] != PairType.REVOLUTE:
                pts = None
                break
            pts.append(mech.point_local[mech.pair_points[k, 0 if a == i else 1]])
        if pts and np.ptp(np.array(pts), axis=0).max() < 1e-12:
            out.append(i)
    return out


def _w_text(n: int, p5: int, p4: int, w: int) -> str:
    tail = f" - {p4}" if p4 else ""
    return f"W = 3n - 2p5{' - p4' if p4 else ''} = 3*{n} - 2*{p5}{tail} = {w}"


def _mismatch(n: int, p5: int, p4: int, w: int, drives_text: str) -> str:
    what = "the mechanism is a rigid structure" if w <= 0 else f"the mechanism has {w} degree(s) of freedom"
    return f"{_w_text(n, p5, p4, w)}: {what}, but {drives_text}; the number of drives must equal W"


def _drives_text(spec: Spec) -> str:
    names = ", ".join(d.joint for d in spec.drives)
    if len(spec.drives) == 1:
        return f"1 drive ({names}) is given"
    return f"{len(spec.drives)} drives ({names}) are given"


def _scale(mech: Mechanism) -> float:
    frame_pts = mech.point_local[mech.point_link == 0]
    spans = [np.abs(frame_pts).max() if len(frame_pts) else 0.0]
    spans.append(float(np.abs(mech.point_local).max()) if len(mech.point_local) else 0.0)
    return max(max(spans), 1e-3)


def _ranks(
    mech: Mechanism, rows: Any, q: np.ndarray, scale: float, pair_rows: list[int], values: Any = None
) -> tuple[int, int]:
    """Rank of the pair constraints, and of pairs and drives together, at pose ``q``."""
    jac = scaled(q, mech, rows, scale, values)[1][:, 3:]
    return rank(jac[pair_rows]), rank(jac)


def _neighbours(mech: Mechanism, rows: Any, q0: np.ndarray, scale: float) -> list[tuple[np.ndarray, np.ndarray]]:
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


def _hint_warnings(mech: Mechanism, hints: dict[int, np.ndarray], scale: float) -> list[str]:
    pts = global_points(mech.pose0, mech.point_link, mech.point_local)
    out: dict[tuple[str, float, float], str] = {}
    for p, h in hints.items():
        gap = float(np.hypot(*(pts[p] - h)))
        name = mech.point_names[p].split(".", 1)[1]
        key = (name, float(h[0]), float(h[1]))
        if gap > 0.1 * scale and key not in out:
            out[key] = (
                f"the hint for {name} at ({h[0]:.4g}, {h[1]:.4g}) is {gap:.3g} m from where it assembled, "
                f"({pts[p][0]:.4g}, {pts[p][1]:.4g}): check that the assembly mode is the one you meant"
            )
    return list(out.values())


def _arrays(spec: Spec) -> tuple[dict[str, Any], dict[int, np.ndarray], tuple[int, int, int]]:
    slots = [j for j, joint in spec.joints.items() if joint.type == "pin-in-slot"]
    link_names = ["frame", *spec.links, *(f"{j}:block" for j in slots)]
    index = {name: i for i, name in enumerate(link_names)}
    point_names: list[str] = []
    point_link: list[int] = []
    point_local: list[tuple[float, float]] = []
    pindex: dict[tuple[int, str], int] = {}

    def add_point(link: int, name: str, xy: tuple[float, float]) -> None:
        pindex[(link, name)] = len(point_names)
        point_names.append(f"{link_names[link]}.{name}")
        point_link.append(link)
        point_local.append(xy)

    for name, xy in spec.frame.points.items():
        add_point(0, name, xy)
    n_total = len(link_names)
    mass = np.zeros(n_total)
    virtual = np.zeros(n_total, dtype=bool)
    ends = np.full((n_total, 2), -1)
    for name, link in spec.links.items():
        i = index[name]
        if link.ends is not None and link.length is not None:
            add_point(i, link.ends[0], (0.0, 0.0))
            add_point(i, link.ends[1], (link.length, 0.0))
            ends[i] = (pindex[(i, link.ends[0])], pindex[(i, link.ends[1])])
        for pname, xy in link.points.items():
            add_point(i, pname, xy)
        mass[i] = link.mass or 0.0
    if spec.frame.mass is not None:
        mass[0] = spec.frame.mass
    com_rule, com_given, inertia_rule, inertia_given = _mass_rules(spec, index, pindex)

    pair_type, pair_links, pair_points, pair_origin, pair_axis, pair_joint = [], [], [], [], [], []
    origin_point: list[int] = []
    pair_members: list[tuple[int, int]] = []  # the links each pair stands for, in the file's order

    def add_pair(
        kind: int, a: int, b: int, pa: int, pb: int, origin: Any = (0.0, 0.0), axis: Any = (1.0, 0.0), joint: str = ""
    ) -> None:
        pair_type.append(kind)
        pair_links.append((a, b))
        named = [index[ln] for ln in spec.joints[joint].links]
        if a in named and b in named:
            pair_members.append((a, b) if named.index(a) < named.index(b) else (b, a))
        else:  # a pin in a slot: its block stands for the other member
            pair_members.append((named[0], named[1]))
        pair_points.append((pa, pb))
        pair_origin.append(origin)
        pair_axis.append(axis)
        pair_joint.append(joint)
        if kind == PairType.REVOLUTE:
            origin_point.append(-1)

    def line(guide: int, through: Any, axis: float) -> tuple[Any, Any]:
        origin_point.append(pindex[(guide, through)] if isinstance(through, str) else -1)
        origin = point_local[pindex[(guide, through)]] if isinstance(through, str) else through
        return origin, (math.cos(axis), math.sin(axis))

    depth = _depths(spec, index)
    joint_pair: dict[str, int] = {}
    driven_joints = {drive.joint for drive in spec.drives}
    p5 = p4 = 0
    for jname, joint in spec.joints.items():
        pt = joint.point or jname
        links = [index[ln] for ln in joint.links]
        if joint.type == "revolute" and len(links) > 2:
            # a compound hinge: k - 1 pairs from the member nearest the frame (whatever the listed order)
            centre = min(links, key=lambda i: (depth[i], i))
            links = [centre] + [i for i in links if i != centre]
        if joint.type == "revolute" and len(links) == 2 and links[1] == 0 and jname in driven_joints:
            # a drive on the frame measures the driven link's angle from the frame, however the file orders them;
            # pair_members keeps the file's order, in which the reactions are given
            links = links[::-1]
        if joint.type == "revolute":
            joint_pair[jname] = len(pair_type)
            for other in links[1:]:
                add_pair(PairType.REVOLUTE, links[0], other, pindex[(links[0], pt)], pindex[(other, pt)], joint=jname)
                p5 += 1
        elif joint.type == "prismatic":
            joint_pair[jname] = len(pair_type)
            origin, axis = line(links[0], joint.through, joint.axis)
            add_pair(PairType.PRISMATIC, links[0], links[1], -1, pindex[(links[1], pt)], origin, axis, jname)
            p5 += 1
        else:
            block = index[f"{jname}:block"]
            virtual[block] = True
            add_point(block, pt, (0.0, 0.0))
            add_pair(PairType.REVOLUTE, links[1], block, pindex[(links[1], pt)], pindex[(block, pt)], joint=jname)
            origin, axis = line(links[0], joint.through, joint.axis)
            add_pair(PairType.PRISMATIC, links[0], block, -1, pindex[(block, pt)], origin, axis, jname)
            p4 += 1

    drive_pair, drive_speed, drive_start = [], [], []
    for drive in spec.drives:
        k = joint_pair[drive.joint]
        drive_pair.append(k)
        sign = -1.0 if drive.direction in ("cw", "backward") else 1.0
        speed = drive.speed if isinstance(drive.speed, float) else (math.nan if drive.law else 0.0)
        drive_speed.append(sign * speed)
        start = drive.angle if pair_type[k] == PairType.REVOLUTE else drive.position
        drive_start.append(start or 0.0)

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

    def f(a: Any, dtype: Any = float) -> np.ndarray:
        arr = np.array(a, dtype=dtype)
        arr.flags.writeable = False
        return arr

    from linkwork.structure.parameters import mass_properties

    rules = dict(
        link_com_rule=f(com_rule, int),
        link_inertia_rule=f(inertia_rule, int),
        link_inertia_given=f(inertia_given),
        link_com=f(com_given).reshape(-1, 2),
        link_ends=f(ends, int).reshape(-1, 2),
        point_link=f(point_link, int),
        link_names=tuple(link_names),
    )
    com, inertia = mass_properties(
        _Rules(**rules), np.array(point_local, dtype=float).reshape(1, -1, 2), mass[None], inertia_given[None]
    )
    arrays = dict(
        name=spec.name or (spec.source.file if spec.source and spec.source.file else "mechanism"),
        source=spec.source.file if spec.source else None,
        link_names=tuple(link_names),
        link_virtual=f(virtual, bool),
        link_mass=f(mass),
        link_com=f(com[0]),
        link_inertia=f(inertia[0]),
        link_com_rule=rules["link_com_rule"],
        link_inertia_rule=rules["link_inertia_rule"],
        link_inertia_given=rules["link_inertia_given"],
        point_names=tuple(point_names),
        point_link=f(point_link, int),
        point_local=f(point_local).reshape(-1, 2),
        pair_type=f(pair_type, int),
        pair_links=f(pair_links, int).reshape(-1, 2),
        pair_points=f(pair_points, int).reshape(-1, 2),
        pair_origin=f(pair_origin).reshape(-1, 2),
        pair_axis=f(pair_axis).reshape(-1, 2),
        pair_joint=tuple(pair_joint),
        pair_members=f(pair_members, int).reshape(-1, 2),
        drive_pair=f(drive_pair, int),
        drive_speed=f(drive_speed),
        drive_start=f(drive_start),
        gravity=spec.gravity,
        joint_names=tuple(spec.joints),
        link_ends=f(ends, int).reshape(-1, 2),
        pair_origin_point=f(origin_point, int),
        delta=spec.machine.delta if spec.machine is not None else None,
        blow=spec.impact,
        spec=spec,
    )
    return arrays, hints, (len(spec.links), p5, p4)


@dataclass(frozen=True)
class _Rules:
    """What :func:`~linkwork.structure.parameters.mass_properties` reads of a mechanism being compiled."""

    link_com_rule: np.ndarray
    link_inertia_rule: np.ndarray
    link_inertia_given: np.ndarray
    link_com: np.ndarray
    link_ends: np.ndarray
    point_link: np.ndarray
    link_names: tuple[str, ...]


def _mass_rules(
    spec: Spec, index: dict[str, int], pindex: dict[tuple[int, str], int]
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """How the file gives each link's centre of mass and moment of inertia (the mass rule of
    :mod:`linkwork.structure.parameters`): the rules ``(N,)``, the given centres ``(N, 2)`` and the
    given moments of inertia ``(N,)``."""
    from linkwork.structure.parameters import (
        COM_CENTROID,
        COM_GIVEN,
        INERTIA_GIVEN,
        INERTIA_NONE,
        INERTIA_ROD,
    )

    n = len(index)
    com_rule = np.full(n, COM_CENTROID)
    com_given = np.zeros((n, 2))
    inertia_rule = np.full(n, INERTIA_NONE)
    inertia_given = np.zeros(n)
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
    return com_rule, com_given, inertia_rule, inertia_given


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
