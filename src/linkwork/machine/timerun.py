"""``linkwork.simulate``: the machine unit run in time from any state, forward or back.

The state is the crank's drive angle ``phi`` (rad, the file's drive coordinate) and its speed
``omega = dphi/dt`` (rad/s, either sign).  At every step the exact kinematics of that one pose gives the
reduced inertia and its slope and the reduced moment of the loads (no table, no interpolation):

    J(phi)       = sum m_i |dr_Ci/dphi|^2 + J_Ci (dtheta_i/dphi)^2             (+ the drive's inertia)
    J'(phi)      = 2 sum m_i dr_Ci/dphi . d2r_Ci/dphi2 + J_Ci dtheta_i/dphi d2theta_i/dphi2
    Q(phi, w)    = sum F . dr_P/dphi + M dtheta/dphi      (gravity and every load at the true speed w:
                                                            springs, dampers, friction, process loads;
                                                            the steady cycle's formula: reduction.load_moment)
    J phi'' + J' phi'^2 / 2 = Q(phi, phi') + M_d(phi')

``M_d`` the motor's moment (:class:`~linkwork.structure.records.MotorGear`, in the drive's direction of rotation),
none without a motor.  Integrated by SciPy's ``solve_ivp`` (DOP853) with the tolerances asked, so the
crank may slow down, stop and turn back; its stops are events.  The samples asked for come from the
solver's dense output, and their kinematics and loads from the true state (speed and angular
acceleration of the run, not a steady speed).

What happens at a stop.  The loads that resist motion, a Coulomb friction and a process load while its
tools close on the workpiece, change with the sense of the speed: ``Q(phi, 0+) = Q0 + R+`` and
``Q(phi, 0-) = Q0 + R-`` with ``R+ <= 0 <= R-`` (``Q0`` gravity, springs and the position's loads).  At rest
they are reactions that take what the rest gives, up to their size (static friction, a knife standing in the
billet).  So with ``M0 = M_d(0)`` the motor's stall moment, a crank at rest at ``phi``

- moves forward where ``Q0 + R+ + M0 > 0`` (the drive overcomes the resistance of moving forward),
- moves back where ``Q0 + R- + M0 < 0``,
- and otherwise stays at rest: ``phi'' = 0`` is the only motion the loads allow (a speed of either sign would
  be braked at once).  Nothing in the equation depends on time, so it stays at rest to the end of the run
  (the ``held`` event), the motor stalled at ``M0``.  The double-cut shears started in the cut from rest is
  such a case: 995 N m at the crank from the motor at rest against 29,000 N m of the cut.

Each stretch between stops is integrated with the loads of its own sense of motion (their limit at rest
from that side where the integrator's trial speed passes zero), up to the next stop as a terminal event.

The run is bounded (:mod:`linkwork.limits`): its length by ``MAX_RUN_TIME``, its work by
``MAX_RUN_EVALUATIONS`` exact poses, counted as it goes and estimated before it starts from the fastest rate of
the loads (:func:`fastest_rate`: a stiff spring or damper makes the crank's motion fast, and an explicit
integrator follows it); a run that would pass the bound is refused with that reason before the work.

A change point reached on the way (a dyad whose normalised Jacobian determinant, the sine of its
transmission angle, comes to zero: its two assembly modes meet there) is an event too: found among the
solver's steps and their midpoints as a dip of the determinant, and refined on the dense output to where it
is least; reported where that least value is within :data:`~linkwork.motion.kernels.CLOSE` of zero.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from linkwork.errors import LinkworkError
from linkwork.kinetostatics.reactions import inertia_and_gravity
from linkwork.machine.integration import IntegrationEvent, integrate
from linkwork.machine.reduction import cycle_of, poses, reduced_terms, terms_of_both, unit_and_true_speeds
from linkwork.motion.kinematic_analysis import Kinematics
from linkwork.structure.model import Mechanism, one_crank
from linkwork.units import turn_deg

if TYPE_CHECKING:
    from linkwork.kinetostatics.reaction_forces import Forces
    from linkwork.structure.records import MotorGear

#: Samples of a run where no times are asked for.
RUN_SAMPLES = 201


@dataclass(frozen=True)
class RunEvent:
    """Something that happened in a run, at ``time`` (s) and drive angle ``angle`` (rad): ``kind`` ``stop``
    (the crank's speed passes zero: it stops and turns back, or goes on the same way), ``held`` (at rest, the
    crank stays there to the end of the run: ``detail`` says why) or ``change-point`` (the dyad ``group``, e.g.
    ``II(2,3) RRP``, on a singular position: its two assembly modes meet)."""

    kind: str
    time: float
    angle: float
    group: str = ""
    detail: str = ""

    def as_dict(self) -> dict[str, Any]:
        out: dict[str, Any] = {"kind": self.kind, "time_s": self.time, "angle_deg": math.degrees(self.angle)}
        if self.group:
            out["group"] = self.group
        if self.detail:
            out["detail"] = self.detail
        return out

    def describe(self) -> str:
        """The event as the CLI prints it (the angle to x in degrees)."""
        where = f"at {self.time:.6g} s, at {turn_deg(self.angle, 4):.4f} deg to x"
        if self.kind == "stop":
            return f"the crank stops {where}"
        if self.kind == "held":
            at = f"{turn_deg(self.angle, 4):.4f} deg to x"
            return f"the crank is held at rest from {self.time:.6g} s on, at {at}: {self.detail}"
        return f"change point of group {self.group} {where}"


@dataclass(frozen=True)
class Run:
    """A run in time.

    Attributes
    ----------
    time : ndarray (K,)
        The times asked for, s.
    angle, speed, acceleration : ndarray (K,)
        The crank's drive angle (rad), speed (rad/s) and angular acceleration (rad/s^2).
    kinematics : Kinematics
        Every link and point at the K samples with the run's speed and acceleration (``angle(link)``,
        ``omega(link)``, ``epsilon(link)``, ``position(point)``...).
    events : tuple of RunEvent
    drive_moment : ndarray (K,)
        The motor's moment on the crank, N m (zero without one).
    rtol, atol : float
        The integrator's tolerances (``atol`` in rad and rad/s).
    evaluations : int
        The right-hand side's evaluations: one exact kinematic solution each.
    """

    time: np.ndarray
    angle: np.ndarray
    speed: np.ndarray
    acceleration: np.ndarray
    kinematics: Kinematics
    events: tuple[RunEvent, ...]
    drive_moment: np.ndarray
    rtol: float
    atol: float
    evaluations: int

    @property
    def mechanism(self) -> Mechanism:
        return self.kinematics.mechanism

    def forces(self) -> Forces:
        """Joint reactions and the drive's torque along the run (:func:`linkwork.forces_of`), with the run's
        own speed and angular acceleration at each sample."""
        from linkwork.kinetostatics.reaction_forces import forces_of

        return forces_of(self.kinematics)

    def kinetic_energy(self) -> np.ndarray:
        """Kinetic energy of the links (J) ``(K,)``, the drive's rotating parts not included."""
        loads = inertia_and_gravity(self.kinematics)
        ms = self.kinematics.mass_properties
        vc, w = loads.com_velocity[0], self.kinematics.vel[0, :, :, 2]
        return 0.5 * np.sum(ms.mass[0] * np.sum(vc * vc, -1) + ms.inertia[0] * w * w, -1)


