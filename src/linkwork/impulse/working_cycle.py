"""What a run of a percussion mechanism gives (:func:`linkwork.impulse.cycle.simulate_blows`): its blows, its
phases, the forces in the pairs during contact and the whole working cycle with its energy ledger."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from linkwork.impulse.contact import Tool
from linkwork.impulse.phases import FREEDOM


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
