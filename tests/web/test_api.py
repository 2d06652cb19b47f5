"""The viewer's server: its cycle against independent computations, edits, exports and bad requests."""

from __future__ import annotations

import json
import math
import os
import re
import signal
import socket
import subprocess
import sys
import time

import numpy as np
import pytest
from typer.testing import CliRunner

pytest.importorskip("fastapi")
pytest.importorskip("httpx")

from fastapi.testclient import TestClient  # noqa: E402

import linkwork as lw  # noqa: E402
from linkwork.examples import text as example_text  # noqa: E402
from linkwork.motion.analysis import guide, working  # noqa: E402
from linkwork.motion.kinematic_analysis import direction  # noqa: E402
from linkwork.web import create_app, cycle_payload, export_page  # noqa: E402
from linkwork.web.edits import MAX_OVERRIDES  # noqa: E402
from linkwork.web.server import MAX_BODY, SHUTDOWN_WAIT_S  # noqa: E402

LOCAL = "http://127.0.0.1"


@pytest.fixture(scope="module")
def shears():
    return TestClient(create_app(lw.load("double-cut-shears")), base_url=LOCAL)


@pytest.fixture(scope="module")
def shears_cycle(shears):
    r = shears.get("/api/cycle")
    assert r.status_code == 200
    return r.json()


def _turn(mech, steps, file=None):
    """The viewer's crank angles: ``steps`` equal steps over a turn from position 0 of ``file`` (the file the
    viewer opened, whose edits ``mech`` may be; ``mech`` itself by default)."""
    from linkwork.motion.analysis import zero_angle
    from linkwork.motion.kinematic_analysis import cycle

    return cycle(mech, steps, start=zero_angle(mech if file is None else file))


def _positions(payload):
    """(A, P, 2) positions of the payload, NaN where null."""
    return np.array(
        [[[np.nan, np.nan] if xy is None or xy[0] is None else xy for xy in pose] for pose in payload["positions"]]
    )


def _plan(payload, kind):
    plan = payload["plans"][kind]
    values = np.array([[[np.nan, np.nan] if v is None or v[0] is None else v for v in row] for row in plan["values"]])
    return {lab: values[:, j] for j, lab in enumerate(plan["labels"])}


def _series(payload, key):
    s = next(s for s in payload["series"] if s["key"] == key)
    return np.array([np.nan if v is None else v for v in s["values"]])


# ---------------------------------------------------------------------------- the cycle


def test_the_cycle_is_the_mechanism_solved_angle_by_angle(shears, shears_cycle):
    """Every position of the precomputed cycle (one batch of 360) equals a solve of that angle alone, and the
    pose endpoint gives the same."""
    mech = lw.compile(lw.load("double-cut-shears"))
    pos = _positions(shears_cycle)
    names = [p["name"] for p in shears_cycle["points"]]
    assert names == list(mech.point_names)
    for i in (0, 45, 97, 180, 271, 359):
        angle = math.radians(shears_cycle["angles_deg"][i])
        kin = lw.kinematics(mech, [angle])
        np.testing.assert_allclose(pos[i], kin.points()[0], atol=1e-8)
        pose = shears.post("/api/pose", json={"angle_deg": shears_cycle["angles_deg"][i]}).json()
        np.testing.assert_allclose(pose["points"]["rod_DE.E"], kin.position("E")[0], atol=1e-12)
    # a whole turn from the assembly angle, in the direction of rotation (30 rpm ccw)
    assert shears_cycle["turn_deg"][0] == 0 and shears_cycle["turn_deg"][-1] == pytest.approx(359)
    assert shears_cycle["period_s"] == pytest.approx(2.0)


def test_plans_are_the_derivatives_of_the_positions(shears_cycle):
    """The velocity plan's point vectors are the central differences of the positions over the cycle, and the
    acceleration plan's those of the velocities (1 degree steps: agreement to 1e-3 of the largest)."""
    pos = _positions(shears_cycle)
    labels = {p["label"]: j for j, p in enumerate(shears_cycle["points"])}
    dt = math.radians(1.0) / abs(shears_cycle["speed"])
    vel, acc = _plan(shears_cycle, "velocity"), _plan(shears_cycle, "acceleration")
    for name in ("A", "B", "C", "D", "E", "F"):
        x = pos[:, labels[name]]
        v_fd = (np.roll(x, -1, 0) - np.roll(x, 1, 0)) / (2 * dt)
        v = vel[name.lower()]
        assert np.abs(v - v_fd).max() < 1e-3 * np.abs(v).max()
        a_fd = (np.roll(v, -1, 0) - np.roll(v, 1, 0)) / (2 * dt)
        a = acc[name.lower()]
        assert np.abs(a - a_fd).max() < 2e-3 * np.abs(a).max()
    assert np.abs(vel["p"]).max() == 0  # the pole
    # the construction of E: v_E = v_D + v_ED (normal to DE) closes on the absolute v_E
    plan = shears_cycle["plans"]["velocity"]
    edges = {(plan["labels"][v["from"]], plan["labels"][v["to"]]): v["kind"] for v in plan["vectors"]}
    assert edges[("d", "e")] == "rotation"
    de = pos[:, labels["E"]] - pos[:, labels["D"]]
    v_ed = vel["e"] - vel["d"]
    assert np.abs(np.sum(de * v_ed, axis=1)).max() < 1e-7 * 0.35 * np.abs(v_ed).max()  # |DE| = 0.35 m


def _d1(f, dt):
    """First derivative of a periodic sampled function, fourth-order central differences."""
    return (-np.roll(f, -2, 0) + 8 * np.roll(f, -1, 0) - 8 * np.roll(f, 1, 0) + np.roll(f, 2, 0)) / (12 * dt)


def _d2(f, dt):
    """Second derivative of a periodic sampled function, fourth-order central differences."""
    return (-np.roll(f, -2, 0) + 16 * np.roll(f, -1, 0) - 30 * f + 16 * np.roll(f, 1, 0) - np.roll(f, 2, 0)) / (
        12 * dt**2
    )


def _com_motion(kin):
    """Centres of mass (A, N, 2) and the kinetic and potential energy (A,) of a kinematics result."""
    mech = kin.mechanism
    q, v = kin.pose[0], kin.vel[0]
    c, s = np.cos(q[..., 2]), np.sin(q[..., 2])
    lx, ly = mech.link_com[:, 0], mech.link_com[:, 1]
    rx, ry = c * lx - s * ly, s * lx + c * ly
    com = np.stack([q[..., 0] + rx, q[..., 1] + ry], -1)
    vx, vy = v[..., 0] - v[..., 2] * ry, v[..., 1] + v[..., 2] * rx
    m, j = mech.link_mass, mech.link_inertia
    kinetic = 0.5 * np.sum(m * (vx**2 + vy**2) + j * v[..., 2] ** 2, axis=1)
    potential = mech.gravity * np.sum(m * com[..., 1], axis=1)
    return com, kinetic, potential


def _cutting_power(kin):
    """Power (W) of the double-cut shears' cutting load on its two knives, from the file's table worked out here:
    the billet spans y = -0.05..0.05 m, the relative penetration is (upper + lower) / 0.10, the force follows
    0 - 250 - 250 - 0 kN at 0, 0.15, 0.30, 0.45 while the knives close (none while they open), up on the upper
    knife's edge and down on the lower's."""
    yu, vu = kin.position("knife_upper.edge")[:, 1], kin.velocity("knife_upper.edge")[:, 1]
    yl, vl = kin.position("knife_lower.edge")[:, 1], kin.velocity("knife_lower.edge")[:, 1]
    eps = (np.maximum(0.05 - yu, 0) + np.maximum(yl + 0.05, 0)) / 0.10
    size = np.interp(eps, [0, 0.15, 0.30, 0.45], [0, 250e3, 250e3, 0], left=0, right=0)
    size = np.where(vl - vu > 0, size, 0.0)
    assert size.max() == 250e3  # the knives cut through the plateau of the table
    return size * vu - size * vl


@pytest.mark.parametrize("name", ["four-bar", "double-cut-shears", "percussion-rocker"])
def test_torque_and_foundation_charts_obey_the_energy_and_momentum_theorems(name):
    """Finite differences over the cycle (720 steps, fourth order): the driving torque chart times the (signed)
    crank speed plus the power of the loads is the rate of change of the kinetic and potential energy; the
    foundation force charts are the weights less the rate of change of the momentum, and the foundation moment
    chart the weights' moment about the origin less the rate of change of the angular momentum about it.  The
    four-bar has no loads, the shears their cutting load (equal and opposite on the knives: no net force on the
    machine), the percussion rocker's crank turns clockwise."""
    mech = lw.compile(lw.load(name))
    payload = cycle_payload(mech, steps=720)
    kin = lw.kinematics(mech, _turn(mech, 720))
    omega = kin.rates[0, 0]
    dt = 2 * math.pi / 720 / abs(omega)
    com, kinetic, potential = _com_motion(kin)
    loads = _cutting_power(kin) if name == "double-cut-shears" else 0.0
    power = _d1(kinetic + potential, dt)
    torque_power = _series(payload, "torque") * omega
    assert np.abs(torque_power + loads - power).max() < 1e-6 * np.abs(torque_power).max()

    m, g = mech.link_mass, mech.gravity
    q, v = kin.pose[0], kin.vel[0]
    c, s = np.cos(q[..., 2]), np.sin(q[..., 2])
    rx = c * mech.link_com[:, 0] - s * mech.link_com[:, 1]
    ry = s * mech.link_com[:, 0] + c * mech.link_com[:, 1]
    vx, vy = v[..., 0] - v[..., 2] * ry, v[..., 1] + v[..., 2] * rx
    momentum = np.sum(m * (com[..., 0] * vy - com[..., 1] * vx) + mech.link_inertia * v[..., 2], axis=1)
    expected = {
        "foundation:fx": -_d2(np.sum(m * com[..., 0], axis=1), dt),
        "foundation:fy": -g * m.sum() - _d2(np.sum(m * com[..., 1], axis=1), dt),
        "foundation:m": -g * np.sum(m * com[..., 0], axis=1) - _d1(momentum, dt),
    }
    for key, value in expected.items():
        assert np.abs(_series(payload, key) - value).max() < 1e-6 * np.abs(value).max(), key


