"""The viewer's family of a synthesised file (GET /api/family; slider-crank, crank-rocker, double-cut shears): each
member an edit of named parameters that the viewer solves, every member, measured on its own, with the
requirements asked for, the member shown that of the file; a file without requirements has none."""

from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("fastapi")
pytest.importorskip("httpx")

from fastapi.testclient import TestClient  # noqa: E402

import linkwork as lw  # noqa: E402
from linkwork.synthesis import synthesize  # noqa: E402
from linkwork.units import parse_quantity  # noqa: E402
from linkwork.web import create_app  # noqa: E402

LOCAL = "http://127.0.0.1"


def test_each_member_of_the_family_keeps_the_stroke_and_time_ratio_and_the_viewer_solves_it(tmp_path):
    path = synthesize("slider-crank", stroke=0.4, time_ratio=1.3, min_transmission_angle=math.radians(30)).write(
        tmp_path / "press.yaml"
    )
    client = TestClient(create_app(lw.load(str(path))), base_url=LOCAL)
    r = client.get("/api/family")
    assert r.status_code == 200, r.text
    f = r.json()
    members = f["overrides"]
    assert len(members) >= 30 and f["parameter"] == "angle O B1 B2"
    picked = members[f["picked"]]
    spec = lw.load(str(path))
    assert picked["links.crank.length"] == pytest.approx(spec.links["crank"].length, rel=0.05)
    theta = math.pi * 0.3 / 2.3
    for m, beta in zip(members[::8], f["values"][::8], strict=True):
        # the law of sines on O B1 B2: l + r = H sin(theta + beta) / sin(theta), l - r = H sin(beta) / sin(theta)
        b = math.radians(beta)
        far, near = 0.4 * math.sin(theta + b) / math.sin(theta), 0.4 * math.sin(b) / math.sin(theta)
        assert m["links.rod.length"] + m["links.crank.length"] == pytest.approx(far, rel=1e-12)
        assert m["links.rod.length"] - m["links.crank.length"] == pytest.approx(near, rel=1e-12)
        solved = client.post("/api/solve", json={"overrides": m, "steps": 360})
        assert solved.status_code == 200, solved.text
    variants = {k: np.array([m[k] for m in members]) for k in members[0]}
    kin = lw.kinematics(spec, steps=720, variants=variants)
    from linkwork.motion.analysis import extremes

    for v in range(len(members)):
        (e,) = extremes(kin, v)
        assert e.stroke == pytest.approx(0.4, rel=1e-9) and e.time_ratio == pytest.approx(1.3, rel=1e-8)


def test_a_file_without_requirements_has_no_family():
    client = TestClient(create_app("four-bar"), base_url=LOCAL)
    assert client.get("/api/family").json() == {"overrides": []}


def _closed_form(a: float, b: float, c: float, d: float) -> tuple[float, float]:
    """(swing, K) of a crank-rocker from its lengths alone: the rocker's angles at the stretched (|O2 B| = b + a)
    and folded (b - a) positions by the law of cosines in O2 B O4, and the crank's angle theta between them."""
    at_o4 = [math.acos((c * c + d * d - q * q) / (2 * c * d)) for q in (b + a, b - a)]
    at_o2 = [math.acos((q * q + d * d - c * c) / (2 * q * d)) for q in (b + a, b - a)]
    theta = abs(at_o2[0] - at_o2[1])
    return abs(at_o4[0] - at_o4[1]), (math.pi + theta) / (math.pi - theta)


