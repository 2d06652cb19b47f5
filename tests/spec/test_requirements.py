"""A file's ``requirements:`` edited by hand: refused where it is read (``check``, ``analyze``, the viewer alike),
with the file's line, never a traceback later."""

from __future__ import annotations

import math

import pytest

import linkwork as lw
from commandline import linkwork
from linkwork.requirements import needs
from linkwork.spec.requirements import KINDS, QUANTITY

SLIDER_CRANK = """\
name: slider-crank
units: {length: mm, angle: deg}
frame:
  points: {O: [0, 0]}
links:
  crank: {ends: [O, A], length: 100}
  rod: {ends: [A, B], length: 350}
  ram: {points: {B: [0, 0]}}
joints:
  O: {type: revolute, links: [frame, crank]}
  A: {type: revolute, links: [crank, rod]}
  B: {type: revolute, links: [rod, ram]}
  guide: {type: prismatic, links: [frame, ram], point: B, through: [0, 0], axis: 0 deg}
drives:
  - {joint: O, angle: 0 deg}
hints:
  B: [450, 0]
requirements:
  kind: slider-crank
  stroke: 200 mm
  time_ratio: 1.0
  max_pressure_angle: 40 deg
"""

#: The line of ``requirements:`` in :data:`SLIDER_CRANK` (1-based); its entries follow.
LINE = SLIDER_CRANK.splitlines().index("requirements:") + 1


def edited(key: str, value: str) -> str:
    """:data:`SLIDER_CRANK` with the requirement ``key`` set to ``value`` (added last where it is not there)."""
    lines = SLIDER_CRANK.splitlines()
    for i, line in enumerate(lines):
        if line.startswith(f"  {key}:"):
            lines[i] = f"  {key}: {value}"
            break
    else:
        lines.append(f"  {key}: {value}")
    return "\n".join(lines) + "\n"


def line_of(text: str, key: str) -> int:
    return next(i for i, line in enumerate(text.splitlines(), 1) if line.startswith(f"  {key}:"))


def test_the_file_as_written_is_read():
    spec = lw.loads(SLIDER_CRANK)
    assert spec.requirements is not None and spec.requirements["stroke"] == "200 mm"


@pytest.mark.parametrize(
    ("key", "value", "says"),
    [
        ("time_ratio", '"1.3 deg"', 'a ratio is a plain number, got "1.3 deg"'),
        ("colour", "blue", '"colour" is no requirement of a slider-crank; expected stroke, time_ratio'),
        ("swing", "45 deg", '"swing" is no requirement of a slider-crank'),
        ("stroke", "0.2", 'give the unit, e.g. "400 mm", got 0.2'),
        ("stroke", '"0.2"', "give the unit"),
        ("stroke", "200 kg", "expected a length"),
        ("stroke", "-200 mm", "expected a finite value in (0, 1e+09] m"),
        ("time_ratio", ".inf", "expected a finite value in [1, 3), got .inf"),
        ("time_ratio", ".nan", "got .nan"),
        ("time_ratio", "3", "expected a finite value in [1, 3), got 3"),
        ("time_ratio", "0.5", "[1, 3)"),
        ("max_pressure_angle", "90 deg", "expected a finite value in (0, 90) deg"),
        ("criterion", "cost", "expected one of pressure, torque"),
        ("kind", "four-bar", "expected one of slider-crank, crank-rocker"),
    ],
)
def test_a_hand_edited_requirement_is_refused_by_check_and_analyze_alike_at_its_line(tmp_path, key, value, says):
    text = edited(key, value)
    path = tmp_path / "edited.yaml"
    path.write_text(text, encoding="utf-8")
    where = f"edited.yaml:{line_of(text, key)}: requirements.{key}: "
    for command in (["check", str(path)], ["analyze", str(path), "--out", str(tmp_path / "out")]):
        result = linkwork(*command)
        assert result.returncode == 2, (command, result.stderr)
        assert result.stderr.count("\n") == 1 and where in result.stderr and says in result.stderr, result.stderr
        assert "Traceback" not in result.stderr
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("kind", list(KINDS))
@pytest.mark.parametrize("value", [".inf", "-.inf", ".nan"])
def test_no_requirement_of_any_kind_may_be_non_finite(kind, value):
    """Every requirement of every kind, given as .inf, -.inf or .nan, and a quantity also with its unit: refused
    (``time_ratio: .inf`` was reported as met)."""
    unit = {"length": "mm", "angle": "deg", "force": "N", "moment": "N*m"}
    for name in KINDS[kind]:
        forms = [value] + ([f'"{value.replace(".", "")} {unit[QUANTITY[name]]}"'] if name in QUANTITY else [])
        for written in forms:
            text = SLIDER_CRANK.replace("  kind: slider-crank\n", f"  kind: {kind}\n")
            text = "\n".join(ln for ln in text.splitlines() if not ln.startswith(("  stroke", "  time", "  max_p")))
            text += f"\n  {name}: {written}\n"
            with pytest.raises(lw.errors.SpecError) as info:
                lw.loads(text, "x.yaml")
            assert f"requirements.{name}: " in str(info.value), written


