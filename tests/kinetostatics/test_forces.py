"""Kinetostatics: a sympy derivation of seed 000, statics by virtual work, Newton's laws, balances."""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings

import linkwork as lw
from mechanisms import (
    TEXTBOOK,
    assembles,
    assert_free_bodies_balance,
    forces_on_b,
    four_bar_spec,
    four_bars,
    heavy_compound_hinge,
)

L, M1, M2, M_HOUSING, OMEGA, G = 0.15, 10.0, 20.0, 500.0, 10.0, 9.81


def seed000_closed_form():
    """Foundation force and driving torque of the seed 000 shears, derived in sympy from the
    positions alone: crank OA and rod AB uniform rods of length l, knife B on the vertical through O."""
    t, w, l, m1, m2, m, g = sp.symbols("t omega l m1 m2 m g", positive=True)  # noqa: E741 - the paper's l
    phi = w * t
    a = sp.Matrix([l * sp.cos(phi), l * sp.sin(phi)])
    b = sp.Matrix([0, 2 * l * sp.sin(phi)])
    bodies = [(m1, a / 2, phi, m1 * l**2 / 12), (m1, (a + b) / 2, sp.atan2(b[1] - a[1], b[0] - a[0]), m1 * l**2 / 12)]
    bodies.append((m2, b, sp.Integer(0), sp.Integer(0)))
    momentum = sum((mass * sp.diff(c, t) for mass, c, _, _ in bodies), sp.zeros(2, 1))
    weight = -(m + 2 * m1 + m2) * g
    force = sp.Matrix([0, weight]) - sp.diff(momentum, t)  # what the machine puts on its foundation
    kinetic = sum(
        (mass * (sp.diff(c, t).dot(sp.diff(c, t))) / 2 + j * sp.diff(ang, t) ** 2 / 2 for mass, c, ang, j in bodies),
        sp.Integer(0),
    )
    potential = sum((mass * g * c[1] for mass, c, _, _ in bodies), sp.Integer(0))
    torque = (sp.diff(kinetic, t) + sp.diff(potential, t)) / w
    values = {l: L, m1: M1, m2: M2, m: M_HOUSING, g: G}
    f = sp.lambdify((t, w), [e.subs(values) for e in (force[0], force[1], torque)], "numpy")
    angle = sp.symbols("phi")
    per_omega2 = sp.simplify((force[1].subs(t, angle / w) - weight) / w**2)  # the inertia part, / omega^2
    assert not per_omega2.has(w)
    grid = np.linspace(0, 2 * np.pi, 100_001)
    coefficient = float(np.max(sp.lambdify(angle, per_omega2.subs(values), "numpy")(grid)))
    return f, coefficient, float(-weight.subs(values))


def test_seed_000_foundation_bolts_and_torque_against_sympy():
    mech = lw.compile(lw.example("shears-slider-crank"))
    f = lw.forces(mech, steps=720)
    phi = f.angles
    closed, coefficient, weight = seed000_closed_form()
    fx, fy, torque = (np.broadcast_to(np.asarray(v, dtype=float), phi.shape) for v in closed(phi / OMEGA, OMEGA))
    ok = np.isfinite(f.foundation[:, 0])  # the reactions are indeterminate at the singular 0 and 180 deg
    assert ok.sum() >= 716
    scale = np.abs(fy).max()
    np.testing.assert_allclose(f.foundation[ok, 0], fx[ok], rtol=0, atol=1e-9 * scale)
    np.testing.assert_allclose(f.foundation[ok, 1], fy[ok], rtol=0, atol=1e-9 * scale)
    np.testing.assert_allclose(f.driving_torque[ok], torque[ok], rtol=0, atol=1e-9 * np.abs(torque).max())
    bolts = f.bolts()
    assert bolts.shear == pytest.approx(np.abs(fx).max(), rel=1e-9)  # m1 omega^2 l = 150 N
    assert bolts.shear == pytest.approx(M1 * OMEGA**2 * L, rel=1e-9)
    assert bolts.pull == 0.0  # at 10 rad/s the shears never lift
    # the speed at which the pull equals the weight: of the whole shears, and of the housing alone
    for pull in (weight, M_HOUSING * G):
        expected = math.sqrt((pull + weight) / coefficient)
        assert lw.bolt_speed(mech, pull=pull) == pytest.approx(expected, rel=1e-9)
    # the paper prints F_max = 3/4 m1 omega^2 l (1/2 + 1/2 summed as 3/4) and, for the last question,
    # omega = sqrt(m1 g / ((m1 + m2) l)) = 4.67 rad/s: there the bolts carry no pull at all
    assert bolts.shear > 1.3 * 0.75 * M1 * OMEGA**2 * L
    paper = math.sqrt(M1 * G / ((M1 + M2) * L))
    assert lw.forces(mech, steps=720, speed=paper).bolts().pull == 0.0


