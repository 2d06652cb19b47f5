"""What a person meets in the files and lines the commands write: ``--out`` paths, the tables' rows and units,
the words printed."""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path

import numpy as np
import pytest

from commandline import linkwork
from linkwork.examples import text


def _rows(path: Path) -> tuple[list[str], np.ndarray]:
    with open(path, newline="", encoding="utf-8") as fh:
        head, *rows = list(csv.reader(fh))
    return head, np.array(rows, dtype=float)


def test_dynamics_csv_holds_each_angle_of_the_steady_turn_once(tmp_path):
    """The steady turn is kept at 720 + 1 equal steps of the turning angle (0 to 360 deg): 721 rows, the
    angle rising by 0.5 deg from each to the next, none twice."""
    result = linkwork("dynamics", "double-cut-shears", "--out", str(tmp_path))
    assert result.returncode == 0, result.stderr
    head, rows = _rows(tmp_path / "dynamics.csv")
    psi = rows[:, head.index("psi [deg]")]
    assert len(psi) == 721
    np.testing.assert_allclose(np.diff(psi), 0.5, rtol=1e-9)
    assert psi[0] == 0.0 and psi[-1] == pytest.approx(360.0, rel=1e-12)
    assert np.all(np.diff(rows[:, head.index("t [s]")]) > 0)


