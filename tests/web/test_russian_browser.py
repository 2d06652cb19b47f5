"""The exported viewer in Russian and in English, read in headless Chromium as a person reads it: every text it shows
(the page, its captions, tables, charts, the scheme's and the plans' drawings, the force plans of every group and
the lever) in Russian but the names from the mechanism's file and the symbols of quantities; the English page's key
labels as they were."""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import pytest

playwright = pytest.importorskip("playwright.sync_api")

import linkwork as lw  # noqa: E402
from linkwork.motion.plans import plan_series  # noqa: E402
from linkwork.web import export_page  # noqa: E402

pytestmark = pytest.mark.browser

NAME = "double-cut-shears"
ARTIFACTS = Path(__file__).resolve().parents[2] / "test-artifacts"

#: Words of Latin letters the Russian page may show besides the file's names: symbols (II(2,3), the forces'
#: Rij), the command that edits a mechanism and the keys that undo and redo.
SYMBOLS = {"II", "III", "IV", "Rij", "linkwork", "view", "Ctrl", "Shift"}

#: Every text an element shows or says: its text, its title and its aria-label, and the SVG drawings' texts.
SHOWN = """() => {
  const out = [document.body.innerText, document.title];
  for (const e of document.querySelectorAll("svg text, svg title")) out.push(e.textContent);
  for (const e of document.querySelectorAll("[title], [aria-label]")) {
    out.push(e.getAttribute("title") || "", e.getAttribute("aria-label") || "");
  }
  return out.join("\\n");
}"""


@pytest.fixture(scope="module")
def browser():
    path = shutil.which("chromium") or shutil.which("chromium-browser")
    if path is None:
        pytest.skip("chromium is not installed (.ci/run installs it)")
    with playwright.sync_playwright() as p:
        b = p.chromium.launch(executable_path=path, args=["--no-sandbox", "--disable-gpu"])
        yield b
        b.close()


def _open(browser, path: Path):
    page = browser.new_page(viewport={"width": 1400, "height": 1000})
    page.errors = []
    page.on("pageerror", lambda exc: page.errors.append(str(exc)))
    page.goto(path.as_uri())
    page.wait_for_selector("#force-plan line.fvec")
    page.check("#show-forces")
    return page


def _turn(page, index: int) -> None:
    page.fill("#angle", str(index))
    page.dispatch_event("#angle", "input")


def _allowed(mech) -> set[str]:
    """The words of the file's names (the mechanism, links, joints, points, loads, the plans' points and the named
    parameters the edit panel lists: ``links.crank.length``)."""
    from linkwork.structure.parameters import parameter_list

    names = {mech.name, *mech.link_names, *mech.pair_joint, *(p.split(".", 1)[1] for p in mech.point_names)}
    names |= {load.name for load in mech.loads}
    labels = plan_series(lw.kinematics(mech, steps=12))[1].labels
    names |= {*labels, *(label.replace("_", "") for label in labels)}  # n_ba, drawn n with its subscript ba
    names |= {p.name for p in parameter_list(mech)}
    return {w for n in names for w in re.findall(r"[A-Za-z]+", n)} | SYMBOLS


def test_the_russian_page_shows_no_english_program_word(browser, tmp_path):
    """At the cut (φ = 90°) and in the idle stroke, with the forces on the scheme and each force plan and the
    lever chosen in turn, the page shows no word of two or more Latin letters but the file's names and the
    symbols; π is the acceleration plan's pole, numbers have a decimal comma."""
    mech = lw.compile(lw.example(NAME))
    out = export_page(NAME, tmp_path / "ru.html", steps=72, lang="ru")
    page = _open(browser, out)
    assert page.get_attribute("html", "lang") == "ru"
    allowed = _allowed(mech)
    english: dict[str, list[str]] = {}
    for index in (18, 50):  # of 72: at 90° the knives cut, at 250° they return
        _turn(page, index)
        choices = page.eval_on_selector_all("#force-plan-choice option", "os => os.map(o => o.value)")
        assert "lever" in choices and len(choices) == 5  # three groups, the driving link, the lever
        for choice in choices:
            page.select_option("#force-plan-choice", choice)
            words = set(re.findall(r"[A-Za-z]{2,}", page.evaluate(SHOWN))) - allowed
            english |= {f"{index}/{choice}": sorted(words)} if words else {}
    assert english == {}
    _turn(page, 18)
    assert page.text_content("#angle-text").startswith("φ = 90,0° от положения 0")
    assert "полюс π, μa = " in page.text_content("#acceleration-caption")
    assert "π" in page.eval_on_selector_all("#acceleration-plan text.plabel", "ts => ts.map(t => t.textContent)")
    assert "полюс p, μv = " in page.text_content("#velocity-caption")
    page.select_option("#force-plan-choice", "lever")
    caption = page.text_content("#force-plan-caption")
    assert caption.startswith("Рычаг Жуковского при φ = 90,0°") and "уравновешивающий момент Mу = " in caption
    inertia = page.eval_on_selector_all('#force-plan text.fname[data-name^="Φ"]', "ts => ts.map(t => t.textContent)")
    assert inertia and all(re.fullmatch(r"Φ\d", t) for t in inertia)
    # the white halo under a name is narrower than a letter's stroke: a halo of 2 units of a drawing whose letters
    # are 3.8 units high covered the leg of R and the bar of G (R07 read P07, G2 C2)
    halo = page.eval_on_selector_all(
        "#force-plan text.fname",
        "ts => ts.map(t => parseFloat(getComputedStyle(t).strokeWidth) / parseFloat(getComputedStyle(t).fontSize))",
    )
    assert halo and max(halo) <= 0.15
    assert page.errors == []
    ARTIFACTS.mkdir(exist_ok=True)
    page.screenshot(path=str(ARTIFACTS / "viewer-ru.png"), full_page=True)


def test_the_english_page_keeps_its_labels(browser, tmp_path):
    """English is the default: the page's buttons, headings and captions as before; the force plans name the inertia
    forces as the figures do, Φ with a subscript (their data-name stays the tables' Phi6)."""
    out = export_page(NAME, tmp_path / "en.html", steps=72)
    page = _open(browser, out)
    assert page.get_attribute("html", "lang") == "en"
    _turn(page, 18)
    assert page.text_content("#play") == "Play" and page.text_content("#charts-panel h2") == "Over the cycle"
    assert page.text_content("#angle-text").startswith("φ = 90.0° from position 0, crank at ")
    assert page.text_content("#velocity-caption").startswith("velocity plan, pole p, μv = ")
    assert page.text_content("#acceleration-caption").startswith("acceleration plan, pole p, μa = ")
    assert page.text_content("#peak-torque").startswith("peak driving torque ")
    assert "drive: joint O1, 30 rpm ccw" in page.text_content("#structure")
    page.select_option("#force-plan-choice", "group:0")
    assert page.text_content("#force-plan-caption").startswith("force plan of II(6,7) RRP at φ = 90.0°, μF = ")
    page.select_option("#force-plan-choice", "lever")
    phi = page.eval_on_selector_all(
        '#force-plan text.fname[data-name^="Phi"]',
        "ts => ts.map(t => [t.getAttribute('data-name'), t.textContent, t.querySelector('tspan.sub').textContent])",
    )
    assert phi and all(shown == "Φ" + name[3:] and sub == name[3:] for name, shown, sub in phi)
    assert page.errors == []