def test_statics_by_virtual_work():
    """At rest the driving torque balances gravity: M = dV/dphi, V the potential energy (finite differences)."""
    mech_heavy = lw.compile(
        lw.from_dict(
            {
                **TEXTBOOK["four-bar"][0]().to_dict(),
                "links": {
                    "crank": {"ends": ["O2", "A"], "length": 0.1, "mass": 2.0},
                    "coupler": {"ends": ["A", "B"], "length": 0.35, "mass": 5.0, "points": {"P": [0.2, 0.1]}},
                    "rocker": {"ends": ["O4", "B"], "length": 0.25, "mass": 3.0, "com": [0.1, 0.02]},
                },
            }
        )
    )
    phi = mech_heavy.drive_start[0] + np.linspace(-1, 1, 41)
    f = lw.forces(mech_heavy, phi, speed=0.0)
    h = 1e-6

    def potential(angles):
        kin = lw.kinematics(mech_heavy, angles, speed=0.0)
        q = kin.pose[0]
        c, s = np.cos(q[..., 2]), np.sin(q[..., 2])
        y = q[..., 1] + s * mech_heavy.link_com[:, 0] + c * mech_heavy.link_com[:, 1]
        return np.sum(mech_heavy.link_mass * mech_heavy.gravity * y, -1)

    dvdphi = (potential(phi + h) - potential(phi - h)) / (2 * h)
    np.testing.assert_allclose(f.driving_torque, dvdphi, rtol=1e-7, atol=1e-8)


def test_newtons_second_law_for_the_coupler():
    """The pair forces on the coupler, its weight and m a_C balance (the reactions read back by joint)."""
    data = TEXTBOOK["four-bar"][0]().to_dict()
    data["links"]["coupler"] = {"ends": ["A", "B"], "length": 0.35, "mass": 5.0, "inertia": 0.07}
    mech = lw.compile(lw.from_dict(data))
    f = lw.forces(mech, steps=90)
    kin = f.kinematics
    on_coupler = f.reaction("A") - f.reaction("B")  # crank -> coupler, and coupler -> rocker reversed
    i = mech.link_names.index("coupler")
    com = kin.position("A") + 0.5 * (kin.position("B") - kin.position("A"))
    a_c = kin.acceleration("A") + 0.5 * (kin.acceleration("B") - kin.acceleration("A"))
    weight = np.array([0.0, -5.0 * mech.gravity])
    np.testing.assert_allclose(on_coupler + weight, 5.0 * a_c, rtol=1e-9, atol=1e-9)
    # moment about the centre of mass: r x F of the two pair forces = J epsilon
    ra, rb = kin.position("A") - com, kin.position("B") - com
    fa, fb = f.reaction("A"), f.reaction("B")
    moment = ra[:, 0] * fa[:, 1] - ra[:, 1] * fa[:, 0] - (rb[:, 0] * fb[:, 1] - rb[:, 1] * fb[:, 0])
    np.testing.assert_allclose(moment, 0.07 * kin.epsilon(i), rtol=1e-9, atol=1e-9)


@pytest.mark.parametrize("name", ["double-cut-shears", "watt-six-bar", "stephenson-six-bar", "class3-triad"])
def test_power_and_momentum_balances_of_the_examples(name):
    f = lw.forces(lw.compile(lw.example(name)), steps=180)
    assert all(v < 1e-9 for v in f.checks.values()), f.checks
    assert_free_bodies_balance(f)


@settings(max_examples=20, deadline=None)
@given(four_bars)
def test_random_four_bars_balance_power_and_momentum(dims):
    a, b, c, d, phi, left = dims
    if not assembles(a, b, c, d, phi):
        return
    data, _ = four_bar_spec(a, b, c, d, phi, left)
    for k, name in enumerate(data["links"]):
        data["links"][name]["mass"] = 1.0 + k
        data["links"][name]["com"] = [0.3 * (k + 1) * data["links"][name].get("length", 0.1), 0.01 * k]
    mech = lw.compile(lw.from_dict(data))
    f = lw.forces(mech, steps=72)
    assert all(v < 1e-9 for v in f.checks.values()), f.checks
    assert_free_bodies_balance(f)


def test_redundant_constraints_are_refused():
    mech = lw.compile(TEXTBOOK["parallelogram"][0]().build())
    with pytest.raises(lw.errors.LinkworkError, match="statically indeterminate"):
        lw.forces(mech, steps=12)