def test_knife_chart_is_the_slider_crank_closed_form():
    """Seed 000's shears, OA = AB = l: the knife moves as y_B = 2 l sin(phi) along its guide through O, also
    through the change points at 0 and 180 deg."""
    payload = cycle_payload(lw.compile(lw.load("shears-slider-crank")), steps=360)
    phi = np.radians(payload["angles_deg"])
    s = _series(payload, "slider:guide:s")  # mm
    np.testing.assert_allclose(s, 1000 * 2 * 0.15 * np.sin(phi), atol=1e-6)
    v = _series(payload, "slider:guide:v")
    np.testing.assert_allclose(v, 2 * 0.15 * np.cos(phi) * 10.0, atol=1e-9)


# ---------------------------------------------------------------------------- edits


def test_an_edit_gives_what_the_edited_file_gives(shears):
    """Overrides of a length and a mass (SI) give the cycle of the file edited by hand."""
    r = shears.post("/api/solve", json={"overrides": {"links.crank.length": 0.12, "links.rod.mass": 90.0}})
    assert r.status_code == 200, r.text
    edited = r.json()
    text = example_text("double-cut-shears")
    crank, rod = "    length: 0.10\n    mass: 40\n", "    length: 0.40\n    mass: 60\n"
    assert text.count(crank) == text.count(rod) == 1
    text = text.replace(crank, "    length: 0.12\n    mass: 40\n").replace(rod, "    length: 0.40\n    mass: 90\n")
    by_hand = lw.compile(lw.loads(text, file="double-cut-shears.yaml"))
    kin = lw.kinematics(by_hand, _turn(by_hand, 360, SHEARS))  # numbered from the opened file's position 0
    np.testing.assert_allclose(_positions(edited), kin.points(), atol=1e-9)
    torque = lw.forces(kin).driving_torque  # the chart rounds to six significant digits
    np.testing.assert_allclose(_series(edited, "torque"), torque, rtol=1e-6, atol=1e-6 * np.abs(torque).max())
    pos = _positions(edited)
    labels = {p["name"]: j for j, p in enumerate(edited["points"])}
    crank = np.hypot(*(pos[:, labels["crank.A"]] - pos[:, labels["crank.O1"]]).T)
    np.testing.assert_allclose(crank, 0.12, atol=1e-8)
    values = {p["name"]: p["value"] for p in edited["parameters"]}
    assert values["links.crank.length"] == pytest.approx(0.12) and values["links.rod.mass"] == 90
    assert edited["overrides"] == {"links.crank.length": 0.12, "links.rod.mass": 90.0}


def test_edits_are_si_whatever_the_files_units():
    """The four-bar's file is in millimetres: an override of 0.11 (m) gives a crank of 110 mm."""
    client = TestClient(create_app("four-bar"), base_url=LOCAL)
    r = client.post("/api/solve", json={"overrides": {"links.crank.length": 0.11}, "steps": 36})
    assert r.status_code == 200, r.text
    pos = _positions(r.json())
    names = [p["name"] for p in r.json()["points"]]
    crank = pos[:, names.index("crank.A")] - pos[:, names.index("crank.O2")]
    np.testing.assert_allclose(np.hypot(*crank.T), 0.11, atol=1e-8)
    assert len(r.json()["angles_deg"]) == 36


@pytest.mark.parametrize(
    "overrides, fragment",
    [
        (
            {"links.rod.length": 0.01},
            "double-cut-shears.yaml: group II(2,3) RRR (links rod, rocker) cannot be assembled",
        ),
        ({"links.rod.length": -0.4}, "links.rod.length: expected a positive length"),
        ({"links.rod.lenght": 0.4}, 'no parameter "links.rod.lenght" (did you mean "links.rod.length"?)'),
        ({"links.rocker.mass": 0.0}, "links.rocker.mass: expected a positive mass"),
        ({"joints.guide_E.axis": 1e9}, "joints.guide_E.axis: expected a value from -100 to 100 rad"),
    ],
)
def test_an_edit_that_fails_answers_422_with_the_reason_and_the_server_goes_on(shears, overrides, fragment):
    r = shears.post("/api/solve", json={"overrides": overrides})
    assert r.status_code == 422
    assert fragment in r.json()["error"]
    assert shears.get("/api/cycle").status_code == 200
    ok = shears.post("/api/solve", json={"overrides": {"links.crank.length": 0.105}})
    assert ok.status_code == 200


def test_a_cycle_that_assembles_only_in_part_has_gaps_where_the_dyad_cannot_close(shears):
    """A crank of 0.3 m puts A farther from O3 than rod + rocker (0.4 + 0.5 m) can reach over part of the turn:
    exactly there the samples are invalid and null, and the events say so."""
    r = shears.post("/api/solve", json={"overrides": {"links.crank.length": 0.3}})
    assert r.status_code == 200
    d = r.json()
    phi = np.radians(d["angles_deg"])
    beyond = np.hypot(0.5 + 0.3 * np.cos(phi), 0.4 + 0.3 * np.sin(phi)) > 0.4 + 0.5
    assert 0 < beyond.sum() < len(phi)
    np.testing.assert_array_equal(~np.array(d["valid"]), beyond)
    i = int(np.flatnonzero(beyond)[0])
    assert d["positions"][i][:2] == [[0.5, 0.4], [0.0, 0.0]]  # frame.O1 and frame.O3 stay
    assert all(xy == [None, None] for xy in d["positions"][i][2:])
    # a pose solved on its own at that angle says the same, and echoes the angle as sent
    pose = shears.post(
        "/api/pose", json={"angle_deg": d["angles_deg"][i], "overrides": {"links.crank.length": 0.3}}
    ).json()
    assert pose["valid"] is False and pose["angle_deg"] == d["angles_deg"][i]
    assert [pose["points"][p["name"]] for p in d["points"]] == d["positions"][i]
    assert all(v == [None, None] for v in d["plans"]["velocity"]["values"][i][1:])
    assert np.isnan(_series(d, "torque")[beyond]).all() and np.isfinite(_series(d, "torque")[~beyond]).all()
    assert any("no assembly" in e["message"] for e in d["events"])


def test_a_spec_built_without_a_file_is_edited_in_si():
    spec = lw.load("four-bar").model_copy()
    spec._source = None  # as if built by hand: no file, no lines
    client = TestClient(create_app(spec), base_url=LOCAL)
    r = client.post("/api/solve", json={"overrides": {"links.crank.length": 0.11, "links.coupler.mass": 3.0}})
    assert r.status_code == 200, r.text
    pos = _positions(r.json())
    names = [p["name"] for p in r.json()["points"]]
    np.testing.assert_allclose(np.hypot(*(pos[:, names.index("crank.A")] - pos[:, names.index("crank.O2")]).T), 0.11)
    assert {p["name"]: p["value"] for p in r.json()["parameters"]}["links.coupler.mass"] == 3.0


def test_a_compiled_mechanism_is_edited_like_its_file():
    """A Mechanism carries the description it was compiled from: the viewer edits it like the file."""
    client = TestClient(create_app(lw.compile(lw.load("four-bar"))), base_url=LOCAL)
    r = client.post("/api/solve", json={"overrides": {"links.crank.length": 0.11}})
    assert r.status_code == 200 and r.json()["editable"] is True
    text = example_text("four-bar")
    edited = lw.compile(lw.loads(text.replace("length: 100\n", "length: 110\n", 1)))
    kin = lw.kinematics(edited, _turn(edited, 360, lw.compile(lw.load("four-bar"))))
    a = [p["name"] for p in r.json()["points"]].index("crank.A")
    np.testing.assert_allclose(_positions(r.json())[:, a], kin.position("crank.A"), atol=1e-8)


def test_a_mechanism_without_its_description_is_shown_but_not_edited():
    import dataclasses

    bare = dataclasses.replace(lw.compile(lw.load("four-bar")), description=None)
    client = TestClient(create_app(bare), base_url=LOCAL)
    cycle = client.get("/api/cycle").json()
    assert cycle["editable"] is False and cycle["parameters"] == []
    r = client.post("/api/solve", json={"overrides": {"links.crank.length": 0.11}})
    assert r.status_code == 422 and "cannot be edited" in r.json()["error"]
    assert client.post("/api/solve", json={}).status_code == 200


# ---------------------------------------------------------------------------- bad requests

JSON = "application/json"
BAD = [
    (b"{bad", JSON, 400, "not valid JSON"),
    (b"\xff\xfe{}", JSON, 400, "not valid JSON"),
    (b"[" * 30000, JSON, 400, "not valid JSON"),
    (b"[]", JSON, 422, "a JSON object"),
    (b'{"overrides": {}}', "text/plain", 415, "application/json"),
    (b'{"overrides": {}}', None, 415, "application/json"),
    (b" " * (MAX_BODY + 1) + b"{}", JSON, 413, "limited to"),
    (b'{"overrides": {"links.crank.length": "__import__(\'os\').system(\'true\')"}}', JSON, 422, "valid number"),
    (b'{"overrides": {"links.crank.length": "0.1"}}', JSON, 422, "valid number"),
    (b'{"overrides": {"links.crank.length": true}}', JSON, 422, "valid number"),
    (b'{"overrides": {"links.crank.length": NaN}}', JSON, 422, "finite number"),
    (b'{"overrides": {"links.crank.length": 1e999}}', JSON, 422, "finite number"),
    (b'{"overrides": [1, 2]}', JSON, 422, "overrides"),
    (b'{"overrides": {}, "code": "print(1)"}', JSON, 422, "code: Extra inputs are not permitted"),
    (b'{"steps": 5}', JSON, 422, "steps"),
    (b'{"steps": 100000000}', JSON, 422, "steps"),
    (b'{"steps": 1441}', JSON, 422, "steps: Input should be less than or equal to 1440"),
    (json.dumps({"overrides": {f"p{i}": 1.0 for i in range(MAX_OVERRIDES + 1)}}).encode(), JSON, 422, "at most"),
    (json.dumps({"overrides": {"x" * 1000: 1.0}}).encode(), JSON, 422, "at most 200 characters"),
]


