"""The viewer in headless Chromium (Debian's, driven by Playwright; nothing is downloaded).

The scheme is drawn in millimetres with y down: a point at (x, y) m is at
``cx = 1000 x``, ``cy = -1000 y`` in the SVG (written to 0.001 mm); a plan
point of vector ``u`` is at ``(u_x, -u_y) / scale`` mm (to 0.0001 mm), with
the plan's ``scale`` in its ``data-scale``.  The page's Content-Security-Policy
forbids evaluating strings, so the tests wait with Playwright's ``expect``
rather than ``wait_for_function``.  The tests read these
coordinates back from the DOM and compare them with linkwork's kinematics
solved at the angle the page shows.  Screenshots of the main states go to
``test-artifacts/``.
"""

from __future__ import annotations

import math
import os
import shutil
import time
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("fastapi")
uvicorn = pytest.importorskip("uvicorn")
playwright = pytest.importorskip("playwright.sync_api")
expect = playwright.expect

import linkwork as lw  # noqa: E402
from linkwork.examples import text as example_text  # noqa: E402
from linkwork.kinetostatics.external import evaluate  # noqa: E402
from linkwork.motion.analysis import zero_angle  # noqa: E402
from linkwork.motion.kinematic_analysis import cycle, direction  # noqa: E402
from linkwork.web import create_app, export_page  # noqa: E402

pytestmark = pytest.mark.browser

ARTIFACTS = Path(__file__).resolve().parents[2] / "test-artifacts"
FLAGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]
NAME = "double-cut-shears"
JOINTS = ("A", "B", "C", "D", "E", "F")


def chromium_path() -> str:
    path = shutil.which("chromium") or shutil.which("chromium-browser")
    if path is None and os.environ.get("CI"):
        pytest.fail("chromium is not installed")
    if path is None:
        pytest.skip("chromium is not installed (.ci/run installs it)")
    return path


@pytest.fixture(scope="module")
def browser():
    path = chromium_path()
    with playwright.sync_playwright() as p:
        b = p.chromium.launch(executable_path=path, args=FLAGS)
        yield b
        b.close()


@pytest.fixture(scope="module")
def server():
    """The viewer of the double-cut shears on 127.0.0.1, a free port, in a background thread."""
    from webserver import serving

    with serving(create_app(lw.load(NAME))) as (host, port):
        yield f"http://{host}:{port}/"


@pytest.fixture
def page(browser):
    context = browser.new_context(viewport={"width": 1400, "height": 1000})
    pg = context.new_page()
    pg.errors = []
    pg.on("console", lambda msg: pg.errors.append(msg.text) if msg.type == "error" else None)
    pg.on("pageerror", lambda exc: pg.errors.append(str(exc)))
    yield pg
    context.close()


def shot(page, name: str) -> None:
    ARTIFACTS.mkdir(exist_ok=True)
    page.screenshot(path=str(ARTIFACTS / f"{name}.png"), full_page=True)


def open_viewer(page, url: str) -> None:
    page.goto(url)
    page.wait_for_selector('#scheme circle.joint[data-point="E"]')


def drawn(page, point: str) -> np.ndarray:
    """Position (m) of a joint as drawn: the inverse of cx = 1000 x, cy = -1000 y."""
    cx, cy = page.eval_on_selector(
        f'#scheme circle[data-point="{point}"]', "e => [e.getAttribute('cx'), e.getAttribute('cy')]"
    )
    return np.array([float(cx) / 1000, -float(cy) / 1000])


def plan_point(page, kind: str, label: str) -> np.ndarray:
    """A plan point's vector (m/s or m/s^2) as drawn: the inverse of (u_x, -u_y) / scale."""
    scale = float(page.get_attribute(f"#{kind}-plan", "data-scale"))
    cx, cy = page.eval_on_selector(
        f'#{kind}-plan circle[data-label="{label}"]', "e => [e.getAttribute('cx'), e.getAttribute('cy')]"
    )
    return np.array([float(cx), -float(cy)]) * scale, scale


def sample_of(drive_deg: float, steps: int = 360) -> int:
    """The sample of the viewer's cycle (``steps`` from position 0) nearest the crank at ``drive_deg`` to x."""
    mech = lw.compile(lw.load(NAME))
    turned = (direction(mech) * (drive_deg - math.degrees(zero_angle(mech)))) % 360
    return round(turned * steps / 360) % steps


def turn_to(page, index: int) -> float:
    """Move the crank slider to sample ``index``; the drive angle the page shows, rad."""
    page.locator("#angle").fill(str(index))
    expect(page.locator("#scheme")).to_have_attribute("data-index", str(index))
    return math.radians(float(page.get_attribute("#scheme", "data-angle-deg")))


def test_the_page_loads_without_errors_and_draws_the_mechanism(page, server):
    open_viewer(page, server)
    mech = lw.compile(lw.load(NAME))
    assert page.locator("#title").text_content() == NAME
    assert page.locator("#formula").text_content() == mech.structure.formula
    # the symbols: 8 pivots, two hatched supports, two slider blocks on two hatched guides, 7 links
    revolute = {j for j, kind in zip(mech.pair_joint, mech.pair_type, strict=True) if kind == 0}
    assert page.locator("#scheme circle.joint").count() == len(revolute) == 8
    assert page.locator("#scheme #ground polygon.support").count() == 2
    assert page.locator("#scheme polygon.block").count() == 2
    assert page.locator("#scheme #ground line.guide").count() == 2
    assert page.locator("#scheme .bar, #scheme .plate").count() == 7
    assert page.locator("#structure table").first.locator("tbody tr").count() == len(mech.structure.groups)
    assert page.locator("#charts svg.chart").count() >= 2
    assert page.locator("#error").is_hidden()
    # first shown with the labels placed at the sample shown, then along the cycle (every eighth sample)
    expect(page.locator("#scheme")).to_have_attribute("data-labels-placed", "45")
    assert page.errors == []
    shot(page, "viewer-loaded")


