"""The crank's main shaft on two bearings: the share of the crank's force each carries, and the shaft's bending.

The crank's pivot is a shaft that runs in two bearings a ``spacing`` ``s`` apart (between their middles).  The
force ``F`` of the crank's pivot acts in the crank's plane; as a beam on two supports:

- the crank midway between the bearings (the default where the file's ``sizing: shaft`` gives no ``overhang``;
  without ``sizing: shaft``, the bearings :data:`SPACING_IN_DIAMETERS` pin diameters apart):
  each bearing carries ``F / 2``, the largest bending moment is ``F s / 4``;
- the crank overhung by ``c`` outside the nearer bearing: it carries ``F (s + c) / s``, the farther one
  ``F c / s`` (against it), the largest bending moment ``F c`` at the nearer bearing.

The least solid shaft for the bending alone, ``d = (32 M / (pi sigma_allow))^(1/3)``; the driving torque's
torsion adds to it and is not counted here (the links' table sizes the crank itself).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any

from linkwork.sizing.common import Table
from linkwork.sizing.pairs import Pair
from linkwork.sizing.pin_shear import Pins

#: The spacing of the two bearings where the file gives none, in shaft diameters of the joint's pin or bush.
SPACING_IN_DIAMETERS = 3.0


@dataclass(frozen=True)
class Shaft:
    """The main shaft (SI): its joint, the bearings' spacing and the crank's overhang (None: midway), whether
    they came from the file, each bearing's share of the force, the peak force, the largest bending moment and
    the least solid diameter for it."""

    joint: str
    spacing: float
    overhang: float | None
    given: bool
    shares: tuple[float, float]
    force: float
    moment: float
    diameter: float

    def table(self) -> Table:
        rows = (
            ("bearings' spacing", self.spacing * 1e3, "mm"),
            (
                "crank's overhang outside bearing 1 (- : midway)",
                math.nan if self.overhang is None else self.overhang * 1e3,
                "mm",
            ),
            ("spacing and overhang from the file", "yes" if self.given else "no", ""),
            ("share of the force on bearing 1", self.shares[0], "1"),
            ("share of the force on bearing 2", self.shares[1], "1"),
            ("peak force of the crank's pivot", self.force / 1e3, "kN"),
            ("largest bending moment", self.moment / 1e3, "kN m"),
            ("least solid shaft for bending", self.diameter * 1e3, "mm"),
        )
        title = f"Main shaft of joint {self.joint} on two bearings ({self.joint}/1, {self.joint}/2)"
        return Table(title, ("quantity", "value", "unit"), rows, "shaft")

    def record(self) -> list[dict[str, Any]]:
        return self.table().record()


def shares(spacing: float, overhang: float | None) -> tuple[float, float]:
    """The share of the crank's force each bearing carries (see the module): midway ``(1/2, 1/2)``, overhung by
    ``c``: ``((s + c) / s, c / s)``."""
    if overhang is None:
        return 0.5, 0.5
    return (spacing + overhang) / spacing, overhang / spacing


def split(pairs: list[Pair], joint: str, factors: tuple[float, float]) -> list[Pair]:
    """``pairs`` with the main ``joint``'s pair replaced by its two bearings (``joint/1`` and ``joint/2``), each
    carrying its share of the force."""
    out = []
    for pair in pairs:
        if pair.label != joint:
            out.append(pair)
            continue
        for n, k in enumerate(factors, start=1):
            out.append(dataclasses.replace(pair, label=f"{joint}/{n}", force=pair.force * k, peak=pair.peak * k))
    return out


def main_shaft(pair: Pair, file_shaft: Any, diameter: float, pins: Pins, phi_force: float) -> Shaft:
    """The shaft of the crank's pivot ``pair`` (its peak force ``phi_force``, N): the file's ``sizing: shaft`` or
    the default (the crank midway, the bearings :data:`SPACING_IN_DIAMETERS` times ``diameter`` apart)."""
    given = file_shaft is not None
    s = float(file_shaft.spacing) if given else SPACING_IN_DIAMETERS * diameter
    c = None if not given or file_shaft.overhang is None else float(file_shaft.overhang)
    moment = phi_force * (s / 4 if c is None else c)
    d = (32 * moment / (math.pi * pins.bending_allowed)) ** (1 / 3) if math.isfinite(moment) else math.inf
    return Shaft(pair.label, s, c, given, shares(s, c), phi_force, moment, d)
