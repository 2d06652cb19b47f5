"""Kinematics: closed forms, finite differences, an independent Newton solver, properties."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import linkwork as lw
from linkwork.errors import UnassemblableError
from linkwork.motion.solve import run
from linkwork.structure.parameters import apply
from mechanisms import (
    RHOMBUS,
    SOLVED,
    TEXTBOOK,
    angles_around,
    assembles,
    circle_intersection,
    compiled,
    four_bar_spec,
    four_bars,
)


def _span(kind, name):
    """Angle span of the comparisons: the Newton reference does not follow change points
    (the isosceles slider-crank at 0 and 180 deg, the parallelogram at 0 and 180 deg), so stay inside."""
    return {"five-bar": 0.6, "class IV": 0.8, "shears-slider-crank": 2.7, "parallelogram": 1.9}.get(name, 2 * np.pi)


@pytest.mark.parametrize("kind, name", SOLVED)
def test_closed_forms_agree_with_the_generic_newton_solver(kind, name):
    """Every kernel against Newton iterations and linear solves on the full constraint equations."""
    mech = compiled(kind, name)
    angles = angles_around(mech, span=_span(kind, name))
    kin = lw.kinematics(mech, angles)
    program = tuple(dataclasses.replace(s, kind="newton") for s in mech.program)
    values = kin.drive
    ref = run(mech, program, apply(mech)[0], values, kin.rates, np.zeros_like(values))
    ok = kin.valid & ref.valid[0]
    assert ok.mean() > 0.5
    pose, vel, acc = (np.moveaxis(x, (0, 1), (2, 3))[0][ok] for x in (ref.q, ref.v, ref.a))
    mine = kin.pose[0][ok]
    np.testing.assert_allclose(mine[..., :2], pose[..., :2], atol=1e-9)
    np.testing.assert_allclose(np.cos(mine[..., 2]), np.cos(pose[..., 2]), atol=1e-9)
    np.testing.assert_allclose(np.sin(mine[..., 2]), np.sin(pose[..., 2]), atol=1e-9)
    scale_v = max(np.nanmax(np.abs(vel)), 1e-9)
    scale_a = max(np.nanmax(np.abs(acc)), 1e-9)
    np.testing.assert_allclose(kin.vel[0][ok], vel, atol=1e-8 * scale_v)
    np.testing.assert_allclose(kin.acc[0][ok], acc, atol=1e-7 * scale_a)


@pytest.mark.parametrize("kind, name", SOLVED)
def test_velocity_and_acceleration_are_derivatives_of_motion(kind, name):
    """Central finite differences in time: every drive moves at its speed (several drives at once)."""
    mech = compiled(kind, name)
    base = angles_around(mech, n=12, span=_span(kind, name))
    rates = lw.kinematics(mech, base[:1]).rates[0]
    step = 1e-5 if mech.pair_type[mech.drive_pair[0]] == 0 else 1e-6
    dt = step / np.abs(rates).max()
    kin = lw.kinematics(mech, np.concatenate([base - rates * dt, base, base + rates * dt]))
    n = len(base)
    pts = kin.points()
    mid = slice(n, 2 * n)
    vel = np.stack([kin.velocity(p) for p in mech.point_names], axis=1)[mid]
    acc = np.stack([kin.acceleration(p) for p in mech.point_names], axis=1)[mid]
    fd_v = (pts[2 * n :] - pts[:n]) / (2 * dt)
    fd_a = (pts[2 * n :] - 2 * pts[mid] + pts[:n]) / dt**2
    ok = kin.valid[:n] & kin.valid[mid] & kin.valid[2 * n :]
    assert ok.mean() > 0.5
    scale = np.nanmax(np.abs(vel[ok])) + 1e-12
    np.testing.assert_allclose(vel[ok], fd_v[ok], atol=1e-6 * scale)
    np.testing.assert_allclose(acc[ok], fd_a[ok], atol=2e-3 * (np.nanmax(np.abs(acc[ok])) + 1e-12))
    omega = np.stack([kin.omega(i) for i in range(mech.n_links_total)], axis=1)[mid]
    theta = np.stack([kin.angle(i) for i in range(mech.n_links_total)], axis=1)
    fd_w = (np.angle(np.exp(1j * (theta[2 * n :] - theta[:n])))) / (2 * dt)
    np.testing.assert_allclose(omega[ok], fd_w[ok], atol=1e-6 * (np.nanmax(np.abs(omega[ok])) + 1e-12))


def slider_crank_closed_form(r, rod, e, phi, w):
    """Offset slider-crank with the guide y = e: x_B and its derivatives (textbook closed form)."""
    s = r * np.sin(phi) - e
    c = np.sqrt(rod * rod - s * s)
    x = r * np.cos(phi) + c
    ds = r * np.cos(phi)
    dx = -r * np.sin(phi) - s * ds / c
    d2s = -r * np.sin(phi)
    d2x = -r * np.cos(phi) - (ds * ds + s * d2s) / c - (s * ds) ** 2 / c**3
    return x, dx * w, d2x * w * w


def test_offset_slider_crank_closed_form():
    mech = lw.compile(TEXTBOOK["offset slider-crank"][0]().build())
    phi = np.linspace(0, 2 * np.pi, 73)
    kin = lw.kinematics(mech, phi)
    w = 100 * 2 * np.pi / 60
    x, v, a = slider_crank_closed_form(0.1, 0.4, 0.05, phi, w)
    np.testing.assert_allclose(kin.position("B")[:, 0], x, atol=1e-12)
    np.testing.assert_allclose(kin.position("B")[:, 1], 0.05, atol=1e-12)
    np.testing.assert_allclose(kin.velocity("B")[:, 0], v, atol=1e-11)
    np.testing.assert_allclose(kin.acceleration("B")[:, 0], a, atol=1e-9)
    np.testing.assert_allclose(kin.velocity("B")[:, 1], 0, atol=1e-12)


def test_four_bar_against_a_sympy_derivation():
    sp = pytest.importorskip("sympy")
    phi = sp.symbols("phi")
    a, b, c, d = sp.Rational(1, 10), sp.Rational(35, 100), sp.Rational(25, 100), sp.Rational(3, 10)
    ax, ay = a * sp.cos(phi), a * sp.sin(phi)
    # B from the circle intersection, the branch below the line A -> O4 (as the test four-bar is built)
    dx, dy = d - ax, -ay
    dist2 = dx**2 + dy**2
    aa = (b**2 - c**2 + dist2) / (2 * sp.sqrt(dist2))
    h = sp.sqrt(b**2 - aa**2)
    bx = ax + aa * dx / sp.sqrt(dist2) + h * dy / sp.sqrt(dist2)
    by = ay + aa * dy / sp.sqrt(dist2) - h * dx / sp.sqrt(dist2)
    w = 2 * sp.pi  # 60 rpm
    exprs = [bx, by, sp.diff(bx, phi) * w, sp.diff(by, phi) * w, sp.diff(bx, phi, 2) * w**2, sp.diff(by, phi, 2) * w**2]
    f = sp.lambdify(phi, exprs, "numpy")
    mech = lw.compile(TEXTBOOK["four-bar"][0]().build())
    angles = np.linspace(0, 2 * np.pi, 25)
    kin = lw.kinematics(mech, angles)
    ref = np.array(f(angles))
    np.testing.assert_allclose(kin.position("B"), ref[0:2].T, atol=1e-12)
    np.testing.assert_allclose(kin.velocity("B"), ref[2:4].T, atol=1e-10)
    np.testing.assert_allclose(kin.acceleration("B"), ref[4:6].T, atol=1e-8)


def test_crank_shaper_rocker_angle_closed_form():
    """RPR: the rocker points from O2 at the crank pin: theta = atan2(A - O2)."""
    mech = lw.compile(TEXTBOOK["crank-shaper"][0]().build())
    phi = np.linspace(0, 2 * np.pi, 37)
    kin = lw.kinematics(mech, phi, speed=1.0)
    ax, ay = 0.1 * np.cos(phi), 0.2 + 0.1 * np.sin(phi)
    np.testing.assert_allclose(np.cos(kin.angle("rocker")), ax / np.hypot(ax, ay), atol=1e-12)
    np.testing.assert_allclose(np.sin(kin.angle("rocker")), ay / np.hypot(ax, ay), atol=1e-12)
    # omega = d/dphi atan2(ay, ax) = (ax ay' - ay ax') / (ax^2 + ay^2)
    dax, day = -0.1 * np.sin(phi), 0.1 * np.cos(phi)
    np.testing.assert_allclose(kin.omega("rocker"), (ax * day - ay * dax) / (ax**2 + ay**2), atol=1e-12)


def test_scotch_yoke_is_simple_harmonic():
    mech = lw.compile(TEXTBOOK["scotch yoke"][0]().build())
    phi = np.linspace(0, 2 * np.pi, 37)
    kin = lw.kinematics(mech, phi, speed=3.0)
    np.testing.assert_allclose(kin.position("yoke.Y")[:, 0], 0.1 * np.cos(phi), atol=1e-12)
    np.testing.assert_allclose(kin.velocity("yoke.Y")[:, 0], -0.3 * np.sin(phi), atol=1e-12)
    np.testing.assert_allclose(kin.acceleration("yoke.Y")[:, 0], -0.9 * np.cos(phi), atol=1e-11)


def test_prp_slider_on_a_slotted_crank():
    """Q at the crossing of the crank's line and y = 0.1: x = 0.1 / tan(phi)."""
    mech = lw.compile(TEXTBOOK["PRP dyad"][0]().build())
    phi = np.linspace(0.3, 2.8, 26)
    kin = lw.kinematics(mech, phi, speed=1.0)
    np.testing.assert_allclose(kin.position("slider.Q"), np.stack([0.1 / np.tan(phi), 0.1 + 0 * phi], -1), atol=1e-12)
    np.testing.assert_allclose(kin.velocity("slider.Q")[:, 0], -0.1 / np.sin(phi) ** 2, atol=1e-11)
    np.testing.assert_allclose(kin.acceleration("slider.Q")[:, 0], 0.2 * np.cos(phi) / np.sin(phi) ** 3, atol=1e-9)


