"""The range of the drive over which a mechanism assembles, and Grashof's class of a four-bar.

The limits are checked against the law of cosines (four-bars) and the closed form of an offset
slider-crank; the classes against cases classified by hand; the closed form against the solved turn.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

import linkwork as lw
from linkwork import MechanismBuilder
from linkwork.cli.main import app
from linkwork.errors import LinkworkError
from linkwork.examples import names
from linkwork.motion.drive_range import drive_range, grashof

runner = CliRunner()


def four_bar(a, b, c, d, phi_deg, *, upper=True, cw=False):
    """Crank a = O2A at phi, coupler b = AB, rocker c = O4B, frame d = O2O4 (lengths in mm); the hint puts B
    on the chosen side of the line A O4, found by intersecting the two circles."""
    phi = math.radians(phi_deg)
    ax, ay = a * math.cos(phi), a * math.sin(phi)
    ex, ey = d - ax, -ay
    e = math.hypot(ex, ey)
    x = (b * b - c * c + e * e) / (2 * e)
    h = math.sqrt(b * b - x * x) * (1 if upper else -1)
    bx, by = ax + (x * ex - h * ey) / e, ay + (x * ey + h * ex) / e
    return (
        MechanismBuilder("four-bar", units={"length": "mm"})
        .frame(points={"O2": (0, 0), "O4": (d, 0)})
        .link("crank", ends=("O2", "A"), length=a)
        .link("coupler", ends=("A", "B"), length=b)
        .link("rocker", ends=("O4", "B"), length=c)
        .revolute("O2", "frame", "crank")
        .revolute("A", "crank", "coupler")
        .revolute("B", "coupler", "rocker")
        .revolute("O4", "frame", "rocker")
        .drive("O2", speed="60 rpm", direction="cw" if cw else "ccw", angle=f"{phi_deg} deg")
        .hint("B", bx, by)
        .build()
    )


def cosine_limits(a, b, c, d):
    """Crank angles in [0, pi] where A is b + c or |b - c| from O4 (law of cosines), where it can be."""
    cosines = [(a * a + d * d - e * e) / (2 * a * d) for e in (abs(b - c), b + c)]
    return sorted(math.acos(x) for x in cosines if abs(x) <= 1)


@pytest.mark.parametrize("cw", [False, True])
def test_a_coupler_that_assembles_only_from_26_to_72_deg_gives_its_limits(cw):
    """The issue's four-bar: crank 100, coupler 250, rocker 35, frame 300 mm. A O4 must lie between
    b - c = 215 and b + c = 285 mm, so the crank moves between 26.33 and 71.76 deg; the mirror interval
    about the frame line assembles too, out of reach."""
    low, high = cosine_limits(100, 250, 35, 300)
    assert math.degrees(low) == pytest.approx(26.33, abs=0.01) and math.degrees(high) == pytest.approx(71.76, abs=0.01)
    r = drive_range(lw.compile(four_bar(100, 250, 35, 300, 50, cw=cw)))
    assert not r.full_turn and r.joint == "O2"
    np.testing.assert_allclose(r.reach, (low, high), atol=1e-5 * math.pi / 180)
    assert len(r.others) == 1
    np.testing.assert_allclose(r.others[0], (-high, -low), atol=1e-5 * math.pi / 180)
    assert "O2 cannot make a full turn: it moves from 26.33 to 71.76 deg only" == r.warning()


NARROW = """\
name: narrow four-bar
units: {length: mm}
frame: {points: {O2: [0, 0], O4: [300, 0]}}
links:
  crank: {ends: [O2, A], length: 100}
  coupler: {ends: [A, B], length: 250}
  rocker: {ends: [O4, B], length: 35}
joints:
  O2: {type: revolute, links: [frame, crank]}
  A: {type: revolute, links: [crank, coupler]}
  B: {type: revolute, links: [coupler, rocker]}
  O4: {type: revolute, links: [frame, rocker]}
drives:
  - {joint: O2, speed: 60 rpm, angle: 50 deg}
