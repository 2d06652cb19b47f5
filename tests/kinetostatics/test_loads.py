"""External loads: virtual work, tables read by hand, the cutting load of seed 002 against the positions."""

from __future__ import annotations

import copy

import numpy as np
import pytest

import linkwork as lw
from mechanisms import TEXTBOOK, assert_free_bodies_balance


def _four_bar_with_loads(moment_table):
    b = TEXTBOOK["four-bar"][0]()
    data = b.to_dict()
    data["links"]["coupler"]["points"] = {"P": [0.2, 0.1]}
    data["loads"] = {
        "push": {"type": "force", "at": "coupler.P", "force": ["30 N", "-50 N"]},
        "spring": {"type": "moment", "on": "rocker", **moment_table},
    }
    return lw.compile(lw.from_dict(data))


def test_statics_with_external_loads_by_virtual_work():
    """At rest, the drive balances the external loads: M = -(F . dP/dphi + M_4 dtheta_4/dphi),
    the derivatives by finite differences of the positions."""
    mech = _four_bar_with_loads({"angle": [0, 360], "moment": ["0 N*m", "36 N*m"]})
    phi = mech.drive_start[0] + np.linspace(-0.8, 0.8, 33)
    f = lw.forces(mech, phi, speed=0.0)
    h = 1e-6
    plus, minus = lw.kinematics(mech, phi + h, speed=0.0), lw.kinematics(mech, phi - h, speed=0.0)
    dp = (plus.position("coupler.P") - minus.position("coupler.P")) / (2 * h)
    dtheta = (np.unwrap(plus.angle("rocker")) - np.unwrap(minus.angle("rocker"))) / (2 * h)
    moment = 36.0 * np.mod(phi, 2 * np.pi) / (2 * np.pi)  # the table is linear over the turn
    expected = -(30.0 * dp[:, 0] - 50.0 * dp[:, 1] + moment * dtheta)
    np.testing.assert_allclose(f.driving_torque, expected, rtol=1e-7, atol=1e-8)
    assert np.isnan(f.checks["driving_torque_vs_power_balance"])  # at rest the power balance says nothing
    assert f.checks["foundation_force_vs_momentum"] < 1e-9
    assert f.checks["foundation_moment_vs_momentum"] < 1e-9


def test_table_against_the_crank_angle_is_linear_inside_and_zero_outside():
    mech = _four_bar_with_loads({"angle": [0, 90, 180], "moment": [0, 10, 30]})
    angles = np.radians([45.0, 135.0, 270.0, 450.0, -315.0, 180.0])
    f = lw.forces(mech, angles, speed=0.0)
    np.testing.assert_allclose(f.loads.external.magnitude["spring"][0], [5, 20, 0, 10, 5, 30], rtol=1e-12)


def _without_loads(spec):
    data = copy.deepcopy(spec.model_dump(exclude_none=True))
    data.pop("loads")
    data["units"] = {"angle": "rad"}
    return lw.compile(lw.from_dict(data))