@pytest.mark.parametrize(
    ("ratio", "given"),
    [
        (1.3, {"rocker": 0.3, "min_transmission_angle": math.radians(10)}),
        (1.3, {"frame": 0.5, "min_transmission_angle": math.radians(10)}),
        (1.0, {"rocker": 0.3, "min_transmission_angle": math.radians(30)}),
    ],
)
def test_each_crank_rocker_member_keeps_the_swing_and_time_ratio_on_the_files_side(tmp_path, ratio, given):
    swing = math.radians(50.0)
    path = synthesize("crank-rocker", swing=swing, time_ratio=ratio, **given).write(tmp_path / "rocker.yaml")
    spec = lw.load(str(path))
    client = TestClient(create_app(spec), base_url=LOCAL)
    f = client.get("/api/family").json()
    members = f["overrides"]
    assert len(members) >= 30 and f["parameter"] == "|O2 B_f|" and "side" in f["note"]
    own = members[f["picked"]]  # the exact member the file's lengths, written to 0.1 mm, round
    assert abs(own["links.crank.length"] - spec.links["crank"].length) <= 0.05e-3 + 1e-12
    assert abs(own["frame.points.O4.x"] - spec.frame.points["O4"][0]) <= 0.05e-3 + 1e-12
    name, fixed = ("links.rocker.length", 0.3) if "rocker" in given else ("frame.points.O4.x", 0.5)
    assert all(m[name] == pytest.approx(fixed, rel=1e-12) for m in members)
    # every member meets the rule; the file's own (kept whatever it measures) within the tolerance its rounding to
    # 0.1 mm implies
    rule = max(10.0, math.degrees(given.get("min_transmission_angle", 0)))
    others = [q for i, q in enumerate(f["quantity_values"]) if i != f["picked"]]
    assert min(others) >= rule - 1e-6
    tol = parse_quantity(spec.requirements["min_transmission_angle_tolerance"], "angle")
    assert f["quantity_values"][f["picked"]] >= rule - math.degrees(tol) - 1e-6
    for m, t in zip(members, f["values"], strict=True):
        a, b, c, d = (
            m[k] for k in ("links.crank.length", "links.coupler.length", "links.rocker.length", "frame.points.O4.x")
        )
        assert (b - a) * 1e3 == pytest.approx(t, rel=1e-12)
        assert _closed_form(a, b, c, d) == pytest.approx((swing, ratio), rel=1e-12)
    assert client.post("/api/solve", json={"overrides": members[-1], "steps": 360}).status_code == 200
    variants = {k: np.array([m[k] for m in members]) for k in members[0]}
    kin = lw.kinematics(spec, steps=720, variants=variants)
    from linkwork.motion.analysis import extremes, transmission

    (file_e,) = extremes(lw.kinematics(spec, steps=720))
    least = np.degrees(np.nanmin(next(iter(transmission(kin).values())), axis=-1))
    for v in range(len(members)):
        (e,) = extremes(kin, v)
        assert e.stroke == pytest.approx(swing, rel=1e-9) and e.time_ratio == pytest.approx(ratio, rel=1e-9)
        # the slow stroke turns the rocker the same way as the file's: the file's side of the chord
        # (the file's lengths written to 0.1 mm: within its K tolerance)
        k_tol = float(spec.requirements["time_ratio_tolerance"])
        assert e.forward_time_ratio == pytest.approx(file_e.forward_time_ratio, abs=k_tol)
    assert least == pytest.approx(f["quantity_values"], abs=0.05)


@pytest.mark.slow
def test_each_shears_member_meets_the_knives_requirements(tmp_path):
    from linkwork.design.evaluate import Evaluation
    from linkwork.design.metrics import METRICS
    from linkwork.motion.analysis import extremes

    s = synthesize("double-cut-shears", upper_stroke=0.14, lower_stroke=0.12, time_ratio=1.1, overlap=0.02)
    path = s.write(tmp_path / "shears.yaml")
    spec = lw.load(str(path))
    f = TestClient(create_app(spec), base_url=LOCAL).get("/api/family").json()
    members = f["overrides"]
    assert len(members) >= 5 and f["parameter"] == "crank length"
    assert abs(members[f["picked"]]["links.crank.length"] - spec.links["crank"].length) <= 0.05e-3 + 1e-12
    variants = {k: np.array([m[k] for m in members]) for k in members[0]}
    kin = lw.kinematics(spec, steps=720, variants=variants)
    ev = Evaluation(kin)
    ratio = np.ravel(METRICS["working_time_ratio"].compute(ev, None))
    overlap = np.ravel(METRICS["knife_overlap"].compute(ev, None))
    for v in range(len(members)):
        strokes = {e.name: e.stroke for e in extremes(kin, v)}
        assert strokes["guide_E"] == pytest.approx(0.14, rel=1e-9)
        assert strokes["guide_F"] == pytest.approx(0.12, rel=1e-9)
        assert ratio[v] == pytest.approx(1.1, rel=1e-9) and overlap[v] == pytest.approx(0.02, abs=0.26e-9)
    assert len({m["links.crank.length"] for m in members}) == len(members)


def test_a_crank_rocker_edited_off_its_family_still_has_it_with_the_member_nearest_picked(tmp_path):
    import re

    path = synthesize(
        "crank-rocker", swing=math.radians(50.0), time_ratio=1.3, rocker=0.3, min_transmission_angle=0.2
    ).write(tmp_path / "r.yaml")
    text = re.sub(r"(coupler:\n\s+ends: \[A, B\]\n\s+length: )[0-9.]+", r"\g<1>650", path.read_text())
    path.write_text(re.sub(r"O4: \[[0-9.]+, 0.0\]", "O4: [600, 0]", text))
    spec = lw.load(str(path))
    assert spec.links["coupler"].length == 0.65 and spec.frame.points["O4"][0] == 0.6
    f = TestClient(create_app(spec), base_url=LOCAL).get("/api/family").json()
    # |O2 B_f| = b - a = 650 mm - a: beyond the family's crank-rockers of this swing and K (under 0.52 m)
    t = np.array(f["values"]) / 1e3
    assert t.max() < 0.65 - spec.links["crank"].length and f["picked"] == len(t) - 1


