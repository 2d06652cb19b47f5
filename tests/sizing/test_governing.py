"""What governs each joint: the pin's and the bush's least diameters side by side (closed forms by hand), rolling
bearings flagged where the joint swings less than the angle between their elements, peaks refined, and joints
whose force grows without bound at a singular position not sized."""

from __future__ import annotations

import math

import numpy as np
import pytest

import linkwork as lw
from commandline import linkwork
from linkwork.sizing.bearings import Bush, bearings
from linkwork.sizing.governing import governing_table, pitch_angle
from linkwork.sizing.pairs import Pair
from linkwork.sizing.pin_shear import Steel, pins

C45 = Steel("C45", 340e6, 620e6, 280e6)
BRONZE = Bush("bronze", 15e6, 1.0, 2.5e6)


def _rocking(force: float, swing: float, w: float = 3.0, k: int = 3600) -> tuple[Pair, np.ndarray]:
    """A pair under a constant ``force`` rocking ``theta = swing / 2 sin(w t)`` over one period."""
    t = np.arange(k) * (2 * math.pi / w) / k
    g = swing / 2
    z = np.zeros(k)
    pair = Pair("J", "revolute", ("a", "b"), np.full(k, force), g * w * np.cos(w * t), g * np.sin(w * t), z, z)
    return pair, np.degrees(w * t)


def _row(force: float, swing: float) -> dict:
    pair, phi = _rocking(force, swing)
    found = bearings([pair], phi, 3.0, life_h=20000, bush=BRONZE)
    (row,) = governing_table(pins([pair], phi, C45, safety=2.0), found).record()
    return row


def test_the_bush_governs_a_pin_sized_for_strength_alone_by_hand():
    """F = 306.5 kN, k = 1: pin bending d = sqrt(4 F / (pi 170 MPa)) = 47.91 mm (its eye pressure
    F / d^2 = pi 170 / 4 = 133.5 MPa); the bronze bush's p: d = sqrt(F / 15 MPa) = 142.9 mm: the bush governs."""
    row = _row(306.5e3, math.radians(40))
    assert row["pin_d_mm"] == pytest.approx(1e3 * math.sqrt(4 * 306.5e3 / (math.pi * 170e6)), rel=1e-12)
    assert row["bush_d_mm"] == pytest.approx(1e3 * math.sqrt(306.5e3 / 15e6), rel=1e-12)
    assert row["pin_by"] == "pin bending" and row["bush_by"] == "bush p"
    assert row["governs"] == "bush p" and row["d_to_make_mm"] == pytest.approx(row["bush_d_mm"])
    assert 306.5e3 / (row["pin_d_mm"] / 1e3) ** 2 / 1e6 == pytest.approx(math.pi * 170 / 4)  # 133.5 MPa


def test_a_rolling_bearing_is_flagged_below_the_angle_between_its_elements():
    pitch = math.degrees(pitch_angle("ball"))  # 36 deg for 10 balls
    assert pitch == pytest.approx(36.0)
    assert _row(10e3, math.radians(1.88))["rolling_bearing"].startswith("no: swings 1.88 < 36 deg")
    assert _row(10e3, math.radians(pitch * 1.01))["rolling_bearing"] == "ok"


def test_the_peaks_are_refined_between_the_samples():
    """The double-cut shears' joint forces peak between the samples (the knives' force stops rising there): the
    sizing's peak is the refined one, at least the samples' largest, whatever the grid."""
    coarse = lw.size("double-cut-shears", motor=False, steps=90)
    fine = lw.size("double-cut-shears", motor=False, steps=360)
    for a, b in zip(coarse.pins.pins, fine.pins.pins, strict=True):
        assert a.force == pytest.approx(b.force, rel=1e-9)
        assert a.phi == pytest.approx(b.phi, abs=1e-6)


def test_joints_whose_force_is_unbounded_at_a_singular_position_are_said_and_not_sized():
    result = linkwork("size", "shears-slider-crank", "--no-motor")
    assert result.returncode == 0, result.stderr
    assert "not sized: joints O, A, B, guide: the force grows without bound" in result.stdout
    assert result.stdout.count("not sized: unbounded") == 4  # O on its two bearings, A, B


# ---------------------------------------------------------------------------------------------- main shaft


def test_the_shaft_shares_of_a_beam_on_two_supports():
    """Midway: F/2 each; overhung by c outside the nearer of two supports s apart: F (s + c)/s and F c/s (their
    difference is F: the moments about the nearer support balance)."""
    from linkwork.sizing.shaft import shares

    assert shares(0.4, None) == (0.5, 0.5)
    near, far = shares(0.4, 0.1)
    assert near == pytest.approx(1.25) and far == pytest.approx(0.25) and near - far == pytest.approx(1.0)


def test_the_main_shaft_runs_in_two_bearings_from_the_file(tmp_path):
    """The double-cut shears' O1 with the shaft 500 mm between bearings and the crank 150 mm outside: bearing 1
    carries 1.3 F, bearing 2 0.3 F; the shaft bends by F c at bearing 1, d = (32 F c / (pi 170 MPa))^(1/3)."""
    from linkwork.examples import text

    path = tmp_path / "m.yaml"
    path.write_text(
        text("double-cut-shears").replace(
            "    guide_F: 0.40\n", "    guide_F: 0.40\n  shaft: {spacing: 500 mm, overhang: 150 mm}\n", 1
        )
    )
    sized = lw.size(path, motor=False)
    shaft = sized.shaft
    assert shaft.joint == "O1" and shaft.given and shaft.shares == pytest.approx((1.3, 0.3))
    rows = {j.label: j for j in sized.bearings.joints}
    assert "O1" not in rows
    assert rows["O1/1"].force_max == pytest.approx(1.3 * shaft.force, rel=1e-12)
    assert rows["O1/2"].force_max == pytest.approx(0.3 * shaft.force, rel=1e-12)
    assert rows["O1/1"].diameter == pytest.approx(0.16)  # the file's pin of O1 is the journal in both
    assert shaft.diameter == pytest.approx((32 * shaft.force * 0.15 / (math.pi * 170e6)) ** (1 / 3), rel=1e-12)


def test_without_a_shaft_in_the_file_the_crank_sits_midway_and_the_default_is_said():
    sized = lw.size("double-cut-shears", motor=False)
    assert sized.shaft.shares == (0.5, 0.5) and not sized.shaft.given
    assert sized.shaft.spacing == pytest.approx(3 * 0.16)  # three journal diameters
    assert sized.shaft.moment == pytest.approx(sized.shaft.force * sized.shaft.spacing / 4)


def test_a_given_pin_below_either_least_diameter_is_said_too_small():
    """F = 100 kN: the bush's least d = sqrt(100 kN / 15 MPa) = 81.6 mm; a given 60 mm pin is too small, a given
    90 mm one is the diameter to make."""
    pair, phi = _rocking(100e3, math.radians(40))
    for d, says in ((0.060, "given too small"), (0.090, "given")):
        sizes = {"J": (d, d)}
        found = bearings([pair], phi, 3.0, life_h=20000, bush=BRONZE, pins=sizes)
        (row,) = governing_table(pins([pair], phi, C45, safety=2.0, sizes=sizes), found).record()
        assert row["governs"] == says and row["d_to_make_mm"] == pytest.approx(d * 1e3)
        assert row["bush_d_mm"] == pytest.approx(1e3 * math.sqrt(100e3 / 15e6), rel=1e-12)