def test_full_balancing_of_a_four_bar_by_linearly_independent_vectors():
    """Counterweights on crank and rocker against the closed form of the method of linearly
    independent vectors (Berkof-Lowen): substituting the coupler direction from the loop
    a e^(i th2) + b e^(i th3) = d + c e^(i th4) into the total mass moment, its terms in
    e^(i th2) and e^(i th4) must vanish.  After balancing, the full solution shows no shaking force."""
    mech = lw.compile(lw.example("four-bar"))
    names = mech.link_names
    crank, coupler, rocker = (names.index(n) for n in ("crank", "coupler", "rocker"))
    pts = {n: mech.point_local[mech.point_index(n)] for n in ("crank.A", "coupler.B", "rocker.B")}
    a, b, c = (float(np.hypot(*pts[n])) for n in ("crank.A", "coupler.B", "rocker.B"))
    m, r = mech.link_mass, mech.link_com[:, 0] + 1j * mech.link_com[:, 1]
    p2 = -(m[crank] * r[crank] + m[coupler] * a * (1 - r[coupler] / b))
    p4 = -(m[rocker] * r[rocker] + m[coupler] * c / b * r[coupler])
    result = lw.balance(mech, ["crank", "rocker"])
    for w, p in zip(result.counterweights, (p2, p4), strict=True):
        assert w.mass_radius == pytest.approx(abs(p), rel=1e-9)
        assert abs(np.exp(1j * w.angle) - np.exp(1j * np.angle(p))) < 1e-9  # the same direction (at +-pi alike)
    before = np.abs(result.before.shaking_force).max()
    assert before > 1.0
    assert np.abs(result.after.shaking_force).max() < 1e-9 * before
    assert all(v < 1e-9 for v in result.after.checks.values())


def test_first_harmonic_balancing_of_the_seed_000_shears():
    """The mass moment of crank, rod and knife about O is (m1 l cos phi, (2 m1 + 2 m2) l sin phi):
    an ellipse with semi-axes X = 1.5 and Y = 9 kg m, the sum of a circle (X + Y) / 2 turning with
    the crank and a circle (Y - X) / 2 turning against it.  A crank counterweight cancels the first,
    (X + Y) / 2 = 5.25 kg m opposite the crank; the second is left, a shaking force of constant
    magnitude (Y - X) / 2 omega^2 = 375 N."""
    mech = lw.compile(lw.example("shears-slider-crank"))
    x_axis, y_axis = M1 * L, (M1 / 2 + 3 * M1 / 2 + 2 * M2) * L
    result = lw.balance(mech, ["crank"], harmonic=1)
    (w,) = result.counterweights
    assert w.mass_radius == pytest.approx((x_axis + y_axis) / 2, rel=1e-9)
    assert abs(np.cos(w.angle) + 1) < 1e-9  # opposite the crank
    assert w.mass == pytest.approx(w.mass_radius / L, rel=1e-12)  # default radius: the crank's length
    before = np.hypot(*result.before.shaking_force.T)
    after = np.hypot(*result.after.shaking_force.T)
    assert before.max() == pytest.approx(y_axis * OMEGA**2, rel=1e-9)
    np.testing.assert_allclose(after, (y_axis - x_axis) / 2 * OMEGA**2, rtol=1e-9)


@pytest.mark.numba
@pytest.mark.parametrize(
    "name", ["double-cut-shears", "shears-slider-crank", "watt-six-bar", "stephenson-six-bar", "class3-triad"]
)
def test_compiled_reactions_equal_the_numpy_solution(name):
    """The compiled kernel (Gaussian elimination per sample) against the batched NumPy solves."""
    from linkwork.kinetostatics import reactions_numba
    from linkwork.kinetostatics.reactions import foundation, solve_reactions

    assert reactions_numba.available()  # the lane's fixture turned them on
    mech = lw.compile(lw.example(name))
    f = lw.forces(mech, steps=360)
    lam, frame = solve_reactions(f.kinematics, f.loads)
    both = np.isfinite(lam) & np.isfinite(f.multipliers)
    assert both.sum() >= 0.99 * lam.size
    scale = np.abs(lam[both]).max()
    np.testing.assert_allclose(f.multipliers[both], lam[both], rtol=0, atol=1e-11 * scale)
    ref = foundation(f.kinematics, frame, f.loads)
    ok = np.isfinite(ref).all(-1)
    np.testing.assert_allclose(f.foundation_all[ok], ref[ok], rtol=0, atol=1e-11 * scale)