@pytest.mark.parametrize("content, kind, status, fragment", BAD)
def test_a_bad_request_gets_a_4xx_with_a_message(shears, content, kind, status, fragment):
    headers = {"content-type": kind} if kind else {}
    r = shears.post("/api/solve", content=content, headers=headers)
    assert r.status_code == status
    assert fragment in r.json()["error"]
    assert shears.get("/api/parameters").status_code == 200  # still serving


def test_only_the_loopback_host_and_the_known_paths_are_served(shears):
    assert shears.get("/api/cycle", headers={"host": "attacker.example"}).status_code == 400
    assert shears.get("/api/cycle", headers={"host": "localhost:8765"}).status_code == 200
    assert shears.get("/static/viewer.js").headers["content-type"].startswith("text/javascript")
    for path in ("/static/../web/server.py", "/static/index.html", "/api/nothing", "/docs", "/openapi.json"):
        assert shears.get(path).status_code == 404, path
    assert shears.delete("/api/cycle").status_code == 405
    r = shears.get("/")
    assert (
        "script-src 'self'" in r.headers["content-security-policy"]
        and "connect-src 'self'" in r.headers["content-security-policy"]
    )
    assert r.headers["x-content-type-options"] == "nosniff"
    for ref in re.findall(r'(?:src|href)="([^"]*)"', r.text):
        assert ref.startswith("static/") or ref.startswith("data:"), ref  # nothing from the network


def test_the_parameters_list_the_files_dimensions_and_masses(shears):
    params = {p["name"]: p for p in shears.get("/api/parameters").json()["parameters"]}
    mech = lw.compile(lw.load("double-cut-shears"))
    for name, value in lw.parameters(mech).items():
        assert params[name]["value"] == pytest.approx(value)
    assert params["links.rocker.mass"]["value"] == 150 and params["links.rocker.inertia"]["value"] == 8.0
    assert params["links.crank.length"]["kind"] == "length" and params["joints.guide_E.axis"]["kind"] == "angle"


# ---------------------------------------------------------------------------- export and command line


def _embedded(page: str) -> dict:
    found = re.search(r'<script type="application/json" id="linkwork-data">(.*?)</script>', page, re.S)
    assert found
    return json.loads(found.group(1))


def test_export_writes_one_self_contained_page_atomically(tmp_path, monkeypatch):
    out = tmp_path / "page.html"
    export_page("shears-slider-crank", out, steps=72)
    page = out.read_text(encoding="utf-8")
    data = _embedded(page)
    mech = lw.compile(lw.load("shears-slider-crank"))
    kin = lw.kinematics(mech, _turn(mech, 72))
    np.testing.assert_allclose(_positions(data), kin.points(), atol=1e-8)
    assert data["editable"] is False
    assert data["labels_placed"] == 72  # the exported page's labels placed at every sample
    assert "<script src" not in page and '<link rel="stylesheet"' not in page
    assert re.findall(r'(?:src|href)="([^"]*)"', page) == ["data:,"]
    assert "default-src 'none'" in page  # the page may fetch nothing
    assert "</script>" not in page.split('id="linkwork-data">', 1)[1].split("</script>", 1)[0]

    import linkwork.web.export as export

    def broken(payload):
        raise RuntimeError("interrupted")

    monkeypatch.setattr(export, "render_page", broken)
    with pytest.raises(RuntimeError):
        export.export_page("four-bar", out)
    assert out.read_text(encoding="utf-8") == page
    assert sorted(p.name for p in tmp_path.iterdir()) == ["page.html"]


def test_export_embeds_text_that_cannot_close_its_script(tmp_path):
    """A mechanism named like markup stays data: the embedded JSON has no '<' at all."""
    text = example_text("four-bar")
    text = text.replace("name: four-bar", 'name: "</script><script>alert(1)</script>"')
    out = export_page(lw.loads(text, file="evil.yaml"), tmp_path / "p.html", steps=24)
    page = out.read_text(encoding="utf-8")
    blob = page.split('id="linkwork-data">', 1)[1].split("</script>", 1)[0]
    assert "<" not in blob
    assert _embedded(page)["name"] == "</script><script>alert(1)</script>"


runner = CliRunner()


def test_view_command_exports_and_reports_errors(tmp_path):
    import linkwork.cli.view  # noqa: F401
    from linkwork.cli.main import app

    out = tmp_path / "v.html"
    result = runner.invoke(app, ["view", "four-bar", "--export", str(out), "--steps", "36"])
    assert result.exit_code == 0, result.output
    assert len(_embedded(out.read_text(encoding="utf-8"))["angles_deg"]) == 36
    result = runner.invoke(app, ["view", "four-barr", "--no-browser"])
    assert result.exit_code == 2
    assert 'no such file or bundled example "four-barr" (did you mean "four-bar"?)' in result.output
    with socket.socket() as busy:
        busy.bind(("127.0.0.1", 0))
        busy.listen()
        port = busy.getsockname()[1]
        result = runner.invoke(app, ["view", "four-bar", "--no-browser", "--port", str(port), "--steps", "24"])
    assert result.exit_code == 2 and f"cannot listen on 127.0.0.1:{port}" in result.output


def _start_view(stderr: int = subprocess.PIPE, before: str = "") -> tuple[subprocess.Popen, re.Match]:
    """``linkwork view four-bar --port 0 --no-browser --steps 24`` in a process of its own (the Python statements
    ``before`` run first), and the URL it printed (the port it found free); the caller stops the process."""
    code = f"import sys; {before}from linkwork.cli.main import main; sys.argv = ['linkwork'] + sys.argv[1:]; main()"
    # the NumPy kernels: serving is tested here, and a cold cache would compile for a minute
    env = {**os.environ, "LINKWORK_NUMBA": "0"}
    args = [sys.executable, "-c", code, "view", "four-bar", "--port", "0", "--no-browser", "--steps", "24"]
    proc = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=stderr, text=True, env=env)
    line = proc.stdout.readline()
    url = re.search(r"http://127\.0\.0\.1:(\d+)/", line)
    if url is None:
        proc.kill()
        pytest.fail(line + (proc.stderr.read() if proc.stderr else ""))
    return proc, url


def test_view_command_serves_on_loopback_with_a_free_port():
    import httpx

    proc, url = _start_view()
    try:
        deadline = time.monotonic() + 20
        while True:
            try:
                r = httpx.get(url.group(0) + "api/parameters", timeout=5)
                break
            except httpx.ConnectError:
                assert time.monotonic() < deadline
                time.sleep(0.1)
        assert r.status_code == 200 and r.json()["editable"] is True
    finally:
        proc.terminate()
        proc.wait(timeout=10)


def test_the_manual_export_command_runs(tmp_path):
    import linkwork.cli.view  # noqa: F401
    from linkwork.cli.main import app
    from manual import page

    section = page("how-to/viewer.md")
    line = next(x for x in re.findall(r"```\n(.*?)```", section, re.S)[0].splitlines() if "--export" in x)
    args = line.split("#")[0].split()
    assert args[:2] == ["linkwork", "view"]
    out = tmp_path / args[args.index("--export") + 1]
    args[args.index("--export") + 1] = str(out)
    result = runner.invoke(app, [*args[1:], "--steps", "36"])
    assert result.exit_code == 0, result.output
    assert _embedded(out.read_text(encoding="utf-8"))["name"] == args[2]


def test_a_frame_pivot_named_second_is_charted_and_drawn_as_when_named_first():
    """``O4: [rocker, frame]`` is the same joint as ``[frame, rocker]``: the rocker's angle and angular velocity,
    the reaction in O4 and the frame point the page draws the support at do not depend on the order."""
    text = example_text("four-bar")
    first = "O4: {type: revolute, links: [frame, rocker]}"
    assert text.count(first) == 1
    swapped = text.replace(first, "O4: {type: revolute, links: [rocker, frame]}")
    a = cycle_payload(lw.compile(lw.loads(text, file="four-bar.yaml")), steps=72)
    b = cycle_payload(lw.compile(lw.loads(swapped, file="four-bar.yaml")), steps=72)
    assert [s["key"] for s in b["series"]] == [s["key"] for s in a["series"]]
    for key in ("link:rocker:angle", "link:rocker:omega", "reaction:O4", "reaction:O2", "torque"):
        np.testing.assert_allclose(_series(b, key), _series(a, key), rtol=1e-9, atol=1e-9)
    # the rocker's angle against the positions: the direction of O4B
    pos = _positions(a)
    names = [p["name"] for p in a["points"]]
    ob = pos[:, names.index("rocker.B")] - pos[:, names.index("rocker.O4")]
    angle = np.degrees(np.unwrap(np.arctan2(ob[:, 1], ob[:, 0])))
    np.testing.assert_allclose(_series(b, "link:rocker:angle"), angle, atol=1e-6)
    # the reaction's size: that of lw.forces for the file as given
    given = lw.compile(lw.loads(text, file="four-bar.yaml"))
    f = lw.forces(given, _turn(given, 72)).reaction("O4")
    np.testing.assert_allclose(_series(b, "reaction:O4"), np.hypot(f[:, 0], f[:, 1]), rtol=1e-8)
    supports = [(p["joint"], a["positions"][0][p["frame_point"]]) for p in a["pairs"] if p["frame_point"] is not None]
    drawn_b = [(p["joint"], b["positions"][0][p["frame_point"]]) for p in b["pairs"] if p["frame_point"] is not None]
    assert supports == drawn_b
    assert [j for j, _ in supports] == ["O2", "O4"] and supports[1][1] == pytest.approx([0.3, 0.0])


