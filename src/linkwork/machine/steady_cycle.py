"""``linkwork.dynamics``: the machine unit run with its drive to the steady cycle, with a flywheel sized for
the coefficient of speed fluctuation asked."""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from linkwork.errors import LinkworkError
from linkwork.limits import DYNAMICS_STEPS
from linkwork.machine.flywheel import Flywheel, size_flywheel_wittenbauer
from linkwork.machine.reduction import Reduced, reduced
from linkwork.machine.simulation import Motion, run_turns
from linkwork.motion.analysis import CrankAngles
from linkwork.structure.model import Mechanism
from linkwork.structure.records import MotorGear


@dataclass(frozen=True)
class Dynamics:
    """Reduced quantities, the simulated runs with the drive, and the flywheel sized for ``delta``.

    ``startup`` is the run from rest; for a machine with process loads it runs idle (no workpiece:
    a shears is brought up to speed before the first cut), and ``motion`` then continues from its
    steady state with the process loads to the steady working cycle.  Without process loads the
    two are the same run.  ``flywheel`` is the sizing (None without ``delta``): its ``flywheel`` is
    the inertia on its own shaft (``drive.flywheel``, the one the run used), ``on_crank`` the same
    reduced to the crank shaft.  ``crank`` says where position 0 is and which way the crank turns (the φ
    of :meth:`to_xarray`, as ``linkwork dynamics`` and the report give it); ``name`` is the mechanism's.
    """

    reduced: Reduced
    drive: MotorGear
    motion: Motion
    flywheel: Flywheel | None
    startup: Motion
    crank: CrankAngles | None = None
    name: str = ""

    def _repr_html_(self) -> str:
        """A notebook's view: the steady cycle's speed fluctuation and powers, the flywheel, the start-up."""
        from linkwork.display import number, table

        rows = [
            ("coefficient of speed fluctuation delta", number(self.delta)),
            ("mean crank speed", number(self.motion.last.omega_mean, "rad/s")),
            ("mean power of the motor", number(self.mean_power, "W")),
            ("start-up time", number(self.startup_time, "s")),
        ]
        if self.flywheel is not None:
            rows.append(("flywheel inertia on its shaft", number(self.flywheel.inertia, "kg m^2")))
        return table("Machine dynamics", rows)

    def to_xarray(self) -> Any:
        """The tables of ``linkwork dynamics --json`` as an xarray Dataset (the ``data`` extra).

        Dimension ``angle`` (the coordinate: φ from position 0, deg; ``crank_angle_to_x`` beside it): the
        reduced ``inertia``, its ``inertia_slope``, the reduced ``load`` moment and its ``work`` from the first
        sample; dimension ``time`` (the coordinate: ``t`` in s from the start of the steady cycle): the
        crank's ``omega``, ``psi`` (turned since the start of the cycle), ``phi``, the motor's torque and
        power.  Each variable's unit in its ``units`` attribute; delta, the powers and the flywheel in the
        Dataset's attributes.

        Raises
        ------
        MissingDependencyError
            Without xarray, naming the extra that brings it.
        """
        from linkwork.machine.tables import to_dataset

        return to_dataset(self)

    def to_pandas(self, by: str = "angle") -> Any:
        """The variables of :meth:`to_xarray` over the crank angle (``by="angle"``) or over the steady
        cycle's time (``by="time"``) as a pandas DataFrame; the units in ``attrs["units"]``.

        Raises
        ------
        MissingDependencyError
            Without pandas, naming the extra that brings it.
        """
        from linkwork.machine.tables import to_frame

        return to_frame(self, by)

    @property
    def startup_time(self) -> float:
        """Time (s) from rest until the mean speed of the turns stays within 2 % of its final value."""
        return self.startup.startup_time()

    def cycle_speed(self, sign: float) -> tuple[np.ndarray, np.ndarray]:
        """The crank's drive angles (rad) and speed (rad/s) over the steady cycle, ``(N,)`` each, the last sample
        closing the turn; ``sign`` +1 where the crank turns counter-clockwise, -1 clockwise."""
        _, psi, omega = self.motion.cycle()
        return self.reduced.angle[0] + sign * (self.motion.cycle_start + psi), omega

    @property
    def delta(self) -> float:
        """Coefficient of speed fluctuation of the steady cycle."""
        return self.motion.last.delta

    @property
    def drive_power(self) -> float:
        """Mean power the drive gives the crank over the steady cycle (after the gear's loss), W: the
        mean power of the loads, which the periodic cycle's drive work balances (the dampers' at the mean speed)."""
        omega = self.motion.last.omega_mean
        return -self.reduced.at_speed(omega).mean_load * omega

    @property
    def mean_power(self) -> float:
        """Mean power of the motor at its shaft over the steady cycle, W (to compare with its rating):
        ``drive_power`` over the gear's efficiency."""
        return self.drive_power / self.drive.efficiency


