"""The slider-crank's group II(2,3) at position 2: the weight G3 down and the inertia force Φ3 up along the guide,
one after the other in the polygon, drawn apart (the second beside the first, joined to its vertices by thin
lines), each still its force at the plan's scale μF, read back from the drawing; no text on another."""

from __future__ import annotations

import functools
import re

import numpy as np
import pytest

import linkwork as lw
from drawing_checks import overlaps
from linkwork.kinetostatics.force_polygons import force_plans
from linkwork.scene.positions import position_angles

pytest.importorskip("matplotlib")

from linkwork.figures.force_plans import force_plans_figure  # noqa: E402


@functools.cache
def _plans():
    """The force plans of the shears' slider-crank at its position 2 alone."""
    mech = lw.compile(lw.load("shears-slider-crank"))
    return force_plans(lw.forces(lw.kinematics(mech, position_angles(mech)[2:3])))


@pytest.mark.parametrize("lang", ["en", "ru"])
def test_a_force_back_along_the_one_before_it_is_drawn_beside_it(lang):
    plans = _plans()
    g = plans.groups[0]
    names = [f.name(lang) for f in g.polygon]
    at = names.index("G3")
    assert names[at + 1] in ("Phi3", "Φ3")  # one after the other
    g3, phi3 = (g.polygon[at + k].vector[0, 0] for k in (0, 1))
    assert g3 @ phi3 < 0 and abs(g3[0] * phi3[1] - g3[1] * phi3[0]) < 1e-9 * np.hypot(*g3) * np.hypot(*phi3)
    fig = force_plans_figure(plans, 0, 2, lang)
    assert overlaps(fig) == []
    ax = fig.axes[0]
    scale = float(re.search(r"μF = ([0-9.,]+)", ax.get_title()).group(1).replace(",", "."))
    lines = {line.get_gid(): np.asarray(line.get_xydata()) for line in ax.lines if line.get_gid()}
    a, b = lines[f"weight:{names[at]}"], lines[f"inertia:{names[at + 1]}"]
    assert np.allclose((a[1] - a[0]) * scale, g3, rtol=1e-9, atol=1e-9)
    assert np.allclose((b[1] - b[0]) * scale, phi3, rtol=1e-9, atol=1e-9)
    u = (a[1] - a[0]) / np.hypot(*(a[1] - a[0]))
    apart = abs(float(np.cross(np.append(u, 0), np.append(b[0] - a[0], 0))[2]))  # mm of the sheet across the line
    mm = apart * (ax.transData.transform([1, 0])[0] - ax.transData.transform([0, 0])[0]) / fig.dpi * 25.4
    assert mm >= 1.0, mm  # printed apart (0 before: Φ3 drawn back over G3)
    # and still head to tail: a thin line joins G3's head to Φ3's tail, and Φ3's head to the next vertex
    joins = [np.asarray(line.get_xydata()) for line in ax.lines if not line.get_gid()]
    assert any(np.allclose(j[0], a[1]) and np.allclose(j[1], b[0]) for j in joins if len(j) == 2)