def test_the_page_shows_the_peak_torque_every_route_gives(page, server):
    """The peak refined between the samples (:func:`linkwork.kinetostatics.torque_peak`), as the command line, the
    report and the sweeps give it, whatever the grid (here 360 steps for the reference)."""
    from linkwork.kinetostatics.peaks import torque_peak

    open_viewer(page, server)
    reference = torque_peak(lw.forces(lw.compile(lw.load(NAME)), steps=360)).value[0]
    expect(page.locator("#peak-torque")).to_contain_text(f"peak driving torque {reference:.6g} N m")
    assert page.errors == []


def test_moving_the_slider_draws_the_positions_the_kinematics_computes(page, server):
    open_viewer(page, server)
    mech = lw.compile(lw.load(NAME))
    before = {j: drawn(page, j) for j in JOINTS}
    for index in (0, 97, 250):
        angle = turn_to(page, index)
        kin = lw.kinematics(mech, [angle])
        api = page.request.post(server + "api/pose", data={"angle_deg": math.degrees(angle)}).json()
        for j in JOINTS:
            expected = kin.position(j)[0]
            assert np.abs(drawn(page, j) - expected).max() < 2e-6, (index, j)  # the drawing's 0.001 mm
            assert np.abs(np.array(api["points"][mech.point_names[mech.point_index(j)]]) - expected).max() < 1e-12
    assert np.abs(drawn(page, "E") - before["E"]).max() > 0.01  # the knife moved
    assert page.errors == []
    shot(page, "viewer-turned")


def test_the_plans_follow_the_crank(page, server):
    open_viewer(page, server)
    mech = lw.compile(lw.load(NAME))
    captions = set()
    for index in (30, 200):
        angle = turn_to(page, index)
        kin = lw.kinematics(mech, [angle])
        for label in ("a", "b", "e", "f"):
            v, scale = plan_point(page, "velocity", label)
            assert np.abs(v - kin.velocity(label.upper())[0]).max() < 2e-4 * scale, (index, label)
            a, scale = plan_point(page, "acceleration", label)
            assert np.abs(a - kin.acceleration(label.upper())[0]).max() < 2e-4 * scale, (index, label)
        caption = page.locator("#velocity-caption").text_content()
        captions.add(caption)
        # the caption's scale is per mm of the plan at full size (the viewBox's units), not of the screen
        mu = page.get_attribute("#velocity-plan", "data-scale")
        assert f"μv = {mu} (m/s)/mm of the plan drawn full size (shown scaled to fit);" in caption
        cursors = page.eval_on_selector_all("#charts line.cursor", "els => els.map(e => e.getAttribute('data-index'))")
        assert cursors and set(cursors) == {str(index)}
    assert len(captions) == 2  # the values in the caption changed with the crank
    shot(page, "viewer-plans")


def test_an_edit_that_does_not_assemble_shows_the_error_and_the_page_recovers(page, server):
    open_viewer(page, server)
    angle = turn_to(page, 60)
    e_before = drawn(page, "E")
    page.fill('input[data-param="links.rod.length"]', "10")  # mm: the rod cannot reach the rocker
    page.click("#apply")
    page.wait_for_selector("#error", state="visible")
    message = page.locator("#error-text").text_content()
    assert "group II(2,3) RRR (links rod, rocker) cannot be assembled" in message
    assert np.abs(drawn(page, "E") - e_before).max() < 1e-9  # the last good mechanism stays drawn
    shot(page, "viewer-edit-error")

    page.fill('input[data-param="links.rod.length"]', "400")
    page.fill('input[data-param="links.crank.length"]', "120")
    page.click("#apply")
    page.wait_for_selector("#error", state="hidden")
    expect(page.locator("#edit-status")).to_contain_text("changed")
    text = example_text(NAME)
    assert text.count("    length: 0.10\n    mass: 40\n") == 1
    edited = lw.compile(lw.loads(text.replace("    length: 0.10\n    mass: 40\n", "    length: 0.12\n    mass: 40\n")))
    kin = lw.kinematics(edited, [angle])
    assert math.radians(float(page.get_attribute("#scheme", "data-angle-deg"))) == pytest.approx(angle)
    for j in JOINTS:
        assert np.abs(drawn(page, j) - kin.position(j)[0]).max() < 2e-6, j
    assert np.hypot(*(drawn(page, "A") - np.array([0.5, 0.4]))) == pytest.approx(0.12, abs=2e-6)
    shot(page, "viewer-edited")

    page.click("#reset")
    base = lw.kinematics(lw.compile(lw.load(NAME)), [angle])
    expect(page.locator("#params .changed")).to_have_count(0)
    assert np.abs(drawn(page, "A") - base.position("A")[0]).max() < 2e-6
    # the browser itself logs the refused edit's response; nothing else went wrong
    assert [e for e in page.errors if "status of 422" not in e] == []
    assert len(page.errors) == 1


def test_an_edit_that_assembles_over_part_of_the_turn_shows_where_it_does_not(page, server):
    open_viewer(page, server)
    page.fill('input[data-param="links.crank.length"]', "300")  # A out of reach of rod + rocker near 40 deg
    page.click("#apply")
    expect(page.locator("#edit-status")).to_contain_text("changed")
    turn_to(page, sample_of(40))
    expect(page.locator("#pose-note")).to_contain_text("does not assemble")
    assert page.locator('#scheme line.bar[data-link="rod"]').get_attribute("visibility") == "hidden"
    assert page.locator("#structure .warn").first.text_content().startswith("no-assembly")
    turn_to(page, sample_of(200))
    expect(page.locator("#pose-note")).to_be_hidden()
    assert page.locator('#scheme line.bar[data-link="rod"]').get_attribute("visibility") == "visible"
    assert page.errors == []
    shot(page, "viewer-partial")


