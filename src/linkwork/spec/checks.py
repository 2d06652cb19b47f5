"""Checks of a mechanism description that go beyond its schema.

They run on the raw data of the file, so that they report their problems in
the same pass as the schema's own (units, types, unknown keys): names and
references, the connection of every link to the frame, the drives and the
hints.
"""

from __future__ import annotations

import unicodedata
from collections import Counter, defaultdict
from collections.abc import Callable, Collection
from typing import Any

from linkwork.did_you_mean import budget, suggest
from linkwork.errors import Problem, UnitParseError
from linkwork.limits import MAX_MAGNITUDE, quote, shown
from linkwork.spec.requirements import check_requirements
from linkwork.spec.schema import direction_word
from linkwork.spec.yamlsource import Path, Source
from linkwork.units import KINDS, parse_quantity


class _Name:
    """The names of points, links, joints and loads: a letter of any script or ``_`` first, then letters,
    combining marks (accents), digits, ``_`` and ``'`` (``crank``, ``O1``, ``B'``, ``кривошип``, ``μοχλός``,
    ``连杆``, ``e\u0301``); no space, dot, sign or other punctuation, which paths and references read."""

    def match(self, word: str) -> bool:
        if not isinstance(word, str) or not word:
            return False
        first = unicodedata.category(word[0])
        return (first[0] == "L" or word[0] == "_") and all(
            c in "_'" or unicodedata.category(c)[0] in "LMN" for c in word[1:]
        )


NAME = _Name()
FRAME = "frame"

#: ``bad(path, message)``: report a problem at ``path`` of the file's data.
Report = Callable[[Path, str], None]


def _dict(value: Any) -> dict[str, Any]:
    return value if isinstance(value, dict) else {}


def link_points(links: dict[str, Any], frame: dict[str, Any]) -> dict[str, set[str]]:
    """Point names of every link (and of ``frame``) as declared in raw data."""
    out: dict[str, set[str]] = {FRAME: set(_dict(frame.get("points")))}
    for name, link in links.items():
        if name == FRAME:
            continue
        link = _dict(link)
        pts = set(_dict(link.get("points")))
        ends = link.get("ends")
        if isinstance(ends, list):
            pts |= {e for e in ends if isinstance(e, str)}
        out[name] = pts
    return out


def check(src: Source, declared: dict[str, str]) -> list[Problem]:
    """All reference and consistency problems of the raw data in ``src``."""
    with budget():
        return _check(src, declared)


def _check(src: Source, declared: dict[str, str]) -> list[Problem]:
    data = _dict(src.data)
    out: list[Problem] = []

    def bad(path: Path, message: str) -> None:
        out.append(src.problem(path, message))

    links = _dict(data.get("links"))
    frame = _dict(data.get("frame"))
    joints = _dict(data.get("joints"))
    points = link_points(links, frame)

    if "links" in data and isinstance(data["links"], dict) and not links:
        bad(("links",), "a mechanism needs at least one moving link")
    for name in frame.get("points", {}) if isinstance(frame.get("points"), dict) else {}:
        if not NAME.match(name):
            bad(("frame", "points", name), f"{quote(name)} is not a valid point name (letters, digits, _)")
    for name, link in links.items():
        if isinstance(name, str):
            _check_link(bad, name, _dict(link), points)
    com = frame.get("com")
    if isinstance(com, str) and com not in points[FRAME]:
        bad(("frame", "com"), f"the frame has no point {quote(com)}{suggest(com, points[FRAME])}")

    known = set(links) | {FRAME}
    for jname, joint in joints.items():
        _check_joint(bad, jname, _dict(joint), known, points)

    _check_connected(bad, links, joints, known)
    _check_drives(bad, data, joints, declared)
    _check_hints(bad, data, joints, points)
    _check_loads(bad, data, points)
    _check_machine(bad, data)
    _check_impact(bad, data, points)
    check_requirements(bad, data)
    return out


