"""Toggle-press synthesis: the written file's stroke, as the kinematic analysis measures it, is the requested
one; the crank torque of the nominal force at the nominal point, by the project's forces, is the virtual-work
closed form and agrees with a finite difference of the ram's position; an insufficient torque limit says
which force it allows."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import linkwork as lw
from linkwork.errors import SynthesisError
from linkwork.motion.analysis import extremes
from linkwork.synthesis import synthesize
from linkwork.synthesis.toggle_press import geometry, nominal


def ram_stroke(spec) -> float:
    (ram,) = [e for e in extremes(lw.kinematics(spec, steps=3600)) if e.kind == "slider"]
    return ram.stroke


def torque_by_difference(spec, stroke: float, before: float, force: float, swing: float, k: float) -> float:
    """F times the ram's descent per radian of the crank (turning clockwise, the drive angle falling) at the
    nominal point, by a central difference of the ram's height that lw.kinematics gives (no velocity
    analysis): the clockwise torque, by virtual work."""
    angle, _ = nominal(geometry(stroke, swing, k), before)
    h = 1e-5
    y = lw.kinematics(spec, np.array([angle - h, angle + h])).position("R")[:, 1]
    return force * float(y[1] - y[0]) / (2 * h)


def test_the_toggle_links_are_as_long_as_the_stroke_for_a_swing_of_60_deg():
    """H = 2 a (1 - cos 60 deg) = a."""
    s = synthesize("toggle-press", stroke=0.2, force=1e5, before=0.01, torque=5e3)
    assert s.dimensions["toggle"] == pytest.approx(0.2, rel=1e-12)
    assert ram_stroke(s.spec) == pytest.approx(0.2, rel=1e-9)
    assert s.measured["torque_at_nominal"] == pytest.approx(s.predicted["torque_at_nominal"], rel=1e-9)
    fd = torque_by_difference(s.spec, 0.2, 0.01, 1e5, math.radians(60), 1.2)
    assert s.measured["torque_at_nominal"] == pytest.approx(fd, rel=1e-6)


@settings(max_examples=8, deadline=None)
@given(
    stroke=st.floats(0.02, 1.0),
    where=st.floats(0.02, 0.9),
    force=st.floats(1e3, 1e6),
    swing=st.floats(math.radians(20), math.radians(80)),
    k=st.floats(1.05, 1.6),
)
def test_random_feasible_requirements_are_met_as_the_analysis_measures_them(stroke, where, force, swing, k):
    before = where * stroke
    _, rho = nominal(geometry(stroke, swing, k), before)
    s = synthesize(
        "toggle-press", stroke=stroke, force=force, before=before, torque=force * rho * 1.5, swing=swing, time_ratio=k
    )
    assert ram_stroke(s.spec) == pytest.approx(stroke, rel=1e-9)
    assert s.measured["torque_at_nominal"] == pytest.approx(force * rho, rel=1e-9)
    fd = torque_by_difference(s.spec, stroke, before, force, swing, k)
    assert s.measured["torque_at_nominal"] == pytest.approx(fd, rel=1e-5)


def test_the_torque_grows_slower_than_the_distance_before_the_bottom():
    """Near the bottom s ~ (phi - phi0)^4, so the torque ratio goes as s^(3/4): a tenth of the distance
    needs about 10^(-3/4) of the torque."""
    geo = geometry(0.2, math.radians(60), 1.2)
    ratio = nominal(geo, 1e-5)[1] / nominal(geo, 1e-4)[1]
    assert ratio == pytest.approx(10 ** (-0.75), rel=0.02)


@pytest.mark.parametrize(
    ("extra", "words"),
    [
        ({"before": 0.3}, "it must lie within the stroke"),
        ({"time_ratio": 1.0}, "the time ratio K must be over 1"),
        ({"swing": math.radians(100)}, "expected between 0 and 90 deg"),
    ],
)
def test_requirements_that_cannot_be_met_say_so(extra, words):
    requirements = {"stroke": 0.2, "force": 1e5, "before": 0.01, "torque": 5e3, **extra}
    with pytest.raises(SynthesisError) as err:
        synthesize("toggle-press", **requirements)
    assert words in str(err.value)


def test_an_insufficient_torque_limit_names_the_force_it_allows_and_that_force_can_be_met():
    with pytest.raises(SynthesisError) as err:
        synthesize("toggle-press", stroke=0.2, force=1e5, before=0.01, torque=3e3)
    text = str(err.value)
    assert "needs a crank torque of" in text and "the limit 3000 N m gives at most" in text
    allowed = float(text.split("gives at most ")[1].split(" kN")[0]) * 1e3
    s = synthesize("toggle-press", stroke=0.2, force=allowed * (1 - 1e-5), before=0.01, torque=3e3)
    assert s.measured["torque_at_nominal"] == pytest.approx(3e3, rel=2e-5)


def test_the_file_carries_the_nominal_force_as_a_process_load():
    s = synthesize("toggle-press", stroke=0.2, force=1e5, before=0.01, torque=5e3)
    (load,) = s.spec.loads.values()
    assert load.type == "process"
    assert any("stroke H = 200 mm" in line for line in s.text.splitlines())
