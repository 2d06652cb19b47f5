"""One impact of the striker on a tool that may move: the impact map of the working cycle.

The machine turns on its crank (reduced inertia ``J`` of the mechanism in the pose, ``J_d`` of the
drive on the crank shaft); the tool, of mass ``m_t``, moves along the normal ``n`` of its face.  With
the normal impulse ``P`` on the striker,

    (J + J_d) (psi'_+ - psi'_-) = G_phi P,   m_t (u'_+ - u'_-) = P,   g'_+ = -R g'_-
    =>  P = -(1 + R) g'_- / (G_n G_phi / (J + J_d) + 1 / m_t)

(``g`` the gap between striker and tool, ``G_n = dK/dpsi . n``, ``G_phi = dK/dpsi . (n + phi t)``,
``phi = -f sgn(sliding)``: Newton's restitution on the normal closing speed, the striker sliding
through the impact), which for a tool that cannot move (``m_t`` infinite) and no drive inertia is
exactly :func:`~linkwork.impulse.impact`.  The impulsive reactions of every pair follow as there; the
drive's row gives the impulse of the drive on the crank, ``-J_d (psi'_+ - psi'_-)`` in the turning
direction.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from linkwork.errors import LinkworkError, SlidingReversal
from linkwork.impulse.mechanism import impulsive_reactions, joint_links, pose_inertia
from linkwork.kinetostatics.reaction_forces import Forces
from linkwork.motion import kinematics
from linkwork.structure.model import Mechanism
from linkwork.units import turn_deg


@dataclass(frozen=True)
class Strike:
    """One impact of the striker on the tool in one pose (:func:`strike`); vectors in global axes.

    Attributes
    ----------
    angle : float
        The crank's drive angle, rad.
    closing_speed : float
        ``g'_-``: the rate of the gap before, m/s (negative: closing).
    crank_speed_before, crank_speed_after : float
        Turning speed of the crank, rad/s, positive in the drive's direction.
    tool_speed_before, tool_speed_after : float
        The tool's speed into the work, m/s.
    omega_before, omega_after : float
        The striking link's angular speed, rad/s, counter-clockwise positive.
    striker_speed : float
        Magnitude of the striker's velocity before, m/s.
    impulse : ndarray (2,)
        Impulse of the tool on the striker, N s.
    phi : float
        Tangential over normal impulse, ``-f sgn(sliding)``.
    inertia : float
        Reduced inertia of mechanism and drive on the crank in the pose, kg m^2.
    energy_lost : float
        J.
    joints, joint_links : dict
        For each joint, the impulse (x, y) its first-named link exerts on the second (N s), and those links.
    drive_impulse : float
        Impulse of the drive on the crank, N m s, counter-clockwise positive.
    forces : Forces
        The impulses as a :class:`~linkwork.kinetostatics.Forces` (``pair_force`` in N s).
    """

    angle: float
    closing_speed: float
    crank_speed_before: float
    crank_speed_after: float
    tool_speed_before: float
    tool_speed_after: float
    omega_before: float
    omega_after: float
    striker_speed: float
    impulse: np.ndarray
    phi: float
    inertia: float
    energy_lost: float
    joints: dict[str, np.ndarray]
    joint_links: dict[str, tuple[str, str]]
    drive_impulse: float
    forces: Forces


class _Approach(NamedTuple):
    """How the striker meets the tool: ``dK/dpsi`` along the face's normal and along the face (m/rad),
    the crank's turning speed (rad/s), the gap's rate (m/s) and ``|dK/dpsi|`` (m/rad)."""

    normal: float
    along: float
    crank_speed: float
    closing: float
    gain: float


class _Jump(NamedTuple):
    """The impact's outcome: friction over normal impulse, the normal impulse ``P`` (N s) and the jump
    of the crank's turning speed (rad/s)."""

    phi: float
    normal_impulse: float
    crank_speed: float