@pytest.mark.parametrize(
    "name, overrides",
    [
        (
            "double-cut-shears",
            {
                "links.crank.length": 0.11,
                "frame.points.O1.x": 0.52,
                "links.rocker.points.B.x": 0.48,
                "links.rod.mass": 70.0,
                "links.rocker.inertia": 9.5,
                "joints.guide_E.axis": 1.6,
            },
        ),
        ("four-bar", {"links.rocker.inertia": 20.0, "links.coupler.points.M.y": 0.09, "links.rocker.mass": 2.0}),
    ],
)
def test_every_kind_of_edit_comes_back_in_the_parameters(name, overrides):
    """A length, coordinates, a mass, an inertia and an angle come back as sent in the answer's parameters, the
    values not edited as in the file (the four-bar's file, in mm, gives no inertias: the crank's and the coupler's
    stay m l^2 / 12 of their unedited masses); the edited crank's length is that of the positions."""
    client = TestClient(create_app(name), base_url=LOCAL)
    before = {p["name"]: p["value"] for p in client.get("/api/parameters").json()["parameters"]}
    r = client.post("/api/solve", json={"overrides": overrides, "steps": 36})
    assert r.status_code == 200, r.text
    after = {p["name"]: p["value"] for p in r.json()["parameters"]}
    assert after.keys() == before.keys()
    for key, value in before.items():
        assert after[key] == pytest.approx(overrides.get(key, value), rel=1e-12, abs=1e-15), key
    if "links.crank.length" in overrides:
        pos = _positions(r.json())
        names = [p["name"] for p in r.json()["points"]]
        crank = pos[:, names.index("crank.A")] - pos[:, names.index("crank.O1")]
        np.testing.assert_allclose(np.hypot(*crank.T), overrides["links.crank.length"], atol=1e-8)
    # a second call (from the cache) answers the same
    assert (
        client.post("/api/solve", json={"overrides": overrides, "steps": 36}).json()["parameters"]
        == r.json()["parameters"]
    )


@pytest.mark.parametrize(
    "target, fragment",
    [
        ("DIR", "is a directory"),
        ("", "give the name of the page to write"),
        ("/proc/x.html", "--export /proc/x.html: cannot write"),
        ("FILE/page.html", "cannot write"),
    ],
)
def test_view_export_to_a_place_that_cannot_be_written_fails_cleanly(tmp_path, monkeypatch, target, fragment):
    """A directory, an empty name, a place where no file can be made: exit 2 and one line, no traceback, and no
    file (finished or partial) left behind."""
    import linkwork.cli.view  # noqa: F401
    from linkwork.cli.main import app

    monkeypatch.chdir(tmp_path)  # an empty name would write beside the working directory
    (tmp_path / "FILE").write_text("x", encoding="utf-8")
    target = target.replace("DIR", str(tmp_path)).replace("FILE", str(tmp_path / "FILE"))
    before = sorted(p.name for p in tmp_path.iterdir())
    result = runner.invoke(app, ["view", "four-bar", "--export", target, "--steps", "24"])
    assert result.exit_code == 2, result.output
    assert fragment in result.output and result.output.startswith("error: ")
    assert isinstance(result.exception, SystemExit) and "Traceback" not in result.output
    assert len(result.output.strip().splitlines()) == 1
    assert sorted(p.name for p in tmp_path.iterdir()) == before
    assert sorted(p.name for p in tmp_path.parent.iterdir() if p.name.endswith(".part")) == []


@pytest.mark.parametrize(
    "host, status",
    [
        ("127.0.0.1:8765", 200),
        ("localhost:8765", 200),
        ("LocalHost:8765", 200),
        ("[::1]:8765", 200),
        ("127.0.0.1", 200),
        ("localhost", 200),
        ("[::1].evil.com", 400),
        ("[::1]evil:80", 400),
        ("localhost.evil.com", 400),
        ("127.0.0.1.nip.io:8765", 400),
        ("evil.com:8765", 400),
        ("localhost:8765:80", 400),
        ("localhost:", 400),
        ("localhost:http", 400),
        ("::1", 400),
        ("evil.com@localhost", 400),
    ],
)
def test_the_whole_host_header_must_be_a_loopback_name_and_a_port(shears, host, status):
    r = shears.get("/api/parameters", headers={"host": host})
    assert r.status_code == status
    if status == 400:
        assert "loopback" in r.json()["error"]


def test_a_pose_never_waits_for_a_solve():
    """With every solving slot held (two edits and a whole cycle being solved), a crank step is solved at once and
    matches the kinematics at its angle; an edit and a cycle wait for a slot and are answered busy (503).  (Under
    load, poses used to queue behind edits for seconds.)"""
    app = create_app("four-bar", steps=36)
    client = TestClient(app, base_url=LOCAL)
    viewer = app.state.viewer
    viewer.wait_s = 0.05
    held = [viewer.edit_slots, viewer.edit_slots, viewer.full_slots]
    assert all(slot.acquire(timeout=1) for slot in held)
    try:
        t = time.perf_counter()
        r = client.post("/api/pose", json={"angle_deg": 30})
        assert r.status_code == 200 and time.perf_counter() - t < 5
        kin = lw.kinematics(lw.compile(lw.load("four-bar")), [math.radians(30)])
        np.testing.assert_allclose(r.json()["points"]["rocker.B"], kin.position("B")[0], atol=1e-12)
        for path, body in (("/api/edit", {"overrides": {"links.crank.length": 0.105}}), ("/api/solve", {"steps": 48})):
            r = client.post(path, json=body)
            assert r.status_code == 503 and "busy" in r.json()["error"], path
    finally:
        for slot in held:
            slot.release()
    assert client.post("/api/edit", json={"overrides": {"links.crank.length": 0.105}}).status_code == 200


def test_view_command_refuses_more_than_1440_steps(tmp_path):
    import linkwork.cli.view  # noqa: F401
    from linkwork.cli.main import app

    result = runner.invoke(app, ["view", "four-bar", "--export", str(tmp_path / "p.html"), "--steps", "1441"])
    assert result.exit_code == 2 and "1440" in result.output
    assert list(tmp_path.iterdir()) == []


def test_the_torque_and_moment_charts_say_counter_clockwise_positive():
    """The percussion rocker's crank turns clockwise: its driving torque is charted counter-clockwise positive,
    as the label says, so that torque times the (negative) crank speed is the rate of change of the energy."""
    mech = lw.compile(lw.load("percussion-rocker"))
    payload = cycle_payload(mech, steps=720)
    labels = {s["key"]: s["label"] for s in payload["series"]}
    assert labels["torque"] == "driving torque on the crank (ccw +)"
    assert labels["foundation:m"].endswith("(ccw +)")
    kin = lw.kinematics(mech, _turn(mech, 720))
    omega = kin.rates[0, 0]
    assert omega < 0 and payload["drives"][0]["direction"] == "cw"
    _, kinetic, potential = _com_motion(kin)
    power = _d1(kinetic + potential, 2 * math.pi / 720 / abs(omega))
    torque = _series(payload, "torque")
    assert np.abs(torque * omega - power).max() < 1e-6 * np.abs(power).max()


@pytest.fixture(scope="module")
def live_server():
    """The four-bar's viewer on a real uvicorn server in a thread (127.0.0.1, a free port): (host, port)."""
    pytest.importorskip("uvicorn")
    from webserver import serving

    with serving(create_app("four-bar", steps=36)) as address:
        yield address


@pytest.mark.parametrize("size, status", [(MAX_BODY + 1, 413), (4 * MAX_BODY, 413), (MAX_BODY - 100, 200)])
def test_a_chunked_body_without_a_length_is_limited_too(live_server, size, status):
    """Transfer-Encoding: chunked and no Content-Length: the server counts the bytes as they come and answers 413
    past the limit; a body under it (padded with spaces) is solved."""
    import http.client

    host, port = live_server
    body = b'{"steps": 24}'
    body = body + b" " * (size - len(body))

    def chunks():
        for i in range(0, len(body), 4096):
            yield body[i : i + 4096]

    conn = http.client.HTTPConnection(host, port, timeout=30)
    try:
        conn.putrequest("POST", "/api/solve")
        conn.putheader("Content-Type", "application/json")
        conn.putheader("Transfer-Encoding", "chunked")
        conn.endheaders()
        try:
            for chunk in chunks():
                conn.send(b"%x\r\n%s\r\n" % (len(chunk), chunk))
            conn.send(b"0\r\n\r\n")
        except (BrokenPipeError, ConnectionResetError):
            pass  # the server may answer and close before the whole body is sent
        r = conn.getresponse()
        assert r.status == status
        answer = json.loads(r.read())
        if status == 413:
            assert f"limited to {MAX_BODY} bytes" in answer["error"]
        else:
            assert len(answer["angles_deg"]) == 24
    finally:
        conn.close()


def test_a_pose_echoes_the_angle_as_sent(shears):
    r = shears.post("/api/pose", json={"angle_deg": 30})
    assert r.status_code == 200 and r.json()["angle_deg"] == 30
    assert shears.post("/api/pose", json={"angle_deg": 0.1 + 0.2}).json()["angle_deg"] == 0.1 + 0.2


def test_an_internal_error_answers_500_with_the_security_headers(monkeypatch):
    app = create_app("four-bar", steps=24)
    client = TestClient(app, base_url=LOCAL, raise_server_exceptions=False)

    def broken(*args, **kwargs):
        raise RuntimeError("broken on purpose")

    monkeypatch.setattr(app.state.viewer, "cycle", broken)
    r = client.get("/api/cycle")
    assert r.status_code == 500 and r.json()["error"] == "internal error: RuntimeError: broken on purpose"
    assert "default-src 'none'" in r.headers["content-security-policy"]
    assert r.headers["x-content-type-options"] == "nosniff" and r.headers["cache-control"] == "no-store"