def test_play_turns_the_crank_and_pause_stops_it(page, server):
    open_viewer(page, server)
    turn_to(page, 0)
    page.select_option("#speed", "2")
    page.click("#play")
    deadline = time.monotonic() + 10
    while int(page.get_attribute("#scheme", "data-index")) <= 5:  # 2x real time: 360 samples in a second
        assert time.monotonic() < deadline, "the crank did not turn"
        page.wait_for_timeout(50)
    page.click("#play")
    stopped = page.get_attribute("#scheme", "data-index")
    page.wait_for_timeout(200)
    assert page.get_attribute("#scheme", "data-index") == stopped
    assert page.locator("#play").text_content() == "Play"


def test_the_exported_page_works_from_a_file_url_with_no_network(page, tmp_path):
    out = export_page(NAME, tmp_path / "shears.html", steps=180)
    requests: list[str] = []
    page.on("request", lambda r: requests.append(r.url))
    open_viewer(page, out.as_uri())
    mech = lw.compile(lw.load(NAME))
    angle = turn_to(page, 123)
    kin = lw.kinematics(mech, [angle])
    for j in JOINTS:
        assert np.abs(drawn(page, j) - kin.position(j)[0]).max() < 2e-6, j
    v, scale = plan_point(page, "velocity", "e")
    assert np.abs(v - kin.velocity("E")[0]).max() < 2e-4 * scale
    assert page.locator("#apply").is_disabled()
    assert "exported" in page.locator("#edit-note").text_content()
    assert all(u.startswith(("file:", "data:")) for u in requests), requests
    assert page.errors == []
    shot(page, "viewer-exported")


def test_a_frame_pivot_named_second_gets_its_support(page, tmp_path):
    """The four-bar with ``O4: [rocker, frame]``: two supports, their apexes at O2 (0, 0) and O4 (300 mm, 0)."""
    text = example_text("four-bar")
    text = text.replace("O4: {type: revolute, links: [frame, rocker]}", "O4: {type: revolute, links: [rocker, frame]}")
    out = export_page(lw.loads(text, file="four-bar.yaml"), tmp_path / "four-bar.html", steps=36)
    page.goto(out.as_uri())
    page.wait_for_selector('#scheme circle.joint[data-joint="O4"]')
    apexes = page.eval_on_selector_all(
        "#ground polygon.support", "els => els.map(e => [e.getAttribute('data-joint'), e.getAttribute('points')])"
    )
    found = {joint: [float(v) for v in points.split(" ")[0].split(",")] for joint, points in apexes}
    assert len(apexes) == 2 and found == {"O2": [0.0, 0.0], "O4": [300.0, 0.0]}
    assert page.errors == []


def chart_geometry(page, key: str) -> dict:
    """A chart's plot as drawn: its axes' ends (viewBox units), the value range, the cursor, the curve's vertices
    and the content box of the svg on the screen (the viewBox stretched onto it: preserveAspectRatio none)."""
    return page.eval_on_selector(
        f'#charts svg.chart[data-series="{key}"]',
        """g => {
            const lines = Array.from(g.querySelectorAll('line.axis')).map(l => ['x1', 'y1', 'x2', 'y2'].map(
                a => Number(l.getAttribute(a))));
            const cursor = g.querySelector('line.cursor');
            const box = g.getBoundingClientRect(), css = getComputedStyle(g);
            const px = (name) => parseFloat(css.getPropertyValue(name));
            const left = box.left + px('border-left-width') + px('padding-left');
            const width = box.width - px('border-left-width') - px('padding-left') - px('padding-right')
                - px('border-right-width');
            const top = box.top + px('border-top-width') + px('padding-top');
            const height = box.height - px('border-top-width') - px('padding-top') - px('padding-bottom')
                - px('border-bottom-width');
            return {
                lines, view: g.getAttribute('viewBox').split(' ').map(Number),
                lo: Number(g.getAttribute('data-lo')), hi: Number(g.getAttribute('data-hi')),
                cursor: Number(cursor.getAttribute('x1')), d: g.querySelector('path.curve').getAttribute('d'),
                ticks: Array.from(g.querySelectorAll('text[text-anchor="end"]')).map(t => [Number(t.getAttribute('y')),
                    t.textContent]),
                content: [left, top, width, height],
            };
        }""",
    )


def plot_area(geo: dict) -> tuple[float, float, float, float]:
    """(left, right, top, bottom) of the plot from its two axes: the x axis is horizontal, the y axis vertical."""
    horizontal = max((ln for ln in geo["lines"] if ln[1] == ln[3]), key=lambda ln: ln[2] - ln[0])
    vertical = max((ln for ln in geo["lines"] if ln[0] == ln[2]), key=lambda ln: ln[3] - ln[1])
    return horizontal[0], horizontal[2], vertical[1], vertical[3]


