"""Working cycle of a percussion mechanism of variable structure: blows, rebounds, contact.

The machine: a one-degree-of-freedom mechanism (turning angle ``psi`` of the crank, reduced
inertia ``J(psi)``, reduced load moment ``M(psi)`` of gravity and the file's loads) driven by a
motor through a gear with a flywheel (:class:`~linkwork.machine.Drive`: moment ``M_d(psi')``,
constant inertia ``J_d``), and the tool, a body of mass ``m_t`` that slides along the normal ``n``
of its face.  The feed presses the tool with a constant force ``F`` towards the striker onto its
seat, where its face passes through the striking point K in the pose of the file's blow; the work
resists its motion into it with a constant force ``F_w`` (a rigid-plastic material: no force
when the tool comes back).  ``u`` is the tool's travel into the work from its seat, ``s(psi)`` the
height of K above the seated face along ``n``; the gap is ``g = s(psi) + u``.

A rigid crank-rocker cannot stop at the tool (it would jam the crank), so the tool gives way and
the structure of the machine changes with the contact:

* ``flight``: the striker free, the tool on its seat: one degree of freedom (``psi``);
* ``apart``: after a blow, striker and tool move apart: two degrees of freedom (``psi``, ``u``);
  the tool flies under ``-(F + F_w)`` into the work, ``-F`` back, and stops on its seat
  (a plastic stop: its kinetic energy there is lost);
* ``contact``: the striker pushes the tool, ``g = 0``: one degree of freedom again, with the
  contact force ``lambda >= 0`` as the constraint's multiplier; the phase ends where
  ``lambda`` falls to zero (separation), where the tool stops in the work and the force the
  contact would need there pulls (the work's resistance lets go), or on the seat.

Striker and tool may meet again after a blow (rebounds, with the same map); a rebound slower than
1e-5 of the striker's speeds ends the chatter as a plastic impact, after which they move together
if the contact force is compressive.

Between events the motion is the energy-exact equation
``(J + J_d) psi'' + J' psi'^2 / 2 = M + M_d + G_phi lambda`` (``G_phi = (dK/dpsi) . (n + phi t)``,
``phi = -f sgn(sliding)``) with scipy's ``solve_ivp`` (DOP853) and its events.  ``J``, ``M``,
``s`` and the sliding transfer function are periodic cubic splines through their exact values on
a grid of the turn (``steps``); the blows use the exact kinematics of their pose.

The blow (``g = 0`` closing) is the impact map of :func:`~linkwork.impulse.impact`, generalised
to a tool that moves: with the normal impulse ``P`` on the striker,

    (J + J_d) (psi'_+ - psi'_-) = G_phi P,   m_t (u'_+ - u'_-) = P,   g'_+ = -R g'_-
    =>  P = -(1 + R) g'_- / (G_n G_phi / (J + J_d) + 1 / m_t)

(``G_n = ds/dpsi``, Newton's restitution on the normal closing speed, the striker sliding through
the impact), which for a tool that cannot move (``m_t`` infinite) and no drive inertia is exactly
:func:`~linkwork.impulse.impact`.  The impulsive reactions of every pair follow as there; the
drive's row gives the impulse of the drive on the crank, ``-J_d (psi'_+ - psi'_-)`` in the
turning direction.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from linkwork.errors import LinkworkError, SlidingReversal
from linkwork.machine.simulate import PeriodicSplines

FLIGHT, APART, CONTACT = "flight", "apart", "contact"
#: Degrees of freedom of the machine (mechanism and tool) in each phase.
FREEDOM = {FLIGHT: 1, APART: 2, CONTACT: 1}


@dataclass(frozen=True)
class Tool:
    """The tool: ``mass`` (kg), the ``feed`` force pressing it towards the striker onto its seat
    (N, positive: it brings the tool back) and the work's ``resistance`` to its motion into it (N)."""

    mass: float
    feed: float
    resistance: float = 0.0

    def __post_init__(self) -> None:
        if not self.mass > 0:
            raise LinkworkError(f"tool: the mass must be positive, got {self.mass}")
        if not self.feed > 0:
            raise LinkworkError(f"tool: the feed force must be positive (it returns the tool), got {self.feed}")
        if not self.resistance >= 0:
            raise LinkworkError(f"tool: the work's resistance must not be negative, got {self.resistance}")


