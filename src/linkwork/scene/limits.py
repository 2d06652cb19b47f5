"""The limit positions of the working member as a scene: the scheme at both extremes of its stroke (or swing)
and the angle theta between the crank's limit positions, marked at the crank's pivot.

At a limit position the output stands still; the crank turns by pi + theta from one to the other and by
pi - theta back, so the time ratio is K = (pi + theta) / (pi - theta).  Drawn: a ray from the pivot along the
crank at the low extreme and one against the crank at the high extreme (for a slider-crank, the lines O B1
and O B2 of the classical construction), the arc of theta between them and its value.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from linkwork.motion.analysis import output_range, working
from linkwork.motion.kinematic_analysis import kinematics
from linkwork.scene.geometry import bounds, text_size
from linkwork.scene.scheme import Label, SchemeScene, scheme_scene

if TYPE_CHECKING:
    from linkwork.motion.kinematic_analysis import Kinematics


@dataclass(frozen=True)
class LimitsScene:
    """The two limit positions and theta.

    Attributes
    ----------
    scheme : SchemeScene
        The scheme at its two samples: the working member's low extreme (0) and high extreme (1).
    member : str
        The working member (a slider's joint, a rocker's link).
    rays : ndarray, shape (2, 2, 2)
        The two lines of theta from the crank's pivot (global, m).
    arc : ndarray, shape (K, 2)
        The arc of theta between them.
    theta : float
        The angle between the crank's limit positions, rad: |pi - the crank's turn between them|.
    turned : float
        The crank's turn from the low extreme to the high one (rad, in its direction).
    label : Label
        ``theta = ...°`` beside the arc (``centre`` of shape (1, 2)).
    """

    scheme: SchemeScene
    member: str
    rays: np.ndarray
    arc: np.ndarray
    theta: float
    turned: float
    label: Label

    def extent(self) -> np.ndarray:
        """``[x0, y0, x1, y1]`` of everything drawn, m."""
        w, h = text_size(self.label.text, self.scheme.em)
        c = self.label.centre[0]
        return bounds(
            self.scheme.extent(paths=True)[None],
            self.rays.reshape(-1, 2),
            self.arc,
            np.array([c - [w / 2, h / 2], c + [w / 2, h / 2]]),
        )


def limits_scene(kin: Kinematics) -> LimitsScene | None:
    """The limit positions of the first working member (:func:`linkwork.motion.analysis.working`) of a whole
    turn ``kin``; None where the mechanism has no such member with two extremes, or no crank pin."""
    from linkwork.scene.positions import _crank_pin

    mech = kin.mechanism
    members = working(mech)
    pin = _crank_pin(mech)
    if not members or pin < 0 or kin.angles.ndim != 1:
        return None
    r = output_range(kin, members[0])
    low, high = float(np.ravel(r.at_low)[0]), float(np.ravel(r.at_high)[0])
    if not (math.isfinite(low) and math.isfinite(high)) or bool(np.ravel(r.turns)[0]):
        return None
    both = kinematics(mech, np.array([low, high]))
    scheme = scheme_scene(both, at=[0], cycle=kin)
    k = int(mech.drive_pair[0])
    pivot = next(int(p) for p in mech.pair_points[k] if p >= 0 and mech.point_link[p] == 0)
    pts = both.points()
    o = pts[0, pivot]
    u = [pts[i, pin] - o for i in (0, 1)]
    crank = float(np.hypot(*u[0]))
    a0, a1 = math.atan2(u[0][1], u[0][0]), math.atan2(-u[1][1], -u[1][0])
    sweep = (a1 - a0 + math.pi) % (2 * math.pi) - math.pi  # the shorter way round, signed
    reach = 2.2 * crank
    rays = np.array([[o, o + reach * np.array([math.cos(a), math.sin(a)])] for a in (a0, a1)])
    radius = 1.5 * crank
    t = a0 + sweep * np.linspace(0.0, 1.0, 33)
    arc = o + radius * np.column_stack([np.cos(t), np.sin(t)])
    theta = abs(sweep)
    text = f"θ = {math.degrees(theta):.2f}°"
    w, h = text_size(text, scheme.em)
    # beside the arc's end, outside the wedge (clear of both rays however narrow theta is)
    side = a1 + math.copysign(math.pi / 2, sweep if sweep else 1.0)
    out = np.array([math.cos(side), math.sin(side)])
    centre = arc[-1] + out * (0.5 * abs(out[0]) * w + 0.5 * abs(out[1]) * h + 0.5 * scheme.em)
    turned = float(np.ravel(r.rising)[0])
    return LimitsScene(scheme, members[0].name, rays, arc, theta, turned, Label(text, "position", 0, o, centre[None]))
