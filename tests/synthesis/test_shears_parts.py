"""The double-cut shears' parts are read from the file, not assumed by name: the same mechanism with every part
renamed gives the renamed parameters and guides, and the knives measure the same."""

from __future__ import annotations

import re

import pytest

import linkwork as lw
from linkwork.errors import SynthesisError
from linkwork.examples import text
from linkwork.synthesis.rounding import knives
from linkwork.synthesis.shears_parts import ShearsParts, parts

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
    same = knives(lw.kinematics(spec, steps=120))
    assert same == pytest.approx(knives(lw.kinematics("double-cut-shears", steps=120)), rel=1e-12)
    assert same["upper_stroke"] > 0.1  # the bundled knives' 120 mm


def test_shears_without_a_guided_knife_are_refused_naming_it():
    spec = lw.loads(_renamed(), "renamed.yaml")
    spec = spec.model_copy(update={"joints": {name: j for name, j in spec.joints.items() if name != "slide_bottom"}})
    with pytest.raises(SynthesisError, match="no prismatic guide of 'bottom_knife'"):
        parts(spec)
