"""The double-cut shears' parts are read from the file, not assumed by name: the same mechanism with every part
renamed gives the renamed parameters and guides, and the knives measure the same."""

from __future__ import annotations

import re

import pytest

import linkwork as lw
from linkwork.errors import SynthesisError
from linkwork.examples import text
from linkwork.spec.shears import ShearsParts
from linkwork.synthesis.measuring import knives
from linkwork.synthesis.shears import parts

#: The bundled file's names and new ones for them (whole words).
RENAMED = {
    "guide_E": "slide_top",
    "guide_F": "slide_bottom",
    "knife_upper": "top_knife",
    "knife_lower": "bottom_knife",
    "rocker": "lever",
    "crank": "drive_crank",
    "O1": "Q",
    "D": "P",
    "edge": "blade",
}


def _renamed() -> str:
    out = text("double-cut-shears")
    for old, new in RENAMED.items():
        out = re.sub(rf"\b{old}\b", new, out)
    return out


def test_the_shears_parts_are_read_from_the_file_whatever_it_calls_them():
    bundled = parts(lw.load("double-cut-shears"))
    assert bundled == ShearsParts(
        "crank", "O1", "rocker", ("D", "C"), ("knife_upper", "knife_lower"), ("edge", "edge"), ("guide_E", "guide_F")
    )
    spec = lw.loads(_renamed(), "renamed.yaml")
    names = parts(spec)
    assert names.paths == [
        "links.drive_crank.length",
        "frame.points.Q.x",
        "links.lever.points.P.x",
        "links.lever.points.C.x",
        "links.top_knife.points.blade.y",
        "links.bottom_knife.points.blade.y",
    ]
    assert names.strokes == ("stroke:slide_top", "stroke:slide_bottom")
    bundled_spec = lw.load("double-cut-shears")
    same = {k: float(v[0]) for k, v in knives(lw.kinematics(spec, steps=120), spec).items()}
    own = {k: float(v[0]) for k, v in knives(lw.kinematics(bundled_spec, steps=120), bundled_spec).items()}
    assert same == pytest.approx(own, rel=1e-12)
    assert same["upper_stroke"] > 0.1  # the bundled knives' 120 mm


def test_shears_without_a_guided_knife_are_refused_naming_it():
    spec = lw.loads(_renamed(), "renamed.yaml")
    spec = spec.model_copy(update={"joints": {name: j for name, j in spec.joints.items() if name != "slide_bottom"}})
    with pytest.raises(SynthesisError, match='the file has no prismatic guide of "bottom_knife" on the frame'):
        parts(spec)


def test_a_renamed_shears_file_carries_the_shears_requirements_and_the_report_measures_them():
    """The file format asks a shears file for its parts, not for the bundled file's names: the renamed file with the
    shears' requirements is read, and its knives are measured on its own guides (the bundled strokes, 120 mm)."""
    from linkwork.synthesis.achieved import requirement_rows

    given = "requirements:\n  kind: double-cut-shears\n  upper_stroke: 120 mm\n  lower_stroke: 120 mm\n"
    spec = lw.loads(_renamed() + given, "renamed.yaml")
    kind, rows = requirement_rows(lw.kinematics(spec, steps=120), spec)
    assert kind == "double-cut-shears"
    strokes = {row.name: row.achieved for row in rows}
    assert strokes["upper_stroke"] == pytest.approx(0.12, rel=0.02)
    assert strokes["lower_stroke"] == pytest.approx(0.12, rel=0.02)
    without = _renamed().replace("  slide_bottom: {type: prismatic", "  slide_bottom: {type: revolute")
    with pytest.raises(lw.errors.SpecError, match='no prismatic guide of "bottom_knife" on the frame'):
        lw.loads(without + given, "x.yaml")
