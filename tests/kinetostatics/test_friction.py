"""Friction in proportion to the pairs' forces: a slider-crank against the friction circle and the friction angle
worked by hand, the power balance with the losses in each pair, self-locking, the shears of seed 000."""

from __future__ import annotations

import copy
import math

import numpy as np
import pytest

import linkwork as lw
from linkwork.errors import FrictionWarning, SpecError
from linkwork.spec.reader import described

R, L, LOAD = 0.1, 0.35, 1000.0  # crank, rod (m), the load on the slider towards O (N)
F_GUIDE = 0.15
RHO = {"O": 0.1 * 0.020, "A": 0.12 * 0.015, "B": 0.08 * 0.010}  # f r: the radii of the friction circles, m


def _slider_crank(masses: bool = False) -> lw.Mechanism:
    """A centric slider-crank (guide along x through O) with friction in all four pairs, a constant force
    ``LOAD`` on the slider towards O; massless unless ``masses``."""
    mass = {"mass": 2.0} if masses else {}
    data = {
        "name": "slider-crank with friction",
        "units": {"length": "m", "mass": "kg", "angle": "deg", "force": "N"},
        "frame": {"points": {"O": [0, 0]}},
        "links": {
            "crank": {"ends": ["O", "A"], "length": R, **mass},
            "rod": {"ends": ["A", "B"], "length": L, **mass},
            "slider": {"points": {"B": [0, 0]}, **({"mass": 5.0, "inertia": 0.01} if masses else {})},
        },
        "joints": {
            "O": {"type": "revolute", "links": ["frame", "crank"], "friction": {"f": 0.1, "radius": "20 mm"}},
            "A": {"type": "revolute", "links": ["crank", "rod"], "friction": {"f": 0.12, "radius": "15 mm"}},
            "B": {"type": "revolute", "links": ["rod", "slider"], "friction": {"f": 0.08, "radius": "10 mm"}},
            "guide": {
                "type": "prismatic",
                "links": ["frame", "slider"],
                "point": "B",
                "through": "O",
                "axis": 0,
                "friction": {"f": F_GUIDE},
            },
        },
        "drives": [{"joint": "O", "speed": "10 rad/s", "direction": "ccw"}],
        "hints": {"B": [0.45, 0]},
        "loads": {"P": {"type": "force", "at": "slider.B", "force": [-LOAD, 0]}},
    }
    return lw.compile(lw.from_dict(data))


def _by_hand(phi: float, omega: float) -> dict[str, float]:
    """The massless slider-crank at crank angle ``phi`` turning at ``omega``, solved with the friction circles
    and the friction angle.

    The rod carries two forces, ``S`` from the crank at A and ``-S`` from the slider at B, and the friction
    moments ``-rho |S| sgn(omega_rod - omega_other)`` of its pins: its moments about A give
    ``(B - A) x S = -|S| h``, ``h = rho_A sgn(w2 - w1) + rho_B sgn(w2)``: S is tangent to the two friction
    circles, at ``sin(theta - alpha) = -h / l`` from the rod's direction ``alpha`` (of the two such lines the
    one along which the slider's balance gives a positive size).  The slider: ``S + (-LOAD, 0) + (0, N)`` and
    the guide's friction ``(-f |N| sgn(v_B), 0)``: ``N = -S_y``, ``|S| (cos theta - f |sin theta| sgn v_B) =
    LOAD``.  The crank: ``M = A x S + rho_A |S| sgn(w1 - w2) + rho_O |S| sgn(w1)``."""
    a = np.array([R * math.cos(phi), R * math.sin(phi)])
    b = np.array([a[0] + math.sqrt(L * L - a[1] ** 2), 0.0])
    psi = math.atan2(b[1] - a[1], b[0] - a[0])
    w2 = -R * math.cos(phi) * omega / (L * math.cos(psi))
    v_b = -R * math.sin(phi) * omega - L * math.sin(psi) * w2
    h = RHO["A"] * np.sign(w2 - omega) + RHO["B"] * np.sign(w2)
    found = []
    for theta in (psi + math.asin(-h / L), psi + math.pi - math.asin(-h / L)):
        size = LOAD / (math.cos(theta) - F_GUIDE * abs(math.sin(theta)) * np.sign(v_b))
        if size > 0:
            found.append((size, theta))
    assert len(found) == 1  # one line of action carries the load: no locking here
    size, theta = found[0]
    s = size * np.array([math.cos(theta), math.sin(theta)])
    torque = a[0] * s[1] - a[1] * s[0] + RHO["A"] * size * np.sign(omega - w2) + RHO["O"] * size * np.sign(omega)
    return {"S": size, "N": abs(s[1]), "torque": torque, "w2": w2, "v_b": v_b}


