"""The kinds of synthesis as one registry: each kind's requirements one record, from which ``lw.synthesize``'s
validation, the command's options and the manual's table follow."""

from __future__ import annotations

import inspect
import re
import typing

import pytest

import linkwork as lw
from commandline import linkwork
from linkwork.errors import SynthesisError
from linkwork.requirements import RECORDS, table
from manual import page

#: What each kind cannot do without, as the manual's first table states it.
REQUIRED = {
    "slider-crank": ["stroke", "time_ratio"],
    "crank-rocker": ["swing", "time_ratio"],
    "slotted-lever": ["stroke", "time_ratio"],
    "toggle-press": ["stroke", "force", "before", "torque"],
    "double-cut-shears": ["upper_stroke", "lower_stroke", "time_ratio"],
}


def test_the_manuals_table_of_requirements_is_the_registrys():
    text = page("how-to/synthesize.md")
    start = "<!-- requirements table: linkwork.requirements.table() -->\n\n"
    end = "\n<!-- end of the requirements table -->"
    found = re.search(re.escape(start) + "(.*?)" + re.escape(end), text, re.S)
    assert found, "the table's markers"
    assert found.group(1) == table()
    for kind in REQUIRED:
        assert f"| `{kind}` |" in found.group(1)


@pytest.mark.parametrize("kind", list(REQUIRED))
def test_each_kind_requires_what_the_manual_says_and_names_what_it_takes(kind):
    with pytest.raises(SynthesisError) as missing:
        lw.synthesize(kind)
    assert str(missing.value) == f"{kind}: missing requirement {', '.join(REQUIRED[kind])}"
    with pytest.raises(SynthesisError) as unknown:
        lw.synthesize(kind, swng="45 deg")
    said = str(unknown.value)
    assert said.startswith(f"{kind}: unknown requirement swng; expected {', '.join(REQUIRED[kind])}, "), said
    assert "min_transmission_angle" in said


def test_every_kind_is_one_entry_taking_its_record():
    """The registry, the records and the file format's kinds are the same five, and each kind's ``synthesize`` takes
    one argument, its record (no function of a dozen keywords)."""
    from linkwork.spec.requirements import KINDS as CARRIED
    from linkwork.synthesis import KINDS

    assert list(KINDS) == list(RECORDS) == list(CARRIED) == list(REQUIRED)
    for name, kind in KINDS.items():
        (param,) = inspect.signature(kind.synthesize).parameters.values()
        assert typing.get_type_hints(kind.synthesize)[param.name] is kind.record is RECORDS[name]
    assert [name for name, kind in KINDS.items() if kind.family is None] == ["toggle-press"]


def test_the_command_offers_each_requirement_and_refuses_another_kinds(tmp_path):
    """``--help`` lists an option for every requirement of every kind; one of another kind is refused by name, exit 2,
    no file written."""
    shown = linkwork("synthesize", "--help").stdout
    for kind in REQUIRED:
        for name in REQUIRED[kind]:
            assert f"--{name.replace('_', '-')}" in shown, name
    for name in ("rod-ratio", "offset", "max-pressure-angle", "min-transmission-angle", "working", "criterion"):
        assert f"--{name}" in shown, name
    out = tmp_path / "r.yaml"
    run = linkwork(
        "synthesize",
        "crank-rocker",
        "--swing",
        "45deg",
        "--time-ratio",
        "1.2",
        "--rocker",
        "250mm",
        "--upper-stroke",
        "10mm",
        "--out",
        str(out),
    )
    assert run.returncode == 2
    assert run.stderr.strip() == "error: crank-rocker: --upper-stroke: not a requirement of crank-rocker"
    assert not out.exists()