def test_a_chart_draws_the_torque_the_forces_compute_and_a_click_turns_the_crank(page, server):
    """The cursor's x and the curve's vertex under it, turned back into a crank angle and a torque through the
    chart's axes, are the angle shown and the driving torque of lw.forces at it; a click at the x of 90 deg
    turned moves the crank there, also on a chart resized and padded."""
    open_viewer(page, server)
    mech = lw.compile(lw.load(NAME))
    first = zero_angle(mech)  # the chart's x is the crank angle turned from position 0, as in the report
    for index in (97, 250):
        angle = turn_to(page, index)
        geo = chart_geometry(page, "torque")
        left, right, top, bottom = plot_area(geo)
        turned = (geo["cursor"] - left) / (right - left) * 360
        assert turned == pytest.approx(math.degrees(angle - first) % 360, abs=0.01 * 360 / (right - left))
        vertices = [tuple(map(float, v.split(","))) for v in geo["d"][1:].replace("M", "L").split("L")]
        y = next(vy for vx, vy in vertices if abs(vx - geo["cursor"]) < 1e-6)
        value = geo["hi"] - (y - top) / (bottom - top) * (geo["hi"] - geo["lo"])
        torque = lw.forces(mech, [angle]).driving_torque[0]
        assert abs(value - torque) < 0.006 / (bottom - top) * (geo["hi"] - geo["lo"]) + 1e-6 * abs(torque)
        # the tick labels sit where the axis puts their values (labels of 3 significant digits)
        for ty, text in geo["ticks"]:
            v = float(text)
            at = top + (bottom - top) * (geo["hi"] - v) / (geo["hi"] - geo["lo"])
            assert abs(at + 4 - ty) < 0.01 + 0.005 * abs(v) / (geo["hi"] - geo["lo"]) * (bottom - top), text

    def click_at(turn: float) -> None:
        page.locator('#charts svg.chart[data-series="torque"]').scroll_into_view_if_needed()
        geo = chart_geometry(page, "torque")
        left, right, top, bottom = plot_area(geo)
        x_view = left + (right - left) * turn / 360
        cx0, cy0, cw, ch = geo["content"]
        page.mouse.click(cx0 + x_view * cw / geo["view"][2], cy0 + (top + bottom) / 2 * ch / geo["view"][3])

    click_at(90.0)
    expect(page.locator("#scheme")).to_have_attribute("data-index", "90")
    page.eval_on_selector(
        '#charts svg.chart[data-series="torque"]',
        "g => { g.style.width = '420px'; g.style.padding = '6px 30px 6px 90px'; g.style.border = '7px solid #ccc'; }",
    )
    click_at(300.0)
    expect(page.locator("#scheme")).to_have_attribute("data-index", "300")
    assert page.errors == []
    shot(page, "viewer-chart-click")


# ---------------------------------------------------------------------------- dragging, undo, saving, forces


CTM = "s => { const m = s.getScreenCTM(); return [m.a, m.b, m.c, m.d, m.e, m.f]; }"


def screen_to_model(page, x: float, y: float) -> np.ndarray:
    """A point of the screen (CSS px) in the mechanism's axes (m): through the scheme's current CTM."""
    a, b, c, d, e, f = page.eval_on_selector("#scheme", CTM)
    assert b == 0 and c == 0
    return np.array([(x - e) / a / 1000, -(y - f) / d / 1000])


def model_to_screen(page, p) -> tuple[float, float]:
    """A point of the mechanism (m) on the screen (CSS px)."""
    a, _, _, d, e, f = page.eval_on_selector("#scheme", CTM)
    return e + a * 1000 * p[0], f - d * 1000 * p[1]


def handle_at(page, name: str) -> tuple[float, float]:
    box = page.locator(f'[data-handle="{name}"]').bounding_box()
    assert box is not None, name
    return box["x"] + box["width"] / 2, box["y"] + box["height"] / 2


def drag(page, start, end, steps: int = 12) -> None:
    page.mouse.move(*start)
    page.mouse.down()
    page.mouse.move(*end, steps=steps)
    page.mouse.up()


def settled(page) -> None:
    """Wait until the page shows the whole cycle of the last edit made (its labels placed again)."""
    expect(page.locator("#scheme")).to_have_attribute("data-labels", "placed", timeout=60_000)


def edited(replacements) -> lw.Mechanism:
    """The double-cut shears' file edited by hand."""
    text = example_text(NAME)
    for old, new in replacements:
        assert text.count(old) == 1, old
        text = text.replace(old, new)
    return lw.compile(lw.loads(text, file=f"{NAME}.yaml"))


def assert_drawn(page, mech, angle, tol=1e-6) -> None:
    kin = lw.kinematics(mech, [angle])
    for j in JOINTS:
        assert np.abs(drawn(page, j) - kin.position(j)[0]).max() < tol, j


def drag_crank_to(page, length_mm: float, angle: float, L0: float = 0.1) -> float:
    """Drag the crank's length handle along the crank (at ``angle``) by ``length_mm - L0``; the value the page
    must take: the pointer's travel along the crank, to the millimetre."""
    x0, y0 = handle_at(page, "links.crank.length")
    u = np.array([math.cos(angle), math.sin(angle)])  # the crank's direction, O1 to A
    p0 = screen_to_model(page, x0, y0)
    x1, y1 = model_to_screen(page, p0 + (length_mm / 1000 - L0) * u)
    drag(page, (x0, y0), (x1, y1))
    travel = (screen_to_model(page, x1, y1) - p0) @ u
    return round((L0 + travel) * 1000) / 1000


