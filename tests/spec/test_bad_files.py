"""The corpus of bad mechanism files: each must give exactly its messages, with file:line, and exit code 2.

``tests/spec/bad/NAME.yaml`` is a small four-bar with one mistake;
``tests/spec/bad/NAME.expected`` lists, one per line, what linkwork must print for
it after the file name: ``LINE: PATH: MESSAGE``, or just the message for
errors of the mechanism as a whole (mobility, assembly).
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest
from typer.testing import CliRunner

from linkwork.cli.main import app
from linkwork.errors import SpecError

BAD = Path(__file__).parent / "bad"
CASES = sorted(p.stem for p in BAD.glob("*.yaml"))


def test_the_corpus_is_large_enough():
    assert len(CASES) >= 20


def expected_lines(name: str) -> list[str]:
    path = BAD / f"{name}.yaml"
    lines = (BAD / f"{name}.expected").read_text(encoding="utf-8").splitlines()
    return [f"{path}:{line}" if line[0].isdigit() else f"{path}: {line}" for line in lines]


@pytest.mark.parametrize("name", CASES)
def test_bad_file_gives_each_problem_with_its_line_and_exit_code_2(name):
    path = BAD / f"{name}.yaml"
    result = CliRunner().invoke(app, ["check", str(path)])
    assert result.exit_code == 2
    assert "Traceback" not in result.output
    assert result.stdout == ""
    got = [line.removeprefix("error: ") for line in result.stderr.splitlines() if line != "error:"]
    assert got == expected_lines(name)


@pytest.mark.parametrize("name", ["yaml-syntax", "wrong-unit", "unassemblable", "mobility-three"])
def test_bad_file_through_the_real_command(name):
    """The installed entry point: exit code 2, messages on stderr, no traceback."""
    path = BAD / f"{name}.yaml"
    proc = subprocess.run([sys.executable, "-m", "linkwork.cli", "check", str(path)], capture_output=True, text=True)
    assert proc.returncode == 2
    assert "Traceback" not in proc.stderr
    assert proc.stdout == ""
    assert expected_lines(name)[0] in proc.stderr


def test_spec_error_collects_every_problem_in_one_pass():
    from linkwork import load

    with pytest.raises(SpecError) as err:
        load(BAD / "missing-joints.yaml")
    assert len(err.value.problems) == 5  # the hint of B: not a problem of its own while the joints are missing
    assert [p.line for p in err.value.problems] == [2, 6, 7, 8, 10]


@pytest.mark.parametrize(
    "text, message",
    [
        ("~\n", "the file is empty"),
        ("foo: &a [*a]\n", "an alias that contains itself"),
        ("name: x\nlinks: {a: {ends: [O, A], length: " + "9" * 400 + "}}\n", "a number too large to use"),
        ("name: x\nlinks: {a: {ends: [O, A], length: 1e300}}\n", "(out of range)"),
        ('name: x\nlinks: {a: {ends: [O, A], length: "10**10**9 mm"}}\n', "write a number and a unit"),
        ("name: x\njoints: {J: {type: revolute, links: 5}}\n", "joints.J.links: expected a list, got 5"),
        ("name: x\nloads: {L: {type: [1]}}\n", "loads.L.type: expected one of force, moment, process, friction"),
        ("name: x\nmachine: {motor: {type: [1]}}\n", "machine.motor.type: expected one of constant, linear"),
    ],
)
def test_hostile_files_give_messages_not_tracebacks(tmp_path, text, message):
    path = tmp_path / "bad.yaml"
    path.write_text(text, encoding="utf-8")
    result = CliRunner().invoke(app, ["check", str(path)])
    assert result.exit_code == 2
    assert message in result.stderr
    assert "Traceback" not in result.output


@pytest.mark.parametrize("ends", ["[]", "[A]"])
def test_a_link_of_fewer_than_two_ends_is_a_message_not_a_traceback(tmp_path, ends):
    """A file the schema accepts whose link has fewer than two ``ends``: the checks that need SI values
    (coincident points) must not index the missing end."""
    from linkwork.examples import text

    path = tmp_path / "bad.yaml"
    path.write_text(text("four-bar").replace("ends: [O2, A]", f"ends: {ends}"), encoding="utf-8")
    result = CliRunner().invoke(app, ["check", str(path)])
    assert result.exit_code == 2, result.output
    assert "links.crank.ends: expected two point names" in result.stderr
    assert "Traceback" not in result.output


def test_rich_markup_in_names_is_printed_as_is(tmp_path):
    from linkwork.examples import text

    path = tmp_path / "m[1].yaml"
    path.write_text(text("four-bar").replace("name: four-bar", 'name: "x [/bold] y"'), encoding="utf-8")
    result = CliRunner().invoke(app, ["check", str(path)])
    assert result.exit_code == 0, result.output
    assert "x [/bold] y" in result.stdout


def test_a_bad_value_is_echoed_one_way_as_the_file_writes_it():
    """true as true wherever it is refused (a length, a direction), .inf as .inf, text in double quotes, a
    list as a list: spelled as YAML writes them, whichever stage of the reading refuses them."""
    import linkwork as lw
    from linkwork.errors import SpecError
    from linkwork.examples import text

    bad = (
        text("four-bar")
        .replace("length: 100", "length: true")
        .replace("direction: ccw", "direction: true")
        .replace("mass: 1.0", "mass: .inf")
        .replace("mass: 2.5", "mass: [1, 2]")
        .replace("type: revolute, links: [frame, crank]", "type: yes, links: [frame, crank]")
    )
    with pytest.raises(SpecError) as caught:
        lw.loads(bad, file="bad.yaml")
    lines = str(caught.value).splitlines()
    assert lines == [
        "bad.yaml:17: links.crank.length: expected a length, got true",
        "bad.yaml:18: links.crank.mass: expected a mass, got .inf",
        "bad.yaml:23: links.coupler.mass: expected a mass, got a list",
        'bad.yaml:30: joints.O2.type: expected one of revolute, prismatic, pin-in-slot, got "yes"',
        "bad.yaml:36: drives[0].direction: expected one of ccw, cw, forward, backward, got true",
    ]


def _edited(example: str, old: str, new: str) -> str:
    from linkwork.examples import text

    body = text(example)
    assert old in body
    return body.replace(old, new, 1)


@pytest.mark.parametrize(
    "example, old, new, says",
    [
        ("double-cut-shears", "axis: 90 deg          #", "axis:  #", 'loads.cutting.axis: "axis" has no value'),
        ("double-cut-shears", "force: [0 kN, 250 kN, 250 kN, 0 kN]", "force: ~", "loads.cutting.force: "),
        ("double-cut-shears", "breakdown: 2.2", "breakdown:", "machine.motor.breakdown: "),
        ("double-cut-shears", "ratio: 48.33", "ratio: 1e300", "machine.gear.ratio: expected a number at most 1000"),
        ("percussion-rocker", "friction: 0.15", "friction: .inf", "impact.friction: expected a finite number"),
        ("percussion-rocker", "breakdown: 2.2", "breakdown: .nan", "machine.motor.breakdown: expected a finite"),
        ("percussion-rocker", "speed: 300 rpm", "speed: 1e300 rpm", "drives[0].speed: expected an angular speed of"),
        ("percussion-rocker", "rod_joint: N", "rod_joint:", "impact.rod_joint: "),
        ("four-bar", "hints:", "gravity:\nhints:", 'gravity: "gravity" has no value'),
    ],
    ids=["axis", "force", "breakdown", "ratio", "friction", "nan", "speed", "rod-joint", "gravity"],
)
def test_an_empty_value_or_an_absurd_magnitude_is_one_message_with_its_line(tmp_path, example, old, new, says):
    """Each is one problem, at the line of the edited key (found by counting the lines of the text, not by
    linkwork), where it used to end in a traceback or in NaN printed as a result."""
    body = _edited(example, old, new)
    line = body[: body.index(new)].count("\n") + 1
    path = tmp_path / "m.yaml"
    path.write_text(body, encoding="utf-8")
    result = CliRunner().invoke(app, ["check", str(path)])
    assert result.exit_code == 2 and "Traceback" not in result.output
    assert result.stderr.splitlines() == [line for line in result.stderr.splitlines() if says in line]
    assert result.stderr.startswith(f"error: {path}:{line}: {says}")