def test_class3_triad_against_an_independent_solver():
    """Each pose solved on its own by scipy's fsolve on the triad's six loop equations."""
    from scipy.optimize import fsolve

    mech = lw.compile(lw.example("class3-triad"))
    angles = np.radians(np.arange(0, 360, 15))
    kin = lw.kinematics(mech, angles)
    assert kin.valid.all()
    pts = {n: mech.points0()[mech.point_names.index(n)] * 1000 for n in ("base.B", "base.C", "base.D")}
    o1, o2, o3 = (0.220, -0.120), (0.51321, 0.13072), (0.16679, 0.26928)
    bc, bd, cd = (
        np.hypot(*(pts[p] - pts[q])) / 1000
        for p, q in (("base.B", "base.C"), ("base.B", "base.D"), ("base.C", "base.D"))
    )
    guess = np.concatenate([pts["base.B"], pts["base.C"], pts["base.D"]]) / 1000
    for i, phi in enumerate(angles):
        a = (o1[0] + 0.03 * math.cos(phi), o1[1] + 0.03 * math.sin(phi))

        def eq(x, a=a):
            b, c, d = x[:2], x[2:4], x[4:]
            return [
                np.hypot(*(b - a)) - 0.19,
                np.hypot(*(c - o2)) - 0.2,
                np.hypot(*(d - o3)) - 0.2,
                np.hypot(*(c - b)) - bc,
                np.hypot(*(d - b)) - bd,
                np.hypot(*(d - c)) - cd,
            ]

        sol = fsolve(eq, guess, xtol=1e-12)
        guess = sol
        np.testing.assert_allclose(kin.position("B")[i], sol[:2], atol=1e-9)
        np.testing.assert_allclose(kin.position("C")[i], sol[2:4], atol=1e-9)
        np.testing.assert_allclose(kin.position("D")[i], sol[4:], atol=1e-9)


def test_non_grashof_four_bar_reports_where_it_cannot_be_assembled():
    """a, b, c, d = 0.1, 0.2, 0.15, 0.3: the crank cannot pass |AO4| > b + c = 0.35,
    i.e. cos(phi) < (a^2 + d^2 - 0.35^2) / (2 a d) -> phi in (112.02, 247.98) deg."""
    data, _ = four_bar_spec(0.1, 0.35, 0.25, 0.3, 1.0, False)
    data["links"]["coupler"]["length"], data["links"]["rocker"]["length"] = 0.2, 0.15
    a = np.pi / 3
    pa = (0.1 * math.cos(a), 0.1 * math.sin(a))
    data["drives"][0]["angle"] = a
    data["hints"] = {"B": list(circle_intersection(pa, 0.2, (0.3, 0.0), 0.15, left=False))}
    mech = lw.compile(lw.from_dict(data))
    angles = np.radians(np.arange(0, 360, 0.5))
    kin = lw.kinematics(mech, angles)
    limit = math.degrees(math.acos((0.01 + 0.09 - 0.35**2) / 0.06))
    bad = np.degrees(angles[~kin.valid])
    assert bad.min() == pytest.approx(limit, abs=0.5) and bad.max() == pytest.approx(360 - limit, abs=0.5)
    assert np.isnan(kin.position("B")[~kin.valid]).all()
    messages = [e.message for e in kin.events if e.kind in ("no-assembly", "dead-point")]
    assert messages == [
        "group II(2,3) RRR: no assembly (no intersection) for crank angles 112.0 to 248.0 deg to the x axis",
        "group II(2,3) RRR: limit (dead) position near crank angle 112.0 deg to the x axis",
        "group II(2,3) RRR: limit (dead) position near crank angle 248.0 deg to the x axis",
    ]
    limits = [e.start for e in kin.events if e.kind == "dead-point"]
    np.testing.assert_allclose(np.degrees(limits), [limit, 360 - limit], atol=1e-5)
    coarse = lw.kinematics(mech, np.radians(np.arange(0, 360, 10.0)))  # limits by parabolas, 5-degree path
    limits = [e.start for e in coarse.events if e.kind == "dead-point"]
    np.testing.assert_allclose(np.degrees(limits), [limit, 360 - limit], atol=0.01)
    with pytest.raises(UnassemblableError, match="112.0 to 248.0"):
        lw.kinematics(mech, angles, strict=True)