@dataclass(frozen=True)
class Blow:
    """One blow of the striker on the tool at rest on its seat, and what followed until the next.

    Speeds of the crank are its turning speed (rad/s, positive in the drive's direction); vectors
    in global axes.

    Attributes
    ----------
    time : float
        s from the start of the run.
    psi : float
        Turning angle of the crank from the assembly angle, rad (growing over the run).
    angle : float
        The crank's drive angle in the pose of the blow, rad.
    crank_speed_before, crank_speed_after : float
    omega_before, omega_after : float
        The striking link's angular speed, rad/s, counter-clockwise positive.
    impact_speed : float
        Speed of the striker towards the tool's face along its normal, m/s.
    striker_speed : float
        Magnitude of the striker's velocity before the blow, m/s.
    tool_speed : float
        The tool's speed into the work after the blow, m/s.
    impulse : ndarray (2,)
        Impulse of the tool on the striker, N s.
    joints : dict
        For each joint, the impulse (x, y) its first-named link exerts on the second, N s.
    joint_links : dict
        For each joint, its (first, second) link names.
    drive_impulse : float
        Impulse of the drive (motor, gear, flywheel) on the crank, N m s, counter-clockwise positive.
    energy_before : float
        Kinetic energy of the machine (mechanism and drive) before the blow, J.
    energy_lost : float
        Kinetic energy lost in the blow (machine and tool), J.
    energy_to_tool : float
        Kinetic energy the blow gives the tool, J: what it carries into the work.
    rebounds : int
        Further impacts of striker and tool before the tool is back on its seat.
    rebound_loss : float
        Kinetic energy lost in them, J.
    work_on_work : float
        Work done on the work (its resistance times the tool's travel into it) until the next blow, J.
    penetration : float
        The tool's deepest travel into the work after this blow, m.
    """

    time: float
    psi: float
    angle: float
    crank_speed_before: float
    crank_speed_after: float
    omega_before: float
    omega_after: float
    impact_speed: float
    striker_speed: float
    tool_speed: float
    impulse: np.ndarray
    joints: dict[str, np.ndarray]
    joint_links: dict[str, tuple[str, str]]
    drive_impulse: float
    energy_before: float
    energy_lost: float
    energy_to_tool: float
    rebounds: int = 0
    rebound_loss: float = 0.0
    work_on_work: float = 0.0
    penetration: float = 0.0


@dataclass(frozen=True)
class Phase:
    """A stretch of motion of one structure: ``kind`` (``flight``, ``apart``, ``contact``), its
    start and end times (s) and turning angles (rad)."""

    kind: str
    start: float
    end: float
    psi_start: float
    psi_end: float

    @property
    def duration(self) -> float:
        return self.end - self.start

    @property
    def freedom(self) -> int:
        """Degrees of freedom of machine and tool in this phase."""
        return FREEDOM[self.kind]


@dataclass(frozen=True)
class ContactLoads:
    """Forces while striker and tool move together (the contact phases of the last cycle), at the
    samples of those phases: from the contact force, gravity and the inertia of every link at the
    crank's actual speed and acceleration.

    Attributes
    ----------
    t : ndarray (k,)
        Time from the last blow, s.
    force : ndarray (k,)
        The contact force, N, along the face's normal.
    phi : ndarray (k,)
        Friction force over contact force (``-f sgn(sliding)``): the tool's force on the striker is
        ``force (n + phi t)``.
    joints : dict
        For each joint, the force (k, 2) its first-named link exerts on the second, N.
    joint_links : dict
        For each joint, its (first, second) link names.
    """

    t: np.ndarray
    force: np.ndarray
    phi: np.ndarray
    joints: dict[str, np.ndarray]
    joint_links: dict[str, tuple[str, str]]

    def peak(self, joint: str) -> tuple[float, np.ndarray]:
        """Time (s from the blow) and force (2,) of the joint's largest force; NaN without contact."""
        if len(self.t) == 0:
            return math.nan, np.full(2, np.nan)
        f = self.joints[joint]
        i = int(np.argmax(np.hypot(f[:, 0], f[:, 1])))
        return float(self.t[i]), f[i]


@dataclass(frozen=True)
class WorkingCycle:
    """The run of :func:`simulate_blows`.

    Attributes
    ----------
    blows : tuple of Blow
        Every blow on the seated tool, each with what followed until the next.
    phases : tuple of Phase
        The phases of the whole run, in order.
    period : float
        Time from the last recorded blow to the next (where the run ends), s.
    steady : bool
        Whether the run reached its steady cycle.
    t, psi, omega, u, v, force, mode : ndarray (N,)
        Samples at the solver's steps: time (s), turning angle (rad), crank speed (rad/s), the
        tool's travel into the work (m) and its speed (m/s), the contact force (N, NaN outside
        contact) and the phase (index into ``("flight", "apart", "contact")``).
    energy : dict
        The run's ledger, J: ``motor`` (work of the motor at its own shaft), ``gear`` (lost in the
        gear), ``drive`` (work of the drive on the crank: ``motor - gear``), ``loads`` (work done
        on the machine), ``kinetic`` (change of the kinetic energy of machine and tool), ``feed``
        (change of the feed's potential ``F u``), ``blows``, ``rebounds``, ``seat`` (kinetic
        energy lost in impacts and on the seat), ``work`` (done on the work), ``friction`` (lost
        sliding in contact phases).
    cycle_energy : dict
        The same over the last cycle, from the last blow to the next.
    tool : Tool
    contact : ContactLoads
        The loads of the pairs while striker and tool moved together in the last cycle.
    """

    blows: tuple[Blow, ...]
    phases: tuple[Phase, ...]
    period: float
    steady: bool
    t: np.ndarray
    psi: np.ndarray
    omega: np.ndarray
    u: np.ndarray
    v: np.ndarray
    force: np.ndarray
    mode: np.ndarray
    energy: dict[str, float]
    cycle_energy: dict[str, float]
    tool: Tool
    contact: ContactLoads

    @property
    def blows_per_minute(self) -> float:
        """Of the steady cycle: 60 over the time between the last two blows."""
        return 60.0 / self.period

    @property
    def last(self) -> Blow:
        return self.blows[-1]

    def cycle_phases(self) -> tuple[Phase, ...]:
        """The phases of the last cycle, from the last blow to the next."""
        start = self.blows[-1].time
        return tuple(p for p in self.phases if p.start >= start - 1e-12)

    @property
    def mean_power(self) -> float:
        """Mean power of the motor at its shaft over the last cycle, W (to compare with its rating)."""
        return self.cycle_energy["motor"] / self.period

    @property
    def drive_power(self) -> float:
        """Mean power the drive gives the crank over the last cycle (after the gear's loss), W."""
        return self.cycle_energy["drive"] / self.period

    @property
    def balance(self) -> float:
        """Motor and load work less everything it went into (the gear's loss included) over the run,
        J: zero up to the integrator's error."""
        e = self.energy
        spent = e["kinetic"] + e["feed"] + e["blows"] + e["rebounds"] + e["seat"] + e["work"] + e["friction"]
        return e["motor"] - e["gear"] + e["loads"] - spent