def _check_link(bad: Report, name: str, link: dict[str, Any], points: dict[str, set[str]]) -> None:
    """The name, the ends and points, and the mass properties' references of the moving link ``name``."""
    path: Path = ("links", name)
    if name == FRAME:
        bad(path, '"frame" is the fixed link; give a moving link another name')
        return
    if not NAME.match(name):
        bad(path, f"{quote(name)} is not a valid link name (letters, digits, _, starting with a letter)")
    _check_ends(bad, path, link)
    for p in _dict(link.get("points")):
        if not NAME.match(p):
            bad(path + ("points", p), f"{quote(p)} is not a valid point name (letters, digits, _)")
    if not points[name]:
        bad(path, 'a link needs at least one point ("ends" with "length", or "points")')
    for key in ("com", "inertia_about"):
        ref = link.get(key)
        if isinstance(ref, str) and ref not in points[name]:
            bad(path + (key,), f"link {quote(name)} has no point {quote(ref)}{suggest(ref, points[name])}")
    if link.get("inertia_about") is not None and link.get("inertia") is None:
        bad(path + ("inertia_about",), '"inertia_about" needs "inertia"')


def _check_ends(bad: Report, path: Path, link: dict[str, Any]) -> None:
    """A link given by ``ends: [P, Q]`` and ``length``: both given, two different valid names, not in ``points``."""
    ends, length = link.get("ends"), link.get("length")
    if ends is not None and length is None:
        bad(path, 'a link given by "ends" needs its "length"')
    if length is not None and ends is None:
        bad(path + ("length",), 'a "length" needs "ends: [P, Q]", the two points it separates')
    if not isinstance(ends, list):
        return
    if len(ends) != 2:
        bad(path + ("ends",), f"expected two point names, got {len(ends)}")
    elif ends[0] == ends[1]:
        bad(path + ("ends",), f"the two ends must differ, got {quote(ends[0])} twice")
    for e in ends:
        if isinstance(e, str) and e in _dict(link.get("points")):
            bad(path + ("points", e), f"point {quote(e)} is already one of the ends")
        elif isinstance(e, str) and not NAME.match(e):
            bad(path + ("ends",), f"{quote(e)} is not a valid point name")


def _check_joint(bad: Report, jname: str, joint: dict[str, Any], known: set[str], points: dict[str, set[str]]) -> None:
    """A joint's name and links (known, at least two, each once), and its point on each of them."""
    path: Path = ("joints", jname)
    if not NAME.match(jname):
        bad(path, f"{quote(jname)} is not a valid joint name (letters, digits, _)")
    names = joint.get("links")
    if not isinstance(names, list):
        return
    kind = joint.get("type")
    for i, ln in enumerate(names):
        if isinstance(ln, str) and ln not in known:
            bad(path + ("links", i), f"unknown link {quote(ln)}{suggest(ln, known)}")
    if len(names) < 2:
        bad(path + ("links",), f"a joint joins at least two links, got {len(names)}")
        return
    counts = Counter(n for n in names if isinstance(n, str))
    for n in sorted(n for n, k in counts.items() if k > 1):
        bad(path + ("links",), f"link {quote(n)} is listed twice")
    point = joint.get("point") or jname
    if not isinstance(point, str):
        return
    if kind == "revolute":
        _check_revolute(bad, path, joint, names, point, points)
    elif kind in ("prismatic", "pin-in-slot"):
        _check_sliding(bad, path, joint, kind, names, point, points)
    _check_pair_friction(bad, path, joint.get("friction"), kind)


def _check_pair_friction(bad: Report, path: Path, friction: Any, kind: Any) -> None:
    """A joint's ``friction``: a pin's ``radius`` in a revolute joint (its friction circle is ``f radius``),
    none in a prismatic one (its friction force is ``f |N|``)."""
    if not isinstance(friction, dict):
        return
    path = path + ("friction",)
    if "f" not in friction:
        bad(path, 'missing field "f" (the friction coefficient)')
    if kind == "revolute" and "radius" not in friction:
        bad(path, 'missing field "radius" (the pin\'s radius: the friction moment is f radius |R|)')
    if kind == "prismatic" and "radius" in friction:
        bad(path + ("radius",), 'a prismatic joint has no "radius": its friction force is f |N|')


