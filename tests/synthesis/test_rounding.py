"""Synthesised files dimensioned to 0.1 mm: the tolerance each requirement carries from the rounding, checked on the
written file by measures of its own (fine turns of the analysis, corners of the +-0.05 mm box of its lengths)."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

import linkwork as lw
from linkwork.motion.analysis import extremes, transmission
from linkwork.synthesis import synthesize
from linkwork.synthesis.achieved import requirement_rows

HALF = 0.05e-3  # half the step of 0.1 mm, m


def lengths(spec) -> dict[str, float]:
    """The nonzero lengths of the file, by named parameter (SI)."""
    from linkwork.structure.parameters import parameter_list

    return {p.name: p.value for p in parameter_list(lw.compile(spec)) if p.kind == "length" and p.value != 0}


def measured(kin, v: int) -> dict[str, float]:
    """The stroke, K and least transmission angle of variant ``v`` of ``kin``, read off the analysis directly."""
    (out,) = [e for e in extremes(kin, v) if e.kind == "slider"] or extremes(kin, v)
    least = min(float(np.nanmin(np.atleast_2d(a)[v])) for a in transmission(kin).values())
    return {"stroke": out.stroke, "time_ratio": out.time_ratio, "min_transmission_angle": least}


@pytest.fixture(scope="module")
def press():
    return synthesize("slider-crank", stroke=0.4, time_ratio=1.2)


def test_every_written_length_is_a_whole_number_of_tenths_of_a_millimetre(press):
    rocker = {"swing": math.radians(45), "time_ratio": 1.2, "rocker": 0.3}
    for kind, req in [("slider-crank", None), ("crank-rocker", rocker)]:
        s = press if req is None else synthesize(kind, **req)
        for name, value in lengths(s.spec).items():
            tenths = value / 1e-4
            assert tenths == pytest.approx(round(tenths), abs=1e-6), (kind, name, value)


def test_the_written_file_read_back_meets_each_requirement_within_the_tolerance_it_states(press, tmp_path):
    path = tmp_path / "press.yaml"
    press.write(path)
    text = path.read_text()
    assert "stroke_tolerance:" in text and "time_ratio_tolerance:" in text
    spec = lw.load(path)
    fine = lw.kinematics(spec, steps=7200)  # a finer turn than the synthesis's own
    got = measured(fine, 0)
    kind, rows = requirement_rows(fine, spec)
    by = {r.name: r for r in rows}
    assert kind == "slider-crank" and all(r.met for r in rows if r.met is not None)
    assert abs(got["stroke"] - 0.4) <= by["stroke"].tolerance
    assert abs(got["time_ratio"] - 1.2) <= by["time_ratio"].tolerance
    assert got["min_transmission_angle"] >= math.radians(40) - by["min_transmission_angle"].tolerance
    # the rounding moved them: a tolerance of 1e-9 would refuse this file
    assert abs(got["stroke"] - 0.4) > 1e-9 * 0.4


def test_the_tolerance_bounds_every_corner_of_the_lengths_plus_or_minus_half_a_tenth(press):
    """Each written length +-0.05 mm at once (all 2^3 corners of the box): no corner moves a requirement by more
    than the tolerance, and the worst corner comes within the first-order bound's headroom of it."""
    base = lengths(press.spec)
    names = list(base)
    corners = np.array(list(itertools.product((-1.0, 1.0), repeat=len(names))))
    variants = {n: np.concatenate([[base[n]], base[n] + HALF * corners[:, i]]) for i, n in enumerate(names)}
    kin = lw.kinematics(press.spec, steps=720, variants=variants)
    own = measured(kin, 0)
    for key in ("stroke", "time_ratio"):
        moved = max(abs(measured(kin, v)[key] - own[key]) for v in range(1, len(corners) + 1))
        tol = press.tolerances[key]
        assert moved <= tol
        assert moved >= 0.8 * tol / 1.1  # sharp: the first-order bound is what a corner reaches


@pytest.mark.slow
def test_the_shears_read_back_meet_their_knives_requirements_within_the_tolerance_they_state(tmp_path):
    s = synthesize("double-cut-shears", upper_stroke=0.15, lower_stroke=0.11, time_ratio=1.05, overlap=0.015)
    path = tmp_path / "shears.yaml"
    s.write(path)
    spec = lw.load(path)
    _, rows = requirement_rows(lw.kinematics(spec, steps=3600), spec)
    asked = {"upper_stroke": 0.15, "lower_stroke": 0.11, "time_ratio": 1.05, "overlap": 0.015}
    for row in rows:
        if row.name in asked:
            assert row.tolerance is not None and abs(row.achieved - asked[row.name]) <= row.tolerance
            assert row.met


@pytest.mark.parametrize(
    ("line", "words"),
    [
        ("  stroke_tolerance: 0.145", 'give the unit, e.g. "400 mm"'),
        ("  stroke_tolerance: -1 mm", "expected a finite value in [0, "),
        ("  swing_tolerance: 1 deg", '"swing_tolerance" is no requirement of a slider-crank'),
    ],
)
def test_a_tolerance_edited_by_hand_is_checked_where_the_file_is_read(press, line, words):
    from linkwork.errors import SpecError

    text = "\n".join(line if raw.startswith("  stroke_tolerance:") else raw for raw in press.text.splitlines())
    with pytest.raises(SpecError) as err:
        lw.loads(text + "\n")
    assert words in str(err.value)
