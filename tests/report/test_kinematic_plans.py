"""The velocity and acceleration plans worked out beside the plans: each equation, segment, ω, ε, aⁿ, aτ."""

from __future__ import annotations

import html
import re

import numpy as np
import pytest

import linkwork as lw
from linkwork.lang import t
from linkwork.motion.analysis import position_angles
from linkwork.report.kinematic_plans import worked_plans


class _Run:
    def __init__(self, lang: str) -> None:
        self.lang = lang

    def t(self, key: str, **values: object) -> str:
        return t(key, self.lang, **values)


def _text(lang: str) -> tuple[str, lw.Kinematics]:
    mech = lw.compile(lw.example("double-cut-shears"))
    kin = lw.kinematics(mech, position_angles(mech))
    page = "".join(worked_plans(_Run(lang), kin, 9, "9"))
    return html.unescape(re.sub(r"<[^>]+>", "\n", page)), kin


def _number(pattern: str, text: str) -> float:
    found = re.search(pattern, text)
    assert found, pattern
    return float(found.group(1))


def test_the_plans_are_worked_out_to_the_digits_of_the_analysis():
    """Position 9 of the double-cut shears: the rod's ω2 and ε2, the segments ab and pb at μv, the normal component
    ω2² l_AB, each as printed equal to the kinematic analysis (velocities of the points, the links' ω and ε, the
    link lengths from the points' positions) rounded to the 4 digits printed."""
    text, kin = _text("en")
    assert "v_B = v_A + v_BA = v_BO3" in text and "a_B = a_A + aⁿ_BA + aτ_BA = aⁿ_BO3 + aτ_BO3" in text
    assert "v_E = v_D + v_ED = v_EE'" in text and "a_E = a_D + aⁿ_ED + aτ_ED = aᵏ_EE' + aʳ_EE'" in text
    four = lambda x: float(f"{x:.4g}")  # noqa: E731
    mu_v = _number(r"μv = ([\d.]+) \(m/s\)/mm", text)
    mu_a = _number(r"μa = ([\d.]+) \(m/s²\)/mm", text)
    v = {p: np.asarray(kin.velocity(p))[9] for p in ("A", "B")}
    l_ab = float(np.hypot(*(np.asarray(kin.position("B"))[9] - np.asarray(kin.position("A"))[9])))
    assert _number(r"ab = ([\d.]+) mm", text) == four(np.hypot(*(v["B"] - v["A"])) / mu_v)
    assert _number(r"pb = ([\d.]+) mm", text) == four(np.hypot(*v["B"]) / mu_v)
    omega2 = float(np.asarray(kin.omega("rod"))[9])
    assert _number(r"ω2 = v_BA / lBA = [\d.]+ / [\d.]+ m = ([\d.]+) rad/s", text) == four(abs(omega2))
    assert _number(r"aⁿ_BA = ω2²·lBA = [\d.]+²·[\d.]+ m = ([\d.e-]+) m/s²", text) == four(omega2**2 * l_ab)
    epsilon2 = float(np.asarray(kin.epsilon("rod"))[9])
    assert _number(r"ε2 = aτ_BA / lBA = ([\d.]+) rad/s²", text) == four(abs(epsilon2))
    a_b = float(np.hypot(*np.asarray(kin.acceleration("B"))[9]))
    assert _number(r"a_B = [pπ]b · μ = [\d.]+ mm · [\d.]+ = ([\d.]+) m/s²", text) == four(a_b)
    assert mu_a > 0


def test_the_russian_plans_are_worked_out_in_russian():
    text, _ = _text("ru")
    assert "План скоростей: полюс p, μv = " in text and "План ускорений: полюс π, μa = " in text
    assert "ω2 = v_BA / lBA" in text and "рад/с" in text and "м/с²" in text
    assert not re.search(r"\b(?:rad|mm|measured|towards|from)\b", text)


@pytest.mark.parametrize("lang", ["en", "ru"])
def test_every_vector_of_the_construction_has_its_line(lang):
    """Each of the shears' 7 velocity and 14 acceleration vectors of the construction is written with its
    segment on the plan."""
    text, _ = _text(lang)
    mm = "mm" if lang == "en" else "мм"
    segments = re.findall(rf"\b[\wπ']+ = [\d.e-]+ {mm}", text)
    assert len(segments) >= 7 + 14


@pytest.mark.parametrize("name", ["four-bar", "shears-slider-crank", "percussion-rocker", "stephenson-six-bar"])
def test_every_plan_of_a_bundled_example_is_worked_out_at_every_position(name):
    """No position of the twelve (dead points, a guide's coincident point at zero distance) stops the text: each
    has a line for each vector of the construction and each point."""
    from linkwork.motion.plans import plan_series

    mech = lw.compile(lw.example(name))
    kin = lw.kinematics(mech, position_angles(mech))
    velocity, acceleration = plan_series(kin)
    for k in range(12):
        page = "".join(worked_plans(_Run("ru"), kin, k, str(k)))
        lines = page.count("<br>") + 2
        assert lines >= len(velocity.edges) + len(acceleration.edges), (name, k)
