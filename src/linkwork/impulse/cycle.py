"""Working cycle of a percussion mechanism of variable structure: blows, rebounds, contact.

The machine: a one-degree-of-freedom mechanism (turning angle ``psi`` of the crank, reduced
inertia ``J(psi)``, reduced load moment ``M(psi)`` of gravity and the file's loads) driven by a
motor through a gear with a flywheel (:class:`~linkwork.machine.MotorGear`: moment ``M_d(psi')``,
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

The blow (``g = 0`` closing) is the impact map of :func:`~linkwork.impulse.impact_map.strike`, generalised
from :func:`~linkwork.impulse.impact` to a tool that moves.

The run is put together from its parts: the blow's inputs read from the file
(:func:`~linkwork.impulse.mechanism.blow_setup`, shared with ``linkwork.impact``), the contact model
(:mod:`linkwork.impulse.contact`), one function per phase returning a segment with its named events
(:mod:`linkwork.impulse.phases`), the energy ledger and the driver here; what the run gives is
:mod:`linkwork.impulse.working_cycle`'s.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from linkwork.errors import LinkworkError, SlidingReversal
from linkwork.impulse.contact import (
    DRIVE_WORK,
    FRICTION_LOSS,
    LOAD_WORK,
    OMEGA,
    PSI,
    WORK_DONE,
    ContactModel,
    FreeTool,
    Tool,
)
from linkwork.impulse.impact_map import Strike, strike
from linkwork.impulse.mechanism import BlowSetup, blow_setup, impulsive_reactions, striking_point
from linkwork.impulse.phases import APART, CONTACT, FLIGHT, KINDS, Samples, Segment, fly, part, press
from linkwork.impulse.working_cycle import Blow, ContactLoads, Phase, WorkingCycle
from linkwork.kinetostatics.reaction_forces import Forces
from linkwork.kinetostatics.reactions import inertia_and_gravity, solve_reactions
from linkwork.limits import DYNAMICS_STEPS
from linkwork.machine.reduction import reduced
from linkwork.machine.simulation import PeriodicSplines
from linkwork.motion import kinematics
from linkwork.structure.model import Mechanism
from linkwork.structure.records import MotorGear


def simulate_blows(
    mech: Mechanism,
    drive: MotorGear | None = None,
    *,
    tool: Tool | None = None,
    at: str | None = None,
    normal: npt.ArrayLike | float | None = None,
    restitution: float | None = None,
    friction: float | None = None,
    link: str | None = None,
    omega0: float | None = None,
    blows: int = 200,
    steps: int = DYNAMICS_STEPS,
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
    drive : MotorGear, optional
        Motor, gear and flywheel (default: the file's ``machine:``).
    tool : Tool, optional
        The tool struck: its mass (kg), the feed force returning it to its seat (N) and the work's resistance
        (N); default the file's ``impact: tool:``.
    at : str, optional
        The point that strikes, ``link.point``; default the file's.
    normal : array_like or float, optional
        The tool face's outward normal, a vector or an angle, rad; default the file's.
    restitution : float, optional
        Newton's coefficient of restitution R, 0 to 1; default the file's.
    friction : float, optional
        The coefficient of friction f at the point of impact; default the file's.
    link : str, optional
        The link that strikes; default the link of ``at``.
    omega0 : float, optional
        Crank speed at the start, rad/s (default: the file's drive speed); the run starts where
        the striker is farthest from the tool.
    blows : int
        At most this many blows.
    steps : int
        Turning angles over a turn at which the machine's reduced inertia, loads and striker's path are
        sampled (periodic splines between them).
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

    Returns
    -------
    WorkingCycle
        The blows until the cycle repeats: each blow's speeds, impulses and energy, and the steady cycle's.

    Examples
    --------
    >>> import linkwork as lw
    >>> cycle = lw.simulate_blows("percussion-rocker", blows=20, steps=360)  # doctest: +SKIP
    """
    drive, tool = _drive_and_tool(mech, drive, tool)
    setup = blow_setup(
        mech, at=at, normal=normal, restitution=restitution, friction=friction, link=link, need_speed=False
    )
    if blows < 3:
        raise LinkworkError(f"blows: expected at least 3 (a steady cycle is two periods alike), got {blows}")
    model, path = _contact_model(mech, setup, drive, tool, steps)
    w = float(abs(mech.drive_speed[0]) if omega0 is None else omega0)
    if not w > 0:
        raise LinkworkError(f"omega0: expected a positive crank speed, got {w}")
    run = _Run(mech, setup, model, path, w, blows=blows, tol=tol, rtol=rtol)
    for _ in range(2000 * blows):
        if run.step():
            return run.result()
    raise LinkworkError("the run did not settle within its limit of phases")


