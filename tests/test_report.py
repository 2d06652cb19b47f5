"""``linkwork analyze``: the report end to end, in a headless browser, and its atomic replacement."""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest
from typer.testing import CliRunner

pytest.importorskip("matplotlib")

import linkwork.cli.analyze  # noqa: E402,F401 - registers the command
from linkwork.cli.app import app  # noqa: E402

runner = CliRunner()
SECTIONS = {
    "double-cut-shears": ["structure", "kinematics", "forces", "dynamics", "animation"],
    "shears-slider-crank": ["structure", "kinematics", "forces", "animation"],
    "percussion-rocker": ["structure", "kinematics", "forces", "impact", "animation"],
}


@pytest.fixture(scope="module")
def reports(tmp_path_factory):
    root = tmp_path_factory.mktemp("reports")
    out = {}
    for name in SECTIONS:
        result = runner.invoke(app, ["analyze", name, "--out", str(root / name), "--steps", "120"])
        assert result.exit_code == 0, result.output
        out[name] = root / name
    return out


@pytest.mark.parametrize("name", list(SECTIONS))
def test_analyze_writes_tables_figures_and_the_report(reports, name):
    folder = reports[name]
    for f in ("report.html", "kinematics.csv", "forces.csv", "forces.json", "animation.gif"):
        assert (folder / f).stat().st_size > 0, f
    svgs = sorted((folder / "figures").glob("*.svg"))
    assert len(svgs) >= 8
    assert all((folder / "figures" / f"{s.stem}.png").exists() for s in svgs)
    text = (folder / "report.html").read_text(encoding="utf-8")
    for key in SECTIONS[name]:
        assert f"id='{key}'" in text
    assert text.count("data:image/png;base64,") >= 8  # figures embedded: one file to send
    assert not list(folder.parent.glob(f".{name}.*"))  # no leftovers of the atomic swap


def test_the_report_renders_in_a_headless_browser(reports):
    """Debian's chromium (installed by .ci/run) opens report.html with no console errors and shows
    every section and its figures."""
    playwright = pytest.importorskip("playwright.sync_api")
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    if chromium is None and os.environ.get("CI"):
        pytest.fail("chromium is not installed")
    if chromium is None:
        pytest.skip("chromium is not installed (.ci/run installs it)")
    with playwright.sync_playwright() as p:
        browser = p.chromium.launch(executable_path=chromium, args=["--no-sandbox"])
        for name, keys in SECTIONS.items():
            page = browser.new_page()
            errors: list[str] = []
            page.on("console", lambda msg, e=errors: e.append(msg.text) if msg.type == "error" else None)
            page.on("pageerror", lambda exc, e=errors: e.append(str(exc)))
            page.goto(Path(reports[name] / "report.html").as_uri())
            assert errors == []
            for key in keys:
                assert page.locator(f"section#{key} h2").is_visible()
            widths = page.eval_on_selector_all("img", "els => els.map(e => e.naturalWidth)")
            assert len(widths) >= 8 and min(widths) > 50  # every image decoded
            page.close()
        browser.close()


def test_a_rerun_replaces_the_report_and_a_failed_run_leaves_the_old_one(tmp_path, monkeypatch):
    import linkwork as lw
    from linkwork import report

    out = tmp_path / "r"
    mech = lw.compile(lw.example("four-bar"))
    report.analyze(mech, out, steps=36, animation=False, pdf=True)
    assert (out / "report.pdf").read_bytes()[:5] == b"%PDF-"
    report.analyze(mech, out, steps=36, animation=False)
    assert not (out / "report.pdf").exists()  # a file of the old run that this one does not write
    good = (out / "report.html").read_bytes()

    def broken(*args, **kwargs):
        raise RuntimeError("interrupted")

    monkeypatch.setattr(report, "_write_html", broken)
    with pytest.raises(RuntimeError):
        report.analyze(mech, out, steps=36, animation=False)
    assert (out / "report.html").read_bytes() == good
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r"]
