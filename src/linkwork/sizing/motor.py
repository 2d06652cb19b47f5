"""The motor from a catalogue, its gear and flywheel, and the run of the machine with them.

The choice, for the crank speed ``omega_c`` of the file and a gear of efficiency ``eta``:

1. the mean power the motor must give over the steady cycle, ``P = -M_mean omega_c / eta`` (``M_mean``
   the mean reduced load moment, the work of the loads a turn over ``2 pi``);
2. the catalogue's motors in order of rated power (then mass); for each whose rated power covers ``P``:
   the gear ratio ``u = n_rated / n_crank``, the flywheel on the motor shaft for ``delta`` (the energy
   method of :func:`linkwork.machine.with_flywheel_for`, at the speed where the motor's moment balances
   the mean load), and the motor torque at the lowest crank speed ``omega_m (1 - delta / 2)``: the largest
   torque of the steady cycle, since the torque of a motor on the stable part of its characteristic grows as
   its speed falls.  The motor passes where that torque is at most ``reserve`` times its breakdown torque
   (``M_k = breakdown M_n``; the default 0.8 keeps the torque under the breakdown torque at a supply
   voltage 10 % low, as the torque goes with the voltage squared: 0.9^2 = 0.81);
3. the machine is then run with the motor (:func:`linkwork.machine.dynamics`: from rest to the steady
   cycle), and the run decides: the peak motor torque of the steady cycle under ``reserve M_k`` and the
   RMS torque over the cycle (the motor's heating, the equivalent-torque method) under the rated torque.
   A motor that fails the run gives way to the next in the order.  A choice is bounded: it runs the machine
   at most ``tries`` times and sizes at most :data:`SCREENS` flywheels (the motors beyond are named, not tried).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np

from linkwork.errors import LinkworkError
from linkwork.machine.drive import InductionMotor
from linkwork.machine.flywheel import Flywheel
from linkwork.machine.reduction import Reduced
from linkwork.machine.steady_cycle import Dynamics, dynamics, with_flywheel_for
from linkwork.sizing.common import COLUMNS, Catalogue, Table, bundled, read_catalogue
from linkwork.structure.model import Mechanism
from linkwork.structure.records import MotorGear

#: The columns of a motor catalogue, by name, with their SI units.
MOTOR_COLUMNS = COLUMNS["motors.csv"]

RPM = 30 / math.pi


def motor_catalogue(path: str | Path | Catalogue | None = None) -> Catalogue:
    """The bundled motor catalogue (``motors.csv``: typical values, see its comments), or a user's CSV file
    with the same columns (:data:`MOTOR_COLUMNS`, any units of the same kinds); a catalogue read already as it is."""
    if isinstance(path, Catalogue):
        return path
    if path is None:
        return bundled("motors.csv")
    return read_catalogue(path, MOTOR_COLUMNS)


def synchronous_problem(cat: Catalogue, synchronous: float) -> str | None:
    """Why no motor of ``cat`` has the synchronous speed ``synchronous`` (rad/s; as the choice matches it, to
    1e-3), naming the speeds it has; None where one has."""
    speeds = cat.columns["synchronous"]
    if np.any(np.isclose(speeds, synchronous, rtol=1e-3)):
        return None
    have = ", ".join(f"{v:.6g}" for v in np.unique(np.round(speeds * RPM, 6))[:20])
    return (
        f"no motor of the catalogue {cat.source} has a synchronous speed of {synchronous * RPM:.6g} rpm "
        f"(it has {have} rpm)"
    )


@dataclass(frozen=True)
class Candidate:
    """A motor of the catalogue as the choice saw it: its row, and why it was passed over ("" for the one chosen)."""

    name: str
    power: float
    why: str


@dataclass(frozen=True)
class MotorChoice:
    """The motor chosen from a catalogue, its gear and flywheel, and the run of the machine with them (SI).

    Attributes
    ----------
    name : str
        The catalogue's name of the motor.
    motor : dict
        Its catalogue row in SI (power W, synchronous and speed rad/s, starting and breakdown ratios,
        inertia kg m^2, mass kg).
    crank_speed : float
        The crank speed the gear is for (the file's drive speed), rad/s.
    ratio, efficiency : float
        The gear: motor speed over crank speed, ``n_rated / n_crank``, and its efficiency.
    reserve : float
        The share of the breakdown torque the peak torque may reach.
    delta : float
        The coefficient of speed fluctuation asked for.
    need_power : float
        The mean power the motor must give at its shaft over the steady cycle, W.
    flywheel : Flywheel
        The flywheel on the motor shaft for ``delta`` with this motor (its ``flywheel``, kg m^2).
    run : Dynamics
        The machine run with the motor, gear and flywheel from rest to its steady cycle.
    peak_torque : float
        The largest motor torque of the steady cycle (at its lowest speed), N m on the motor shaft.
    peak_phi_deg : float
        The crank angle from position 0 where it is, deg.
    rms_torque : float
        The RMS motor torque over the steady cycle in time, N m.
    passed : tuple of Candidate
        The motors before it in the order and why each was passed over.
    catalogue : str
        Where the catalogue came from.
    """

    name: str
    motor: dict[str, float]
    crank_speed: float
    ratio: float
    efficiency: float
    reserve: float
    delta: float
    need_power: float
    flywheel: Flywheel
    run: Dynamics
    peak_torque: float
    peak_phi_deg: float
    rms_torque: float
    passed: tuple[Candidate, ...] = field(default=())
    catalogue: str = "motors.csv"

    @property
    def rated_torque(self) -> float:
        """``P_n / omega_n``, N m."""
        return self.motor["power"] / self.motor["speed"]

    @property
    def breakdown_torque(self) -> float:
        """``breakdown * M_n``, N m."""
        return self.motor["breakdown"] * self.rated_torque

    @property
    def delta_reached(self) -> float:
        return self.run.delta

    @property
    def startup_time(self) -> float:
        return self.run.startup_time

    def table(self) -> Table:
        """The choice and the run, one quantity a row."""
        m = self.motor
        rows = [
            ("motor", self.name, ""),
            ("rated power", m["power"] / 1e3, "kW"),
            ("rated speed", m["speed"] * RPM, "rpm"),
            ("synchronous speed", m["synchronous"] * RPM, "rpm"),
            ("rated torque", self.rated_torque, "N m"),
            ("breakdown torque", self.breakdown_torque, "N m"),
            ("rotor inertia", m["inertia"], "kg m^2"),
            ("mass", m["mass"], "kg"),
            ("mean power needed at the motor shaft", self.need_power / 1e3, "kW"),
            ("load of the rating (mean power / rated)", self.need_power / m["power"], "1"),
            ("gear ratio (rated speed / crank speed)", self.ratio, "1"),
            ("gear efficiency", self.efficiency, "1"),
            ("flywheel on the motor shaft", self.flywheel.flywheel, "kg m^2"),
            ("delta asked", self.delta, "1"),
            ("delta of the run", self.delta_reached, "1"),
            ("start-up time", self.startup_time, "s"),
            ("peak motor torque of the steady cycle", self.peak_torque, "N m"),
            ("  at crank angle phi", self.peak_phi_deg, "deg"),
            ("peak / breakdown torque (allowed: reserve)", self.peak_torque / self.breakdown_torque, "1"),
            ("reserve", self.reserve, "1"),
            ("RMS motor torque (heating)", self.rms_torque, "N m"),
            ("RMS / rated torque (allowed: 1)", self.rms_torque / self.rated_torque, "1"),
        ]
        return Table("Motor, gear and flywheel", ("quantity", "value", "unit"), tuple(rows), "motor")

    def record(self) -> dict[str, Any]:
        """The JSON record: the motor (catalogue row in the units of the table), the gear, the flywheel,
        the run's figures and the motors passed over."""
        m = self.motor
        return {
            "catalogue": self.catalogue,
            "motor": {
                "name": self.name,
                "power_kW": m["power"] / 1e3,
                "speed_rpm": m["speed"] * RPM,
                "synchronous_rpm": m["synchronous"] * RPM,
                "starting_ratio": m["starting"],
                "breakdown_ratio": m["breakdown"],
                "inertia_kg_m2": m["inertia"],
                "mass_kg": m["mass"],
                "rated_torque_N_m": self.rated_torque,
                "breakdown_torque_N_m": self.breakdown_torque,
            },
            "need_power_kW": self.need_power / 1e3,
            "crank_speed_rpm": self.crank_speed * RPM,
            "gear": {"ratio": self.ratio, "efficiency": self.efficiency},
            "flywheel": {
                "inertia_kg_m2": self.flywheel.flywheel,
                "on": "motor",
                "on_crank_kg_m2": self.flywheel.on_crank,
            },
            "delta": self.delta,
            "reserve": self.reserve,
            "run": {
                "delta": self.delta_reached,
                "startup_time_s": self.startup_time,
                "steady": self.run.motion.steady,
                "crank_speed_mean_rpm": self.run.motion.last.omega_mean * RPM,
                "peak_torque_N_m": self.peak_torque,
                "peak_phi_deg": self.peak_phi_deg,
                "peak_over_breakdown": self.peak_torque / self.breakdown_torque,
                "rms_torque_N_m": self.rms_torque,
                "rms_over_rated": self.rms_torque / self.rated_torque,
            },
            "passed_over": [{"motor": c.name, "power_kW": c.power / 1e3, "why": c.why} for c in self.passed],
        }

    def machine_section(self) -> dict[str, Any]:
        """The file's ``machine:`` section for this motor, gear and flywheel (values with their units)."""
        m = self.motor
        return {
            "motor": {
                "type": "induction",
                "power": f"{m['power'] / 1e3:.6g} kW",
                "speed": f"{m['speed'] * RPM:.6g} rpm",
                "synchronous": f"{m['synchronous'] * RPM:.6g} rpm",
                "breakdown": float(f"{m['breakdown']:.6g}"),
                "inertia": f"{m['inertia']:.6g} kg*m^2",
                "torque": None,
                "stall": None,
                "no_load": None,
            },
            "gear": {"ratio": float(f"{self.ratio:.6g}"), "efficiency": float(f"{self.efficiency:.6g}")},
            "flywheel": {"inertia": f"{self.flywheel.flywheel:.6g} kg*m^2", "on": "motor"},
            "delta": float(f"{self.delta:.6g}"),
        }


def drive_of(row: dict[str, float], crank_speed: float, efficiency: float) -> MotorGear:
    """The drive of a catalogue row: the induction motor (Kloss), the gear from its rated speed to
    ``crank_speed``, its rotor, no flywheel yet (one goes on the motor shaft)."""
    motor = InductionMotor(row["power"], row["speed"], row["synchronous"], row["breakdown"])
    return MotorGear(
        motor, ratio=row["speed"] / crank_speed, efficiency=efficiency, rotor=row["inertia"], flywheel_on="motor"
    )


def quick_screen(
    red: Reduced, row: dict[str, float], crank_speed: float, efficiency: float, reserve: float, need: float
) -> str:
    """Why the motor of ``row`` cannot drive the machine, by what needs no flywheel ("" where that does not tell):
    its rated power under ``need``, or the mean torque of the load at its shaft (at its rated speed, the gear's
    ratio) over its rated torque or over ``reserve`` of its breakdown torque (the peak and the RMS torque are at
    least the mean)."""
    if row["power"] < need:
        return f"rated power {row['power'] / 1e3:.4g} kW under the mean power {need / 1e3:.4g} kW"
    mean = -red.mean_load / (row["speed"] / crank_speed * efficiency)
    rated = row["power"] / row["speed"]
    if mean > reserve * row["breakdown"] * rated:
        limit = reserve * row["breakdown"] * rated
        return f"its mean torque {mean:.4g} N m is over {reserve:g} x breakdown {limit:.4g} N m"
    if mean > rated:
        return f"its mean torque {mean:.4g} N m (a lower bound of the RMS torque) is over the rated {rated:.4g} N m"
    return ""


def screen(
    red: Reduced,
    row: dict[str, float],
    crank_speed: float,
    efficiency: float,
    delta: float,
    reserve: float,
    need: float,
) -> str:
    """Why the motor of ``row`` cannot drive the machine by the estimate of step 2 of the module ("" where it
    can): its rated power under ``need``, no speed where it balances the mean load, or its torque at the lowest
    speed of the cycle above ``reserve`` of its breakdown torque."""
    why = quick_screen(red, row, crank_speed, efficiency, reserve, need)
    if why:
        return why
    drive = drive_of(row, crank_speed, efficiency)
    try:
        drive, fly = with_flywheel_for(red, drive, delta, fallback=math.nan)
    except LinkworkError as exc:
        return str(exc)
    if not math.isfinite(fly.omega_mean):
        return "its torque nowhere balances the mean load"
    low = fly.omega_mean * (1 - delta / 2)
    torque = float(drive.motor(drive.ratio * low))
    limit = reserve * row["breakdown"] * row["power"] / row["speed"]
    s_k = drive.motor.critical_slip  # type: ignore[attr-defined]
    if 1 - drive.ratio * low / row["synchronous"] >= s_k:
        return "at the lowest speed of the cycle it is past its breakdown torque"
    if torque > limit:
        return f"torque at the lowest speed {torque:.4g} N m over {reserve:g} x breakdown {limit:.4g} N m"
    return ""


def choose_motor(
    mech: Mechanism,
    red: Reduced,
    delta: float,
    *,
    efficiency: float = 0.95,
    reserve: float = 0.8,
    catalogue: Catalogue | None = None,
    synchronous: float | None = None,
    progress: Callable[[int, int], None] | None = None,
) -> MotorChoice:
    """The smallest motor of ``catalogue`` (default: the bundled one) that drives ``mech`` (reduced
    quantities ``red``) with a flywheel for ``delta`` (see the module); ``synchronous`` (rad/s) keeps to
    motors of that synchronous speed.  At most :data:`TRIES` runs of the machine and :data:`SCREENS` flywheels sized;
    ``progress(k, n)`` is told of each motor ``k`` of the ``n`` looked at.

    Raises
    ------
    LinkworkError
        No motor of the catalogue will do (each one's reason in the message), or the mechanism has no crank speed.
    """
    if not 0 < reserve <= 1:
        raise LinkworkError(f"reserve: the share of the breakdown torque allowed, in (0, 1], got {reserve}")
    cat = catalogue if catalogue is not None else motor_catalogue()
    crank = abs(float(mech.drive_speed[0]))
    if not crank > 0:
        raise LinkworkError("the motor is chosen for the crank's speed: give the drive a speed in the file")
    need = -red.mean_load * crank / efficiency
    cols = cat.columns
    order = np.lexsort((cols["mass"], cols["power"]))
    if synchronous is not None:
        order = order[np.isclose(cols["synchronous"][order], synchronous, rtol=1e-3)]
    passed: list[Candidate] = []
    runs = screened = 0
    for k, i in enumerate(map(int, order)):
        if progress is not None:
            progress(k, len(order))
        row = cat.row(i)
        why = quick_screen(red, row, crank, efficiency, reserve, need)
        if why == "" and (runs >= TRIES or screened >= SCREENS):
            left = len(order) - k
            raise LinkworkError(_none_drives(cat, need, delta, reserve, passed, left, TRIES if runs >= TRIES else None))
        if why == "":
            screened += 1
            why = screen(red, row, crank, efficiency, delta, reserve, need)
        if why == "":
            runs += 1
            choice = _run(mech, row, cat.names[i], _Duty(crank, efficiency, delta, reserve, need, None))
            why = _fails(choice)
            if why == "":
                return _with(choice, tuple(passed), cat.source)
        if row["power"] >= need:
            passed.append(Candidate(cat.names[i], row["power"], why))
    raise LinkworkError(_none_drives(cat, need, delta, reserve, passed, 0, None))


#: Motors screened with their flywheel at most in one choice (each takes about a second): those beyond are named.
SCREENS = 40
#: Runs of the machine with a motor and its flywheel at most in one choice (:func:`choose_motor`).
TRIES = 12


def _none_drives(
    cat: Catalogue, need: float, delta: float, reserve: float, passed: list[Candidate], left: int, tries: int | None
) -> str:
    """Why no motor of ``cat`` was chosen: the first of those passed over with their reasons, and how many were
    left unscreened (``left``) because ``tries`` runs, or :data:`SCREENS` screens, were spent."""
    reasons = "\n".join(f"  {c.name}: {c.why}" for c in passed[:12])
    more = f"\n  ... and {len(passed) - 12:,} more passed over" if len(passed) > 12 else ""
    if left:
        spent = f"{tries} runs of the machine" if tries is not None else f"{SCREENS} motors screened with a flywheel"
        more += (
            f"\n  {left:,} larger motors of the catalogue not tried: {spent} is the most a choice makes "
            "(narrow the catalogue, or keep to one speed with --synchronous)"
        )
    return (
        f"no motor of the catalogue {cat.source} drives the machine (mean power {need / 1e3:.4g} kW at the motor "
        f"shaft, delta {delta:g}, peak torque at most {reserve:g} x breakdown)"
        + (f":\n{reasons}{more}" if passed or left else "")
    )


def _with(choice: MotorChoice, passed: tuple[Candidate, ...], source: str) -> MotorChoice:
    import dataclasses

    return dataclasses.replace(choice, passed=passed, catalogue=source)


def _fails(choice: MotorChoice) -> str:
    """Why the run of ``choice`` fails it ("" where it passes)."""
    limit = choice.reserve * choice.breakdown_torque
    if choice.peak_torque > limit:
        return f"the run's peak torque {choice.peak_torque:.4g} N m is over {choice.reserve:g} x breakdown"
    if choice.rms_torque > choice.rated_torque:
        return f"the run's RMS torque {choice.rms_torque:.4g} N m is over the rated {choice.rated_torque:.4g} N m"
    return ""


class _Duty(NamedTuple):
    """What the choice asks of every motor it runs: the crank's speed (rad/s), the gear's efficiency, the
    coefficient of speed fluctuation, the reserve of the breakdown torque, the mean power needed (W) and the
    steps of the run (None: the default)."""

    crank: float
    efficiency: float
    delta: float
    reserve: float
    need: float
    steps: int | None


def _run(mech: Mechanism, row: dict[str, float], name: str, duty: _Duty) -> MotorChoice:
    """Run the machine with the motor of ``row`` and its flywheel for the duty's ``delta``, and read the run."""
    crank, efficiency, delta, reserve, need, steps = duty
    from linkwork.limits import DYNAMICS_STEPS
    from linkwork.motion.analysis import CrankAngles

    drive = drive_of(row, crank, efficiency)
    run = dynamics(mech, drive, delta=delta, steps=steps or DYNAMICS_STEPS)
    assert run.flywheel is not None
    t, psi, omega = run.motion.cycle()
    torque = np.asarray(run.drive.motor(run.drive.ratio * omega), dtype=float)
    rms = math.sqrt(float(np.trapezoid(torque**2, t)) / float(t[-1]))
    low = run.motion.last.omega_min  # refined between the samples
    peak = max(float(run.drive.motor(run.drive.ratio * low)), float(torque.max()))
    i = int(np.argmax(torque))
    angles = CrankAngles.of(mech)
    sign = float(np.sign(mech.drive_speed[0]) or 1.0)
    drive_angle = float(run.reduced.angle[0]) + sign * (run.motion.cycle_start + float(psi[i]))
    phi = float(angles.phi(drive_angle)) if angles is not None else math.nan
    ratio = row["speed"] / crank
    return MotorChoice(name, row, crank, ratio, efficiency, reserve, delta, need, run.flywheel, run, peak, phi, rms)
