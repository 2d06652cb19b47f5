"""What a result shows in a notebook (``_repr_html_``): its numbers, each with its unit, and the names of the
file escaped (a mechanism's name is any text)."""

from __future__ import annotations

import re

import numpy as np

import linkwork as lw


def _cells(page: str) -> dict[str, str]:
    return dict(re.findall(r"<th[^>]*>(.*?)</th><td[^>]*>(.*?)</td>", page))


def test_kinematics_shows_where_each_variant_assembles():
    """A crank of 300 mm on the four-bar (frame 300, coupler 350, rocker 250 mm) cannot turn fully: the samples
    that assemble are counted from the positions the result gives (NaN where it does not assemble)."""
    kin = lw.kinematics("four-bar", steps=72, variants={"links.crank.length": [0.1, 0.3]})
    cells = _cells(kin._repr_html_())
    assembled = int(np.isfinite(kin.position("B")[..., 0]).sum())
    assert 72 < assembled < 144
    assert cells["assembles at"] == f"{assembled} of 144 samples"
    assert cells["variants x angles"] == "2 x 72"
    assert cells["moving links"] == "crank, coupler, rocker"


def test_forces_show_the_largest_sampled_torque_with_its_unit():
    f = lw.forces("double-cut-shears", steps=72)
    cells = _cells(f._repr_html_())
    assert cells["largest driving torque of the samples"] == f"{np.abs(f.driving_torque).max():.6g} N m"
    assert cells["singular samples (reactions NaN)"] == "0"


def test_a_name_is_shown_as_text():
    text = lw.example("four-bar").model_dump_json()
    spec = lw.Spec.model_validate_json(text).model_copy(update={"name": "<b>four & bar</b>"})
    page = lw.kinematics(spec, steps=12)._repr_html_()
    assert "&lt;b&gt;four &amp; bar&lt;/b&gt;" in page and "<b>four" not in page


def test_a_sweep_shows_each_column_s_range_and_unit():
    t = lw.sweep("four-bar", {"links.crank.length": ("90 mm", "110 mm", 3)}, ["swing", "time_ratio"])
    cells = _cells(t._repr_html_())
    assert cells["links.crank.length"] == "0.09 to 0.11 m"
    low, high = np.min(t.columns["swing"]), np.max(t.columns["swing"])
    assert cells["swing"] == f"{low:.6g} to {high:.6g} rad"
    assert cells["time_ratio"].count(" ") == 2  # a ratio has no unit


def test_dynamics_show_the_speed_fluctuation_and_the_flywheel():
    run = lw.dynamics("double-cut-shears")
    cells = _cells(run._repr_html_())
    assert cells["coefficient of speed fluctuation delta"] == f"{run.delta:.6g}"
    assert abs(run.delta - 0.05) < 0.002  # the file asks a flywheel for delta = 0.05
    assert cells["flywheel inertia on its shaft"] == f"{run.flywheel.inertia:.6g} kg m^2"