def test_compiled_reactions_of_design_variants():
    """Variants of the geometry go through the kernel too: each equals its own single solution."""
    mech = lw.compile(lw.example("four-bar"))
    lengths = {"links.coupler.length": [0.33, 0.35, 0.37]}
    f = lw.forces(mech, steps=24, variants=lengths)
    assert all(v < 1e-9 for v in f.checks.values()), f.checks
    for k, value in enumerate(lengths["links.coupler.length"]):
        one = lw.forces(mech, steps=24, variants={"links.coupler.length": [value]})
        np.testing.assert_allclose(f.driving_torque[k], one.driving_torque[0], rtol=1e-12, atol=1e-12)


def test_compiled_reactions_take_the_structured_solves():
    """Dyads and cranks go through the closed 2 x 2 and 3 x 3 solves, a class III triad through elimination
    (the comparison above with the NumPy solution then covers each kind)."""
    from linkwork.kinetostatics import reactions_numba as twin

    for name, expected in [
        ("double-cut-shears", [twin.DYAD, twin.DYAD, twin.DYAD, twin.SINGLE]),
        ("shears-slider-crank", [twin.DYAD, twin.SINGLE]),
        ("class3-triad", [twin.GENERAL, twin.SINGLE]),
    ]:
        rows, groups, _ = twin.encode(lw.compile(lw.example(name)))
        assert list(twin.shapes(rows, groups)[:, 0]) == expected, name


def _drive_written(order):
    """The bundled four-bar with its drive joint O2 written ``links: order``."""
    from linkwork.examples import text

    src = text("four-bar")
    return lw.compile(lw.loads(src.replace("links: [frame, crank]", f"links: [{', '.join(order)}]")))


def _crank_mass_only(order):
    data = TEXTBOOK["four-bar"][0]().to_dict()
    data["links"]["crank"].update(mass=3.0, inertia=0.01)  # coupler and rocker massless: they carry nothing
    data["joints"]["O2"]["links"] = list(order)
    return lw.compile(lw.from_dict(data))