def simulate(
    mech: Mechanism,
    until: float,
    *,
    angle: float | None = None,
    speed: float = 0.0,
    times: npt.ArrayLike | None = None,
    drive: MotorGear | None = None,
    motor: bool = True,
    rtol: float = 1e-10,
    atol: float = 1e-10,
    progress: Callable[[float], None] | None = None,
) -> Run:
    """Run the machine unit from the state ``(angle, speed)`` for ``until`` seconds.

    Parameters
    ----------
    mech : Mechanism
        One crank (a revolute drive); ``linkwork.simulate`` also takes a path, an example name or a Spec.
    until : float
        Length of the run, s, at most :data:`~linkwork.limits.MAX_RUN_TIME`.
    angle : float, optional
        The crank's drive angle at the start, rad (the file's convention: counter-clockwise from +x);
        default its assembly angle.
    speed : float
        Its speed at the start, rad/s, counter-clockwise positive; default at rest.
    times : array_like, optional
        Times (s, within ``[0, until]``) of the samples kept; default :data:`RUN_SAMPLES` equal steps.
    drive : MotorGear, optional
        The motor, gear and flywheel; default the file's ``machine:``.  ``motor=False``: none (free motion
        under the loads and springs).
    motor : bool, default True
        Drive the crank by the motor (``drive`` or the file's); False: the machine moves freely under its loads
        and springs from ``(angle, speed)``.
    rtol, atol : float
        The integrator's tolerances (``atol`` in rad and rad/s).
    progress : callable, optional
        Called with the time (s) the run has reached as it goes, for a progress bar.

    Returns
    -------
    Run
        ``time`` (s), the crank's ``angle`` (rad) and ``speed`` (rad/s) at each step, and the ``events``
        (stops, reversals) on the way.

    Raises
    ------
    LinkworkError
        For a run past the bounds of :mod:`linkwork.limits`: its length; its work, estimated from the loads'
        stiffness before it starts (:func:`fastest_rate`) and counted as it goes.  Where the run reaches a pose
        that does not assemble.

    Examples
    --------
    >>> import linkwork as lw
    >>> run = lw.simulate("four-bar", 0.5)  # doctest: +SKIP
    >>> float(run.time[-1])  # doctest: +SKIP
    0.5
    """
    from linkwork.limits import run_time_problem

    if not one_crank(mech):
        raise LinkworkError("a run in time needs one crank (a revolute drive)")
    problem = run_time_problem(until, "until")
    if problem:
        raise LinkworkError(problem)
    drive = (drive if drive is not None else mech.motor_gear) if motor else None
    unit = _Unit(mech, drive, until, progress, cycle_of(mech))
    unit.atol = atol
    phi0 = float(mech.drive_start[0]) if angle is None else float(angle)
    grid = np.linspace(0.0, until, RUN_SAMPLES) if times is None else np.asarray(times, dtype=float).ravel()
    if grid.size == 0 or grid.min() < 0 or grid.max() > until * (1 + 1e-12):
        raise LinkworkError(f"times: expected times within [0, {until:g}] s")
    if speed or unit.at_rest(phi0)[0]:  # a crank held at rest from the start costs nothing
        _refuse_stiff(unit, phi0, float(speed), until, rtol)
    pieces, stops = _integrate(unit, phi0, float(speed), rtol, atol)
    y, eps, md = _samples(unit, pieces, grid)
    kin = poses(unit.cycle, y[0][:, None], y[1][:, None], eps[:, None])
    steps = np.unique(np.concatenate([p.steps for p in pieces]))
    events = tuple(sorted(stops + _change_points(unit.cycle, steps, _Dense(pieces)), key=lambda e: e.time))
    return Run(grid, y[0], y[1], eps, kin, events, md, rtol, atol, unit.evaluations)


