"""``linkwork simulate``: the run in time on the command line, its JSON and its table read back."""

from __future__ import annotations

import csv
import json
import math

import numpy as np
import yaml
from typer.testing import CliRunner

import linkwork as lw
from linkwork.cli.main import app

runner = CliRunner()

PENDULUM = {
    "name": "pendulum",
    "gravity": {"value": "9.81 m/s^2", "direction": "270 deg"},
    "frame": {"points": {"O": [0, 0]}},
    "links": {"arm": {"points": {"O": [0, 0], "P": [0.4, 0]}, "mass": 2.0, "com": [0.4, 0], "inertia": "0.05 kg*m^2"}},
    "joints": {"O": {"type": "revolute", "links": ["frame", "arm"]}},
    "drives": [{"joint": "O", "angle": "270 deg"}],
    "loads": {"t": {"type": "torsion_spring", "joint": "O", "stiffness": "30 N*m/rad", "free_angle": "270 deg"}},
}


def test_simulate_writes_the_run_the_python_call_gives(tmp_path):
    path = tmp_path / "pendulum.yaml"
    path.write_text(yaml.safe_dump(PENDULUM), encoding="utf-8")
    args = ["simulate", str(path), "--until", "400 ms", "--angle", "275 deg", "--samples", "5"]
    result = runner.invoke(app, [*args, "--json", "--out", str(tmp_path / "run")])
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)
    run = lw.simulate(str(path), 0.4, angle=math.radians(275), times=np.linspace(0, 0.4, 5))
    np.testing.assert_allclose(data["samples"]["omega"], run.speed, rtol=1e-9)
    assert [e["kind"] for e in data["events"]] == ["stop"]
    with open(tmp_path / "run" / "simulate.csv", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    assert float(rows[-1]["arm.angle [deg]"]) == np.degrees(run.angle[-1])
    assert float(rows[0]["t [s]"]) == 0.0 and float(rows[-1]["t [s]"]) == 0.4
    # the free pendulum's pivot carries its weight and the centripetal force, the drive's pair nothing
    assert max(abs(x) for x in data["driving_torque"]) < 1e-9


def test_simulate_refuses_a_time_without_its_unit():
    result = runner.invoke(app, ["simulate", "four-bar", "--until", "30"])
    assert result.exit_code == 2
    assert "--until: give the unit" in result.stderr and "Traceback" not in result.output


def test_simulate_reports_the_change_points_of_the_shears_slider_crank():
    """The shears' crank and rod are of equal length on a guide through the crank's pivot: the rod stands across
    the guide (the two assembly modes meet) with the crank at 180 and 360 deg to x.  A free run from 90 deg at
    10 rad/s passes both: two ``change-point`` events of the RRP dyad at those angles, in the JSON and printed."""
    args = ["simulate", "shears-slider-crank", "--until", "600 ms", "--speed", "10 rad/s", "--no-motor"]
    result = runner.invoke(app, [*args, "--samples", "3", "--json"])
    assert result.exit_code == 0, result.output
    events = json.loads(result.stdout)["events"]
    assert [(e["kind"], e["group"]) for e in events] == [("change-point", "II(2,3) RRP")] * 2
    np.testing.assert_allclose([e["angle_deg"] for e in events], [180.0, 360.0], rtol=0, atol=1e-5)
    assert events[0]["time_s"] < events[1]["time_s"]
    printed = runner.invoke(app, [*args, "--samples", "3"])
    assert printed.exit_code == 0, printed.output
    lines = [ln.strip() for ln in printed.stdout.splitlines() if "change point" in ln]
    assert [ln.split(", at ")[1] for ln in lines] == ["180.0000 deg to x", "0.0000 deg to x"]
    assert all(ln.startswith("change point of group II(2,3) RRP at ") for ln in lines)


def test_the_shears_started_in_the_cut_finish_and_say_they_are_held():
    """The flagship example with its own motor from rest at its assembly angle (in the billet): the run of 100 ms
    ends at once, at rest, saying why (it used to step on without end at the stop)."""
    result = runner.invoke(app, ["simulate", "double-cut-shears", "--until", "100 ms", "--json"])
    assert result.exit_code == 0, result.output
    events = json.loads(result.stdout)["events"]
    assert [e["kind"] for e in events] == ["held"]
    assert "holds it" in events[0]["detail"]
    printed = runner.invoke(app, ["simulate", "double-cut-shears", "--until", "1 ms"])
    assert printed.exit_code == 0 and "the crank is held at rest from 0 s on" in printed.stdout


def test_simulate_refuses_every_length_past_its_one_bound_in_one_line():
    """``--until`` from 0 s to MAX_RUN_TIME (600 s): 1e9 s, an hour and a hundred years alike refused, with the
    bound named, before any work; the file's ``simulate: until:`` the same."""
    for text in ("1e9 s", "1 h", "100 years", "600.001 s", "0 s", "-1 ms"):
        result = runner.invoke(app, ["simulate", "four-bar", "--until", text])
        assert result.exit_code == 2, (text, result.output)
        assert result.stderr.count("\n") == 1 and "at most 600 s" in result.stderr and "Traceback" not in result.output


def test_the_progress_bar_shows_on_a_terminal_only(monkeypatch):
    """With stderr a terminal (FORCE_COLOR makes rich take it for one) a run that takes longer than the bar's
    delay draws it; piped, stderr stays empty."""
    from linkwork.cli import simulate as command

    monkeypatch.setattr(command._Bar, "AFTER", 0.0)
    args = ["simulate", "shears-slider-crank", "--until", "50 ms", "--speed", "10 rad/s", "--no-motor"]
    piped = runner.invoke(app, args)
    assert piped.exit_code == 0 and piped.stderr == ""
    monkeypatch.setenv("FORCE_COLOR", "1")
    shown = runner.invoke(app, args)
    assert shown.exit_code == 0 and "simulate" in shown.stderr and "of 0.05 s" in shown.stderr
