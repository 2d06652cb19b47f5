"""Drawings: every figure on every bundled example; the plans drawn to their stated scale."""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import numpy as np
import pytest

import linkwork as lw
from linkwork.examples import names

pytest.importorskip("matplotlib")

from linkwork import figures  # noqa: E402


@pytest.mark.parametrize("name", names())
def test_every_figure_draws_every_example(name, tmp_path):
    mech = lw.compile(lw.example(name))
    kin = lw.kinematics(mech, steps=72)
    f = lw.forces(mech, steps=72) if not mech.structure.redundant else None
    joint = next(j for j in mech.pair_joint)
    point = mech.point_names[int(mech.pair_points[1, 1])]
    drawn = [
        figures.draw_scheme(kin, 5, trajectories=True),
        figures.draw_positions(kin),
        figures.velocity_plan(kin, 5),
        figures.acceleration_plan(kin, 5),
        figures.motion_diagram(kin, point),
        figures.link_angles(kin),
    ]
    if f is not None:
        drawn += [figures.torque_diagram(f), figures.foundation_diagram(f), figures.hodograph(f, joint)]
    if mech.machine is not None:
        drawn.append(figures.dynamics_diagrams(lw.dynamics(mech, steps=720)))
    for i, fig in enumerate(drawn):
        assert fig.axes, f"figure {i} has no axes"
        fig.savefig(tmp_path / f"{i}.svg")
        fig.savefig(tmp_path / f"{i}.png", dpi=40)
        assert (tmp_path / f"{i}.png").stat().st_size > 1000


@pytest.mark.parametrize("name", ["double-cut-shears", "four-bar", "watt-six-bar"])
def test_plans_are_drawn_to_their_stated_scale(name):
    """Every absolute vector drawn from the pole, read back from the figure and multiplied by the
    scale, is the point's computed velocity (acceleration); every relative vector joins the
    right plan points."""
    from linkwork.io.motion_tables import point_labels
    from linkwork.motion.plans import plans

    mech = lw.compile(lw.example(name))
    kin = lw.kinematics(mech, steps=36)
    index = 7
    vplan, aplan = plans(kin, index)
    checked = 0
    for plan, fig, state in (
        (vplan, figures.velocity_plan(kin, index), kin.velocity),
        (aplan, figures.acceleration_plan(kin, index), kin.acceleration),
    ):
        lines = {line.get_gid(): line for line in fig.axes[0].get_lines() if line.get_gid()}
        for label, p in point_labels(mech):
            gid = f"absolute:p->{label.lower()}"
            if gid not in lines:
                continue
            x, y = lines[gid].get_data()
            drawn = np.array([x[1] - x[0], y[1] - y[0]]) * plan.scale
            np.testing.assert_allclose(drawn, state(mech.point_names[p])[index], rtol=1e-9, atol=1e-12)
            checked += 1
        for vec in plan.vectors:
            line = lines[f"{vec.kind}:{vec.start}->{vec.end}"]
            x, y = line.get_data()
            np.testing.assert_allclose(np.array([x[1] - x[0], y[1] - y[0]]) * plan.scale, vec.vector, rtol=1e-9,
                                       atol=1e-12)  # fmt: skip
            origin = np.zeros(2) if vec.start == "p" else np.asarray(plan.points.get(vec.start, (np.nan, np.nan)))
            if np.isfinite(origin).all():
                np.testing.assert_allclose([x[0], y[0]], origin / plan.scale, rtol=1e-9, atol=1e-9)
        assert plan.scale > 0
        longest = max(np.hypot(*v) for v in plan.points.values()) / plan.scale
        assert 20 < longest <= 100  # mm on the sheet
    assert checked >= 4


BASELINES = Path(__file__).parent / "baseline"


def _baseline_figures():
    kin = lw.kinematics(lw.compile(lw.example("double-cut-shears")), steps=36)
    return {
        "scheme": figures.draw_scheme(kin, 3),
        "velocity_plan": figures.velocity_plan(kin, 3),
        "acceleration_plan": figures.acceleration_plan(kin, 3),
    }


@pytest.mark.parametrize("name", ["scheme", "velocity_plan", "acceleration_plan"])
def test_drawings_match_their_baselines(name, tmp_path):
    """The drawings as they were checked by eye (tests/baseline, regenerate with
    ``LINKWORK_NEW_BASELINES=1``), within a tolerance for rendering differences."""
    from matplotlib.testing.compare import compare_images

    fig = _baseline_figures()[name]
    got = tmp_path / f"{name}.png"
    fig.savefig(got, dpi=60)
    expected = BASELINES / f"{name}.png"
    if os.environ.get("LINKWORK_NEW_BASELINES"):
        shutil.copy(got, expected)
    assert compare_images(str(expected), str(got), tol=8) is None
