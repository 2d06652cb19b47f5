"""The crank angle people read: φ, turned from position 0 in the drive's direction, in [0, 360), in every
table, JSON file and printed line; the crank's angle to the x axis only under its own name.

The expected angles are derived here from the mechanism itself: the crank's angle to x from the crank pin's
written coordinates, and position 0 from its definition (the working member at the high end of its stroke or
swing) in closed form for a crank-shaper, or from a fine scan of the knife's height for the double-cut shears.
"""

from __future__ import annotations

import csv
import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

import linkwork as lw
from linkwork import MechanismBuilder
from linkwork.cli.main import app
from linkwork.examples import names

runner = CliRunner()

#: The crank-shaper's frame: the crank's pivot O1 a distance D above the rocker's pivot O2, crank R.
D, R = 0.2, 0.1


def _shaper(direction: str, angle: float = 90.0) -> MechanismBuilder:
    """A slotted-lever quick return with masses, assembled with its crank at ``angle`` deg to x (the issue's
    crank-shaper: ``forces --json`` ran from 90 to 449 deg)."""
    return (
        MechanismBuilder("crank-shaper")
        .frame(points={"O1": (0, D), "O2": (0, 0)})
        .link("crank", ends=("O1", "A"), length=R, mass=2)
        .link("block", points={"A": (0, 0)}, mass=1)
        .link("rocker", points={"O2": (0, 0), "T": (0.5, 0)}, mass=5)
        .revolute("O1", "frame", "crank")
        .revolute("A", "crank", "block")
        .prismatic("slot", "rocker", "block", point="A", through="O2", axis=0)
        .revolute("O2", "frame", "rocker")
        .drive("O1", angle=angle, speed="60 rpm", direction=direction)
        .hint("slot", R * math.cos(math.radians(angle)), D + R * math.sin(math.radians(angle)))
        .hint("rocker.T", 0, 0.5)
    )


def _shaper_zero() -> float:
    """Position 0 of the crank-shaper, deg to x: the rocker at the high end of its swing, where the slot is
    tangent to the crank circle (O2A normal to O1A: R + D sin(theta) = 0) on the side where the rocker's angle
    is largest (the pin left of O2's vertical, theta = 180 + asin(R / D))."""
    return 180.0 + math.degrees(math.asin(R / D))


def _turned(to_x: np.ndarray, zero: float, sign: float) -> np.ndarray:
    """φ by hand: the angle turned from ``zero`` in the direction ``sign``, deg in [0, 360)."""
    return np.mod(sign * (np.asarray(to_x, dtype=float) - zero), 360.0)


def _close(a: np.ndarray, b: np.ndarray, tol: float) -> None:
    """Angles ``a`` and ``b`` (deg) agree to ``tol`` on the circle (359.9999999 and 0 are 1e-7 apart)."""
    gap = np.abs((np.asarray(a, dtype=float) - np.asarray(b, dtype=float) + 180.0) % 360.0 - 180.0)
    assert gap.max() <= tol, (gap.max(), a, b)


def _columns(path: Path) -> dict[str, np.ndarray]:
    with open(path, encoding="utf-8") as fh:
        rows = list(csv.reader(fh))
    return {name: np.array([float(r[i]) for r in rows[1:]]) for i, name in enumerate(rows[0])}


def _in_turn(values: np.ndarray) -> None:
    values = np.asarray(values, dtype=float)
    assert values.size and np.all((values >= 0.0) & (values < 360.0)), values


def _crank_pin_to_x(cols: dict[str, np.ndarray], pivot: str, pin: str) -> np.ndarray:
    """The crank's angle to x (deg) from the written coordinates of its pivot and pin."""
    dx, dy = cols[f"{pin}.x [m]"] - cols[f"{pivot}.x [m]"], cols[f"{pin}.y [m]"] - cols[f"{pivot}.y [m]"]
    return np.degrees(np.arctan2(dy, dx))


