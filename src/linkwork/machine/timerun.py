"""``linkwork.simulate``: the machine unit run in time from any state, forward or back.

The state is the crank's drive angle ``phi`` (rad, the file's drive coordinate) and its speed
``omega = dphi/dt`` (rad/s, either sign).  At every step the exact kinematics of that one pose gives the
reduced inertia and its slope and the reduced moment of the loads (no table, no interpolation):

    J(phi)       = sum m_i |dr_Ci/dphi|^2 + J_Ci (dtheta_i/dphi)^2             (+ the drive's inertia)
    J'(phi)      = 2 sum m_i dr_Ci/dphi . d2r_Ci/dphi2 + J_Ci dtheta_i/dphi d2theta_i/dphi2
    Q(phi, w)    = sum F . dr_P/dphi + M dtheta/dphi      (gravity and every load at the true speed w:
                                                            springs, dampers, friction, process loads)
    J phi'' + J' phi'^2 / 2 = Q(phi, phi') + M_d(phi')

``M_d`` the motor's moment (:class:`~linkwork.structure.records.MotorGear`, in the drive's direction of rotation),
none without a motor.  Integrated by SciPy's ``solve_ivp`` (DOP853) with the tolerances asked, so the
crank may slow down, stop and turn back; its stops are events.  The samples asked for come from the
solver's dense output, and their kinematics and loads from the true state (speed and angular
acceleration of the run, not a steady speed).

A change point reached on the way (a dyad whose normalised Jacobian determinant, the sine of its
transmission angle, comes to zero: its two assembly modes meet there) is an event too: found among the
solver's steps and their midpoints as a dip of the determinant, and refined on the dense output to where it
is least; reported where that least value is within :data:`~linkwork.motion.kernels.CLOSE` of zero.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from linkwork.errors import LinkworkError
from linkwork.kinetostatics.reactions import inertia_and_gravity
from linkwork.motion.kinematic_analysis import Kinematics, kinematics_at
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
    (the crank's speed passes zero: it stops and turns back, or stays) or ``change-point`` (the dyad
    ``group``, e.g. ``II(2,3) RRP``, on a singular position: its two assembly modes meet)."""

    kind: str
    time: float
    angle: float
    group: str = ""

    def as_dict(self) -> dict[str, Any]:
        out: dict[str, Any] = {"kind": self.kind, "time_s": self.time, "angle_deg": math.degrees(self.angle)}
        if self.group:
            out["group"] = self.group
        return out

    def describe(self) -> str:
        """The event as the CLI prints it (the angle to x in degrees)."""
        where = f"at {self.time:.6g} s, at {turn_deg(self.angle, 4):.4f} deg to x"
        if self.kind == "stop":
            return f"the crank stops {where}"
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


@dataclass(frozen=True)
class _Terms:
    """``J`` (kg m^2, the drive's included), ``J'`` (kg m^2/rad) and ``Q`` (N m), each ``(K,)``."""

    inertia: np.ndarray
    slope: np.ndarray
    load: np.ndarray


def reduced_terms(mech: Mechanism, phi: np.ndarray, omega: np.ndarray, extra_inertia: float = 0.0) -> _Terms:
    """The reduced inertia, its slope and the loads' reduced moment at the states ``(phi, omega)`` ``(K,)``,
    from one kinematic solution of the 2K samples: each pose at unit speed (the transfer functions) and at
    its true speed (the loads: a damper's force, a friction's sense).

    Raises
    ------
    LinkworkError
        Where a pose does not assemble, or a load has no value there (a spring whose points meet).
    """
    k = len(phi)
    angles = np.concatenate([phi, phi])[:, None]
    speeds = np.concatenate([np.ones(k), omega])[:, None]
    kin = kinematics_at(mech, angles, speeds, np.zeros((2 * k, 1)))
    if not kin.valid_all.all():
        bad = float(phi[np.flatnonzero(~kin.valid_all[0, :k] | ~kin.valid_all[0, k:])[0]])
        raise LinkworkError(
            f"the run reaches a pose where the mechanism does not assemble: crank at "
            f"{turn_deg(bad):.6g} deg to x (a dead point, or past the end of its travel)"
        )
    loads = inertia_and_gravity(kin)
    ms = kin.mass_properties
    m, j = ms.mass[0], ms.inertia[0]
    vc, ac = loads.com_velocity[0, :k], loads.com_acceleration[0, :k]
    w, e = kin.vel[0, :k, :, 2], kin.acc[0, :k, :, 2]
    inertia = np.sum(m * np.sum(vc * vc, -1) + j * w * w, -1) + extra_inertia
    slope = 2 * np.sum(m * np.sum(vc * ac, -1) + j * w * e, -1)
    load = np.sum(loads.applied[0, k:] * kin.vel[0, :k], axis=(-1, -2))
    if not np.isfinite(load).all():
        _no_value(kin, phi, k)
    return _Terms(inertia, slope, load)


