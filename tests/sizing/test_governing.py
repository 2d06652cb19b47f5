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
    assert result.stdout.count("not sized: unbounded") == 3
