"""The sized parts against each other and the mechanism's geometry: what a designer checks before drawing them.

Each joint's pin is made to the diameter ``d`` that governs it (the joints' table: the larger of the pin's least
for strength and its plain bush's; the file's where it gives one), in an eye of outer diameter ``2 d`` (a wall of
``d / 2`` round the pin), the rule the blocks' masses use (:mod:`~linkwork.sizing.masses`).  Three rules follow,
each a row of the table with what the part has, what it needs and which size governs:

1. **The eyes fit their link**: two joints of one link are at least ``d1 + d2`` apart (their eyes' radii);
   nearer, the eyes overlap and the link cannot be made: the pins govern, and the fix is a longer link (the
   geometry) or smaller forces; a crank (the link the drive turns) whose eyes overlap is made as an eccentric on
   its shaft instead, whose rod's eye then encloses the shaft and the throw (``pins: an eccentric``): the rod's
   bush is larger than the joints' table sizes, which the warning says.
2. **A link no thinner than its pin**: a bar's section is at least as deep in the mechanism's plane as the
   largest pin it carries (the eye of ``2 d`` blends into a shank of at least ``d``): the depth of the least
   round bar for its stresses, or of the file's section (round and tube ``d``, rectangle and I ``h``).  Where
   the pin is the deeper, the pin governs the section to make: a least section is made to it (enforced; the
   links' table and the sized masses keep the section for the stresses), a section the file gives that is
   thinner does not fit.
3. **A block stays in its slot**: a block sliding along a moving link (a slotted lever) reaches half its length
   ``l / 2`` (the block rule's length) either side of its pin, whose travel along the slot the analysis
   measures; the slot runs along the link between the eyes of its joints at either end.  The block's farthest
   reach must be within the slot's far end and its nearest beyond the near end.

A row that does not fit is a warning of the sizing (``size`` prints it; the report's sizing section says it).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from linkwork.sizing.common import Table
from linkwork.sizing.links import Bars
from linkwork.structure.model import Mechanism, PairType

#: The eye's outer diameter over its pin's.
EYE = 2.0


@dataclass(frozen=True)
class Check:
    """One rule on one part (SI): what the part ``has`` and what it ``needs`` (m; it fits where has >= needs),
    and which size ``governs``."""

    part: str
    rule: str
    has: float
    needs: float
    governs: str
    enforced: bool = False  # the sizing makes the part to what it needs (a least section raised to its pin)

    @property
    def fits(self) -> bool:
        return self.enforced or not self.has < self.needs * (1 - 1e-9)

    @property
    def verdict(self) -> str:
        if not self.has < self.needs * (1 - 1e-9):
            return "yes"
        return "made to it" if self.enforced else "NO"

    def warning(self) -> str:
        """The sentence ``size`` prints for a part that does not fit."""
        return (
            f"{self.part}: {self.rule} {self.has * 1e3:.4g} mm, needs {self.needs * 1e3:.4g} mm "
            f"(governs: {self.governs})"
        )


@dataclass(frozen=True)
class Proportions:
    checks: tuple[Check, ...]

    def warnings(self) -> list[str]:
        return [c.warning() for c in self.checks if not c.fits]

    def table(self) -> Table:
        return Table(
            f"Proportions: eyes of {EYE:g} d round each pin, shanks at least d deep, blocks within their slots",
            ("part", "rule", "has [mm]", "needs [mm]", "governs", "fits"),
            tuple((c.part, c.rule, c.has * 1e3, c.needs * 1e3, c.governs, c.verdict) for c in self.checks),
            "proportions",
        )

    def record(self) -> dict[str, Any]:
        return {"proportions": self.table().record(), "warnings": self.warnings()}


def pair_label(mech: Mechanism, k: int) -> str:
    """The sizing's name of pair ``k``: its joint's, ``joint:link`` for each pair of a compound hinge."""
    joint = str(mech.pair_joint[k])
    if list(mech.pair_joint).count(joint) > 1:
        return f"{joint}:{mech.link_names[int(mech.pair_links[k, 1])]}"
    return joint


def proportions(
    mech: Mechanism, kin: Any, made: dict[str, float], bars: Bars, depths: dict[str, float], blocks: dict[str, float]
) -> Proportions:
    """The checks of the module for ``mech`` over the cycle ``kin`` (its kinematics): ``made`` the diameter (m)
    each joint's pin is made to (by the sizing's label), ``bars`` the links as bars, ``depths`` each bar's section
    depth in the plane (m), ``blocks`` each block's length along its guide (m)."""
    checks: list[Check] = []
    cranks = {int(i) for k in mech.drive_pair for i in mech.pair_links[int(k)] if int(i) != 0}
    for bar in bars.bars:
        link = mech.link_names.index(bar.link)
        eyes = _eyes(mech, link, made)
        for (p, d1, n1), (q, d2, n2) in _pairs_of(eyes):
            gap = float(np.hypot(*(mech.point_local[p] - mech.point_local[q])))
            by = "pins: an eccentric" if link in cranks and gap < d1 + d2 else "pins"
            checks.append(Check(bar.link, f"eyes {n1}-{n2} apart", gap, d1 + d2, by))
        if eyes and bar.link in depths:
            pin = max(d for _, d, _ in eyes)
            depth = depths[bar.link]
            by = "pin" if pin > depth else "stress"
            checks.append(Check(bar.link, "shank depth", depth, pin, by, enforced=not bar.given))
    checks += _slots(mech, kin, made, blocks)
    return Proportions(tuple(checks))


