"""Machine dynamics: reduced inertia and loads, the drive, forward simulation, flywheel sizing.

One equation of motion: its reduced terms are :mod:`linkwork.machine.reduction`'s, and every run integrates it
through :func:`linkwork.machine.integration.integrate`.  :func:`simulate` is the run in time from a crank angle
and speed (as :func:`linkwork.simulate`); :func:`run_turns` the run turn by turn to the steady cycle that
:func:`dynamics` starts from.

>>> import linkwork as lw
>>> from linkwork.machine import ConstantTorque, MotorGear
>>> red = lw.reduced(lw.compile(lw.load("four-bar")), steps=360)
>>> red.inertia.shape
(360,)
"""

from __future__ import annotations

from linkwork.machine.drive import ConstantTorque, InductionMotor, LinearMotor
from linkwork.machine.flywheel import (
    Flywheel,
    constant_moment_cycle,
    size_flywheel,
    size_flywheel_wittenbauer,
    wittenbauer,
    wittenbauer_tangents,
)
from linkwork.machine.reduction import Reduced, reduced
from linkwork.machine.simulation import Motion, Turn, run_turns
from linkwork.machine.steady_cycle import Dynamics, balance_speed, dynamics, with_flywheel_for
from linkwork.machine.timerun import Run, RunEvent, simulate
from linkwork.structure.records import MotorGear

__all__ = [
    "ConstantTorque",
    "Dynamics",
    "Flywheel",
    "InductionMotor",
    "LinearMotor",
    "Motion",
    "MotorGear",
    "Reduced",
    "Run",
    "RunEvent",
    "Turn",
    "balance_speed",
    "constant_moment_cycle",
    "dynamics",
    "reduced",
    "run_turns",
    "simulate",
    "size_flywheel",
    "size_flywheel_wittenbauer",
    "wittenbauer",
    "with_flywheel_for",
    "wittenbauer_tangents",
]
