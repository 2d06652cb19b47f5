"""Force plans and Zhukovsky's lever against the analytic kinetostatics (two methods, one answer)."""

from __future__ import annotations

import functools

import numpy as np
import pytest

import linkwork as lw
from linkwork.examples import names as example_names
from linkwork.kinetostatics.force_polygons import force_plans
from linkwork.kinetostatics.zhukovsky import lever
from linkwork.scene.positions import position_angles
from linkwork.structure.model import PairType

EXAMPLES = example_names()


@functools.cache
def _at_positions(name: str) -> lw.Forces:
    """The forces at the twelve positions the plans are drawn at."""
    mech = lw.compile(lw.load(name))
    return lw.forces(lw.kinematics(mech, position_angles(mech)))


@pytest.mark.parametrize("name", EXAMPLES)
def test_every_force_plan_closes_to_1e12_of_its_largest_force(name: str) -> None:
    f = _at_positions(name)
    plans = force_plans(f)
    assert [g.label for g in plans.groups] == [g.label for g in reversed(f.mechanism.structure.groups)]
    for g in plans.groups:
        for i in np.flatnonzero(~f.singular):
            vectors = np.array([p.vector[0, i] for p in g.polygon])
            largest = np.max(np.hypot(*vectors.T))
            assert largest > 0
            assert np.hypot(*vectors.sum(0)) <= 1e-12 * largest, (g.label, i)


@pytest.mark.parametrize("name", EXAMPLES)
def test_reactions_read_off_the_plans_equal_those_of_the_analytic_solution(name: str) -> None:
    f = _at_positions(name)
    m = f.mechanism
    ok = ~f.singular
    for g in force_plans(f).groups:
        largest = max(float(np.nanmax(np.hypot(*p.vector[0, ok].T))) for p in g.polygon)
        for r in g.reactions:
            joint, on = r.about, m.link_names[r.link]
            if len(f.pairs(joint)) == 1:  # a joint of one pair: its force on the link, as Forces gives it
                expected = f.reaction(joint, on=on)
            else:
                a, b = (int(x) for x in m.pair_links[r.pair])
                expected = f.pair_force(r.pair)[0] * (1 if r.link == b else -1)
            assert np.abs(r.vector[0, ok] - expected[ok]).max() <= 1e-12 * largest, (g.label, r.name())
            if m.pair_type[r.pair] == PairType.PRISMATIC and r.kind != "internal":
                couple = f.pair_moment(joint) * (1 if r.link == int(m.pair_links[r.pair, 1]) else -1)
                scale = largest * 1.0  # N m of a force at 1 m
                assert np.abs(r.moment[0, ok] - couple[ok]).max() <= 1e-12 * scale


def test_a_split_reaction_is_its_normal_along_the_link_and_its_tangential_across_it() -> None:
    f = _at_positions("four-bar")
    g = force_plans(f).groups[0]  # II(2,3) RRR
    m = f.mechanism
    points = {n.split(".", 1)[1]: f.kinematics.position(n) for n in m.point_names}
    parts = {(p.name(), p.part): p.vector[0] for p in g.polygon if p.part}
    whole = {r.name(): r.vector[0] for r in g.reactions}
    along = points["B"] - points["A"]  # rod 2 from A to the inner joint B
    n, t = parts[("R12n", "n")], parts[("R12τ", "t")]
    assert np.abs(n[:, 0] * along[:, 1] - n[:, 1] * along[:, 0]).max() <= 1e-9 * np.abs(n).max()
    assert np.abs(np.sum(t * along, -1)).max() <= 1e-9 * np.abs(t).max() * np.abs(along).max()
    assert np.allclose(whole["R12"], n + t, rtol=0, atol=1e-12 * np.abs(whole["R12"]).max())


def test_the_double_cut_shears_at_position_9_have_a_plan_by_the_method_for_each_of_four_groups() -> None:
    f = _at_positions("double-cut-shears")
    plans = force_plans(f)
    assert len(plans.groups) == 4 and all(g.solved for g in plans.groups)
    names = {g.label: [p.name("ru") for p in g.polygon] for g in plans.groups}
    assert names["II(2,3) RRR"][0] == "R12τ" and names["II(2,3) RRR"][-2:] == ["R03n", "R12n"]
    assert names["II(4,5) RRP"][0] == "R34τ" and names["II(4,5) RRP"][-2:] == ["R05", "R34n"]
    assert {"G4", "Φ4", "G5", "Φ5", "F5"} <= set(names["II(4,5) RRP"])
    assert {"R43", "R63"} <= set(names["II(2,3) RRR"])  # the reactions of the groups taken before it
    assert all(g.closure(9) <= 1e-12 for g in plans.groups)