def test_dragging_the_crank_length_puts_the_joints_where_the_edited_file_does_and_undo_returns(page, server):
    """The handle on the crank dragged 12 mm outwards: the crank becomes 112 mm (the panel says so), every joint
    is drawn where lw.kinematics puts it in the file edited by hand to 112 mm (1e-6 m), also once the whole cycle
    is placed again; undo returns to the file's values and positions, redo to the edit."""
    open_viewer(page, server)
    angle = turn_to(page, 60)
    length = drag_crank_to(page, 112.0, angle)
    assert length == pytest.approx(0.112)
    expect(page.locator('input[data-param="links.crank.length"]')).to_have_value("112")
    by_hand = edited([("    length: 0.10\n    mass: 40\n", "    length: 0.112\n    mass: 40\n")])
    assert_drawn(page, by_hand, angle)
    settled(page)
    assert_drawn(page, by_hand, angle)
    assert np.hypot(*(drawn(page, "A") - [0.5, 0.4])) == pytest.approx(0.112, abs=1e-6)
    shot(page, "viewer-dragged")

    page.click("#undo")
    expect(page.locator('input[data-param="links.crank.length"]')).to_have_value("100")
    assert_drawn(page, lw.compile(lw.load(NAME)), angle)
    expect(page.locator("#params .changed")).to_have_count(0)
    page.keyboard.press("Control+Shift+Z")
    expect(page.locator('input[data-param="links.crank.length"]')).to_have_value("112")
    assert_drawn(page, by_hand, angle)
    assert page.errors == []


def test_the_saved_file_solves_to_what_the_page_shows(page, server, tmp_path):
    """After a drag, Save gives the file with its comments and the new value, and it solves to the joints drawn."""
    open_viewer(page, server)
    angle = turn_to(page, 200)
    length = drag_crank_to(page, 95.0, angle)
    expect(page.locator('input[data-param="links.crank.length"]')).to_have_value(f"{1000 * length:g}")
    with page.expect_download() as info:
        page.click("#save")
    download = info.value
    assert download.suggested_filename == f"{NAME}-edited.yaml"
    path = tmp_path / download.suggested_filename
    download.save_as(path)
    text = path.read_text(encoding="utf-8")
    assert "# crank pivot" in text and "# rocker pivot" in text and f"length: {length:g}" in text
    assert_drawn(page, lw.compile(lw.load(str(path))), angle)
    assert page.errors == []


def test_a_drag_into_no_assembly_shows_where_and_recovers(page, server):
    """Dragged to a crank of 300 mm, the rod and the rocker cannot reach A over part of the turn: the message says
    where, the arcs of those crank angles are drawn, the last mechanism that assembled stays drawn; dragged back
    to 110 mm, the message goes and the joints are those of the file edited to 110 mm."""
    open_viewer(page, server)
    angle = turn_to(page, 100)
    x0, y0 = handle_at(page, "links.crank.length")
    u = np.array([math.cos(angle), math.sin(angle)])
    p0 = screen_to_model(page, x0, y0)
    good = model_to_screen(page, p0 + 0.005 * u)
    far = model_to_screen(page, p0 + 0.2 * u)
    back = model_to_screen(page, p0 + 0.010 * u)
    page.mouse.move(x0, y0)
    page.mouse.down()
    page.mouse.move(*good, steps=4)
    expect(page.locator('input[data-param="links.crank.length"]')).to_have_value("105")
    e_good = drawn(page, "E")
    page.mouse.move(*far)  # in one move: no value between that assembles
    page.wait_for_selector("#error", state="visible")
    message = page.locator("#error-text").text_content()
    assert "does not assemble over the whole turn" in message and "group II(2,3) RRR" in message
    assert page.locator("#trouble path.trouble").count() >= 1
    assert page.locator('[data-handle="links.crank.length"].bad').count() == 1
    assert np.abs(drawn(page, "E") - e_good).max() < 1e-9  # the last good mechanism stays
    shot(page, "viewer-drag-no-assembly")
    page.mouse.move(*back, steps=6)
    page.wait_for_selector("#error", state="hidden")
    page.mouse.up()
    travel = (screen_to_model(page, *back) - p0) @ u
    length = round((0.1 + travel) * 1000) / 1000
    assert length == pytest.approx(0.110)
    expect(page.locator('input[data-param="links.crank.length"]')).to_have_value("110")
    assert page.locator("#trouble path").count() == 0
    assert_drawn(page, edited([("    length: 0.10\n    mass: 40\n", "    length: 0.110\n    mass: 40\n")]), angle)
    assert [e for e in page.errors if "status of 422" not in e] == []


def test_dragging_a_frame_pivot_and_a_guide_gives_the_edited_files_mechanism(page, server):
    """The crank's pivot O1 dragged by (-15, +8) mm, then the upper knife's guide turned about O3 by the angle the
    pointer sweeps (to 0.1 degree): the joints are those of the file with O1 at (485, 408) mm and the guide's axis
    edited so."""
    open_viewer(page, server)
    angle = turn_to(page, 30)
    x0, y0 = handle_at(page, "frame.points.O1")
    p0 = screen_to_model(page, x0, y0)
    x1, y1 = model_to_screen(page, p0 + np.array([-0.015, 0.008]))
    drag(page, (x0, y0), (x1, y1))
    moved = np.round((np.array([0.5, 0.4]) + screen_to_model(page, x1, y1) - p0) * 1000) / 1000
    expect(page.locator('input[data-param="frame.points.O1.x"]')).to_have_value(f"{1000 * moved[0]:g}")
    o1 = ("O1: [0.50, 0.40]", f"O1: [{moved[0]:g}, {moved[1]:g}]")
    assert_drawn(page, edited([o1]), angle)

    x0, y0 = handle_at(page, "joints.guide_E.axis")
    s0 = screen_to_model(page, x0, y0)  # the guide turns about O3, at the origin
    turn = math.radians(4.0)
    s1 = np.array([[math.cos(turn), -math.sin(turn)], [math.sin(turn), math.cos(turn)]]) @ s0
    x1, y1 = model_to_screen(page, s1)
    drag(page, (x0, y0), (x1, y1))
    p1 = screen_to_model(page, x1, y1)
    swept = math.degrees(math.atan2(p1[1], p1[0]) - math.atan2(s0[1], s0[0]))
    axis = round((90 + swept) * 10) / 10
    expect(page.locator('input[data-param="joints.guide_E.axis"]')).to_have_value(f"{axis:g}")
    guide = (
        "guide_E: {type: prismatic, links: [frame, knife_upper], point: E, through: O3, axis: 90 deg}",
        f"guide_E: {{type: prismatic, links: [frame, knife_upper], point: E, through: O3, axis: {axis:g} deg}}",
    )
    assert_drawn(page, edited([o1, guide]), angle)
    settled(page)
    shot(page, "viewer-dragged-frame-and-guide")
    assert page.errors == []