def _drive_and_tool(mech: Mechanism, drive: MotorGear | None, tool: Tool | None) -> tuple[MotorGear, Tool]:
    """The drive and the tool given, else the file's."""
    blow_spec = mech.blow
    if drive is None:
        drive = mech.motor_gear
    if drive is None:
        raise LinkworkError('the working cycle needs a drive: give a "machine:" section (motor, gear, flywheel)')
    if tool is None and blow_spec is not None and blow_spec.tool is not None:
        t_spec = blow_spec.tool
        tool = Tool(t_spec.mass, t_spec.feed, t_spec.resistance)
    if tool is None:
        raise LinkworkError('the working cycle needs the tool: give "tool:" (mass, feed, resistance) in "impact:"')
    return drive, tool


@dataclass(frozen=True)
class _Path:
    """The striking point over the turn: the ``link`` that strikes (its name), the turning angle
    where the run starts (``start``, rad: where the striker is farthest from the tool) and the largest
    speed of the striker along the normal per unit crank speed (``normal_gain``, m/rad)."""

    link: str
    start: float
    normal_gain: float


def _contact_model(
    mech: Mechanism, setup: BlowSetup, drive: MotorGear, tool: Tool, steps: int
) -> tuple[ContactModel, _Path]:
    """The machine's curves on ``steps`` turning angles of a turn, with the drive and the tool; the
    tool's face on its seat passes through the striking point in the assembly pose."""
    n = setup.normal
    tang = np.array([n[1], -n[0]])
    red = reduced(mech, steps=steps)
    sign = -1.0 if mech.drive_speed[0] < 0 else 1.0
    start_angle = float(mech.drive_start[0])
    point = striking_point(kinematics(mech, red.angle, speed=sign), setup.at)
    pos, vel = point.position, point.velocity
    face = pos[0].copy()  # the seated face passes through K in the assembly pose
    height = (pos - face) @ n
    if not height.max() > 0:
        raise LinkworkError(f'"{setup.at}" never leaves the tool\'s face: no room for a blow')
    splines = PeriodicSplines(red.psi, [red.inertia, red.load, height, vel @ tang])
    efficiency = float(getattr(drive, "efficiency", 1.0))
    model = ContactModel(
        splines, float(drive.inertia), efficiency, drive.moment, tool, float(setup.friction), start_angle, sign
    )
    link = setup.link if setup.link is not None else mech.link_names[point.link]
    return model, _Path(link, float(red.psi[int(np.argmax(height))]), abs(float(np.max(np.abs(vel @ n)))))


@dataclass
class _Losses:
    """Energy the run has lost so far, J: kinetic energy in the blows, in the rebounds and on the seat,
    and the work done on the work while the tool flew free."""

    blows: float = 0.0
    rebounds: float = 0.0
    seat: float = 0.0
    work_free: float = 0.0


