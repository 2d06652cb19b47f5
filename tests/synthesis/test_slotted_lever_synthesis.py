"""Slotted-lever (crank-shaper) synthesis: the written file, as the kinematic analysis measures it, meets the
stroke and time ratio; the tangent construction agrees with a brute-force sweep of the geometry; the guide's
height is the one with the least largest pressure angle; impossible requirements say what can be met."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import linkwork as lw
from linkwork.errors import SynthesisError
from linkwork.motion.analysis import extremes, transmission
from linkwork.synthesis import synthesize

#: A bound on the least transmission angle low enough that the geometry alone decides (the design rule's 40 deg
#: refuses some of the random requests, which these tests make for the geometry).
FREE = 1e-6


def brute_force(d: float, r: float, lever: float, h: float, rod: float, n: int = 400_001) -> tuple:
    """Ram stroke, time ratio and largest rod pressure angle of the shaper swept over a dense turn of the
    crank by its plain geometry (no tangent construction): the lever through O2 and the crank pin, the ram
    where the rod from the lever's tip meets the guide."""
    phi = np.linspace(0.0, 2 * np.pi, n, endpoint=False)
    ax, ay = r * np.cos(phi), d + r * np.sin(phi)
    lever_angle = np.arctan2(ax, ay)  # from the vertical
    cx, cy = lever * np.sin(lever_angle), lever * np.cos(lever_angle)
    x = cx + np.sqrt(rod**2 - (h - cy) ** 2)
    lo, hi = int(np.argmin(x)), int(np.argmax(x))
    turned = (phi[lo] - phi[hi]) % (2 * np.pi)
    k = max(turned, 2 * np.pi - turned) / min(turned, 2 * np.pi - turned)
    return x[hi] - x[lo], k, float(np.max(np.abs(np.arcsin((h - cy) / rod))))


def analysed(spec) -> tuple[float, float, float]:
    """The ram's stroke, K and the rod's largest pressure angle as the analysis measures them (a fine turn)."""
    kin = lw.kinematics(spec, steps=3600)
    (ram,) = [e for e in extremes(kin) if e.kind == "slider"]
    (mu,) = [v for k, v in transmission(kin).items() if k.endswith("RRP")]
    return ram.stroke, ram.time_ratio, math.pi / 2 - float(np.min(mu))


def test_k_2_gives_the_lever_as_long_as_the_stroke_and_the_block_a_tenth_of_it_from_its_end():
    """K = 2: theta = 60 deg, sin(theta / 2) = 1/2, so L = H, d + d/2 = 0.9 L (the block's margin) and r = d / 2."""
    s = synthesize("slotted-lever", stroke=0.5, time_ratio=2.0)
    dims = s.dimensions
    assert dims["lever"] == pytest.approx(0.5, rel=1e-12)
    assert dims["frame"] == pytest.approx(0.3, rel=1e-12) and dims["crank"] == pytest.approx(0.15, rel=1e-12)
    assert dims["guide_height"] == pytest.approx(0.25 * (1 + math.sqrt(3) / 2), rel=1e-12)
    stroke, k, alpha = analysed(s.spec)
    tol = s.tolerances  # the lengths written to 0.1 mm
    assert stroke == pytest.approx(0.5, abs=tol["stroke"]) and k == pytest.approx(2.0, abs=tol["time_ratio"])
    assert alpha == pytest.approx(math.radians(10), abs=tol["max_pressure_angle"] + 1e-6)  # sampled


def test_the_tangent_construction_agrees_with_a_brute_force_sweep_of_the_geometry():
    s = synthesize("slotted-lever", stroke=0.6, time_ratio=1.6, frame=0.5, rod=0.3)
    d, r, lever, h, rod = (s.dimensions[n] for n in ("frame", "crank", "lever", "guide_height", "rod"))
    stroke, k, alpha = brute_force(d, r, lever, h, rod)
    assert stroke == pytest.approx(0.6, rel=1e-8) and k == pytest.approx(1.6, rel=1e-4)
    from linkwork.synthesis.slotted_lever import largest_pressure_angle

    theta = math.pi * 0.6 / 2.6  # K = 1.6
    assert alpha == pytest.approx(largest_pressure_angle(lever, theta, rod), rel=1e-8)  # the closed form's


@pytest.mark.parametrize("shift", [-0.02, -0.002, 0.002, 0.02])
def test_the_guide_at_the_middle_of_the_sagitta_has_the_least_largest_pressure_angle(shift):
    s = synthesize("slotted-lever", stroke=0.6, time_ratio=1.6, rod=0.3)
    d, r, lever, h, rod = (s.dimensions[n] for n in ("frame", "crank", "lever", "guide_height", "rod"))
    assert brute_force(d, r, lever, h + shift, rod)[2] > brute_force(d, r, lever, h, rod)[2]