def _check_revolute(
    bad: Report, path: Path, joint: dict[str, Any], names: list[Any], point: str, points: dict[str, set[str]]
) -> None:
    """A revolute joint: no guide line, and its ``point`` on every link it joins."""
    for key in ("through", "axis"):
        if key in joint:
            bad(path + (key,), f"{quote(key)} applies to prismatic and pin-in-slot joints only")
    for ln in names:
        if isinstance(ln, str) and ln in points and point not in points[ln]:
            where = "the frame" if ln == FRAME else f"link {quote(ln)}"
            bad(path, f"{where} has no point {quote(point)} for this joint{suggest(point, points[ln])}")


def _check_sliding(
    bad: Report,
    path: Path,
    joint: dict[str, Any],
    kind: str,
    names: list[Any],
    point: str,
    points: dict[str, set[str]],
) -> None:
    """A prismatic or pin-in-slot joint: a guide and a slider, its ``point`` on the slider, a guide line
    ``through`` a point of the guide along ``axis``."""
    if len(names) != 2:
        bad(path + ("links",), f"a {kind} joint joins exactly two links: [guide, slider], got {len(names)}")
        return
    guide, slider = names
    if isinstance(slider, str) and slider in points and point not in points[slider]:
        role = "slider" if kind == "prismatic" else "pin link"
        hint = suggest(point, points[slider])
        if joint.get("point") is None:  # the joint's name stood for the point: say how to name it
            some = sorted(points[slider])[:1]
            example = f", e.g. point: {some[0]}" if some else ""
            hint += f"; give the {role}'s point on the guide line as point:{example}"
        bad(path, f"the {role} {quote(slider)} has no point {quote(point)}{hint}")
    for key, what in (("axis", "direction of the guide line"), ("through", "a point of the guide line")):
        if joint.get(key) is None:
            bad(path, f"missing field {quote(key)} ({what})")
    through = joint.get("through")
    if isinstance(through, str) and isinstance(guide, str) and guide in points and through not in points[guide]:
        where = "the frame" if guide == FRAME else f"the guide link {quote(guide)}"
        bad(path + ("through",), f"{where} has no point {quote(through)}{suggest(through, points[guide])}")
    if guide == FRAME and slider == FRAME:
        bad(path + ("links",), "a joint cannot join the frame to itself")


def _check_connected(bad: Report, links: dict[str, Any], joints: dict[str, Any], known: set[str]) -> None:
    """Every moving link reached from the frame through the joints (a search over links and joints, in
    time linear in the joints' lists)."""
    adj: dict[Any, set[Any]] = defaultdict(set)  # a link's joints, and a joint's links (keyed by its index)
    for j, joint in enumerate(joints.values()):
        listed = _dict(joint).get("links")
        for n in listed if isinstance(listed, list) else []:
            if isinstance(n, str) and n in known:
                adj[n].add(j)
                adj[j].add(n)
    seen: set[Any] = {FRAME}
    stack: list[Any] = [FRAME]
    while stack:
        for nxt in adj[stack.pop()] - seen:
            seen.add(nxt)
            stack.append(nxt)
    for name in links:
        if name != FRAME and name not in seen:
            bad(("links", name), "not connected to the frame: no chain of joints leads from this link to the frame")


def _check_drives(bad: Report, data: dict[str, Any], joints: dict[str, Any], declared: dict[str, str]) -> None:
    """Every drive on an existing joint, driven once; each drive's own fields (:func:`_check_drive`)."""
    drives = data.get("drives")
    if isinstance(drives, list) and not drives:
        bad(("drives",), "a mechanism needs at least one drive")
    if not isinstance(drives, list):
        return
    seen: dict[str, int] = {}
    for i, drive in enumerate(drives):
        path: Path = ("drives", i)
        drive = _dict(drive)
        jname = drive.get("joint")
        if not isinstance(jname, str):
            continue
        if jname in seen:
            bad(path + ("joint",), f"joint {quote(jname)} is already driven by drives[{seen[jname]}]")
        seen[jname] = i
        if jname not in joints:
            bad(path + ("joint",), f"drive on a missing joint {quote(jname)}{suggest(jname, joints)}")
            continue
        _check_drive(bad, path, drive, jname, _dict(joints[jname]), declared)