@pytest.mark.parametrize(
    ("command", "name", "kind"),
    [
        ("kinematics", "kin.csv", "csv"),
        ("kinematics", "kin.nc", "nc"),
        ("forces", "f.csv", "csv"),
        ("forces", "f.json", "json"),
        ("dynamics", "d.json", "json"),
        ("dynamics", "d.CSV", "csv"),
    ],
)
def test_out_with_the_suffix_of_a_table_writes_that_file_alone(tmp_path, command, name, kind):
    example = "double-cut-shears"
    args = [command, example, "--out", name] + (["--steps", "36"] if command != "dynamics" else [])
    result = linkwork(*args, cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert [p.name for p in tmp_path.iterdir()] == [name]
    path = tmp_path / name
    assert path.is_file()
    if kind == "csv":
        head, rows = _rows(path)
        assert len(rows) == (721 if command == "dynamics" else 36)
    elif kind == "json":
        assert json.loads(path.read_text())["name"] == "double-cut-shears"
    else:
        assert path.read_bytes()[:3] == b"CDF"


@pytest.mark.parametrize("command", ["kinematics", "forces", "dynamics", "analyze"])
def test_out_with_another_file_suffix_is_refused_before_any_work(tmp_path, command):
    result = linkwork(
        command, "four-bar" if command != "dynamics" else "double-cut-shears", "--out", "kin.txt", cwd=tmp_path
    )
    assert result.returncode == 2
    assert result.stderr.startswith("error: --out kin.txt: names a .txt file")
    assert "--out kin" in result.stderr and "Traceback" not in result.stderr
    assert list(tmp_path.iterdir()) == []


def test_out_an_existing_folder_with_a_dot_stays_a_folder(tmp_path):
    (tmp_path / "run.v1").mkdir()
    result = linkwork("forces", "four-bar", "--steps", "12", "--out", "run.v1", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert sorted(p.name for p in (tmp_path / "run.v1").iterdir()) == ["forces.csv", "forces.json"]


def test_the_columns_of_the_loads_name_each_unit(tmp_path):
    """A moment in N m and a force in N, each in a column that names its own unit, with the values the
    file gives (a constant moment of 2 N m, a force of 30 N along y)."""
    spec = text("four-bar") + (
        "loads:\n"
        "  brake: {type: moment, on: rocker, moment: 2 N*m}\n"
        "  push: {type: force, at: coupler.M, magnitude: 30 N, direction: 90 deg}\n"
    )
    (tmp_path / "m.yaml").write_text(spec)
    result = linkwork("forces", "m.yaml", "--steps", "12", "--out", "f", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    head, rows = _rows(tmp_path / "f" / "forces.csv")
    assert not any(" or " in h for h in head)
    np.testing.assert_array_equal(rows[:, head.index("load.brake [N m]")], 2.0)
    np.testing.assert_array_equal(rows[:, head.index("load.push [N]")], 30.0)
    units = json.loads((tmp_path / "f" / "forces.json").read_text())["units"]["loads"]
    assert units == {"brake": "N m", "push": "N"}


@pytest.fixture(scope="module")
def four_bar_report(tmp_path_factory):
    """``linkwork analyze four-bar --out r`` (36 steps, no animation), piped, run once for the tests that read it:
    the process's result and the folder it ran in."""
    cwd = tmp_path_factory.mktemp("four-bar-report")
    result = linkwork("analyze", "four-bar", "--out", "r", "--steps", "36", "--no-animation", cwd=cwd)
    assert result.returncode == 0, result.stderr
    return result, cwd


@pytest.mark.slow  # over the default lane's budget on the NumPy kernels (tests/conftest.py)
def test_piped_analyze_prints_one_line(four_bar_report):
    result, _ = four_bar_report
    assert result.stdout == "wrote r/report.html\n"


def test_a_rocker_named_rocker_is_named_once(four_bar_report):
    result = linkwork("kinematics", "four-bar")
    assert result.returncode == 0, result.stderr
    assert "rocker rocker" not in result.stdout
    assert "\n  rocker: swing " in result.stdout
    page = (four_bar_report[1] / "r" / "report.html").read_text()
    assert "rocker rocker" not in page and "extreme position of the output rocker at the" in page


def test_a_slider_without_its_point_is_told_how_to_name_it(tmp_path):
    spec = text("shears-slider-crank").replace(" point: B,", "")
    (tmp_path / "s.yaml").write_text(spec)
    result = linkwork("check", "s.yaml", cwd=tmp_path)
    assert result.returncode == 2
    assert 'the slider "knife" has no point "guide"' in result.stderr
    assert "give the slider's point on the guide line as point:, e.g. point: B" in result.stderr


@pytest.mark.parametrize("command", ["kinematics", "forces", "analyze"])
def test_speed_is_one_option_of_every_command_that_turns_the_crank(command):
    """``--speed`` has one definition (its help and its checks): the same text in each command."""
    help_text = linkwork(command, "--help").stdout
    assert 'uniform drive speed with a unit, e.g. "30 rpm"' in " ".join(help_text.split())
    bare = linkwork(command, "four-bar", "--speed", "120", "--out", "never")
    assert bare.returncode == 2 and bare.stderr == 'error: --speed: give the unit, e.g. "30 rpm", got "120"\n'


@pytest.mark.slow  # over the default lane's budget on the NumPy kernels (tests/conftest.py)
def test_kinematics_and_analyze_at_another_speed(tmp_path):
    """At 120 rpm the crank pin A of the four-bar (crank 100 mm) moves at omega l = 4 pi 0.1 m/s, and its
    acceleration is omega^2 l; the report's table has the same."""
    omega = 120 * math.pi / 30
    result = linkwork("kinematics", "four-bar", "--angles", "0,90", "--speed", "120 rpm", "--json")
    assert result.returncode == 0, result.stderr
    a = json.loads(result.stdout)["points"]["A"]
    np.testing.assert_allclose(np.hypot(a["vx"], a["vy"]), omega * 0.1, rtol=1e-11)  # JSON: 12 digits
    np.testing.assert_allclose(np.hypot(a["ax"], a["ay"]), omega**2 * 0.1, rtol=1e-11)
    done = linkwork(
        "analyze", "four-bar", "--speed", "120 rpm", "--out", "r", "--steps", "36", "--no-animation", cwd=tmp_path
    )
    assert done.returncode == 0, done.stderr
    head, rows = _rows(tmp_path / "r" / "kinematics.csv")
    speed = np.hypot(rows[:, head.index("A.vx [m/s]")], rows[:, head.index("A.vy [m/s]")])
    np.testing.assert_allclose(speed, omega * 0.1, rtol=1e-12)
