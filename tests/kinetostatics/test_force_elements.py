"""Gravity of any size and direction; springs, dampers and torsion springs as loads of every analysis."""

from __future__ import annotations

import math

import numpy as np
import pytest

import linkwork as lw
from mechanisms import four_bar_spec, meeting_spring_four_bar


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


SPEED = 40 * 2 * math.pi / 60  # rad/s, the drive speed of heavy_four_bar


def with_loads(loads: dict, gravity: object = 0) -> lw.Mechanism:
    data = heavy_four_bar(0.0, gravity)
    data["loads"] = loads
    return lw.compile(lw.from_dict(data))


def element_torque(loads: dict, steps: int = 48) -> tuple[np.ndarray, np.ndarray]:
    """The driving torque the elements ``loads`` add (forces are linear in the loads), and the crank angles."""
    f = lw.forces(with_loads(loads), steps=steps)
    bare = lw.forces(with_loads({}), steps=steps)
    return f.driving_torque - bare.driving_torque, f.kinematics.angles


def derivative(fn, x: np.ndarray, h: float = 1e-5) -> np.ndarray:
    return (fn(x + h) - fn(x - h)) / (2 * h)


def test_a_springs_torque_is_the_slope_of_its_potential():
    """The driving torque a spring between the coupler's B and the frame's O2 adds is dV/dphi, V = k (L - L0)^2 / 2
    from the positions alone (a spring's work is minus its potential's change); the preload form gives the free
    length L0 = L(assembly) - F0 / k."""
    k, free = 1500.0, 0.2
    torque, phi = element_torque(
        {"s": {"type": "spring", "between": ["coupler.B", "O2"], "stiffness": k, "free_length": free}}
    )
    mech = with_loads({})

    def energy(x):
        b = lw.kinematics(mech, x).position("B")
        return 0.5 * k * (np.hypot(b[:, 0], b[:, 1]) - free) ** 2

    np.testing.assert_allclose(torque, derivative(energy, phi), rtol=1e-6, atol=1e-6)
    b0 = lw.kinematics(mech, [1.0]).position("B")[0]
    preload = k * (math.hypot(*b0) - free)
    same = with_loads({"s": {"type": "spring", "between": ["coupler.B", "O2"], "stiffness": k, "preload": preload}})
    assert same.loads[0].free == pytest.approx(free, rel=1e-12)


def test_a_torsion_springs_torque_is_the_slope_of_its_potential():
    """A torsion spring in the joint B (coupler, rocker): V = k (theta_rocker - theta_coupler - theta_0)^2 / 2 from
    the links' angles; and in the drive's own joint O2 (frame, crank) the torque is k (phi - theta_0)."""
    k, free = 40.0, math.radians(-30.0)
    torque, phi = element_torque(
        {
            "t": {
                "type": "torsion_spring",
                "joint": "B",
                "stiffness": f"{k} N*m/rad",
                "free_angle": f"{math.degrees(free)} deg",
            }
        }
    )
    mech = with_loads({})

    def energy(x):
        kin = lw.kinematics(mech, x)
        turn = np.angle(np.exp(1j * (kin.angle("rocker") - kin.angle("coupler") - free)))
        return 0.5 * k * turn**2

    np.testing.assert_allclose(torque, derivative(energy, phi), rtol=1e-6, atol=1e-6)
    torque, phi = element_torque({"t": {"type": "torsion_spring", "joint": "O2", "stiffness": k, "free_angle": 0}})
    np.testing.assert_allclose(torque, k * phi, rtol=1e-12)


def test_a_dampers_torque_dissipates_its_power():
    """A damper between the crank's A and the frame's O4: the torque it adds is c omega (dL/dphi)^2, its force
    times the rate of its length over the crank speed, L from the positions alone."""
    c = 80.0
    torque, phi = element_torque({"d": {"type": "damper", "between": ["crank.A", "O4"], "damping": f"{c} N*s/m"}})
    mech = with_loads({})

    def length(x):
        a = lw.kinematics(mech, x).position("A")
        return np.hypot(a[:, 0] - 0.3, a[:, 1])

    np.testing.assert_allclose(torque, c * SPEED * derivative(length, phi) ** 2, rtol=1e-6, atol=1e-9)


def test_force_elements_are_checked_in_the_file():
    good = {"type": "spring", "between": ["coupler.B", "O2"], "stiffness": 10.0, "free_length": 0.1}
    cases = [
        ({**good, "free_length": None, "preload": None}, "free_length"),
        ({**good, "preload": 3.0}, "one of them"),
        ({**good, "between": ["coupler.B", "coupler.A"]}, "on one link"),
        ({**good, "between": ["coupler.Q", "O2"]}, "no point"),
        ({"type": "torsion_spring", "joint": "Z", "stiffness": 1.0, "free_angle": 0}, "unknown joint"),
        ({"type": "damper", "between": ["crank.A", "O4"], "damping": -1.0}, "non-negative"),
    ]
    for load, says in cases:
        load = {k: v for k, v in load.items() if v is not None}
        with pytest.raises(lw.errors.SpecError, match=says):
            with_loads({"e": load})


def test_a_spring_whose_points_meet_is_one_clear_error():
    """A spring from the crank's A to the frame's O4 on a crank as long as O2 O4: the points meet with the crank at
    0 deg to x, and the error names the load and that angle."""
    data = meeting_spring_four_bar()
    with pytest.raises(lw.errors.LinkworkError, match=r'load "s".*meet with the crank at 0 deg'):
        lw.forces(lw.compile(lw.from_dict(data)), [0.5, 0.0, -0.5])


def test_check_values_reads_each_stiffness_in_its_own_kind():
    """A spring's stiffness in N/m, a torsion spring's in N m/rad (the same key, by the load's type)."""
    import yaml

    from linkwork.spec.values import values_read

    data = heavy_four_bar(0.0, 9.81)
    data["loads"] = {
        "s": {"type": "spring", "between": ["coupler.B", "O2"], "stiffness": "20 N/mm", "free_length": 0.2},
        "t": {"type": "torsion_spring", "joint": "B", "stiffness": "2 N*m/deg", "free_angle": "10 deg"},
        "d": {"type": "damper", "between": ["crank.A", "O4"], "damping": "3 N*s/mm"},
    }
    spec = lw.loads(yaml.safe_dump(data))
    read = {v.path: v for v in values_read(spec)}
    assert (read["loads.s.stiffness"].value, read["loads.s.stiffness"].unit) == (20000.0, "N/m")
    assert read["loads.t.stiffness"].value == pytest.approx(2 * 180 / math.pi, rel=1e-12)
    assert read["loads.t.stiffness"].kind == "torsion_stiffness"
    assert (read["loads.d.damping"].value, read["loads.d.damping"].unit) == (3000.0, "N*s/m")