def test_cutting_load_of_seed_002_against_the_knife_positions():
    """The relative penetration from the blade edges' positions, the force from the table of
    example-data.md, acting only while the knives close; the drive does the cutting work
    (torque x omega = P x closing speed); the foundation does not feel the cut (the two equal and
    opposite forces act along one line)."""
    spec = lw.example("double-cut-shears")
    mech = lw.compile(spec)
    bare = _without_loads(spec)
    steps = 720
    f, f0 = lw.forces(mech, steps=steps), lw.forces(bare, steps=steps)
    kin = f.kinematics
    upper, lower = kin.position("knife_upper.edge")[:, 1], kin.position("knife_lower.edge")[:, 1]
    eps = (np.maximum(0.05 - upper, 0) + np.maximum(lower + 0.05, 0)) / 0.10
    np.testing.assert_allclose(f.loads.external.penetration["cutting"][0], eps, atol=1e-12)
    # closing speed by finite differences of the positions in the crank angle
    h = 1e-6
    plus, minus = lw.kinematics(mech, kin.angles + h), lw.kinematics(mech, kin.angles - h)
    gap = lambda k: k.position("knife_upper.edge")[:, 1] - k.position("knife_lower.edge")[:, 1]  # noqa: E731
    omega = mech.drive_speed[0]
    closing = -(gap(plus) - gap(minus)) / (2 * h) * omega
    table = np.interp(eps, [0, 0.15, 0.30, 0.45], [0, 250e3, 250e3, 0], right=0.0)
    force = np.where(closing > 0, table, 0.0)
    sure = np.abs(closing) > 1e-3  # away from the turning points of the knives
    np.testing.assert_allclose(f.loads.external.magnitude["cutting"][0][sure], force[sure], atol=1e-6)
    assert force.max() == pytest.approx(250e3)
    assert np.all(force[closing < 0] == 0)
    extra = (f.driving_torque - f0.driving_torque) * omega
    np.testing.assert_allclose(extra, force * closing, rtol=1e-6, atol=1e-6 * 250e3)
    np.testing.assert_allclose(f.foundation, f0.foundation, rtol=0, atol=1e-9 * 250e3)
    # but the pairs carry it: the guides of the knives do not, O3 does
    assert np.nanmax(np.abs(f.reaction("O3") - f0.reaction("O3"))) > 100e3
    assert all(v < 1e-9 for v in f.checks.values()), f.checks


def test_one_tool_leaves_the_reaction_on_the_frame():
    """A press: one tool, the workpiece on the frame.  The force on the tool and the reaction on
    the frame cancel in the foundation; the drive still does the work."""
    b = TEXTBOOK["offset slider-crank"][0]()
    data = b.to_dict()
    # off the guide: the guide takes a couple
    data["links"]["slider"].update(mass=2.0, com=[30, 20], inertia="0.01 kg*mm^2")
    data["loads"] = {
        "press": {
            "type": "process",
            "tools": ["slider.B"],
            "axis": "0 deg",
            "workpiece": [280, 380],
            "penetration": [0, 0.5, 1.0],
            "force": ["0 N", "2 kN", "0 N"],
        }
    }
    mech = lw.compile(lw.from_dict(data))
    data.pop("loads")
    bare = lw.compile(lw.from_dict(data))
    f, f0 = lw.forces(mech, steps=360), lw.forces(bare, steps=360)
    kin = f.kinematics
    x = kin.position("slider.B")[:, 0]
    vx = kin.velocity("slider.B")[:, 0]
    eps = np.maximum(0.380 - x, 0) / 0.100
    force = np.where(vx < 0, np.interp(eps, [0, 0.5, 1.0], [0, 2000, 0], right=0.0), 0.0)
    assert force.max() > 1500
    np.testing.assert_allclose(f.foundation, f0.foundation, rtol=0, atol=1e-9 * 2000)
    extra = (f.driving_torque - f0.driving_torque) * mech.drive_speed[0]
    np.testing.assert_allclose(extra, force * -vx, rtol=1e-9, atol=1e-9 * 2000)
    assert all(v < 1e-9 for v in f.checks.values()), f.checks
    assert np.abs(f.pair_moment("guide")).max() > 0.1
    assert_free_bodies_balance(f)


def test_the_drive_does_the_cutting_work_of_seed_002_per_turn():
    """At a uniform crank speed gravity and inertia do no net work over a turn, so the mean driving
    torque times 2 pi is the cutting work: h * P_max * (area under s(eps)) = 0.10 m * 250 kN * 0.30
    = 7500 J (the trapezoid through (0, 0), (0.15, 1), (0.30, 1), (0.45, 0))."""
    f = lw.forces(lw.compile(lw.example("double-cut-shears")), steps=7200)
    work = np.mean(f.driving_torque) * 2 * np.pi
    assert work == pytest.approx(0.10 * 250e3 * 0.30, rel=2e-4)  # the rectangle rule over the cut


