"""Gravity of any size and direction; springs, dampers and torsion springs as loads of every analysis."""

from __future__ import annotations

import math

import numpy as np
import pytest

import linkwork as lw
from mechanisms import four_bar_spec


def heavy_four_bar(rot: float, gravity: object) -> dict:
    """A four-bar with masses, turned rigidly by ``rot`` (rad) about the origin, with ``gravity``."""
    data, _ = four_bar_spec(0.1, 0.35, 0.25, 0.3, 1.0, False, transform=(0.0, 0.0, rot))
    for k, name in enumerate(data["links"]):
        data["links"][name]["mass"] = 2.0 + k
        data["links"][name]["com"] = [0.04 * (k + 1), 0.01 * (k - 1)]
    data["gravity"] = gravity
    data["drives"][0]["speed"] = "40 rpm"
    return data


def run(data: dict) -> lw.kinetostatics.Forces:
    return lw.forces(lw.compile(lw.from_dict(data)), steps=36)


@pytest.mark.parametrize("rot", [0.7, -2.0])
def test_tilted_gravity_is_the_same_machine_turned(rot):
    """Gravity along ``270 deg + rot`` on the four-bar turned by ``rot``: the same driving torque and the same
    reaction sizes as the upright one under ordinary gravity; the foundation force turns with it."""
    upright = run(heavy_four_bar(0.0, 9.81))
    turned = run(heavy_four_bar(rot, {"value": "9.81 m/s^2", "direction": f"{math.degrees(rot) + 270.0} deg"}))
    np.testing.assert_allclose(turned.driving_torque, upright.driving_torque, rtol=1e-9, atol=1e-9)
    for joint in ("O2", "A", "B", "O4"):
        size = [np.linalg.norm(f.reaction(joint), axis=-1) for f in (upright, turned)]
        np.testing.assert_allclose(size[1], size[0], rtol=1e-9, atol=1e-9)
    c, s = math.cos(rot), math.sin(rot)
    f0 = upright.foundation[..., :2]
    np.testing.assert_allclose(turned.foundation[..., 0], c * f0[..., 0] - s * f0[..., 1], atol=1e-8)
    np.testing.assert_allclose(turned.foundation[..., 1], s * f0[..., 0] + c * f0[..., 1], atol=1e-8)


def test_zero_gravity_leaves_only_inertia():
    """``gravity: 0``: the torque is the rate of change of kinetic energy over the speed, the foundation force
    minus the rate of change of momentum, both from finite differences of the positions (no weights)."""
    data = heavy_four_bar(0.0, 0)
    mech = lw.compile(lw.from_dict(data))
    assert mech.gravity == 0.0
    f = lw.forces(mech, steps=36)
    heavy = run(heavy_four_bar(0.0, 9.81))
    assert np.max(np.abs(f.driving_torque - heavy.driving_torque)) > 1.0  # gravity mattered there
    total = mech.link_mass.sum()
    kin = f.kinematics
    m, com = mech.link_mass, mech.link_com
    omega = 40 * 2 * math.pi / 60

    def centres(angles):
        k = lw.kinematics(mech, angles)
        q = k.pose
        c, s = np.cos(q[..., 2]), np.sin(q[..., 2])
        return q[..., :2] + np.stack([c * com[:, 0] - s * com[:, 1], s * com[:, 0] + c * com[:, 1]], -1)

    h = 1e-4
    x = kin.angles
    cm = [np.sum(m[:, None] * centres(x + k * h), -2) / total for k in (-1, 0, 1)]
    acc = (cm[2] - 2 * cm[1] + cm[0]) / h**2 * omega**2
    np.testing.assert_allclose(f.foundation[..., :2], -total * acc[0], atol=1e-4 * np.abs(total * acc).max())


def test_gravity_is_read_in_every_form():
    for given, vector in [
        (0, (0.0, 0.0)),
        ("9.81 m/s^2", (0.0, -9.81)),
        ({"value": 2.0, "direction": "0 deg"}, (2.0, 0.0)),
        ({"value": 3.0}, (0.0, -3.0)),
    ]:
        mech = lw.compile(lw.from_dict(heavy_four_bar(0.0, given)))
        np.testing.assert_allclose(mech.gravity_vector, vector, atol=1e-15)
    with pytest.raises(lw.errors.SpecError, match="gravity"):
        lw.from_dict(heavy_four_bar(0.0, -1.0))