def test_dead_points_of_a_crank_rocker_driven_by_its_rocker_are_found():
    """Drive the four-bar's rocker instead: dead points where crank and coupler are in line."""
    b = TEXTBOOK["four-bar"][0]()
    data = b.to_dict()
    a = math.radians(60)
    pa = (0.1 * math.cos(a), 0.1 * math.sin(a))
    pb = circle_intersection(pa, 0.35, (0.3, 0.0), 0.25, left=False)
    data["drives"] = [{"joint": "O4", "angle": math.degrees(math.atan2(pb[1], pb[0] - 0.3))}]
    data["links"]["rocker"] = {"ends": ["O4", "B"], "length": 0.25}
    data["hints"] = {"A": list(pa)}
    mech = lw.compile(lw.from_dict(data))
    angles = np.linspace(-np.pi, np.pi, 3601)
    kin = lw.kinematics(mech, angles)
    sing = sorted(e.start for e in kin.events if e.kind in ("singular", "dead-point"))
    # rocker angles where |A B| in line: |B - O2| = b + a or b - a
    expect = []
    for r in (0.45, 0.25):
        cos_t = (0.3**2 + 0.25**2 - r * r) / (2 * 0.3 * 0.25)
        expect += [math.pi - math.acos(cos_t), -(math.pi - math.acos(cos_t))]
    for e in sorted(expect):
        assert min(abs(s - e) for s in sing) < 2e-3


@settings(max_examples=30, deadline=None)
@given(four_bars, st.floats(-2, 2), st.floats(-2, 2), st.floats(-math.pi, math.pi))
def test_random_four_bars_keep_their_lengths_and_move_rigidly_with_the_frame(dims, dx, dy, rot):
    a, b, c, d, phi, left = dims
    if not assembles(a, b, c, d, phi):
        return
    base, _ = four_bar_spec(a, b, c, d, phi, left)
    moved, _ = four_bar_spec(a, b, c, d, phi, left, (dx, dy, rot))
    m0, m1 = lw.compile(lw.from_dict(base)), lw.compile(lw.from_dict(moved))
    offsets = np.linspace(-0.5, 0.5, 21)
    k0 = lw.kinematics(m0, phi + offsets)
    k1 = lw.kinematics(m1, phi + rot + offsets)
    assert (k0.valid == k1.valid).all()
    ok = k0.valid
    pa, pb = k0.position("A")[ok], k0.position("B")[ok]
    np.testing.assert_allclose(np.hypot(*(pb - pa).T), b, atol=1e-12)
    np.testing.assert_allclose(np.hypot(*(pb - (d, 0)).T), c, atol=1e-12)
    cr, sr = math.cos(rot), math.sin(rot)
    for p in ("A", "B"):
        x = k0.position(p)[ok]
        moved_x = np.stack([cr * x[:, 0] - sr * x[:, 1] + dx, sr * x[:, 0] + cr * x[:, 1] + dy], -1)
        np.testing.assert_allclose(k1.position(p)[ok], moved_x, atol=1e-11)
        v = k0.velocity(p)[ok]
        np.testing.assert_allclose(
            k1.velocity(p)[ok], np.stack([cr * v[:, 0] - sr * v[:, 1], sr * v[:, 0] + cr * v[:, 1]], -1), atol=1e-10
        )
    # batch equals a per-sample loop (to rounding: one may take the compiled kernels, the other NumPy's)
    for i in (0, 7, 20):
        one = lw.kinematics(m0, [phi + offsets[i]])
        np.testing.assert_allclose(one.position("B")[0], k0.position("B")[i], rtol=1e-14, atol=1e-15)


def test_design_variants_equal_separately_compiled_mechanisms():
    lengths = np.array([0.09, 0.10, 0.11])
    mech = lw.compile(lw.example("double-cut-shears"))
    angles = np.radians(np.arange(0, 360, 10))
    kin = lw.kinematics(mech, angles, variants={"links.crank.length": lengths})
    assert kin.position("E").shape == (3, 36, 2)
    from linkwork.examples import text

    for i, length in enumerate(lengths):
        spec = lw.loads(text("double-cut-shears").replace("length: 0.10\n", f"length: {length}\n", 1))
        one = lw.kinematics(lw.compile(spec), angles)
        np.testing.assert_allclose(kin.position("E")[i], one.position("E"), atol=1e-12)
        np.testing.assert_allclose(kin.acceleration("F")[i], one.acceleration("F"), atol=1e-9)


def test_unknown_variant_dimension_is_named():
    mech = lw.compile(lw.example("four-bar"))
    with pytest.raises(
        lw.errors.ParameterError, match='no parameter "links.crank.lenght" .did you mean "links.crank.length"'
    ):
        lw.kinematics(mech, [0.0], variants={"links.crank.lenght": [0.1, 0.2]})


def test_steps_cover_a_turn_in_the_direction_of_rotation():
    mech = lw.compile(lw.example("four-bar"))
    kin = lw.kinematics(mech, steps=8)
    np.testing.assert_allclose(kin.angles, np.radians(60) + np.arange(8) * np.pi / 4)
    assert kin.position("B").shape == (8, 2)
    assert kin.omega("crank") == pytest.approx(2 * np.pi)


def test_isosceles_slider_crank_goes_through_its_change_points_smoothly():
    """Seed 000: OA = AB = l, so y_B = 2 l sin(phi) over the whole turn; at 0 and 180 deg the two
    assembly modes meet (B at O), and the motion must go on in the other mode, with the exact
    velocity 2 l w cos(phi) and acceleration -2 l w^2 sin(phi) even on those samples."""
    mech = lw.compile(lw.example("shears-slider-crank"))
    kin = lw.kinematics(mech, steps=24)
    phi, r, w = kin.angles, 0.15, 10.0
    assert kin.valid.all()
    np.testing.assert_allclose(kin.position("B")[:, 1], 2 * r * np.sin(phi), atol=1e-12)
    np.testing.assert_allclose(kin.velocity("B")[:, 1], 2 * r * w * np.cos(phi), atol=1e-8)
    np.testing.assert_allclose(kin.acceleration("B")[:, 1], -2 * r * w * w * np.sin(phi), atol=1e-6)
    # the rod turns at -w: A B mirrors O A about the horizontal through A
    np.testing.assert_allclose(kin.omega("rod"), -w, atol=1e-8)
    kinds = [e.kind for e in kin.events]
    assert kinds.count("change-point") == 2


def test_jumps_of_a_newton_group_are_found():
    """A link moving on a circle, smooth except for one sample where it jumps across."""
    from linkwork.motion.newton import _jumps
    from linkwork.motion.state import State

    phi = np.linspace(0, 2, 41)
    state = State.empty(2, np.zeros((1, 2, 1, 1)), np.zeros((0, 2, 1, 1)), np.zeros((0, 2, 1, 1)), len(phi))
    state.q[1, 0, 0], state.q[1, 1, 0] = np.cos(phi), np.sin(phi)
    assert _jumps(state, [1], phi) == []
    state.q[1, :2, 0, 25:] *= -1  # the other assembly mode from sample 25 on
    assert _jumps(state, [1], phi) == [(0, 24)]


