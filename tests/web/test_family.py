"""The viewer's family of a synthesised slider-crank (GET /api/family): each member an edit of named parameters
that the viewer solves, every member with the stroke and time ratio asked for, the member shown that of the
file; a file without requirements has none."""

from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("fastapi")
pytest.importorskip("httpx")

from fastapi.testclient import TestClient  # noqa: E402

import linkwork as lw  # noqa: E402
from linkwork.synthesis import synthesize  # noqa: E402
from linkwork.web import create_app  # noqa: E402

LOCAL = "http://127.0.0.1"


def test_each_member_of_the_family_keeps_the_stroke_and_time_ratio_and_the_viewer_solves_it(tmp_path):
    path = synthesize("slider-crank", stroke=0.4, time_ratio=1.3).write(tmp_path / "press.yaml")
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