def test_the_shears_requirements_on_a_slider_crank_name_what_the_file_lacks():
    """The knives' strokes are measured on the shears' guides and their process load: a slider-crank file
    with the shears' requirements is refused at ``kind``, naming them (``analyze`` failed on it with an
    AssertionError, the viewer's family with a 500)."""
    text = SLIDER_CRANK.replace("kind: slider-crank", "kind: double-cut-shears")
    text = text.replace("  stroke: 200 mm\n", "  upper_stroke: 200 mm\n  lower_stroke: 200 mm\n  overlap: 20 mm\n")
    text = text.replace("  max_pressure_angle: 40 deg\n", "")
    with pytest.raises(lw.errors.SpecError) as info:
        lw.loads(text, "x.yaml")
    message = str(info.value)
    assert f"x.yaml:{LINE + 1}: requirements.kind" in message
    assert message.endswith("this file has no process load with two tools (the knives)"), message


@pytest.mark.parametrize(
    ("kind", "asked"),
    [
        ("slider-crank", {"stroke": "400 mm", "time_ratio": 1.2, "offset": "50 mm", "max_pressure_angle": "50 deg"}),
        ("crank-rocker", {"swing": "45 deg", "time_ratio": 1.2, "rocker": "300 mm"}),
        ("slotted-lever", {"stroke": "600 mm", "time_ratio": 1.4, "rod": "300 mm", "max_pressure_angle": "30 deg"}),
        (
            "toggle-press",
            {"stroke": "200 mm", "force": "100 kN", "before": "10 mm", "torque": "5 kN*m", "swing": "40 deg"},
        ),
    ],
)
def test_the_requirements_each_kind_may_carry_are_those_its_synthesis_writes(kind, asked):
    """What a kind's synthesis writes into the file's ``requirements:`` is what the file format accepts for that kind,
    each requirement given in the same kind of quantity as the file reads it (the file is read back through the
    checks, and its values agree with the request); the slider-crank's bound on K is the synthesis's own
    (derived: theta < 90 deg)."""
    from linkwork.spec.edit import round_trip_yaml
    from linkwork.synthesis.slider_crank import K_LIMIT
    from linkwork.units import parse_quantity

    written = dict(round_trip_yaml().load(lw.synthesize(kind, **asked).text)["requirements"])
    assert written.pop("kind") == kind
    names = [n for n in written if not n.endswith("_tolerance")]
    assert set(asked) <= set(names) <= set(KINDS[kind])
    for name, value in asked.items():
        got = parse_quantity(written[name], QUANTITY[name]) if name in QUANTITY else float(written[name])
        want = parse_quantity(value, QUANTITY[name]) if isinstance(value, str) else value
        assert got == pytest.approx(want, rel=1e-12), name
    assert needs("slider-crank")["time_ratio"].within[1] == K_LIMIT
    theta = math.pi / 2
    assert (math.pi + theta) / (math.pi - theta) == K_LIMIT
