"""The one measurement of a mechanism for its kind's requirements (:func:`linkwork.synthesis.measuring.measure`,
read by the synthesis's verification, its tolerances and the report) against the closed forms of an offset
slider-crank and a crank-rocker written here by hand, on a coarse turn whose samples miss the extremes."""

import math

import numpy as np
import pytest

import linkwork as lw
from linkwork.motion.analysis import transmission
from linkwork.synthesis.achieved import requirement_rows
from linkwork.synthesis.measuring import measure

#: Crank r, rod l, offset e of the slider-crank (m): the guide along x at y = e, the crank pivot at the origin.
R, L, E = 0.1, 0.35, 0.04
#: Crank a, coupler b, rocker c, frame d of the crank-rocker (m): b^2 + c^2 = a^2 + d^2 nearly, so its two least
#: transmission angles (the crank along the frame, towards O4 and away) lie 1.04e-5 rad apart.
A, B, C, D = 0.1, 0.3, 0.206154, 0.35


def slider_crank(start_deg: float) -> str:
    return f"""
name: offset slider-crank
units: {{length: m, mass: kg, angle: deg}}
frame: {{points: {{O: [0.0, 0.0]}}}}
links:
  crank: {{ends: [O, A], length: {R}, mass: 1.0}}
  rod: {{ends: [A, B], length: {L}, mass: 1.0}}
  ram: {{points: {{B: [0.0, 0.0]}}, mass: 1.0, inertia: 0}}
joints:
  O: {{type: revolute, links: [frame, crank]}}
  A: {{type: revolute, links: [crank, rod]}}
  B: {{type: revolute, links: [rod, ram]}}
  guide: {{type: prismatic, links: [frame, ram], point: B, through: [0.0, {E}], axis: 0.0}}
drives: [{{joint: O, speed: 60 rpm, direction: ccw, angle: {start_deg}}}]
hints: {{B: [0.4, {E}]}}
requirements: {{kind: slider-crank, stroke: 200 mm, time_ratio: 1.1}}
"""


def crank_rocker(start_deg: float) -> str:
    return f"""
name: crank-rocker
units: {{length: m, mass: kg, angle: deg}}
frame: {{points: {{O2: [0.0, 0.0], O4: [{D}, 0.0]}}}}
links:
  crank: {{ends: [O2, A], length: {A}, mass: 1.0}}
  coupler: {{ends: [A, B], length: {B}, mass: 1.0}}
  rocker: {{ends: [O4, B], length: {C}, mass: 1.0}}
joints:
  O2: {{type: revolute, links: [frame, crank]}}
  A: {{type: revolute, links: [crank, coupler]}}
  B: {{type: revolute, links: [coupler, rocker]}}
  O4: {{type: revolute, links: [frame, rocker]}}
drives: [{{joint: O2, speed: 60 rpm, direction: ccw, angle: {start_deg}}}]
hints: {{B: [0.3, 0.2]}}
"""


def test_the_slider_cranks_measures_are_its_closed_forms_between_the_samples():
    """Offset slider-crank: the ram's extremes at x = sqrt((l +- r)^2 - e^2) (crank and rod in line), so
    H = sqrt((l + r)^2 - e^2) - sqrt((l - r)^2 - e^2); the crank's angle between them
    theta = asin(e / (l - r)) - asin(e / (l + r)), K = (pi + theta) / (pi - theta); the rod's pressure angle
    sin(alpha) = |r sin(phi) - e| / l, largest at phi = -90 deg: alpha = asin((r + e) / l).  On 360 steps from
    13.7 deg no sample falls on phi = -90 deg: the samples alone miss alpha by 4e-6 rad."""
    spec = lw.loads(slider_crank(13.7))
    kin = lw.kinematics(spec, steps=360)
    (got,) = measure(kin, spec)
    stroke = math.sqrt((L + R) ** 2 - E**2) - math.sqrt((L - R) ** 2 - E**2)
    theta = math.asin(E / (L - R)) - math.asin(E / (L + R))
    alpha = math.asin((R + E) / L)
    assert got["stroke"] == pytest.approx(stroke, rel=1e-10)
    assert got["time_ratio"] == pytest.approx((math.pi + theta) / (math.pi - theta), rel=1e-10)
    assert got["max_pressure_angle"] == pytest.approx(alpha, abs=1e-10)
    assert got["min_transmission_angle"] == pytest.approx(math.pi / 2 - alpha, abs=1e-10)
    sampled = math.pi / 2 - min(float(np.nanmin(mu)) for mu in transmission(kin).values())
    assert alpha - sampled > 1e-6  # what the samples alone give: the refinement is what meets the closed form
    # the report's requirements section reads the same measurement
    _, rows = requirement_rows(kin, spec)
    assert {r.name: r.achieved for r in rows} == {"stroke": got["stroke"], "time_ratio": got["time_ratio"]}