def _no_value(kin: Kinematics, phi: np.ndarray, k: int) -> None:
    """Raise for the first load without a value at the run's poses (a spring whose two points meet)."""
    assert kin.mechanism.loads
    from linkwork.kinetostatics.external import evaluate

    for name, size in evaluate(kin).magnitude.items():
        bad = np.flatnonzero(~np.isfinite(size[0, k:]))
        if len(bad):
            where = turn_deg(float(phi[bad[0]]))
            raise LinkworkError(
                f'load "{name}" has no value with the crank at {where:.6g} deg to x: '
                "a spring's or damper's two points meet there, and its line has no direction"
            )
    raise LinkworkError("the loads have no value at a pose of the run")


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
) -> Run:
    """Run the machine unit from the state ``(angle, speed)`` for ``until`` seconds.

    Parameters
    ----------
    mech : Mechanism
        One crank (a revolute drive); ``linkwork.simulate`` also takes a path, an example name or a Spec.
    until : float
        Length of the run, s.
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
    rtol, atol : float
        The integrator's tolerances (``atol`` in rad and rad/s).
    """
    from scipy.integrate import solve_ivp

    if not one_crank(mech):
        raise LinkworkError("a run in time needs one crank (a revolute drive)")
    if not (math.isfinite(until) and until > 0):
        raise LinkworkError(f"until: expected a positive time, got {until!r} s")
    drive = (drive if drive is not None else mech.motor_gear) if motor else None
    sense = -1.0 if mech.drive_speed[0] < 0 else 1.0
    extra = drive.inertia if drive is not None else 0.0

    def moment(omega: np.ndarray) -> np.ndarray:
        if drive is None:
            return np.zeros_like(omega)
        return sense * np.asarray(drive.moment(sense * omega), dtype=float)

    def rhs(_t: float, y: np.ndarray) -> list[float]:
        terms = reduced_terms(mech, y[:1], y[1:], extra)
        if not terms.inertia[0] > 0:
            raise LinkworkError(
                f"the crank carries no inertia at {turn_deg(float(y[0])):.6g} deg to x: give the links' masses "
                "(and moments of inertia) for a run in time"
            )
        eps = (terms.load[0] + float(moment(y[1:])[0]) - 0.5 * terms.slope[0] * y[1] ** 2) / terms.inertia[0]
        return [float(y[1]), float(eps)]

    def stopped(_t: float, y: np.ndarray) -> float:
        return float(y[1])

    phi0 = float(mech.drive_start[0]) if angle is None else float(angle)
    grid = np.linspace(0.0, until, RUN_SAMPLES) if times is None else np.asarray(times, dtype=float).ravel()
    if grid.size == 0 or grid.min() < 0 or grid.max() > until * (1 + 1e-12):
        raise LinkworkError(f"times: expected times within [0, {until:g}] s")
    sol = solve_ivp(
        rhs,
        (0.0, until),
        [phi0, float(speed)],
        method="DOP853",
        rtol=rtol,
        atol=atol,
        events=stopped,
        dense_output=True,
    )
    if sol.status < 0:
        raise LinkworkError(f"the run in time failed at {float(sol.t[-1]):.6g} s: {sol.message}")
    y = sol.sol(grid)
    y[:, grid == until] = sol.y[:, -1:]  # the end from the solver's last step, not the interpolant
    terms = reduced_terms(mech, y[0], y[1], extra)
    md = moment(y[1])
    eps = (terms.load + md - 0.5 * terms.slope * y[1] ** 2) / terms.inertia
    kin = kinematics_at(mech, y[0][:, None], y[1][:, None], eps[:, None])
    starts = [float(t) for t in sol.t_events[0] if t > 0]
    stops = [RunEvent("stop", t, float(sol.sol(t)[0])) for t in starts]
    events = tuple(sorted(stops + _change_points(mech, sol.t, sol.sol), key=lambda e: e.time))
    return Run(grid, y[0], y[1], eps, kin, events, md, rtol, atol, int(sol.nfev))


#: A dip of a dyad's determinant among the solver's steps below this is refined (:func:`_change_points`).
DIP = 0.5


def _change_points(mech: Mechanism, steps: np.ndarray, dense: Any) -> list[RunEvent]:
    """Change points along a run: the solver's ``steps`` (s) and the ``dense`` output ``t -> (phi, omega)``.

    Each dyad's determinant (:attr:`Kinematics.step_det`, zero where its assembly modes meet) is looked at
    on the steps and their midpoints; each local least value below :data:`DIP` is refined by a bounded
    minimisation over time between its neighbours, and is a change point where it is within
    :data:`~linkwork.motion.kernels.CLOSE` of zero."""
    from scipy.optimize import minimize_scalar

    from linkwork.motion.analysis import DYADS
    from linkwork.motion.kernels import CLOSE

    dyads = [i for i, step in enumerate(mech.program) if step.kind in DYADS]
    if not dyads or len(steps) < 2:
        return []

    def det(t: np.ndarray) -> np.ndarray:
        phi = dense(t)[0][:, None]
        kin = kinematics_at(mech, phi, np.ones_like(phi), np.zeros_like(phi))
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
