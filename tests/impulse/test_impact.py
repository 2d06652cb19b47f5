"""The rocker's impact on the tool (seed 004): impulse-momentum balances, the paper's special
cases, the centre of percussion."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import linkwork as lw

# the tool below K (its upper end face): the striker comes down on it, turning clockwise
DATA = dict(inertia=0.30, mass=6.0, com=(0.16, 0.01), impact_point=(0.30, -0.02), omega_before=-30.0)
DATA.update(restitution=0.4, friction=0.15, rod_mass=1.2, rod_joint=(0.10, 0.02), normal=(0.0, 1.0))


def _balances(r, kw):
    """Linear momentum of rocker and reduced rod mass, angular momentum about O."""
    o = np.asarray(kw.get("support", (0.0, 0.0)))
    dw = r.omega_after - r.omega_before

    def dv(p):
        rel = np.asarray(p) - o
        return np.array([-dw * rel[1], dw * rel[0]])

    momentum = kw["mass"] * dv(kw["com"]) + kw.get("rod_mass", 0.0) * dv(kw.get("rod_joint", (0.0, 0.0)))
    scale = np.abs(r.impulse).max()
    np.testing.assert_allclose(momentum, r.impulse + r.support_impulse, rtol=0, atol=1e-12 * scale)
    rk = np.asarray(kw["impact_point"]) - o
    moment = rk[0] * r.impulse[1] - rk[1] * r.impulse[0]
    assert moment == pytest.approx(r.inertia * dw, rel=1e-12)


def test_the_example_against_the_papers_general_formulas():
    """Equations (4), (5), (8), (9) of the paper hold as printed for y_K < 0 (the example)."""
    r = lw.rocker_impact(**DATA)
    _balances(r, DATA)
    j_o = 0.30 + 1.2 * (0.10**2 + 0.02**2)
    w, big_r, f, xk, yk = -30.0, 0.4, 0.15, 0.30, -0.02
    iy = j_o * w * (1 + big_r) / (f * yk - xk)  # (4)
    ix = f * j_o * w * (1 + big_r) * math.copysign(1, yk) / (xk - yk * f)  # (5)
    i0x = w * (1 + big_r) * (6.0 * 0.01 + 1.2 * 0.02 - j_o * f * math.copysign(1, yk) / (xk - f * yk))  # (8)
    i0y = -w * (1 + big_r) * (6.0 * 0.16 + 1.2 * 0.10 + j_o / (f * yk - xk))  # (9)
    np.testing.assert_allclose(r.impulse, [ix, iy], rtol=1e-12)
    np.testing.assert_allclose(r.support_impulse, [i0x, i0y], rtol=1e-12)
    assert r.omega_after == pytest.approx(12.0)
    assert r.energy_loss == pytest.approx(0.5 * j_o * 30.0**2 * (1 - 0.4**2), rel=1e-12)


def test_the_collinear_case_of_the_paper():
    """C, N and K on the x axis (the paper's (10)): the support takes f J_O omega (1 + R) / x_K
    along x; along y the printed (10) has lost the minus sign of (9)."""
    kw = {**DATA, "com": (0.16, 0.0), "rod_joint": (0.10, 0.0), "impact_point": (0.30, 0.0)}
    r = lw.rocker_impact(**kw)
    _balances(r, kw)
    j_o, w = 0.30 + 1.2 * 0.10**2, -30.0 * 1.4
    assert r.support_impulse[0] == pytest.approx(w * j_o * 0.15 / 0.30, rel=1e-12)
    assert r.support_impulse[1] == pytest.approx(-w * (6.0 * 0.16 + 1.2 * 0.10 - j_o / 0.30), rel=1e-12)


def test_the_centre_of_percussion():
    """No friction, no rod, K on the x axis (the paper's (18)): the support feels nothing when the
    centre of mass is at x = J / (m x_K), y = 0."""
    kw = {**DATA, "friction": 0.0, "rod_mass": 0.0, "impact_point": (0.30, 0.0)}
    r = lw.rocker_impact(**kw)
    np.testing.assert_allclose(r.ideal_com, [0.30 / (6.0 * 0.30), 0.0], atol=1e-15)
    again = lw.rocker_impact(**{**kw, "com": tuple(r.ideal_com)})
    np.testing.assert_allclose(again.support_impulse, 0.0, atol=1e-12)
    # frictionless central impact: the impulse is J omega (1 + R) / x_K, the energy lost (1 - R^2) T
    assert again.impulse[1] == pytest.approx(0.30 * 30.0 * 1.4 / 0.30, rel=1e-12)
    assert again.energy_loss == pytest.approx((1 - 0.4**2) * 0.5 * 0.30 * 30.0**2, rel=1e-12)


def test_the_ideal_centre_of_mass_removes_the_support_impulse():
    r = lw.rocker_impact(**DATA)
    for com, rod in ((r.ideal_com, 1.2), (r.ideal_com_without_rod, 0.0)):
        again = lw.rocker_impact(**{**DATA, "com": tuple(com), "rod_mass": rod})
        np.testing.assert_allclose(again.support_impulse, 0.0, atol=1e-12 * np.abs(again.impulse).max())


@settings(max_examples=60, deadline=None)
@given(
    st.floats(0.05, 2.0),
    st.floats(1.0, 20.0),
    st.tuples(st.floats(-0.3, 0.3), st.floats(-0.3, 0.3)),
    st.tuples(st.floats(0.1, 0.6), st.floats(-0.1, 0.1)),
    st.floats(0.0, 0.3),
    st.floats(0.0, 1.0),
    st.floats(0.0, 3.0),
    st.floats(0.0, 2 * math.pi),
)
def test_impulse_momentum_balances_for_random_rockers(j, m, com, k, f, big_r, mu, turn):
    """Turned as a whole by ``turn`` (the face normal with it), any rocker balances to 1e-12."""
    c, s = math.cos(turn), math.sin(turn)

    def rot(p):
        return (c * p[0] - s * p[1], s * p[0] + c * p[1])

    kw = dict(inertia=j + m * (com[0] ** 2 + com[1] ** 2), mass=m, com=rot(com), impact_point=rot(k))
    kw.update(omega_before=-25.0, restitution=big_r, friction=f, rod_mass=mu, rod_joint=rot((0.1, 0.02)))
    kw.update(normal=rot((0.0, 1.0)))
    try:
        r = lw.rocker_impact(**kw)
    except lw.errors.LinkworkError:
        return  # a striker moving away from the tool: refused with a message
    _balances(r, kw)
    assert r.energy_loss >= 0
    assert float(np.dot(r.impulse, kw["normal"])) > 0  # the tool pushes the striker out


def test_impossible_impacts_are_refused():
    with pytest.raises(lw.errors.LinkworkError, match="does not move towards the tool"):
        lw.rocker_impact(**{**DATA, "normal": (0.0, -1.0)})
    with pytest.raises(lw.errors.LinkworkError, match="does not move towards the tool"):
        lw.rocker_impact(**{**DATA, "impact_point": (0.0, -0.3)})  # K below O: it slides along the face


BLOW = dict(normal=(0.0, 1.0), omega_before=-30.0, restitution=0.4, friction=0.15)


def _percussion(crank_mass=4.0, crank_inertia=0.004, rod=None):
    data = lw.example("percussion-rocker").model_dump(exclude_none=True)
    data["units"] = {"angle": "rad"}
    data["links"]["crank"].update(mass=crank_mass, inertia=crank_inertia)
    if rod is not None:
        data["links"]["rod"].update(rod)
    return lw.compile(lw.from_dict(data))


def test_whole_mechanism_reduced_to_one_body_equals_the_papers_model():
    """A massless crank, and the rod's mass as a point at N: the whole-mechanism impact is the
    model of item 1 with m_u at N, to rounding."""
    from linkwork.impulse import reduced_model

    mech = _percussion(crank_mass=1e-300, crank_inertia=0.0, rod={"mass": 1.2, "com": [0.20, 0.0], "inertia": 0.0})
    whole = lw.impact(mech, at="rocker.K", **BLOW)
    model = reduced_model(mech, at="rocker.K", rod_joint="N", **BLOW)
    assert model.inertia == pytest.approx(0.30 + 1.2 * (0.10**2 + 0.02**2), rel=1e-12)
    np.testing.assert_allclose(whole.impulse, model.impulse, rtol=1e-10)
    np.testing.assert_allclose(whole.on("O", "rocker"), model.support_impulse, rtol=1e-10, atol=1e-10)
    assert abs(whole.drive_impulse) < 1e-12 * np.abs(whole.impulse).max()


def test_whole_mechanism_impulses_balance_every_link():
    """Each link's change of momentum and of angular momentum about its centre of mass equals the
    impulses on it: the joints' (read back by joint) and the blow's."""
    from linkwork.kinetostatics.free_body import contacts

    mech = lw.compile(lw.example("percussion-rocker"))
    r = lw.impact(mech, at="rocker.K", **BLOW)
    assert abs(r.drive_impulse) < 1e-12 * np.abs(r.impulse).max()
    kin = r.forces.kinematics
    every = contacts(r.forces)
    for i, name in enumerate(mech.link_names[1:], 1):
        com = kin.pose[0, 0, i, :2]
        c, s = np.cos(kin.pose[0, 0, i, 2]), np.sin(kin.pose[0, 0, i, 2])
        lc = mech.link_com[i]
        rc = np.array([c * lc[0] - s * lc[1], s * lc[0] + c * lc[1]])
        dv = r.velocities_after[i] - r.velocities_before[i]
        dvc = dv[:2] + dv[2] * np.array([-rc[1], rc[0]])
        total, moment = np.zeros(2), 0.0
        for contact in every:
            if contact.on == i and not contact.drive:
                f = contact.force[0, 0]
                arm = contact.point[0, 0] - (com + rc)
                total += f
                moment += arm[0] * f[1] - arm[1] * f[0]
        if name == "rocker":
            arm = kin.position("rocker.K")[0] - (com + rc)
            total += r.impulse
            moment += arm[0] * r.impulse[1] - arm[1] * r.impulse[0]
        scale = np.abs(r.impulse).max()
        np.testing.assert_allclose(total, mech.link_mass[i] * dvc, rtol=0, atol=1e-12 * scale)
        assert moment == pytest.approx(mech.link_inertia[i] * dv[2], abs=1e-12 * scale)
    # the real crank and rod make the blow harder than the reduced model says
    assert np.abs(r.impulse[1]) > 1.1 * 43.3


def test_whole_mechanism_ideal_centre_of_mass():
    """Moved there (mass and inertia about O kept), the rocker's centre of mass leaves its support
    without an impulse."""
    import dataclasses

    mech = lw.compile(lw.example("percussion-rocker"))
    r = lw.impact(mech, at="rocker.K", **BLOW)
    i = mech.link_names.index("rocker")
    q = mech.pose0[i]
    c, s = np.cos(q[2]), np.sin(q[2])
    d = r.ideal_com - q[:2]
    local = np.array([c * d[0] + s * d[1], -s * d[0] + c * d[1]])
    com = np.array(mech.link_com)
    inertia = np.array(mech.link_inertia)
    about_o = inertia[i] + mech.link_mass[i] * np.sum(com[i] ** 2)  # O is the rocker's origin
    com[i] = local
    inertia[i] = about_o - mech.link_mass[i] * np.sum(local**2)
    moved = dataclasses.replace(mech, link_com=com, link_inertia=inertia)
    again = lw.impact(moved, at="rocker.K", **BLOW)
    np.testing.assert_allclose(again.on("O", "rocker"), 0.0, atol=1e-12 * np.abs(again.impulse).max())
    np.testing.assert_allclose(again.impulse, r.impulse, rtol=1e-12)


def test_impact_command_json():
    from typer.testing import CliRunner

    import linkwork.cli.impact  # noqa: F401 - registers the command
    from linkwork.cli.main import app

    result = CliRunner().invoke(app, ["impact", "percussion-rocker", "--json"])
    assert result.exit_code == 0, result.output
    out = json.loads(result.stdout)
    for key in ("impulse", "support_impulse", "omega_after", "energy_loss", "ideal_com"):
        assert key in out
    assert out["omega_after"] == pytest.approx(12.0, rel=1e-12)
    assert out["support_impulse"]["O"]["on"] == "rocker"
    # the reduced model against the paper's (4), (5), (8), (9) (valid for y_K < 0)
    j_o, w, f, xk, yk = 0.30 + 1.2 * (0.10**2 + 0.02**2), -30.0 * 1.4, 0.15, 0.30, -0.02
    iy = j_o * w / (f * yk - xk)
    i0y = -w * (6.0 * 0.16 + 1.2 * 0.10 + j_o / (f * yk - xk))
    assert out["model"]["impulse"]["y"] == pytest.approx(iy, rel=1e-12)
    assert out["model"]["impulse"]["x"] == pytest.approx(f * iy, rel=1e-12)
    assert out["model"]["support_impulse"]["O"]["y"] == pytest.approx(i0y, rel=1e-12)
    bare = CliRunner().invoke(app, ["impact", "four-bar"])
    assert bare.exit_code == 2 and 'give an "impact:" section' in bare.stderr


def test_the_whole_mechanism_impact_says_when_the_sliding_reverses():
    """In one degree of freedom K's velocity after the blow is -R times the one before, tangential part
    included: with R > 0 the sliding reverses (read off the velocities), with R = 0 it only stops."""
    mech = lw.compile(lw.load("percussion-rocker"))
    kw = dict(at="rocker.K", normal=(0.0, 1.0), omega_before=-30.0, friction=0.15)
    bouncing, plastic = lw.impact(mech, restitution=0.4, **kw), lw.impact(mech, restitution=0.0, **kw)
    kin = lw.kinematics(mech, mech.drive_start[:1], speed=1.0)
    g_t = float(kin.velocity("rocker.K")[0, 0])  # the tangent of a horizontal face is x
    before, after = g_t * bouncing.speed_before, g_t * bouncing.speed_after
    assert before * after < 0 and bouncing.sliding_reverses
    assert g_t * plastic.speed_after == 0 and not plastic.sliding_reverses
    assert not lw.impact(mech, restitution=0.4, **{**kw, "friction": 0.0}).sliding_reverses
