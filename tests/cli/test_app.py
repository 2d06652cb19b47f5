"""The command line: check, schema, examples, example; missing optional packages, JSON and tables."""

from __future__ import annotations

import json
import math
import os
import re
import subprocess
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from typer.testing import CliRunner

import linkwork as lw
from commandline import linkwork
from linkwork.cli.main import app
from linkwork.examples import names, text

runner = CliRunner()
ROOT = Path(__file__).resolve().parents[2]


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


def test_readme_quick_start_has_two_commands_and_the_main_job_runs(main_job):
    assert len(main_job.commands) == 2
    assert main_job.args[:2] == ["linkwork", "analyze"]
    assert main_job.returncode == 0, main_job.stderr
    report = (main_job.folder / "report.html").read_text(encoding="utf-8")
    assert "I(0,1) -&gt; II(2,3) -&gt; II(4,5) -&gt; II(6,7)" in report
    ci = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    assert main_job.commands[1] in ci


def test_written_files_have_the_mode_of_a_plain_open(tmp_path):
    """Outputs are written through a temporary file, and get the permissions open() would give them."""
    import os

    from linkwork.atomic import write_atomic

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
        assert v["value"] == pytest.approx(si, rel=1e-11)  # JSON numbers have 12 significant digits
    assert [v["line"] for v in out["values"]] == sorted(v["line"] for v in out["values"])
    result = runner.invoke(app, ["check", str(path), "--values"], terminal_width=200)
    assert result.exit_code == 0, result.output
    rows = [re.split(r"\s{2,}", line.strip()) for line in result.stdout.splitlines()]  # piped: plain columns
    table = {r[1]: r for r in rows if len(r) == 5}
    for line, where, written, si, unit in VALUES:
        assert table[where] == [str(line), where, str(written), f"{si:.10g}", unit or "-"]
    assert "values" not in json.loads(runner.invoke(app, ["check", str(path), "--json"]).stdout)


def _commands() -> None:
    """Register every command on ``app`` (as ``linkwork``'s entry point does)."""
    import linkwork.cli.analyze  # noqa: F401
    import linkwork.cli.design  # noqa: F401
    import linkwork.cli.dynamics  # noqa: F401
    import linkwork.cli.forces  # noqa: F401
    import linkwork.cli.impact  # noqa: F401
    import linkwork.cli.motion  # noqa: F401
    import linkwork.cli.view  # noqa: F401


def _hide(monkeypatch: pytest.MonkeyPatch, *packages: str) -> None:
    """Make ``packages`` (and their submodules) fail to import, as if they were not installed."""
    for name in list(sys.modules):
        if name.split(".", 1)[0] in packages:
            monkeypatch.setitem(sys.modules, name, None)
    for name in packages:
        monkeypatch.setitem(sys.modules, name, None)


PIP = 'pip install "linkwork'
SWEEP = ["sweep", "four-bar", "--vary", "links.crank.length=90mm:110mm:3", "--metric", "swing", "--quiet"]


@pytest.mark.parametrize(
    ("hidden", "args", "missing"),
    [
        (("xarray",), ["kinematics", "four-bar", "--out", "{out}"], 'xarray: pip install "linkwork[data]"'),
        (("xarray",), ["analyze", "four-bar", "--out", "{out}"], 'xarray: pip install "linkwork[data]"'),
        (("matplotlib",), ["analyze", "four-bar", "--out", "{out}"], 'matplotlib: pip install "linkwork[plot]"'),
        (
            ("matplotlib", "xarray"),
            ["analyze", "four-bar", "--out", "{out}"],
            'matplotlib and xarray: pip install "linkwork[plot,data]"',
        ),
        (("pyarrow",), [*SWEEP, "--out", "{out}.parquet"], 'pyarrow: pip install "linkwork[design]"'),
        (("xarray",), [*SWEEP, "--out", "{out}.nc"], 'xarray: pip install "linkwork[data]"'),
        (("distributed",), [*SWEEP, "--workers", "1", "--out", "{out}.parquet"], f'distributed: {PIP}[design]"'),
        (("fastapi", "uvicorn"), ["view", "four-bar", "--no-browser"], f'fastapi and uvicorn: {PIP}[web]"'),
    ],
)
def test_a_missing_optional_package_is_one_line_before_any_work(tmp_path, monkeypatch, hidden, args, missing):
    """Without the package an output needs, the command says which and how to install it, exits 2 and
    has written nothing (no CSV before a NetCDF it cannot write, no report without its NetCDF table)."""
    _commands()
    _hide(monkeypatch, *hidden)
    result = runner.invoke(app, [a.format(out=tmp_path / "out") for a in args])
    assert result.exit_code == 2, result.output
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: ") and lines[0].endswith(f" needs {missing}"), lines
    assert list(tmp_path.iterdir()) == []