@settings(max_examples=30, deadline=None)
@given(st.floats(0.02, 0.3), st.floats(1.5, 6.0), st.floats(-0.8, 0.8), st.floats(0.5, 50.0))
def test_random_slider_cranks_match_the_closed_form(r, ratio, offset, w):
    """Crank r, rod l = ratio r, guide y = e with |e| < l - r: the slider always assembles."""
    rod = ratio * r
    e = offset * (rod - r)
    b = TEXTBOOK["offset slider-crank"][0]()
    data = b.to_dict()
    data["units"] = {"length": "m"}
    data["frame"]["points"] = {"O": [0, 0], "G": [0, e]}
    data["links"]["crank"]["length"] = r
    data["links"]["rod"]["length"] = rod
    data["drives"][0].update(speed=f"{w} rad/s", angle=30)
    a = (r * math.cos(math.pi / 6), r * math.sin(math.pi / 6))
    data["hints"] = {"B": [a[0] + math.sqrt(rod**2 - (e - a[1]) ** 2), e]}
    mech = lw.compile(lw.from_dict(data))
    phi = np.linspace(0, 2 * np.pi, 50)
    kin = lw.kinematics(mech, phi)
    x, v, acc = slider_crank_closed_form(r, rod, e, phi, w)
    np.testing.assert_allclose(kin.position("B")[:, 0], x, atol=1e-12)
    np.testing.assert_allclose(kin.velocity("B")[:, 0], v, atol=1e-10 * max(1.0, w * r))
    np.testing.assert_allclose(kin.acceleration("B")[:, 0], acc, atol=1e-8 * max(1.0, w * w * r))
    np.testing.assert_allclose(np.hypot(*(kin.position("B") - kin.position("A")).T), rod, atol=1e-12)


@settings(max_examples=15, deadline=None)
@given(st.floats(-1, 1), st.floats(-1, 1), st.floats(-math.pi, math.pi))
def test_six_bars_move_rigidly_with_the_frame(dx, dy, rot):
    """The Watt and Stephenson examples turned and shifted as a whole give turned and shifted motions."""
    from linkwork.examples import text
    from linkwork.spec.yamlsource import read_yaml

    c, s = math.cos(rot), math.sin(rot)
    for name in ("watt-six-bar", "stephenson-six-bar"):
        data = read_yaml(text(name)).data
        moved = read_yaml(text(name)).data
        for group in (moved["frame"]["points"], moved["hints"]):
            for key, (x, y) in group.items():
                group[key] = [c * x - s * y + dx * 1000, s * x + c * y + dy * 1000]  # mm
        moved["drives"][0]["angle"] = f"{60 + math.degrees(rot)!r} deg"
        k0 = lw.kinematics(lw.compile(lw.from_dict(data)), steps=24)
        k1 = lw.kinematics(lw.compile(lw.from_dict(moved)), steps=24)
        for p in ("B", "C", "D"):
            x0, x1 = k0.position(p), k1.position(p)
            np.testing.assert_allclose(
                x1, np.stack([c * x0[:, 0] - s * x0[:, 1] + dx, s * x0[:, 0] + c * x0[:, 1] + dy], -1), atol=1e-10
            )
            a0, a1 = k0.acceleration(p), k1.acceleration(p)
            np.testing.assert_allclose(
                a1, np.stack([c * a0[:, 0] - s * a0[:, 1], s * a0[:, 0] + c * a0[:, 1]], -1), atol=1e-8
            )


@pytest.mark.parametrize(
    "angles",
    [
        np.radians(90 + 360 * np.arange(8) / 8),
        np.radians(90 + 360 * np.arange(10) / 10),
        np.radians(np.arange(90, -270, -1.0)),  # clockwise
        np.radians([0.0]),
        np.radians([180.0]),
        np.radians([270.0]),  # alone, beyond a change point
        np.radians([30, 210, 120, 300]),  # unsorted
        np.radians(90 + 360 * np.arange(5) / 5),  # coarse
        np.linspace(0, 2 * np.pi, 13),
    ],
)
def test_change_points_of_the_isosceles_slider_crank_in_any_order(angles):
    mech = lw.compile(lw.example("shears-slider-crank"))
    kin = lw.kinematics(mech, angles)
    np.testing.assert_allclose(kin.position("B")[:, 1], 0.3 * np.sin(angles), atol=1e-12)
    np.testing.assert_allclose(kin.velocity("B")[:, 1], 3.0 * np.cos(angles), atol=1e-8)


@pytest.mark.parametrize("steps", [37, 100, 360, 361, 1000])
def test_a_parallelogram_stays_a_parallelogram(steps):
    from mechanisms import parallelogram_with_redundant_link

    mech = lw.compile(parallelogram_with_redundant_link().build())
    kin = lw.kinematics(mech, steps=steps)
    assert kin.valid.all()
    np.testing.assert_allclose(kin.position("B") - kin.position("A"), np.tile([0.3, 0.0], (steps, 1)), atol=1e-8)
    assert {e.kind for e in kin.events} <= {"singular", "change-point"}


@pytest.mark.parametrize(
    "kwargs, message",
    [
        ({"steps": 0}, "steps: expected a positive whole number"),
        ({"steps": 2.5}, "steps: expected a positive whole number"),
        ({"angles": []}, "no angles given"),
        ({"angles": [float("nan")]}, "angles must be finite"),
        ({"angles": [0.0], "speed": [1, 2]}, "speed: expected 1 finite value"),
        ({"angles": [0.0], "variants": {"links.crank.length": [[0.1, 0.2]]}}, "one-dimensional"),
    ],
)
def test_odd_inputs_give_clear_errors(kwargs, message):
    mech = lw.compile(lw.example("four-bar"))
    with pytest.raises(lw.errors.LinkworkError, match=message):
        lw.kinematics(mech, **kwargs)


def test_a_drive_on_the_frame_measures_the_crank_angle_whatever_the_order_of_its_links():
    """``links: [crank, frame]`` describes the same drive as ``[frame, crank]``: the crank angle is the crank's
    angle counter-clockwise from the frame's x axis, and ``ccw`` turns it counter-clockwise."""
    from linkwork.examples import text

    src = text("four-bar")
    swapped = src.replace("links: [frame, crank]", "links: [crank, frame]")
    assert swapped != src
    a, b = (lw.compile(lw.loads(s)) for s in (src, swapped))
    phi = np.radians([0.0, 60.0, 135.0, 250.0])
    ka, kb = lw.kinematics(a, phi), lw.kinematics(b, phi)
    np.testing.assert_allclose(np.cos(kb.angle("crank") - phi), 1.0, atol=1e-15)  # the angle asked for
    assert kb.omega("crank") == pytest.approx(np.full(4, 2 * np.pi))  # 60 rpm ccw
    for point in ("A", "B"):
        np.testing.assert_allclose(kb.position(point), ka.position(point), atol=1e-15)
        np.testing.assert_allclose(kb.acceleration(point), ka.acceleration(point), atol=1e-12)
    fa, fb = lw.forces(a, phi), lw.forces(b, phi)
    np.testing.assert_allclose(fb.driving_torque, fa.driving_torque, rtol=1e-12)
    np.testing.assert_allclose(fb.reaction("O2", on="crank"), fa.reaction("O2", on="crank"), rtol=1e-12)