@pytest.mark.parametrize("name", EXAMPLES)
def test_the_levers_balancing_moment_is_the_kinetostatic_driving_torque_to_1e9(name: str) -> None:
    f = _at_positions(name)
    torque = np.asarray(f.driving_torque)
    moment = lever(f).balancing[0]
    assert np.isfinite(moment).all()
    assert np.abs(moment - torque).max() <= 1e-9 * np.abs(torque).max()
    big = np.abs(torque) > 1e-6 * np.abs(torque).max()
    assert np.all(np.abs(moment - torque)[big] <= 1e-9 * np.abs(torque)[big])


def test_the_lever_is_the_velocity_plan_turned_by_90_degrees() -> None:
    f = _at_positions("double-cut-shears")
    lv = lever(f)
    kin = f.kinematics
    v = kin.velocity("knife_upper.edge")
    load = next(x for x in lv.forces if x.force.kind == "load" and x.force.link == 5)
    assert np.allclose(load.image[0], np.stack([-v[:, 1], v[:, 0]], -1), rtol=0, atol=1e-12)
    # the balancing force is normal to the crank and its moment about O1 is the balancing moment
    arm = kin.position("crank.A") - kin.position("crank.O1")
    fb = lv.balancing_force[0]
    assert np.allclose(arm[:, 0] * fb[:, 1] - arm[:, 1] * fb[:, 0], lv.balancing[0], rtol=1e-12, atol=1e-9)


SLIDER_CRANK = """
name: static-slider-crank
units: {length: m, mass: kg, angle: deg}
frame: {points: {O: [0, 0]}}
links:
  crank: {ends: [O, A], length: 0.1}
  rod: {ends: [A, B], length: 0.3}
  knife: {points: {B: [0, 0]}}
joints:
  O: {type: revolute, links: [frame, crank]}
  A: {type: revolute, links: [crank, rod]}
  B: {type: revolute, links: [rod, knife]}
  guide: {type: prismatic, links: [frame, knife], point: B, through: O, axis: 0 deg}
drives: [{joint: O, speed: 10 rad/s, angle: 60 deg}]
loads:
  press: {type: force, at: knife.B, force: [-1000 N, 0 N]}
hints: {B: [0.35, 0]}
"""


def test_a_massless_slider_crank_against_its_closed_form(tmp_path):
    """Massless links, a force P = 1000 N against the slider along its guide: the rod is a two-force member,
    S = P / cos(beta) along it, the guide pushes N = P tan(beta) across, the crank needs M = -r S sin(phi + beta)
    (sin(beta) = r sin(phi) / l); the plans' reactions and the lever's moment, at every angle."""
    path = tmp_path / "slider-crank.yaml"
    path.write_text(SLIDER_CRANK, encoding="utf-8")
    mech = lw.compile(lw.load(str(path)))
    phi = np.radians(np.arange(5.0, 360.0, 10.0))
    f = lw.forces(lw.kinematics(mech, phi))
    r, length, p = 0.1, 0.3, 1000.0
    beta = np.arcsin(r * np.sin(phi) / length)  # the rod's angle below the guide, B on the +x side
    along = np.stack([np.cos(beta), -np.sin(beta)], -1)  # unit vector from A to B
    s = p / np.cos(beta)  # the rod pushes the slider along AB with s
    plans = force_plans(f)
    rrp, crank = plans.groups
    found = {x.name(): x.vector[0] for x in rrp.reactions + crank.reactions}
    assert np.allclose(found["R32"], -s[:, None] * along, rtol=0, atol=1e-9 * p)  # the knife on the rod, at B
    assert np.allclose(found["R03"][:, 0], 0.0, atol=1e-9 * p)
    assert np.allclose(found["R03"][:, 1], p * np.tan(beta), rtol=0, atol=1e-9 * p)  # the guide across
    assert np.allclose(found["R12"], s[:, None] * along, rtol=0, atol=1e-9 * p)
    tangential = next(x for x in rrp.polygon if x.part == "t")
    assert np.abs(tangential.vector[0]).max() <= 1e-9 * p  # a massless rod carries no tangential component
    torque = -r * s * np.sin(phi + beta)  # the rod's push on the pin turns the crank back: the drive holds it
    assert np.allclose(plans.balancing[0], torque, rtol=1e-12, atol=1e-9)
    assert np.allclose(lever(f).balancing[0], torque, rtol=1e-12, atol=1e-9)