def test_the_python_api_names_the_missing_package_too(monkeypatch):
    """``to_pandas`` without pandas, the drawings without matplotlib: a LinkworkError that is also an
    ImportError, with the pip command."""
    from linkwork.design.sweeps import SweepTable
    from linkwork.errors import LinkworkError, MissingDependencyError

    table = SweepTable({"variant": np.arange(2), "swing": np.array([0.5, 0.6])}, {"variant": "1", "swing": "rad"})
    _hide(monkeypatch, "pandas")
    with pytest.raises(MissingDependencyError, match=r'needs pandas: pip install "linkwork\[design\]"$') as err:
        table.to_pandas()
    assert isinstance(err.value, LinkworkError) and isinstance(err.value, ImportError)
    _hide(monkeypatch, "matplotlib")
    for name in [n for n in sys.modules if n.startswith("linkwork.figures")]:
        monkeypatch.delitem(sys.modules, name)
    with pytest.raises(MissingDependencyError, match=r'needs matplotlib: pip install "linkwork\[plot\]"$'):
        import linkwork.figures  # noqa: F401


def test_numba_comes_with_linkwork_and_pandas_with_its_tables():
    """numba is a core dependency where it has wheels (CPython 3.11 to 3.15 on x86-64 and ARM Linux,
    x86-64 Windows, macOS); pandas comes with the extra whose tables offer ``to_pandas``."""
    import tomllib

    from packaging.requirements import Requirement

    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    core = {Requirement(r).name: Requirement(r) for r in project["dependencies"]}
    marker = core["numba"].marker

    def env(python: str, system: str, machine: str, implementation: str = "CPython") -> dict[str, str]:
        return {
            "python_version": python,
            "sys_platform": system,
            "platform_machine": machine,
            "platform_python_implementation": implementation,
        }

    for python in ("3.11", "3.12", "3.13", "3.14", "3.15"):
        for system, machine in (("linux", "x86_64"), ("linux", "aarch64"), ("win32", "AMD64"), ("darwin", "arm64")):
            assert marker.evaluate(env(python, system, machine)), (python, system, machine)
    assert marker.evaluate(env("3.13", "darwin", "x86_64"))
    assert not marker.evaluate(env("3.14", "darwin", "x86_64"))  # no wheel: the NumPy kernels run
    assert not marker.evaluate(env("3.16", "linux", "x86_64"))
    assert not marker.evaluate(env("3.11", "linux", "x86_64", "PyPy"))
    extras = project["optional-dependencies"]
    assert "pandas" in {Requirement(r).name for r in extras["design"]}
    assert not any(Requirement(r).name == "numba" for reqs in extras.values() for r in reqs)
    from linkwork.motion import kernels_numba

    if marker.evaluate() and os.environ.get("LINKWORK_NUMBA") == "1":
        assert kernels_numba.available()  # installed with linkwork here, and asked for: the compiled kernels run


def _strict(text: str) -> Any:
    def refuse(constant: str) -> None:
        raise ValueError(f"not JSON: {constant}")

    return json.loads(text, parse_constant=refuse)