def test_slider_crank_with_friction_in_all_four_pairs_against_the_friction_circle_and_angle():
    mech = _slider_crank()
    phi = np.radians(np.r_[15:166:10, 195:346:10])  # away from the dead points 0 and 180 deg
    f = lw.forces(mech, phi)
    omega = 10.0
    hand = [_by_hand(p, omega) for p in phi]
    size = np.array([h["S"] for h in hand])
    np.testing.assert_allclose(f.driving_torque, [h["torque"] for h in hand], rtol=1e-10)
    for joint in ("O", "A", "B"):
        np.testing.assert_allclose(np.hypot(*f.reaction(joint).T), size, rtol=1e-10)
    np.testing.assert_allclose(np.abs(f.reaction("guide")[:, 1]), [h["N"] for h in hand], rtol=1e-10)
    assert f.friction is not None
    expected = np.stack([RHO["O"] * size, RHO["A"] * size, RHO["B"] * size, F_GUIDE * np.array([h["N"] for h in hand])])
    np.testing.assert_allclose(f.friction.size[0], expected.T, rtol=1e-10)
    assert not f.friction.problems
    # the guide's whole force on the slider leans from its normal by the friction angle, against the sliding
    tangential = -F_GUIDE * np.abs(f.reaction("guide")[:, 1]) * np.sign([h["v_b"] for h in hand])
    lean = np.arctan2(np.abs(tangential), np.abs(f.reaction("guide")[:, 1]))
    np.testing.assert_allclose(lean, math.atan(F_GUIDE), rtol=1e-12)


def test_friction_raises_the_drive_torque_on_the_working_stroke_and_eases_it_on_the_return():
    """Against the same mechanism without friction: friction takes power from the drive at every sample."""
    mech = _slider_crank()
    smooth = lw.compile(lw.from_dict(_without_friction(described(mech.description))))
    phi = np.radians(np.arange(5.0, 360.0, 10.0))
    with_f, without = lw.forces(mech, phi), lw.forces(smooth, phi)
    omega = 10.0
    assert np.all(with_f.driving_torque * omega > without.driving_torque * omega)
    e = with_f.efficiency
    np.testing.assert_allclose(e.drive - e.friction, without.driving_torque * omega, atol=1e-9 * np.max(e.drive))


def _without_friction(spec: lw.Spec) -> dict:
    data = copy.deepcopy(spec.model_dump(exclude_none=True))
    for joint in data["joints"].values():
        joint.pop("friction", None)
    data["units"] = {"angle": "rad"}
    return data


def test_power_balance_with_friction_at_every_sample():
    """Drive power = useful power + the losses in the pairs + dT/dt (+ dPi/dt of the weights), each term
    computed here from the kinematics: the loss of a pair as its friction times its relative speed."""
    mech = _slider_crank(masses=True)
    f = lw.forces(mech, steps=360, speed=30.0)
    kin, fr = f.kinematics, f.friction
    assert fr is not None and not fr.problems
    w = kin.vel[0, :, :, 2]  # links: frame, crank, rod, slider
    v_b = kin.velocity("slider.B")[:, 0]
    relative = np.stack([w[:, 1], w[:, 2] - w[:, 1], w[:, 3] - w[:, 2], v_b], -1)
    losses = fr.size[0] * np.abs(relative)
    useful = LOAD * v_b  # the load (-LOAD, 0) takes -F . v
    ms = kin.mass_properties
    vc, ac = f.loads.com_velocity[0], f.loads.com_acceleration[0]
    kinetic = np.sum(ms.mass[0] * np.sum(vc * ac, -1) + ms.inertia[0] * w * kin.acc[0, :, :, 2], -1)
    potential = mech.gravity * np.sum(ms.mass[0] * vc[..., 1], -1)
    drive = f.driving_torque * 30.0
    gap = drive - useful - losses.sum(-1) - kinetic - potential
    assert np.max(np.abs(gap)) <= 1e-9 * np.max(np.abs(drive))
    e = f.efficiency
    assert e.joints == ("O", "A", "B", "guide")
    np.testing.assert_allclose(e.losses, losses, rtol=1e-12, atol=1e-12 * np.max(losses))
    assert np.max(np.abs(e.imbalance)) <= 1e-9 * np.max(np.abs(drive))
    giving = drive > 0
    np.testing.assert_allclose(e.instantaneous[giving], 1 - losses.sum(-1)[giving] / drive[giving], rtol=1e-12)
    assert np.all(np.isnan(e.instantaneous[~giving]))


def test_constant_friction_counts_among_the_losses():
    """The constant friction of a ``friction`` load: its loss is its size times the relative speed."""
    data = _without_friction(described(_slider_crank().description))
    data["loads"]["bearing"] = {"type": "friction", "joint": "O", "moment": 2.0}
    f = lw.forces(lw.compile(lw.from_dict(data)), steps=36)
    e = f.efficiency
    assert e.joints == ("O",)
    np.testing.assert_allclose(e.losses[:, 0], 2.0 * 10.0, rtol=1e-12)
    assert np.max(np.abs(e.imbalance)) <= 1e-9 * np.max(np.abs(e.drive))


