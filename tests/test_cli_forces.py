"""``linkwork forces`` and ``linkwork balance`` on the command line."""

from __future__ import annotations

import csv
import json

import numpy as np
import pytest
from typer.testing import CliRunner

import linkwork.cli.forces  # noqa: F401 - registers the commands
from linkwork.cli.app import app

runner = CliRunner()


def test_forces_json_of_the_shears_at_rest_by_hand():
    """Crank and rod stand vertical at 90 deg: the rod holds the knife's weight, the crank pivot
    the weight of all three, and gravity has no lever arm about O: no driving torque."""
    result = runner.invoke(app, ["forces", "shears-slider-crank", "--angles", "90", "--speed", "0 rpm", "--json"])
    assert result.exit_code == 0, result.output
    out = json.loads(result.stdout)
    assert set(out) >= {"angles_deg", "driving_torque", "joints", "foundation", "checks", "convention"}
    assert out["angles_deg"] == [pytest.approx(90.0)]
    g = 9.81
    assert out["joints"]["B"]["links"] == ["rod", "knife"]
    assert out["joints"]["B"]["fy"][0] == pytest.approx(20 * g, rel=1e-12)
    assert out["joints"]["B"]["fx"][0] == pytest.approx(0, abs=1e-9)
    assert out["joints"]["O"]["fy"][0] == pytest.approx(40 * g, rel=1e-12)
    assert out["joints"]["guide"]["fx"][0] == pytest.approx(0, abs=1e-9)
    assert "moment" in out["joints"]["guide"] and "moment" not in out["joints"]["O"]
    assert out["driving_torque"][0] == pytest.approx(0, abs=1e-9)
    assert out["foundation"]["fy"][0] == pytest.approx(-540 * g, rel=1e-12)  # housing included, pressing down
    assert "first-named link exerts on the second" in out["convention"]


def test_forces_out_writes_csv_and_json(tmp_path):
    result = runner.invoke(app, ["forces", "double-cut-shears", "--steps", "36", "--out", str(tmp_path)])
    assert result.exit_code == 0, result.output
    assert "driving torque: peak" in result.stdout
    with open(tmp_path / "forces.csv", encoding="utf-8") as fh:
        rows = list(csv.reader(fh))
    header = rows[0]
    assert header[:2] == ["angle [deg]", "driving_torque [N m]"]
    assert "O3 (frame on rocker).fx [N]" in header and "load.cutting [N or N m]" in header
    assert len(rows) == 37
    data = json.loads((tmp_path / "forces.json").read_text(encoding="utf-8"))
    torque = np.array([float(r[1]) for r in rows[1:]])
    np.testing.assert_allclose(torque, data["driving_torque"], rtol=1e-11)  # JSON: 12 significant digits
    assert max(data["loads"]["cutting"]) == pytest.approx(250e3)
    assert all(v < 1e-9 for v in data["checks"].values())
    assert not list(tmp_path.glob(".*part"))


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--speed", "30"], 'give the unit, e.g. "30 rpm"'),
        (["--speed", "30 kg"], "--speed: expected an angular speed"),
        (["--speed", "-30 rpm"], "the direction comes from the file"),
        (["--steps", "0"], "--steps: expected a positive number"),
    ],
)
def test_forces_bad_options_exit_2(args, message):
    result = runner.invoke(app, ["forces", "four-bar", *args])
    assert result.exit_code == 2
    assert message in result.stderr
    assert "Traceback" not in result.output


def test_forces_refuses_redundant_constraints_with_a_message(tmp_path):
    from ruamel.yaml import YAML

    from mechanisms import TEXTBOOK

    path = tmp_path / "parallelogram.yaml"
    with open(path, "w", encoding="utf-8") as fh:
        YAML().dump(TEXTBOOK["parallelogram"][0]().to_dict(), fh)
    result = runner.invoke(app, ["forces", str(path)])
    assert result.exit_code == 2
    assert "statically indeterminate" in result.stderr


def test_balance_json_four_bar_and_bad_link():
    result = runner.invoke(app, ["balance", "four-bar", "--links", "crank,rocker", "--json"])
    assert result.exit_code == 0, result.output
    out = json.loads(result.stdout)
    assert [w["link"] for w in out["counterweights"]] == ["crank", "rocker"]
    assert out["after"]["shaking_force_peak"] < 1e-9 * out["before"]["shaking_force_peak"]
    bad = runner.invoke(app, ["balance", "four-bar", "--links", "coupler"])
    assert bad.exit_code == 2
    assert "does not turn about a frame pivot" in bad.stderr
    typo = runner.invoke(app, ["balance", "four-bar", "--links", "crnk"])
    assert typo.exit_code == 2 and 'did you mean "crank"' in typo.stderr


def test_forces_lift_speed_and_free_bodies_in_json():
    """The bolts start to be pulled when 2 (m1 + m2) l omega^2 reaches the weight (m + 2 m1 + m2) g."""
    result = runner.invoke(app, ["forces", "shears-slider-crank", "--steps", "72", "--pull", "0 N", "--json"])
    assert result.exit_code == 0, result.output
    out = json.loads(result.stdout)
    g, m1, m2, m, length = 9.81, 10.0, 20.0, 500.0, 0.15
    lift = ((m + 2 * m1 + m2) * g / (2 * (m1 + m2) * length)) ** 0.5
    assert out["bolts"]["speed_for_pull_rad_s"] == pytest.approx(lift, rel=1e-9)
    assert [b["group"] for b in out["groups"]] == ["I(0,1) R", "II(2,3) RRP"]
    assert out["groups"][1]["internal"] == ["B"]
    assert all(b["residual"] < 1e-12 for b in out["groups"])
    bad = runner.invoke(app, ["forces", "shears-slider-crank", "--pull", "5 kg"])
    assert bad.exit_code == 2 and "--pull: expected a force" in bad.stderr
