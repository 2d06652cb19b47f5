"""The Russian diagrams write their tick labels with a decimal comma (0,5), the English ones with a point; read back
from the labels the figure draws."""

from __future__ import annotations

import re

import pytest

import linkwork as lw
from drawing_checks import drawn_texts

pytest.importorskip("matplotlib")

from linkwork import figures  # noqa: E402


def _ticks(fig):
    texts = drawn_texts(fig)  # drawn: the tick labels are those of the axes' final limits
    ticks = {id(t) for ax in fig.axes for t in (*ax.get_xticklabels(), *ax.get_yticklabels())}
    return [re.sub(r"[${}]|\\mathdefault", "", t.get_text()) for t in texts if id(t) in ticks]


@pytest.mark.parametrize(("lang", "sign", "other"), [("ru", ",", "."), ("en", ".", ",")])
def test_the_tick_labels_write_the_decimal_sign_of_the_language(lang, sign, other):
    kin = lw.kinematics("shears-slider-crank", steps=72)
    ticks = _ticks(figures.link_angles(kin, lang=lang))
    decimals = [s for s in ticks if re.search(r"\d[.,]\d", s)]
    assert decimals, ticks  # the links' angular velocities have ticks with decimals
    assert all(re.search(rf"\d{re.escape(sign)}\d", s) for s in decimals), decimals
    assert not any(re.search(rf"\d{re.escape(other)}\d", s) for s in ticks), ticks


def test_the_russian_plans_and_torque_diagram_write_every_number_with_a_decimal_comma():
    """Not only the ticks: the plan's scale under its title (μv = 0,005 (м/с)/мм) and the mean driving torque in the
    legend (среднее 1,194) have decimal commas in Russian, as the report's page has."""
    kin = lw.kinematics("shears-slider-crank", steps=72)
    plan = figures.velocity_plan(kin, 9, position=9, lang="ru")
    torque = figures.torque_diagram(lw.forces("double-cut-shears", steps=72), lang="ru")  # a mean not zero: the cut
    texts = [t.get_text() for fig in (plan, torque) for t in drawn_texts(fig)]
    assert any(re.search(r"μv = \d+,\d+ \(м/с\)/мм", s) for s in texts), texts
    assert any(re.fullmatch(r"среднее -?\d+,\d+(·10[⁻¹²³⁴⁵⁶⁷⁸⁹⁰]+)?", s) for s in texts), texts
    assert not any(re.search(r"\d\.\d", s) for s in texts), [s for s in texts if re.search(r"\d\.\d", s)]
