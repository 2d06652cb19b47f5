"""Crank-rocker synthesis: the circle construction holds the bundled four-bar, the written file meets the
swing and time ratio as the analysis measures them, the pick is the best of the family, and impossible
bounds say what can be met."""

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
from linkwork.synthesis.crank_rocker import family, largest_time_ratio, members

#: A bound on the least transmission angle low enough that the geometry alone decides (the design rule's 40 deg
#: refuses some of the random requests, which these tests make for the geometry).
FREE = 1e-6


def law_of_cosines(a: float, b: float, c: float, d: float) -> tuple[float, float]:
    """Swing psi and the crank's angle theta between the limit positions of a crank-rocker (frame d,
    crank a, coupler b, rocker c) from the two triangles O2 O4 B with O2 B = b +- a."""

    def angle(p: float, q: float, opposite: float) -> float:
        return math.acos((p * p + q * q - opposite * opposite) / (2 * p * q))

    psi = angle(d, c, b + a) - angle(d, c, b - a)
    theta = angle(d, b - a, c) - angle(d, b + a, c)
    return abs(psi), abs(theta)


def test_the_bundled_four_bar_is_a_member_of_the_family_of_its_swing_and_time_ratio():
    a, b, c, d = 0.10, 0.35, 0.25, 0.30
    psi, theta = law_of_cosines(a, b, c, d)
    (out,) = extremes(lw.kinematics("four-bar", steps=3600))
    assert out.stroke == pytest.approx(psi, rel=1e-9)  # the analysis agrees with the hand formulas
    assert out.time_ratio == pytest.approx((math.pi + theta) / (math.pi - theta), rel=1e-9)
    found = [members(psi, theta, np.array([(b - a) / c]), side) for side in (1.0, -1.0)]
    hit = [[float(m[k][0]) * c for k in ("crank", "coupler", "rocker", "frame")] for m in found if m["valid"][0]]
    assert [a, b, c, d] in [pytest.approx(h, rel=1e-12) for h in hit]
    for h in hit:  # the other side of the chord, where it is a crank-rocker, has the same swing and theta
        assert law_of_cosines(*h) == pytest.approx((psi, theta), rel=1e-12)


def test_the_least_transmission_angle_closed_form_is_the_analysis_least():
    a, b, c, d = 0.10, 0.35, 0.25, 0.30
    from linkwork.synthesis.crank_rocker import least_transmission_angle

    mu = least_transmission_angle(a, b, c, d)
    # crank along the frame (towards O4 and away): the closed form's angles
    (at,) = transmission(lw.kinematics("four-bar", np.array([0.0, math.pi]))).values()
    assert float(np.min(at)) == pytest.approx(float(mu), rel=1e-12)
    (over,) = transmission(lw.kinematics("four-bar", steps=3600)).values()
    assert float(np.min(over)) >= float(mu) - 1e-12


@settings(max_examples=10, deadline=None)
@given(
    swing=st.floats(math.radians(20), math.radians(120)),
    k=st.floats(1.01, 2.0),
    scale=st.floats(0.05, 2.0),
    by=st.sampled_from(["rocker", "frame"]),
)
def test_random_feasible_requirements_are_met_as_the_analysis_measures_them(swing, k, scale, by):
    from linkwork.synthesis.crank_rocker import best

    try:
        s = synthesize("crank-rocker", swing=swing, time_ratio=k, **{by: scale}, min_transmission_angle=FREE)
    except SynthesisError as err:  # a file to 0.1 mm cannot hold K this near a dead point: refused, and said so
        assert best(swing, math.pi * (k - 1) / (k + 1))[2] < math.radians(10) and "of a dead point" in str(err)
        return
    kin = lw.kinematics(s.spec, steps=3600)
    (out,) = extremes(kin)
    tol = s.tolerances  # the lengths written to 0.1 mm (the closed form's exact lengths are checked below)
    assert out.stroke == pytest.approx(swing, abs=tol["swing"])
    assert out.time_ratio == pytest.approx(k, abs=tol["time_ratio"])
    assert s.dimensions[by] == pytest.approx(scale, rel=1e-12)
    (mu,) = transmission(kin).values()
    least = s.predicted["least_transmission_angle"]
    assert float(np.min(mu)) >= least - tol["min_transmission_angle"]
    assert s.measured["least_transmission_angle"] == pytest.approx(least, abs=tol["min_transmission_angle"])
    psi, theta = law_of_cosines(*(s.dimensions[n] for n in ("crank", "coupler", "rocker", "frame")))
    assert (psi, (math.pi + theta) / (math.pi - theta)) == pytest.approx((swing, k), rel=1e-9)


def test_the_pick_has_the_greatest_least_transmission_angle_of_the_family():
    s = synthesize("crank-rocker", swing=math.radians(60), time_ratio=1.5, rocker=1.0, min_transmission_angle=FREE)
    curve = family(math.radians(60), 1.5, count=4001).columns["least_transmission_angle"]
    assert np.nanmax(curve) <= s.predicted["least_transmission_angle"] + 1e-12
    assert np.nanmax(curve) > s.predicted["least_transmission_angle"] - 1e-5


def test_k_1_takes_the_rules_bound_or_the_one_given_and_meets_it_with_the_nearest_pivot():
    rule = synthesize("crank-rocker", swing=math.radians(45), time_ratio=1.0, rocker=0.25)
    (mu,) = transmission(lw.kinematics(rule.spec, steps=3600)).values()
    # within what the lengths written to 0.1 mm allow (the tolerance the file states)
    assert float(np.min(mu)) == pytest.approx(math.radians(40), abs=rule.tolerances["min_transmission_angle"])
    s = synthesize(
        "crank-rocker", swing=math.radians(45), time_ratio=1.0, frame=0.4, min_transmission_angle=math.radians(50)
    )
    assert s.measured["least_transmission_angle"] == pytest.approx(
        math.radians(50), abs=s.tolerances["min_transmission_angle"]
    )
    assert s.measured["time_ratio"] == pytest.approx(1.0, abs=s.tolerances["time_ratio"])