#: Speed (rad/s) at which the loads of one direction of motion are taken at rest: their limit as the speed goes
#: to zero from that side (the sense of a friction, whether a process load's tools close), a damper's share
#: 1e-150 of its coefficient.
CREEP = 1e-150


class _Unit:
    """The machine unit's equation of motion ``J phi'' + J' phi'^2 / 2 = Q(phi, phi') + M_d(phi')`` with the loads
    of one direction of motion at a time, and the work it has done (the evaluations, each one exact pose)."""

    def __init__(
        self,
        mech: Mechanism,
        drive: MotorGear | None,
        until: float,
        progress: Callable[[float], None] | None,
        cycle: Kinematics,
    ) -> None:
        self.mech, self.drive, self.until, self.progress = mech, drive, until, progress
        self.cycle = cycle  # whose assembly modes the run keeps to (:func:`poses`)
        self.atol = 1e-10  # rad: the run's (:func:`simulate` sets it)
        self.sense = -1.0 if mech.drive_speed[0] < 0 else 1.0
        self.extra = drive.inertia if drive is not None else 0.0
        self.evaluations = 0
        self.shown = 0.0

    def moment(self, omega: np.ndarray) -> np.ndarray:
        """The motor's moment on the crank (N m) at the speeds ``omega`` (rad/s), zero without one."""
        if self.drive is None:
            return np.zeros_like(omega)
        return self.sense * np.asarray(self.drive.moment(self.sense * omega), dtype=float)

    def acceleration(self, phi: np.ndarray, omega: np.ndarray, direction: np.ndarray) -> np.ndarray:
        """``phi''`` (rad/s^2) at the states ``(phi, omega)`` ``(K,)`` moving in ``direction`` (+1 or -1): the loads
        at the speed itself where it goes that way, else at their limit at rest from that side (:data:`CREEP`)."""
        speed = np.where(direction * omega > 0, omega, direction * CREEP)
        terms = reduced_terms(self.mech, phi, speed, self.extra, self.cycle)
        if not (terms.inertia > 0).all():
            where = turn_deg(float(phi[np.flatnonzero(~(terms.inertia > 0))[0]]))
            raise LinkworkError(
                f"the crank carries no inertia at {where:.6g} deg to x: give the links' masses "
                "(and moments of inertia) for a run in time"
            )
        return (terms.load + self.moment(omega) - 0.5 * terms.slope * omega**2) / terms.inertia

    def rhs(self, direction: int) -> Callable[[float, np.ndarray], list[float]]:
        """The right-hand side of ``(phi, omega)`` moving in ``direction``, counting its work against
        :data:`~linkwork.limits.MAX_RUN_EVALUATIONS`."""
        from linkwork.limits import MAX_RUN_EVALUATIONS

        way = np.array([float(direction)])

        def f(t: float, y: np.ndarray) -> list[float]:
            self.evaluations += 1
            if self.evaluations > MAX_RUN_EVALUATIONS:
                raise LinkworkError(
                    f"the run in time stops at {t:.6g} s of {self.until:.6g} s: it has taken {MAX_RUN_EVALUATIONS:,} "
                    "exact poses, the bound on a run's work; ask for a shorter run"
                )
            if self.progress is not None and t > self.shown + 0.002 * self.until:
                self.shown = t
                self.progress(t)
            return [float(y[1]), float(self.acceleration(y[:1], y[1:], way)[0])]

        return f

    def at_rest(self, phi: float) -> tuple[int, float, float]:
        """Which way the crank at rest at ``phi`` moves: +1 where the moment of the motor at rest and of the loads
        moving forward turns it forward, -1 where that of moving back turns it back, 0 where neither (the loads
        that resist motion, a process load or a friction, hold it: at rest they take what the others give, up
        to their size; or it is in equilibrium); with those two moments (N m).  An acceleration that would not
        move the crank by :attr:`atol` (rad) over the whole run (``a T^2 / 2``), or that is within 1e-12 of those
        the loads give 0.01 rad either side, is none: the rounding of a balance (a pendulum hanging down) starts
        nothing."""
        pose = np.array([phi, phi, phi - 0.01, phi + 0.01])
        forward, back, *near = self.acceleration(pose, np.zeros(4), np.array([1.0, -1.0, 1.0, 1.0]))
        span = max(self.until, 1e-100)  # a run shorter than that (1e-300 s) moves nothing; its square is no zero
        least = max(2 * self.atol / span**2, 1e-12 * max(abs(near[0]), abs(near[1])))
        j = reduced_terms(self.mech, pose[:1], np.zeros(1), self.extra, self.cycle).inertia[0]
        way = 1 if forward > least else -1 if back < -least else 0
        return way, float(forward * j), float(back * j)


