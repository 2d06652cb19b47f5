"""``linkwork.bolt_speed``: the crank speed at which the foundation bolts start to be pulled (or carry a
given pull)."""

from __future__ import annotations

import math

import numpy as np

from linkwork.kinetostatics.forces import forces
from linkwork.limits import TURN_STEPS
from linkwork.structure.model import Mechanism


def bolt_speed(mech: Mechanism, pull: float = 0.0, *, steps: int = TURN_STEPS) -> float:
    """Uniform crank speed (rad/s) at which the largest pull on the bolts reaches ``pull`` (N), over
    ``steps`` equal steps of the turn.

    With the crank turning uniformly, every velocity is proportional to the
    speed and every acceleration to its square, so the vertical foundation
    force is ``F(phi) = G(phi) + omega^2 I(phi)``: ``G`` from the weights
    (computed at rest) and ``I`` from the inertia (the force at 1 rad/s less
    ``G``).  The pull reaches ``pull`` first at ``omega^2 = min (pull - G) / I``
    over the angles where ``I > 0``.  Returns ``inf`` if no speed does it,
    0 if the bolts carry that pull at rest already.
    """
    rest = forces(mech, steps=steps, speed=0.0).foundation[..., 1]
    one = forces(mech, steps=steps, speed=1.0).foundation[..., 1]
    inertia = one - rest
    if np.nanmax(rest) >= pull:
        return 0.0
    with np.errstate(divide="ignore", invalid="ignore"):
        need = np.where(inertia > 0, (pull - rest) / inertia, np.inf)
    best = float(np.nanmin(need))
    return math.sqrt(best) if math.isfinite(best) else math.inf