hints: {B: [290, 30]}
"""


def test_check_reports_the_range_and_warns_but_exits_0(tmp_path):
    path = tmp_path / "narrow.yaml"
    path.write_text(NARROW, encoding="utf-8")
    result = runner.invoke(app, ["check", str(path)])
    assert result.exit_code == 0, result.output
    assert "drive range: O2 from 26.33 to 71.76 deg, between its limit positions" in result.stdout
    assert "(it assembles also from -71.76 to -26.33 deg, out of its reach)" in result.stdout
    assert "warning: O2 cannot make a full turn: it moves from 26.33 to 71.76 deg only" in result.stdout
    assert "Grashof: s + l = 0.335 m < p + q = 0.35 m: crank-rocker, rocker turns fully" in result.stdout
    out = json.loads(runner.invoke(app, ["check", str(path), "--json"]).stdout)
    low, high = cosine_limits(100, 250, 35, 300)
    assert out["drive_range"]["full_turn"] is False
    np.testing.assert_allclose(out["drive_range"]["reach_deg"], np.degrees([low, high]), atol=1e-5)
    assert out["drive_range"]["grashof"]["class"] == "crank-rocker"
    assert out["drive_range"]["grashof"]["drive_turns"] is False
    assert any("cannot make a full turn" in w for w in out["warnings"])


def test_a_full_turn_crank_rocker():
    """The bundled four-bar: crank 100, coupler 350, rocker 250, frame 300 mm; s + l = 450 < p + q = 550
    with the crank the shortest, so the crank turns fully."""
    r = drive_range(lw.compile(lw.example("four-bar")))
    assert r.full_turn and r.others == () and r.warning() is None
    assert r.reach[1] - r.reach[0] == pytest.approx(2 * math.pi)
    g = r.grashof
    assert (g.kind, g.cranks, g.drive_turns) == ("crank-rocker", ("crank",), True)
    assert g.links == ("frame", "crank", "coupler", "rocker")
    np.testing.assert_allclose(g.lengths, (0.3, 0.1, 0.35, 0.25), rtol=1e-12)
    assert (g.s_plus_l, g.p_plus_q) == (pytest.approx(0.45), pytest.approx(0.55))
    result = runner.invoke(app, ["check", "four-bar"])
    assert result.exit_code == 0 and "drive range: full turn of O2 (assembles at all 720 angles)" in result.stdout
    assert "warning" not in result.stdout


# (crank a, coupler b, rocker c, frame d, crank angle of the assembly pose): class, cranks, drive turns;
# each worked by hand from s + l against p + q and which link is the shortest
HAND = [
    ((100, 350, 250, 300, 60), "crank-rocker", ("crank",), True),  # s = a: 450 < 550
    ((250, 350, 100, 300, 90), "crank-rocker", ("rocker",), False),  # s = c: 450 < 550, the crank rocks
    ((300, 350, 250, 100, 60), "double-crank", ("crank", "rocker"), True),  # s = d: 450 < 550
    ((250, 100, 350, 300, 80), "double-rocker", (), False),  # s = b: 450 < 550, only the coupler turns
    ((220, 350, 250, 300, 60), "triple-rocker", (), False),  # 220 + 350 = 570 > 550
    ((100, 300, 100, 300, 50), "change-point", ("crank", "rocker"), True),  # parallelogram: 400 = 400
]


@pytest.mark.parametrize("dims, kind, cranks, turns", HAND)
def test_grashof_classes_worked_by_hand(dims, kind, cranks, turns):
    *lengths, phi = dims
    g = grashof(lw.compile(four_bar(*lengths, phi)))
    assert (g.kind, g.cranks, g.drive_turns) == (kind, cranks, turns)


@pytest.mark.parametrize("dims, kind, cranks, turns", [h for h in HAND if h[1] != "change-point"])
def test_the_solved_turn_agrees_with_grashof_and_the_law_of_cosines(dims, kind, cranks, turns):
    """Where the crank cannot turn fully its limits are where A O4 reaches b + c or |b - c|."""
    *lengths, phi = dims
    r = drive_range(lw.compile(four_bar(*lengths, phi)))
    assert r.full_turn == turns
    if turns:
        return
    a, b, c, d = lengths
    inner = [x for x in cosine_limits(a, b, c, d) if 0 < x < math.pi]  # limits above the frame line
    exact = (inner[0], inner[1]) if len(inner) == 2 else (inner[0], 2 * math.pi - inner[0])
    np.testing.assert_allclose(r.reach, exact, atol=1e-5 * math.pi / 180)


def test_random_four_bars_turn_fully_exactly_when_grashof_says_so():
    rng = np.random.default_rng(7)
    seen = set()
    for _ in range(24):
        a, b, c = rng.uniform(40, 400, 3)
        d = 300.0
        for phi in (90, 60, 120, 30, 150):
            try:
                mech = lw.compile(four_bar(a, b, c, d, phi))
            except (ValueError, LinkworkError):  # no assembly at this angle
                continue
            break
        else:
            continue
        g = grashof(mech)
        if abs(g.s_plus_l - g.p_plus_q) < 1e-3:
            continue
        assert drive_range(mech).full_turn == g.drive_turns, (a, b, c)
        seen.add(g.drive_turns)
    assert seen == {True, False}


def test_an_offset_slider_crank_assembles_where_the_rod_reaches_the_guide():
    """Crank 100, rod 150 mm, guide the line y = 100 mm: B is on it only while 100 - 100 sin(phi) <= 150,
    i.e. sin(phi) >= -1/2: the crank moves from -30 to 210 deg."""
    spec = (
        MechanismBuilder("offset slider-crank", units={"length": "mm"})
        .frame(points={"O": (0, 0), "G": (0, 100)})
        .link("crank", ends=("O", "A"), length=100)
        .link("rod", ends=("A", "B"), length=150)
        .link("slider", points={"B": (0, 0)})
        .revolute("O", "frame", "crank")
        .revolute("A", "crank", "rod")
        .revolute("B", "rod", "slider")
        .prismatic("guide", "frame", "slider", point="B", through="G", axis=0)
        .drive("O", speed="100 rpm", angle="90 deg")
        .hint("B", 150, 100)
        .build()
    )
    r = drive_range(lw.compile(spec))
    assert not r.full_turn and r.others == () and r.grashof is None
    np.testing.assert_allclose(r.reach, np.radians([-30.0, 210.0]), atol=1e-5 * math.pi / 180)


def test_the_bundled_examples_make_full_turns():
    for name in names():
        r = drive_range(lw.compile(lw.example(name)))
        assert r.full_turn, (name, r.describe())