def test_the_crank_rockers_measures_are_its_closed_forms_and_the_least_of_its_two_near_equal_leasts():
    """Crank-rocker: the rocker's limit positions with crank and coupler in line, |O2 B| = b +- a, so the swing is
    the difference of the angles at O4, cos(gamma) = (c^2 + d^2 - (b +- a)^2) / (2 c d), and theta that of the
    angles at O2, cos(beta) = ((b +- a)^2 + d^2 - c^2) / (2 (b +- a) d); the transmission angle
    cos(mu) = (b^2 + c^2 - |A O4|^2) / (2 b c), |A O4| = d -+ a at its extremes (the crank along the frame), the
    obtuse one folded to 180 deg - mu.  The two leasts lie 1.04e-5 rad apart, the one at phi = 180 deg the lesser;
    121 steps from phi = 0 put a sample on the other and none within 1.5 deg of it, so the least sample is the
    wrong one's (by 2e-4 rad): each sampled least that may hold the turn's is refined, and the lesser kept."""
    spec = lw.loads(crank_rocker(0.0))
    kin = lw.kinematics(spec, steps=121)
    (got,) = measure(kin, spec)
    gamma = [math.acos((C**2 + D**2 - (B + s * A) ** 2) / (2 * C * D)) for s in (1, -1)]
    beta = [math.acos(((B + s * A) ** 2 + D**2 - C**2) / (2 * (B + s * A) * D)) for s in (1, -1)]
    theta = abs(beta[0] - beta[1])
    mu = [math.acos((B**2 + C**2 - (D + s * A) ** 2) / (2 * B * C)) for s in (-1, 1)]
    least = min(mu[0], math.pi - mu[1])
    assert 0 < mu[0] - (math.pi - mu[1]) < 2e-5  # the two leasts nearly equal, as the test means them
    samples = np.ravel(next(iter(transmission(kin).values())))
    assert abs(math.degrees(float(np.ravel(kin.angles)[np.argmin(samples)]))) < 1e-9  # the grid picks phi = 0
    assert got["swing"] == pytest.approx(abs(gamma[0] - gamma[1]), rel=1e-9)
    assert got["time_ratio"] == pytest.approx((math.pi + theta) / (math.pi - theta), rel=1e-9)
    assert got["min_transmission_angle"] == pytest.approx(least, abs=1e-10)


def test_each_variant_is_measured_as_the_mechanism_alone():
    """A batch of variants (as the tolerances solve them) measures each variant as its own file does."""
    spec = lw.loads(slider_crank(13.7))
    rods = np.array([L, L + 0.01, L - 0.01])
    runs = measure(lw.kinematics(spec, steps=360, variants={"links.rod.length": rods}), spec)
    for rod, run in zip(rods, runs, strict=True):
        alone = lw.loads(slider_crank(13.7).replace(f"length: {L}", f"length: {float(rod)!r}"))
        (own,) = measure(lw.kinematics(alone, steps=360), alone)
        assert run == pytest.approx(own, rel=1e-9, abs=1e-12)
