"""``linkwork forces`` and ``linkwork balance`` on the command line."""

from __future__ import annotations

import csv
import json

import numpy as np
import pytest
from typer.testing import CliRunner

import linkwork.cli.forces  # noqa: F401 - registers the commands
from linkwork.cli.main import app

runner = CliRunner()


def test_forces_json_of_the_shears_at_rest_by_hand():
    """Crank and rod stand vertical at 90 deg: the rod holds the knife's weight, the crank pivot
    the weight of all three, and gravity has no lever arm about O: no driving torque."""
    result = runner.invoke(app, ["forces", "shears-slider-crank", "--angles", "90", "--speed", "0 rpm", "--json"])
    assert result.exit_code == 0, result.output
    out = json.loads(result.stdout)
    assert set(out) >= {"phi_deg", "crank_angle_to_x_deg", "driving_torque", "joints", "foundation", "checks"}
    assert out["crank_angle_to_x_deg"] == [90.0]
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
    assert header[:3] == ["phi [deg]", "crank_angle_to_x [deg]", "driving_torque [N m]"]
    assert "O3 (frame on rocker).fx [N]" in header and "load.cutting [N]" in header
    assert len(rows) == 37
    data = json.loads((tmp_path / "forces.json").read_text(encoding="utf-8"))
    torque = np.array([float(r[2]) for r in rows[1:]])
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


def test_forces_json_and_csv_give_the_drive_joint_in_the_files_order(tmp_path):
    """The four-bar with its drive written ``O2: links: [crank, frame]``: the table gives the crank's force on
    the frame, by Newton's law on the crank (1 kg at mid-length, 60 rpm ccw: a_C = -omega^2 r_C) with the
    coupler's force on it (-A, the crank's on the coupler) from the same table."""
    from linkwork.examples import text

    path = tmp_path / "four-bar.yaml"
    path.write_text(text("four-bar").replace("links: [frame, crank]", "links: [crank, frame]"), encoding="utf-8")
    result = runner.invoke(app, ["forces", str(path), "--angles", "0,60,135,250", "--json", "--out", str(tmp_path)])
    assert result.exit_code == 0, result.output
    out = json.loads(result.stdout)
    assert out["joints"]["O2"]["links"] == ["crank", "frame"]
    assert out["joints"]["A"]["links"] == ["crank", "coupler"]
    phi = np.radians(out["crank_angle_to_x_deg"])
    a_c = -((2 * np.pi) ** 2) * 0.05 * np.stack([np.cos(phi), np.sin(phi)], -1)
    crank_on_coupler = np.stack([out["joints"]["A"]["fx"], out["joints"]["A"]["fy"]], -1)
    frame_on_crank = 1.0 * a_c - np.array([0.0, -9.81]) + crank_on_coupler
    crank_on_frame = np.stack([out["joints"]["O2"]["fx"], out["joints"]["O2"]["fy"]], -1)
    np.testing.assert_allclose(crank_on_frame, -frame_on_crank, rtol=1e-12, atol=1e-9)
    with open(tmp_path / "forces.csv", encoding="utf-8") as fh:
        rows = list(csv.reader(fh))
    column = rows[0].index("O2 (crank on frame).fx [N]")
    csv_fx = [float(r[column]) for r in rows[1:]]
    np.testing.assert_allclose(csv_fx, crank_on_frame[:, 0], rtol=1e-11)  # from JSON numbers of 12 digits


def test_forces_json_of_a_compound_hinge_and_a_pin_in_a_slot():
    """Each pair of the hinge B (the rocker carries the pin) as the file orders its two links, against the
    free body of each member; a pin in a slot once, as the slot's force on the pin."""
    import linkwork as lw
    from linkwork.io.force_tables import to_json
    from mechanisms import forces_on_b, heavy_compound_hinge, pin_in_slot

    f = lw.forces(heavy_compound_hinge(("coupler", "rocker", "rod")), steps=12)
    joints, on = to_json(f)["joints"], forces_on_b(f)
    assert {k: v["links"] for k, v in joints.items() if k.startswith("B")} == {
        "B:coupler": ["coupler", "rocker"],
        "B:rod": ["rocker", "rod"],
    }
    np.testing.assert_allclose(joints["B:coupler"]["fx"], -on["coupler"][:, 0], rtol=1e-9, atol=1e-7)
    np.testing.assert_allclose(joints["B:rod"]["fy"], on["rod"][:, 1], rtol=1e-9, atol=1e-7)
    data = pin_in_slot().to_dict()
    data["links"]["crank"]["mass"] = 2.0
    data["links"]["rocker"].update(mass=4.0, com=[0.25, 0], inertia=0.08)
    f = lw.forces(lw.compile(lw.from_dict(data)), steps=12)
    joints = to_json(f)["joints"]
    assert sorted(joints) == ["O1", "O2", "slot"]
    assert (joints["slot"]["type"], joints["slot"]["links"]) == ("pin-in-slot", ["rocker", "crank"])
    a_c = 0.5 * f.kinematics.acceleration("crank.A")
    frame_on_crank = np.stack([joints["O1"]["fx"], joints["O1"]["fy"]], -1)
    slot_on_pin = 2.0 * a_c - np.array([0.0, -2.0 * 9.81]) - frame_on_crank
    assert np.abs(slot_on_pin).max() > 10.0
    np.testing.assert_allclose(np.stack([joints["slot"]["fx"], joints["slot"]["fy"]], -1), slot_on_pin, atol=1e-9)
