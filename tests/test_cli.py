"""The command line: check, schema, examples, example."""

from __future__ import annotations

import json
import math
import re
import subprocess
import sys
from pathlib import Path

import pytest
from typer.testing import CliRunner

import linkwork as lw
from linkwork.cli.app import app
from linkwork.examples import names, text

runner = CliRunner()
ROOT = Path(__file__).resolve().parents[1]


def test_check_double_cut_shears_json():
    result = runner.invoke(app, ["check", "double-cut-shears", "--json"])
    assert result.exit_code == 0, result.output
    out = json.loads(result.stdout)
    assert (out["n_links"], out["p5"], out["p4"], out["dof"], out["redundant"]) == (7, 10, 0, 1, 0)
    assert out["formula"] == "I(0,1) -> II(2,3) -> II(4,5) -> II(6,7)"
    groups = [(g["class"], g["order"], g["kind"], g["links"]) for g in out["groups"]]
    assert groups == [(1, None, "R", [1]), (2, 2, "RRR", [2, 3]), (2, 2, "RRP", [4, 5]), (2, 2, "RRP", [6, 7])]
    assert all(set(g) >= {"class", "order", "kind", "links", "joints"} for g in out["groups"])
    assert out["drives"][0]["speed"] == pytest.approx(3.141592653589793)


def test_check_prints_a_readable_report():
    result = runner.invoke(app, ["check", "class3-triad"])
    assert result.exit_code == 0
    assert "W = 3n - 2p5 - p4 = 3*5 - 2*7 = 1" in result.stdout
    assert "I(0,1) -> III(2,3,4,5)" in result.stdout


def test_check_a_file_path(tmp_path):
    path = tmp_path / "mine.yaml"
    path.write_text(text("four-bar"), encoding="utf-8")
    result = runner.invoke(app, ["check", str(path), "--json"])
    assert result.exit_code == 0
    assert json.loads(result.stdout)["formula"] == "I(0,1) -> II(2,3)"


def test_unknown_example_suggests_a_name():
    result = runner.invoke(app, ["check", "double-cut-shear"])
    assert result.exit_code == 2
    assert 'no such file or bundled example "double-cut-shear" (did you mean "double-cut-shears"?)' in result.stderr


def test_missing_file_is_an_error_not_a_traceback(tmp_path):
    result = runner.invoke(app, ["check", str(tmp_path / "none.yaml")])
    assert result.exit_code == 2
    assert result.stderr.strip() == f"error: {tmp_path / 'none.yaml'}: no such file"


def test_bad_option_exits_2():
    result = runner.invoke(app, ["check", "four-bar", "--jsn"])
    assert result.exit_code == 2


def test_examples_lists_every_bundled_example():
    result = runner.invoke(app, ["examples"])
    assert result.exit_code == 0
    assert [line.split()[0] for line in result.stdout.splitlines()] == names()
    assert set(names()) >= {
        "shears-slider-crank",
        "double-cut-shears",
        "percussion-rocker",
        "four-bar",
        "watt-six-bar",
        "stephenson-six-bar",
        "class3-triad",
    }


def test_example_prints_yaml_that_loads():
    result = runner.invoke(app, ["example", "percussion-rocker"])
    assert result.exit_code == 0
    assert lw.loads(result.stdout).model_dump() == lw.example("percussion-rocker").model_dump()


def test_schema_is_json():
    result = runner.invoke(app, ["schema"])
    assert result.exit_code == 0
    assert json.loads(result.stdout)["title"] == "Spec"


def test_readme_quick_start_has_two_commands_and_the_main_job_runs(tmp_path):
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    quick = readme.split("## Quick start", 1)[1].split("\n## ", 1)[0]
    commands = re.findall(r"```(?:bash|sh)?\n(.*?)```", quick, flags=re.S)
    lines = [line for block in commands for line in block.strip().splitlines()]
    assert len(lines) == 2
    main_job = lines[0].split("&&")[-1].strip().split()
    assert main_job[:2] == ["linkwork", "analyze"]
    proc = subprocess.run(
        [sys.executable, "-m", "linkwork.cli.app", *main_job[1:]], capture_output=True, text=True, cwd=tmp_path
    )
    assert proc.returncode == 0, proc.stderr
    report = (tmp_path / main_job[main_job.index("--out") + 1] / "report.html").read_text(encoding="utf-8")
    assert "I(0,1) -&gt; II(2,3) -&gt; II(4,5) -&gt; II(6,7)" in report
    ci = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    assert lines[1] in ci