@pytest.mark.parametrize("angle", [0.5, 1.0, 2.0, 4.9])
def test_a_single_angle_of_a_rhombus_reports_no_event_it_was_not_asked_about(angle):
    """All four sides equal: the parallelogram and the folded (kite) modes meet at 0 and 180 deg.  An
    angle a little beside 0 is reached from the assembly pose (60 deg, parallelogram) on a path whose
    grid has a point at 0; what happens there is not at the angle asked, and is not reported.  The
    pose itself is the parallelogram's: B = A + (100 mm, 0)."""
    mech = lw.compile(lw.loads(RHOMBUS))
    phi = np.radians([angle])
    kin = lw.kinematics(mech, phi)
    assert kin.valid.all()
    assert kin.events == ()
    a = 0.1 * np.stack([np.cos(phi), np.sin(phi)], -1)
    np.testing.assert_allclose(kin.position("A"), a, atol=1e-15)
    np.testing.assert_allclose(kin.position("B"), a + [0.1, 0.0], atol=1e-12)


def test_events_of_asked_angles_lie_within_their_span():
    """Angles that straddle the change point at 180 deg report it there, and nothing at 0 deg, which the
    path from the assembly pose passes but the angles do not."""
    mech = lw.compile(lw.loads(RHOMBUS))
    kin = lw.kinematics(mech, np.radians([3.0, 185.0, 175.0]))
    assert kin.valid.all()
    assert {e.kind for e in kin.events} == {"singular", "change-point"}
    for e in kin.events:
        assert math.degrees(e.start) == pytest.approx(180.0, abs=1e-6)
        assert math.degrees(e.end) == pytest.approx(180.0, abs=1e-6)


KERNELS = pytest.mark.parametrize(
    "compiled", [pytest.param(True, marks=pytest.mark.numba), False], ids=["compiled", "numpy"]
)


def _kernels(monkeypatch, compiled):
    """Solve with the compiled kernels or with NumPy's."""
    from linkwork.motion import kernels_numba

    monkeypatch.setenv("LINKWORK_NUMBA", "1" if compiled else "0")
    assert kernels_numba.available() == compiled  # the compiled case is in the numba lane, which turns them on


def _check_motion(mech, runs, expected, point="B", atol=1e-12, vtol=1e-8, slope=None):
    """Every run (angles asked, or steps) assembles everywhere, with ``point`` where ``expected(phi)`` has it
    and its velocity the closed form's derivative ``slope(phi)`` (default central differences) times the
    crank's speed."""
    h = 1e-6
    slope = slope or (lambda phi: (expected(phi + h) - expected(phi - h)) / (2 * h))
    for run_kw in runs:
        kin = lw.kinematics(mech, **run_kw)
        phi = kin.angles
        assert kin.valid.all(), run_kw
        np.testing.assert_allclose(kin.position(point), expected(phi), atol=atol, err_msg=str(run_kw))
        np.testing.assert_allclose(
            kin.velocity(point), slope(phi) * kin.omega("crank")[:, None], atol=vtol, err_msg=str(run_kw)
        )


def _single_batch_coarse(angles, *fine):
    """The angles one at a time, all at once, the fine batches given, and a coarse whole turn."""
    return [{"angles": [x]} for x in angles] + [{"angles": angles}] + [{"angles": f} for f in fine] + [{"steps": 8}]


@KERNELS
@pytest.mark.parametrize("folded", [False, True], ids=["parallelogram", "folded"])
def test_a_rhombus_keeps_its_mode_through_its_flat_positions(folded, compiled, monkeypatch):
    """All sides 100 mm, the frame along x.  Assembled as a parallelogram (60 deg) it stays one,
    B = A + (100 mm, 0), moving with A; assembled folded (B on O2) it stays folded, B at rest.  At 0 deg
    A lies on O4 (coupler and rocker could turn together about it; the two modes are 200 mm apart), at
    180 deg the two modes meet (B on O2): each mode goes on with a continuous velocity.  So it is
    whether the angles are asked one at a time, all at once with samples on 0 and 180 deg, or in
    coarse steps whose path from the assembly angle has points on 0 and 180 deg."""
    _kernels(monkeypatch, compiled)
    mech = lw.compile(lw.loads(RHOMBUS.replace("B: [150, 86.6]", "B: [0, 0]") if folded else RHOMBUS))

    def expected(phi):
        a = 0.1 * np.stack([np.cos(phi), np.sin(phi)], -1)
        return np.zeros_like(a) if folded else a + [0.1, 0.0]

    angles = np.radians([-20.0, -0.5, 0.0, 0.5, 30.0, 175.0, 180.0, 185.0, 270.0])
    down, up = np.radians(np.arange(65.0, -26.0, -1.0)), np.radians(np.arange(55.0, 200.0, 1.0))
    _check_motion(mech, _single_batch_coarse(angles, down, up, np.radians(np.arange(-10.0, 11.0, 1.0))), expected)
    kin = lw.kinematics(mech, down)  # on 0 deg: a singular position, and the modes trade places there
    assert {e.kind for e in kin.events} == {"singular", "change-point"}
    for e in kin.events:
        assert math.degrees(e.start) == pytest.approx(0.0, abs=1e-9)


@KERNELS
@pytest.mark.parametrize("transform", [(0.0, 0.0, 0.02), (0.0, 1.0, 1.0), (2.0, -2.0, 2.5)])
@pytest.mark.parametrize("left", [True, False], ids=["parallelogram", "folded"])
def test_a_rhombus_moved_rigidly_moves_alike_with_its_crank_on_the_frame(left, transform, compiled, monkeypatch):
    """The unit rhombus turned and shifted: samples a rounding off the crank lying on the frame (A on O4)
    assemble as those exactly on it do, with B where the parallelogram (B = A + the frame's unit vector)
    or the folded rhombus (B on O2) has it, and its velocity (that of A, or none), the coupler and
    rocker there following the motion through the position, not anywhere on their common circle."""
    _kernels(monkeypatch, compiled)
    dx, dy, rot = transform
    data, _ = four_bar_spec(1.0, 1.0, 1.0, 1.0, 0.5, left, transform)
    mech = lw.compile(lw.from_dict(data))
    frame = np.array([math.cos(rot), math.sin(rot)])

    def expected(angle):
        a = np.stack([np.cos(angle), np.sin(angle)], -1)
        return [dx, dy] + (a + frame if left else 0 * a)

    def slope(angle):
        return np.stack([-np.sin(angle), np.cos(angle)], -1) * (1.0 if left else 0.0)

    offsets = np.linspace(-0.5, 0.5, 21)
    angles = rot + np.array([0.0, -0.25, 0.75])
    runs = _single_batch_coarse(angles, rot + 0.5 + offsets, rot + 0.25 + offsets)
    _check_motion(mech, runs, expected, atol=1e-12, vtol=1e-12, slope=slope)