def _heavy(kind: str) -> lw.Mechanism:
    """A PRP dyad (a slotted crank driving a slider: the plan's closing is two guides' normals) or an RPR dyad (a
    crank-shaper: closed by the analytic reactions), with masses, inertias and a speed."""
    from linkwork.spec.builder import MechanismBuilder

    b = MechanismBuilder(kind)
    if kind == "PRP":
        b = (
            b.frame(points={"O1": (0, 0), "G": (0, 0.1)})
            .link("crank", points={"O1": (0, 0), "T": (0.3, 0)}, mass=4, com=(0.1, 0.01), inertia=0.05)
            .link("block", points={"Q": (0, 0)}, mass=1.5, inertia=0.002)
            .link("slider", points={"Q": (0, 0)}, mass=6, com=(0.02, -0.03), inertia=0.01)
            .revolute("O1", "frame", "crank")
            .prismatic("on_crank", "crank", "block", point="Q", through="O1", axis=0)
            .revolute("Q", "block", "slider")
            .prismatic("guide", "frame", "slider", point="Q", through="G", axis=0)
            .drive("O1", angle=45, speed="200 rpm")
            .hint("Q", 0.1, 0.1)
        )
    else:
        b = (
            b.frame(points={"O1": (0, 0.2), "O2": (0, 0)})
            .link("crank", ends=("O1", "A"), length=0.1, mass=3)
            .link("block", points={"A": (0, 0)}, mass=1, inertia=0.001)
            .link("rocker", points={"O2": (0, 0), "T": (0.5, 0)}, mass=8, com=(0.25, 0), inertia=0.2)
            .revolute("O1", "frame", "crank")
            .revolute("A", "crank", "block")
            .prismatic("slot", "rocker", "block", point="A", through="O2", axis=0)
            .revolute("O2", "frame", "rocker")
            .drive("O1", angle=0, speed="120 rpm")
            .hint("slot", 0.1, 0.2)
            .hint("rocker.T", 0.22, 0.45)
        )
    return lw.compile(b.build())


@pytest.mark.parametrize("kind", ["PRP", "RPR"])
def test_dyads_with_guides_close_their_plans_and_their_levers_give_the_torque(kind):
    mech = _heavy(kind)
    f = lw.forces(lw.kinematics(mech, position_angles(mech)))
    plans = force_plans(f)
    dyad = plans.groups[0]
    assert dyad.solved == (kind == "PRP")
    ok = np.flatnonzero(~f.singular)
    assert len(ok) >= 10
    for g in plans.groups:
        assert max(g.closure(i) for i in ok) <= 1e-12
        largest = max(float(np.nanmax(np.hypot(*p.vector[0, ok].T))) for p in g.polygon)
        for r in g.reactions:
            a, b = (int(x) for x in mech.pair_links[r.pair])
            expected = f.pair_force(r.pair)[0] * (1 if r.link == b else -1)
            assert np.abs(r.vector[0, ok] - expected[ok]).max() <= 1e-12 * largest, (g.label, r.name())
            if mech.pair_type[r.pair] == PairType.PRISMATIC and r.kind != "internal":
                couple = f.multipliers[0, ok, 2 * r.pair] * (1 if r.link == b else -1)
                assert np.abs(r.moment[0, ok] - couple).max() <= 1e-12 * largest
    torque = np.asarray(f.driving_torque)
    assert np.abs(torque).max() > 1.0
    assert np.abs(lever(f).balancing[0] - torque).max() <= 1e-9 * np.abs(torque).max()
    assert np.abs(plans.balancing[0, ok] - torque[ok]).max() <= 1e-9 * np.abs(torque).max()


