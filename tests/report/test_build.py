"""``linkwork analyze``: the report end to end, in a headless browser, and its atomic replacement."""

from __future__ import annotations

import functools
import html
import math
import os
import re
import shutil
import sys
from html.parser import HTMLParser
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

pytest.importorskip("matplotlib")

import linkwork.cli.analyze  # noqa: E402,F401 - registers the command
import linkwork.cli.dynamics  # noqa: E402,F401 - registers the command
import linkwork.cli.motion  # noqa: E402,F401 - registers the command
from linkwork import figures  # noqa: E402
from linkwork.cli.main import app  # noqa: E402

runner = CliRunner()
SECTIONS = {
    "double-cut-shears": ["structure", "kinematics", "forces", "dynamics", "sizing", "animation"],
    "shears-slider-crank": ["structure", "kinematics", "forces", "animation"],
    "percussion-rocker": ["structure", "kinematics", "forces", "impact", "animation"],
}


@pytest.fixture(scope="module")
def reports(tmp_path_factory, main_job):
    """The folder of an example's report, built when first asked for; the double-cut shears' is the README's
    main job's (built once for the whole run)."""
    root = tmp_path_factory.mktemp("reports")
    assert main_job.returncode == 0, main_job.stderr

    @functools.cache
    def report(name: str) -> Path:
        if name == "double-cut-shears":
            return main_job.folder
        result = runner.invoke(app, ["analyze", name, "--out", str(root / name), "--steps", "120"])
        assert result.exit_code == 0, result.output
        return root / name

    return report


@pytest.mark.parametrize("name", list(SECTIONS))
def test_analyze_writes_tables_figures_and_the_report(reports, name):
    folder = reports(name)
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


@pytest.mark.browser
@pytest.mark.parametrize("name", list(SECTIONS))
def test_the_report_renders_in_a_headless_browser(reports, name):
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
        page = browser.new_page()
        errors: list[str] = []
        page.on("console", lambda msg, e=errors: e.append(msg.text) if msg.type == "error" else None)
        page.on("pageerror", lambda exc, e=errors: e.append(str(exc)))
        page.goto(Path(reports(name) / "report.html").as_uri())
        assert errors == []
        for key in SECTIONS[name]:
            assert page.locator(f"section#{key} h2").is_visible()
        widths = page.eval_on_selector_all("img", "els => els.map(e => e.naturalWidth)")
        assert len(widths) >= 8 and min(widths) > 50  # every image decoded
        page.close()
        browser.close()


def test_a_rerun_replaces_the_report_and_a_failed_run_leaves_the_old_one(tmp_path, monkeypatch, sketched_figures):
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

    monkeypatch.setattr(report, "write_html", broken)
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
def test_the_time_ratio_of_a_crank_shaper_is_one_number_in_every_output(tmp_path, direction, sketched_figures):
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
    (viewer,) = cycle_payload(mech, steps)["extremes"]  # sampled from position 0: refined from other samples
    assert viewer["time_ratio"] == pytest.approx(rocker.time_ratio, rel=1e-10)
    assert viewer["forward_time_ratio"] == pytest.approx(rocker.forward_time_ratio, rel=1e-10)
    t = lw.sweep(
        spec, {"links.crank.length": ("0.13 m", "0.13 m", 1)}, ["time_ratio", "forward_time_ratio"], steps=steps
    )
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
    row = html[html.index("<td>rocker</td>", html.index("<section id='kinematics'>")) :].split("</tr>")[0]  # swings
    cells = [c.split("</td>")[0] for c in row.split("<td>")[1:]]
    assert cells[-2:] == [f"{rocker.time_ratio:.6g}", f"{rocker.forward_time_ratio:.6g}"]


class _Text(HTMLParser):
    """The text a reader sees in a report page: its data and the images' alternative texts, not the style
    nor the input file's own words (a <pre> of the file, the <code> of its keys and values)."""

    def __init__(self) -> None:
        super().__init__()
        self.parts: list[str] = []
        self.skip = 0

    def handle_starttag(self, tag, attrs):
        self.skip += tag in ("style", "pre", "script", "code")
        self.parts += [v for k, v in attrs if k == "alt" and v]

    def handle_endtag(self, tag):
        self.skip -= tag in ("style", "pre", "script", "code")

    def handle_data(self, data):
        if not self.skip:
            self.parts.append(data)