@pytest.mark.parametrize("direction, sign", [("ccw", 1.0), ("cw", -1.0)])
def test_every_crank_angle_analyze_writes_for_a_crank_shaper_is_phi_from_position_0(tmp_path, direction, sign):
    """kinematics.csv, kinematics.nc, forces.csv and forces.json of the report: φ in [0, 360) equal to the
    angle turned from the closed-form position 0 to the crank pin's written angle, and the angle to x equal to
    that pin angle wrapped; the whole-degree grid is written exactly (no 268.84468815685517 noise)."""
    pytest.importorskip("matplotlib")
    xr = pytest.importorskip("xarray")
    from linkwork import report

    mech = lw.compile(_shaper(direction).build())
    report.analyze(mech, tmp_path / "r", steps=36, animation=False)
    zero = _shaper_zero()
    kin = _columns(tmp_path / "r" / "kinematics.csv")
    pin = _crank_pin_to_x(kin, "O1", "A")
    _in_turn(kin["phi [deg]"])
    _in_turn(kin["crank_angle_to_x [deg]"])
    _close(kin["phi [deg]"], _turned(pin, zero, sign), 1e-7)
    _close(kin["crank_angle_to_x [deg]"], pin, 1e-7)
    assert kin["phi [deg]"].tolist() == [10.0 * k for k in range(36)]  # exact, from position 0
    with xr.open_dataset(tmp_path / "r" / "kinematics.nc") as ds:
        np.testing.assert_array_equal(ds["angle"].values, kin["phi [deg]"])
        np.testing.assert_array_equal(ds["crank_angle_to_x"].values, kin["crank_angle_to_x [deg]"])
        assert "position 0" in ds["angle"].attrs["long_name"]
    forces = _columns(tmp_path / "r" / "forces.csv")
    np.testing.assert_array_equal(forces["phi [deg]"], kin["phi [deg]"])
    np.testing.assert_array_equal(forces["crank_angle_to_x [deg]"], kin["crank_angle_to_x [deg]"])
    data = json.loads((tmp_path / "r" / "forces.json").read_text(encoding="utf-8"))
    assert data["phi_deg"] == kin["phi [deg]"].tolist()
    assert data["crank_angle_to_x_deg"] == kin["crank_angle_to_x [deg]"].tolist()
    assert data["position_0_deg"] == pytest.approx(zero, abs=1e-9) and data["direction"] == sign
    for name in ("shear", "push", "moment"):
        phi, to_x = data["bolts"][f"{name}_phi_deg"], data["bolts"][f"{name}_to_x_deg"]
        _in_turn(np.array([phi, to_x]))
        _close(np.array([phi]), _turned(np.array([to_x]), zero, sign), 1e-7)
    assert not any(k.endswith("_angle_deg") or k == "angles_deg" for k in [*data, *data["bolts"]])


@pytest.fixture(scope="module")
def shaper_files(tmp_path_factory: pytest.TempPathFactory) -> dict[str, str]:
    """The crank-shaper turning either way, as files (the command line's argument)."""
    from ruamel.yaml import YAML

    folder = tmp_path_factory.mktemp("shapers")
    out = {}
    for direction in ("ccw", "cw"):
        path = folder / f"shaper-{direction}.yaml"
        with open(path, "w", encoding="utf-8") as fh:
            YAML().dump(_shaper(direction).to_dict(), fh)
        out[direction] = str(path)
    return out