def _check_drive(
    bad: Report, path: Path, drive: dict[str, Any], jname: str, joint: dict[str, Any], declared: dict[str, str]
) -> None:
    """A drive's fields for the type of its joint ``jname``: its direction, its pose coordinate, its speed
    or its motion law."""
    kind = joint.get("type")
    if kind not in ("revolute", "prismatic", "pin-in-slot"):
        return  # the joint's own problem is reported at the joint
    if kind == "pin-in-slot":
        bad(path + ("joint",), f"{quote(jname)} is a pin-in-slot pair, which cannot be driven")
        return
    listed = joint.get("links")
    nlinks = len(listed) if isinstance(listed, list) else 0
    if kind == "revolute" and nlinks != 2:
        bad(path + ("joint",), f"a driven revolute joint must join exactly two links, {quote(jname)} joins {nlinks}")
    rot = kind == "revolute"
    direction = direction_word(drive.get("direction"))
    if rot and direction in ("forward", "backward"):
        bad(path + ("direction",), f'a revolute drive turns "ccw" or "cw", got {quote(direction)}')
    if not rot and direction in ("ccw", "cw"):
        bad(path + ("direction",), f'a prismatic drive moves "forward" or "backward", got {quote(direction)}')
    wrong = "position" if rot else "angle"
    if drive.get(wrong) is not None:
        right = "an angle" if rot else "a position"
        bad(
            path + (wrong,),
            f"a {kind} drive has {right} (the drive coordinate of the assembly pose), not a {quote(wrong)}",
        )
    if drive.get("speed") is not None:
        quantity = "angular_speed" if rot else "speed"
        try:
            speed = parse_quantity(drive["speed"], quantity, declared)
        except UnitParseError as exc:
            bad(path + ("speed",), str(exc))
            speed = 0.0
        if not abs(speed) <= MAX_MAGNITUDE:
            bad(path + ("speed",), f"expected {KINDS[quantity][0]} of a machine's size, got {shown(drive['speed'])}")
    law = _dict(drive.get("law"))
    _check_law(bad, path, law, rot, declared)
    if law and drive.get("speed") is not None:
        bad(path + ("speed",), 'give either a uniform "speed" or a motion "law", not both')


def _check_law(bad: Report, path: Path, law: dict[str, Any], rot: bool, declared: dict[str, str]) -> None:
    """A drive's motion law: its values (angles where ``rot``, else lengths) against increasing times."""
    values = law.get("value")
    if not isinstance(values, list):
        return
    for j, v in enumerate(values):
        try:
            parse_quantity(v, "angle" if rot else "length", declared)
        except UnitParseError as exc:
            bad(path + ("law", "value", j), str(exc))
    times = law.get("time")
    if not isinstance(times, list):
        return
    if len(times) != len(values):
        bad(path + ("law",), f"time has {len(times)} entries but value has {len(values)}")
    elif len(times) < 2:
        bad(path + ("law",), f"a motion law needs at least two points, got {len(times)}")
    else:
        try:
            t = [parse_quantity(x, "time", declared) for x in times]
        except UnitParseError:
            t = []
        if any(b <= a for a, b in zip(t, t[1:], strict=False)):
            bad(path + ("law", "time"), "the times of a motion law must increase")


def _check_hints(bad: Report, data: dict[str, Any], joints: dict[str, Any], points: dict[str, set[str]]) -> None:
    hints = _dict(data.get("hints"))
    names = hint_names(joints, points)
    owned = _owners(points)
    by_point = _by_point(names)
    for key in hints:
        if key in names:
            continue
        owners = sorted(owned.get(key, ()))
        if len(owners) > 1:  # a point of several links that no joint joins: the joint is missing, not the hint
            if "joints" not in data:
                continue  # the missing section is the problem, reported as such
            bad(
                ("joints",),
                f"no joint {quote(key)}: {_and(owners)} have a point {quote(key)} that no joint joins "
                f"(the hint {quote(key)} names it as a joint)",
            )
            continue
        same = sorted(by_point.get(key, ()))
        hint = f" (did you mean {quote(same[0])}?)" if same else suggest(key, names)
        bad(("hints", key), f"no moving point {quote(key)} (give a joint name or link.point){hint}")