def _kite_and_moved(left, transform, c=0.625):
    """The kite O2 A = A B = 0.5, O2 O4 = O4 B = c assembled at 0.25 rad (``left``: the kite, B the
    mirror image of O2 in A O4; else folded, B on O2), moved rigidly by ``transform``, and the closed
    form of B over the crank angle measured from the frame."""
    data, _ = four_bar_spec(0.5, 0.5, c, c, 0.25, left, transform)
    dx, dy, rot = transform
    cr, sr = math.cos(rot), math.sin(rot)

    def expected(angle):
        phi = angle - rot
        a = 0.5 * np.stack([np.cos(phi), np.sin(phi)], -1)
        u = np.array([c, 0.0]) - a
        u /= np.linalg.norm(u, axis=-1, keepdims=True)
        b = 2 * (a - np.sum(a * u, -1, keepdims=True) * u) if left else np.zeros_like(a)
        return np.stack([cr * b[:, 0] - sr * b[:, 1] + dx, sr * b[:, 0] + cr * b[:, 1] + dy], -1)

    return lw.compile(lw.from_dict(data)), expected


@KERNELS
@pytest.mark.parametrize("c", [0.625, 0.5625])
@pytest.mark.parametrize("transform", [(0.0, 0.0, 0.0), (0.0, 0.0, 0.02), (0.3, -0.2, 1.0), (0.3, 0.0, 0.0)])
@pytest.mark.parametrize("left", [True, False], ids=["kite", "folded"])
def test_a_kite_goes_through_its_change_points_alike_however_sampled_and_placed(
    left, transform, c, compiled, monkeypatch
):
    """The kite's two modes meet at 0 (A nearest O4) and at pi (farthest): the kite goes on as the
    mirror image, the folded one stays folded, the same one angle at a time, all at once with samples
    on the change points (exactly, or a rounding off them once the frame is turned), or in coarse
    steps; and the same with the whole mechanism turned and shifted.  With c = 0.5625 A passes only
    62.5 mm from O4, and their distance turns sharply there."""
    _kernels(monkeypatch, compiled)
    mech, expected = _kite_and_moved(left, transform, c)
    rot = transform[2]
    angles = rot + np.array([-0.25, 0.0, 0.1, np.pi - 0.1, np.pi, np.pi + 0.1])
    offsets = np.linspace(-0.5, 0.5, 21)
    runs = _single_batch_coarse(angles, rot + 0.25 + offsets, rot + 0.5 + offsets, rot + 0.05 * np.arange(-60, 71))
    if left:
        _check_motion(mech, runs, expected, atol=1e-11, vtol=1e-7)
        return
    # folded, B rests on O2: its velocity is zero, to rounding on the change points themselves (the
    # motion's limit there), to the conditioning of the velocity equations beside them
    _check_motion(mech, runs, expected, atol=1e-11, vtol=1e-10, slope=lambda phi: np.zeros((len(phi), 2)))
    for phi in (angles, rot + 0.5 + offsets):
        kin = lw.kinematics(mech, phi)
        on = np.abs(np.sin(phi - rot)) < 1e-12
        assert on.any()
        np.testing.assert_allclose(kin.velocity("B")[on], 0.0, atol=1e-13)


@KERNELS
@pytest.mark.parametrize("a, d, phi", [(0.8125, 0.75, 0.1), (1.0, 0.9375, 0.25)])
@pytest.mark.parametrize("crossed", [True, False], ids=["antiparallelogram", "parallelogram"])
def test_a_parallelogram_linkage_keeps_its_mode_through_its_flat_position(crossed, a, d, phi, compiled, monkeypatch):
    """Crank and rocker a, coupler and frame d < a, assembled at phi.  Open, B = A + (d, 0); crossed,
    A O4 B O2 is an isosceles trapezoid and B the mirror image of O2 in the perpendicular bisector of
    A O4.  At 0 rad (laid flat) the two modes meet; the crossed one sweeps through fast there (B at
    a / (a - d) times the crank's speed), too fast for any step to follow its curve: one on the flat
    position, whose velocity is lost, or a 5-degree path that steps across it."""
    _kernels(monkeypatch, compiled)
    data, _ = four_bar_spec(a, d, a, d, phi, not crossed)
    mech = lw.compile(lw.from_dict(data))

    def expected(phi):
        pa = a * np.stack([np.cos(phi), np.sin(phi)], -1)
        if not crossed:
            return pa + [d, 0.0]
        mid, u = (pa + [d, 0.0]) / 2, [d, 0.0] - pa
        u /= np.linalg.norm(u, axis=-1, keepdims=True)
        return -2 * np.sum(-mid * u, -1, keepdims=True) * u

    runs = _single_batch_coarse(np.array([-0.4, -0.25, -0.05, 0.0, 0.6]), phi + np.linspace(-0.5, 0.5, 21))
    _check_motion(mech, runs, expected, atol=1e-12, vtol=1e-6)


@KERNELS
@pytest.mark.parametrize("left", [True, False])
def test_a_dead_point_gap_between_samples_is_not_crossed(left, compiled, monkeypatch):
    """Crank and frame 0.5, coupler 0.09375, rocker 0.09765625: A passes over O4 at 0 rad, but the
    coupler and rocker cannot reach each other within 0.45 deg of it (|b - c| > |A O4|).  Samples on
    either side of that gap, whether a batch steps across it, a 5-degree path does, or fine steps go
    through it (NaN inside), keep B on the side of A O4 the hints gave it."""
    _kernels(monkeypatch, compiled)
    a, b, c = 0.5, 0.09375, 0.09765625
    data, _ = four_bar_spec(a, b, c, a, 0.3125, left)
    mech = lw.compile(lw.from_dict(data))

    def expected(phi):
        return np.array([circle_intersection((a * math.cos(x), a * math.sin(x)), b, (a, 0.0), c, left) for x in phi])

    def assembles(phi):  # c - b <= |A O4| <= b + c
        reach = 2 * a * np.abs(np.sin(np.asarray(phi) / 2))
        return (reach >= c - b) & (reach <= b + c)

    fine = np.linspace(0.3125, -0.2, 1025)
    assert not assembles(fine).all()
    for angles in ([-0.1875], 0.3125 + np.linspace(-0.5, 0.5, 21), fine):
        kin = lw.kinematics(mech, angles)
        keep = assembles(angles)
        assert (kin.valid == keep).all()
        np.testing.assert_allclose(kin.position("B")[keep], expected(np.asarray(angles)[keep]), atol=1e-12)