@pytest.mark.parametrize("direction, sign", [("ccw", 1.0), ("cw", -1.0)])
def test_forces_and_kinematics_json_of_a_crank_shaper_give_phi_and_the_angle_to_x(shaper_files, direction, sign):
    """The issue's crank-shaper, assembled at 90 deg: ``forces --json`` ran from 90 to 449.  Now its ``phi_deg``
    is the angle turned from position 0 (210 deg to x), in [0, 360), and ``crank_angle_to_x_deg`` the drive
    angle 90 + k deg (or 90 - k turning clockwise) wrapped, exactly; the rocker's extremes in ``kinematics
    --json`` are at φ = 0 (the high end, position 0) and at φ = 120 or 240 (the low end, 330 deg to x)."""
    path_args = [shaper_files[direction]]
    out = runner.invoke(app, ["forces", *path_args, "--json"])
    assert out.exit_code == 0, out.output
    data = json.loads(out.stdout)
    to_x = np.mod(90.0 + sign * np.arange(360.0), 360.0)
    assert data["crank_angle_to_x_deg"] == to_x.tolist()
    assert data["phi_deg"] == _turned(to_x, _shaper_zero(), sign).tolist()  # whole degrees, exactly
    out = runner.invoke(app, ["kinematics", *path_args, "--json"])
    assert out.exit_code == 0, out.output
    data = json.loads(out.stdout)
    assert data["phi_deg"] == _turned(to_x, _shaper_zero(), sign).tolist()
    (rocker,) = [e for e in data["events"] if e["kind"] == "stroke"]
    _close(np.array([rocker["at_high_phi_deg"], rocker["at_high_to_x_deg"]]), np.array([0.0, 210.0]), 1e-6)
    low = 120.0 if sign > 0 else 240.0
    _close(np.array([rocker["at_low_phi_deg"], rocker["at_low_to_x_deg"]]), np.array([low, 330.0]), 1e-6)
    assert "at_low_deg" not in rocker and "at_high_deg" not in rocker


def test_the_printed_peak_angle_of_forces_is_the_reports(tmp_path, shaper_files):
    """``linkwork forces`` prints where the driving torque peaks as the report does, φ from position 0 ("604
    N m at phi = 102.0 deg" where it printed "at 83.0 deg", the angle to x): the crank-shaper assembled at
    90 deg samples the report's whole degrees from position 0 (210 deg), so both find the peak at one
    sample; and the angle printed is that of the refined peak of ``forces --json``, within a step of its largest
    sampled |torque|."""
    pytest.importorskip("matplotlib")
    from linkwork import report

    path_args = [shaper_files["ccw"]]
    out = runner.invoke(app, ["forces", *path_args])
    assert out.exit_code == 0, out.output
    printed = float(re.search(r"driving torque: peak \S+ N m at phi = ([\d.]+) deg", out.stdout).group(1))
    data = json.loads(runner.invoke(app, ["forces", *path_args, "--json"]).stdout)
    torque = np.abs(np.array(data["driving_torque"], dtype=float))
    assert printed == pytest.approx(data["driving_torque_peak"]["at_phi_deg"], abs=0.05)  # refined: the same peak
    assert printed == pytest.approx(data["phi_deg"][int(np.argmax(torque))], abs=1.0)  # within a step of the sample
    html = report.analyze(lw.compile(lw.load(path_args[0])), tmp_path / "r", steps=360, animation=False)
    text = html.read_text(encoding="utf-8")
    reported = float(re.search(r"Driving torque on the crank: largest [^<]*? at φ = ([\d.]+)°", text).group(1))
    assert printed == reported


def test_the_double_cut_shears_report_writes_phi_from_the_knives_open(main_job):
    """The README's main job: kinematics.csv, forces.csv, forces.json and dynamics.json give φ in [0, 360)
    from position 0, the upper knife at its highest (found here by a fine scan of its height), and the crank's
    angle to x from the crank pin's written coordinates (before: 268.84468815685517 to 627.84...)."""
    assert main_job.returncode == 0, main_job.stderr
    folder = main_job.folder
    mech = lw.compile(lw.example("double-cut-shears"))
    fine = lw.kinematics(mech, steps=36000)
    zero = math.degrees(fine.angles[int(np.argmax(fine.position("E")[:, 1]))])  # to 0.01 deg
    kin = _columns(folder / "kinematics.csv")
    pin = _crank_pin_to_x(kin, "O1", "A")
    for table in (kin, _columns(folder / "forces.csv")):
        _in_turn(table["phi [deg]"])
        _in_turn(table["crank_angle_to_x [deg]"])
        _close(table["phi [deg]"], _turned(pin, zero, 1.0), 0.011)
        _close(table["crank_angle_to_x [deg]"], pin, 1e-7)
        assert table["phi [deg]"].tolist() == [float(k) for k in range(len(pin))]  # 360 steps from position 0
    forces = json.loads((folder / "forces.json").read_text(encoding="utf-8"))
    assert forces["phi_deg"] == kin["phi [deg]"].tolist()
    dyn = json.loads((folder / "dynamics.json").read_text(encoding="utf-8"))
    for phi, to_x in ((dyn["phi_deg"], dyn["crank_angle_to_x_deg"]), (dyn["cycle"]["phi_deg"], None)):
        _in_turn(np.array(phi))
        if to_x is not None:
            _in_turn(np.array(to_x))
            _close(np.array(phi), _turned(np.array(to_x), zero, 1.0), 0.011)
    assert "angles_deg" not in dyn and "crank_angle_deg" not in dyn["cycle"]