def test_written_files_have_the_mode_of_a_plain_open(tmp_path):
    """Outputs are written through a temporary file, and get the permissions open() would give them."""
    import os

    from linkwork.io.atomic import write_atomic

    umask = os.umask(0o022)
    try:
        out = write_atomic(tmp_path / "table.csv", lambda p: p.write_text("x\n"))
        plain = tmp_path / "plain.csv"
        plain.write_text("x\n")
    finally:
        os.umask(umask)
    assert out.read_text() == "x\n"
    assert out.stat().st_mode & 0o777 == plain.stat().st_mode & 0o777 == 0o644
    assert [p.name for p in tmp_path.iterdir() if p.name.startswith(".")] == []


VALUES_FILE = """\
units: {length: mm, force: kN}
frame: {points: {O2: [0, 0], O4: [300, 0]}}
links:
  crank: {ends: [O2, A], length: 100, mass: 1, inertia: "0.002 kg*m^2"}
  coupler: {ends: [A, B], length: 350, mass: 2}
  rocker: {ends: [O4, B], length: 250, mass: 1.5}
joints:
  O2: {type: revolute, links: [frame, crank]}
  A: {type: revolute, links: [crank, coupler]}
  B: {type: revolute, links: [coupler, rocker]}
  O4: {type: revolute, links: [frame, rocker]}
drives:
  - {joint: O2, speed: 60 rpm, angle: 90}
hints: {B: [330, 240]}
loads:
  push: {type: force, at: coupler.B, magnitude: 2, direction: 270}
machine:
  motor: {type: constant, torque: 5 N*m}
  gear: {ratio: 3}
"""

# (line, path, text, SI value, unit), converted by hand
VALUES = [
    (2, "frame.points.O4[0]", 300, 0.3, "m"),
    (4, "links.crank.length", 100, 0.1, "m"),
    (4, "links.crank.mass", 1, 1.0, "kg"),
    (4, "links.crank.inertia", "0.002 kg*m^2", 0.002, "kg*m^2"),
    (13, "drives[0].speed", "60 rpm", 2 * math.pi, "rad/s"),
    (13, "drives[0].angle", 90, math.pi / 2, "rad"),
    (14, "hints.B[1]", 240, 0.24, "m"),
    (16, "loads.push.magnitude", 2, 2000.0, "N"),
    (16, "loads.push.direction", 270, 1.5 * math.pi, "rad"),
    (18, "machine.motor.torque", "5 N*m", 5.0, "N*m"),
    (19, "machine.gear.ratio", 3, 3.0, ""),
]


def test_check_values_lists_every_value_read_in_si(tmp_path):
    path = tmp_path / "values.yaml"
    path.write_text(VALUES_FILE, encoding="utf-8")
    out = json.loads(runner.invoke(app, ["check", str(path), "--json", "--values"]).stdout)
    got = {v["path"]: v for v in out["values"]}
    assert len(got) == 19  # 4 of the frame, 3 + 2 + 2 of the links, 2 drive, 2 hint, 2 load, 1 motor, 1 gear
    for line, where, written, si, unit in VALUES:
        v = got[where]
        assert (v["line"], v["text"], v["unit"]) == (line, written, unit), v
        assert v["value"] == pytest.approx(si, rel=1e-12)
    assert [v["line"] for v in out["values"]] == sorted(v["line"] for v in out["values"])
    result = runner.invoke(app, ["check", str(path), "--values"], terminal_width=200)
    assert result.exit_code == 0, result.output
    rows = [re.split(r"\s*│\s*", line.strip("│ ")) for line in result.stdout.splitlines() if "│" in line]
    table = {r[1]: r for r in rows if len(r) == 5}
    for line, where, written, si, unit in VALUES:
        assert table[where] == [str(line), where, str(written), f"{si:.10g}", unit or "-"]
    assert "values" not in json.loads(runner.invoke(app, ["check", str(path), "--json"]).stdout)
