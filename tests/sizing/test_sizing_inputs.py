"""The inputs of the sizing are one record, the schema of the file's ``sizing:`` section (the one home of their
defaults), and every bundled catalogue declares its columns and units and is checked on load."""

from __future__ import annotations

import math
from importlib import resources

import pytest

import linkwork as lw
from commandline import linkwork
from linkwork.errors import LinkworkError, SpecError
from linkwork.examples import text
from linkwork.sizing.common import COLUMNS, bundled, parse_catalogue
from linkwork.sizing.machine_sizing import sizing_inputs
from linkwork.spec.schema import SizingSpec

SHEARS = text("double-cut-shears")


def _shears(extra: str) -> lw.Mechanism:
    """The bundled shears with ``extra`` lines added to its ``sizing:`` section."""
    return lw.compile(lw.loads(SHEARS.replace("  life: 20000 h ", extra + "  life: 20000 h ", 1)))


def test_the_file_section_then_the_record_then_the_keywords_each_over_the_one_before():
    """A field the file gives wins over the schema's default; ``sizing=`` over the file, field by field; a keyword
    option over ``sizing=``; a field given nowhere keeps the schema's default."""
    mech = _shears("  reserve: 0.7\n  steel: C35 normalised\n  friction: 0.3\n")
    inp = sizing_inputs(mech)
    assert (inp.reserve, inp.steel, inp.friction) == (0.7, "C35 normalised", 0.3)
    assert inp.life == 20000 * 3600.0  # the file's, in seconds
    assert inp.bush == SizingSpec().bush == "tin bronze CuSn12 greased"  # given nowhere: the schema's
    over = sizing_inputs(mech, {"reserve": 0.6, "life": "30000 h"}, {"steel": "C45 normalised", "reserve": None})
    assert (over.reserve, over.steel, over.friction) == (0.6, "C45 normalised", 0.3)
    assert over.life == 30000 * 3600.0
    kw = sizing_inputs(mech, SizingSpec(reserve=0.6), {"reserve": 0.5, "life_h": 10000.0, "kind": "roller"})
    assert (kw.reserve, kw.life, kw.bearings) == (0.5, 10000 * 3600.0, "roller")
    assert kw.pins == inp.pins and kw.bolts == inp.bolts  # the file's parts stay


def test_the_defaults_of_the_record_are_those_the_sizing_states():
    """Without a ``sizing:`` section every input is the schema's default: 20000 h, ball bearings, C45, S = 2..."""
    inp = sizing_inputs(lw.compile("four-bar"))
    assert inp == SizingSpec()
    assert (inp.life / 3600, inp.bearings, inp.steel, inp.safety, inp.width_ratio) == (
        20000,
        "ball",
        "C45 normalised",
        2,
        1,
    )
    assert (inp.bolt_class, inp.bolt_safety, inp.joint_safety, inp.friction, inp.load_factor) == (
        "5.6",
        1.5,
        1.5,
        0.2,
        0.25,
    )


def test_a_bare_speed_given_in_python_is_si_and_a_unit_is_read():
    mech = lw.compile("four-bar")
    assert sizing_inputs(mech, {"synchronous": 157.0}).synchronous == 157.0
    assert sizing_inputs(mech, {"synchronous": "1500 rpm"}).synchronous == pytest.approx(1500 * math.pi / 30, rel=1e-15)


def test_an_option_that_is_no_input_is_refused_with_the_one_it_may_mean():
    with pytest.raises(TypeError, match=r"unexpected keyword argument 'steal'.*steel"):
        sizing_inputs(lw.compile("four-bar"), options={"steal": "C45 normalised"})
    with pytest.raises(TypeError, match="'motor'"):  # the file's motor flag is the report's, not an option
        sizing_inputs(lw.compile("four-bar"), options={"motor": True})


def test_values_out_of_range_give_one_problem_each_naming_the_field():
    with pytest.raises(SpecError) as caught:
        sizing_inputs(lw.compile("four-bar"), {"reserve": 1.5, "bearings": "needle", "width_ratio": 0.01})
    paths = sorted(p.path for p in caught.value.problems)
    assert paths == ["sizing.bearings", "sizing.reserve", "sizing.width_ratio"]
    assert len(str(caught.value).splitlines()) == 3