def _owners(points: dict[str, set[str]]) -> dict[str, list[str]]:
    """Point name -> the links (and the frame) that have a point of that name."""
    out: dict[str, list[str]] = defaultdict(list)
    for link, pts in points.items():
        for p in pts:
            out[p].append(link)
    return out


def _by_point(names: Collection[str]) -> dict[str, list[str]]:
    """Point name -> the ``link.point`` names among ``names`` that end in it."""
    out: dict[str, list[str]] = defaultdict(list)
    for n in names:
        if "." in n:
            out[n.rsplit(".", 1)[1]].append(n)
    return out


def _and(names: list[str]) -> str:
    """``a``, ``a and b``, ``a, b and c``."""
    return " and ".join([", ".join(names[:-1]), names[-1]]) if len(names) > 1 else "".join(names)


def hint_names(joints: dict[str, Any], points: dict[str, set[str]]) -> set[str]:
    """Names a hint may use: joint names and ``link.point`` of moving links."""
    names = {f"{ln}.{p}" for ln, pts in points.items() if ln != FRAME for p in pts}
    names |= {j for j, joint in joints.items() if _dict(joint).get("type") in ("revolute", "prismatic", "pin-in-slot")}
    return names


_LOAD_FIELDS = {
    "force": ({"at"}, {"at", "force", "magnitude", "direction", "angle"}),
    "moment": ({"on", "moment"}, {"on", "moment", "angle"}),
    "friction": ({"joint"}, {"joint", "moment", "magnitude"}),
    "process": (
        {"tools", "axis", "workpiece", "penetration", "force"},
        {"tools", "axis", "workpiece", "penetration", "force"},
    ),
    "spring": ({"between", "stiffness"}, {"between", "stiffness", "free_length", "preload"}),
    "damper": ({"between", "damping"}, {"between", "damping"}),
    "torsion_spring": ({"joint", "stiffness", "free_angle"}, {"joint", "stiffness", "free_angle"}),
}


def _check_loads(bad: Report, data: dict[str, Any], points: dict[str, set[str]]) -> None:
    """Fields and references of the external loads; their values are checked in SI after validation."""
    loads = _dict(data.get("loads"))
    names = {f"{ln}.{p}" for ln, pts in points.items() for p in pts}
    joints = _dict(data.get("joints"))
    for name, load in loads.items():
        path: Path = ("loads", name)
        if not isinstance(name, str) or not NAME.match(name):
            bad(path, f"{quote(name)} is not a valid load name (letters, digits, _)")
        load = _dict(load)
        kind = load.get("type")
        if not isinstance(kind, str) or kind not in _LOAD_FIELDS:
            continue  # reported by the schema
        _check_load_fields(bad, path, load, kind)
        if kind == "force":
            _check_force(bad, path, load, names)
        elif kind == "friction":
            _check_friction(bad, path, load, joints)
        elif kind == "moment":
            on = load.get("on")
            if isinstance(on, str) and on not in points:
                bad(path + ("on",), f"unknown link {quote(on)}{suggest(on, points)}")
            _check_table(bad, path, load, "moment")
        elif kind == "process":
            _check_process(bad, path, load, names)
        else:
            _check_element(bad, path, load, names | frame_points(points), joints)


def frame_points(points: dict[str, set[str]]) -> set[str]:
    """The frame's points by their own names, as a force element may name them."""
    return set(points.get(FRAME, set()))


