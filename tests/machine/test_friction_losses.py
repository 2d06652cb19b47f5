"""Machine dynamics with friction in proportion to the pairs' forces: the losses feed the motor's load."""

from __future__ import annotations

import copy
import math

import numpy as np
import pytest

import linkwork as lw
from linkwork.machine.reduction import reduced


def _double_cut_shears(friction: bool) -> lw.Mechanism:
    data = copy.deepcopy(lw.example("double-cut-shears").model_dump(exclude_none=True))
    data["units"] = {"angle": "rad"}
    if friction:
        for joint in data["joints"].values():
            joint["friction"] = {"f": 0.08} if joint["type"] == "prismatic" else {"f": 0.08, "radius": 0.025}
    return lw.compile(lw.from_dict(data))


def test_reduced_load_loses_the_friction_power_at_the_nominal_speed():
    """The reduced friction moment is the power lost over the nominal speed; the same as the rise of the
    driving torque that friction causes in the kinetostatics at that speed (the drive pays for the losses
    alone: the useful loads, kinetic and potential energy are the same)."""
    with_f, without = _double_cut_shears(True), _double_cut_shears(False)
    red_f, red_0 = reduced(with_f, steps=720), reduced(without, steps=720)
    assert red_f.friction is not None and np.all(red_f.friction >= 0) and red_f.friction.max() > 0
    np.testing.assert_allclose(red_0.load - red_f.load, red_f.friction, rtol=1e-12, atol=1e-12)
    omega = float(with_f.drive_speed[0])
    rise = (
        lw.forces(with_f, red_f.angle, speed=omega).driving_torque
        - lw.forces(without, red_f.angle, speed=omega).driving_torque
    )
    scale = np.max(np.abs(red_f.friction))
    np.testing.assert_allclose(rise * math.copysign(1.0, omega), red_f.friction, rtol=0, atol=1e-9 * scale)


# the steady cycle with friction solves the friction at every point of the integrals: 16 s of processor time on
# the NumPy kernels
@pytest.mark.slow
def test_dynamics_with_friction_needs_more_power_from_the_motor():
    """The steady cycle with friction: the drive's mean power exceeds that without by the mean power lost
    (the losses at the nominal speed, the crank turning near it)."""
    with_f, without = _double_cut_shears(True), _double_cut_shears(False)
    run_f, run_0 = lw.dynamics(with_f), lw.dynamics(without)
    assert run_f.motion.steady and run_0.motion.steady
    lost = np.mean(run_f.reduced.friction) * run_f.motion.last.omega_mean
    assert run_f.drive_power - run_0.drive_power > 0.9 * lost > 0