def test_the_support_reaction_of_a_compound_hinge_is_the_force_on_the_frame():
    """The Watt six-bar with its output swinging about O4 too (O4 joins the frame, the rocker and the output):
    the viewer's reaction in O4 is the size of the force on the frame, minus the forces O4 puts on the rocker
    and on the output, each from that link's own free body (m a_C - W less its other joints' forces)."""
    src = example_text("watt-six-bar")
    src = src.replace(
        "O4: {type: revolute, links: [frame, rocker]}", "O4: {type: revolute, links: [frame, rocker, output]}"
    )
    src = src.replace("  O6: {type: revolute, links: [frame, output]}\n", "")
    src = src.replace("O6: [650, 100]", "O6: [300, 0]").replace("ends: [O6, D]", "ends: [O4, D]")
    src = src.replace("length: 269.3", "length: 345.745").replace("D: [550, 350]", "D: [338.197, 343.649]")
    mech = lw.compile(lw.loads(src, file="watt-six-bar.yaml"))
    payload = cycle_payload(mech, steps=36)
    f = lw.forces(mech, _turn(mech, 36))
    kin, g = f.kinematics, np.array([0.0, -mech.gravity])
    a_rocker = (kin.acceleration("rocker.B") + kin.acceleration("rocker.C")) / 3  # the centroid; O4 is fixed
    on_rocker = 3.0 * a_rocker - 3.0 * g - f.reaction("B") + f.reaction("C")  # coupler on it at B, rod at C
    on_output = 1.5 * 0.5 * kin.acceleration("D") - 1.5 * g - f.reaction("D")  # the rod's force on it at D
    on_frame = -(on_rocker + on_output)
    size = np.hypot(on_frame[:, 0], on_frame[:, 1])
    assert np.abs(size - np.hypot(*f.reaction("O4").T)).max() > 1.0  # more than the pair of one link
    np.testing.assert_allclose(_series(payload, "reaction:O4"), size, rtol=1e-7)  # the payload keeps 8 digits


# ---------------------------------------------------------------------------- edits as variants, compact answers


def _array(c):
    """An array of an edit's answer (:func:`_edit`), as float."""
    return np.asarray(c, dtype=float)


def test_an_edits_answer_is_its_json_then_its_arrays_bytes_each_where_the_json_says():
    """The layout the page reads (viewer.js readEdit), read here byte by byte with :mod:`struct`: the JSON's
    length (uint32, little-endian), the JSON (as :func:`json.dumps` writes the answer, each array
    ``{"dtype", "shape", "offset"}``), zeros up to a multiple of 8, then each array's little-endian values at
    its offset, a multiple of 8; NaN is refused as by the strict writer."""
    import struct

    from linkwork.web.update import compact, decode_edit, encode_edit

    x, ok, empty = np.arange(15.0).reshape(3, 5) / 7, np.array([1, 0, 1]), np.ones((0, 2))
    data = {
        "a": compact(x),
        "label": 'φ \\ "x"',
        "nested": [{"b": compact(ok, "u1"), "c": compact(x, "f8")}],
        "n": [1.5, 2],
        "e": compact(empty),
    }
    body = encode_edit(data)
    (n,) = struct.unpack_from("<I", body)
    head = json.loads(body[4 : 4 + n].decode("utf-8"))
    base = 4 + n + (-(4 + n) % 8)
    assert base % 8 == 0 and body[4 + n : base] == bytes(base - 4 - n)
    assert head["label"] == 'φ \\ "x"' and head["n"] == [1.5, 2]
    want = {"a": (x, "<f4"), "b": (ok, "u1"), "c": (x, "<f8"), "e": (empty, "<f4")}
    found = {"a": head["a"], "b": head["nested"][0]["b"], "c": head["nested"][0]["c"], "e": head["e"]}
    for key, c in found.items():
        values, kind = want[key]
        assert c["offset"] % 8 == 0 and c["shape"] == list(values.shape) and c["dtype"] == kind.strip("<")
        raw = body[base + c["offset"] : base + c["offset"] + values.size * np.dtype(kind).itemsize]
        assert raw == values.astype(kind).tobytes(), key
    assert len(body) >= base + found["c"]["offset"] + x.size * 8
    back = decode_edit(body)
    assert np.array_equal(back["nested"][0]["c"], x) and back["label"] == data["label"]
    with pytest.raises(ValueError):
        encode_edit({"a": compact(x), "x": math.nan})
    with pytest.raises(TypeError):
        encode_edit({"x": object()})


def _edit(r):
    """An edit's answer (its JSON, its arrays as NumPy arrays), checked to be of the edit's media type."""
    from linkwork.web.update import EDIT_MEDIA, decode_edit

    assert r.status_code == 200, r.text
    assert r.headers["content-type"] == EDIT_MEDIA
    return decode_edit(r.content)


def _positions_of_edit(answer, points):
    """(A, P, 2) positions as the page places them from an edit's answer: each point's link pose applied to the
    point in the link's axes; the frame's points as given; NaN where the mechanism does not assemble."""
    poses, local = _array(answer["scene"]["poses"]), np.array(answer["local"])
    valid = _array(answer["valid"]).astype(bool)
    link = np.array([p["link"] for p in points])
    q = poses[:, link]  # (A, P, 3)
    c, s = np.cos(q[..., 2]), np.sin(q[..., 2])
    out = np.stack([q[..., 0] + c * local[:, 0] - s * local[:, 1], q[..., 1] + s * local[:, 0] + c * local[:, 1]], -1)
    out[:, link == 0] = local[link == 0]
    out[np.ix_(~valid, link != 0)] = np.nan
    return out


SHEARS = lw.compile(lw.load("double-cut-shears"))
SHEARS_EDIT = {"links.crank.length": 0.12, "links.rod.mass": 90.0, "frame.points.O3.x": 0.01}


def _shears_by_hand():
    """The double-cut shears' file edited by hand to SHEARS_EDIT."""
    text = example_text("double-cut-shears")
    for old, new in (
        ("    length: 0.10\n    mass: 40\n", "    length: 0.12\n    mass: 40\n"),
        ("    length: 0.40\n    mass: 60\n", "    length: 0.40\n    mass: 90\n"),
        ("O3: [0.00, 0.00]", "O3: [0.01, 0.00]"),
    ):
        assert text.count(old) == 1
        text = text.replace(old, new)
    return lw.compile(lw.loads(text, file="double-cut-shears.yaml"))


def test_an_edit_is_solved_as_a_variant_and_gives_what_the_edited_file_gives(shears, shears_cycle, monkeypatch):
    """POST /api/edit compiles nothing (compiling is made to fail here) and answers what the file edited by hand
    gives: the points as the page places them from the links' poses, the plans, the driving torque, the force
    arrows and the parameters (the rod's mass as sent), to the compact arrays' 7 digits."""
    import linkwork.api

    def no_compile(*args, **kwargs):
        raise AssertionError("an edit compiled the mechanism again")

    monkeypatch.setattr(linkwork.api, "compile", no_compile)
    answer = _edit(shears.post("/api/edit", json={"overrides": SHEARS_EDIT}))
    monkeypatch.undo()
    by_hand = _shears_by_hand()
    kin = lw.kinematics(by_hand, _turn(by_hand, 360, SHEARS))
    pos = _positions_of_edit(answer, shears_cycle["points"])
    np.testing.assert_allclose(pos, kin.points(), atol=1e-6)
    vel = _array(answer["plans"]["velocity"]["values"])
    labels = shears_cycle["plans"]["velocity"]["labels"]
    v_e = kin.velocity("E")
    np.testing.assert_allclose(vel[:, labels.index("e")], v_e, atol=1e-6 * np.abs(v_e).max())
    forces = lw.forces(by_hand, _turn(by_hand, 360, SHEARS))
    series = _array(answer["series"]["values"])
    torque = series[answer["series"]["keys"].index("torque")]
    top = np.abs(forces.driving_torque).max()
    np.testing.assert_allclose(torque, forces.driving_torque, rtol=1e-6, atol=1e-6 * top)
    arrows, values = answer["forces"]["arrows"], _array(answer["forces"]["values"])
    k = next(j for j, a in enumerate(arrows) if a["name"] == "B")
    np.testing.assert_allclose(values[:, k], forces.reaction("B", on="rocker"), rtol=1e-6, atol=1e-3)
    params = {p["name"]: p["value"] for p in answer["parameters"]}
    assert params["links.rod.mass"] == 90.0 and params["links.crank.length"] == 0.12
    assert answer["overrides"] == SHEARS_EDIT


@pytest.mark.parametrize("whole_turn", [False, True])
def test_an_edits_scheme_is_the_scheme_of_the_file_edited_by_hand(shears, whole_turn):
    """The scheme of an edit's answer (the supports turned to their free side, the guides' length, every outline, the
    sizes, the labels' anchors), after another edit that moved the same support elsewhere, is that of the file edited
    by hand and compiled afresh, drawn from the same number of crank angles of its own turn (the whole cycle's
    symbols for a typed edit, fewer for a drag), to 1e-9 m; the links' poses to float32."""
    from linkwork.scene.scheme import CYCLE, scheme_scene
    from linkwork.web.cycle import DRAGGED

    other = {**SHEARS_EDIT, "frame.points.O3.x": -0.03, "links.crank.length": 0.095}
    assert shears.post("/api/edit", json={"overrides": other, "whole_turn": whole_turn}).status_code == 200
    scene = _edit(shears.post("/api/edit", json={"overrides": SHEARS_EDIT, "whole_turn": whole_turn}))["scene"]
    by_hand = _shears_by_hand()
    turn = lw.kinematics(by_hand, _turn(by_hand, DRAGGED if whole_turn else CYCLE, SHEARS))
    expected = scheme_scene(turn, at=[], cycle=turn)
    table = scene["item_table"]
    fields = ("kind", "link", "name", "closed", "radius")
    items = [dict(zip(fields, row, strict=True)) for row in zip(*(table[key] for key in fields), strict=True)]
    for it, start, end in zip(items, [0, *table["ends"][:-1]], table["ends"], strict=True):
        it["xy"] = table["xy"][start:end]
    assert [(it["kind"], it["link"], it["name"], it["closed"]) for it in items] == [
        (it.kind, it.link, it.name, it.closed) for it in expected.items
    ]
    for it, want in zip(items, expected.items, strict=True):
        np.testing.assert_allclose(np.array(it["xy"]), want.xy, rtol=0, atol=1e-9, err_msg=f"{it['kind']} {it['name']}")
        assert it["radius"] == pytest.approx(want.radius, rel=1e-12)
    assert scene["size"] == pytest.approx(expected.size, rel=1e-12) and scene["em"] == pytest.approx(expected.em)
    np.testing.assert_allclose(np.array(scene["label_at"]), [lab.at for lab in expected.labels], atol=1e-9)
    poses = _array(scene["poses"])
    want = lw.kinematics(by_hand, _turn(by_hand, 360, SHEARS)).pose[0]
    ok = np.isfinite(want).all(-1)
    turned = np.angle(np.exp(1j * (poses[..., 2] - want[..., 2])))  # angles compared modulo a turn
    np.testing.assert_allclose(poses[..., :2][ok], want[..., :2][ok], atol=1e-6)
    np.testing.assert_allclose(turned[ok], 0, atol=1e-6)