def test_json_numbers_are_rounded_and_zeros_are_zeros():
    """The four-bar's crank at 60 + 30 k deg: the angles are written as the round numbers they are, and
    the crank pin A at 90 and 270 deg has x = 0 (at 0 and 180, y = 0), not a round-off of 1e-17."""
    _commands()
    result = runner.invoke(app, ["kinematics", "four-bar", "--steps", "12", "--json"])
    assert result.exit_code == 0, result.output
    out = _strict(result.stdout)
    angles = out["crank_angle_to_x_deg"]
    assert angles == [(60.0 + 30 * k) % 360 for k in range(12)]
    a = out["points"]["A"]
    for k, angle in enumerate(angles):
        if angle % 180 == 90:
            assert a["x"][k] == 0.0 and a["vy"][k] == 0.0 and a["ax"][k] == 0.0
            assert a["y"][k] == (0.1 if angle % 360 == 90 else -0.1)
        if angle % 180 == 0:
            assert a["y"][k] == 0.0 and a["vx"][k] == 0.0 and a["ay"][k] == 0.0
            assert a["x"][k] == (0.1 if angle % 360 == 0 else -0.1)


def test_json_has_null_where_a_number_is_not_finite(tmp_path):
    """A four-bar whose coupler (100 mm) lets it assemble only over part of the turn: the positions it
    does not reach, and the quantities that have no value, are null; the output is strict JSON."""
    _commands()
    src = text("four-bar").replace("length: 350", "length: 100").replace("B: [330, 240]", "B: [140, 130]")
    path = tmp_path / "partial.yaml"
    path.write_text(src.replace("M: [175, 80]", "M: [50, 20]"), encoding="utf-8")
    result = runner.invoke(app, ["kinematics", str(path), "--steps", "36", "--json"])
    assert result.exit_code == 0, result.output
    assert "NaN" not in result.stdout and "Infinity" not in result.stdout
    out = _strict(result.stdout)
    x = out["points"]["B"]["x"]
    assert 0 < x.count(None) < 36
    assert all((v is None) == (not ok) for v, ok in zip(x, out["valid"], strict=True))


def test_the_json_writer_rule():
    """Twelve significant digits; zero below 1e-10 of the typical magnitude of its quantity (its array, with
    the other component of its vector: fx with fy); a number alone as it is; NaN and infinities as null."""
    from linkwork.io.jsonout import dumps

    data = {
        "angle": 29.999999999999996,
        "point": {"x": 0.3, "y": -2e-12},
        "fx": [250.0, 1e-13, -0.0],
        "fy": [3e-14, -1e-7],
        "residuals": {"power": 1.6e-16, "momentum": 2.5e-15},
        "rows": [[1e-20, 2.0], [3.0, float("inf")]],
        "stroke": float("nan"),
        "count": np.int64(12),
        "array": np.array([1.0, 1e-15]),
    }
    assert _strict(dumps(data)) == {
        "angle": 30.0,
        "point": {"x": 0.3, "y": 0.0},
        "fx": [250.0, 0.0, 0.0],
        "fy": [0.0, -1e-07],
        "residuals": {"power": 1.6e-16, "momentum": 2.5e-15},
        "rows": [[0.0, 2.0], [3.0, None]],
        "stroke": None,
        "count": 12,
        "array": [1.0, 0.0],
    }


def _quantity(record: dict[str, Any], key: str) -> list[Any]:
    """The numbers of ``record[key]`` with those of the other component of the same vector (``x`` with ``y``)."""
    other = key[:-1] + ("y" if key.endswith("x") else "x") if key[-1:] in ("x", "y") else None
    group = [record[key]] + ([record[other]] if other in record else [])
    return [v for g in group for v in (g if isinstance(g, list | tuple | np.ndarray) else [g])]


def _round_off(value: float, quantity: list[Any]) -> bool:
    """Whether ``value`` is a zero of round-off by the manual's rule: below 1e-10 of the magnitude below which
    nine tenths of the non-zero finite numbers of its quantity lie."""
    m = sorted(abs(float(v)) for v in quantity if v is not None and math.isfinite(float(v)) and v != 0)
    if not m:
        return False
    at = 0.9 * (len(m) - 1)
    typical = m[int(at)] + (at - int(at)) * (m[min(int(at) + 1, len(m) - 1)] - m[int(at)])
    return abs(value) < 1e-10 * typical


