"""The viewer in Russian (``linkwork view --lang ru``): its texts from the catalogues of :mod:`linkwork.lang`, the
notation of the Russian report (π for the acceleration plan's pole, ВВП for a group's kind, Φ for inertia forces),
an unknown language refused as ``analyze`` refuses it, and the English page as it was."""

from __future__ import annotations

import html
import re

import pytest
from typer.testing import CliRunner

from linkwork.lang import texts
from linkwork.web.force_plans import tex_runs
from linkwork.web.session import SCRIPTS, Viewer, page_html, static_text
from linkwork.web.texts import page_texts

runner = CliRunner()

#: The keys the scripts make from a value (``T(`view.kind.${e.kind}`)``), with the values they take.
MADE = {
    "view.kind.": ("slider", "rocker"),
    "view.group.": ("dimensions", "masses"),
    "view.": ("ccw", "cw", "pause", "play"),
    "plan.": ("velocity", "acceleration"),
    "plan.unit.": ("velocity", "acceleration"),
}


@pytest.mark.parametrize("export", [True, False])
def test_an_unknown_language_is_refused_in_one_line_with_exit_2(tmp_path, export):
    """``view --lang de``: one line, the message of ``analyze --lang de``, exit 2, no page written and no server
    started (the language is checked before the mechanism is solved)."""
    import linkwork.cli.view  # noqa: F401
    from linkwork.cli.main import app

    out = tmp_path / "v.html"
    args = ["view", "four-bar", "--lang", "de"] + (
        ["--export", str(out)] if export else ["--no-browser", "--port", "1"]
    )
    result = runner.invoke(app, args)
    assert result.exit_code == 2
    lines = [line for line in result.output.splitlines() if line.strip()]
    assert lines == ["error: --lang: expected one of en, ru, got 'de'"]
    assert not out.exists() and list(tmp_path.iterdir()) == []


def test_every_text_the_scripts_ask_for_is_in_both_catalogues():
    """Each key the page's scripts read (``T("view.peak", ...)``, and those made from a value) is a text the
    payload carries in each language, and each ``data-t`` key of the page one of the catalogues'."""
    scripts = "\n".join(static_text(name) for name in SCRIPTS)
    asked = set(re.findall(r'\bT\("([\w.]+)"', scripts))
    asked |= {prefix + value for prefix, values in MADE.items() for value in values}
    assert len(asked) > 60
    for lang in ("en", "ru"):
        carried = page_texts(lang)
        assert sorted(asked - set(carried)) == [], lang
    page = static_text("index.html")
    assert set(re.findall(r'data-t(?:-[a-z-]+)?="([^"]+)"', page)) <= set(texts())


def test_the_page_is_written_in_the_language_asked_for():
    """The page's own words: English as they were, Russian from the catalogue; the html element says which."""
    en, ru = page_html("en"), page_html("ru")
    assert en.startswith('<!DOCTYPE html>\n<html lang="en">')
    for words in ('id="play" data-t="view.play">Play<', ">Over the cycle<", ">Structure and motion<", ">Apply<"):
        assert words in en
    assert '<html lang="ru">' in ru and 'id="play" data-t="view.play">Пуск<' in ru and ">За цикл<" in ru
    visible = html.unescape(re.sub(r"<script.*?</script>|<style.*?</style>|<[^>]*>", " ", ru, flags=re.S))
    assert re.findall(r"[A-Za-z]{2,}", visible) == []  # every word the page shows before its payload, in Russian
    attributes = re.findall(r'\s(?:title|aria-label)="([^"]*)"', ru)
    assert attributes and all(re.search("[а-я]", a) or a.startswith("Ctrl") for a in attributes)


def test_tex_runs_sets_the_figures_names_with_their_sub_and_superscripts():
    """The names as the figures' mathtext writes them, set as runs: R₁₂ⁿ, Φ₂, R₁₂^τ, M_Φ2, F_у."""
    assert tex_runs("$R_{12}^{n}$") == [["R", ""], ["12", "sub"], ["n", "sup"]]
    assert tex_runs("$\\Phi_{2}$") == [["Φ", ""], ["2", "sub"]]
    assert tex_runs("$R_{12}^{\\tau}$") == [["R", ""], ["12", "sub"], ["τ", "sup"]]
    assert tex_runs("$M_{\\Phi 2}$") == [["M", ""], ["Φ2", "sub"]]
    assert tex_runs("$F_{у}$") == [["F", ""], ["у", "sub"]]
    assert tex_runs("cutting") == [["cutting", ""]]


