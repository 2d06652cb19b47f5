"""The command line: check, schema, examples, example."""

from __future__ import annotations

import json
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