def test_an_edits_answer_carries_only_what_changed_in_compact_arrays(shears, shears_cycle):
    """No names, structure, labels' texts or positions again; the big arrays as float32 bytes; under a quarter
    of the whole payload's size; strict JSON."""
    r = shears.post("/api/edit", json={"overrides": {"links.crank.length": 0.105}})
    answer = _edit(r)
    n = int.from_bytes(r.content[:4], "little")
    json.loads(r.content[4 : 4 + n], parse_constant=lambda c: pytest.fail(f"bare {c} in the answer"))
    for key in ("points", "positions", "links", "pairs", "structure", "drives", "name"):
        assert key not in answer, key
    assert "labels" not in answer["scene"] and "text" not in answer["scene"]["plans"]["velocity"]
    assert answer["scene"]["poses"].dtype == "<f4" and answer["plans"]["velocity"]["values"].dtype == "<f4"
    assert len(r.content) < len(json.dumps(shears_cycle)) / 4


def test_a_drag_out_of_the_files_range_is_refused_with_where_and_a_typed_edit_shows_the_gaps(shears):
    """A crank of 0.3 m: A is farther from O3 than rod + rocker (0.9 m) reach over part of the turn.  Dragged there
    (whole_turn) the edit is refused (422) with the group and the crank angles, which are those of the closed form;
    typed, it is shown with its gaps."""
    r = shears.post("/api/edit", json={"overrides": {"links.crank.length": 0.3}, "whole_turn": True})
    assert r.status_code == 422
    body = r.json()
    assert "links.crank.length = 300 mm" in body["error"] and "II(2,3) RRR" in body["error"]
    (event,) = body["events"]
    phi = np.radians(np.linspace(0, 360, 36001))
    beyond = np.hypot(0.5 + 0.3 * np.cos(phi), 0.4 + 0.3 * np.sin(phi)) > 0.9
    edges = np.degrees(phi[np.flatnonzero(np.diff(beyond.astype(int)))])
    for got, want in zip((event["start_deg"], event["end_deg"]), edges, strict=True):  # drive angles, not wrapped
        assert (got - want + 180) % 360 - 180 == pytest.approx(0, abs=0.02)
    typed = shears.post("/api/edit", json={"overrides": {"links.crank.length": 0.3}})
    assert typed.status_code == 200
    valid = _array(_edit(typed)["valid"]).astype(bool)
    assert 0 < (~valid).sum() < len(valid)


def test_an_edit_that_cannot_assemble_at_the_assembly_pose_gets_the_compilers_message(shears):
    for path in ("/api/edit", "/api/pose"):
        body = {"overrides": {"links.rod.length": 0.01}} | ({"angle_deg": 10.0} if path == "/api/pose" else {})
        r = shears.post(path, json=body)
        assert r.status_code == 422, path
        assert "group II(2,3) RRR (links rod, rocker) cannot be assembled at the drive position" in r.json()["error"]


def test_a_pose_of_a_variant_is_that_of_the_edited_file(shears):
    kin = lw.kinematics(_shears_by_hand(), [math.radians(200)])
    r = shears.post("/api/pose", json={"angle_deg": 200, "overrides": SHEARS_EDIT})
    assert r.status_code == 200
    np.testing.assert_allclose(r.json()["points"]["knife_upper.edge"], kin.position("knife_upper.edge")[0], atol=1e-12)


def test_an_edit_waiting_for_a_slot_is_superseded_by_a_newer_one_of_its_page():
    """Latest wins: with both edit slots held, a page's edit 1 waits; its edit 2 comes; edit 1 is answered 409
    unsolved and edit 2 is solved once a slot frees."""
    import threading

    app = create_app("four-bar", steps=36)
    client = TestClient(app, base_url=LOCAL)
    viewer = app.state.viewer
    assert viewer.edit_slots.acquire(timeout=1) and viewer.edit_slots.acquire(timeout=1)
    answers = {}

    def send(seq, length):
        body = {"overrides": {"links.crank.length": length}, "client": "page-1", "seq": seq}
        answers[seq] = client.post("/api/edit", json=body)

    first = threading.Thread(target=send, args=(1, 0.101))
    first.start()
    time.sleep(0.3)
    second = threading.Thread(target=send, args=(2, 0.102))
    second.start()
    first.join(timeout=10)
    assert answers[1].status_code == 409 and "superseded" in answers[1].json()["error"]
    viewer.edit_slots.release()
    second.join(timeout=30)
    viewer.edit_slots.release()
    assert _edit(answers[2])["overrides"] == {"links.crank.length": 0.102}


def test_the_saved_file_keeps_the_files_comments_and_solves_to_the_edit(shears):
    r = shears.post("/api/save", json={"overrides": SHEARS_EDIT})
    assert r.status_code == 200
    assert r.headers["content-disposition"] == (
        "attachment; filename=\"double-cut-shears-edited.yaml\"; filename*=UTF-8''double-cut-shears-edited.yaml"
    )
    text = r.text
    original = example_text("double-cut-shears")
    comments = [line.split("#", 1)[1] for line in original.splitlines() if "#" in line]
    assert comments and all(c in text for c in comments)
    assert "length: 0.12\n" in text and "O3: [0.01, 0.00]" in text.replace("0.01, 0.0]", "0.01, 0.00]")
    saved = lw.kinematics(lw.compile(lw.loads(text, file="saved.yaml")), steps=360)
    np.testing.assert_allclose(saved.points(), lw.kinematics(_shears_by_hand(), steps=360).points(), atol=1e-12)
    edit = _edit(shears.post("/api/edit", json={"overrides": SHEARS_EDIT}))
    torque = _array(edit["series"]["values"])[edit["series"]["keys"].index("torque")]
    np.testing.assert_allclose(
        torque, lw.forces(saved.mechanism, _turn(saved.mechanism, 360, SHEARS)).driving_torque, rtol=1e-6, atol=1e-3
    )


def test_the_force_arrows_are_the_reactions_and_the_cutting_force(shears_cycle):
    """Each joint's arrow is the force on its link of the highest number: the crank's two arrows close its free
    body (R01 - R12 = m a_C - m g: the rod's force on the crank is -R12); the knives' arrows are the table's cutting
    force at their penetration, up on the upper knife, down on the lower; one scale of the 1-2-5 series."""
    f = shears_cycle["forces"]
    arrows = {a["label"]: j for j, a in enumerate(f["arrows"])}
    values = np.array([[[np.nan if v is None else v for v in xy] for xy in row] for row in f["values"]])
    assert [f["arrows"][arrows["R12"]][k] for k in ("name", "on", "by")] == ["A", "rod", ["crank"]]
    kin = lw.kinematics(SHEARS, _turn(SHEARS, 360))
    a_c = (kin.acceleration("crank.O1") + kin.acceleration("crank.A")) / 2  # the crank's centre, mid-length
    np.testing.assert_allclose(
        values[:, arrows["R01"]] - values[:, arrows["R12"]],
        40.0 * (a_c - [0, -9.81]),
        atol=1e-6 * np.nanmax(np.abs(values)),
    )
    upper, lower = kin.position("knife_upper.edge")[:, 1], kin.position("knife_lower.edge")[:, 1]
    closing = np.gradient(upper - lower) < 0
    eps = (np.maximum(0.05 - upper, 0) + np.maximum(lower + 0.05, 0)) / 0.1
    cutting = np.where(closing & (eps > 0), np.interp(eps, [0, 0.15, 0.30, 0.45], [0, 250e3, 250e3, 0], right=0), 0)
    cut = [j for j, a in enumerate(f["arrows"]) if a["kind"] == "load"]
    assert [f["arrows"][j]["on"] for j in cut] == ["knife_upper", "knife_lower"]
    sure = np.abs(np.gradient(upper - lower)) > 1e-4  # away from the turning points of the knives
    np.testing.assert_allclose(values[sure, cut[0], 1], cutting[sure], atol=1e-3 * 250e3)
    np.testing.assert_allclose(values[sure, cut[1], 1], -cutting[sure], atol=1e-3 * 250e3)
    assert np.abs(values[:, cut, 0]).max() < 1e-6
    mantissa = f["scale_per_mm"] / 10 ** math.floor(math.log10(f["scale_per_mm"]))
    assert round(mantissa, 9) in (1, 2, 2.5, 5)


@pytest.mark.parametrize("path", ["/api/edit", "/api/save", "/api/solve"])
@pytest.mark.parametrize("content, kind, status, fragment", [b for b in BAD if b"steps" not in b[0]])
def test_the_edit_and_save_endpoints_refuse_bad_bodies_too(shears, path, content, kind, status, fragment):
    headers = {"content-type": kind} if kind else {}
    r = shears.post(path, content=content, headers=headers)
    assert r.status_code == status, r.text
    assert fragment in r.json()["error"]


@pytest.mark.parametrize(
    "body, fragment",
    [
        ({"overrides": {}, "client": "a b"}, "client: String should match pattern"),
        ({"overrides": {}, "client": "x" * 65}, "client: String should match pattern"),
        ({"overrides": {}, "seq": -1}, "seq: Input should be greater than or equal to 0"),
        ({"overrides": {}, "seq": 1.5}, "seq: Input should be a valid integer"),
        ({"overrides": {}, "whole_turn": "yes"}, "whole_turn: Input should be a valid boolean"),
        ({"overrides": {}, "steps": 1441}, "steps: Input should be less than or equal to 1440"),
        ({"overrides": {"links.crank.length": 1e3}}, "expected a positive length up to 100 m"),
        ({"overrides": {"links.crank.lenght": 0.1}}, 'did you mean "links.crank.length"'),
    ],
)
def test_an_edit_with_bad_fields_gets_a_4xx_with_a_message(shears, body, fragment):
    r = shears.post("/api/edit", json=body)
    assert r.status_code == 422
    assert fragment in r.json()["error"]