def balance_speed(drive: MotorGear, moment: float) -> float:
    """The crank speed (rad/s) at which the drive gives ``moment`` on the stable (falling) part of
    its characteristic, the highest such speed; NaN if there is none (a constant torque).

    The speed is doubled from 1 rad/s until the drive's moment there is at most ``moment`` with a speed
    below it where the moment is at least ``moment`` (a characteristic still rising at 1 rad/s, as an
    induction motor's geared far down is, is followed past its peak); then bisected between the two."""
    lo = math.nan
    hi = 1.0
    while hi < 2e6:
        if drive.moment(hi) <= moment:
            if drive.moment(hi / 2.0) >= moment:
                lo = hi / 2.0
                break
            grid = np.linspace(0.0, hi, 4097)
            above = np.flatnonzero(drive.moment(grid) >= moment)
            if len(above):
                lo = float(grid[above[-1]])
                break
        hi *= 2.0
    if not math.isfinite(lo):
        return float("nan")
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if drive.moment(mid) >= moment:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def with_flywheel_for(
    red: Reduced, drive: MotorGear, delta: float, speed: float | None = None, *, fallback: float
) -> tuple[MotorGear, Flywheel]:
    """``drive`` with the flywheel for ``delta`` (Wittenbauer's tangents, :func:`size_flywheel_wittenbauer`)
    on its ``flywheel_on`` shaft in place of its own, and that sizing.  The mean crank speed ``speed`` (rad/s)
    defaults to where the drive's moment balances the loads' mean moment (:func:`balance_speed`), or to
    ``fallback`` for a drive without such a point (a constant torque)."""
    if speed is None:
        speed = balance_speed(drive, -red.mean_load)
    if speed is None or not math.isfinite(speed):
        speed = fallback
    base = drive.with_flywheel(0.0)
    at_speed = red.at_speed(speed)  # the dampers' moment at the mean speed
    fly = size_flywheel_wittenbauer(at_speed, delta, speed, base.inertia, shaft=drive.flywheel_on, ratio=drive.ratio)
    return drive.with_flywheel(fly.flywheel), fly


def dynamics(
    mech: Mechanism,
    drive: MotorGear | None = None,
    *,
    delta: float | None = None,
    speed: float | None = None,
    steps: int = DYNAMICS_STEPS,
    omega0: float = 0.0,
    start: float | None = None,
    turns: int = 500,
) -> Dynamics:
    """Run the machine unit with ``drive`` (default: the file's ``machine:``) from ``omega0`` to its
    steady cycle.  ``mech``: a compiled Mechanism (``linkwork.dynamics`` also takes a path, an example
    name or a Spec: :mod:`linkwork.api`).

    With ``delta`` (default: the file's), the flywheel is first sized for that coefficient of speed
    fluctuation by the energy method (Wittenbauer's tangents), at the mean crank speed ``speed``
    (default: where the drive's moment balances the loads' mean moment, or the file's speed for a
    drive without such a point), and put on the drive's ``flywheel_on`` shaft; the run then checks
    it.  The run starts at the turning angle ``start`` (rad from the assembly angle; default: where
    the loads resist least, e.g. the knives open).

    Parameters
    ----------
    mech : Mechanism
        A compiled mechanism with one crank (``linkwork.dynamics`` also takes a path, an example name or a Spec).
    drive : MotorGear, optional
        The motor and gear; default the file's ``machine:`` section.
    delta : float, optional
        The coefficient of speed fluctuation the flywheel is sized for, (max - min) / mean; default the file's.
    speed : float, optional
        The mean crank speed for the flywheel's size, rad/s.
    steps : int
        Equal steps of one turn of the reduced model; default 3600.
    omega0 : float
        The crank's angular speed at the start, rad/s; default 0 (a start from rest).
    start : float, optional
        The crank angle at the start, rad from the assembly angle.
    turns : int
        The most turns run to reach the steady cycle; default 500.

    Returns
    -------
    Dynamics
        The flywheel (inertia, kg m^2, on which shaft), the start-up and steady motion of the crank in time
        (angle, rad; speed, rad/s), the reached ``delta``, the mean and drive power (W).

    Raises
    ------
    LinkworkError
        Without a ``machine:`` section or ``drive``, or for a mechanism without one crank.

    Examples
    --------
    >>> import linkwork as lw
    >>> run = lw.dynamics("double-cut-shears", steps=360, turns=10)  # doctest: +SKIP
    >>> round(run.delta, 3)  # doctest: +SKIP
    0.05
    """
    if drive is None:
        drive = mech.motor_gear
    if drive is None:
        raise LinkworkError(
            'the mechanism has no motor for its dynamics: give a "machine:" section in its file with the motor '
            "(type constant, linear or induction, and its data), and the gear and flywheel if it has them"
        )
    if delta is None:
        delta = mech.delta
    red = reduced(mech, steps=steps)
    if start is None:
        start = float(red.psi[int(np.argmax(red.load))])
    fly = None
    if delta is not None:
        drive, fly = with_flywheel_for(red, drive, delta, speed, fallback=abs(float(mech.drive_speed[0])))
    process = [load for load in mech.loads if load.kind == "process"]
    if not process:
        motion = run_turns(red, drive, omega0=omega0, start=start, turns=turns)
        return Dynamics(red, drive, motion, fly, motion, CrankAngles.of(mech), mech.name)
    idle = dataclasses.replace(mech, loads=tuple(load for load in mech.loads if load.kind != "process"))
    startup = run_turns(reduced(idle, steps=steps), drive, omega0=omega0, start=start, turns=turns)
    motion = run_turns(
        red, drive, omega0=float(startup.omega[-1]), start=start + 2 * np.pi * len(startup.turns), turns=turns
    )
    return Dynamics(red, drive, motion, fly, startup, CrankAngles.of(mech), mech.name)