def test_the_force_arrows_are_the_reactions_of_lw_forces_times_the_scale(page, server):
    """With the forces shown, each joint's arrow, turned back through the scheme's transform and its scale, is the
    reaction lw.forces gives on its link at the angle shown; the knives' arrows the cutting force; the torque arc
    the driving torque.  After a drag, the arrows are those of the file edited so."""
    open_viewer(page, server)
    page.check("#show-forces")
    mech = lw.compile(lw.load(NAME))
    from linkwork.web.payload import cycle_payload

    mech_size = cycle_payload(mech, steps=36, placed=1)["scene"]["size"]  # the scheme's size does not move

    def check(mech, index):
        angle = turn_to(page, index)
        forces = lw.forces(mech, [angle])
        scale = float(page.get_attribute("#forces", "data-scale"))  # m of the drawing per N
        size = mech_size  # the scheme's size, m: no arrow is longer than 0.2 of it
        for joint, on in (
            ("O1", "crank"),
            ("A", "rod"),
            ("B", "rocker"),
            ("O3", "rocker"),
            ("E", "knife_upper"),
            ("guide_E", "knife_upper"),
            ("F", "knife_lower"),
        ):
            line = page.locator(f'#forces line.force[data-name="{joint}"]')
            assert line.get_attribute("data-on") == on
            x1, y1, x2, y2 = (float(line.get_attribute(a)) for a in ("x1", "y1", "x2", "y2"))
            arrow = np.array([x2 - x1, y1 - y2]) / 1000  # m
            expected = forces.reaction(joint, on=on)[0]
            if line.get_attribute("data-beyond") == "true":  # longer than the panel allows: shortened
                length, force = np.hypot(*arrow), np.hypot(*expected)
                assert length < force * scale and length <= 0.2 * size * 1.02  # size: of a coarser turn
                cross = arrow[0] * expected[1] - arrow[1] * expected[0]
                assert arrow @ expected > 0 and abs(cross) < 1e-6 * length * force  # its direction kept
                continue
            assert np.abs(arrow / scale - expected).max() < 1e-7 / scale + 1e-6 * np.abs(expected).max(), joint
            at = drawn(page, {"guide_E": "E"}.get(joint, joint))  # a guide's force acts at its slider's point
            assert np.abs(np.array([x1, -y1]) / 1000 - at).max() < 1e-6
        cutting = evaluate(forces.kinematics).magnitude["cutting"][0, 0]  # the load lw.forces applies
        for k, sign in enumerate((1, -1)):  # up on the upper knife, down on the lower
            cut = page.locator('#forces line.force[data-kind="load"]').nth(k)
            if cutting == 0:
                assert cut.get_attribute("visibility") == "hidden"
                continue
            x1, y1, x2, y2 = (float(cut.get_attribute(a)) for a in ("x1", "y1", "x2", "y2"))
            assert abs(x2 - x1) < 1e-6 and sign * (y1 - y2) > 0
            if cut.get_attribute("data-beyond") == "true":  # the cut's force: drawn as long as the panel allows
                assert abs(y1 - y2) / 1000 == pytest.approx(0.2 * size, rel=0.02)
                assert abs(y1 - y2) / 1000 < cutting * scale
            else:
                assert (y1 - y2) / 1000 / scale == pytest.approx(sign * cutting, rel=1e-6)
        torque = float(page.get_attribute("#forces path.force.torque", "data-torque"))
        # the charts' series are written to six significant digits of their largest value (about 30 kN m)
        assert torque == pytest.approx(forces.driving_torque[0], rel=1e-6, abs=0.01)
        return cutting

    assert check(mech, 60) == 0
    turn = lw.forces(mech, cycle(mech, 360, start=zero_angle(mech)))  # the page's samples, from position 0
    cutting = int(np.argmax(np.abs(turn.driving_torque)))  # where the knives cut hardest
    assert check(mech, cutting) > 100e3
    shot(page, "viewer-forces")
    angle = turn_to(page, 100)
    drag_crank_to(page, 108.0, angle)
    expect(page.locator('input[data-param="links.crank.length"]')).to_have_value("108")
    check(edited([("    length: 0.10\n    mass: 40\n", "    length: 0.108\n    mass: 40\n")]), cutting)
    assert page.errors == []


def test_a_long_drag_shows_many_answers_and_ends_on_its_last_value(page, server):
    """Latest wins: forty pointer moves, one edit in flight at a time; the page shows answers as they come and
    ends on the value of the last move."""
    open_viewer(page, server)
    angle = turn_to(page, 10)
    before = int(page.get_attribute("#scheme", "data-updates"))
    x0, y0 = handle_at(page, "links.crank.length")
    u = np.array([math.cos(angle), math.sin(angle)])
    p0 = screen_to_model(page, x0, y0)
    page.mouse.move(x0, y0)
    page.mouse.down()
    for k in range(1, 41):
        page.mouse.move(*model_to_screen(page, p0 + 0.0005 * k * u))
    page.mouse.up()
    expect(page.locator('input[data-param="links.crank.length"]')).to_have_value("120")
    assert int(page.get_attribute("#scheme", "data-updates")) - before >= 2
    assert_drawn(page, edited([("    length: 0.10\n    mass: 40\n", "    length: 0.120\n    mass: 40\n")]), angle)
    assert page.errors == []