def _shears(f: float, radius: float, cut: bool = True) -> lw.Mechanism:
    """The bundled shears of seed 000 with friction in every pair, and a cutting force of 5 kN against the
    knife while it comes down."""
    data = copy.deepcopy(lw.example("shears-slider-crank").model_dump(exclude_none=True))
    data["units"] = {"angle": "rad"}
    for joint in data["joints"].values():
        joint["friction"] = {"f": f} if joint["type"] == "prismatic" else {"f": f, "radius": radius}
    if cut:
        down = [math.radians(100), math.radians(260)]  # the drive angle, from 90 deg: the knife going down
        data["loads"] = {
            "cut": {"type": "force", "at": "knife.B", "direction": math.pi / 2, "magnitude": [5e3, 5e3], "angle": down}
        }
    return lw.compile(lw.from_dict(data))


def test_shears_with_friction_in_every_pair_efficiency_and_power_balance():
    """Light friction (f = 0.01, pins of 10 mm): no sample of the turn locks; the cycle's efficiency lies
    between 0 and 1 and is the share of the drive's work not lost to friction (the kinetic and potential
    energy come back over the turn); the power balance closes at every sample."""
    with pytest.warns(FrictionWarning, match=r"taken as zero at phi = 90, 270 deg, where the reactions are indet"):
        f = lw.forces(_shears(0.01, 0.010), steps=360)
    fr, e = f.friction, f.efficiency
    assert fr is not None
    assert [p.kind for p in fr.problems] == ["indeterminate"]  # the dead points, phi = 90 and 270 deg
    assert fr.problems[0].angles == (90.0, 270.0)
    assert np.max(np.abs(e.imbalance)) <= 1e-9 * np.max(np.abs(e.drive))
    assert np.isfinite(e.drive).all()
    cycle = float(e.cycle)
    assert 0 < cycle < 1
    drive = e.work(e.drive)
    assert abs(cycle - (1 - e.work(e.friction) / drive)) < 1e-6  # T and Pi return over the turn
    assert abs(e.work(e.kinetic)) < 1e-9 * drive


def test_shears_lock_near_their_dead_points_within_the_friction_angle():
    """At phi = 90 and 270 deg the rod lies across the knife's guide: within about the friction angle
    (atan 0.1 = 5.7 deg, a little more for the pins' friction circles) of those positions no drive moves the
    knife.  The power balance closes wherever it moves."""
    with pytest.warns(FrictionWarning) as caught:
        f = lw.forces(_shears(0.1, 0.020), steps=360)
    assert [w.message.kind for w in caught] == ["locks", "indeterminate"]
    assert "locks the mechanism (self-locking) at phi = 83, 84, 85" in str(caught[0].message)
    fr = f.friction
    assert fr is not None
    kinds = {p.kind: p for p in fr.problems}
    assert set(kinds) == {"locks", "indeterminate"}
    assert all(isinstance(p, FrictionWarning) for p in fr.problems)
    locked = np.array(kinds["locks"].angles)
    for centre in (90.0, 270.0):
        near = np.abs(locked - centre)
        assert np.all(near[near < 30] <= 8.0) and {centre - 5, centre + 5} <= set(locked)
    assert not ({80.0, 100.0, 260.0, 280.0} & set(locked))
    e = f.efficiency
    moves = np.isfinite(e.drive)
    assert np.max(np.abs(e.imbalance[moves])) <= 1e-9 * np.max(np.abs(e.drive[moves]))


def test_friction_field_is_checked_with_its_line():
    text = """name: bad friction
units: {length: mm, mass: kg, angle: deg}
frame:
  points: {O: [0, 0], C: [200, 0]}
links:
  crank: {ends: [O, A], length: 50}
  rod: {ends: [A, B], length: 200}
  slider: {points: {B: [0, 0]}}
joints:
  O: {type: revolute, links: [frame, crank], friction: {f: 0.1}}
  A: {type: revolute, links: [crank, rod], friction: {f: 0.1, radius: 5}}
  B: {type: revolute, links: [rod, slider]}
  guide: {type: prismatic, links: [frame, slider], point: B, through: O, axis: 0, friction: {f: 0.1, radius: 5}}
drives:
  - {joint: O, speed: 10 rad/s}
hints:
  B: [240, 0]
"""
    with pytest.raises(SpecError) as caught:
        lw.loads(text, file="bad.yaml")
    text_of = "\n".join(str(p) for p in caught.value.problems)
    assert "bad.yaml:10" in text_of and 'missing field "radius"' in text_of
    assert "bad.yaml:13" in text_of and 'no "radius"' in text_of
    assert "bad.yaml:11" not in text_of
    fixed = text.replace("{f: 0.1}}\n  A", "{f: 0.1, radius: 5}}\n  A").replace(", radius: 5}}\ndrives", "}}\ndrives")
    with pytest.raises(SpecError) as caught:
        lw.loads(fixed.replace("[crank, rod], friction: {f: 0.1", "[crank, rod], friction: {f: -0.1"), file="bad.yaml")
    (problem,) = caught.value.problems
    assert "bad.yaml:11" in str(problem) and "joints.A.friction.f" in str(problem)