@pytest.fixture(scope="module")
def slider_crank():
    """The shears slider-crank's payloads in English and Russian (24 samples) and their force drawings at sample 3."""
    out = {}
    for lang in ("en", "ru"):
        viewer = Viewer("shears-slider-crank", 24, placed=None, lang=lang)
        out[lang] = (viewer.cycle(), viewer.force_plans_at([3]))
    return out


def test_the_russian_payload_writes_the_report_s_notation(slider_crank):
    """π for the acceleration plan's pole (p stays the velocity plan's), the groups' kinds in В and П, the series
    and units in Russian, the inertia forces Φ; the file's names as written."""
    payload, plans = slider_crank["ru"]
    assert payload["lang"] == "ru" and payload["texts"]["view.play"] == "Пуск"
    acceleration, velocity = payload["scene"]["plans"]["acceleration"], payload["scene"]["plans"]["velocity"]
    assert acceleration["pole"] == "π" and velocity["pole"] == "p"
    first = [text for row in acceleration["text"] for text in row if text]
    assert any(text.split(",")[0] == "π" for text in first) and not any(t.split(",")[0] == "p" for t in first)
    kinds = {g["kind"]: g["kind_shown"] for g in payload["structure"]["groups"]}
    assert kinds == {"R": "В", "RRP": "ВВП"}
    assert all(re.search("[а-я]", s["label"]) for s in payload["series"])
    assert {s["unit"] for s in payload["series"]} <= {"мм", "м/с", "м/с²", "°", "рад/с", "Н·м", "Н"}
    assert payload["units"]["length"] == ["мм", 1000.0] and payload["units"]["angle"][0] == "°"
    names = {a["text"] for d in plans["at"][0]["drawings"] for a in d["arrows"]}
    assert "Φ3" in names and not any("Phi" in n for n in names)
    assert plans["groups"][-1]["title"] == "Рычаг Жуковского" and "ВВП" in plans["groups"][0]["title"]


def test_the_english_payload_keeps_its_labels(slider_crank):
    """English stays the default, its labels as before; the inertia forces are drawn as the figures write them
    (Φ with a subscript), their plain names (``Phi3``) kept for the tables."""
    payload, plans = slider_crank["en"]
    assert payload["lang"] == "en" and payload["units"]["length"] == ["mm", 1000.0]
    labels = {s["key"]: (s["label"], s["unit"]) for s in payload["series"]}
    assert labels["torque"] == ("driving torque on the crank (ccw +)", "N m")
    assert labels["foundation:fy"] == ("force on the foundation, y (up +: pulls the bolts)", "N")
    joint = next(k for k in labels if k.startswith("slider:") and k.endswith(":v")).split(":")[1]
    assert labels[f"slider:{joint}:v"][0].startswith("velocity of ") and labels[f"slider:{joint}:v"][1] == "m/s"
    assert {p["pole"] for p in payload["scene"]["plans"].values()} == {"p"}
    assert payload["scene"]["plans"]["velocity"]["kinds"]["absolute"] == "absolute (from the pole)"
    assert [g["kind_shown"] for g in payload["structure"]["groups"]] == [
        g["kind"] for g in payload["structure"]["groups"]
    ]
    phi = [a for d in plans["at"][0]["drawings"] for a in d["arrows"] if a["text"] == "Phi3"]
    assert phi and phi[0]["runs"] == [["Φ", ""], ["3", "sub"]]
    assert plans["groups"][-1]["title"] == "Zhukovsky's lever"


def test_the_viewer_refuses_an_unknown_language():
    from linkwork.errors import LinkworkError

    with pytest.raises(LinkworkError, match="expected one of en, ru, got 'fr'"):
        Viewer("four-bar", 12, lang="fr")