def _ledger(model: ContactModel, y: np.ndarray, losses: _Losses) -> dict[str, float]:
    """The energy ledger of the run at the state ``y``, with the tool on its seat (every blow starts
    and the run ends so): the keys of :attr:`WorkingCycle.energy`."""
    # the gear passes eta of the motor's moment times its ratio to the crank: the motor's shaft does the
    # crank's work over eta
    on_crank = float(y[DRIVE_WORK])
    eta = model.efficiency
    return dict(
        motor=on_crank / eta,
        gear=on_crank / eta - on_crank,
        drive=on_crank,
        loads=float(y[LOAD_WORK]),
        kinetic=model.kinetic(float(y[PSI]), float(y[OMEGA]), 0.0),
        feed=0.0,
        blows=losses.blows,
        rebounds=losses.rebounds,
        seat=losses.seat,
        work=float(y[WORK_DONE]) + losses.work_free,
        friction=float(y[FRICTION_LOSS]),
    )


@dataclass
class _Aftermath:
    """What followed a blow until the next: the fields of :class:`Blow` that grow over the phases."""

    rebounds: int = 0
    rebound_loss: float = 0.0
    work_on_work: float = 0.0
    penetration: float = 0.0


class _Run:
    """The run between its segments: the time, the state and the phase it is in, the tool's free
    flight, the blows so far and what followed each, the energy lost, the samples and the phases."""

    def __init__(
        self,
        mech: Mechanism,
        setup: BlowSetup,
        model: ContactModel,
        path: _Path,
        w: float,
        *,
        blows: int,
        tol: float,
        rtol: float,
    ) -> None:
        self.mech, self.setup, self.model, self.path = mech, setup, model, path
        self.max_blows, self.tol, self.rtol = blows, tol, rtol
        # rebounds slower than this end the chatter (plastic): their height would drown in rounding
        self.v_eps = 1e-5 * max(path.normal_gain * w, 1e-3)
        self.w_eps = 1e-9 * w  # rad/s: a crank slower than this has stopped
        self.t = 0.0
        self.y = np.array([path.start, w, 0.0, 0.0, 0.0, 0.0])
        self.mode = FLIGHT
        self.free: FreeTool | None = None
        self.fine_until = -math.inf
        self.losses = _Losses()
        self.first = _ledger(model, self.y, self.losses)
        self.snapshots: list[dict[str, float]] = []  # the ledger before each blow
        self.blows: list[Blow] = []
        self.after: list[_Aftermath] = []
        self.samples: list[Samples] = []
        self.phases: list[Phase] = []
        self.stuck = 0  # segments in a row that did not advance the time
        self.impacts_since = 0  # impacts since the last blow
        self.steady = False
        self.end_time = math.nan

    def step(self) -> bool:
        """Integrate the next segment and act on how it ended; True where the run is over."""
        if not self.y[OMEGA] > self.w_eps:  # the crank has stopped (or turns back) where a phase begins
            raise self.stall(self.y[PSI])
        work_before = float(self.y[WORK_DONE])
        seg = self.integrate()
        self.keep(seg)
        if self.mode == FLIGHT:
            return self.after_flight(seg)
        if self.mode == APART:
            self.after_apart(seg, work_before)
        else:
            self.after_contact(seg, work_before)
        return False

    def integrate(self) -> Segment:
        """The next segment of the phase the run is in."""
        if self.mode == FLIGHT:
            return fly(self.model, self.t, self.y, self.rtol, self.setup.at)
        if self.mode == APART:
            assert self.free is not None
            return part(self.model, self.t, self.y, self.rtol, self.free, self.fine_until)
        return press(self.model, self.t, self.y, self.rtol)

    def keep(self, seg: Segment) -> None:
        """Take the segment's samples, phase, end time and end state; refuse a run that stands still."""
        self.samples.append(seg.samples)
        self.t, self.y = seg.end, seg.state
        self.phases.append(Phase(seg.kind, seg.start, seg.end, seg.psi_start, float(self.y[PSI])))
        self.stuck = self.stuck + 1 if seg.end <= seg.start else 0
        if self.stuck > 3:
            raise LinkworkError(
                f"the {self.mode} phase makes no progress at {self.model.degrees(self.y[PSI]):.1f} deg (t = "
                f"{self.t:.6g} s, crank speed {self.y[OMEGA]:.3g} rad/s): its events fire where it starts"
            )

    def stall(self, psi: float, how: str = "") -> LinkworkError:
        """The error of a crank that stops at the turning angle ``psi`` in the phase the run is in."""
        return LinkworkError(
            f"the crank stops at {self.model.degrees(psi):.1f} deg (in the {self.mode} phase{how}): the drive "
            "cannot carry the machine through the blow (too weak a motor, too little flywheel, or too stiff a work)"
        )

    def after_flight(self, seg: Segment) -> bool:
        """The striker has reached the seated tool: the run ends here, or the blow."""
        if "stalled" in seg.events:
            raise self.stall(self.y[PSI])
        if self.blows and self.done():
            self.end_time = self.t
            return True
        self.blow()
        return False

    def done(self) -> bool:
        """Whether the run ends at the blow now due: the cycle is steady (the last two blow-to-blow
        periods and crank speeds before the blows alike within ``tol``), or the blows are all made."""
        periods = [b.time for b in self.blows] + [self.t]
        speeds = [b.crank_speed_before for b in self.blows] + [self.y[OMEGA]]
        if len(periods) >= 4:
            p1, p2, p3 = np.diff(periods[-4:])
            s2, s3 = speeds[-2:]
            tol = self.tol
            if abs(p3 - p2) <= tol * p3 and abs(p2 - p1) <= tol * p3 and abs(s3 - s2) <= tol * s3:
                self.steady = True
        return self.steady or len(self.blows) >= self.max_blows

    def impact(self, v: float, plastic: bool) -> Strike:
        """The impact of the striker on the tool moving at ``v`` in the run's state; a crank it stops
        or throws back is a stall."""
        psi, w = self.y[PSI], self.y[OMEGA]
        model, setup = self.model, self.setup
        try:
            b = strike(
                self.mech,
                at=setup.at,
                normal=setup.normal,
                angle=model.start_angle + model.sign * psi,
                crank_speed=w,
                tool_speed=v,
                restitution=0.0 if plastic else setup.restitution,
                friction=model.friction,
                tool_mass=model.tool.mass,
                drive_inertia=model.drive_inertia,
                link=self.path.link,
            )
        except SlidingReversal as err:
            raise self.stall(psi, ", thrown back by an impact") from err
        if not b.crank_speed_after > self.w_eps:
            # the crank turns back (or stops dead) in the impact: the blow has stalled the drive
            raise self.stall(psi, f", an impact leaves it at {b.crank_speed_after:.4g} rad/s")
        return b

    def blow(self) -> None:
        """The blow on the seated tool: its record, its loss, and the phase that follows."""
        y, model = self.y, self.model
        self.snapshots.append(_ledger(model, y, self.losses))
        b = self.impact(0.0, plastic=False)
        e0 = model.kinetic(y[PSI], y[OMEGA], 0.0)
        w_a, v_a = b.crank_speed_after, b.tool_speed_after
        e1 = model.kinetic(y[PSI], w_a, v_a)
        self.blows.append(
            Blow(
                time=self.t,
                psi=float(y[PSI]),
                angle=b.angle % (2 * math.pi),
                crank_speed_before=float(y[OMEGA]),
                crank_speed_after=float(w_a),
                omega_before=b.omega_before,
                omega_after=b.omega_after,
                impact_speed=-b.closing_speed,
                striker_speed=b.striker_speed,
                tool_speed=float(v_a),
                impulse=b.impulse,
                joints=b.joints,
                joint_links=b.joint_links,
                drive_impulse=b.drive_impulse,
                energy_before=e0,
                energy_lost=e0 - e1,
                energy_to_tool=0.5 * model.tool.mass * float(v_a) ** 2,
            )
        )
        self.after.append(_Aftermath())
        self.losses.blows += e0 - e1
        self.impacts_since = 0
        y[OMEGA] = w_a
        self.mode = self.after_impact(w_a, 0.0, v_a, -self.setup.restitution * b.closing_speed)

    def after_impact(self, w_a: float, u_a: float, v_a: float, rel: float) -> str:
        """The phase that follows an impact that leaves the crank at ``w_a``, the tool at ``u_a`` going
        at ``v_a``, and the two separating at ``rel`` along the normal."""
        psi, tool = self.y[PSI], self.model.tool
        if rel > self.v_eps:
            free = self.free = FreeTool(self.t, u_a, v_a, tool)
            # the time to meet again, were the striker to keep its speed: 2 rel / the tool's deceleration
            self.fine_until = self.t + 8 * rel / -free.a_in
            return APART
        lam = self.model.pressing(psi, w_a, self.model.flags(psi, w_a)).force
        if lam > 0:
            return CONTACT
        self.free = FreeTool(self.t, u_a, v_a, tool)
        return APART

    def after_apart(self, seg: Segment, work_before: float) -> None:
        """The end of a stretch apart: on in long steps, a rebound, or the tool back on its seat."""
        if "stalled" in seg.events:
            raise self.stall(self.y[PSI])
        free, t, after = self.free, self.t, self.after[-1]
        assert free is not None
        after.work_on_work += float(self.y[WORK_DONE]) - work_before
        u_now, v_now = free.state(t)
        after.penetration = max(after.penetration, free.u_top if free.v0 > 0 else u_now)
        self.losses.work_free += free.work(t) - free.work(seg.start)
        after.work_on_work += free.work(t) - free.work(seg.start)
        if not seg.events and t < free.t_seat:
            return  # on from the short steps to the long ones
        if "gap" in seg.events:  # striker and tool meet again
            self.rebound(u_now, v_now)
            return
        # the tool is back on its seat: it stops there
        self.losses.seat += 0.5 * self.model.tool.mass * v_now**2
        self.mode = FLIGHT

    def rebound(self, u: float, v: float) -> None:
        """Striker and tool meet again, the tool at ``u`` going at ``v``; slower than ``v_eps`` apart
        after it, the impact is taken plastic."""
        self.impacts_since += 1
        if self.impacts_since > 500:
            raise LinkworkError("striker and tool chatter without end (more than 500 impacts after a blow)")
        y, model, restitution = self.y, self.model, self.setup.restitution
        b = self.impact(v, plastic=False)
        plastic = -b.closing_speed * restitution <= self.v_eps
        if plastic:
            b = self.impact(v, plastic=True)
        e0 = model.kinetic(y[PSI], y[OMEGA], v)
        w_a, v_a = b.crank_speed_after, b.tool_speed_after
        e1 = model.kinetic(y[PSI], w_a, v_a)
        after = self.after[-1]
        after.rebounds += 1
        after.rebound_loss += e0 - e1
        self.losses.rebounds += e0 - e1
        y[OMEGA] = w_a
        self.mode = self.after_impact(w_a, u, v_a, 0.0 if plastic else -restitution * b.closing_speed)

    def after_contact(self, seg: Segment, work_before: float) -> None:
        """The end of a contact phase: the tool goes on alone, stops on its seat, or the phase goes on
        afresh (the tool's motion or the sliding turned)."""
        y, model, t = self.y, self.model, self.t
        assert seg.flags is not None
        if "locking" in seg.events:
            raise model.locked(y[PSI], model.effective_inertia(y[PSI], seg.flags.phi))
        if "stalled" in seg.events:
            raise self.stall(y[PSI])
        after = self.after[-1]
        after.work_on_work += float(y[WORK_DONE]) - work_before
        height = model.curves(y[PSI]).height
        u_now, v_now = -height.value, -height.slope * y[OMEGA]
        after.penetration = max(after.penetration, float(np.max(seg.samples.u)))
        if "separate" in seg.events:  # the contact force falls to zero: the tool goes on alone
            self.free = FreeTool(t, u_now, v_now, model.tool)
            self.mode = APART
        elif "seated" in seg.events:  # on the seat: the tool stops, the striker goes on up
            self.losses.seat += 0.5 * model.tool.mass * v_now**2
            self.mode = FLIGHT
        elif model.pressing(y[PSI], y[OMEGA], model.flags(y[PSI], y[OMEGA])).force < 0:
            # the tool stops in the work and its resistance lets go (or the sliding turns): the force
            # the contact would need pulls, so the two part here
            self.free = FreeTool(t, u_now, v_now, model.tool)
            self.mode = APART
        # otherwise the same phase goes on afresh

    def result(self) -> WorkingCycle:
        """The run's blows, phases, samples, ledger and the loads of the last contact phases."""
        if len(self.blows) < 2:
            raise LinkworkError(f"only {len(self.blows)} blow(s) in the run: give more blows")
        blows = tuple(dataclasses.replace(b, **vars(a)) for b, a in zip(self.blows, self.after, strict=True))
        last = blows[-1]
        s = Samples(*(np.concatenate(column) for column in zip(*self.samples, strict=True)))
        contact = _contact_loads(self.mech, self.setup, self.model, s, last.time, last.joint_links)
        end = _ledger(self.model, self.y, self.losses)
        energy = {k: end[k] - self.first[k] for k in end}
        per_cycle = {k: end[k] - self.snapshots[-1][k] for k in end}
        return WorkingCycle(
            blows,
            _merged(self.phases),
            self.end_time - last.time,
            self.steady,
            s.t,
            s.psi,
            s.omega,
            s.u,
            s.v,
            s.force,
            s.mode,
            energy,
            per_cycle,
            self.model.tool,
            contact,
        )