@pytest.mark.numba
@pytest.mark.filterwarnings("ignore::linkwork.errors.FrictionWarning")
def test_compiled_reactions_with_friction_equal_the_numpy_solution(monkeypatch):
    """The friction solve goes through the compiled kernel (its loads are external loads): the same reactions
    and friction as through the batched NumPy solves."""
    import importlib

    from linkwork.kinetostatics import reactions_numba

    assert reactions_numba.available()  # the lane's fixture turned them on
    forces = importlib.import_module("linkwork.kinetostatics.reaction_forces")
    mech = _shears(0.1, 0.020)
    compiled = lw.forces(mech, steps=360)
    monkeypatch.setattr(forces.reactions_numba, "available", lambda: False)
    numpy = lw.forces(mech, steps=360)
    assert compiled.friction is not None and numpy.friction is not None
    both = np.isfinite(compiled.multipliers) & np.isfinite(numpy.multipliers)
    assert np.array_equal(both, np.isfinite(numpy.multipliers))
    scale = np.abs(numpy.multipliers[both]).max()
    np.testing.assert_allclose(compiled.multipliers[both], numpy.multipliers[both], rtol=0, atol=1e-11 * scale)
    assert [(p.kind, p.angles) for p in compiled.friction.problems] == [
        (p.kind, p.angles) for p in numpy.friction.problems
    ]


def test_friction_of_design_variants_equals_each_variant_alone():
    mech = _slider_crank(masses=True)
    lengths = [0.33, 0.35, 0.37]
    f = lw.forces(mech, steps=24, variants={"links.rod.length": lengths})
    assert f.friction is not None and f.friction.size.shape == (3, 24, 4)
    for k, value in enumerate(lengths):
        one = lw.forces(mech, steps=24, variants={"links.rod.length": [value]})
        np.testing.assert_allclose(f.driving_torque[k], one.driving_torque[0], rtol=1e-12, atol=1e-9)
        np.testing.assert_allclose(f.efficiency.losses[k], one.efficiency.losses[0], rtol=1e-12, atol=1e-9)


def _write(tmp_path, mech: lw.Mechanism) -> str:
    import yaml

    path = tmp_path / "friction.yaml"
    data = described(mech.description).model_dump(exclude_none=True) | {"units": {"angle": "rad"}}
    path.write_text(yaml.safe_dump(data, sort_keys=False))
    return str(path)


@pytest.mark.slow  # over the default lane's budget on the NumPy kernels (tests/conftest.py)
def test_forces_command_reports_the_efficiency_and_where_the_pairs_lock(tmp_path):
    import json

    from commandline import linkwork

    path = _write(tmp_path, _shears(0.1, 0.020))
    text = linkwork("forces", path, "--steps", "360")
    assert text.returncode == 0, text.stderr
    assert "warning: friction in O, A, B, guide locks the mechanism (self-locking) at phi = 83, 84" in text.stdout
    assert "lost to friction: O " in text.stdout and "efficiency: of the cycle none" in text.stdout
    light = linkwork("forces", _write(tmp_path, _shears(0.01, 0.010)), "--json", "--out", str(tmp_path / "out"))
    data = json.loads(light.stdout)["efficiency"]
    assert 0 < data["cycle"] < 1 and data["balance"] < 1e-9
    assert list(data["friction_power"]) == ["O", "A", "B", "guide"]
    assert data["friction"]["joints"]["A"] == {"f": 0.01, "friction_circle_m": pytest.approx(1e-4)}
    assert [p["kind"] for p in data["friction"]["problems"]] == ["indeterminate"]
    head = (tmp_path / "out" / "forces.csv").read_text().splitlines()[0].split(",")
    assert {"drive_power [W]", "friction_power.guide [W]", "efficiency [1]"} <= set(head)


def test_check_values_lists_the_friction_in_si(tmp_path):
    import json

    from commandline import linkwork

    out = json.loads(linkwork("check", _write(tmp_path, _slider_crank()), "--json", "--values").stdout)
    got = {v["path"]: v for v in out["values"]}
    assert got["joints.O.friction.radius"]["value"] == pytest.approx(0.02)
    assert got["joints.O.friction.radius"]["unit"] == "m"
    assert got["joints.guide.friction.f"]["value"] == pytest.approx(F_GUIDE)