@KERNELS
def test_outer_joints_passing_near_each_other_keep_the_mode_however_sampled(compiled, monkeypatch):
    """O2 A = 0.19921875, O2 O4 = 0.203125 and A B = O4 B = 1: A passes 3.9 mm from O4 at 0 rad, and
    the coupler swings round within a few hundredths of a radian; no singular position is passed, so
    B stays on the same side of A O4 (a coarse path from the assembly angle must not take the swing
    for a change point)."""
    _kernels(monkeypatch, compiled)
    a, d = 0.19921875, 0.203125
    data, _ = four_bar_spec(a, 1.0, 1.0, d, 0.25, False)
    mech = lw.compile(lw.from_dict(data))

    def expected(phi):
        return np.array(
            [circle_intersection((a * math.cos(x), a * math.sin(x)), 1.0, (d, 0.0), 1.0, False) for x in phi]
        )

    runs = _single_batch_coarse(np.array([-0.25, -0.1, 0.5]), 0.25 + np.linspace(-0.5, 0.5, 21))
    _check_motion(mech, runs, expected, atol=1e-12, vtol=1e-6)


@KERNELS
@pytest.mark.parametrize("turn, dx, dy", [(0.0, 0.0, 0.0), (30.0, 1.0, 1.0), (-70.0, -0.3, 0.2)])
def test_the_isosceles_slider_crank_turned_and_shifted_keeps_its_change_points(turn, dx, dy, compiled, monkeypatch):
    """Seed 000 with its frame turned by ``turn`` deg and shifted: B = O + 2 l sin(phi) along the turned
    guide, with velocity 2 l w cos(phi), also on samples exactly on the change points (phi = 0, 180 deg
    from the guide's normal), where the margin of the dyad is a rounding off zero."""
    from linkwork.examples import text

    _kernels(monkeypatch, compiled)
    r = math.radians(turn)
    src = (
        text("shears-slider-crank")
        .replace("O: [0, 0]\n  mass", f"O: [{dx!r}, {dy!r}]\n  mass")
        .replace("axis: 90 deg", f"axis: {90 + turn!r} deg")
        .replace("angle: 90 deg ", f"angle: {90 + turn!r} deg ")
        .replace("B: [0, 0.30]", f"B: [{dx - 0.3 * math.sin(r)!r}, {dy + 0.3 * math.cos(r)!r}]")
    )
    mech = lw.compile(lw.loads(src))
    phi = np.radians(np.arange(0.0, 360.0, 15.0))
    kin = lw.kinematics(mech, phi + r)
    axis = np.array([-math.sin(r), math.cos(r)])
    np.testing.assert_allclose(kin.position("B"), [dx, dy] + 0.3 * np.sin(phi)[:, None] * axis, atol=1e-12)
    np.testing.assert_allclose(kin.velocity("B"), 3.0 * np.cos(phi)[:, None] * axis, atol=1e-8)


def test_readings_of_a_point_are_the_callers_own():
    """What a point's position, velocity and acceleration return can be written to without changing the
    next reading, and they are the crank pin's closed form (the file's crank O2A = 100 mm about O2 at the
    origin, 60 rpm counter-clockwise)."""
    kin = lw.kinematics(lw.compile(lw.example("four-bar")), steps=36)
    kin.position("A")[:] = 0.0
    kin.velocity("A")[:] = 0.0
    theta, w, r = kin.angles, 2 * math.pi, 0.100
    ring = np.stack([np.cos(theta), np.sin(theta)], -1)
    np.testing.assert_allclose(kin.position("A"), r * ring, atol=1e-15)
    np.testing.assert_allclose(kin.velocity("A"), w * r * ring[:, ::-1] * [-1, 1], atol=1e-14)
    np.testing.assert_allclose(kin.acceleration("A"), -w * w * r * ring, atol=1e-13)


def test_a_result_is_made_with_every_field_of_its_class():
    """The result is made without the dataclass's ``__init__`` (for speed): it holds every field all the
    same, and one made through ``__init__`` from its fields reads the same."""
    kin = lw.kinematics(lw.compile(lw.example("four-bar")), steps=12)
    assert set(vars(kin)) == {f.name for f in dataclasses.fields(lw.Kinematics)}
    again = dataclasses.replace(kin)
    np.testing.assert_array_equal(again.position("B"), kin.position("B"))
    np.testing.assert_array_equal(again.acceleration("coupler.A"), kin.acceleration("coupler.A"))
    assert again.events == kin.events


@pytest.mark.parametrize("name", ["double-cut-shears", "class3-triad", "shears-slider-crank"])
@pytest.mark.parametrize("ahead", [1.0, -1.0])
def test_a_turn_that_does_not_reach_the_assembly_angle_is_the_motion_followed_from_it(name, ahead):
    """Angles of a turn from elsewhere (the viewer's, from position 0): the same motion, change points, gaps and
    all, as the samples of one fine path that starts at the assembly angle and runs through them, in either
    direction, and the same angles backwards; for the slider-crank also with a crank too long for part of the
    turn."""
    mech = lw.compile(lw.load(name))
    crank = mech.link_names[max(int(i) for i in mech.pair_links[int(mech.drive_pair[0])])]
    length = lw.parameters(mech)[f"links.{crank}.length"]
    variants = {f"links.{crank}.length": [length, 1.4 * length if name == "shears-slider-crank" else length]}
    fine = float(mech.drive_start[0]) + ahead * np.radians(np.arange(0.0, 720.0, 0.5))  # from the assembly angle
    # 250 to 610 degrees on (the assembly angle is not among them), then the same backwards, ending before it
    whole = lw.kinematics(mech, fine, variants=variants)
    for taken in (slice(500, 1220), slice(1219, 499, -1)):  # towards the assembly angle's far side, and back to it
        led = lw.kinematics(mech, fine[taken], variants=variants)
        np.testing.assert_array_equal(led.valid_all, whole.valid_all[:, taken])
        for got, want in ((led.pose, whole.pose), (led.vel, whole.vel), (led.acc, whole.acc)):
            np.testing.assert_allclose(got, want[:, taken], rtol=0, atol=1e-9)
    if name == "shears-slider-crank":
        assert not led.valid_all[1].all() and led.valid_all[1].any()  # the second variant has its gaps


POINTS_AND_GUIDES = ["double-cut-shears", "stephenson-six-bar", "class3-triad", "crank-shaper", "offset slider-crank"]


@pytest.mark.parametrize("name", POINTS_AND_GUIDES)
def test_the_points_read_at_once_are_each_points_position_bit_for_bit(name):
    """``point_positions`` (the plans', the scheme's and ``points()``'s one pass over every point and variant)
    against ``position`` of each point, for three design variants and for each of them alone."""
    from mechanisms import TEXTBOOK

    mech = lw.compile(lw.load(name) if name not in TEXTBOOK else TEXTBOOK[name][0]().build())
    crank = mech.link_names[max(int(i) for i in mech.pair_links[int(mech.drive_pair[0])])]
    length = lw.parameters(mech)[f"links.{crank}.length"]
    kin = lw.kinematics(mech, steps=48, variants={f"links.{crank}.length": [length, 1.1 * length, 0.9 * length]})
    each = np.stack([kin.position(p) for p in mech.point_names])  # (P, V, A, 2)
    every = np.arange(len(mech.point_names))
    assert np.array_equal(kin.point_positions(every), each, equal_nan=True)
    assert np.array_equal(kin.points(), each.transpose(1, 2, 0, 3), equal_nan=True)
    for v in range(3):
        assert np.array_equal(kin.point_positions(every[::-1], v)[:, 0], each[::-1, v], equal_nan=True)


