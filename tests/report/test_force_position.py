"""Where the report's force analysis is done: under the load, by default; ``--position`` takes an angle."""

from __future__ import annotations

import html
import math
import re

import numpy as np
import pytest
from typer.testing import CliRunner

pytest.importorskip("matplotlib")

import linkwork.cli.analyze  # noqa: E402,F401 - registers the command
from linkwork.cli.main import app  # noqa: E402

runner = CliRunner()


def _phi_of_largest_torque_while_the_knives_close() -> tuple[float, float]:
    """Independently of the report's rule: on a 0.2° grid from position 0, where the upper knife moves down
    (its velocity's y below zero, as the file's guide is vertical), the crank angle φ (deg) of the largest
    driving torque and that torque (N m)."""
    import linkwork as lw
    from linkwork.motion.analysis import zero_angle

    mech = lw.compile(lw.example("double-cut-shears"))
    phi = np.arange(1800) * 0.2
    kin = lw.kinematics(mech, zero_angle(mech) + np.radians(phi))  # the crank turns ccw: φ adds to the angle
    down = np.asarray(kin.velocity("E"))[..., 1].reshape(-1)[: len(phi)] < 0
    torque = np.asarray(lw.forces(kin).driving_torque)
    k = int(np.argmax(np.where(down, np.abs(torque), -np.inf)))
    return float(phi[k]), float(torque[k])


def test_the_force_analysis_is_done_under_the_cutting_load(main_job):
    """The double-cut shears' file asks for the plans at position 9, where nothing is cut; the force plans
    are drawn at the largest driving torque of the stroke the knives close on (φ within the grid's 0.2° of a
    brute-force search), under the cutting force of 250 kN, drawn on both knives' plans; the lever's row
    there (marked *) gives the kinetostatic torque to its 7 digits."""
    page = html.unescape((main_job.folder / "report.html").read_text(encoding="utf-8"))
    phi, torque = _phi_of_largest_torque_while_the_knives_close()
    found = re.search(r"Kinetostatic analysis by the graphical method, position φ = ([\d.]+)°", page)
    assert found, "the force analysis is not at a crank angle of its own"
    assert float(found.group(1)) == pytest.approx(phi, abs=0.2 + 0.05)
    assert f"Md = {torque:.0f}"[:-1] in page  # to the newton-metre, but for rounding
    start = found.end()
    loads = re.findall(r"<td>(F[57])</td><td>external load \(cutting\)</td><td>([^<]+)</td>", page[start:])
    assert sorted(name for name, _ in loads) == ["F5", "F7"]
    assert all(float(value) == pytest.approx(250e3) for _, value in loads)
    star = re.search(r"<tr><td>\*</td><td>([\d.]+)</td><td>([^<]+)</td><td>([^<]+)</td>", page)
    assert star and float(star.group(1)) == pytest.approx(phi, abs=0.25)
    assert float(star.group(2)) == pytest.approx(torque, rel=1e-3) and star.group(2) == star.group(3)


@pytest.mark.parametrize("asked", ["12", "-1", "400deg", "87", "87 kg", "abc"])
def test_a_position_that_is_neither_a_number_of_the_twelve_nor_an_angle_is_refused(asked, tmp_path):
    result = runner.invoke(app, ["analyze", "double-cut-shears", "--position", asked, "--out", str(tmp_path / "r")])
    assert result.exit_code == 2
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: --position: expected one of the 12 positions")
    assert "87deg" in lines[0] and "Traceback" not in result.output
    assert not (tmp_path / "r").exists()


@pytest.mark.slow
def test_position_takes_a_crank_angle_for_the_force_analysis(tmp_path):
    """``--position 87deg``: the force plans, the lever and the plans they need at φ = 87° (not one of the twelve),
    the driving torque there as the kinetostatic solution gives it at that crank angle."""
    import linkwork as lw
    from linkwork.motion.analysis import zero_angle

    out = tmp_path / "r"
    result = runner.invoke(
        app, ["analyze", "double-cut-shears", "--position", "87deg", "--out", str(out), "--no-animation"]
    )
    assert result.exit_code == 0, result.output
    page = html.unescape((out / "report.html").read_text(encoding="utf-8"))
    assert "Kinetostatic analysis by the graphical method, position φ = 87.0°" in page
    assert {"id='velocity_plan_forces'", "id='acceleration_plan_forces'", "id='force_plans'"} <= set(
        re.findall(r"id='[a-z_]+'", page)
    )
    mech = lw.compile(lw.example("double-cut-shears"))
    torque = float(lw.forces(lw.kinematics(mech, [zero_angle(mech) + math.radians(87)])).driving_torque[0])
    star = re.search(r"<tr><td>\*</td><td>87</td><td>([^<]+)</td>", page)
    assert star and float(star.group(1)) == pytest.approx(torque, rel=1e-6)