def test_the_new_endpoints_answer_only_the_loopback_host(shears):
    for path, body in (("/api/edit", {}), ("/api/save", {}), ("/api/pose", {"angle_deg": 1})):
        r = shears.post(path, json=body, headers={"host": "evil.example:8765"})
        assert r.status_code == 400 and "loopback" in r.json()["error"], path
        assert "default-src 'none'" in r.headers["content-security-policy"]
    r = shears.post("/api/save", json={})
    assert r.status_code == 200 and "frame-ancestors 'none'" in r.headers["content-security-policy"]


def test_a_saved_mechanism_without_its_description_is_refused():
    import dataclasses

    bare = dataclasses.replace(lw.compile(lw.load("four-bar")), description=None)
    client = TestClient(create_app(bare), base_url=LOCAL)
    for path in ("/api/save", "/api/edit"):
        r = client.post(path, json={"overrides": {"links.crank.length": 0.11}})
        assert r.status_code == 422 and "cannot be edited" in r.json()["error"], path


def test_clients_that_go_away_mid_request_leave_no_traceback():
    """Issue 19: a client that disconnects while sending its body, or before its answer, must not make the server
    log a traceback (it logged one per client); the server goes on answering."""
    import http.client

    proc, url = _start_view()
    try:
        port = int(url.group(1))
        head = "POST {} HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\nContent-Length: {}\r\n\r\n"
        for k in range(40):
            path = ("/api/solve", "/api/edit", "/api/pose")[k % 3]
            with socket.create_connection(("127.0.0.1", port)) as s:
                if k % 2:  # half a body, then gone
                    s.sendall(head.format(path, 1000).encode() + b'{"overrides": {')
                else:  # a whole edit, gone before its answer
                    body = json.dumps({"overrides": {"links.crank.length": 0.1 + k * 1e-4}, "angle_deg": 1.0})
                    body = body.encode() if path == "/api/pose" else body.replace(', "angle_deg": 1.0', "").encode()
                    s.sendall(head.format(path, len(body)).encode() + body)
                time.sleep(0.01)
        conn = http.client.HTTPConnection("127.0.0.1", port, timeout=30)
        conn.request("GET", "/api/parameters", headers={"Host": "127.0.0.1"})
        assert conn.getresponse().status == 200
        conn.close()
        time.sleep(0.5)
    finally:
        err = _ended(proc, signal.SIGTERM)
    assert "Traceback" not in err and "Exception" not in err, err[-2000:]


def _ended(proc: subprocess.Popen, sig: int) -> str:
    """Send ``sig`` to the viewer ``proc``; what it wrote on stderr once it has ended, by that signal, within
    :data:`SHUTDOWN_WAIT_S` + 5 s (the answers in progress get SHUTDOWN_WAIT_S; 5 s for a loaded machine)."""
    proc.send_signal(sig)
    try:
        _, err = proc.communicate(timeout=SHUTDOWN_WAIT_S + 5)
    except subprocess.TimeoutExpired:
        proc.kill()
        _, err = proc.communicate(timeout=20)
        raise AssertionError(f"the viewer did not end within {SHUTDOWN_WAIT_S + 5} s of {sig!r}") from None
    assert proc.returncode == -sig, err[-2000:]
    return err


def test_ctrl_c_ends_the_viewer_whatever_work_the_gone_clients_left():
    """Three clients ask for a crank step and leave while it is solved; each step takes a minute here (as numba
    compiling its kernels for a new kind of batch: the viewer this suite ran on the compiled kernels still ran
    90 s after SIGTERM, compiling for the poses of gone clients).  Ctrl+C ends the viewer at once, without a
    traceback: it used to wait for every piece of work in its threads (asyncio's runner for each request it
    cancelled, the interpreter's exit for every worker thread), however long."""
    slow = "import time; from linkwork.web.session import Viewer; Viewer.pose = lambda *a: time.sleep(60); "
    proc, url = _start_view(before=slow)
    try:
        port = int(url.group(1))
        body = b'{"angle_deg": 1.0}'
        head = "POST /api/pose HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\n"
        for _ in range(3):
            with socket.create_connection(("127.0.0.1", port)) as s:
                s.sendall(f"{head}Content-Length: {len(body)}\r\n\r\n".encode() + body)
                time.sleep(0.2)  # read, and its step started in a worker thread; then the client leaves
        time.sleep(0.5)
    finally:
        start = time.monotonic()
        err = _ended(proc, signal.SIGINT)
    # no answer was in progress: nothing to wait for, nothing cancelled ("Cancel 3 running task(s)")
    assert time.monotonic() - start < SHUTDOWN_WAIT_S, err[-2000:]
    assert "Traceback" not in err and "Exception" not in err and "Cancel" not in err, err[-2000:]