def _tables(page: str) -> list[list[list[str]]]:
    """Every table of a report page as rows of cells (the heading first)."""
    out = []
    for table in re.findall(r"<table>(.*?)</table>", page, flags=re.S):
        rows = re.findall(r"<tr>(.*?)</tr>", table, flags=re.S)
        out.append([[html.unescape(c) for c in re.findall(r"<t[hd]>(.*?)</t[hd]>", row, flags=re.S)] for row in rows])
    return out


def _report(name: str, folder: Path, lang: str = "en", steps: int = 72, position: int | str | None = None):
    """``analyze`` on an example; returns the page and the figures it drew, by name."""
    import linkwork as lw
    from linkwork.report import build
    from linkwork.report import run as report_run

    drawn = {}
    draw = report_run.ReportRun._draw

    def keep(self, key, make):
        drawn[key] = fig = make()
        return draw(self, key, lambda: fig)

    with pytest.MonkeyPatch.context() as m:
        m.setattr(report_run.ReportRun, "_draw", keep)
        m.setattr(build, "PARALLEL", False)  # every figure drawn in this process
        build.analyze(lw.compile(lw.example(name)), folder, steps=steps, position=position, animation=False, lang=lang)
    return (folder / "report.html").read_text(encoding="utf-8"), drawn


#: Symbols of quantities and notation written in Latin letters in Russian texts too.
SYMBOLS = {"Fx", "Fy", "II", "III", "IV", "linkwork", "size", "ISO", "CuSn", "pv"}  # linkwork size; ISO 281; CuSn12


@pytest.mark.parametrize("name", ["double-cut-shears", "percussion-rocker"])
def test_no_english_is_left_in_the_russian_report(name, tmp_path):
    """The page of ``analyze --lang ru --position all`` and the texts of every figure (the diagrams, the
    scheme, the plan of positions, the plans and the sheets of twelve plans with their legends) hold no
    word in Latin letters but the names from the mechanism's file and the symbols of quantities (W, n, p5,
    Fx, II(2,3) ...)."""
    import linkwork as lw
    from drawing_checks import drawn_texts
    from linkwork.motion.plans import plan_series

    mech = lw.compile(lw.example(name))
    names = {mech.name, *mech.link_names, *mech.pair_joint, *(p.split(".", 1)[1] for p in mech.point_names)}
    names |= set(plan_series(lw.kinematics(mech, steps=12))[1].labels)  # the plans' points: b, n_ba, k'_e ...
    names |= {load.name for load in mech.loads}  # the file's names of its loads (F5 (cutting) on a force plan)
    # the plans worked out: vectors and lengths of point pairs (v_BA, lBA, aⁿ_BO3), segments of the plans (ab, n_bab)
    points = {p.split(".", 1)[1] for p in mech.point_names}
    labels = [*plan_series(lw.kinematics(mech, steps=12))[1].labels, "p"]
    names |= {f"l{a}{b}" for a in points for b in points} | {a + b for a in [*points, *labels] for b in points}
    names |= {a + b for a in labels for b in labels}
    allowed = {w for n in names for w in re.findall(r"[A-Za-z]+", n)} | SYMBOLS
    page, drawn = _report(name, tmp_path / "r", lang="ru", position="all")
    assert {"scheme", "positions", "velocity_plan", "acceleration_plan", "velocity_plans"} <= set(drawn)
    assert {"force_plans", "lever", "levers", "force_plans_2_3"} <= set(drawn)  # the graphical kinetostatics
    assert "<html lang='ru'>" in page
    reader = _Text()
    reader.feed(page)
    texts = {"report.html": " ".join(reader.parts)}
    texts |= {key: " ".join(t.get_text() for t in drawn_texts(fig)) for key, fig in drawn.items()}
    texts = {key: re.sub(r"\\[A-Za-z]+", "", text) for key, text in texts.items()}  # mathtext's commands
    english = {
        key: sorted({w for w in re.findall(r"[A-Za-z]{2,}", text) if w not in allowed}) for key, text in texts.items()
    }
    assert {key: words for key, words in english.items() if words} == {}
    assert "Кинематический анализ" in page and "План скоростей" in page
    assert "План сил:" in page and "Рычаг Жуковского" in page and "уравновешивающий момент Mу" in page