@dataclass(frozen=True)
class _Piece:
    """A stretch of the run from ``start`` to ``end`` (s): moving in ``direction`` (+1, -1) by the solver's dense
    output ``dense`` with its ``steps`` (s) and its last state ``final`` from its last step; or held at rest
    (``direction`` 0) at the angle ``final[0]``."""

    start: float
    end: float
    direction: int
    final: np.ndarray
    dense: Any = None
    steps: np.ndarray = field(default_factory=lambda: np.zeros(0))

    def state(self, t: np.ndarray) -> np.ndarray:
        """``(phi, omega)`` ``(2, K)`` at the times ``t`` ``(K,)`` within the piece, its end from the solver's step."""
        if self.dense is None:
            return np.stack([np.full(len(t), self.final[0]), np.zeros(len(t))])
        y = np.asarray(self.dense(t), dtype=float).reshape(2, -1)
        y[:, t >= self.end] = self.final[:, None]
        return y


class _Dense:
    """The state of a run of several pieces at any time (``(2,)`` for a scalar, ``(2, K)`` for ``K`` times)."""

    def __init__(self, pieces: list[_Piece]) -> None:
        self.pieces = pieces
        self.starts = np.array([p.start for p in pieces])

    def __call__(self, t: Any) -> np.ndarray:
        times = np.atleast_1d(np.asarray(t, dtype=float))
        which = np.clip(np.searchsorted(self.starts, times, side="right") - 1, 0, len(self.pieces) - 1)
        out = np.empty((2, len(times)))
        for i in np.unique(which):
            sel = which == i
            out[:, sel] = self.pieces[i].state(times[sel])
        return out[:, 0] if np.ndim(t) == 0 else out


