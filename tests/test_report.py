"""``linkwork analyze``: the report end to end, in a headless browser, and its atomic replacement."""

from __future__ import annotations

import math
import os
import shutil
from pathlib import Path

import pytest
from typer.testing import CliRunner

pytest.importorskip("matplotlib")

import linkwork.cli.analyze  # noqa: E402,F401 - registers the command
import linkwork.cli.motion  # noqa: E402,F401 - registers the command
from linkwork.cli.main import app  # noqa: E402

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
    from linkwork.report import build as report

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


def _crank_shaper(crank: float, direction: str):
    """A slotted-lever quick return: crank O1A (O1 0.2 m above the rocker's pivot O2) whose pin's block
    slides in the rocker's slot through O2."""
    from linkwork import MechanismBuilder

    return (
        MechanismBuilder("crank-shaper")
        .frame(points={"O1": (0, 0.2), "O2": (0, 0)})
        .link("crank", ends=("O1", "A"), length=crank)
        .link("block", points={"A": (0, 0)})
        .link("rocker", points={"O2": (0, 0), "T": (0.5, 0)})
        .revolute("O1", "frame", "crank")
        .revolute("A", "crank", "block")
        .prismatic("slot", "rocker", "block", point="A", through="O2", axis=0)
        .revolute("O2", "frame", "rocker")
        .drive("O1", angle=0, speed="60 rpm", direction=direction)
        .hint("slot", crank, 0.2)
        .hint("rocker.T", 0.5 * crank / math.hypot(crank, 0.2), 0.5 * 0.2 / math.hypot(crank, 0.2))
    )


@pytest.mark.parametrize("direction", ["ccw", "cw"])
def test_the_time_ratio_of_a_crank_shaper_is_one_number_in_every_output(tmp_path, direction):
    """The rocker's extremes are where the slot is tangent to the crank circle (O2A normal to O1A): the crank
    turns pi + 2 asin(r / d) during one stroke and pi - 2 asin(r / d) during the other (d = O1O2), so
    K = (pi + 2 asin(r / d)) / (pi - 2 asin(r / d)), whichever way it turns.  The long stroke passes the crank
    over the top, away from O2, where the pin moves to the left and turns the rocker counter-clockwise: the
    forward ratio is K turning counter-clockwise and 1 / K clockwise.  The kinematics, the command line, the
    viewer, the report and the sweep metric give one number for each."""
    pytest.importorskip("pyarrow")
    import json

    import linkwork as lw
    from linkwork import report
    from linkwork.motion.analysis import extremes
    from linkwork.web import cycle_payload

    r, d, steps = 0.13, 0.2, 360
    k = (math.pi + 2 * math.asin(r / d)) / (math.pi - 2 * math.asin(r / d))
    forward = k if direction == "ccw" else 1 / k
    builder = _crank_shaper(r, direction)
    spec = builder.build()
    mech = lw.compile(spec)
    (rocker,) = extremes(lw.kinematics(mech, steps=steps))
    assert rocker.time_ratio == pytest.approx(k, rel=1e-9)
    assert rocker.forward_time_ratio == pytest.approx(forward, rel=1e-9)
    (viewer,) = cycle_payload(mech, steps)["extremes"]
    assert (viewer["time_ratio"], viewer["forward_time_ratio"]) == (rocker.time_ratio, rocker.forward_time_ratio)
    t = lw.sweep(spec, {"links.crank.length": ("0.13 m", "0.13 m", 1)}, ["time_ratio", "forward_time_ratio"],
                 steps=steps)  # fmt: skip
    assert (t["time_ratio"][0], t["forward_time_ratio"][0]) == (rocker.time_ratio, rocker.forward_time_ratio)
    path = tmp_path / "shaper.yaml"
    from ruamel.yaml import YAML

    with open(path, "w") as fh:
        YAML().dump(builder.to_dict(), fh)
    cli = runner.invoke(app, ["kinematics", str(path), "--steps", str(steps), "--json"])
    assert cli.exit_code == 0, cli.output
    (stroke,) = [e for e in json.loads(cli.stdout)["events"] if e["kind"] == "stroke"]
    ratios = (stroke["time_ratio"], stroke["forward_time_ratio"])  # JSON numbers have 12 significant digits
    assert ratios == pytest.approx((rocker.time_ratio, rocker.forward_time_ratio), rel=1e-11)
    report.analyze(mech, tmp_path / "report", steps=steps, animation=False)
    html = (tmp_path / "report" / "report.html").read_text(encoding="utf-8")
    row = html[html.index("<td>rocker</td>") :].split("</tr>")[0]  # the table of the rockers' swings
    cells = [c.split("</td>")[0] for c in row.split("<td>")[1:]]
    assert cells[-2:] == [f"{rocker.time_ratio:.6g}", f"{rocker.forward_time_ratio:.6g}"]