def test_english_is_the_default_and_an_unknown_language_is_refused(tmp_path, sketched_figures):
    import linkwork as lw
    from linkwork import report

    page = report.analyze(lw.compile(lw.example("four-bar")), tmp_path / "en", steps=36, animation=False).read_text(
        encoding="utf-8"
    )
    assert "<html lang='en'>" in page and "Kinematics" in page
    out = tmp_path / "de"
    result = runner.invoke(app, ["analyze", "four-bar", "--out", str(out), "--lang", "de"])
    assert result.exit_code == 2 and "--lang: expected one of en, ru, got 'de'" in result.stderr
    assert not out.exists()


def test_the_tables_state_their_units_and_measure_the_crank_angle_from_position_0(main_job):
    """The strokes (mm) and the rocker's swing (°) of the double-cut shears as a dense sampling of the
    motion finds them (0.005° apart), each in a column that names its unit; the 12 positions from
    position 0, where the upper knife is at its highest, 30° apart.  The page is the README's main job's
    (``analyze`` at its 360 steps)."""
    import linkwork as lw
    from linkwork.motion.analysis import coordinate, outputs

    assert main_job.returncode == 0, main_job.stderr
    assert main_job.args[2] == "double-cut-shears" and "--steps" not in main_job.args
    mech = lw.compile(lw.example("double-cut-shears"))
    page = (main_job.folder / "report.html").read_text(encoding="utf-8")
    found = _tables(page)
    tables = {t[0][1]: t for t in found if len(t[0]) > 1}
    kin = lw.kinematics(mech, steps=72000)
    dense = {out.name: coordinate(kin, out)[0][0] for out in outputs(mech)}
    sliders, rockers = tables["stroke H, mm"], tables["swing β, °"]
    for row in sliders[1:]:
        joint = row[0].split("(")[1].rstrip(")")
        assert float(row[1]) == pytest.approx(np.ptp(dense[joint]) * 1000, abs=0.01)
    (row,) = rockers[1:]
    assert row[0] == "rocker" and float(row[1]) == pytest.approx(math.degrees(np.ptp(dense["rocker"])), abs=1e-3)
    (positions,) = [t for t in found if t[0][1:3] == ["φ, °", "crank to the x axis, °"]]
    assert [r[1] for r in positions[1:]] == [str(30 * k) for k in range(12)]
    e = positions[0].index("E")
    y = [float(r[e].split("<br>")[1]) for r in positions[1:]]  # a point's x over its y
    assert y[0] == max(y) == pytest.approx(1000 * dense["guide_E"].max() + 0.0, abs=0.05)  # guide_E is along y


def test_the_report_runs_the_machine_unit_as_linkwork_dynamics_does(main_job, monkeypatch):
    """One run of the machine unit behind every entry point: the report's ``dynamics.json`` holds the steady
    cycle, start-up time and flywheel that ``linkwork dynamics --json`` prints for the same file (a report
    that sampled the reduced inertia and loads more coarsely would differ in the fifth digit of its speed
    fluctuation, and take longer: the solver steps over more corners of the load).  Both on the NumPy kernels,
    as the main job runs: the compiled ones differ in the last bits, which the adaptive solver's steps carry
    to its tolerance (1e-7 of the speed fluctuation)."""
    import json

    assert main_job.returncode == 0, main_job.stderr
    report = json.loads((main_job.folder / "dynamics.json").read_text(encoding="utf-8"))
    monkeypatch.setenv("LINKWORK_NUMBA", "0")
    result = runner.invoke(app, ["dynamics", "double-cut-shears", "--json"])
    assert result.exit_code == 0, result.output
    cli = json.loads(result.output)
    keys = ("omega_mean", "omega_min", "omega_max", "delta", "mean_power", "startup_time", "flywheel_inertia")
    assert {k: report[k] for k in keys} == {k: cli[k] for k in keys}
    assert report["steady"] and len(report["phi_deg"]) == len(cli["phi_deg"])