def _check_element(bad: Report, path: Path, load: dict[str, Any], names: set[str], joints: dict[str, Any]) -> None:
    """A force element: a spring or damper between two points of different links, with a free length or a
    preload (not both); a torsion spring in a revolute joint."""
    if load.get("type") == "torsion_spring":
        jname = load.get("joint")
        if isinstance(jname, str) and jname not in joints:
            bad(path + ("joint",), f"unknown joint {quote(jname)}{suggest(jname, joints)}")
        elif isinstance(jname, str) and _dict(joints.get(jname)).get("type") != "revolute":
            bad(path + ("joint",), f"a torsion spring acts in a revolute joint; {quote(jname)} is not one")
        return
    between = load.get("between")
    if not isinstance(between, list) or len(between) != 2 or not all(isinstance(p, str) for p in between):
        if between is not None:
            bad(path + ("between",), "expected two points [link.point, link.point] (a frame point by its name)")
        return
    links = [_load_point(bad, names, path + ("between", i), p) for i, p in enumerate(between)]
    links = [FRAME if p in names and "." not in p else ln for p, ln in zip(between, links, strict=True)]
    if links[0] is not None and links[0] == links[1]:
        bad(path + ("between",), f"the two points are on one link ({quote(links[0])}): the element does nothing")
    if load.get("type") == "spring" and ("free_length" in load) == ("preload" in load):
        bad(path, 'a spring needs its "free_length" or its "preload" (one of them)')


def _check_load_fields(bad: Report, path: Path, load: dict[str, Any], kind: str) -> None:
    """The fields a load of ``kind`` needs, and those of other kinds of load it has."""
    needed, allowed = _LOAD_FIELDS[kind]
    for key in sorted(needed - set(load)):
        bad(path, f"missing field {quote(key)} (a {kind} load needs {', '.join(sorted(needed))})")
    for key in sorted(set(load) - allowed - {"type", "description"}):
        if key in {f for _, a in _LOAD_FIELDS.values() for f in a}:
            bad(path + (key,), f"{quote(key)} does not apply to a {kind} load")


def _load_point(bad: Report, names: set[str], path: Path, ref: Any) -> str | None:
    """The link of a load's point ``ref`` (``link.point``, one of ``names``); None where it is not one."""
    if not isinstance(ref, str):
        return None
    if ref not in names:
        same = sorted(n for n in names if n.endswith(f".{ref}")) if len(names) <= 1000 else []
        hint = f" (did you mean {quote(same[0])}?)" if same else suggest(ref, names)
        bad(path, f"no point {quote(ref)}: give link.point, the link the load acts on and its point{hint}")
        return None
    return ref.split(".", 1)[0]


def _check_force(bad: Report, path: Path, load: dict[str, Any], names: set[str]) -> None:
    """A force: its point, and either ``force: [Fx, Fy]`` or ``magnitude`` with ``direction`` (or a table)."""
    _load_point(bad, names, path + ("at",), load.get("at"))
    vector, magnitude = load.get("force"), load.get("magnitude")
    if (vector is None) == (magnitude is None):
        bad(path, 'give either "force: [Fx, Fy]" or "magnitude" with "direction"')
    if vector is not None and (not isinstance(vector, list) or len(vector) != 2):
        bad(path + ("force",), "expected the two components [Fx, Fy] of a force")
    if magnitude is not None and load.get("direction") is None:
        bad(path, 'missing field "direction" (the direction of the magnitude)')
    if vector is not None and (load.get("direction") is not None or load.get("angle") is not None):
        bad(path, '"force: [Fx, Fy]" is constant; for a table give "magnitude", "direction" and "angle"')
    _check_table(bad, path, load, "magnitude")


def _check_friction(bad: Report, path: Path, load: dict[str, Any], joints: dict[str, Any]) -> None:
    """A friction: in an existing joint, a ``moment`` in a revolute one, a force ``magnitude`` in a sliding one."""
    jname = load.get("joint")
    jtype = _dict(joints.get(jname)).get("type") if isinstance(jname, str) else None
    sliding = jtype in ("prismatic", "pin-in-slot")
    if isinstance(jname, str) and jname not in joints:
        bad(path + ("joint",), f"unknown joint {quote(jname)}{suggest(jname, joints)}")
    elif jtype == "revolute" and load.get("moment") is None:
        bad(path, 'missing field "moment" (the friction moment of a revolute joint)')
    elif sliding and load.get("magnitude") is None:
        bad(path, 'missing field "magnitude" (the friction force of a sliding joint)')
    if jtype == "revolute" and load.get("magnitude") is not None:
        bad(path + ("magnitude",), 'a revolute joint has a friction "moment", not a force "magnitude"')
    if sliding and load.get("moment") is not None:
        bad(path + ("moment",), 'a sliding joint has a friction force "magnitude", not a "moment"')
    for key in ("moment", "magnitude"):
        if isinstance(load.get(key), list):
            bad(path + (key,), "friction is one value, not a table")