def _integrate(unit: _Unit, phi: float, omega: float, rtol: float, atol: float) -> tuple[list[_Piece], list[RunEvent]]:
    """The run as pieces between the crank's stops, and the stops.

    The loads that resist motion (a friction, a process load while its tools close) change with the sense of the
    speed, so the equation has no solution through a stop as one smooth right-hand side (an integrator steps on
    there with shrinking steps and the time does not advance).  So each piece moves one way, with the loads of
    that way, up to the next stop (a terminal event); at a stop :meth:`_Unit.at_rest` says which way the next goes,
    or that the crank stays at rest for the rest of the run: nothing in the equation depends on time, so a crank
    held at rest once is held to the end (an ``held`` event saying by how much the drive falls short)."""
    pieces: list[_Piece] = []
    stops: list[RunEvent] = []
    t = 0.0
    while t < unit.until:
        direction = (1 if omega > 0 else -1) if omega != 0 else unit.at_rest(phi)[0]
        if direction == 0:
            pieces.append(_Piece(t, unit.until, 0, np.array([phi, 0.0]), steps=np.array([t])))
            stops.append(_held(unit, t, phi))
            break
        stop = IntegrationEvent("stop", lambda _t, y: float(y[1]), -direction)
        sol = integrate(unit.rhs(direction), (t, unit.until), [phi, omega], rtol=rtol, atol=atol, events=stop)
        if sol.status < 0:
            raise LinkworkError(f"the run in time failed at {float(sol.t[-1]):.6g} s: {sol.message}")
        pieces.append(_Piece(t, float(sol.t[-1]), direction, sol.y[:, -1].copy(), sol.sol, sol.t))
        if sol.status != 1:
            break
        t, phi, omega = float(sol.t[-1]), float(sol.y[0, -1]), 0.0
        stops.append(RunEvent("stop", t, phi))
    return pieces, stops