def _heading(value: float, rate: float, scale: float) -> float:
    """The sign a quantity is taking: its own, or its rate's where it is zero (to rounding)."""
    if abs(value) > 1e-12 * max(abs(scale), 1.0):
        return math.copysign(1.0, value)
    return math.copysign(1.0, rate)


class _Free:
    """The tool flying free from ``(t0, u0, v0)``: a parabola into the work, another back."""

    def __init__(self, t0: float, u0: float, v0: float, tool: Tool) -> None:
        self.t0, self.u0, self.v0 = t0, u0, v0
        self.a_in = -(tool.feed + tool.resistance) / tool.mass
        self.a_out = -tool.feed / tool.mass
        if v0 > 0:
            self.t_top = t0 + v0 / -self.a_in
            self.u_top = u0 + v0 * v0 / (2 * -self.a_in)
        else:
            self.t_top, self.u_top = t0, u0
        self.resistance = tool.resistance
        # on the seat (u = 0) coming back
        if v0 > 0 or u0 > 0:
            if v0 > 0:
                self.t_seat = self.t_top + math.sqrt(2 * self.u_top / -self.a_out)
            else:
                a = 0.5 * self.a_out
                self.t_seat = t0 + (-v0 - math.sqrt(v0 * v0 - 4 * a * u0)) / (2 * a)
        else:
            self.t_seat = t0

    def state(self, t: float) -> tuple[float, float]:
        if t <= self.t_top and self.v0 > 0:
            d = t - self.t0
            return self.u0 + self.v0 * d + 0.5 * self.a_in * d * d, self.v0 + self.a_in * d
        if self.v0 > 0:
            d = t - self.t_top
            return self.u_top + 0.5 * self.a_out * d * d, self.a_out * d
        d = t - self.t0
        return self.u0 + self.v0 * d + 0.5 * self.a_out * d * d, self.v0 + self.a_out * d

    def work(self, t: float) -> float:
        """Work done on the work from ``t0`` to ``t``."""
        if self.v0 <= 0:
            return 0.0
        return self.resistance * (self.state(min(t, self.t_top))[0] - self.u0)


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
    forces: Any


