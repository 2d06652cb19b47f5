"""Reduced (generalised) inertia and load moment of a one-degree-of-freedom mechanism.

With the turning angle ``psi`` of the crank as the generalised coordinate
(``psi = 0`` at the assembly angle, increasing in the file's direction of
rotation), the kinetic energy is ``T = J(psi) psi'^2 / 2`` and the power of
the loads is ``M(psi) psi'``.  Both follow exactly from a kinematic solution
at unit crank speed, where every velocity is a first transfer function
(``d r / d psi``) and, the crank turning uniformly, every acceleration is
the second (``d2 r / d psi2``):

    J(psi)      = sum m_i |v_Ci|^2 + J_Ci omega_i^2
    dJ/dpsi     = 2 sum m_i v_Ci . a_Ci + J_Ci omega_i epsilon_i
    M(psi)      = sum F . v_P + M omega_i        (gravity and the file's loads)
                  - P_friction / |omega_n|        (friction in proportion to the pairs' forces)

The friction in proportion to the pairs' forces depends on the speed (the inertia forces load the pairs):
its power lost is taken from the kinetostatics at the file's nominal crank speed ``omega_n``
(:mod:`linkwork.kinetostatics.friction`) and reduced to the crank, a moment always against the turning;
a constant friction is a load like the others.  The equation of motion of the machine unit is then
``J(psi) psi'' + J'(psi) psi'^2 / 2 = M(psi) + M_drive``.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from linkwork.errors import LinkworkError
from linkwork.kinetostatics.external import evaluate
from linkwork.kinetostatics.external import power as external_power
from linkwork.kinetostatics.reaction_forces import forces_of
from linkwork.kinetostatics.reactions import gravity_power, inertia_and_gravity
from linkwork.limits import DYNAMICS_STEPS
from linkwork.motion import cycle, kinematics
from linkwork.motion.kinematic_analysis import Kinematics
from linkwork.structure.model import Mechanism, one_crank
from linkwork.units import turn_deg


@dataclass(frozen=True)
class Reduced:
    """Reduced quantities on a uniform grid of the turning angle over one turn.

    Attributes
    ----------
    psi : ndarray (K,)
        Turning angle of the crank from its assembly angle, rad, ``2 pi k / K``.
    angle : ndarray (K,)
        The crank's drive angle at each ``psi``.
    inertia : ndarray (K,)
        Reduced moment of inertia ``J``, kg m^2, on the crank shaft.
    inertia_slope : ndarray (K,)
        ``dJ/dpsi``, kg m^2/rad.
    load : ndarray (K,)
        Reduced moment of gravity, the external loads and the friction in the pairs, N m; positive where
        they drive the crank forward (a cutting load gives a negative moment); the dampers' apart.
    friction : ndarray (K,)
        The part of ``load`` that the friction in proportion to the pairs' forces takes, N m (>= 0: it is
        subtracted); zero without it.
    damping : ndarray (K,) or None
        The dampers' reduced damping coefficient ``B``, N m s/rad: their moment is ``-B psi'``; None
        without dampers.
    """

    psi: np.ndarray
    angle: np.ndarray
    inertia: np.ndarray
    inertia_slope: np.ndarray
    load: np.ndarray
    friction: np.ndarray | None = None
    damping: np.ndarray | None = None

    def at_speed(self, omega: float) -> Reduced:
        """The same with the dampers' moment at the crank speed ``omega`` (rad/s) in ``load``: the loads of a
        machine turning at that speed, for what reads the load moment alone (a flywheel's sizing)."""
        if self.damping is None:
            return self
        return dataclasses.replace(self, load=self.load - self.damping * omega, damping=None)

    def work(self) -> np.ndarray:
        """Work of the loads from ``psi = 0`` (J), by the trapezoid rule over the grid, ``(K + 1,)``
        (the last value after the whole turn)."""
        step = 2 * np.pi / len(self.psi)
        m = np.append(self.load, self.load[0])
        return np.concatenate([[0.0], np.cumsum((m[1:] + m[:-1]) * step / 2)])

    @property
    def mean_load(self) -> float:
        """Mean reduced load moment over the turn, N m: the drive must supply its opposite."""
        return float(np.mean(self.load))


def reduced(mech: Mechanism, *, steps: int = DYNAMICS_STEPS) -> Reduced:
    """Reduced inertia, its slope and the reduced load moment over ``steps`` equal steps of one turn of
    the crank.

    Raises
    ------
    LinkworkError
        Unless the mechanism has one crank (a revolute drive) and assembles over the whole turn.
    """
    if not one_crank(mech):
        raise LinkworkError("machine dynamics needs one crank (a revolute drive)")
    if steps < 16:
        raise LinkworkError(f"steps: expected at least 16 angles over the turn, got {steps}")
    sign = -1.0 if mech.drive_speed[0] < 0 else 1.0
    angle = cycle(mech, steps)
    kin = kinematics(mech, angle, speed=sign)
    if not np.all(kin.valid):
        bad = turn_deg(angle[~np.asarray(kin.valid)][0])
        raise LinkworkError(f"the mechanism does not assemble over the whole turn (first at {bad:.1f} deg)")
    loads = inertia_and_gravity(kin)
    ms = kin.mass_properties
    m, j = ms.mass[0], ms.inertia[0]
    vc, ac = loads.com_velocity[0], loads.com_acceleration[0]
    w, e = kin.vel[0, :, :, 2], kin.acc[0, :, :, 2]
    inertia = np.sum(m * np.sum(vc * vc, -1) + j * w * w, -1)
    slope = 2 * np.sum(m * np.sum(vc * ac, -1) + j * w * e, -1)
    friction = friction_moment(mech, angle, sign)
    load = (gravity_power(kin, loads.com_velocity) + external_power(kin, loads.external))[0] - friction
    damping = _damping(kin)
    if damping is not None:
        load = load + damping  # the dampers' moment at unit speed is -B: kept apart, in B
    psi = 2 * np.pi * np.arange(steps) / steps
    return Reduced(psi, angle, inertia, slope, load, friction, damping)


def friction_moment(mech: Mechanism, angle: np.ndarray, sign: float) -> np.ndarray:
    """The power lost to friction in proportion to the pairs' forces at the crank angles ``angle``, turning
    at the file's speed (``sign`` its direction), over that speed: N m, ``(K,)``, zero without such friction.

    Raises
    ------
    LinkworkError
        Where the friction has no solution (the pairs lock, or it does not converge).
    """
    if not mech.friction:
        return np.zeros(len(angle))
    rate = abs(float(mech.drive_speed[0]))
    rate = rate if math.isfinite(rate) and rate > 0 else 1.0
    f = forces_of(kinematics(mech, angle, speed=sign * rate))
    assert f.friction is not None
    for problem in f.friction.problems:
        if problem.kind != "indeterminate":
            raise LinkworkError(f"machine dynamics needs the friction at every angle: {problem}")
    return np.sum(f.friction.loss[0], -1) / rate


def _damping(kin: Kinematics) -> np.ndarray | None:
    """The dampers' reduced damping coefficient ``(K,)`` over ``kin`` at unit crank speed (minus their power
    there), or None without dampers."""
    if not any(load.kind == "damper" for load in kin.mechanism.loads):
        return None
    return -external_power(kin, evaluate(kin, ("damper",)))[0]
