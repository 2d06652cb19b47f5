"""The report's "Sizing" section: asked by the file's sizing: section, in the report's language."""

from __future__ import annotations

import linkwork as lw
from linkwork.lang import t
from linkwork.report.sizing import asks_sizing, sizing_body
from linkwork.study import Study

CRANK = (
    "links: {crank: {ends: [O, A], length: 0.2, mass: 100, com: [0, 0], inertia: 1}}\n"
    "frame: {points: {O: [0, 0]}}\n"
    "joints: {O: {type: revolute, links: [frame, crank]}}\n"
    "drives: [{joint: O, speed: 30 rpm}]\n"
)


def test_the_file_s_sizing_section_asks_for_the_report_s_and_an_option_overrides_it():
    plain = lw.compile(lw.loads(CRANK))
    sized = lw.compile(lw.loads(CRANK + "sizing: {pins: {O: {diameter: 40 mm, width: 50 mm}}}\n"))
    assert not asks_sizing(plain, None) and asks_sizing(sized, None)
    assert asks_sizing(plain, True) and not asks_sizing(sized, False)


def test_the_section_is_written_in_russian_with_the_figures_of_the_sizing():
    mech = lw.compile(lw.loads(CRANK + "sizing: {pins: {O: {diameter: 40 mm, width: 50 mm}}}\n"))
    body, result = sizing_body(Study(mech), lambda key, **values: t(key, "ru", **values))
    text = "".join(body)
    assert result is not None
    for words in ("Подшипники качения по ISO 281", "C треб, кН", "вращается", "Оси (пальцы)", "Не рассчитано"):
        assert words in text, words
    rating = result.bearings.joints[0].rating / 1e3
    assert f"<td>{rating:.4g}</td>" in text  # C needed, kN, as the table of linkwork size gives it


def test_a_file_that_gives_its_motor_is_not_told_the_motor_was_not_asked():
    """The double-cut shears' file gives its motor (machine.motor) and does not ask sizing to choose one: the
    section says the motor is the file's, not "Not sized: motor: not asked"."""
    study = Study(lw.compile(lw.example("double-cut-shears")))  # sized once, read in both languages
    for lang, said in (("en", "The motor is the file&#x27;s (machine.motor)"), ("ru", "Двигатель задан в файле")):
        body, _ = sizing_body(study, lambda key, **values: t(key, lang, **values))  # noqa: B023
        text = "".join(body)
        assert said in text and "not asked" not in text and "не запрошен" not in text