def test_the_dynamics_diagram_and_json_measure_the_crank_angle_from_position_0():
    """The double-cut shears slow down while they cut and speed up after: the lowest crank speed of the
    steady cycle comes where the cutting load falls below the drive's moment, at the end of the cut.  The
    cut is read off the reduced load moment at its own angles; the lowest speed at ``cycle.phi_deg``
    of ``linkwork dynamics --json`` and on the diagram's speed curve, both from position 0
    (``cycle.psi_deg`` counts from the start of the steady turn, 281° from it)."""
    import linkwork as lw
    from linkwork.io.dynamics_tables import to_json
    from linkwork.motion.analysis import from_position_0, zero_angle

    mech = lw.compile(lw.example("double-cut-shears"))
    result = lw.dynamics(mech)
    zero = zero_angle(mech)
    red = result.reduced
    phi = np.degrees(from_position_0(red.angle, zero, 1.0))
    falling = phi[red.load < 0.5 * red.load.min()].max()  # the load past its half on the way out of the cut
    ended = phi[red.load < 0.01 * red.load.min()].max()  # and over
    data = to_json(mech, result)
    cycle = data["cycle"]
    lowest = cycle["phi_deg"][int(np.argmin(cycle["omega"]))]
    assert falling < lowest <= ended + 0.5  # where the drive's moment overcomes the load's
    assert data["position_0_deg"] == pytest.approx(math.degrees(zero))
    fig = figures.dynamics_diagrams(result, zero)
    speed = next(ax for ax in fig.axes if ax.get_ylabel().startswith("crank speed"))
    x, y = speed.get_lines()[0].get_xydata().T
    assert x[np.argmin(y)] == pytest.approx(lowest, abs=0.5)


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="the second process is forked on Linux only")
def test_the_two_processes_share_the_jobs_and_each_runs_once(tmp_path):
    """Whichever process is free takes the next job: the first holds one process for half a second, the other
    takes the rest meanwhile; every job runs once, and both processes run some."""
    import time

    from linkwork.report.beside import Beside

    log = tmp_path / "log"

    def job(i):
        def run():
            if i == 0:
                time.sleep(0.5)
            with open(log, "a", encoding="utf-8") as f:  # one short append per line: lines do not mix
                f.write(f"{i} {os.getpid()}\n")

        return run

    beside = Beside()
    beside.start([job(i) for i in range(12)])
    beside.wait()
    runs = [line.split() for line in log.read_text(encoding="utf-8").splitlines()]
    assert sorted(int(i) for i, _ in runs) == list(range(12))
    assert str(os.getpid()) in {pid for _, pid in runs} and len({pid for _, pid in runs}) == 2


@pytest.mark.slow  # over the default lane's budget on the NumPy kernels (tests/conftest.py)
def test_a_figure_that_fails_in_the_second_process_fails_the_report_and_writes_nothing(tmp_path, monkeypatch):
    """The figures of the kinematics are drawn in a forked process: its error comes back as it was raised,
    and no report is put in place."""
    import linkwork as lw
    from linkwork.report import beside, build

    def broken(*args, **kwargs):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(figures, "draw_positions", broken)
    mech = lw.compile(lw.example("four-bar"))
    with pytest.raises(OSError, match="No space left on device"):
        build.analyze(mech, tmp_path / "r", steps=36, animation=False)
    assert list(tmp_path.iterdir()) == []
    assert beside.FORKS == sys.platform.startswith("linux")