@pytest.mark.parametrize("swing", [40, 50, 60])
@pytest.mark.parametrize("bound", [20, 30, 35])
def test_k_1_with_a_bound_it_can_meet_is_met_and_not_refused(swing, bound):
    # the root of the bound is taken on the side that meets it, not a rounding short of it
    s = synthesize(
        "crank-rocker",
        swing=math.radians(swing),
        time_ratio=1.0,
        rocker=0.3,
        min_transmission_angle=math.radians(bound),
    )
    assert s.predicted["least_transmission_angle"] >= math.radians(bound)
    assert s.measured["least_transmission_angle"] == pytest.approx(
        math.radians(bound), abs=s.tolerances["min_transmission_angle"]
    )


def test_the_members_for_k_1_have_their_pivot_on_the_chords_line_to_the_last_digits():
    psi = math.radians(40)
    t = np.linspace(0.05, 50, 400)
    m = members(psi, 0.0, t, 1.0)
    for a, b, d in zip(m["crank"], m["coupler"], m["frame"], strict=True):
        assert law_of_cosines(a, b, 1.0, d) == pytest.approx((psi, 0.0), rel=1e-12, abs=1e-12)


def test_an_impossible_bound_names_the_best_angle_and_the_largest_k_that_meets_it():
    with pytest.raises(SynthesisError) as err:
        synthesize(
            "crank-rocker", swing=math.radians(60), time_ratio=1.5, frame=0.4, min_transmission_angle=math.radians(40)
        )
    text = str(err.value)
    curve = family(math.radians(60), 1.5, count=4001).columns["least_transmission_angle"]
    best = float(text.split("least transmission angle of ")[1].split(" deg")[0])
    assert math.radians(best) <= np.nanmax(curve) + 1e-9 < math.radians(best + 0.01)  # rounded down, 4 digits
    k = float(text.split("K <= ")[1].split(" ")[0])
    assert k <= largest_time_ratio(math.radians(60), math.radians(40)) < k * (1 + 1e-3)
    s = synthesize(
        "crank-rocker",
        swing=math.radians(60),
        time_ratio=k,
        frame=0.4,
        min_transmission_angle=math.radians(40),
    )
    assert s.measured["least_transmission_angle"] >= math.radians(40) * (1 - 1e-9)


def test_a_170_deg_crank_rocker_is_refused_by_the_rule_with_the_largest_swing_that_meets_it(tmp_path):
    """The report's 170 deg rocker (K 1.2) comes within 1.86 deg of a dead point: exit 2, no file, the least angle
    it would have (as the analysis measures the file written without the rule) and a swing that meets the rule."""
    from commandline import linkwork

    out = tmp_path / "r.yaml"
    run = linkwork(
        "synthesize", "crank-rocker", "--swing", "170deg", "--time-ratio", "1.2", "--rocker", "100mm", "--out", str(out)
    )
    assert run.returncode == 2 and not out.exists() and len(run.stderr.splitlines()) == 1
    free = synthesize("crank-rocker", swing=math.radians(170), time_ratio=1.2, rocker=0.1, min_transmission_angle=FREE)
    (mu,) = transmission(lw.kinematics(free.spec, steps=36000)).values()
    said = float(run.stderr.split("least transmission angle of ")[1].split(" deg")[0])
    tol = math.degrees(free.tolerances["min_transmission_angle"])  # the free file's lengths written to 0.1 mm
    assert said - tol <= math.degrees(float(np.min(mu))) < said + 0.01 + tol and said == pytest.approx(1.86, abs=0.01)
    swing = float(run.stderr.split("a swing of at most ")[1].split(" deg")[0])
    s = synthesize("crank-rocker", swing=math.radians(swing), time_ratio=1.2, rocker=0.1)
    (mu,) = transmission(lw.kinematics(s.spec, steps=3600)).values()
    tol = s.tolerances["min_transmission_angle"]  # the lengths written to 0.1 mm
    assert math.radians(40) - tol <= float(np.min(mu)) < math.radians(40.1) + tol  # the nearest: a little wider fails


def test_a_time_ratio_no_crank_rocker_of_the_swing_reaches_names_the_largest_that_one_does():
    with pytest.raises(SynthesisError) as err:
        synthesize("crank-rocker", swing=math.radians(40), time_ratio=5.0, rocker=0.3)
    text = str(err.value)
    assert "no crank-rocker has these limit positions; the swing 40 deg gives K <= 4.14" in text
    from linkwork.synthesis.crank_rocker import best

    theta = math.pi * (4.1 - 1) / (4.1 + 1)
    t, side, _ = best(math.radians(40), theta)
    a, b, c, d = (
        float(members(math.radians(40), theta, np.array([t]), side)[k][0])
        for k in ("crank", "coupler", "rocker", "frame")
    )
    assert law_of_cosines(a, b, c, d) == pytest.approx((math.radians(40), theta), rel=1e-9)


def test_a_measure_off_by_more_than_its_tolerance_is_refused_and_the_message_says_how_near_a_dead_point():
    from linkwork.synthesis.common import confirm

    tol = {"time_ratio": 2.9e-9}
    confirm({"time_ratio": 2.9 * (1 + 9e-10)}, {"time_ratio": 2.9}, math.radians(0.25), tol)
    with pytest.raises(SynthesisError, match="comes within 0.25 deg of a dead point"):
        confirm({"time_ratio": 2.9 * (1 + 2e-9)}, {"time_ratio": 2.9}, math.radians(0.25), tol)
