"""The motor characteristics of a machine unit, and its motor, gear and flywheel
(:class:`~linkwork.structure.records.MotorGear`, compiled from a file's ``machine:`` section by
:func:`linkwork.stage_records.from_spec`).

A motor characteristic gives the torque on the motor shaft against its
speed.  The gear (ratio ``u = omega_motor / omega_crank``, efficiency
``eta``) turns it into a moment on the crank, ``u eta M(u omega)``; the
rotor and a flywheel on the motor shaft add ``u^2 J`` to the reduced
inertia, a flywheel on the crank shaft adds its own inertia.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from linkwork.errors import LinkworkError
from linkwork.structure.records import speeds

#: A motor's characteristic: torque (N m) on its shaft against its speed (rad/s), scalars or arrays.
Characteristic = Callable[[Any], Any]


@dataclass(frozen=True)
class ConstantTorque:
    """A torque independent of the speed, N m."""

    torque: float

    def __call__(self, omega: Any) -> Any:
        return self.torque + 0.0 * speeds(omega)


@dataclass(frozen=True)
class LinearMotor:
    """A straight characteristic: ``stall`` torque at rest falling to zero at ``no_load`` speed (rad/s)
    (a DC shunt motor, or the working part of an induction motor's)."""

    stall: float
    no_load: float

    def __call__(self, omega: Any) -> Any:
        return self.stall * (1.0 - speeds(omega) / self.no_load)


@dataclass(frozen=True)
class InductionMotor:
    """An induction motor by the Kloss formula ``M = 2 M_k / (s / s_k + s_k / s)``.

    From the rated ``power`` (W) at the rated ``speed`` (rad/s), the ``synchronous`` speed (rad/s)
    and the breakdown torque ratio ``breakdown = M_k / M_n``:
    ``M_n = P / omega_n``, ``s_n = 1 - omega_n / omega_s``, ``s_k = s_n (lambda + sqrt(lambda^2 - 1))``.
    """

    power: float
    speed: float
    synchronous: float
    breakdown: float = 2.0

    def __post_init__(self) -> None:
        if not 0 < self.speed < self.synchronous:
            raise LinkworkError(
                f"induction motor: the rated speed ({self.speed:.6g} rad/s) must lie between 0 and the "
                f"synchronous speed ({self.synchronous:.6g} rad/s)"
            )
        if not self.breakdown > 1:
            raise LinkworkError(f"induction motor: the breakdown torque ratio must exceed 1, got {self.breakdown}")
        if not self.power > 0:
            raise LinkworkError(f"induction motor: the rated power must be positive, got {self.power}")

    @property
    def rated_torque(self) -> float:
        return self.power / self.speed

    @functools.cached_property
    def critical_slip(self) -> float:
        s_n = 1.0 - self.speed / self.synchronous
        lam = self.breakdown
        return s_n * (lam + math.sqrt(lam * lam - 1.0))

    def __call__(self, omega: Any) -> Any:
        s = 1.0 - speeds(omega) / self.synchronous
        sk = self.critical_slip
        mk = self.breakdown * self.rated_torque
        return 2 * mk * s * sk / (s * s + sk * sk)