def _eyes(mech: Mechanism, link: int, made: dict[str, float]) -> list[tuple[int, float, str]]:
    """(point, pin diameter, joint) of each revolute joint of ``link`` whose pin is sized (the largest of a
    compound hinge's pairs at one point)."""
    out: dict[int, tuple[int, float, str]] = {}
    for k in range(mech.n_pairs):
        if mech.pair_type[k] != PairType.REVOLUTE or link not in mech.pair_links[k]:
            continue
        side = 0 if int(mech.pair_links[k, 0]) == link else 1
        label = pair_label(mech, k)
        d = max((v for key, v in made.items() if key == label or key.startswith(label + "/")), default=math.nan)
        p = int(mech.pair_points[k, side])
        if math.isfinite(d) and p >= 0 and d > out.get(p, (p, 0.0, ""))[1]:
            out[p] = (p, d, str(mech.pair_joint[k]))
    return list(out.values())


def _pairs_of(eyes: list) -> list:
    return [(a, b) for i, a in enumerate(eyes) for b in eyes[i + 1 :] if a[0] != b[0]]


def _slots(mech: Mechanism, kin: Any, made: dict[str, float], blocks: dict[str, float]) -> list[Check]:
    """The far and near ends of each slot (a sliding pair on a moving link) against its block's reach."""
    out = []
    for k in range(mech.n_pairs):
        guide, block = (int(i) for i in mech.pair_links[k])
        name = mech.link_names[block]
        if mech.pair_type[k] != PairType.PRISMATIC or guide == 0 or name not in blocks:
            continue
        axis = np.asarray(mech.pair_axis[k], dtype=float)
        point = mech.point_names[int(mech.pair_points[k, 1])]
        along = _along(kin, point, guide, axis)
        ends = [(float(mech.point_local[p] @ axis), d) for p, d, _ in _eyes(mech, guide, made)]
        if len(ends) < 1 or not np.isfinite(along).any():
            continue
        half = blocks[name] / 2
        far, near = float(np.nanmax(along)), float(np.nanmin(along))
        top = max(ends, key=lambda e: e[0])
        low = min(ends, key=lambda e: e[0])
        where = f"{name} in {mech.link_names[guide]}"
        if top[0] > far:
            out.append(Check(where, "slot far end", top[0] - top[1], far + half, "block length"))
        if low[0] < near:
            out.append(Check(where, "slot near end", near - half, low[0] + low[1], "block length"))
    return out


def _along(kin: Any, point: str, link: int, axis: np.ndarray) -> np.ndarray:
    """The coordinate of ``point`` along ``axis`` (local to ``link``) in ``link``'s own frame, over the cycle."""
    pos = np.reshape(kin.position(point), (-1, 2))
    pose = np.reshape(kin.pose[0][:, link], (-1, 3))
    rel = pos - pose[:, :2]
    c, s = np.cos(pose[:, 2]), np.sin(pose[:, 2])
    local = np.stack([c * rel[:, 0] + s * rel[:, 1], -s * rel[:, 0] + c * rel[:, 1]], -1)
    return local @ axis