def _held(unit: _Unit, t: float, phi: float) -> RunEvent:
    """The event of a crank held at rest from ``t`` at ``phi``, saying the moments that fall short."""
    _, forward, back = unit.at_rest(phi)
    stall = float(unit.moment(np.zeros(1))[0])
    why = (
        f"with the motor's moment at rest ({stall:.6g} N m) the loads leave {forward:.6g} N m to move it forward and "
        f"{back:.6g} N m to move it back: "
    )
    why += "what resists motion (a process load, a friction) holds it" if forward < 0 < back else "they balance there"
    return RunEvent("held", t, phi, detail=why)


#: Evaluations of the equation of motion per radian of phase of the run's fastest motion at ``rtol`` 1e-10 (DOP853:
#: measured 55 to 63 on a pendulum's swings and on a slider-crank's against springs of 4e3 to 1e6 N/m; they grow
#: as ``rtol ** (-1 / 8)``, the order of the method).
PER_RADIAN = 60.0


def fastest_rate(
    mech: Mechanism, phi: float, extra_inertia: float = 0.0, cycle: Kinematics | None = None
) -> tuple[float, float]:
    """The fastest rate (1/s) of small motions of the machine unit over a turn of the crank from ``phi`` (rad), and
    the drive angle (rad) where it is: ``sqrt(|k| / J)`` with ``k = -dQ/dphi`` the stiffness of the loads at rest
    reduced to the crank (N m/rad: springs, gravity, the position's loads; not a process load nor a friction, which
    only take energy), and ``c / J`` with ``c = -dQ/domega`` the dampers' (N m s/rad); poses that do not assemble
    are left out."""
    n = 72
    phis = phi + np.linspace(0.0, 2 * math.pi, n, endpoint=False)
    h = 1e-5
    angles = np.concatenate([phis - h, phis + h, phis, phis])
    speeds = np.repeat([0.0, 0.0, 1.0, 2.0], n)  # the stiffness at rest: a resistance to motion springs nothing back
    kin = unit_and_true_speeds(mech, angles, speeds, cycle)
    with np.errstate(all="ignore"):
        terms = terms_of_both(kin, 4 * n, extra_inertia)
        q = terms.load.reshape(4, n)
        j = terms.inertia.reshape(4, n)[2]
        k = -(q[1] - q[0]) / (2 * h)
        c = -(q[3] - q[2])
        rate = np.maximum(np.sqrt(np.abs(k) / j), np.abs(c) / j)
    ok = kin.valid_all[0, : 4 * n].reshape(4, n).all(0) & kin.valid_all[0, 4 * n :].reshape(4, n).all(0)
    ok &= np.isfinite(rate) & (j > 0)
    if not ok.any():
        return 0.0, phi
    i = int(np.argmax(np.where(ok, rate, -1.0)))
    return float(rate[i]), float(phis[i])


def _refuse_stiff(unit: _Unit, phi: float, speed: float, until: float, rtol: float) -> None:
    """Refuse, before the work, a run whose fastest motion (:func:`fastest_rate`, or the speed at the start) would
    take more than :data:`~linkwork.limits.MAX_RUN_EVALUATIONS` exact poses to follow for ``until`` s.

    A stiff spring is no stiff equation here: the crank's one degree of freedom is what it moves, so its fast
    motion is the run itself, and an implicit (stiff) method would have to follow it to the tolerances just the
    same, or damp it away, which would be wrong.  So such a run is refused, naming the bound and the longest run
    within it."""
    from linkwork.limits import MAX_RUN_EVALUATIONS

    rate, at = fastest_rate(unit.mech, phi, unit.extra, unit.cycle)
    per_second = max(rate, abs(speed)) * PER_RADIAN * (1e-10 / min(rtol, 1e-10)) ** 0.125
    need = until * per_second
    if need <= MAX_RUN_EVALUATIONS:
        return
    elements = [load.name for load in unit.mech.loads if load.kind in ("spring", "damper", "torsion_spring")]
    if abs(speed) > rate:
        why, other = f"the speed at the start, {abs(speed):.4g} rad/s,", "a lower speed"
    else:
        named = f" (its force elements: {', '.join(elements)})" if elements else ""
        where = f"{rate:.4g} rad/s (at {turn_deg(at):.4g} deg to x)"
        why = f"the loads{named} reduced to the crank make its fastest motion {where},"
        other = "a softer spring or damper"
    raise LinkworkError(
        f"a run of {until:.6g} s is past the bound on a run's work: {why} about {need:,.0f} exact poses to follow, "
        f"more than {MAX_RUN_EVALUATIONS:,}; ask for at most {MAX_RUN_EVALUATIONS / per_second:.3g} s, or {other}"
    )