def test_lw_size_refuses_a_bad_input_before_any_computing():
    """``lw.size`` reads its inputs first: a bad one is refused at once (the loads take seconds)."""
    with pytest.raises(SpecError, match=r"sizing\.reserve"):
        lw.size("double-cut-shears", sizing={"reserve": 0.0})
    with pytest.raises(TypeError, match="width_ratio"):
        lw.size("double-cut-shears", width_ratoi=1.0)


def test_a_bad_input_in_the_file_is_its_line_and_the_command_exits_2():
    bad = SHEARS.replace("  life: 20000 h ", "  reserve: 1.5\n  life: 20000 h ", 1)
    line = bad.splitlines().index("  reserve: 1.5") + 1
    with pytest.raises(SpecError) as caught:
        lw.loads(bad, file="shears.yaml")
    assert [(p.path, p.line) for p in caught.value.problems] == [("sizing.reserve", line)]


def test_the_command_line_exits_2_on_a_bad_input_of_the_file(tmp_path):
    path = tmp_path / "shears.yaml"
    path.write_text(SHEARS.replace("  life: 20000 h ", "  bearings: needle\n  life: 20000 h ", 1))
    result = linkwork("size", str(path), "--no-motor")
    assert result.returncode == 2 and "Traceback" not in result.stderr
    assert "sizing.bearings" in result.stderr


# ---------------------------------------------------------------------------------------------- catalogues


def test_every_bundled_catalogue_declares_its_columns_and_reads_against_them():
    """Each CSV file bundled is declared (a new one cannot be added undeclared), and reads with every declared
    column, in SI: the steels' yield strength in Pa, the threads' stress area in m^2 (ISO 898-1: M12, 84.3 mm^2)."""
    data = resources.files("linkwork.sizing").joinpath("data")
    files = sorted(p.name for p in data.iterdir() if p.name.endswith(".csv"))
    assert files == sorted(COLUMNS)
    for name, columns in COLUMNS.items():
        assert set(bundled(name).columns) == set(columns), name
    steels = bundled("steels.csv")
    assert steels.row(steels.names.index("C45 normalised"))["yield"] > 1e8  # hundreds of MPa, in Pa
    threads = bundled("threads.csv")
    assert threads.row(threads.names.index("M12"))["stress area"] == pytest.approx(84.3e-6, rel=1e-12)


def test_a_catalogue_against_its_declaration_says_each_problem_on_its_own_line():
    """A declared column missing, one in a unit of another kind and a value that is no number: three problems,
    one line each, with the catalogue's name and line."""
    body = resources.files("linkwork.sizing").joinpath("data", "steels.csv").read_text(encoding="utf-8")
    lines = body.splitlines()
    head = next(i for i, line in enumerate(lines) if line.startswith("name,"))
    lines[head] = "name,yield [MPa],tensile [mm]"
    first = lines[head + 1].split(",")
    lines[head + 1] = ",".join([first[0], "lots", *first[2:3]])
    lines[head + 2 :] = [",".join(line.split(",")[:3]) for line in lines[head + 2 :]]
    with pytest.raises(LinkworkError) as caught:
        parse_catalogue("\n".join(lines), "steels.csv", COLUMNS["steels.csv"])
    said = str(caught.value).splitlines()
    assert len(said) == 3, said
    assert f"steels.csv:{head + 1}: no column 'endurance' [Pa]" in said
    assert any(s.startswith(f"steels.csv:{head + 1}: column 'tensile': unit [mm] is not a unit of Pa") for s in said)
    assert f"steels.csv:{head + 2}: column 'yield': expected a number" in said


def test_no_such_bundled_catalogue_names_those_there_are():
    with pytest.raises(LinkworkError, match="no bundled catalogue 'gears.csv': one of motors.csv, steels.csv"):
        bundled("gears.csv")
