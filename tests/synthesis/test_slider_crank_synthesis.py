"""Slider-crank synthesis: the written file, as the kinematic analysis measures it, meets the requirements;
the inverse construction recovers mechanisms given by the forward closed forms; the pick is the least over
the family; impossible requirements say what can be met."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import linkwork as lw
from linkwork.errors import SynthesisError
from linkwork.motion.analysis import extremes, transmission
from linkwork.synthesis import synthesize
from linkwork.synthesis.slider_crank import largest_time_ratio, least_pressure_angle

#: A bound on the least transmission angle low enough that the geometry alone decides (the design rule's 40 deg
#: refuses some of the random requests, which these tests make for the geometry).
FREE = 1e-6


def forward(r: float, ell: float, e: float) -> tuple[float, float, float]:
    """Stroke, K and the largest pressure angle of an offset slider-crank by the textbook forward formulas:
    the limit positions at |OB| = l +- r, theta = asin(e / (l - r)) - asin(e / (l + r))."""
    stroke = math.sqrt((ell + r) ** 2 - e * e) - math.sqrt((ell - r) ** 2 - e * e)
    theta = math.asin(e / (ell - r)) - math.asin(e / (ell + r))
    return stroke, (math.pi + theta) / (math.pi - theta), math.asin((r + e) / ell)


def analysed(spec) -> tuple[float, float, float]:
    """Stroke, K and the largest pressure angle of a written file, measured by the analysis (a fine turn)."""
    kin = lw.kinematics(spec, steps=3600)
    (out,) = extremes(kin)
    (mu,) = transmission(kin).values()
    return out.stroke, out.time_ratio, math.pi / 2 - float(np.min(mu))


def test_k_1_gives_the_central_slider_crank_with_half_the_stroke_as_crank():
    s = synthesize("slider-crank", stroke=0.3, time_ratio=1.0, rod_ratio=0.25)
    assert s.dimensions == pytest.approx({"crank": 0.15, "rod": 0.6, "offset": 0.0}, rel=1e-12, abs=1e-15)
    stroke, k, alpha = analysed(s.spec)
    assert stroke == pytest.approx(0.3, rel=1e-9) and k == pytest.approx(1.0, rel=1e-9)
    assert alpha == pytest.approx(math.asin(0.25), rel=1e-6)  # sampled: the exact value is the crank square


def test_the_bound_alone_at_k_1_gives_the_shortest_rod_that_meets_it():
    s = synthesize("slider-crank", stroke=0.2, time_ratio=1.0, max_pressure_angle=math.radians(15))
    assert s.dimensions["rod"] == pytest.approx(0.1 / math.sin(math.radians(15)), rel=1e-12)


@pytest.mark.parametrize("by", ["offset", "rod_ratio"])
def test_an_offset_slider_crank_is_recovered_from_its_stroke_and_time_ratio(by):
    r, ell, e = 0.1, 0.4, 0.1
    stroke, k, alpha = forward(r, ell, e)
    s = synthesize("slider-crank", stroke=stroke, time_ratio=k, **{by: e if by == "offset" else r / ell})
    assert [s.dimensions[n] for n in ("crank", "rod", "offset")] == pytest.approx([r, ell, e], rel=1e-9)
    assert s.predicted["largest_pressure_angle"] == pytest.approx(math.radians(30), rel=1e-12)
    assert s.measured["largest_pressure_angle"] == pytest.approx(math.radians(30), rel=1e-9)


def test_the_default_pick_has_the_least_largest_pressure_angle_of_all_slider_cranks_of_that_k():
    """Random offset slider-cranks (forward formulas, no synthesis): none with K >= 1.3 has a smaller
    largest pressure angle than the pick, and the best of them comes close."""
    rng = np.random.default_rng(1)
    ell, e = rng.uniform(1.0, 6.0, 400_000), rng.uniform(0.0, 6.0, 400_000)
    ok = ell > 1.0 + e
    ell, e = ell[ok], e[ok]
    theta = np.arcsin(e / (ell - 1)) - np.arcsin(e / (ell + 1))
    k = (np.pi + theta) / (np.pi - theta)
    alpha = np.arcsin((1 + e) / ell)
    least = least_pressure_angle(1.3)
    found = alpha[k >= 1.3].min()
    assert least <= found + 1e-12 and found - least < math.radians(0.3)
    s = synthesize("slider-crank", stroke=0.4, time_ratio=1.3, min_transmission_angle=FREE)
    assert s.predicted["largest_pressure_angle"] == pytest.approx(least, rel=1e-12)


@settings(max_examples=12, deadline=None)
@given(
    stroke=st.floats(0.02, 2.0),
    k=st.floats(1.0, 2.5),
    by=st.sampled_from(["best", "offset", "rod_ratio"]),
    where=st.floats(0.05, 0.95),
)
def test_random_feasible_requirements_are_met_as_the_analysis_measures_them(stroke, k, by, where):
    theta = math.pi * (k - 1) / (k + 1)
    extra: dict[str, float] = {}
    if by == "offset" and theta > 0:
        extra["offset"] = where * stroke / math.tan(theta)
    elif by == "rod_ratio" or theta == 0:
        low = math.tan(theta / 2) ** 2
        extra["rod_ratio"] = low + where * (1 - low)
    from linkwork.synthesis.slider_crank import largest_pressure_angle, solve

    r, ell, e, _ = solve(stroke, k, extra.get("rod_ratio"), extra.get("offset"), None, FREE)
    try:
        s = synthesize("slider-crank", stroke=stroke, time_ratio=k, **extra, min_transmission_angle=FREE)
    except SynthesisError as err:  # a file to 0.1 mm cannot hold K this near a dead point: refused, and said so
        assert math.pi / 2 - float(largest_pressure_angle(r, ell, e)) < math.radians(10)
        assert "of a dead point" in str(err)
        return
    measured_stroke, measured_k, alpha = analysed(s.spec)
    tol = s.tolerances  # the lengths written to 0.1 mm (the closed form's exact lengths are checked below)
    assert measured_stroke == pytest.approx(stroke, abs=tol["stroke"])
    assert measured_k == pytest.approx(k, abs=tol["time_ratio"])
    assert alpha <= s.predicted["largest_pressure_angle"] + tol["max_pressure_angle"]
    assert s.measured["largest_pressure_angle"] == pytest.approx(
        s.predicted["largest_pressure_angle"], abs=tol["max_pressure_angle"]
    )
    r, ell, e = (s.dimensions[n] for n in ("crank", "rod", "offset"))
    assert forward(r, ell, e)[:2] == pytest.approx((stroke, k), rel=1e-9)
    if "rod_ratio" in extra:
        assert r / ell == pytest.approx(extra["rod_ratio"], rel=1e-9)
    if "offset" in extra:
        assert e == pytest.approx(extra["offset"], rel=1e-9)


def test_an_impossible_bound_names_the_least_angle_for_k_and_the_largest_k_for_the_bound():
    with pytest.raises(SynthesisError) as err:
        synthesize("slider-crank", stroke=0.4, time_ratio=1.3, max_pressure_angle=math.radians(30))
    text = str(err.value)
    assert "K = 1.3 needs a largest pressure angle of at least 51.01 deg" in text  # 51.0015 rounded up
    assert "at most 30 deg gives K <= 1.092" in text
    # the nearest feasible value is feasible: just under it the bound is met
    k = largest_time_ratio(math.radians(30))
    s = synthesize("slider-crank", stroke=0.4, time_ratio=k * (1 - 1e-9), max_pressure_angle=math.radians(30))
    assert s.measured["largest_pressure_angle"] <= math.radians(30) + s.tolerances["max_pressure_angle"]
    # the r = 1, l = 4, e = 1 mechanism has exactly 30 deg: its K cannot be over the largest
    assert forward(1.0, 4.0, 1.0)[1] <= k


@pytest.mark.parametrize(
    ("extra", "words"),
    [
        ({"time_ratio": 3.2}, "1 <= K < 3"),
        ({"time_ratio": 1.3, "rod_ratio": 0.01}, "the rod ratio must lie in (0.04318"),
        ({"time_ratio": 1.3, "offset": 5.0}, "and under H cot(theta)"),
        ({"time_ratio": 1.0, "offset": 0.1}, "K = 1 needs a zero offset"),
        ({"time_ratio": 1.3, "offset": 0.0}, "the offset must be over 0 (a central slider-crank has K = 1)"),
        ({"time_ratio": 1.0}, "give the rod ratio or the largest pressure angle"),
        ({"time_ratio": 1.3, "rod_ratio": 0.3, "offset": 0.1}, "give one of the rod ratio and the offset"),
    ],
)
def test_requirements_that_cannot_be_met_together_say_so(extra, words):
    with pytest.raises(SynthesisError, match=None) as err:
        synthesize("slider-crank", stroke=0.4, **extra)
    assert words in str(err.value)


def test_the_file_comments_each_derived_dimension_with_the_requirement_it_meets():
    s = synthesize("slider-crank", stroke=0.4, time_ratio=1.2, offset=0.05)
    lines = s.text.splitlines()
    crank = next(line for line in lines if line.strip().startswith("length:"))
    assert "stroke H = 400 mm" in crank
    assert any("through:" in line and "time ratio K = 1.2" in line for line in lines)
    assert lw.loads(s.text).links["rod"].length is not None


def test_the_torque_criterion_picks_the_member_with_the_least_peak_torque_within_the_pressure_bound():
    """Members of the family built one by one by their offsets (up to the pick's), each sampled finely by
    lw.forces: none has a smaller peak driving torque than the pick, which meets the bound (here at it: the
    torque falls towards the dead point)."""
    import linkwork as lw

    req = {"stroke": 0.4, "time_ratio": 1.3, "force": 20e3, "min_transmission_angle": math.radians(30)}
    pick = synthesize("slider-crank", **req, max_pressure_angle=math.radians(60), criterion="torque")
    tol = pick.tolerances  # the lengths written to 0.1 mm
    assert pick.measured["largest_pressure_angle"] <= math.radians(60) + tol["max_pressure_angle"]
    assert pick.measured["stroke"] == pytest.approx(0.4, abs=tol["stroke"])
    assert "working:" in pick.text and "20000 N" in pick.text

    def sampled(spec) -> float:
        return float(np.max(np.abs(lw.forces(spec, steps=3600).driving_torque)))

    best = sampled(pick.spec)
    for offset in np.linspace(0.0, pick.dimensions["offset"], 6)[1:-1]:
        member = synthesize("slider-crank", **req, offset=float(offset))
        assert sampled(member.spec) > best
    assert pick.measured["largest_pressure_angle"] == pytest.approx(math.radians(60), abs=tol["max_pressure_angle"])


def test_rounded_numbers_of_a_refusal_do_not_contradict_it():
    """At the edge (K 1.3 needs 51.0015 deg): the least angle is rounded up and the largest K down, so the message
    no longer reads "needs at least 51 deg; at most 51 deg gives K <= 1.3", and each number it gives is feasible."""
    with pytest.raises(SynthesisError) as err:
        synthesize("slider-crank", stroke=0.4, time_ratio=1.3, max_pressure_angle=math.radians(51))
    text = str(err.value)
    least = float(text.split("at least ")[1].split(" deg")[0])
    k = float(text.split("K <= ")[1])
    assert least > 51 and k < 1.3
    assert least_pressure_angle(1.3) <= math.radians(least) and k <= largest_time_ratio(math.radians(51))
    free = {"stroke": 0.4, "min_transmission_angle": FREE}
    synthesize("slider-crank", **free, time_ratio=1.3, max_pressure_angle=math.radians(least))
    synthesize("slider-crank", **free, time_ratio=k, max_pressure_angle=math.radians(51))


@pytest.mark.parametrize("ratio", ["1", "1.5", "1e300", "0", "-1"])
def test_a_central_rod_as_long_as_the_crank_or_shorter_is_refused(tmp_path, ratio):
    """K = 1, r/l >= 1 (or not positive): the rod cannot follow the crank round (r/l = 1 divided by zero, 1.5
    was measured within "nan deg of a dead point"): exit 2, one line, no file, the rod ratio the rule allows,
    cos 40 deg = 0.766 rounded down."""
    from commandline import linkwork

    out = tmp_path / "s.yaml"
    run = linkwork(
        "synthesize", "slider-crank", "--stroke", "400mm", "--time-ratio", "1", "--rod-ratio", ratio, "--out", str(out)
    )
    assert run.returncode == 2 and not out.exists() and len(run.stderr.splitlines()) == 1, run.stderr
    assert "r/l <= 0.766" in run.stderr and "nan" not in run.stderr