def test_the_force_labels_cover_no_other_label_and_the_arrows_stay_in_the_panel(page, server):
    """Where the knives cut hardest (the largest forces of the turn), each force's label covers no other force's
    label and no joint's name, and no arrow reaches farther than a fifth of the scheme's size from its point."""
    open_viewer(page, server)
    page.check("#show-forces")
    mech = lw.compile(lw.load(NAME))
    turn = lw.forces(mech, cycle(mech, 360, start=zero_angle(mech)))
    turn_to(page, int(np.argmax(np.abs(turn.driving_torque))))
    forces = page.locator("#forces text.force-label:not(.torque)")
    boxes = [
        forces.nth(k).bounding_box()
        for k in range(forces.count())
        if forces.nth(k).get_attribute("visibility") == "visible"
    ]
    names = page.locator("#labels text.label")
    joints = [names.nth(k).bounding_box() for k in range(names.count())]
    assert len(boxes) >= 8

    def overlap(a, b):
        return (
            a["x"] < b["x"] + b["width"]
            and b["x"] < a["x"] + a["width"]
            and a["y"] < b["y"] + b["height"]
            and b["y"] < a["y"] + a["height"]
        )

    pairs = [(i, j) for i in range(len(boxes)) for j in range(i) if overlap(boxes[i], boxes[j])]
    assert pairs == []
    assert [i for i, b in enumerate(boxes) for j in joints if j and overlap(b, j)] == []
    from linkwork.web.payload import cycle_payload

    size = cycle_payload(mech, steps=36, placed=1)["scene"]["size"]  # the page's (of 360 samples) within 2 %
    lines = page.locator("#forces line.force")
    for k in range(lines.count()):
        line = lines.nth(k)
        if line.get_attribute("visibility") == "visible":
            x1, y1, x2, y2 = (float(line.get_attribute(a)) for a in ("x1", "y1", "x2", "y2"))
            assert math.hypot(x2 - x1, y2 - y1) / 1000 <= 0.2 * size * 1.02
    assert page.errors == []


def test_a_spring_and_a_damper_are_drawn_between_their_points(page, tmp_path):
    """Andrews' squeezer with a damper added: the spring's zigzag and the damper's strokes (polylines of class
    ``spring``, ``damper``) end on their points as the kinematics puts them at the angle shown (the drawing's
    0.001 mm), at two angles of the crank."""
    text = (Path(__file__).resolve().parents[1] / "machine" / "andrews-squeezer.yaml").read_text()
    text = text.replace(
        "free_length: 0.07785}", "free_length: 0.07785}\n  push: {type: damper, between: [b7.H, B], damping: 0.5 N*s/m}"
    )
    spec = lw.loads(text, file="andrews-squeezer.yaml")
    mech = lw.compile(spec)
    page.goto(export_page(spec, tmp_path / "sprung.html", steps=36).as_uri())
    page.wait_for_selector('#scheme polyline.spring[data-element="spring"]')
    c, b = np.array([0.014, 0.072]), np.array([-0.03635, 0.03273])  # the frame's C and B in the file
    for index in (3, 20):
        angle = turn_to(page, index)
        kin = lw.kinematics(mech, [angle])

        def ends(selector: str) -> list[np.ndarray]:
            found = page.eval_on_selector_all(selector, "els => els.map(e => e.getAttribute('points'))")
            lines = [np.array([[float(v) for v in xy.split(",")] for xy in p.split(" ")]) for p in found]
            return [line * [0.001, -0.001] for line in lines]

        spring, damper = ends("#scheme polyline.spring"), ends("#scheme polyline.damper")
        assert len(spring) == 1 and len(spring[0]) == 12 and len(damper) == 4
        np.testing.assert_allclose(spring[0][[0, -1]], [kin.position("b3.D")[0], c], rtol=0, atol=2e-6)
        np.testing.assert_allclose([damper[0][0], damper[-1][-1]], [kin.position("b7.H")[0], b], rtol=0, atol=2e-6)
    assert page.errors == []


def force_drawing(page) -> list[dict]:
    """The arrows of the force plan (or lever) shown: name, kind, whether read off the plan, its ends as drawn
    (x, -y: mm of the sheet, y up) and the force its length gives at the drawing's ``data-scale`` (N per mm)."""
    scale = float(page.get_attribute("#force-plan", "data-scale"))
    found = page.eval_on_selector_all(
        "#force-plan line.fvec",
        "els => els.map(e => [e.getAttribute('data-name'), e.getAttribute('data-kind'),"
        " e.classList.contains('resultant'), ['x1', 'y1', 'x2', 'y2'].map(k => Number(e.getAttribute(k)))])",
    )
    return [
        {
            "name": name,
            "kind": kind,
            "resultant": resultant,
            "start": np.array([x1, -y1]),
            "end": np.array([x2, -y2]),
            "force": math.hypot(x2 - x1, y2 - y1) * scale,
        }
        for name, kind, resultant, (x1, y1, x2, y2) in found
    ]


def show_force_drawing(page, key: str, index: int) -> None:
    page.select_option("#force-plan-choice", key)
    expect(page.locator("#force-plan")).to_have_attribute("data-group", key)
    expect(page.locator("#force-plan")).to_have_attribute("data-index", str(index))


