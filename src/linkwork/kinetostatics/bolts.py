"""What the foundation bolts carry: pull, push, shear (:mod:`linkwork.kinetostatics.bolt_lift`: the speed
at which they start to be pulled).

The machine stands on its foundation and is held down by bolts; friction
between the two is neglected, so the bolts take all of the horizontal force
(shear) and the part of the vertical force that lifts the machine (pull);
a downward vertical force presses the machine onto the foundation (push).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from linkwork.kinetostatics.peaks import Peak
from linkwork.units import turn_deg


@dataclass(frozen=True)
class Bolts:
    """Extremes of the foundation force over the cycle (of the first variant), refined between the samples
    (:meth:`linkwork.kinetostatics.Forces.bolts`).

    ``*_angle`` is the drive coordinate (rad) where the extreme occurs.
    ``pull`` is 0 where the machine never lifts.
    """

    shear: float
    shear_angle: float
    pull: float
    pull_angle: float
    push: float
    push_angle: float
    moment: float
    moment_angle: float

    def __str__(self) -> str:
        """The extremes as a person reads them, in N, N m and degrees (the crank's angle to the x axis,
        0 to 360, as :meth:`as_dict` gives it): ``print(f.bolts())``."""
        d = self.as_dict()
        units = {"shear": "N", "pull": "N", "push": "N", "moment": "N m"}
        return (
            "Bolts("
            + ", ".join(
                f"{k} {d[k]:.6g} {u} at {turn_deg(math.radians(d[k + '_angle_deg']))} deg" for k, u in units.items()
            )
            + "; crank angles to the x axis)"
        )

    def as_dict(self) -> dict[str, float]:
        out: dict[str, float] = {}
        for name in ("shear", "pull", "push", "moment"):
            out[name] = getattr(self, name)
            out[f"{name}_angle_deg"] = math.degrees(getattr(self, f"{name}_angle")) % 360
        return out


def bolt_loads(found: Peak, first: float) -> Bolts:
    """The bolt loads of the peaks ``(4,)`` of the shear ``|Fx|``, the upward force ``Fy``, the downward ``-Fy`` and
    the size of the moment (:meth:`linkwork.kinetostatics.Forces.bolts`): a pull or push that never occurs is 0, at
    the drive coordinate ``first`` (the first sample's)."""
    out = []
    for k, (value, at) in enumerate(zip(found.value.tolist(), found.at.tolist(), strict=True)):
        never = k in (1, 2) and not value > 0
        out += [0.0 if never else value, first if never or not math.isfinite(at) else at]
    return Bolts(*out)