def _twelve_digits(value: float, written: Any) -> bool:
    """Whether ``written`` is ``value`` to 12 significant digits (a tie of the 13th either way)."""
    if value == 0.0 or written is None:
        return written == value
    unit = 10.0 ** (math.floor(math.log10(abs(value))) - 11)
    return abs(written - value) <= 0.501 * unit and written == float(f"{written:.12g}")


def _disagreements(python: Any, written: Any, path: str = "") -> list[str]:
    """Each number of the record ``python`` that the JSON ``written`` does not give to 12 significant digits
    and that is not a zero of round-off of its own quantity (paths)."""
    wrong: list[str] = []
    for key, v in python.items() if isinstance(python, dict) else []:
        items = list(np.ravel(v)) if isinstance(v, np.ndarray) else v
        if isinstance(v, dict):
            wrong += _disagreements(v, written[key], f"{path}.{key}")
        elif isinstance(items, list | tuple) and any(isinstance(x, dict) for x in items):
            wrong += [e for x, w in zip(items, written[key], strict=True) for e in _disagreements(x, w, path)]
        elif isinstance(v, float | list | tuple | np.ndarray):
            pairs = zip(np.ravel(np.asarray(v, dtype=object)), np.ravel(written[key]), strict=True)
            for i, (p, w) in enumerate(pairs):
                if not isinstance(p, bool | str | type(None)) and not _agrees(float(p), w, _quantity(python, key)):
                    wrong.append(f"{path}.{key}[{i}]: {p!r} written {w!r}")
    return wrong


def _agrees(value: float, written: Any, quantity: list[Any]) -> bool:
    """Whether ``written`` is ``value`` (a float of ``quantity``) as the manual says the JSON writes it."""
    if not math.isfinite(value):
        return written is None
    return _twelve_digits(value, written) or (written == 0.0 and _round_off(value, quantity))


@pytest.mark.parametrize("example", [*names(), "four-bar stopping on a sample"])
def test_every_json_number_is_the_value_or_a_zero_of_round_off(example, tmp_path, monkeypatch):
    """Every number `kinematics --json` and `forces --json` write equals the Python value to 12 significant
    digits or is a zero of round-off of its own quantity, for every bundled example and a four-bar whose
    crank stops exactly on the 300 deg sample (O4 at 100 mm: the speeds there have no finite limit, an
    acceleration of 2.6e23 m/s^2), whose B moves and whose driving torque is not zero at any valid angle."""
    import linkwork.io.jsonout as jsonout

    _commands()
    source = example
    if example not in names():
        source = str(tmp_path / "stops.yaml")
        Path(source).write_text(text("four-bar").replace("O4: [300, 0]", "O4: [100, 0]"), encoding="utf-8")
    seen: list[tuple[Any, str]] = []
    dumps = jsonout.dumps
    monkeypatch.setattr(jsonout, "dumps", lambda data, **kw: seen.append((data, dumps(data, **kw))) or seen[-1][1])
    for command in ("kinematics", "forces"):
        result = runner.invoke(app, [command, source, "--json"])
        assert result.exit_code == 0, result.output
        python, written = seen[-1]
        assert _strict(written) == _strict(result.stdout)
        assert _disagreements(python, _strict(written)) == []
    if example not in names():
        kin, forces = (_strict(text) for _, text in seen)
        ok = np.array(kin["valid"])
        assert 0 < ok.sum() < ok.size
        for key in ("x", "y", "vx", "vy", "ax", "ay"):
            assert all(v != 0.0 for v in np.array(kin["points"]["B"][key])[ok]), key
        assert all(v != 0.0 for v in np.array(forces["driving_torque"])[ok])


def test_positions_at_the_bound_take_each_point_once_and_write_what_each_position_gives(monkeypatch):
    """`positions --count N` reads each point's positions once for all N (not once a position: 100,000 took
    minutes), and writes for each position the point's coordinates in mm to 0.001 mm, as a pose of the
    kinematics at that one angle gives them."""
    from linkwork.motion.kinematic_analysis import Kinematics

    _commands()
    calls = []
    position = Kinematics.position
    monkeypatch.setattr(Kinematics, "position", lambda self, name: calls.append(name) or position(self, name))
    result = runner.invoke(app, ["positions", "four-bar", "--count", "2000", "--json"])
    assert result.exit_code == 0, result.output
    rows = _strict(result.stdout)["positions"]
    assert len(rows) == 2000 and len(calls) == len(rows[0]) - 3  # position, phi_deg, crank_angle_to_x_deg
    mech = lw.compile(lw.example("four-bar"))
    for row in rows[::397]:
        one = lw.kinematics(mech, angles=[math.radians(row["crank_angle_to_x_deg"])])
        for label in ("A", "B", "M"):
            point = "coupler.M" if label == "M" else label
            assert row[label] == pytest.approx(one.position(point)[0] * 1000, abs=6e-4), (row, label)