def test_the_force_plans_and_the_lever_follow_the_crank_dragged(page, server):
    """The first group's force plan (the lower knife's dyad II(6,7)): the names of the forces lw's force plans give
    it at the angle shown, subscripts in tspans, one arrow each (and the reactions read off it), closing head to
    tail as read back from the SVG; the lever's balancing force is the driving torque of lw.forces over the crank's
    length; dragging the crank's slider draws another position."""
    from linkwork.kinetostatics.force_polygons import force_plans

    open_viewer(page, server)
    mech = lw.compile(lw.load(NAME))
    expect(page.locator("#force-plan-figure")).to_be_visible()
    seen = {}
    for index in (90, 250):
        angle = turn_to(page, index)
        show_force_drawing(page, "group:0", index)
        group = force_plans(lw.forces(mech, [angle])).groups[0]
        assert group.label == "II(6,7) RRP"
        sizes = {f.name(): float(np.hypot(*f.vector[0, 0])) for f in group.polygon}
        names = {name for name, size in sizes.items() if size > 1e-6 * max(sizes.values())}
        arrows = force_drawing(page)
        polygon = [a for a in arrows if not a["resultant"]]
        assert {a["name"] for a in polygon} == names and len(polygon) == len(names)
        assert any(a["resultant"] for a in arrows)  # R36 = R36n + R36τ and the inner joint's R76
        for a in polygon:  # each to the plan's scale: the force lw's plan has
            assert a["force"] == pytest.approx(sizes[a["name"]], rel=1e-9)
        gap = np.sum([a["end"] - a["start"] for a in polygon], axis=0)
        assert np.hypot(*gap) < 1e-9 * max(np.hypot(*(a["end"] - a["start"])) for a in polygon)
        labels = page.eval_on_selector_all("#force-plan text.fname", "els => els.map(e => e.getAttribute('data-name'))")
        drawn = page.eval_on_selector_all(
            "#force-plan line.fvec",
            "els => els.map(e => [e.getAttribute('data-name'), Math.hypot(e.x2.baseVal.value - e.x1.baseVal.value, "
            "e.y2.baseVal.value - e.y1.baseVal.value)])",
        )
        length = {name: size for name, size in drawn}
        assert names <= set(length)  # every force drawn; named at it, or (shorter than its name) listed, not placed
        unnamed = names - set(labels)
        assert all(length[n] < min(length[m] for m in names & set(labels)) for n in unnamed)
        assert page.locator('#force-plan text.fname[data-name="R07"] tspan.sub').text_content() == "07"
        seen[index] = [(a["name"], tuple(a["end"])) for a in arrows]
        # the lever at the same angle
        show_force_drawing(page, "lever", index)
        torque = float(lw.forces(mech, [angle]).driving_torque[0])
        kin = lw.kinematics(mech, [angle])
        crank = float(np.hypot(*(kin.position("A")[0] - kin.position("O1")[0])))
        (fb,) = [a for a in force_drawing(page) if a["kind"] == "balancing"]
        assert fb["force"] == pytest.approx(abs(torque) / crank, rel=1e-9)
        named = page.eval_on_selector_all("#force-plan text.fname", "els => els.map(e => e.getAttribute('data-name'))")
        assert "Fb" in named and ({"F5", "F7"} <= set(named)) == (index == 90)  # the knives cut at 90
        assert "balancing moment Mb" in page.locator("#force-plan-caption").text_content()
    assert seen[90] != seen[250]
    shot(page, "viewer-lever")
    # dragging the crank's slider with the mouse draws the plan of the position it stops at
    show_force_drawing(page, "group:0", 250)
    box = page.locator("#angle").bounding_box()
    page.mouse.move(box["x"] + 0.7 * box["width"], box["y"] + box["height"] / 2)
    page.mouse.down()
    page.mouse.move(box["x"] + 0.3 * box["width"], box["y"] + box["height"] / 2, steps=8)
    page.mouse.up()
    index = int(page.get_attribute("#scheme", "data-index"))
    assert index != 250
    expect(page.locator("#force-plan")).to_have_attribute("data-index", str(index))
    assert [(a["name"], tuple(a["end"])) for a in force_drawing(page)] != seen[250]
    assert page.errors == []
    shot(page, "viewer-force-plan")


def test_the_exported_page_shows_the_force_plan_nearest_the_crank(page, tmp_path):
    """An exported page carries the drawings of every tenth of the turn's samples here and shows the one nearest
    the crank, with no server."""
    out = export_page("four-bar", tmp_path / "four-bar.html", steps=72)
    page.goto(out.as_uri())
    page.wait_for_selector("#force-plan line.fvec")
    turn_to(page, 31)
    show_force_drawing(page, "group:0", 30)  # of the 36 samples carried, every second one
    assert "force plan of II(2,3) RRR at φ = 150.0°" in page.locator("#force-plan-caption").text_content()
    assert page.locator("#force-plan line.fvec").count() >= 4
    assert page.errors == []


def test_the_lever_of_a_dragged_crank_length_is_the_edited_files(page, server):
    """The crank dragged to 112 mm: the lever drawn is that of the file edited by hand to 112 mm, its balancing
    force the driving torque of lw.forces over 0.112 m at the angle shown."""
    open_viewer(page, server)
    index = 60
    angle = turn_to(page, index)
    show_force_drawing(page, "lever", index)
    before = [a["force"] for a in force_drawing(page) if a["kind"] == "balancing"]
    assert drag_crank_to(page, 112.0, angle) == pytest.approx(0.112)
    settled(page)
    by_hand = edited([("    length: 0.10\n    mass: 40\n", "    length: 0.112\n    mass: 40\n")])
    torque = float(lw.forces(by_hand, [angle]).driving_torque[0])
    expect(page.locator("#force-plan-caption")).to_contain_text(f"Mb = {float(f'{torque:.5g}'):g} N·m")
    (fb,) = [a for a in force_drawing(page) if a["kind"] == "balancing"]
    assert fb["force"] == pytest.approx(abs(torque) / 0.112, rel=1e-9)
    assert [fb["force"]] != before
    assert page.errors == []