def _merged(phases: list[Phase]) -> tuple[Phase, ...]:
    """The phases with those that a restart of the same phase split joined again."""
    merged: list[Phase] = []
    for ph in phases:
        if merged and merged[-1].kind == ph.kind and merged[-1].end == ph.start:
            merged[-1] = dataclasses.replace(merged[-1], end=ph.end, psi_end=ph.psi_end)
        else:
            merged.append(ph)
    return tuple(merged)


def _contact_loads(
    mech: Mechanism,
    setup: BlowSetup,
    model: ContactModel,
    s: Samples,
    since: float,
    links: dict[str, tuple[str, str]],
) -> ContactLoads:
    """The loads of the pairs while striker and tool move together after the time ``since`` (the
    last blow), at the samples ``s`` of the run: the contact force's, gravity's and the inertia's of
    every link at the crank's actual speed and acceleration."""
    n = setup.normal
    tang = np.array([n[1], -n[0]])
    sel = np.flatnonzero((s.mode == KINDS.index(CONTACT)) & (s.t >= since))
    first_pairs = mech.first_pairs()
    pair_loads = {name: np.zeros((len(sel), 2)) for name in first_pairs}
    for row, j in enumerate(sel):
        angle = np.array([model.start_angle + model.sign * s.psi[j]])
        unit = kinematics(mech, angle, speed=model.sign)
        at_speed = kinematics(mech, angle, speed=model.sign * s.omega[j])
        point = striking_point(unit, setup.at)
        push = s.force[j] * (n + s.phi[j] * tang)  # the tool's force on the striker
        _, _, from_push = impulsive_reactions(unit, point.link, point.position[0], push, float(s.acceleration[j]))
        lam, frame = solve_reactions(at_speed, inertia_and_gravity(at_speed))
        steady_part = Forces(at_speed, lam, frame)
        for name in first_pairs:
            pair_loads[name][row] = from_push[name] + steady_part.reaction(name)[0]
    return ContactLoads(s.t[sel] - since, s.force[sel], s.phi[sel], pair_loads, dict(links))