def test_many_records_are_written_as_each_alone():
    """The JSON writer's column-by-column path for many records alike writes what it writes of each record
    alone (numbers, short arrays with their own zeros of round-off, nulls, ints and text)."""
    from linkwork.io.jsonout import _clean, dumps

    rng = np.random.default_rng(7)
    for _ in range(50):
        width = int(rng.integers(1, 5))
        rows = []
        for k in range(int(rng.integers(9, 30))):
            point = (rng.standard_normal(width) * 10.0 ** rng.integers(-18, 6, size=width)).tolist()
            point[int(rng.integers(width))] = [0.0, None, -1e-17, point[0]][int(rng.integers(4))]
            rows.append({"k": k, "angle": float(rng.standard_normal()), "P": point, "name": "e\u0301"})
        assert dumps(rows) == json.dumps([_clean(r, None) for r in rows])


def test_a_piped_table_is_written_as_rich_lays_it_out(monkeypatch, capsys):
    """The piped tables are written without rich's layout (100,000 rows of positions took minutes), line for
    line as rich lays them out: widths of wide (CJK) and combining characters, escaped markup, right-justified
    columns, an empty cell."""
    from rich.markup import escape

    import linkwork.cli.app as cli

    def table():
        tab = cli.make_table(escape("Ножницы [剪刀] e\u0301: positions"))
        tab.add_column("pos")
        tab.add_column("连杆, mm", justify="right")
        tab.add_column(escape("[B]"))
        for row in (("0", "1.5, 2.0", "x"), ("11", "-", ""), ("2", "刀_下", escape("a[b]\\"))):
            tab.add_row(*row)
        return tab

    cli.show(cli.make_console(), table())
    ours = capsys.readouterr().out
    monkeypatch.setattr(cli, "_plain_lines", lambda tab: None)
    cli.show(cli.make_console(), table())
    assert ours == capsys.readouterr().out and "刀_下" in ours


def test_tables_are_plain_text_when_piped():
    """Piped, `linkwork check` prints what the manual shows: no box characters, no trailing blanks (the
    command in a process of its own, its stdout a pipe; the tables of the others, whose stdout is no terminal
    either, in this process)."""
    from manual import page

    shown = page("how-to/check.md").split("$ linkwork check double-cut-shears\n", 1)[1].split("```", 1)[0]
    proc = subprocess.run(
        [sys.executable, "-m", "linkwork.cli", "check", "double-cut-shears"], capture_output=True, text=True
    )
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout == shown
    for command in (["positions", "four-bar"], ["forces", "four-bar", "--steps", "36"]):
        proc = linkwork(*command)
        assert proc.returncode == 0, proc.stderr
        assert proc.stdout.isascii(), command
        assert all(line == line.rstrip() for line in proc.stdout.splitlines())