@settings(max_examples=10, deadline=None)
@given(
    stroke=st.floats(0.02, 2.0),
    k=st.floats(1.05, 3.5),
    by=st.sampled_from(["best", "frame", "crank", "rod", "max_pressure_angle"]),
    where=st.floats(0.05, 0.95),
)
def test_random_feasible_requirements_are_met_as_the_analysis_measures_them(stroke, k, by, where):
    half = math.pi * (k - 1) / (k + 1) / 2
    lever = stroke / (2 * math.sin(half))
    top = 0.9 * lever / (1 + math.sin(half))  # the block a tenth of the lever from its end
    sag = lever * (1 - math.cos(half)) / 2
    # a pressure angle below 90 deg - theta/2 (at theta/2 + alpha = 90 deg the rod folds against the lever at its
    # limit positions: K = 3.5 leaves 40 deg), kept 1 deg clear of it
    steepest = min(math.radians(45), math.pi / 2 - half - math.radians(1))
    extra = {
        "best": {},
        "frame": {"frame": where * top},
        "crank": {"crank": where * top * math.sin(half)},
        "rod": {"rod": sag * (1 + 10 * where)},
        "max_pressure_angle": {"max_pressure_angle": math.radians(5) + where * (steepest - math.radians(5))},
    }[by]
    try:
        s = synthesize("slotted-lever", stroke=stroke, time_ratio=k, **extra, min_transmission_angle=FREE)
    except SynthesisError as err:  # a long lever near K = 1 on a short rod: refused as beyond making, and said so
        said = re.search(r"lever of (\S+) mm and a rod of (\S+) mm, more than 1000 times apart", str(err))
        assert said, str(err)
        assert float(said.group(1)) == pytest.approx(lever * 1e3, rel=1e-3)  # the lever H / (2 sin(theta / 2))
        assert float(said.group(1)) > 1000 * float(said.group(2))
        return
    measured_stroke, measured_k, alpha = analysed(s.spec)
    tol = s.tolerances  # the lengths written to 0.1 mm
    assert measured_stroke == pytest.approx(stroke, abs=tol["stroke"])
    assert measured_k == pytest.approx(k, abs=tol["time_ratio"])
    assert alpha <= s.predicted["largest_pressure_angle"] + tol["max_pressure_angle"]
    assert s.measured["largest_pressure_angle"] == pytest.approx(
        s.predicted["largest_pressure_angle"], abs=tol["max_pressure_angle"]
    )
    if "max_pressure_angle" in extra:
        assert s.measured["largest_pressure_angle"] == pytest.approx(
            extra["max_pressure_angle"], abs=tol["max_pressure_angle"]
        )
    for name in ("frame", "crank", "rod"):
        if name in extra:
            assert s.dimensions[name] == pytest.approx(extra[name], rel=1e-12)


def test_the_default_pick_is_the_greatest_frame_of_the_family():
    s = synthesize("slotted-lever", stroke=0.6, time_ratio=1.4)
    assert s.family is not None and s.dimensions["frame"] == pytest.approx(s.family.values.max(), rel=1e-12)
    # the block's pin a tenth of the lever from its end at its farthest: the block stays in the slot
    assert s.dimensions["frame"] + s.dimensions["crank"] == pytest.approx(0.9 * s.dimensions["lever"], rel=1e-12)
    spec = s.spec
    d, r, lever = spec.frame.points["O1"][1], spec.links["crank"].length, spec.links["lever"].length
    a = np.reshape(lw.kinematics(spec, steps=720).position("A"), (-1, 2))  # the block's pin; O2 at the origin
    reach = float(np.max(np.hypot(a[:, 0], a[:, 1])))
    assert reach == pytest.approx(d + r, rel=1e-9) and reach <= 0.9 * lever + 1e-4  # as written, to 0.1 mm
    assert synthesize("slotted-lever", stroke=0.6, time_ratio=1.4, frame=0.5).family is None


@pytest.mark.parametrize(
    ("extra", "words"),
    [
        ({"time_ratio": 1.0}, "a slotted lever gives any finite K > 1"),
        ({"time_ratio": 1.4, "frame": 2.0}, "the frame must be at most 828.713 mm"),
        ({"time_ratio": 1.4, "crank": 0.3}, "the crank at most 214.486 mm"),  # 0.9 x 238.3186 rounded down
        ({"time_ratio": 1.4, "frame": 0.5, "crank": 0.1}, "give one of the frame and the crank"),
        ({"time_ratio": 1.4, "rod": 0.1, "max_pressure_angle": math.radians(5)}, "needs a rod of at least"),
        ({"time_ratio": 1.4, "rod": 0.01}, "the rod must be longer than half the lever tip's sagitta"),
    ],
)
def test_requirements_that_cannot_be_met_together_say_so(extra, words):
    with pytest.raises(SynthesisError) as err:
        synthesize("slotted-lever", stroke=0.6, **extra)
    assert words in str(err.value)


def test_the_file_comments_each_derived_dimension_with_the_requirement_it_meets():
    s = synthesize("slotted-lever", stroke=0.6, time_ratio=1.4)
    lines = s.text.splitlines()
    assert any("length:" in line and "stroke H = 600 mm" in line for line in lines)
    assert any("length:" in line and "time ratio K = 1.4" in line for line in lines)
    assert any("through:" in line and "least largest pressure angle" in line for line in lines)