def test_friction_in_a_hinge_and_a_guide_costs_its_power():
    """Coulomb friction of constant size: the drive pays M_f |relative turning speed| in the hinge
    and F_f |sliding speed| in the guide (both by finite differences of the positions), and the
    balances still hold."""
    b = TEXTBOOK["offset slider-crank"][0]()
    data = b.to_dict()
    data["links"]["slider"]["mass"] = 2.0
    data["links"]["rod"]["mass"] = 1.5
    bare = lw.compile(lw.from_dict(data))
    data["loads"] = {
        "pin": {"type": "friction", "joint": "A", "moment": "3 N*m"},
        "guide": {"type": "friction", "joint": "guide", "magnitude": "40 N"},
    }
    mech = lw.compile(lw.from_dict(data))
    phi = bare.drive_start[0] + np.linspace(0.05, 2 * np.pi - 0.05, 91)
    f, f0 = lw.forces(mech, phi), lw.forces(bare, phi)
    h = 1e-6
    plus, minus = lw.kinematics(mech, phi + h), lw.kinematics(mech, phi - h)
    turn = (plus.angle("rod") - plus.angle("crank") - minus.angle("rod") + minus.angle("crank")) / (2 * h)
    slide = (plus.position("slider.B")[:, 0] - minus.position("slider.B")[:, 0]) / (2 * h)
    omega = mech.drive_speed[0]
    lost = (3.0 * np.abs(turn) + 40.0 * np.abs(slide)) * abs(omega)
    np.testing.assert_allclose((f.driving_torque - f0.driving_torque) * omega, lost, rtol=1e-6)
    assert all(v < 1e-9 for v in f.checks.values()), f.checks
    assert_free_bodies_balance(f)
    red, red0 = lw.reduced(mech, steps=720), lw.reduced(bare, steps=720)
    assert red0.mean_load - red.mean_load == pytest.approx(np.mean(lost) / abs(omega), rel=2e-2)


def test_a_constant_process_force_acts_from_the_touch_of_the_tool_only():
    """A press cutting a constant 4 kN (the table ``[4 kN, 4 kN]`` from penetration 0) acts only once the
    tool is in the work: per turn the drive does F * c, c the cut from the workpiece's face to the tool's
    lowest point, by the closed form of the offset slider-crank (x_min = sqrt((l - r)^2 - e^2)), not F times
    the whole closing stroke.  Gravity and inertia do no net work over a turn at uniform speed."""
    b = TEXTBOOK["offset slider-crank"][0]()
    data = b.to_dict()
    data["links"]["rod"]["mass"] = 1.5
    data["links"]["slider"].update(mass=2.0)
    face = 0.450  # the tool closes from x = 497.5 mm down to 295.8 mm
    data["loads"] = {
        "cut": {
            "type": "process",
            "tools": ["slider.B"],
            "axis": "0 deg",
            "workpiece": [250, 1000 * face],
            "penetration": [0, 1],
            "force": ["4 kN", "4 kN"],
        }
    }
    mech = lw.compile(lw.from_dict(data))
    steps = 14400
    f = lw.forces(mech, steps=steps)
    x = f.kinematics.position("slider.B")[:, 0]
    vx = f.kinematics.velocity("slider.B")[:, 0]
    size = f.loads.external.magnitude["cut"][0]
    assert np.all(size[x >= face] == 0)  # not in the work: no force, whatever the table gives at zero
    assert np.all(size[(x < face) & (vx < 0)] == 4000.0)
    cut = face - np.sqrt((0.4 - 0.1) ** 2 - 0.05**2)
    work = np.mean(f.driving_torque) * 2 * np.pi
    assert work == pytest.approx(4000.0 * cut, rel=1e-3)  # the rectangle rule over the jump at the touch
    assert all(v < 1e-9 for v in f.checks.values()), f.checks