def _check_process(bad: Report, path: Path, load: dict[str, Any], names: set[str]) -> None:
    """A process load: one or two tools on different moving links, a workpiece ``[low, high]``, a table of
    force against penetration."""
    tools = load.get("tools")
    if isinstance(tools, list):
        if len(tools) not in (1, 2):
            bad(path + ("tools",), f"expected one or two tool points, got {len(tools)}")
        owners = [_load_point(bad, names, path + ("tools", i), t) for i, t in enumerate(tools)]
        if len(owners) == 2 and owners[0] is not None and owners[0] == owners[1]:
            bad(path + ("tools",), "the two tools must be on different links")
        if FRAME in owners:
            bad(path + ("tools",), "a tool is a point of a moving link, not of the frame")
    workpiece = load.get("workpiece")
    if workpiece is not None and (not isinstance(workpiece, list) or len(workpiece) != 2):
        bad(path + ("workpiece",), "expected [low, high]: the extent of the workpiece along the axis")
    pen, force = load.get("penetration"), load.get("force")
    if isinstance(pen, list) and isinstance(force, list) and len(pen) != len(force):
        bad(path, f"penetration has {len(pen)} entries but force has {len(force)}")
    elif isinstance(pen, list) and len(pen) < 2:
        bad(path + ("penetration",), f"a table needs at least two points, got {len(pen)}")


def _check_table(bad: Report, path: Path, load: dict[str, Any], key: str) -> None:
    angle, value = load.get("angle"), load.get(key)
    if angle is None:
        if isinstance(value, list):
            bad(path + (key,), 'a list of values is a table: give the crank angles in "angle"')
        return
    if not isinstance(angle, list) or value is None:
        return
    if not isinstance(value, list):
        bad(path + (key,), f'with "angle", {quote(key)} is a list of the same length')
    elif len(value) != len(angle):
        bad(path, f"angle has {len(angle)} entries but {key} has {len(value)}")
    elif len(angle) < 2:
        bad(path + ("angle",), f"a table needs at least two points, got {len(angle)}")


_MOTOR_FIELDS = {
    "constant": {"torque"},
    "linear": {"stall", "no_load"},
    "induction": {"power", "speed", "synchronous", "breakdown"},
}


def _check_machine(bad: Report, data: dict[str, Any]) -> None:
    machine = _dict(data.get("machine"))
    motor = _dict(machine.get("motor"))
    kind = motor.get("type")
    if not isinstance(kind, str) or kind not in _MOTOR_FIELDS:
        return  # reported by the schema
    path = ("machine", "motor")
    needed = _MOTOR_FIELDS[kind]
    what = f"{'an' if kind[0] in 'aeiou' else 'a'} {kind} motor"
    for key in sorted(needed - set(motor)):
        bad(path, f"missing field {quote(key)} ({what} needs {', '.join(sorted(needed))})")
    others = {f for fields in _MOTOR_FIELDS.values() for f in fields} - needed
    for key in sorted(others & set(motor)):
        bad(path + (key,), f"{quote(key)} does not apply to {what}")


def _check_impact(bad: Report, data: dict[str, Any], points: dict[str, set[str]]) -> None:
    blow = _dict(data.get("impact"))
    at = blow.get("at")
    names = {f"{ln}.{p}" for ln, pts in points.items() if ln != FRAME for p in pts}
    if isinstance(at, str) and at not in names:
        bad(("impact", "at"), f"no point {quote(at)} of a moving link (give link.point){suggest(at, names)}")
    link = blow.get("link")
    if isinstance(link, str) and (link not in points or link == FRAME):
        bad(("impact", "link"), f"unknown link {quote(link)}{suggest(link, set(points) - {FRAME})}")
    joint = blow.get("rod_joint")
    joints = _dict(data.get("joints"))
    if isinstance(joint, str) and joint not in joints:
        bad(("impact", "rod_joint"), f"unknown joint {quote(joint)}{suggest(joint, joints)}")