def test_the_report_presents_the_kinetostatics_by_the_graphical_method(main_job):
    """The README's main job (the double-cut shears, under the cutting load): each group's moment equations and
    force plan, the force plans and the lever drawn, and the lever's balancing moment beside the kinetostatic
    driving torque at the twelve positions, equal to the 7 digits written."""
    import linkwork as lw
    from linkwork.scene.positions import position_angles

    page = html.unescape((main_job.folder / "report.html").read_text(encoding="utf-8"))
    assert "id='force_plans'" in page and "id='lever'" in page
    assert page.count("Force plan: ") == 4  # one for each of the four groups
    assert "R12τ + G2 + Phi2 + G3 + Phi3 + R43 + R63 + R03τ + R03n + R12n = 0" in page
    mech = lw.compile(lw.example("double-cut-shears"))
    torque = lw.forces(lw.kinematics(mech, position_angles(mech))).driving_torque
    start = page.index("Zhukovsky's lever: the balancing moment")
    rows = re.findall(r"<tr><td>(\d+)</td><td>\d+</td><td>([^<]+)</td><td>([^<]+)</td>", page[start:])[:12]
    assert [int(r[0]) for r in rows] == list(range(12))
    for k, lever_value, kinetostatic in rows:
        assert float(lever_value) == pytest.approx(torque[int(k)], rel=1e-6)
        assert lever_value == kinetostatic


def test_the_report_draws_the_run_in_time_the_file_asks_for(tmp_path):
    """A pendulum with a torsion spring and ``simulate: {until: 0.5 s, angle: 275 deg}``: the report has the
    section, its diagram, and simulate.csv whose last row is the run lw.simulate gives."""
    import csv

    import linkwork as lw
    from linkwork.report import build as report

    b = lw.MechanismBuilder("pendulum", gravity="9.81 m/s^2")
    b.frame(points={"O": (0, 0)})
    b.link("arm", points={"O": (0, 0), "P": (0.4, 0)}, mass=2.0, com=(0.4, 0), inertia="0.05 kg*m^2")
    b.revolute("O", "frame", "arm").drive("O", angle="270 deg")
    b.torsion_spring("t", "O", "30 N*m/rad", "270 deg")
    data = b.to_dict()
    data["simulate"] = {"until": "0.5 s", "angle": "275 deg"}
    mech = lw.compile(lw.from_dict(data))
    out = tmp_path / "r"
    report.analyze(mech, out, steps=36, animation=False)
    page = (out / "report.html").read_text(encoding="utf-8")
    assert "<h2>Run in time</h2>" in page and re.search(r"Figure \d+\. Run in time", page)
    assert (out / "figures" / "simulate.svg").stat().st_size > 1000
    with open(out / "simulate.csv", encoding="utf-8") as f:
        last = list(csv.DictReader(f))[-1]
    run = lw.simulate(mech, 0.5, angle=math.radians(275), times=[0.5])
    assert float(last["omega [rad/s]"]) == pytest.approx(run.speed[0], rel=1e-9)


@pytest.mark.slow  # a whole report (its figures sketched): over the default lane's budget
def test_the_structures_warnings_are_in_the_reports_language(tmp_path, sketched_figures):
    """The four-bar with the hint for B 100 mm from where B assembles: the Russian report's warnings section says
    so in Russian, with decimal commas, as the viewer does; the English one as ``linkwork check`` does."""
    import copy

    import linkwork as lw
    from linkwork.report import build

    data = copy.deepcopy(lw.example("four-bar").model_dump(exclude_none=True)) | {"units": {"angle": "rad"}}
    data["hints"] = {"B": [0.33, 0.14]}
    mech = lw.compile(lw.from_dict(data))
    for lang, said in (("en", mech.structure.warnings[0]), ("ru", "подсказка для B в точке (0,33; 0,14) отстоит на")):
        build.analyze(mech, tmp_path / lang, steps=36, animation=False, lang=lang)
        page = (tmp_path / lang / "report.html").read_text(encoding="utf-8")
        section = page[page.index("<section id='warnings'>") :]
        assert said in section.replace("&#x27;", "'"), section[:400]