def _samples(unit: _Unit, pieces: list[_Piece], grid: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The state ``(2, K)``, the angular acceleration ``(K,)`` (rad/s^2; zero where held) and the motor's moment
    ``(K,)`` (N m) at the times ``grid``; a sample at a stop belongs to the piece after it."""
    y = _Dense(pieces)(grid)
    way = np.array([p.direction for p in pieces], dtype=float)[
        np.clip(np.searchsorted([p.start for p in pieces], grid, side="right") - 1, 0, len(pieces) - 1)
    ]
    eps = np.zeros(len(grid))
    moving = way != 0
    if moving.any():
        eps[moving] = unit.acceleration(y[0, moving], y[1, moving], way[moving])
    return y, eps, unit.moment(y[1])


#: A dip of a dyad's determinant among the solver's steps below this is refined (:func:`_change_points`).
DIP = 0.5


def _change_points(cycle: Kinematics, steps: np.ndarray, dense: Any) -> list[RunEvent]:
    """Change points along a run of the mechanism of ``cycle`` (:func:`poses`): the solver's ``steps`` (s) and the
    ``dense`` output ``t -> (phi, omega)``.

    Each dyad's determinant (:attr:`Kinematics.step_det`, zero where its assembly modes meet) is looked at
    on the steps and their midpoints; each local least value below :data:`DIP` is refined by a bounded
    minimisation over time between its neighbours, and is a change point where it is within
    :data:`~linkwork.motion.kernels.CLOSE` of zero."""
    from scipy.optimize import minimize_scalar

    from linkwork.motion.groups import KINDS
    from linkwork.motion.kernels import CLOSE

    mech = cycle.mechanism
    dyads = [i for i, step in enumerate(mech.program) if KINDS[step.kind].transmission]
    if not dyads or len(steps) < 2:
        return []

    def det(t: np.ndarray) -> np.ndarray:
        phi = dense(t)[0][:, None]
        kin = poses(cycle, phi, np.ones_like(phi), np.zeros_like(phi))
        return np.abs(np.stack([kin.step_det[i][0] for i in dyads]))  # (dyads, K)

    t = np.sort(np.concatenate([steps, 0.5 * (steps[1:] + steps[:-1])]))
    d = det(t)
    found: list[RunEvent] = []
    for row, k in zip(d, dyads, strict=True):
        dips = np.flatnonzero((row[1:-1] <= row[:-2]) & (row[1:-1] <= row[2:]) & (row[1:-1] < DIP)) + 1
        for i in dips:
            best = minimize_scalar(
                lambda x, k=k: float(det(np.array([x]))[dyads.index(k), 0]),
                bounds=(t[i - 1], t[i + 1]),
                method="bounded",
                options={"xatol": 1e-14},
            )
            if best.fun < CLOSE and not any(
                e.group == mech.program[k].label and abs(e.time - best.x) < 1e-9 for e in found
            ):
                found.append(RunEvent("change-point", float(best.x), float(dense(best.x)[0]), mech.program[k].label))
    return found
