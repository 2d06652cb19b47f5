"""The parts of a double-cut shears' file, read from its structure rather than assumed by name: which link is the
crank and where it is pivoted, which link (the rocker) drives the two knives' rods and at which of its points, the
two knives (the tools of the process load, the upper first), their edges and their guides.

The file's check of a ``requirements: {kind: double-cut-shears}`` (:mod:`linkwork.spec.requirements`) and the
synthesis of the shears (:mod:`linkwork.synthesis.shears`: the named parameters it sets, the guides it measures
the knives on) read them here, from the raw file or from its Spec alike.
"""

from __future__ import annotations

from typing import Any, NamedTuple

from linkwork.limits import quote

#: The fixed link's name in every file.
FRAME = "frame"


class ShearsParts(NamedTuple):
    """The names a double-cut shears' file gives its parts (the upper knife's first in each pair).

    Attributes
    ----------
    crank : str
        The driven link.
    pivot : str
        The frame point the crank turns about.
    rocker : str
        The link whose points drive both knives' rods.
    arms : tuple of str
        The rocker's points of the upper and the lower knife's rods.
    knives : tuple of str
        The upper and the lower knife's links (the process load's tools, in its order).
    edges : tuple of str
        Their edge points (the tools' points).
    guides : tuple of str
        Their prismatic joints with the frame.
    """

    crank: str
    pivot: str
    rocker: str
    arms: tuple[str, str]
    knives: tuple[str, str]
    edges: tuple[str, str]
    guides: tuple[str, str]

    @property
    def paths(self) -> list[str]:
        """The named parameters the synthesis sets: the crank's length (the family's free one), the pivot's x
        (the time ratio), the rocker's arms' x (the knives' strokes) and the edges' y (the overlap)."""
        return [
            f"links.{self.crank}.length",
            f"frame.points.{self.pivot}.x",
            *(f"links.{self.rocker}.points.{arm}.x" for arm in self.arms),
            *(f"links.{knife}.points.{edge}.y" for knife, edge in zip(self.knives, self.edges, strict=True)),
        ]

    @property
    def strokes(self) -> tuple[str, str]:
        """The metrics of the upper and the lower knife's strokes (``stroke:GUIDE``)."""
        return (f"stroke:{self.guides[0]}", f"stroke:{self.guides[1]}")


def shears_parts(data: Any) -> ShearsParts | str:
    """The :class:`ShearsParts` of ``data`` (a Spec, or a file's raw mapping), or the part it lacks, as a phrase
    ("process load with two tools (the knives)", "prismatic guide of "knife_lower" on the frame", ...)."""
    tools = next(
        (
            _get(load, "tools")
            for load in _items(_get(data, "loads"))
            if _get(load, "type") == "process" and _strings(_get(load, "tools"), 2, ".")
        ),
        None,
    )
    if tools is None:
        return "process load with two tools (the knives)"
    (upper, upper_edge), (lower, lower_edge) = (tool.split(".", 1) for tool in tools)
    joints = {name: j for name, j in _named(_get(data, "joints")) if _strings(_get(j, "links"), 2)}
    guides: list[str] = []
    arms: list[tuple[str, str]] = []
    for knife in (upper, lower):
        guide, arm = _between(joints, "prismatic", {FRAME, knife}), _arm(joints, knife)
        if guide is None:
            return f"prismatic guide of {quote(knife)} on the frame"
        if isinstance(arm, str):
            return arm
        guides.append(guide)
        arms.append(arm)
    (rocker, upper_arm), (other, lower_arm) = arms
    if rocker != other:
        return f"one link driving both knives' rods (they hang from {quote(rocker)} and {quote(other)})"
    drives = _get(data, "drives") if isinstance(_get(data, "drives"), list) else []
    drive = next((j for j in (_get(d, "joint") for d in drives) if isinstance(j, str) and j in joints), None)
    if drive is None:
        return "drive at a joint of the crank"
    crank = next(link for link in _get(joints[drive], "links") if link != FRAME)
    return ShearsParts(
        crank,
        _get(joints[drive], "point") or drive,
        rocker,
        (upper_arm, lower_arm),
        (upper, lower),
        (upper_edge, lower_edge),
        (guides[0], guides[1]),
    )


def _get(x: Any, key: str) -> Any:
    """``x``'s ``key``: an item of a raw mapping, an attribute of a Spec's model."""
    return x.get(key) if isinstance(x, dict) else getattr(x, key, None)


def _named(x: Any) -> list[tuple[str, Any]]:
    return list(x.items()) if isinstance(x, dict) else []


def _items(x: Any) -> list[Any]:
    return [v for _, v in _named(x)]


def _strings(x: Any, count: int, sep: str = "") -> bool:
    """Whether ``x`` is a list of ``count`` strings (each with ``sep`` in it, where given)."""
    return isinstance(x, list) and len(x) == count and all(isinstance(s, str) and sep in s for s in x)


def _between(joints: dict[str, Any], kind: str, links: set[str]) -> str | None:
    """The one joint of ``kind`` between exactly ``links``; None where there is not one."""
    found = [name for name, j in joints.items() if _get(j, "type") == kind and set(_get(j, "links")) == links]
    return found[0] if len(found) == 1 else None


def _arm(joints: dict[str, Any], knife: str) -> tuple[str, str] | str:
    """(rocker, point): the link and point that drive ``knife``'s rod (the rod: the link jointed to the knife but
    the frame), or what is missing."""
    revolute = [
        (name, _get(j, "links"), _get(j, "point")) for name, j in joints.items() if _get(j, "type") == "revolute"
    ]
    rods = [next(x for x in links if x != knife) for _, links, _ in revolute if knife in links and FRAME not in links]
    if len(rods) != 1:
        return f"one rod driving {quote(knife)}"
    ends = [
        (next(x for x in links if x != rods[0]), point or name)
        for name, links, point in revolute
        if rods[0] in links and knife not in links
    ]
    if len(ends) != 1:
        return f"one link driving the rod {quote(rods[0])}"
    return ends[0]
