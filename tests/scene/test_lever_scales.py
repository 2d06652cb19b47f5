"""Zhukovsky's lever of the double-cut shears at position 3, under the 250 kN cut: the inertia forces and weights,
thousands of times smaller than the cutting forces, drawn dash-dotted to a scale of their kind (μΦ, μG) stated in
the legend and the title, each arrow as long as its force at that scale (read back from the drawing); the legend
names every line style drawn; nothing overlaps."""

from __future__ import annotations

import functools
import re

import numpy as np
import pytest

import linkwork as lw
from drawing_checks import drawn_texts, overlaps
from linkwork.kinetostatics.zhukovsky import lever
from linkwork.scene.positions import position_angles

pytest.importorskip("matplotlib")

from linkwork.figures.force_plans import SECOND, lever_figure  # noqa: E402


@functools.cache
def _shears():
    mech = lw.compile(lw.load("double-cut-shears"))
    kin = lw.kinematics(mech, position_angles(mech))
    return kin, lever(lw.forces(kin))


@pytest.mark.slow  # the shears' forces at the twelve positions: 5 to 20 s on the NumPy kernels
@pytest.mark.parametrize("lang", ["en", "ru"])
def test_the_levers_small_forces_are_drawn_to_a_scale_of_their_kind(lang):
    kin, lv = _shears()
    fig = lever_figure(lv, kin, 3, 3, lang)
    assert overlaps(fig) == []
    texts = [t.get_text() for t in drawn_texts(fig)]
    legend = [t.get_text() for t in fig.legends[0].get_texts()]
    scales = {
        m.group(1): float(m.group(2).replace(",", "."))
        for s in legend
        if (m := re.search(r"μ([GΦ]) = ([0-9.,]+) (?:N|Н)/(?:mm|мм)", s))
    }
    assert "Φ" in scales and "G" in scales, legend  # the inertia forces are on the lever, and in its legend
    assert any("μΦ" in s for s in texts)  # and in the title
    ax = fig.axes[0]
    drawn = {line.get_gid(): line for line in ax.lines if line.get_gid()}
    checked = 0
    for lf in lv.forces:
        f = lf.force
        if f.kind not in ("inertia", "weight"):
            continue
        line = drawn.get(f"{f.kind}:{f.name(lang)}")
        if line is None:
            continue
        xy = np.asarray(line.get_xydata())
        scale = scales["Φ" if f.kind == "inertia" else "G"]
        assert np.allclose((xy[1] - xy[0]) * scale, f.vector[0, 3], rtol=1e-9, atol=1e-9)
        assert line._unscaled_dash_pattern == SECOND  # dash-dotted, as the legend says
        checked += f.kind == "inertia"
    assert checked >= 3  # Φ1, Φ2, Φ5, Φ7 drawn (the ones under 1.75 mm even at μΦ are listed in the title)


def _point_letters(texts):
    """The point letters of a lever's drawn texts (``p, b, c`` -> p, b, c), one list per text; the forces' names
    (mathtext) and the titles left out."""
    return [s.split(", ") for s in texts if re.fullmatch(r"[a-zπ][0-9]*(, [a-zπ][0-9]*)*", s)]


@pytest.mark.slow  # the shears' forces at the twelve positions: 5 to 20 s on the NumPy kernels
@pytest.mark.parametrize("lang", ["en", "ru"])
def test_the_levers_points_at_rest_share_the_poles_label_and_nothing_crowds(lang):
    """At position 6 the shears' rocker is at an extreme: B, C, D, E, F stand still, so on the lever (the velocity
    plan turned) their images lie within a third of the lettering of the pole.  They are named once, with p, in one
    label, as the velocity plan names points that coincide on the sheet, not in nine letters piled about the pole;
    the same on the sheet of the twelve levers; every letter written once; nothing overlaps (read back)."""
    from linkwork.figures.force_plans import lever_sheet
    from linkwork.scene.plans import LETTERING, TOGETHER

    kin, lv = _shears()
    fig = lever_figure(lv, kin, 6, 6, lang)
    assert overlaps(fig) == []
    texts = [t.get_text() for t in drawn_texts(fig)]
    title = next(s for s in texts if "μv = " in s)
    mu_v = float(re.search(r"μv = ([0-9.,]+)", title).group(1).replace(",", "."))  # (m/s)/mm
    at_rest = set()
    for joint in "BCDEF":
        v = kin.motion_of(joint)[1][0, 6]
        if np.hypot(*v) / mu_v < TOGETHER * LETTERING:  # mm on the lever from the pole
            at_rest.add(joint.lower())
    assert at_rest == set("bcdef")  # the rocker's extreme: every joint it drives stands still
    # the forces too short to draw, listed in the title, are named as their labels draw them: Φ₄, not Phi4 or Φ4
    plain = [re.sub(r"\$[^$]*\$", "", s) for s in texts]  # mathtext ($\Phi_{1}$) is drawn Φ₁
    assert not [s for s in plain if re.search(r"Phi|Φ\d", s)], texts
    assert any("Φ$_{\\mathregular{4}}$" in s for s in texts), texts
    letters = _point_letters(texts)
    pole = [group for group in letters if "p" in group]
    assert len(pole) == 1 and at_rest <= set(pole[0]), letters
    flat = [x for group in letters for x in group]
    assert len(flat) == len(set(flat)), letters  # each point named once
    sheet = lever_sheet(lv, kin, lang)
    assert overlaps(sheet) == []
    cell = [t.get_text() for t in drawn_texts(sheet) if t.axes is sheet.axes[6]]
    pole = [group for group in _point_letters(cell) if "p" in group]
    assert len(pole) == 1 and at_rest <= set(pole[0]), cell
    if lang == "ru":  # the sheet's numbers with decimal commas, its title's among them
        assert not [s for s in (t.get_text() for t in drawn_texts(sheet)) if re.search(r"\d\.\d", s)]
