"""What the foundation bolts carry: pull, push, shear; the speed at which they start to be pulled.

The machine stands on its foundation and is held down by bolts; friction
between the two is neglected, so the bolts take all of the horizontal force
(shear) and the part of the vertical force that lifts the machine (pull);
a downward vertical force presses the machine onto the foundation (push).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np


@dataclass(frozen=True)
class Bolts:
    """Extremes of the foundation force over the cycle (of the first variant).

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

    def as_dict(self) -> dict[str, float]:
        out: dict[str, float] = {}
        for name in ("shear", "pull", "push", "moment"):
            out[name] = getattr(self, name)
            out[f"{name}_angle_deg"] = math.degrees(getattr(self, f"{name}_angle")) % 360
        return out


def bolt_loads(foundation: np.ndarray, angles: np.ndarray) -> Bolts:
    """Extremes of a foundation force ``(V, A, 3)`` (x, y up, moment) over the angles ``(A,)``."""
    f = foundation[0]
    out = []
    for values in (np.abs(f[:, 0]), np.maximum(f[:, 1], 0.0), np.maximum(-f[:, 1], 0.0), np.abs(f[:, 2])):
        i = int(np.nanargmax(values)) if np.isfinite(values).any() else 0
        out += [float(values[i]), float(angles[i])]
    return Bolts(*out)


def bolt_speed(mech: Any, pull: float = 0.0, steps: int = 720) -> float:
    """Uniform crank speed (rad/s) at which the largest pull on the bolts reaches ``pull`` (N).

    With the crank turning uniformly, every velocity is proportional to the
    speed and every acceleration to its square, so the vertical foundation
    force is ``F(phi) = G(phi) + omega^2 I(phi)``: ``G`` from the weights
    (computed at rest) and ``I`` from the inertia (the force at 1 rad/s less
    ``G``).  The pull reaches ``pull`` first at ``omega^2 = min (pull - G) / I``
    over the angles where ``I > 0``.  Returns ``inf`` if no speed does it,
    0 if the bolts carry that pull at rest already.
    """
    from linkwork.kinetostatics import forces
    from linkwork.resolve import mechanism_of

    mech = mechanism_of(mech, "bolt_speed")
    rest = forces(mech, steps=steps, speed=0.0).foundation[..., 1]
    one = forces(mech, steps=steps, speed=1.0).foundation[..., 1]
    inertia = one - rest
    if np.nanmax(rest) >= pull:
        return 0.0
    with np.errstate(divide="ignore", invalid="ignore"):
        need = np.where(inertia > 0, (pull - rest) / inertia, np.inf)
    best = float(np.nanmin(need))
    return math.sqrt(best) if math.isfinite(best) else math.inf