def test_crank_steps_do_not_queue_behind_solves_under_load():
    """Issue 19: under load, poses waited behind edits for seconds (p50 13 s).  Four whole cycles of the
    double-cut shears at about 1440 steps (about a second each, one at a time) are asked for at once; the crank
    steps asked meanwhile, while a solve is still running, are answered in well under a second."""
    import threading

    import httpx

    pytest.importorskip("uvicorn")
    from webserver import serving

    ended: list[float] = []

    def solve(url: str, steps: int) -> None:
        httpx.post(f"{url}/api/solve", json={"steps": steps}, timeout=300)
        ended.append(time.perf_counter())

    with serving(create_app("double-cut-shears", steps=36)) as (host, port):
        url = f"http://{host}:{port}"
        solves = [threading.Thread(target=solve, args=(url, 1440 - n)) for n in range(4)]
        for t in solves:
            t.start()
        time.sleep(0.5)
        waits = []
        with httpx.Client(timeout=120) as client:
            for k in range(10):
                t0 = time.perf_counter()
                r = client.post(f"{url}/api/pose", json={"angle_deg": 10.0 * k})
                waits.append(time.perf_counter() - t0)
                assert r.status_code == 200
        last_pose = time.perf_counter()
        for t in solves:
            t.join(timeout=300)
    assert len(ended) == 4 and max(ended) > last_pose, "the solves were over before the poses: the test proves nothing"
    assert sorted(waits)[len(waits) // 2] < 1.0, waits


def test_small_answers_are_not_held_back_for_the_clients_delayed_ack():
    """Each small answer (a pose, the parameters) came some 40 ms late: the server's connections kept Nagle's
    algorithm, which holds the body back until the headers are acknowledged, and clients delay that ACK.  A
    crank step over HTTP now takes a few milliseconds."""
    import http.client
    import statistics

    proc, url = _start_view(stderr=subprocess.DEVNULL)
    try:
        port = int(url.group(1))
        conn = http.client.HTTPConnection("127.0.0.1", port, timeout=30)
        waits = {}
        for path, body in (("/api/parameters", None), ("/api/pose", b'{"angle_deg": 10}')):
            times = []
            for _ in range(21):
                t = time.perf_counter()
                conn.request("GET" if body is None else "POST", path, body, {"Content-Type": JSON})
                response = conn.getresponse()
                response.read()
                assert response.status == 200
                times.append(time.perf_counter() - t)
            waits[path] = statistics.median(times[1:])
        conn.close()
    finally:
        proc.terminate()
        proc.wait(timeout=10)
    assert max(waits.values()) < 0.02, waits


def test_the_page_is_answered_first_with_its_labels_at_the_shown_sample_then_along_the_cycle(shears):
    """Opening a file: placing the labels at all 360 samples took 2.4 s of the shears' first answer (0.15 s
    before labels were placed).  The first answer places them at the first sample (the one shown), the next at
    every eighth; an exported page at every one (above); a bad ``labels`` is refused."""
    first = shears.get("/api/cycle?labels=first").json()
    assert first["labels_placed"] == 1 and first["steps"] == 360
    cycle = shears.get("/api/cycle").json()
    assert cycle["labels_placed"] == 45
    assert first["positions"] == cycle["positions"]
    r = shears.get("/api/cycle?labels=everywhere")
    assert r.status_code == 422 and "first" in r.json()["error"]


def test_labels_between_the_samples_placed_keep_their_offsets_from_the_points_they_name(shears_cycle, shears):
    """Placed every eighth sample of 360, a point's label is, at every sample, as far from that point (where
    lw.kinematics puts it) as at the nearest sample placed along the turn, which closes on itself; where placed,
    the label is off its point."""
    kin = lw.kinematics(SHEARS, _turn(SHEARS, 360))
    i = np.arange(360)
    nearest = (8 * np.round(i / 8).astype(int)) % 360  # 356 to 359 are nearer to 0 than to 352
    nearest[i % 8 == 4] = i[i % 8 == 4] - 4  # halfway: the earlier one
    checked = 0
    for lab in shears_cycle["scene"]["labels"]:
        if lab["kind"] != "point" or lab["text"] not in {"O1", "A", "B", "O3", "C", "D", "E", "F"}:
            continue
        centre = np.array([[np.nan, np.nan] if c is None or c[0] is None else c for c in lab["centre"]])
        offset = centre - kin.position(lab["text"])
        np.testing.assert_allclose(offset, offset[nearest], rtol=0, atol=1.1e-5, err_msg=lab["text"])  # 10 um: JSON
        assert (np.hypot(*offset[::8].T) > 0.003).all(), lab["text"]
        checked += 1
    assert checked == 8


@pytest.mark.parametrize("name", ["double-cut-shears", "four-bar", "shears-slider-crank"])
def test_the_viewer_numbers_the_cycle_from_position_0_as_the_report_does(name):
    """The first sample is position 0, the working member at the high end of its stroke (the shears' upper
    knife up: largest y, at rest), and the page's angle turned is the report's φ: the crank's angle to x less
    position 0's, in the drive's direction, 0 to 360."""
    mech = lw.compile(lw.load(name))
    payload = cycle_payload(mech, steps=360)
    out = working(mech)[0]

    def coordinate(kin):  # the slider's along its guide (m), or the rocker's angle (rad)
        if out.kind == "rocker":
            return kin.angle(int(out.link))
        origin, axis = guide(kin, out.pair)
        return np.sum((kin.position(mech.point_names[out.point]) - origin[0]) * axis[0], axis=-1)

    s = coordinate(lw.kinematics(mech, np.radians(payload["angles_deg"])))
    fine = coordinate(lw.kinematics(mech, steps=36000))
    assert s[0] == pytest.approx(fine.max(), abs=1e-9) and s[0] >= s.max() - 1e-12
    zero = math.radians(payload["angles_deg"][0])
    phi = np.degrees(np.mod(direction(mech) * (np.radians(payload["angles_deg"]) - zero), 2 * math.pi))
    np.testing.assert_allclose(payload["turn_deg"], phi, atol=1e-6)
    assert payload["turn_deg"][0] == 0


def test_the_exported_series_are_written_as_the_command_line_writes_numbers(tmp_path):
    """The page's series, read back from the exported file, are the driving torque and foundation forces of
    lw.forces to 12 significant digits (not 9), and the round-off beside a zero (the isosceles slider-crank's
    torque and foundation at its change points) is the 0 the command line's JSON writes, never -0.0."""
    from linkwork.io import jsonout

    out = export_page("shears-slider-crank", tmp_path / "page.html", steps=72)
    data = _embedded(out.read_text(encoding="utf-8"))
    mech = lw.compile(lw.load("shears-slider-crank"))
    f = lw.forces(mech, _turn(mech, 72))
    for key, want in (("torque", f.driving_torque), ("foundation:fx", f.foundation[:, 0])):
        got = next(s for s in data["series"] if s["key"] == key)["values"]
        np.testing.assert_allclose(got, want, rtol=1e-11, atol=1e-9 * np.abs(want).max())
        assert not any(v == 0 and math.copysign(1.0, v) < 0 for v in got)
        assert got == json.loads(jsonout.dumps(want))  # what --json writes of the same numbers


def test_a_request_whose_head_never_ends_is_closed_and_others_are_answered():
    """Slow clients (slowloris): a connection that sends half a request's head and then nothing, one that
    sends nothing, and one that sends half the head of its second request after an answer, are closed
    within the head timeout (1 s here) and a little; a whole request on another connection meanwhile is
    answered."""
    pytest.importorskip("uvicorn")
    import socket
    import time

    from webserver import serving

    with serving(create_app("four-bar", steps=36), head_timeout=1.0) as (host, port):
        request = f"GET /api/parameters HTTP/1.1\r\nHost: {host}\r\n\r\n".encode()
        slow = [socket.create_connection((host, port), timeout=10) for _ in range(3)]
        slow[0].sendall(request[:30])
        slow[2].sendall(request)
        assert slow[2].recv(4096).startswith(b"HTTP/1.1 200")
        slow[2].sendall(request[:30])
        start = time.monotonic()
        with socket.create_connection((host, port), timeout=10) as good:
            good.sendall(request)
            assert good.recv(4096).startswith(b"HTTP/1.1 200")
        for sock in slow:
            with sock:
                assert sock.recv(4096) == b""  # closed by the server
        assert time.monotonic() - start < 1.0 + 3.0


def test_a_pose_is_answered_while_an_edit_is_solved():
    """An edit that takes long (1 s here, held in the solver) does not hold up a pose sent after it on another
    connection: the pose is answered while the edit is still being solved (edits are solved off the event
    loop), and the edit's answer comes after."""
    pytest.importorskip("uvicorn")
    import http.client
    import threading
    import time

    from webserver import serving

    app = create_app("four-bar", steps=36)
    viewer = app.state.viewer
    solve, started = viewer.edit, threading.Event()

    def slow_edit(*args, **kwargs):
        started.set()
        time.sleep(1.0)
        return solve(*args, **kwargs)

    viewer.edit = slow_edit
    with serving(app) as (host, port):
        done = {}

        def edit() -> None:
            conn = http.client.HTTPConnection(host, port, timeout=30)
            conn.request(
                "POST",
                "/api/edit",
                json.dumps({"overrides": {"links.crank.length": 0.101}}),
                {"Content-Type": "application/json"},
            )
            done["edit"] = (conn.getresponse().status, time.monotonic())

        thread = threading.Thread(target=edit)
        thread.start()
        assert started.wait(10)
        conn = http.client.HTTPConnection(host, port, timeout=30)
        conn.request("POST", "/api/pose", json.dumps({"angle_deg": 30.0}), {"Content-Type": "application/json"})
        r = conn.getresponse()
        posed = time.monotonic()
        assert r.status == 200 and "edit" not in done
        thread.join(30)
        assert done["edit"][0] == 200 and done["edit"][1] > posed


def test_the_work_of_a_client_that_left_while_it_waited_is_not_started(monkeypatch):
    """The slot for whole cycles is held by a long solve; ten clients ask for a cycle each and leave before their
    turn.  None of their cycles is solved once the slot frees (each used to be, one after another, so that a
    viewer asked to stop waited for minutes of work nobody would read); a client that stays is answered."""
    import http.client
    import threading

    import httpx

    pytest.importorskip("uvicorn")
    from linkwork.web.session import Viewer
    from webserver import serving

    started: list[int | None] = []
    release = threading.Event()
    solve = Viewer.cycle

    def counted(self, overrides=None, steps=None, **kwargs):
        started.append(steps)
        if steps == 37:  # the long solve: holds the slot until the clients have left
            release.wait(30)
        return solve(self, overrides, steps, **kwargs)

    app = create_app("four-bar", steps=36)
    monkeypatch.setattr(Viewer, "cycle", counted)
    with serving(app) as (host, port):
        url = f"http://{host}:{port}/api/solve"
        holder = threading.Thread(target=lambda: httpx.post(url, json={"steps": 37}, timeout=60))
        holder.start()
        while not started:
            time.sleep(0.01)
        body = b'{"steps": 40}'
        head = "POST /api/solve HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\n"
        for _ in range(10):
            with socket.create_connection((host, port)) as s:
                s.sendall(f"{head}Content-Length: {len(body)}\r\n\r\n".encode() + body)
                time.sleep(0.05)  # its request is read and waits for the slot; then the client leaves
        time.sleep(0.5)
        release.set()
        holder.join(30)
        conn = http.client.HTTPConnection(host, port, timeout=30)
        conn.request("POST", "/api/solve", body=b'{"steps": 41}', headers={"Content-Type": "application/json"})
        assert conn.getresponse().status == 200
        conn.close()
    assert started == [37, 41]


def test_a_springs_force_is_an_arrow_of_the_viewer():
    """A spring from the four-bar's coupler point B to the frame's O2: one load arrow, on the coupler at B, whose
    value is k (L - L0) along B -> O2 at every angle (L from the positions)."""
    text = example_text("four-bar").replace(
        "hints:",
        "loads:\n  s: {type: spring, between: [coupler.B, O2], stiffness: 2000 N/m, free_length: 200 mm}\nhints:",
        1,
    )
    mech = lw.compile(lw.loads(text))
    f = cycle_payload(mech, steps=24)["forces"]
    cut = [j for j, a in enumerate(f["arrows"]) if a["kind"] == "load"]
    assert [(f["arrows"][j]["name"], f["arrows"][j]["on"]) for j in cut] == [("s", "coupler")]
    values = np.array([[[np.nan if v is None else v for v in xy] for xy in row] for row in f["values"]])[:, cut[0]]
    kin = lw.kinematics(mech, _turn(mech, 24))
    d = kin.position("O2") - kin.position("B")
    length = np.hypot(d[:, 0], d[:, 1])
    np.testing.assert_allclose(values, (2000 * (length - 0.2) / length)[:, None] * d, rtol=1e-6, atol=1e-6)


def test_a_toggle_whose_swing_ends_on_the_guide_keeps_its_mode_in_every_route():
    """A toggle press whose upper link swings 89.9999 deg: at its assembly pose (the top of the swing) the ram's
    dyad's two modes are 35 nm apart.  That is no change point: the upper link itself is at rest there (the rocker's
    dead point), so the gap between the modes grows as the square of the time either side and the motion keeps its
    mode.  With upper and lower links of equal length and the ram on the vertical through P, the ram is at twice the
    knee's height (the other mode would leave it at P): the cycle, the viewer's poses and a run in time all put it
    there, and ``check`` warns that the assembly pose is on the dyad's singular position."""
    from pathlib import Path

    from linkwork.cli.main import app
    from linkwork.machine.reduction import cycle_of, poses
    from linkwork.web.cycle import solve_cycle

    path = Path(__file__).with_name("toggle-at-dead-centre.yaml")
    mech = lw.compile(str(path))
    cycle = solve_cycle(mech, 360).kin
    assert not [e for e in cycle.events if e.kind == "change-point"]
    knee, ram = cycle.position("K"), cycle.position("R")
    np.testing.assert_allclose(ram, np.column_stack([0 * ram[:, 0], 2 * knee[:, 1]]), atol=1e-12)
    assert ram[:, 1].min() == pytest.approx(-0.020, abs=1e-6)  # the stroke of the file, H = 20 mm
    client = TestClient(create_app(lw.load(str(path))), base_url=LOCAL)
    pick = [64, 164, 264, 359]
    angles = cycle.angles[pick]
    for a, r in zip(np.degrees(angles), ram[pick], strict=True):
        got = client.post("/api/pose", json={"angle_deg": float(a)}).json()["points"]["ram.R"]
        np.testing.assert_allclose(got, r, atol=1e-9)
    alone = poses(cycle_of(mech), angles[::-1, None], np.ones((4, 1)), np.zeros((4, 1)))
    np.testing.assert_allclose(alone.position("R"), ram[pick][::-1], atol=1e-12)
    out = runner.invoke(app, ["check", str(path)])
    assert out.exit_code == 0
    said = " ".join(out.output.split())
    assert "group II(4,5) RRP is on a singular position in the assembly pose (crank at 36.9316 deg" in said