def test_a_process_exits_with_its_objects_frozen_and_all_its_output_written():
    """The command's process freezes its objects as it exits (after every other exit handler: a handler
    registered before ``main`` runs after it and finds them frozen), so that the shutdown's collections
    skip them; 3.6 MB of JSON piped out of it still arrive whole, the last sample equal to
    ``lw.kinematics`` of the same angle solved here."""
    import linkwork as lw

    code = (
        "import atexit, gc, sys\n"
        "atexit.register(lambda: print('frozen', gc.get_freeze_count(), file=sys.stderr))\n"
        "from linkwork.cli.main import main\n"
        "sys.argv = ['linkwork', 'kinematics', 'double-cut-shears', '--steps', '3600', '--json']\n"
        "main()\n"
    )
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    frozen = re.search(r"^frozen (\d+)$", proc.stderr, re.MULTILINE)
    assert frozen is not None and int(frozen.group(1)) > 10_000, proc.stderr
    data = json.loads(proc.stdout)
    assert len(data["crank_angle_to_x_deg"]) == 3600
    kin = lw.kinematics(lw.compile(lw.load("double-cut-shears")), np.radians(data["crank_angle_to_x_deg"][-1:]))
    edge = next(name for name in data["points"] if name.endswith(".edge"))  # a knife's edge
    xy = kin.position(edge)[-1]
    assert data["points"][edge]["x"][-1] == pytest.approx(xy[0], abs=1e-12)
    assert data["points"][edge]["y"][-1] == pytest.approx(xy[1], abs=1e-12)


def test_tables_fit_the_terminal():
    """In a terminal 50 columns wide, the table of the 12 positions comes in parts that fit, each with the
    position and the crank angle, no cell cut short."""
    import fcntl
    import pty
    import struct
    import termios

    leader, follower = pty.openpty()
    fcntl.ioctl(follower, termios.TIOCSWINSZ, struct.pack("HHHH", 50, 50, 0, 0))
    env = {k: v for k, v in os.environ.items() if k not in ("COLUMNS", "LINES", "FORCE_COLOR", "NO_COLOR")}
    proc = subprocess.Popen(
        [sys.executable, "-m", "linkwork.cli", "positions", "four-bar"],
        stdout=follower,
        stderr=follower,
        env={**env, "TERM": "xterm"},
    )
    os.close(follower)
    chunks = []
    while True:
        try:
            chunk = os.read(leader, 4096)
        except OSError:  # the other end closed
            break
        if not chunk:
            break
        chunks.append(chunk)
    assert proc.wait(timeout=60) == 0
    os.close(leader)
    screen = re.sub(r"\x1b\[[0-9;?]*[A-Za-z]", "", b"".join(chunks).decode("utf-8"))
    lines = screen.replace("\r", "").splitlines()
    assert max(len(line) for line in lines) <= 50
    assert "…" not in screen
    headers = [line for line in lines if line.startswith("┃ pos")]
    assert len(headers) > 1
    assert {"O2", "A", "B", "M", "O4"} <= {c.strip() for h in headers for c in h.split("┃")}
    rows = [line for line in lines if line.startswith("│ ")]
    assert len(rows) == 12 * len(headers)


@pytest.mark.parametrize("position", ["12", "-1"])
def test_analyze_takes_one_of_the_12_positions(tmp_path, position):
    _commands()
    result = runner.invoke(app, ["analyze", "four-bar", "--out", str(tmp_path / "r"), "--position", position])
    assert result.exit_code == 2
    assert result.stderr.strip() == (
        "error: --position: expected one of the 12 positions, 0 to 11, all, or a crank angle from position 0 with "
        f'its unit, 0 to 360 deg (e.g. 87deg), got "{position}"'
    )
    assert list(tmp_path.iterdir()) == []


def test_check_starts_without_the_packages_it_does_not_need():
    """``linkwork check`` (and the start of every command) needs neither pint's registry for the common
    units, nor scipy's optimiser, numba (imported when compiled kernels first run), matplotlib or xarray."""
    code = (
        "import sys\nfrom linkwork.cli.main import app\ntry:\n    app(['check', 'double-cut-shears'])\n"
        "except SystemExit:\n    pass\n"
        "print(sorted(m for m in ('pint', 'scipy.optimize', 'numba', 'matplotlib', 'xarray') if m in sys.modules))"
    )
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, env=env)
    assert "W = 3n - 2p5 - p4 = 3*7 - 2*10 = 1" in out.stdout
    assert out.stdout.strip().splitlines()[-1] == "[]"