def test_springs_dampers_and_a_torsion_spring_enter_the_plans_and_the_lever() -> None:
    """The four-bar with a spring from the coupler's point M to the frame's O4, a damper along the coupler's AB
    and a torsion spring in B: each element's pair of forces (or moments) is named after it in the plans, each
    plan closes, its reactions are the analytic ones and the lever's moment is the driving torque (to 1e-9)."""
    from linkwork.examples import text as example_text

    loads = """loads:
  pull: {type: spring, between: [coupler.M, O4], stiffness: 2000 N/m, free_length: 150 mm}
  slow: {type: damper, between: [crank.A, rocker.B], damping: 40 N*s/m}
  twist: {type: torsion_spring, joint: B, stiffness: 30 N*m/rad, free_angle: 90 deg}

"""
    text = example_text("four-bar").replace("hints:", loads + "hints:")
    mech = lw.compile(lw.loads(text, file="four-bar.yaml"))
    f = lw.forces(lw.kinematics(mech, position_angles(mech)))
    plans = force_plans(f)
    named = {p.about for g in plans.groups for p in (*g.polygon, *g.couples) if p.symbol in ("F", "M")}
    assert named == {"pull", "slow", "twist"}
    for g in plans.groups:
        for i in range(len(f.angles)):
            vectors = np.array([p.vector[0, i] for p in g.polygon])
            assert np.hypot(*vectors.sum(0)) <= 1e-12 * np.max(np.hypot(*vectors.T)), (g.label, i)
    for g in plans.groups:  # every joint of the four-bar is one pair
        for r in g.reactions:
            expected = f.reaction(r.about, on=mech.link_names[r.link])
            assert np.abs(r.vector[0] - expected).max() <= 1e-12 * np.abs(expected).max(), (g.label, r.name())
    torque = np.asarray(f.driving_torque)
    assert np.abs(lever(f).balancing[0] - torque).max() <= 1e-9 * np.abs(torque).max()


@pytest.mark.filterwarnings("ignore::linkwork.errors.FrictionWarning")
def test_friction_in_proportion_to_the_pairs_forces_enters_the_plans_and_the_lever() -> None:
    """The slider-crank shears with f = 0.05 in every pair (pins of 10 mm), at the twelve positions: the friction
    solved with the reactions is a known load of the plans, a couple on each link of a pin and a force along the
    guide on the knife and the frame, named after its joint; each plan closes, its reactions are the analytic ones
    and the lever's moment is the driving torque (to 1e-9) wherever the shears move (the plans raised before)."""
    from kinetostatics.test_friction import _shears

    mech = _shears(0.05, 0.010)
    f = lw.forces(lw.kinematics(mech, position_angles(mech)))
    moving = ~f.singular & np.isfinite(np.asarray(f.driving_torque))
    assert moving.sum() >= 10
    plans = force_plans(f)
    named = {p.about for g in plans.groups for p in (*g.polygon, *g.couples) if p.symbol in ("Ff", "Mf")}
    assert named == {"friction O", "friction A", "friction B", "friction guide"}
    rubbed = [p for g in plans.groups for p in (*g.polygon, *g.couples) if p.symbol in ("Ff", "Mf")]
    assert {p.name() for p in rubbed} == {"Mf1", "Mf2", "Mf3", "Ff3"}  # a pin's couple on each link, the guide's force
    assert {p.name("ru") for p in rubbed} == {"Mтр1", "Mтр2", "Mтр3", "Fтр3"}
    for g in plans.groups:
        for i in np.flatnonzero(moving):
            vectors = np.array([p.vector[0, i] for p in g.polygon])
            assert np.hypot(*vectors.sum(0)) <= 1e-12 * np.max(np.hypot(*vectors.T)), (g.label, i)
        for r in g.reactions:
            expected = f.pair_force(r.pair)[0] * (1 if r.link == int(mech.pair_links[r.pair, 1]) else -1)
            gap = np.abs(r.vector[0, moving] - expected[moving]).max()
            assert gap <= 1e-12 * np.abs(expected[moving]).max(), (g.label, r.name())
    torque = np.asarray(f.driving_torque)[moving]
    assert np.abs(lever(f).balancing[0][moving] - torque).max() <= 1e-9 * np.abs(torque).max()
