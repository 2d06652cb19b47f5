"""The structure of a double-cut shears' file, read from the file: which link is the crank and where it is
pivoted, which link (the rocker) drives the two knives' rods and at which of its points, the two knives (the
tools of the process load, the upper first), their edges and their guides.  The synthesis edits the named
parameters these give (:attr:`ShearsParts.paths`) and measures the knives on those guides, whatever the file calls
them."""

from __future__ import annotations

from typing import Any, NamedTuple

from linkwork.errors import SynthesisError

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


def parts(spec: Any) -> ShearsParts:
    """The :class:`ShearsParts` of ``spec`` (a Spec of double-cut shears); raises :class:`SynthesisError` naming
    the part it lacks."""
    tools = next(
        (load.tools for load in (spec.loads or {}).values() if load.type == "process" and len(load.tools or ()) == 2),
        None,
    )
    if tools is None:
        raise SynthesisError("double-cut shears: the file has no process load with two tools (the knives)")
    (upper, upper_edge), (lower, lower_edge) = (tool.split(".", 1) for tool in tools)
    knives = (upper, lower)
    guides = tuple(_joint(spec, "prismatic", {FRAME, knife}, f"no prismatic guide of {knife!r}") for knife in knives)
    arms = [_arm(spec, knife) for knife in knives]
    if arms[0][0] != arms[1][0]:
        raise SynthesisError(f"double-cut shears: the knives' rods hang from {arms[0][0]!r} and {arms[1][0]!r}")
    drive = spec.drives[0].joint
    crank = next(link for link in spec.joints[drive].links if link != FRAME)
    return ShearsParts(
        crank,
        spec.joints[drive].point or drive,
        arms[0][0],
        (arms[0][1], arms[1][1]),
        knives,
        (upper_edge, lower_edge),
        (guides[0], guides[1]),
    )


def _joint(spec: Any, kind: str, links: set[str], missing: str) -> str:
    """The name of the joint of ``kind`` between exactly ``links``."""
    found = [name for name, j in spec.joints.items() if j.type == kind and set(j.links) == links]
    if len(found) != 1:
        raise SynthesisError(f"double-cut shears: {missing}")
    return found[0]


def _arm(spec: Any, knife: str) -> tuple[str, str]:
    """(rocker, point): the link and point that drive ``knife``'s rod (the rod: the link jointed to the knife)."""
    rods = [
        next(link for link in j.links if link != knife)
        for j in spec.joints.values()
        if j.type == "revolute" and knife in j.links and FRAME not in j.links
    ]
    if len(rods) != 1:
        raise SynthesisError(f"double-cut shears: no one rod driving {knife!r}")
    ends = [
        (next(link for link in j.links if link != rods[0]), j.point or name)
        for name, j in spec.joints.items()
        if j.type == "revolute" and rods[0] in j.links and knife not in j.links
    ]
    if len(ends) != 1:
        raise SynthesisError(f"double-cut shears: no one link driving the rod {rods[0]!r}")
    return ends[0]