def test_the_sweep_draws_its_progress_bar_on_a_terminal_only(tmp_path):
    """Piped to a file, stderr holds no bar (rich's box characters, cursor moves); on a terminal (a
    pseudo-terminal given to a process of its own here) the bar is drawn; the table is the same either way."""
    import pty

    sweep = [a for a in SWEEP if a != "--quiet"]
    piped = linkwork(*sweep, "--out", str(tmp_path / "a.parquet"))  # stderr no terminal
    assert piped.returncode == 0, piped.stderr
    assert "━" not in piped.stderr and "\x1b[" not in piped.stderr and "chunks" not in piped.stderr
    leader, follower = pty.openpty()
    args = [sys.executable, "-m", "linkwork.cli", *sweep, "--out", str(tmp_path / "b.parquet")]
    with subprocess.Popen(
        args, stdout=subprocess.DEVNULL, stderr=follower, env={**os.environ, "COLUMNS": "100", "TERM": "xterm"}
    ) as proc:
        os.close(follower)
        drawn = b""
        while True:
            try:
                chunk = os.read(leader, 4096)
            except OSError:
                break
            if not chunk:
                break
            drawn += chunk
    os.close(leader)
    shown = re.sub(r"\x1b\[[0-9;?]*[A-Za-z]", "", drawn.decode("utf-8", "replace"))
    assert proc.returncode == 0 and "━" in shown and "1/1 chunks" in shown, shown
    pq = pytest.importorskip("pyarrow.parquet")
    a, b = (pq.read_table(tmp_path / n).to_pydict() for n in ("a.parquet", "b.parquet"))
    assert a["swing"] == b["swing"] and len(a["swing"]) == 3


def test_the_pair_table_shows_a_zero_where_the_json_writes_one():
    """The knives' guides of the double-cut shears carry no moment (each knife's forces pass through its
    slider point, on the guide's axis), so the largest moment of each guide is round-off: the table shows 0,
    as the JSON does, and the largest forces are those refined between the JSON's samples (never below them) to the
    table's six digits."""
    from linkwork.kinetostatics.peaks import pair_force_peaks

    args = ["forces", "double-cut-shears", "--steps", "72"]
    text = linkwork(*args)
    data = json.loads(linkwork(*args, "--json").stdout)
    assert text.returncode == 0, text.stderr
    rows = {line.split()[0]: line.split() for line in text.stdout.splitlines() if line.startswith("  guide_")}
    assert set(rows) == {"guide_E", "guide_F"}
    for name, row in rows.items():
        joint = data["joints"][name]
        assert row[-1] == "0" and max(map(abs, joint["moment"])) == 0.0, row
        mech = lw.compile(lw.load("double-cut-shears"))
        k = [i for i in range(mech.n_pairs) if mech.pair_joint[i] == name]
        refined = pair_force_peaks(lw.forces(mech, steps=72), k).value[0]
        assert float(row[-4]) == pytest.approx(refined, rel=1e-5)
        assert float(row[-4]) >= np.hypot(joint["fx"], joint["fy"]).max() * (1 - 1e-5)


def test_a_command_that_loaded_arrow_ends_with_its_code_its_output_and_its_exit_handlers(tmp_path):
    """``run`` (the script's entry point) ends a process that loaded Arrow before the native teardown, which can
    abort it after its work (apache/arrow#34314): the exit code, every line written (also unflushed, also a
    ``sys.exit`` message) and Python's exit handlers must survive that ending.  Each case in a process of its
    own: the code, what stdout and stderr hold, and the file an exit handler writes."""
    marker = tmp_path / "handler-ran"
    cases = {
        "sys.exit(3)": (3, ""),
        "sys.exit('no such file: x.yaml')": (1, "no such file: x.yaml"),
        "pass": (0, ""),
    }
    for body, (code, message) in cases.items():
        marker.unlink(missing_ok=True)
        script = (
            "import atexit, pathlib, sys\nimport pyarrow\nimport linkwork.cli.main as m\n"
            f"atexit.register(lambda: pathlib.Path({str(marker)!r}).write_text('ran'))\n"
            f"def main():\n    print('partial line', end='')\n    {body}\n"
            "m.main = main\nm.run()\nprint('not reached')\n"
        )
        proc = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True)
        assert proc.returncode == code, (body, proc.stderr)
        assert proc.stdout == "partial line" and proc.stderr.strip() == message, (body, proc.stdout, proc.stderr)
        assert marker.read_text() == "ran", body