def strike(
    mech: Mechanism,
    *,
    at: str,
    normal: npt.ArrayLike,
    angle: float,
    crank_speed: float,
    restitution: float,
    friction: float = 0.0,
    tool_mass: float = math.inf,
    tool_speed: float = 0.0,
    drive_inertia: float = 0.0,
    link: str | None = None,
) -> Strike:
    """The impact of the point ``at`` on the tool's face (outward ``normal``) in the pose of the drive
    angle ``angle``, the crank turning at ``crank_speed`` (rad/s, in the drive's direction) with
    ``drive_inertia`` (kg m^2) on its shaft, the tool of ``tool_mass`` (infinite: it cannot move)
    moving at ``tool_speed`` into the work; ``restitution`` on the normal closing speed, the striker
    sliding through the impact with ``friction``; ``link``: whose angular speed to report (default:
    the striking link).

    Raises
    ------
    LinkworkError
        If the mechanism does not assemble, the striker does not close on the tool, or the friction
        would lock the blow.
    SlidingReversal
        (a LinkworkError) With friction, if the blow would turn the crank back: in a chain of one degree
        of freedom the sliding of K is ``(dK/dpsi . t) psi'``, so it would reverse within the impact,
        which this map (one friction sign throughout) does not model.
    """
    if not (0 <= restitution <= 1 and friction >= 0 and tool_mass > 0):
        raise LinkworkError("expected 0 <= R <= 1, friction >= 0 and a positive tool mass")
    sign = -1.0 if mech.drive_speed[0] < 0 else 1.0
    n = np.asarray(normal, dtype=float)
    n = n / np.linalg.norm(n)
    tang = np.array([n[1], -n[0]])
    kin = kinematics(mech, np.array([angle]), speed=sign)
    if not bool(np.all(kin.valid)):
        raise LinkworkError(f"the mechanism does not assemble at {turn_deg(angle, 3):.3f} deg")
    p = kin.point_index(at)
    striker = int(mech.point_link[p])
    link = link if link is not None else mech.link_names[striker]
    pos, g, _ = kin.motion_of(mech.point_names[p])
    pos, g = pos[0, 0], g[0, 0]
    jt = pose_inertia(kin) + drive_inertia
    w = float(crank_speed)
    sn, st = float(g @ n), float(g @ tang)
    approach = _Approach(sn, st, w, sn * w + tool_speed, float(np.linalg.norm(g)))
    if not approach.closing < 0:
        raise LinkworkError(f'"{at}" does not close on the tool: the gap opens at {approach.closing:.6g} m/s')
    inv_mass = 0.0 if math.isinf(tool_mass) else 1.0 / tool_mass
    phi, big_p, dw = _jump(approach, jt, inv_mass, restitution, friction, angle)
    v_after = tool_speed + big_p * inv_mass
    impulse = big_p * (n + phi * tang)
    forces, lam, joints = impulsive_reactions(kin, striker, pos, impulse, dw)
    gain = float(kin.omega(link)[0])
    lost = 0.5 * jt * (w * w - (w + dw) ** 2)
    if inv_mass:
        lost += 0.5 * tool_mass * (tool_speed**2 - v_after**2)
    return Strike(
        angle,
        approach.closing,
        w,
        w + dw,
        tool_speed,
        v_after,
        gain * w,
        gain * (w + dw),
        approach.gain * abs(w),
        impulse,
        phi,
        jt,
        lost,
        joints,
        joint_links(mech),
        float(lam[0, 0, 2 * mech.n_pairs]),
        forces,
    )


def _jump(approach: _Approach, jt: float, inv_mass: float, restitution: float, friction: float, angle: float) -> _Jump:
    """The impact's normal impulse and the crank's jump, with the inertia ``jt`` of the machine on
    the crank and ``inv_mass`` the tool's inverse mass; refused where friction locks the blow or
    the crank would turn back with friction (the drive angle ``angle`` for the messages)."""
    sn, st, w = approach.normal, approach.along, approach.crank_speed
    sliding = st * w
    if abs(sliding) > 1e-12 * abs(w) * approach.gain:
        phi = -friction * math.copysign(1.0, sliding)
    else:
        phi = friction
    gphi = sn + phi * st
    if not sn * gphi > 0:
        raise LinkworkError(
            f"friction f = {friction:g} locks the blow at {turn_deg(angle, 3):.3f} deg: the impulse "
            "would pull the striker into the tool"
        )
    big_p = -(1.0 + restitution) * approach.closing / (sn * gphi / jt + inv_mass)
    dw = gphi * big_p / jt
    # the sliding of K on the tool (which moves along n only) is st psi': it turns where the crank does
    if friction > 0 and st != 0.0 and w * (w + dw) < 0 and abs(w + dw) > 1e-9 * abs(w):
        raise SlidingReversal(
            f"the blow at {turn_deg(angle, 3):.3f} deg would throw the crank back (from {w:.6g} to "
            f"{w + dw:.6g} rad/s), so the striker's sliding on the tool would reverse within the impact: the "
            f"impact map assumes it slides one way throughout (friction f = {friction:g})"
        )
    return _Jump(phi, big_p, dw)