def test_an_event_is_said_in_russian_at_the_crank_angles_of_the_closed_form():
    """A crank of 0.3 m puts A beyond the reach of rod and rocker (0.4 + 0.5 m from O3) where
    |O3O1 + 0.3 u(a)| > 0.9: 0.5 cos a + 0.4 sin a > 0.31 / 0.6, for drive angles a between 38.66° ∓ 36.2°.  The
    Russian page says so as the report does, at φ = a turned from position 0 (the drive ccw), decimal commas."""
    import math

    import linkwork as lw
    from linkwork.web.cycle import solve_cycle
    from linkwork.web.payload import events_part

    cycle = solve_cycle(lw.compile(lw.example("double-cut-shears")), 24, {"links.crank.length": 0.3})
    theta, half = math.atan2(0.4, 0.5), math.acos(0.31 / 0.6 / math.hypot(0.5, 0.4))
    zero = math.degrees(float(cycle.kin.angles[0]))  # the drive angle of position 0
    start, end = (f"{(math.degrees(a) - zero) % 360:.1f}".replace(".", ",") for a in (theta - half, theta + half))
    said = [e["text"] for e in events_part(cycle, "ru") if e["kind"] == "no-assembly"]
    assert said == [f"Группа II(2,3) ВВВ не собирается при φ от {start}° до {end}°."]
    english = events_part(cycle, "en")
    assert english and all("text" not in e for e in english)  # English: the analysis's message, as before
    # a drag there is refused in the page's language, the edit written as the page writes it
    from linkwork.web.cycle import OutOfRange

    with pytest.raises(OutOfRange) as refused:
        Viewer("double-cut-shears", 24, lang="ru").solve({"links.crank.length": 0.3}, whole_turn=True)
    assert str(refused.value) == (f"links.crank.length = 300 мм: механизм собирается не на всём обороте: {said[0]}")


def test_the_warnings_of_the_structure_and_the_friction_are_said_in_the_pages_language():
    """A hint 100 mm from where B assembles (the four-bar's B assembles near (330, 240) mm): the structure's
    warning in English and in Russian with the same gap, the distance from the hint to the point assembled; a
    slider-crank whose friction (f 0.3 in every pair) locks it: the Russian page says where as the report does
    (Самоторможение при φ = ...), and the English page as the analysis words it."""
    import copy
    import re

    import numpy as np

    import linkwork as lw
    from linkwork.web import payload
    from linkwork.web.cycle import solve_cycle

    data = copy.deepcopy(lw.example("four-bar").model_dump(exclude_none=True)) | {"units": {"angle": "rad"}}
    data["hints"] = {"B": [0.33, 0.14]}
    mech = lw.compile(lw.from_dict(data))
    gap = float(np.hypot(*(mech.points0()[mech.point_names.index("rocker.B")] - np.array([0.33, 0.14]))))
    assert gap > 0.05
    (en,), (ru,) = (payload._structure(mech, lang)["warnings"] for lang in ("en", "ru"))
    assert en == mech.structure.warnings[0] and en.startswith("the hint for B at (0.33, 0.14)")
    assert ru.startswith("подсказка для B в точке (0,33; 0,14) отстоит на") and "вариант сборки" in ru  # commas
    for text in (en, ru):
        assert re.search(r" (\d+[.,]\d+) [mм] ", text).group(1).replace(",", ".") == f"{gap:.3g}"  # to 3 digits
    locked = copy.deepcopy(lw.example("shears-slider-crank").model_dump(exclude_none=True)) | {
        "units": {"angle": "rad"}
    }
    for joint in locked["joints"].values():
        joint["friction"] = {"f": 0.3} if joint["type"] == "prismatic" else {"f": 0.3, "radius": 0.02}
    cycle = solve_cycle(lw.compile(lw.from_dict(locked)), 36)
    en, ru = payload._notes(cycle, "en"), payload._notes(cycle, "ru")
    assert any("locks the mechanism" in w for w in en), en
    assert any(w.startswith("Самоторможение при φ = ") for w in ru) and not any("locks" in w for w in ru), ru