GUIDED = ["double-cut-shears", "shears-slider-crank", "crank-shaper", "offset slider-crank", "pin in slot"]


@pytest.mark.parametrize("name", GUIDED)
def test_each_slider_stays_on_its_guide_line(name):
    """``guide_lines`` (every guide at once, the one home of carrying a guide with its link): a unit direction, and
    the point of the pair's second link on the line, wherever the mechanism assembles, for two variants."""
    from linkwork.motion.analysis import guide_lines
    from linkwork.structure.model import PairType
    from mechanisms import TEXTBOOK

    mech = lw.compile(lw.load(name) if name not in TEXTBOOK else TEXTBOOK[name][0]().build())
    crank = mech.link_names[max(int(i) for i in mech.pair_links[int(mech.drive_pair[0])])]
    length = lw.parameters(mech)[f"links.{crank}.length"]
    kin = lw.kinematics(mech, steps=72, variants={f"links.{crank}.length": [length, 1.05 * length]})
    pairs = np.flatnonzero(mech.pair_type == PairType.PRISMATIC)
    assert len(pairs)
    origin, u = guide_lines(kin, pairs)  # (K, 2, V, A)
    ok = kin.valid_all
    np.testing.assert_allclose(np.hypot(u[:, 0], u[:, 1])[:, ok], 1.0, rtol=0, atol=1e-12)
    at = kin.point_positions(mech.pair_points[pairs, 1]).transpose(0, 3, 1, 2) - origin  # (K, 2, V, A)
    off = at[:, 0] * u[:, 1] - at[:, 1] * u[:, 0]  # across the line
    np.testing.assert_allclose(off[:, ok], 0.0, rtol=0, atol=1e-9)


NEAR_DUPLICATES = [
    [0.0, 1e-9],
    [1e-9, 0.0],
    [0.0, 1e-9, 2e-9],
    [-1e-9, 0.0, 1e-9],
    [0.0, 1e-9, 0.1, 0.2],
    [0.2, 1e-9, 0.0],
]


@pytest.mark.parametrize("base", [0.0, 180.0])
@pytest.mark.parametrize("offsets", NEAR_DUPLICATES + [[0.0, -1e-9], [-1e-9, 0.0, 1e-9, 1.0]])
def test_samples_a_rounding_beside_a_change_point_keep_the_motion_through_it(base, offsets):
    """The isosceles slider-crank (OA = AB = 0.15 m, 10 rad/s) at samples on and a 1e-9 deg beside its change
    points, in one batch: y_B = 2 l sin(phi), v_B = 2 l w cos(phi), the rod turning at -w, the foundation
    pushed along x by the crank's and the rod's centripetal share, (m1 + m1) (l / 2) w^2 cos(phi) (150 N)."""
    phi = np.radians(base + np.array(offsets))
    kin = lw.kinematics("shears-slider-crank", phi)
    np.testing.assert_allclose(kin.velocity("B")[:, 1], 3.0 * np.cos(phi), rtol=0, atol=1e-8)
    np.testing.assert_allclose(kin.omega("rod"), -10.0, rtol=0, atol=1e-8)
    forces = lw.forces("shears-slider-crank", phi)
    np.testing.assert_allclose(forces.foundation[:, 0], 150.0 * np.cos(phi), rtol=0, atol=1e-6)


@pytest.mark.parametrize("base", [0.0, 180.0])
@pytest.mark.parametrize("offsets", NEAR_DUPLICATES)
def test_a_parallelogram_batch_a_rounding_beside_its_flat_position_moves_as_one(base, offsets):
    """Crank and rocker 0.1 m, coupler and frame 0.3 m, assembled open: B = A + (0.3 m, 0), so the rocker
    turns with the crank, on its flat positions and a 1e-9 deg beside them alike."""
    data, _ = four_bar_spec(0.1, 0.3, 0.1, 0.3, 1.0, True)
    phi = np.radians(base + np.array(offsets))
    kin = lw.kinematics(lw.compile(lw.from_dict(data)), phi)
    np.testing.assert_allclose(kin.omega("rocker"), kin.omega("crank"), rtol=0, atol=1e-8)
    np.testing.assert_allclose(kin.velocity("B"), kin.velocity("A"), rtol=0, atol=1e-9)


def _batch_and_alone(mech, phi):
    kin = lw.kinematics(mech, phi)
    for i, x in enumerate(phi):
        one = lw.kinematics(mech, [x])
        here, alone = kin.pose[:, i], one.pose[:, 0]
        where = f"{x!r} in {phi}"
        np.testing.assert_allclose(here[..., :2], alone[..., :2], rtol=0, atol=1e-9, err_msg=where)
        np.testing.assert_allclose(np.cos(here[..., 2] - alone[..., 2]), 1.0, rtol=0, atol=1e-12, err_msg=where)
        np.testing.assert_allclose(kin.vel[:, i], one.vel[:, 0], rtol=0, atol=1e-7, err_msg=where)


@settings(max_examples=25, deadline=None)
@given(
    which=st.sampled_from(["shears-slider-crank", "rhombus", "parallelogram"]),
    base=st.sampled_from([0.0, np.pi, 1.0]),
    offsets=st.lists(
        st.sampled_from([0.0, 1e-12, -1e-12, 1e-9, -1e-9, 2e-9, 1e-6, 1e-3, -0.05, 0.1, 0.3]), min_size=2, max_size=5
    ),
)
def test_a_batch_gives_each_sample_what_the_sample_alone_gives(which, base, offsets):
    """Whatever the other samples of a batch (near duplicates, samples on either side of a change point, in
    any order), each sample's pose and velocities are those it has asked alone."""
    if which == "rhombus":
        mech = lw.compile(lw.loads(RHOMBUS))
    elif which == "parallelogram":
        mech = lw.compile(lw.from_dict(four_bar_spec(0.1, 0.3, 0.1, 0.3, 1.0, True)[0]))
    else:
        mech = lw.compile(lw.example(which))
    _batch_and_alone(mech, base + np.asarray(offsets))


@pytest.mark.parametrize("steps", [360, 24, 7])
def test_a_flat_touch_of_the_two_modes_is_no_change_point(steps):
    """A toggle press whose upper link ends its 89.9999 deg swing on the line of the ram's guide (the assembly pose):
    the ram's dyad's modes come within 35 nm there, but the upper link is itself at rest (the distance of the knee
    from the guide goes as tau^4), so the motion keeps its mode whatever the steps: with upper and lower links of
    equal length the ram is at twice the knee's height (the other mode would leave it at the pivot P), and its
    stroke is the file's 20 mm; no change point is reported."""
    from pathlib import Path

    mech = lw.compile(str(Path(__file__).parents[1] / "web" / "toggle-at-dead-centre.yaml"))
    kin = lw.kinematics(mech, steps=steps)
    knee, ram = kin.position("K"), kin.position("R")
    np.testing.assert_allclose(ram[:, 1], 2 * knee[:, 1], atol=1e-12)
    assert not [e for e in kin.events if e.kind == "change-point"]
    if steps == 360:
        assert ram[:, 1].min() == pytest.approx(-0.020, abs=1e-6)