def test_tables_write_the_crank_angle_to_x_wrapped_and_exact():
    """The one rule of the angles written: wrapped before rounding to 1e-9 deg, so 627.5 deg and -92.5 deg
    are 267.5 exactly, a whole-degree grid from an irrational position 0 is whole degrees of φ, and a hair
    below a whole turn is 0, not 360."""
    from linkwork.motion.analysis import CrankAngles, phi_deg, position_angles, to_x_deg

    assert to_x_deg(math.radians(627.5)) == 267.5 and to_x_deg(math.radians(-92.5)) == 267.5
    assert to_x_deg(-1e-13) == 0.0 and phi_deg(2 * math.pi - 1e-12, 0.0, 1.0) == 0.0
    mech = lw.compile(lw.example("double-cut-shears"))
    crank = CrankAngles.of(mech)
    assert crank is not None
    grid = position_angles(mech, 720)
    assert crank.phi(grid).tolist() == [0.5 * k for k in range(720)]
    to_x = crank.columns(grid)["crank_angle_to_x"]
    assert repr(float(to_x[1])) == "269.344688157"
    # wrapped before rounding: no 158.84468815699995 where the turn passes 360 (489 of the 720 did)
    assert max(len(repr(float(x)).partition(".")[2]) for x in to_x) <= 9


@pytest.mark.parametrize("name", names())
def test_every_bundled_example_writes_phi_from_position_0(report, name):
    """Every bundled example's report: φ in every table and JSON file is in [0, 360), starts at position 0
    and steps by 360 / steps exactly, and is the angle turned from ``position_0_deg`` to the crank link's
    written angle (``crank.angle [rad]``: a drive sets the driven link's angle, so it is the drive angle), in
    the drive's direction; ``crank_angle_to_x`` is that link angle wrapped."""
    pytest.importorskip("matplotlib")
    pytest.importorskip("xarray")
    mech = lw.compile(lw.example(name))
    folder = report(name)  # the run's shared report of the example: 36 steps, no animation
    crank = mech.link_names[int(mech.pair_links[mech.drive_pair[0], 1])]
    kin = _columns(folder / "kinematics.csv")
    to_x = np.degrees(kin[f"{crank}.angle [rad]"])
    _close(kin["crank_angle_to_x [deg]"], to_x, 1e-7)
    files = [kin]
    zero, sign = to_x[0], -1.0 if mech.drive_speed[0] < 0 else 1.0  # the report's turn starts at position 0
    if (folder / "forces.csv").exists():
        files.append(_columns(folder / "forces.csv"))
        forces = json.loads((folder / "forces.json").read_text(encoding="utf-8"))
        _close(np.array([forces["position_0_deg"]]), np.array([zero]), 1e-7)
        assert forces["direction"] == sign and forces["phi_deg"] == kin["phi [deg]"].tolist()
        for key in ("shear", "push", "moment"):
            _in_turn(np.array([forces["bolts"][f"{key}_phi_deg"]]))
    for table in files:
        _in_turn(table["phi [deg]"])
        _in_turn(table["crank_angle_to_x [deg]"])
        assert table["phi [deg]"].tolist() == [10.0 * k for k in range(36)]
        _close(table["phi [deg]"], _turned(to_x, zero, sign), 1e-7)
    if (folder / "dynamics.json").exists():
        dyn = json.loads((folder / "dynamics.json").read_text(encoding="utf-8"))
        _in_turn(np.array(dyn["phi_deg"]))
        _in_turn(np.array(dyn["cycle"]["phi_deg"]))
        _close(np.array(dyn["phi_deg"]), _turned(np.array(dyn["crank_angle_to_x_deg"]), zero, sign), 1e-7)
