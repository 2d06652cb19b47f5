"""The viewer's force plans and Zhukovsky's lever (:mod:`linkwork.web.force_plans`): what the payload carries.

Each group's plan, read back from the payload's coordinates (mm of the sheet), closes head to tail; the lever's
balancing force, read off its arrow and its scale, is the driving torque of :func:`linkwork.forces` at the same
crank angle over the crank's length measured on the positions.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("fastapi")
from fastapi.testclient import TestClient  # noqa: E402

import linkwork as lw  # noqa: E402
from linkwork.web import create_app, export_page  # noqa: E402

LOCAL = "http://127.0.0.1"
NAME = "double-cut-shears"


@pytest.fixture(scope="module")
def shears():
    return TestClient(create_app(lw.load(NAME)), base_url=LOCAL)


@pytest.fixture(scope="module")
def cycle(shears):
    return shears.get("/api/cycle?labels=first").json()


def _at(client, index, overrides=None):
    r = client.post("/api/force-plans", json={"index": index, "overrides": overrides or {}})
    assert r.status_code == 200, r.text
    return r.json()


def _vector(arrow):
    return np.subtract(arrow["end"], arrow["start"])


def test_the_payload_names_each_group_and_the_lever(cycle):
    part = cycle["force_plans"]
    mech = lw.compile(lw.load(NAME))
    assert part["available"]
    assert part["samples"] == [] and part["at"] == []  # the live page asks for the sample it shows
    keys = [g["key"] for g in part["groups"]]
    assert keys == [f"group:{k}" for k in range(len(mech.structure.groups))] + ["lever"]
    titles = [g["title"] for g in part["groups"]]
    assert titles[0].startswith("II(6,7)") and titles[-2].startswith("driving link I(0,1)")  # the last group first


@pytest.mark.parametrize("index", [10, 90, 200, 300])
def test_each_force_plan_closes_in_the_payloads_coordinates(shears, index):
    sample = _at(shears, index)["at"][0]
    assert sample["index"] == index
    plans = [d for d in sample["drawings"] if d["kind"] == "force_plan"]
    assert len(plans) == 4
    for d in plans:
        polygon = [a for a in d["arrows"] if not a["resultant"]]
        assert len(polygon) >= 3
        vectors = np.array([_vector(a) for a in polygon])
        largest = np.hypot(*vectors.T).max()
        # head to tail from the pole, and back to it: the polygon closes (an arrow that runs back over the one
        # before it drawn beside it, a thin line of the drawing's joining each of its ends to its vertex)
        joins = np.asarray(d["lines"], dtype=float).reshape(-1, 2, 2)
        for a, b in zip(polygon, polygon[1:], strict=False):
            meet = np.hypot(*np.subtract(b["start"], a["end"])) < 1e-9 * largest
            joined = any(
                np.allclose(j[0], a["end"], atol=1e-9 * largest) and np.allclose(j[1], b["start"], atol=1e-9 * largest)
                for j in joins
            )
            assert meet or joined
        assert np.hypot(*vectors.sum(0)) < 1e-9 * largest, (index, d["extent"])
        assert polygon[0]["start"] == [0.0, 0.0]
        # each arrow is its force over the plan's scale μF
        for a in d["arrows"]:
            assert abs(np.hypot(*_vector(a)) * d["scale"] - a["value"]) < 1e-9 * a["value"]


@pytest.mark.parametrize("index", [10, 90, 200, 300])
def test_the_levers_balancing_force_is_the_driving_torque_over_the_crank(shears, cycle, index):
    mech = lw.compile(lw.load(NAME))
    angle = math.radians(cycle["angles_deg"][index])
    torque = float(lw.forces(mech, [angle]).driving_torque[0])
    kin = lw.kinematics(mech, [angle])
    crank = float(np.hypot(*(kin.position("A")[0] - kin.position("O1")[0])))
    lever = _at(shears, index)["at"][0]["drawings"][-1]
    assert lever["kind"] == "lever"
    (fb,) = [a for a in lever["arrows"] if a["kind"] == "balancing"]
    force = np.hypot(*_vector(fb)) * lever["scale"]
    assert force == pytest.approx(abs(torque) / crank, rel=1e-9)
    assert lever["balancing"] == pytest.approx(torque, rel=1e-9)
    # normal to the crank, as the pin's velocity is
    v, arrow = kin.velocity("A")[0], _vector(fb)
    assert abs(arrow[0] * v[1] - arrow[1] * v[0]) < 1e-9 * np.hypot(*arrow) * np.hypot(*v)


def test_an_edit_draws_the_edited_mechanisms_plans(shears):
    before = _at(shears, 90)["at"][0]["drawings"][0]
    after = _at(shears, 90, {"links.knife_lower.mass": 400.0})["at"][0]["drawings"][0]
    names = {a["text"] for a in before["arrows"]}
    assert {a["text"] for a in after["arrows"]} == names
    assert before["arrows"] != after["arrows"]


def test_a_sample_outside_the_cycle_is_refused_with_a_message(shears):
    r = shears.post("/api/force-plans", json={"index": 360})
    assert r.status_code == 422
    assert "outside the cycle" in r.json()["error"]


def test_the_exported_page_carries_the_drawings_of_some_samples(tmp_path):
    import json
    import re

    text = export_page("four-bar", tmp_path / "four-bar.html", steps=72).read_text(encoding="utf-8")
    data = json.loads(re.search(r'id="linkwork-data">(.*?)</script>', text, re.S).group(1))
    part = data["force_plans"]
    assert part["samples"] == list(range(0, 72, 2))
    assert [s["index"] for s in part["at"]] == part["samples"]
    assert all(len(s["drawings"]) == 3 for s in part["at"])  # the dyad's plan, the crank's and the lever