def test_the_reaction_of_a_drive_joint_is_the_first_named_links_force_on_the_second_in_either_order():
    """``reaction("O2")`` is the force of the link the file names first on the other, also for the drive
    joint, which the model measures from the frame whichever way it is written.  A lone crank (3 kg, its
    centre of mass at mid-length) turning uniformly at omega: the frame holds it with
    m a_C - W = -m omega^2 r_C + m g y, in closed form; with every link heavy, Newton's law on the crank
    with the coupler's force known (-reaction("A"))."""
    phi = np.radians([0.0, 60.0, 135.0, 250.0])
    omega = 2 * np.pi  # 60 rpm
    r_c = 0.05 * np.stack([np.cos(phi), np.sin(phi)], -1)
    frame_on_crank = -3.0 * omega**2 * r_c + np.array([0.0, 3.0 * 9.81])
    for order, sign in ((("frame", "crank"), 1.0), (("crank", "frame"), -1.0)):
        f = lw.forces(_crank_mass_only(order), phi)
        np.testing.assert_allclose(f.reaction("O2"), sign * frame_on_crank, rtol=1e-12, atol=1e-12)
    heavy = {order: lw.forces(_drive_written(order), phi) for order in (("frame", "crank"), ("crank", "frame"))}
    for order, f in heavy.items():
        mech, kin = f.mechanism, f.kinematics
        m_crank = mech.link_mass[mech.link_names.index("crank")]
        a_c = 0.5 * kin.acceleration("A")  # the centroid of O2 and A; O2 does not move
        expected = m_crank * a_c - np.array([0.0, -m_crank * 9.81]) + f.reaction("A")
        first_on_second = expected if order[0] == "frame" else -expected
        np.testing.assert_allclose(f.reaction("O2"), first_on_second, rtol=1e-12, atol=1e-9)
        np.testing.assert_allclose(f.reaction("O2", on="crank"), expected, rtol=1e-12, atol=1e-9)
        np.testing.assert_allclose(f.reaction("O2", on="frame"), -expected, rtol=1e-12, atol=1e-9)
    a, b = heavy.values()
    np.testing.assert_allclose(b.reaction("O2"), -a.reaction("O2"), rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(b.driving_torque, a.driving_torque, rtol=1e-12)


@pytest.mark.parametrize(
    ("order", "first", "on"),
    [
        (("coupler", "rocker", "rod"), -1.0, "coupler"),  # the coupler's force on the rocker, which carries the pin
        (("rod", "coupler", "rocker"), -1.0, "rod"),  # the rod's on the rocker
        (("rocker", "rod", "coupler"), 1.0, "rod"),  # the first-named carries the pin: its force on the second
    ],
)
def test_a_compound_hinge_gives_the_force_on_each_of_its_links(order, first, on):
    """B joins the coupler, the rocker and the rod.  ``reaction("B", on=link)`` is the force of the other two
    on that link, equal to what the link's own free body needs; the three sum to zero (the pin carries
    nothing).  ``reaction("B")`` is the pair of the first-named link with the rocker, which carries the pin."""
    f = lw.forces(heavy_compound_hinge(order), steps=36)
    expected = forces_on_b(f)
    scale = max(np.abs(v).max() for v in expected.values())
    assert scale > 50.0
    for link, force in expected.items():
        np.testing.assert_allclose(f.reaction("B", on=link), force, rtol=0, atol=1e-9 * scale)
    np.testing.assert_allclose(sum(expected.values()), 0.0, atol=1e-9 * scale)
    np.testing.assert_allclose(f.reaction("B"), first * expected[on], rtol=0, atol=1e-9 * scale)
    kin = f.kinematics  # the rod's moment about its centre of mass, with the force on it at B: J epsilon
    com = 0.5 * (kin.position("B") + kin.position("C"))
    rb, rc = kin.position("B") - com, kin.position("C") - com
    fb, fc = expected["rod"], -f.reaction("C")
    moment = rb[:, 0] * fb[:, 1] - rb[:, 1] * fb[:, 0] + rc[:, 0] * fc[:, 1] - rc[:, 1] * fc[:, 0]
    np.testing.assert_allclose(moment, 3.0 * 0.3**2 / 12 * kin.epsilon(4), rtol=1e-9, atol=1e-9 * scale)


def test_a_link_that_is_not_in_the_joint_is_refused_by_name():
    f = lw.forces(heavy_compound_hinge(("coupler", "rocker", "rod")), steps=4)
    with pytest.raises(KeyError, match='joint "B" joins coupler, rocker, rod, not "crank"'):
        f.reaction("B", on="crank")
    with pytest.raises(KeyError, match='did you mean "rocker"'):
        f.reaction("B", on="rockr")
    with pytest.raises(KeyError, match='no joint "Q"'):
        f.reaction("Q", on="rod")


def test_a_pin_in_a_slot_gives_the_slots_force_on_the_pin():
    """Joint ``slot`` is written ``[rocker, crank]``: the rocker's slot holds the crank's pin A.  Newton's
    law on the crank (2 kg at mid-length, turning uniformly) with the frame's force at O1 known."""
    from mechanisms import pin_in_slot

    data = pin_in_slot().to_dict()
    data["links"]["crank"]["mass"] = 2.0
    data["links"]["rocker"].update(mass=4.0, com=[0.25, 0], inertia=0.08)
    f = lw.forces(lw.compile(lw.from_dict(data)), steps=24)
    kin = f.kinematics
    expected = 2.0 * 0.5 * kin.acceleration("crank.A") - np.array([0.0, -2.0 * 9.81]) - f.reaction("O1")
    assert np.abs(expected).max() > 10.0
    np.testing.assert_allclose(f.reaction("slot"), expected, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(f.reaction("slot", on="crank"), expected, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(f.reaction("slot", on="rocker"), -expected, rtol=1e-9, atol=1e-9)


@pytest.mark.parametrize(
    "name", ["double-cut-shears", "shears-slider-crank", "stephenson-six-bar", "percussion-rocker"]
)
def test_reactions_gathered_at_once_are_each_joints_reaction_bit_for_bit(name):
    """``Forces.reactions`` (the viewer's arrows and charts: every joint at once) against ``reaction`` of each
    joint on each of its links, guides and compound hinges included, for two design variants; an unknown link
    is refused with ``reaction``'s message."""
    mech = lw.compile(lw.load(name))
    crank = mech.link_names[max(int(i) for i in mech.pair_links[int(mech.drive_pair[0])])]
    length = lw.parameters(mech)[f"links.{crank}.length"]
    f = lw.forces(mech, steps=24, variants={f"links.{crank}.length": [length, 1.02 * length]})
    asked = [
        (str(mech.pair_joint[k]), mech.link_names[int(i)])
        for k in range(mech.n_pairs)
        for i in mech.pair_links[k]
        if not mech.link_virtual[int(i)]
    ]
    joints, links = zip(*dict.fromkeys(asked), strict=True)
    assert len(joints) > 6
    want = np.stack([f.reaction(j, on=link) for j, link in zip(joints, links, strict=True)], -2)
    assert np.array_equal(f.reactions(joints, links), want, equal_nan=True)
    with pytest.raises(KeyError, match="did you mean"):
        f.reactions([joints[0]], [links[0] + "x"])
