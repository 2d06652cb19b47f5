"""Sliders and blocks sized as steel blocks carrying their pins; the sized parts' proportions checked against each
other and the geometry, with what governs (each figure derived by hand from the rule stated in the module)."""

from __future__ import annotations

import math

import numpy as np
import pytest

import linkwork as lw
from linkwork.sizing.masses import STEEL, block_mass, block_of
from linkwork.synthesis import synthesize


def test_a_lightly_pressed_block_is_as_long_as_it_is_wide_and_a_loaded_one_as_its_guide_asks():
    # d = 100 mm, k = 1: w = 200 mm, t = 100 mm; no guide force: l = w
    assert block_mass(0.1, 1.0, 0.0, 0.0, 15e6) == pytest.approx(STEEL * 0.2 * 0.1 * 0.2, rel=1e-12)
    # N = 1 MN on bronze at 15 MPa over t = 100 mm: l = N / (p t) = 0.6667 m
    assert block_mass(0.1, 1.0, 1e6, 0.0, 15e6) == pytest.approx(STEEL * 0.2 * 0.1 * (1e6 / 1.5e6), rel=1e-12)
    # with a moment the bearing length balances p t = N / l + 6 M / l^2 (the guide's linear pressure)
    b = block_of(0.1, 1.0, 2e5, 3e4, 15e6)
    assert 15e6 * 0.1 == pytest.approx(2e5 / b.length + 6 * 3e4 / b.length**2, rel=1e-12)


@pytest.fixture(scope="module")
def press_40t(tmp_path_factory):
    """A central press of 160 mm stroke loaded with 400 kN (40 t) over the last 10 mm."""
    path = tmp_path_factory.mktemp("press") / "press.yaml"
    synthesize("slider-crank", stroke=0.16, time_ratio=1.0, rod_ratio=0.25, force=4e5, working=0.01).write(path)
    return path


@pytest.mark.slow  # a sizing to the fixed point, about 6 s
def test_the_ram_of_a_40_t_press_carries_its_pin_not_the_mass_of_a_40_x_20_mm_bar(press_40t):
    s = lw.size(press_40t, motor=False)  # masses sized by default
    assert s.masses is not None and "ram" in s.masses.blocks
    joints = {row[0]: row for row in s.tables()[0].rows}  # the joints' table: what governs
    d = joints["B"][7] / 1e3  # the diameter B is made to, m
    # the bush governs at 400 kN: d = sqrt(F / (k p)) at p = 15 MPa
    assert d == pytest.approx(math.sqrt(joints["B"][1] * 1e3 / 15e6), rel=1e-3)
    guide = next(g for g in s.bearings.guides if "ram" in g.links)
    expected = block_mass(d, 1.0, guide.force_max, guide.moment_max, 15e6)
    assert s.masses.masses["ram"] == pytest.approx(expected, rel=2e-3)  # the fixed point's last round
    assert s.masses.masses["ram"] > 100.0  # 1.9 kg by the bar rule


@pytest.mark.slow  # a synthesis and a sizing, about 10 s
def test_toggle_links_shorter_than_their_pins_eyes_are_warned_with_the_length_they_need(tmp_path):
    from commandline import linkwork

    path = tmp_path / "knuckle.yaml"
    synthesize("toggle-press", stroke=0.04, force=1e6, before=0.002, torque=2e4).write(path)
    s = lw.size(path, motor=False)
    made = {row[0]: row[7] / 1e3 for row in s.tables()[0].rows}
    main = max(made["O/1"], made["O/2"])  # the crank's main shaft on its two bearings
    crank = lw.load(path).links["crank"].length
    assert crank < main + made["A"]  # the eyes of 2 d overlap: by hand from the joints' table
    eyes = next(c for c in s.proportions.checks if c.part == "crank" and c.rule.startswith("eyes"))
    assert not eyes.fits and eyes.needs == pytest.approx(main + made["A"], rel=1e-12)
    assert eyes.has == pytest.approx(crank, rel=1e-12) and eyes.governs == "pins: an eccentric"  # the driven crank
    rod = next(c for c in s.proportions.checks if c.part == "rod" and c.rule.startswith("eyes"))
    assert not rod.fits and rod.governs == "pins"
    run = linkwork("size", str(path), "--no-motor")
    assert run.returncode == 0 and "warning: does not fit: rod: eyes A-K apart" in run.stdout


@pytest.mark.slow  # a synthesis and a sizing, about 8 s
def test_the_shapers_block_stays_in_its_slot_and_says_so(tmp_path):
    path = tmp_path / "shaper.yaml"
    synthesize("slotted-lever", stroke=0.5, time_ratio=1.6).write(path)
    s = lw.size(path, motor=False)
    slot = [c for c in s.proportions.checks if c.rule.startswith("slot")]
    assert {c.rule for c in slot} == {"slot far end", "slot near end"} and all(c.fits for c in slot)
    spec = lw.load(path)
    far = next(c for c in slot if c.rule == "slot far end")
    # the block's pin reaches d + r along the lever; the need is that plus half the block of its rule
    reach = spec.frame.points["O1"][1] + spec.links["crank"].length
    crank = next(b for b in s.links.bars if b.link == "crank")  # the block's pin no thinner than the crank's bar
    bar = math.sqrt(4 * max(crank.area, math.pi * (crank.length / 20) ** 2 / 4) / math.pi)
    d = max({row[0]: row[7] / 1e3 for row in s.tables()[0].rows}["A"], bar)
    guide = next(g for g in s.bearings.guides if "block" in g.links)
    half = block_of(d, 1.0, guide.force_max, guide.moment_max, 15e6).length / 2
    assert far.needs == pytest.approx(reach + half, rel=1e-6)
    assert far.needs <= 0.9 * spec.links["lever"].length + 1e-4 + half  # the synthesis's margin holds it


def test_each_pair_of_a_bars_eyes_is_checked_against_the_sum_of_its_pins_diameters():
    """The four-bar (crank 100, coupler 350, rocker 250 mm) with pins chosen by hand: an eye fits where the joints
    are at least d1 + d2 apart; a shank needs the largest pin of its bar; the crank's overlap is an eccentric's."""
    from linkwork.sizing.links import bars
    from linkwork.sizing.pin_shear import Steel
    from linkwork.sizing.proportions import proportions

    f = lw.forces("four-bar", steps=36)
    linked = bars(f, np.degrees(np.ravel(f.angles)), Steel("C45", 340e6, 620e6, 280e6))
    made = {"O2": 0.06, "A": 0.05, "B": 0.02, "O4": 0.03}  # m
    depths = {b.link: 0.04 for b in linked.bars}
    checked = {(c.part, c.rule): c for c in proportions(f.mechanism, f.kinematics, made, linked, depths, {}).checks}
    crank = checked[("crank", "eyes O2-A apart")]
    assert crank.has == pytest.approx(0.1) and crank.needs == pytest.approx(0.11) and not crank.fits
    assert crank.governs == "pins: an eccentric"  # the link the drive turns
    coupler = checked[("coupler", "eyes A-B apart")]
    assert coupler.needs == pytest.approx(0.07) and coupler.fits and coupler.governs == "pins"
    assert checked[("rocker", "eyes B-O4 apart")].needs == pytest.approx(0.05)
    shank = checked[("crank", "shank depth")]
    assert shank.needs == pytest.approx(0.06) and shank.governs == "pin" and shank.verdict == "made to it"
    assert checked[("rocker", "shank depth")].verdict == "yes"  # 40 mm deep for a 30 mm pin: stress governs
