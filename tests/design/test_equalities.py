"""Newton's method on equality constraints over named parameters (design.equalities.meet): the crank and rod
lengths of an offset slider-crank that give a stroke and time ratio, against the closed form of the circle
construction (linkwork.synthesis.slider_crank), several members at once."""

from __future__ import annotations

import math

import numpy as np
import pytest

from linkwork.api import mechanism_of
from linkwork.design.equalities import meet
from linkwork.synthesis import synthesize
from linkwork.synthesis.common import crank_angle_between_limits
from linkwork.synthesis.slider_crank import dimensions


def closed_form(stroke: float, k: float, offset: float) -> tuple[float, float]:
    """(r, l) of the offset slider-crank with stroke H, time ratio K and offset e: cos(theta + 2 beta) =
    cos(theta) - 2 e sin(theta) / H, then the law of sines on the triangle O B1 B2."""
    theta = crank_angle_between_limits(k)
    beta = (math.acos(math.cos(theta) - 2 * offset * math.sin(theta) / stroke) - theta) / 2
    r, ell, e = dimensions(stroke, theta, beta)
    assert e == pytest.approx(offset, rel=1e-12)
    return float(r), float(ell)


def test_meet_finds_the_closed_forms_crank_and_rod_for_each_member():
    start = synthesize("slider-crank", stroke=0.4, time_ratio=1.2, rod_ratio=0.3)
    offset = abs(start.spec.joints["guide"].through[0])  # the guide as written (to 0.1 mm), which the members keep
    mech = mechanism_of(start.spec, "mechanism")
    paths = ["links.crank.length", "links.rod.length"]
    strokes, ratios = np.array([0.45, 0.38]), np.array([1.3, 1.15])
    x0 = np.tile([start.dimensions["crank"], start.dimensions["rod"]], (2, 1))
    met = meet(
        mech,
        paths,
        lambda u, member: u,
        x0,
        {"stroke": strokes, "time_ratio": ratios},
        scales=np.array([0.1, 0.1]),
        steps=720,
    )
    assert met.solved.all()
    for i in range(2):
        r, ell = closed_form(strokes[i], ratios[i], offset)
        assert met.unknowns[i] == pytest.approx([r, ell], rel=1e-9)
        assert met.metrics["stroke"][i] == pytest.approx(strokes[i], rel=1e-11)


def test_a_target_out_of_reach_leaves_the_member_unsolved(monkeypatch):
    from linkwork.design import equalities

    monkeypatch.setattr(equalities, "ITERATIONS", 15)  # fewer Newton steps than its 40: quicker to give up
    start = synthesize("slider-crank", stroke=0.4, time_ratio=1.2, rod_ratio=0.3)
    mech = mechanism_of(start.spec, "mechanism")
    x0 = np.array([[start.dimensions["crank"], start.dimensions["rod"]]])
    met = meet(
        mech,
        ["links.crank.length", "links.rod.length"],
        lambda u, member: u,
        x0,
        {"stroke": 0.4, "time_ratio": 3.5},
        scales=np.array([0.1, 0.1]),
        steps=360,
    )
    assert not met.solved[0] and np.isnan(met.unknowns[0]).all()