def test_the_russian_viewer_says_the_family_in_russian_with_the_same_members(tmp_path):
    """``view --lang ru``: the slider's parameter, criterion, note and units in Russian, the members and values
    those of the English page (the same family, only its words translated)."""
    path = synthesize("slotted-lever", stroke=0.5, time_ratio=1.4).write(tmp_path / "shaper.yaml")
    en, ru = (
        TestClient(create_app(lw.load(str(path)), lang=lang), base_url=LOCAL).get("/api/family").json()
        for lang in ("en", "ru")
    )
    assert (ru["parameter"], ru["unit_shown"], ru["quantity_unit_shown"]) == ("стойка d", " мм", " мм")
    assert ru["quantity"] == "наименьшее расстояние камня от оси кулисы" and "ходом" in ru["note"]
    assert (en["parameter"], en["unit_shown"]) == ("frame d", " mm") and "stroke" in en["note"]
    assert ru["overrides"] == en["overrides"] and ru["values"] == en["values"] and ru["picked"] == en["picked"]


def test_each_slotted_lever_member_keeps_the_stroke_and_time_ratio(tmp_path):
    """A crank-shaper for H = 500 mm, K = 1.4: the members over the frame d, each with r = d sin(theta / 2)
    (theta = 180 deg (K - 1) / (K + 1) = 30 deg), solved together as variants of the file, each measured on its
    own: the ram's stroke and K as asked; the file's own member is the one picked."""
    from linkwork.motion.analysis import extremes

    path = synthesize("slotted-lever", stroke=0.5, time_ratio=1.4).write(tmp_path / "shaper.yaml")
    spec = lw.load(str(path))
    f = TestClient(create_app(spec), base_url=LOCAL).get("/api/family").json()
    members = f["overrides"]
    assert len(members) >= 30 and f["quantity_unit"] == "mm" and f["quantity_unit_shown"] == " mm"
    for m in members:
        assert m["links.crank.length"] == pytest.approx(m["frame.points.O1.y"] * math.sin(math.radians(15)), rel=1e-12)
    assert members[f["picked"]]["frame.points.O1.y"] == pytest.approx(spec.frame.points["O1"][1], rel=0.03)
    chosen = members[2::6]
    variants = {k: np.array([m[k] for m in chosen]) for k in chosen[0]}
    kin = lw.kinematics(spec, steps=720, variants=variants)
    for v in range(len(chosen)):
        (e,) = [x for x in extremes(kin, v) if x.name == "guide"]  # the ram along its guide
        # H = 2 L sin(theta / 2) of the file's lever L (written to 0.1 mm), whatever the member's frame
        stroke = 2 * spec.links["lever"].length * math.sin(math.radians(15))
        assert e.stroke == pytest.approx(stroke, rel=1e-9) and e.time_ratio == pytest.approx(1.4, rel=1e-8)


def test_simultaneous_first_calls_of_the_family_wait_for_one_computation(tmp_path, monkeypatch):
    """20 requests at once on a real server, before any answer: the family is computed once (counted), every
    answer the same, and the wall time that of about one computation (each held 0.5 s), not twenty."""
    import http.client
    import json
    import threading
    import time

    from linkwork.synthesis import achieved
    from webserver import serving

    path = synthesize("slider-crank", stroke=0.4, time_ratio=1.25).write(tmp_path / "press.yaml")
    app = create_app(lw.load(str(path)))
    calls = []
    real = achieved.family_members

    def counted(spec, lang="en"):
        calls.append(threading.get_ident())
        time.sleep(0.5)
        return real(spec, lang)

    monkeypatch.setattr(achieved, "family_members", counted)
    answers: list[tuple[int, str]] = []
    with serving(app) as (host, port):

        def ask() -> None:
            conn = http.client.HTTPConnection(host, port, timeout=60)
            conn.request("GET", "/api/family")
            r = conn.getresponse()
            answers.append((r.status, r.read().decode()))
            conn.close()

        threads = [threading.Thread(target=ask) for _ in range(20)]
        began = time.monotonic()
        for t in threads:
            t.start()
        for t in threads:
            t.join(60)
        took = time.monotonic() - began
    assert len(calls) == 1
    assert len(answers) == 20 and {status for status, _ in answers} == {200}
    assert len({text for _, text in answers}) == 1 and json.loads(answers[0][1])["overrides"]
    assert took < 5.0


def test_a_failed_family_is_not_kept_and_every_waiter_hears_of_it():
    """The once-per-key cache: a computation that raises raises for the callers waiting on it and is tried again
    by the next call."""
    import threading
    import time

    from linkwork.web.session import _Cache

    cache, tries, errors = _Cache(1), [], []

    def failing():
        tries.append(1)
        time.sleep(0.2)
        raise lw.errors.LinkworkError("no family")

    def ask():
        try:
            cache.once("k", failing)
        except lw.errors.LinkworkError as exc:
            errors.append(str(exc))

    threads = [threading.Thread(target=ask) for _ in range(5)]
    for t in threads:
        t.start()
    for t in threads:
        t.join(10)
    assert len(tries) == 1 and errors == ["no family"] * 5
    assert cache.once("k", lambda: 42) == 42 and cache.once("k", failing) == 42