def strike(
    mech: Any,
    *,
    at: str,
    normal: Any,
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
    from linkwork.impulse.mechanism import impulsive_reactions, pose_inertia
    from linkwork.motion import kinematics

    if not (0 <= restitution <= 1 and friction >= 0 and tool_mass > 0):
        raise LinkworkError("expected 0 <= R <= 1, friction >= 0 and a positive tool mass")
    sign = -1.0 if mech.drive_speed[0] < 0 else 1.0
    n = np.asarray(normal, dtype=float)
    n = n / np.linalg.norm(n)
    tang = np.array([n[1], -n[0]])
    kin = kinematics(mech, np.array([angle]), speed=sign)
    if not bool(np.all(kin.valid)):
        raise LinkworkError(f"the mechanism does not assemble at {math.degrees(angle) % 360:.3f} deg")
    p = kin.point_index(at)
    striker = int(mech.point_link[p])
    link = link if link is not None else mech.link_names[striker]
    pos, g, _ = kin._point(mech.point_names[p])
    pos, g = pos[0, 0], g[0, 0]
    jt = pose_inertia(kin) + drive_inertia
    w = float(crank_speed)
    sn, st = float(g @ n), float(g @ tang)
    closing = sn * w + tool_speed
    if not closing < 0:
        raise LinkworkError(f'"{at}" does not close on the tool: the gap opens at {closing:.6g} m/s')
    sliding = st * w
    if abs(sliding) > 1e-12 * abs(w) * float(np.linalg.norm(g)):
        phi = -friction * math.copysign(1.0, sliding)
    else:
        phi = friction
    gphi = sn + phi * st
    if not sn * gphi > 0:
        raise LinkworkError(
            f"friction f = {friction:g} locks the blow at {math.degrees(angle) % 360:.3f} deg: the impulse "
            "would pull the striker into the tool"
        )
    inv_mass = 0.0 if math.isinf(tool_mass) else 1.0 / tool_mass
    big_p = -(1.0 + restitution) * closing / (sn * gphi / jt + inv_mass)
    dw = gphi * big_p / jt
    # the sliding of K on the tool (which moves along n only) is st psi': it turns where the crank does
    if friction > 0 and st != 0.0 and w * (w + dw) < 0 and abs(w + dw) > 1e-9 * abs(w):
        raise SlidingReversal(
            f"the blow at {math.degrees(angle) % 360:.3f} deg would throw the crank back (from {w:.6g} to "
            f"{w + dw:.6g} rad/s), so the striker's sliding on the tool would reverse within the impact: the "
            f"impact map assumes it slides one way throughout (friction f = {friction:g})"
        )
    v_after = tool_speed + big_p * inv_mass
    impulse = big_p * (n + phi * tang)
    forces, lam, joints = impulsive_reactions(kin, striker, pos, impulse, dw)
    links = {
        name: (mech.link_names[int(mech.pair_members[k, 0])], mech.link_names[int(mech.pair_members[k, 1])])
        for name, k in mech.first_pairs().items()
    }
    gain = float(kin.omega(link)[0])
    lost = 0.5 * jt * (w * w - (w + dw) ** 2)
    if inv_mass:
        lost += 0.5 * tool_mass * (tool_speed**2 - v_after**2)
    return Strike(
        angle, closing, w, w + dw, tool_speed, v_after, gain * w, gain * (w + dw), float(np.linalg.norm(g)) * abs(w),
        impulse, phi, jt, lost, joints, links, float(lam[0, 0, 2 * mech.n_pairs]), forces,
    )  # fmt: skip


def simulate_blows(
    mech: Any,
    drive: Any = None,
    *,
    tool: Tool | None = None,
    at: str | None = None,
    normal: Any = None,
    restitution: float | None = None,
    friction: float | None = None,
    link: str | None = None,
    omega0: float | None = None,
    blows: int = 200,
    steps: int = 3600,
    tol: float = 1e-6,
    rtol: float = 1e-10,
) -> WorkingCycle:
    """Run the percussion machine from ``omega0`` until its steady cycle (``blows`` at the most).

    Parameters
    ----------
    mech : Mechanism
        One crank; its file's ``impact:`` section gives the defaults of ``at``, ``normal``
        (a vector, or the angle of the file), ``restitution``, ``friction``, ``link`` and ``tool``
        (its ``tool:``); the tool's face on its seat passes through ``at`` in the assembly pose.
    drive : Drive, optional
        Motor, gear and flywheel (default: the file's ``machine:``).
    omega0 : float, optional
        Crank speed at the start, rad/s (default: the file's drive speed); the run starts where
        the striker is farthest from the tool.
    blows : int
        At most this many blows.
    tol : float
        The cycle is steady when two blow-to-blow periods in a row and the crank speeds before
        the blows agree within ``tol`` (relative).
    rtol : float
        Of the integrator (DOP853).

    Raises
    ------
    LinkworkError
        Without a drive or a tool; if the striker never reaches the tool, the crank stops (also when
        an impact throws it back, or stops it dead), or friction would lock the blow.
    """
    from scipy.integrate import solve_ivp

    from linkwork.impulse.mechanism import blow_setup, impulsive_reactions
    from linkwork.kinetostatics import Forces
    from linkwork.kinetostatics.reactions import inertia_and_gravity, solve_reactions
    from linkwork.machine import reduced
    from linkwork.motion import kinematics
    blow_spec = mech.blow
    if drive is None:
        drive = mech.machine
    if drive is None:
        raise LinkworkError('the working cycle needs a drive: give a "machine:" section (motor, gear, flywheel)')
    if tool is None and blow_spec is not None and blow_spec.tool is not None:
        t_spec = blow_spec.tool
        tool = Tool(t_spec.mass, t_spec.feed, t_spec.resistance)
    if tool is None:
        raise LinkworkError('the working cycle needs the tool: give "tool:" (mass, feed, resistance) in "impact:"')
    setup = blow_setup(
        mech, at=at, normal=normal, restitution=restitution, friction=friction, link=link, need_speed=False
    )
    at, n, restitution, friction, link = setup.at, setup.normal, setup.restitution, setup.friction, setup.link
    if blows < 3:
        raise LinkworkError(f"blows: expected at least 3 (a steady cycle is two periods alike), got {blows}")
    tang = np.array([n[1], -n[0]])
    red = reduced(mech, steps)
    sign = -1.0 if mech.drive_speed[0] < 0 else 1.0
    start_angle = float(mech.drive_start[0])
    kin = kinematics(mech, red.angle, speed=sign)
    p = kin.point_index(at)
    striker = int(mech.point_link[p])
    link = link if link is not None else mech.link_names[striker]
    pos, vel, _ = kin._point(mech.point_names[p])
    pos, vel = pos[0], vel[0]
    face = pos[0].copy()  # the seated face passes through K in the assembly pose
    height = (pos - face) @ n
    if not height.max() > 0:
        raise LinkworkError(f'"{at}" never leaves the tool\'s face: no room for a blow')
    spl = PeriodicSplines(red.psi, [red.inertia, red.load, height, vel @ tang])
    jd = float(drive.inertia)
    eta = float(getattr(drive, "efficiency", 1.0))
    moment = drive.moment
    mt, feed, resist = tool.mass, tool.feed, tool.resistance
    f_c = float(friction)

    def flags(psi: float, w: float) -> tuple[bool, float]:
        """In contact: whether the tool is going into the work, and phi (against the sliding), from
        the signs the two velocities are taking (where they are zero, from their rates)."""
        _, _, _, _, _, _, _, ds, dds, gt, dgt, _ = spl.at(psi)
        into = _heading(-ds * w, -dds * w * w, w * abs(ds) + 1e-300) > 0
        sliding = _heading(gt * w, dgt * w * w, w * abs(gt) + 1e-300)
        return into, -f_c * sliding

    def locked(psi: float, inertia: float) -> LinkworkError:
        deg = math.degrees(start_angle + sign * psi) % 360
        return LinkworkError(
            f"friction f = {f_c:g} locks the contact at {deg:.1f} deg: the striker pressing the tool would "
            f"have no positive effective inertia (J + J_d + m_t s' G_phi = {inertia:.4g} kg m^2)"
        )

    seg: dict[str, Any] = {"into": True, "phi": 0.0}  # the flags of the contact phase being integrated

    def contact_force(psi: float, w: float, into: bool | None = None, phi: float | None = None) -> tuple[float, ...]:
        """lambda, psi'', the sliding transfer function and phi in contact (flags: the segment's), then the
        load moment, s' and the drive's moment there."""
        j, dj, _, m, _, _, s, ds, dds, gt, _, _ = spl.at(psi)
        jt = j + jd
        md = float(moment(w))
        q = m + md - 0.5 * dj * w * w
        into = seg["into"] if into is None else into
        phi = seg["phi"] if phi is None else phi
        gphi = ds + phi * gt
        rr = resist if into else 0.0
        den = 1.0 + mt * ds * gphi / jt  # the effective inertia of the contact over J + J_d
        if not den > 0:
            raise locked(psi, jt * den)
        lam = (feed + rr - mt * (dds * w * w + ds * q / jt)) / den
        return lam, (q + gphi * lam) / jt, gt, phi, m, ds, md

    # state: psi, omega, work of the drive on the crank, load work, friction loss, work on the work
    def rhs_free(t: float, y: np.ndarray) -> list[float]:
        j, dj, _, m, _, _ = spl.at(y[0])[:6]
        w = y[1]
        md = float(moment(w))
        return [w, (m + md - 0.5 * dj * w * w) / (j + jd), md * w, m * w, 0.0, 0.0]

    def rhs_contact(t: float, y: np.ndarray) -> list[float]:
        w = y[1]
        lam, acc, gt, phi, m, ds, md = contact_force(y[0], w)
        v = -ds * w
        return [w, acc, md * w, m * w, -phi * lam * gt * w, resist * v if seg["into"] else 0.0]

    def stalled(t: float, y: np.ndarray) -> float:
        return y[1]

    stalled.terminal = True  # type: ignore[attr-defined]
    stalled.direction = -1  # type: ignore[attr-defined]

    def kinetic(psi: float, w: float, v: float) -> float:
        return 0.5 * (spl.at(psi)[0] + jd) * w * w + 0.5 * mt * v * v

    # start where the striker is farthest from the tool
    i0 = int(np.argmax(height))
    psi = float(red.psi[i0])
    w = float(abs(mech.drive_speed[0]) if omega0 is None else omega0)
    if not w > 0:
        raise LinkworkError(f"omega0: expected a positive crank speed, got {w}")
    t = 0.0
    y = np.array([psi, w, 0.0, 0.0, 0.0, 0.0])
    mode = FLIGHT
    free: _Free | None = None
    ledger = dict(blows=0.0, rebounds=0.0, seat=0.0, work_free=0.0)
    snapshots: list[dict[str, float]] = []

    def account(y_: np.ndarray) -> dict[str, float]:
        """The ledger so far, with the tool on its seat (every blow starts and the run ends so)."""
        # the gear passes eta of the motor's moment times its ratio to the crank: the motor's shaft
        # does the crank's work over eta
        on_crank = float(y_[2])
        return dict(
            motor=on_crank / eta, gear=on_crank / eta - on_crank, drive=on_crank, loads=float(y_[3]),
            kinetic=kinetic(float(y_[0]), float(y_[1]), 0.0), feed=0.0,
            blows=ledger["blows"], rebounds=ledger["rebounds"], seat=ledger["seat"],
            work=float(y_[5]) + ledger["work_free"], friction=float(y_[4]),
        )  # fmt: skip

    first = account(y)
    records: list[dict[str, Any]] = []
    phases: list[list[Any]] = []
    samples: list[tuple[np.ndarray, ...]] = []
    impacts_since = 0
    speed_scale = abs(float(np.max(np.abs(vel @ n)))) * w
    # rebounds slower than this end the chatter (plastic): their height would drown in rounding
    v_eps = 1e-5 * max(speed_scale, 1e-3)
    w_eps = 1e-9 * w  # rad/s: a crank slower than this has stopped
    slack = 1e-12  # m: a gap event fires this far past touching, not lost to rounding at zero
    steady = False
    end_time = math.nan
    fine_until = -math.inf

    def report_stall(psi_now: float, how: str = "") -> LinkworkError:
        deg = math.degrees(start_angle + sign * psi_now) % 360
        return LinkworkError(
            f"the crank stops at {deg:.1f} deg (in the {mode} phase{how}): the drive cannot carry the machine "
            "through the blow (too weak a motor, too little flywheel, or too stiff a work)"
        )

    def blow_map(psi_b: float, w_b: float, v_b: float, plastic: bool) -> Strike:
        try:
            b = strike(
                mech, at=at, normal=n, angle=start_angle + sign * psi_b, crank_speed=w_b, tool_speed=v_b,
                restitution=0.0 if plastic else restitution, friction=f_c, tool_mass=mt, drive_inertia=jd,
                link=link,
            )  # fmt: skip
        except SlidingReversal as err:
            raise report_stall(psi_b, ", thrown back by an impact") from err
        if not b.crank_speed_after > w_eps:
            # the crank turns back (or stops dead) in the impact: the blow has stalled the drive
            raise report_stall(psi_b, f", an impact leaves it at {b.crank_speed_after:.4g} rad/s")
        return b

    def after_impact(t_b: float, psi_b: float, w_a: float, u_a: float, v_a: float, rel: float) -> str:
        """The phase that follows an impact with normal separating speed ``rel``."""
        nonlocal free, fine_until
        if rel > v_eps:
            free = _Free(t_b, u_a, v_a, tool)
            # the time to meet again, were the striker to keep its speed: 2 rel / the tool's deceleration
            fine_until = t_b + 8 * rel / -free.a_in
            return APART
        lam = contact_force(psi_b, w_a, *flags(psi_b, w_a))[0]
        if lam > 0:
            return CONTACT
        free = _Free(t_b, u_a, v_a, tool)
        return APART

    max_segments = 2000 * blows
    stuck = 0  # segments in a row that did not advance the time
    for _ in range(max_segments):
        t_seg = t
        if not y[1] > w_eps:  # the crank has stopped (or turns back) where a phase begins
            raise report_stall(y[0])
        if mode == FLIGHT:

            def reach(t_: float, y_: np.ndarray) -> float:
                return spl.at(y_[0])[6] + slack

            reach.terminal, reach.direction = True, -1  # type: ignore[attr-defined]
            horizon = t + 40 * math.pi / max(y[1], 1e-6)
            sol = solve_ivp(rhs_free, (t, horizon), y, method="DOP853", rtol=rtol, atol=1e-12, events=[reach, stalled])
            if sol.status == 0:
                raise LinkworkError(f'"{at}" does not come back to the tool within 20 turns of the crank')
            uu = np.zeros_like(sol.t)
            vv = np.zeros_like(sol.t)
            ff = np.full_like(sol.t, np.nan)
        elif mode == APART:
            assert free is not None
            fr = free

            def gap(t_: float, y_: np.ndarray, fr: _Free = fr) -> float:
                return spl.at(y_[0])[6] + fr.state(t_)[0] + slack

            gap.terminal, gap.direction = True, -1  # type: ignore[attr-defined]
            span = max(fr.t_seat - t, 1e-12)
            if t < fine_until:  # short steps while the two may meet again at once
                t_end, step = min(fine_until, t + span), (fine_until - t_seg) / 32
            else:
                t_end, step = t + span, span / 64
            sol = solve_ivp(
                rhs_free, (t, t_end), y, method="DOP853", rtol=rtol, atol=1e-12, events=[gap, stalled],
                max_step=max(step, 1e-12),
            )  # fmt: skip
            st_ = [fr.state(x) for x in sol.t]
            uu = np.array([a for a, _ in st_])
            vv = np.array([b for _, b in st_])
            ff = np.full_like(sol.t, np.nan)
        else:

            def separate(t_: float, y_: np.ndarray) -> float:
                return contact_force(y_[0], y_[1])[0]

            def seated(t_: float, y_: np.ndarray) -> float:
                return -spl.at(y_[0])[6]

            def turn(t_: float, y_: np.ndarray) -> float:
                return -spl.at(y_[0])[7] * y_[1]

            def slide(t_: float, y_: np.ndarray) -> float:
                return spl.at(y_[0])[9] * y_[1]

            def locking(t_: float, y_: np.ndarray) -> float:  # the effective inertia, over J + J_d
                j, _, _, _, _, _, _, ds, _, gt = spl.at(y_[0])[:10]
                return 1.0 + mt * ds * (ds + seg["phi"] * gt) / (j + jd) - 1e-9

            separate.terminal, separate.direction = True, -1  # type: ignore[attr-defined]
            seated.terminal, seated.direction = True, -1  # type: ignore[attr-defined]
            into, phi = flags(y[0], y[1])
            seg["into"], seg["phi"] = into, phi
            turn.terminal, turn.direction = True, (-1 if into else 1)  # type: ignore[attr-defined]
            slide.terminal, slide.direction = True, (1 if phi > 0 else -1)  # type: ignore[attr-defined]
            locking.terminal, locking.direction = True, -1  # type: ignore[attr-defined]
            horizon = t + 4 * math.pi / max(y[1], 1e-6)
            sol = solve_ivp(
                rhs_contact, (t, horizon), y, method="DOP853", rtol=rtol, atol=1e-12,
                events=[separate, seated, turn, stalled, locking] + ([slide] if f_c > 0 else []), dense_output=True,
            )  # fmt: skip
            if sol.status == 0:
                raise LinkworkError("the striker stays on the tool for two turns of the crank")
            # the contact phase carries the forces: sampled densely, from the solver's interpolant
            tt = np.linspace(sol.t[0], sol.t[-1], max(len(sol.t), 33))
            yy = sol.sol(tt)
            yy[:, 0], yy[:, -1] = sol.y[:, 0], sol.y[:, -1]
            hh = np.array([spl.at(a)[6:8] for a in yy[0]])
            uu = -hh[:, 0]
            vv = -hh[:, 1] * yy[1]
            both = np.array([contact_force(a, b)[:2] for a, b in zip(yy[0], yy[1], strict=True)])
            ff, aa = both[:, 0], both[:, 1]
        if mode == CONTACT:
            ts, ps, ws, pp = tt, yy[0], yy[1], np.full(len(tt), seg["phi"])
        else:
            ts, ps, ws = sol.t, sol.y[0], sol.y[1]
            aa = pp = np.full(len(ts), np.nan)
        code = np.full(len(ts), (FLIGHT, APART, CONTACT).index(mode))
        samples.append((ts, ps, ws, uu, vv, ff, code, aa, pp))
        t = float(sol.t[-1])
        work_before = float(y[5])
        y = sol.y[:, -1].copy()
        phases.append([mode, t_seg, t, float(sol.y[0, 0]), float(y[0])])
        if sol.status == -1:
            raise LinkworkError(f"the integrator failed in the {mode} phase: {sol.message}")
        which = [k for k, ev in enumerate(sol.t_events) if len(ev)]
        stuck = stuck + 1 if t <= t_seg else 0
        if stuck > 3:
            deg = math.degrees(start_angle + sign * y[0]) % 360
            raise LinkworkError(
                f"the {mode} phase makes no progress at {deg:.1f} deg (t = {t:.6g} s, crank speed {y[1]:.3g} "
                "rad/s): its events fire where it starts"
            )
        if mode == CONTACT and 4 in which:
            j_, _, _, _, _, _, _, ds_, _, gt_ = spl.at(y[0])[:10]
            raise locked(y[0], j_ + jd + mt * ds_ * (ds_ + seg["phi"] * gt_))
        if mode == FLIGHT:
            if 1 in which:
                raise report_stall(y[0])
            # a blow on the seated tool
            if records:
                periods = [r["time"] for r in records] + [t]
                speeds = [r["crank_speed_before"] for r in records] + [y[1]]
                if len(periods) >= 4:
                    p1, p2, p3 = np.diff(periods[-4:])
                    s1, s2, s3 = speeds[-3:]
                    if abs(p3 - p2) <= tol * p3 and abs(p2 - p1) <= tol * p3 and abs(s3 - s2) <= tol * s3:
                        steady = True
                if steady or len(records) >= blows:
                    end_time = t
                    break
            snapshots.append(account(y))
            b = blow_map(y[0], y[1], 0.0, plastic=False)
            e0 = kinetic(y[0], y[1], 0.0)
            w_a, v_a = b.crank_speed_after, b.tool_speed_after
            e1 = kinetic(y[0], w_a, v_a)
            records.append(
                dict(
                    time=t, psi=float(y[0]), angle=b.angle % (2 * math.pi), crank_speed_before=float(y[1]),
                    crank_speed_after=float(w_a), omega_before=b.omega_before, omega_after=b.omega_after,
                    impact_speed=-b.closing_speed, striker_speed=b.striker_speed, tool_speed=float(v_a),
                    impulse=b.impulse, joints=b.joints, joint_links=b.joint_links, drive_impulse=b.drive_impulse,
                    energy_before=e0, energy_lost=e0 - e1,
                    energy_to_tool=0.5 * mt * float(v_a) ** 2, rebounds=0, rebound_loss=0.0, work_on_work=0.0,
                    penetration=0.0,
                )
            )  # fmt: skip
            ledger["blows"] += e0 - e1
            impacts_since = 0
            y[1] = w_a
            mode = after_impact(t, y[0], w_a, 0.0, v_a, -restitution * b.closing_speed)
            continue
        if (mode == CONTACT and 3 in which) or (mode == APART and 1 in which):
            raise report_stall(y[0])
        rec = records[-1]
        rec["work_on_work"] += float(y[5]) - work_before
        if mode == APART:
            assert free is not None
            u_now, v_now = free.state(t)
            rec["penetration"] = max(rec["penetration"], free.u_top if free.v0 > 0 else u_now)
            ledger["work_free"] += free.work(t) - free.work(t_seg)
            rec["work_on_work"] += free.work(t) - free.work(t_seg)
            if not which and t < free.t_seat:
                continue  # on from the short steps to the long ones
            if 0 in which:  # striker and tool meet again
                impacts_since += 1
                if impacts_since > 500:
                    raise LinkworkError("striker and tool chatter without end (more than 500 impacts after a blow)")
                b = blow_map(y[0], y[1], v_now, plastic=False)
                plastic = -b.closing_speed * restitution <= v_eps
                if plastic:
                    b = blow_map(y[0], y[1], v_now, plastic=True)
                e0 = kinetic(y[0], y[1], v_now)
                w_a, v_a = b.crank_speed_after, b.tool_speed_after
                e1 = kinetic(y[0], w_a, v_a)
                rec["rebounds"] += 1
                rec["rebound_loss"] += e0 - e1
                ledger["rebounds"] += e0 - e1
                y[1] = w_a
                mode = after_impact(t, y[0], w_a, u_now, v_a, 0.0 if plastic else -restitution * b.closing_speed)
                continue
            # the tool is back on its seat: it stops there
            ledger["seat"] += 0.5 * mt * v_now**2
            mode = FLIGHT
            continue
        # contact
        hs = spl.at(y[0])
        u_now, v_now = -hs[6], -hs[7] * y[1]
        rec["penetration"] = max(rec["penetration"], float(np.max(uu)))
        if 0 in which:  # the contact force falls to zero: the tool goes on alone
            free = _Free(t, u_now, v_now, tool)
            mode = APART
        elif 1 in which:  # on the seat: the tool stops, the striker goes on up
            ledger["seat"] += 0.5 * mt * v_now**2
            mode = FLIGHT
        elif contact_force(y[0], y[1], *flags(y[0], y[1]))[0] < 0:
            # the tool stops in the work and its resistance lets go (or the sliding turns): the force
            # the contact would need pulls, so the two part here
            free = _Free(t, u_now, v_now, tool)
            mode = APART
        # otherwise the same phase goes on afresh
    else:
        raise LinkworkError("the run did not settle within its limit of phases")
    if len(records) < 2:
        raise LinkworkError(f"only {len(records)} blow(s) in the run: give more blows")
    # merge the phases split by restarts
    merged: list[list[Any]] = []
    for ph in phases:
        if merged and merged[-1][0] == ph[0] and merged[-1][2] == ph[1]:
            merged[-1][2], merged[-1][4] = ph[2], ph[4]
        else:
            merged.append(list(ph))
    cat = [np.concatenate([s[i] for s in samples]) for i in range(9)]
    # the loads of the pairs while striker and tool move together, in the last cycle
    sel = np.flatnonzero((cat[6] == 2) & (cat[0] >= records[-1]["time"]))
    first_pairs = mech.first_pairs()
    pair_loads = {name: np.zeros((len(sel), 2)) for name in first_pairs}
    for row, j in enumerate(sel):
        angle = np.array([start_angle + sign * cat[1][j]])
        unit = kinematics(mech, angle, speed=sign)
        at_speed = kinematics(mech, angle, speed=sign * cat[2][j])
        k_pos = unit._point(mech.point_names[p])[0][0, 0]
        push = cat[5][j] * (n + cat[8][j] * tang)  # the tool's force on the striker
        _, _, from_push = impulsive_reactions(unit, striker, k_pos, push, float(cat[7][j]))
        lam, frame = solve_reactions(at_speed, inertia_and_gravity(at_speed))
        steady_part = Forces(at_speed, lam, frame)
        for name in first_pairs:
            pair_loads[name][row] = from_push[name] + steady_part.reaction(name)[0]
    contact = ContactLoads(
        cat[0][sel] - records[-1]["time"], cat[5][sel], cat[8][sel], pair_loads, dict(records[-1]["joint_links"])
    )
    last = account(y)
    energy = {k: last[k] - first[k] for k in last}
    per_cycle = {k: last[k] - snapshots[-1][k] for k in last}
    out = tuple(Blow(**r) for r in records)
    return WorkingCycle(
        out,
        tuple(Phase(*ph) for ph in merged),
        end_time - records[-1]["time"],
        steady,
        cat[0],
        cat[1],
        cat[2],
        cat[3],
        cat[4],
        cat[5],
        cat[6],
        energy,
        per_cycle,
        tool,
        contact,
    )
