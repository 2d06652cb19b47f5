"""``linkwork forces``, ``linkwork dynamics`` and ``linkwork size`` print what one study of the mechanism reads
(:class:`linkwork.study.Study`): the same numbers as :func:`linkwork.forces`, :func:`linkwork.dynamics` and
:func:`linkwork.size` called with the same options, which compose their analyses without the study."""

from __future__ import annotations

import json

import numpy as np
import pytest
from typer.testing import CliRunner

import linkwork as lw
from linkwork.cli.main import app
from linkwork.io.jsonout import dumps
from mechanisms import meeting_spring_four_bar

runner = CliRunner()


def _printed(args: list[str]) -> dict:
    """The ``--json`` record a command prints, without its explanation of the nulls."""
    result = runner.invoke(app, [*args, "--json"])
    assert result.exit_code == 0, result.output
    out = json.loads(result.stdout)
    out.pop("nulls", None)
    return out


def _written(record: dict) -> dict:
    """``record`` as the command line's one JSON writer writes it (rounded numbers, NaN as null)."""
    return json.loads(dumps(record))


@pytest.mark.parametrize(
    ("name", "options", "call"),
    [
        ("four-bar", ["--steps", "36"], {"steps": 36}),
        ("shears-slider-crank", ["--angles", "30,95,200"], {"angles": np.radians([30, 95, 200])}),
        ("double-cut-shears", ["--steps", "24", "--speed", "45 rpm"], {"steps": 24, "speed": 1.5 * np.pi}),
    ],
)
def test_the_forces_command_prints_lw_forces(name, options, call):
    """The command's grid (``--steps`` from the assembly pose, ``--angles`` to the frame's x axis) and speed are
    those of :func:`linkwork.forces`: every angle, reaction, torque, foundation load and check agrees."""
    from linkwork.io.force_tables import to_json

    mech = lw.compile(lw.example(name))
    assert _printed(["forces", name, *options]) == _written(to_json(lw.forces(mech, **call)))


def test_the_forces_command_s_pull_is_lw_bolt_speed():
    out = _printed(["forces", "four-bar", "--steps", "12", "--pull", "5 kN"])
    assert out["bolts"]["pull_target"] == 5000
    assert out["bolts"]["speed_for_pull_rad_s"] == pytest.approx(lw.bolt_speed("four-bar", pull=5000.0), rel=1e-11)


def test_the_dynamics_command_prints_lw_dynamics():
    """``--delta`` and ``--steps`` reach the machine's run as :func:`linkwork.dynamics` takes them: the flywheel,
    the steady cycle's samples and the powers agree."""
    from linkwork.io.dynamics_tables import to_json

    mech = lw.compile(lw.example("percussion-rocker"))
    expected = _written(to_json(mech, lw.dynamics(mech, delta=0.08, steps=180)))
    assert expected["energy_method"]["delta"] == 0.08 and len(expected["reduced_inertia"]) == 180
    assert _printed(["dynamics", "percussion-rocker", "--delta", "0.08", "--steps", "180"]) == expected


def test_the_size_command_prints_lw_size():
    """The options reach the sizing as fields of the file's ``sizing:`` section over it, as :func:`linkwork.size`
    takes them: the bearings' life and kind, the pins' width ratio and the masses as the file gives them."""
    mech = lw.compile(lw.example("shears-slider-crank"))
    options = ["--no-motor", "--life", "10000 h", "--kind", "roller", "--width-ratio", "1.2", "--masses", "file"]
    inputs = {"life": 10000 * 3600.0, "bearings": "roller", "width_ratio": 1.2, "masses": "file"}
    expected = _written(lw.size(mech, sizing=inputs, motor=False).record())
    assert expected["inputs"]["life_h"] == 10000 and expected["inputs"]["bearing_kind"] == "roller"
    assert _printed(["size", "shears-slider-crank", *options]) == expected


def test_the_forces_command_refuses_a_spring_whose_points_meet(tmp_path):
    """As :func:`linkwork.forces` does (:func:`mechanisms.meeting_spring_four_bar`): one line naming the load and
    the crank angle, exit code 2, no traceback, no file written."""
    import yaml

    data = meeting_spring_four_bar()
    path = tmp_path / "meet.yaml"
    path.write_text(yaml.safe_dump(data), encoding="utf-8")
    out = tmp_path / "out"
    result = runner.invoke(app, ["forces", str(path), "--angles", "28.6,0,-28.6", "--out", str(out)])
    assert result.exit_code == 2
    assert result.stderr.count("\n") == 1 and "Traceback" not in result.output
    assert 'load "s"' in result.stderr and "meet with the crank at 0 deg" in result.stderr
    assert not out.exists()


def test_the_balance_command_prints_lw_balance():
    """The counterweights on the crank and the rocker of a four-bar cancel its shaking force (Lowen and Berkof: a
    four-bar is balanced fully by the two), and the command prints those of :func:`linkwork.balance`."""
    out = _printed(["balance", "four-bar", "--links", "crank,rocker", "--steps", "36"])
    found = lw.balance("four-bar", ["crank", "rocker"], steps=36)
    expected = {"name": "four-bar", "mode": "full", "counterweights": [w.as_dict() for w in found.counterweights]}
    assert out == _written({**expected, **found.summary()})
    assert out["after"]["shaking_force_peak"] < 1e-9 * out["before"]["shaking_force_peak"]
