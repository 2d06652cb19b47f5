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
        figures.kinematic_diagrams(kin),
        figures.link_angles(kin),
    ]
    if f is not None:
        drawn += [figures.torque_diagram(f), figures.foundation_diagram(f), figures.hodograph(f, joint)]
    if mech.motor_gear is not None:
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
            np.testing.assert_allclose(
                np.array([x[1] - x[0], y[1] - y[0]]) * plan.scale, vec.vector, rtol=1e-9, atol=1e-12
            )
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
    """The drawings as they were checked by eye (tests/figures/baseline, regenerate with
    ``LINKWORK_NEW_BASELINES=1``), within a tolerance for rendering differences."""
    from matplotlib.testing.compare import compare_images

    fig = _baseline_figures()[name]
    got = tmp_path / f"{name}.png"
    fig.savefig(got, dpi=60)
    expected = BASELINES / f"{name}.png"
    if os.environ.get("LINKWORK_NEW_BASELINES"):
        shutil.copy(got, expected)
    assert compare_images(str(expected), str(got), tol=8) is None


#: The figures of the scene (scheme, positions, plans), whose drawings the scene's own tests check.
SCENE = {"scheme", "positions", "velocity_plan", "acceleration_plan"}


def _report_figures(name, lang, folder, monkeypatch, sketched_figures):
    """The figures ``analyze`` draws for an example, by name, each laid out as :func:`render.save` lays it out
    before it writes the files (the files themselves sketched: writing them is not what is checked here)."""
    from linkwork.report import build
    from linkwork.report import run as report_run
    from linkwork.report.render import lay_out

    drawn = {}
    sketch = report_run.ReportRun._draw  # the sketched_figures fixture's

    def keep(self, key, make):
        drawn[key] = fig = make()
        lay_out(fig)
        return sketch(self, key, lambda: fig)

    monkeypatch.setattr(report_run.ReportRun, "_draw", keep)
    # the sizing section draws no figure: not sized here
    build.analyze(lw.compile(lw.example(name)), folder, steps=72, animation=False, lang=lang, sizing=False)
    return drawn


@pytest.mark.parametrize("lang", ["en", "ru"])
@pytest.mark.parametrize("name", names())
def test_no_text_of_a_report_figure_covers_another_and_no_axes_cover_axes(
    name, lang, tmp_path, monkeypatch, sketched_figures
):
    """Every diagram ``analyze`` draws, laid out as it is saved and read back through the Agg renderer: no
    text's box covers another's, none lies under other axes or a legend or beyond the edge, no axes cover axes."""
    from drawing_checks import overlaps

    drawn = _report_figures(name, lang, tmp_path / "r", monkeypatch, sketched_figures)
    assert {"kinematic_diagrams", "link_angles"} <= set(drawn)
    problems = [f"{key}: {p}" for key, fig in drawn.items() if key not in SCENE for p in overlaps(fig)]
    assert problems == []


def test_the_overlap_checks_can_fail():
    """Two texts on one spot, a text under another axes and two axes on each other are each found."""
    from matplotlib.figure import Figure

    from drawing_checks import overlaps

    fig = Figure(figsize=(4, 3))
    a = fig.add_axes((0.1, 0.1, 0.5, 0.5))
    fig.add_axes((0.3, 0.3, 0.5, 0.5))
    a.text(0.5, 0.5, "one")
    a.text(0.5, 0.5, "two")
    found = overlaps(fig)
    assert any("'one'" in p and "'two'" in p for p in found)
    assert any(p.startswith("axes") for p in found)
    assert any("is under axes" in p for p in found)


def _lines(ax):
    return {line.get_label(): line.get_xydata() for line in ax.get_lines() if not line.get_label().startswith("_")}


@pytest.mark.parametrize("name", names())
def test_the_kinematic_diagrams_chart_the_working_members_from_position_0(name):
    """The diagrams read back from the figure: each working member's displacement starts at 0 at position 0
    (φ = 0), where the first one is at the high end of its stroke; none is a frame pivot's flat line; the
    velocity is the slope of the drawn displacement times the crank speed, the acceleration the slope of the
    drawn velocity (central differences of the drawing, to 1e-3 of the largest)."""
    from linkwork.motion.analysis import working

    mech = lw.compile(lw.example(name))
    kin = lw.kinematics(mech, steps=720)
    fig = figures.kinematic_diagrams(kin)
    disp, vel, acc = (_lines(ax) for ax in fig.axes)
    members = working(mech)
    assert len(disp) == len(members) >= 1
    omega = abs(float(mech.drive_speed[0]))
    for k, label in enumerate(disp):
        s, v, a = disp[label], vel[label], acc[label]
        phi = np.radians(s[:, 0])
        assert s[0, 0] <= 0.0 and s[-1, 0] >= 360.0  # the whole cycle
        assert np.ptp(s[:, 1]) > 1.0  # mm or degrees: it moves
        assert abs(np.interp(0.0, s[:, 0], s[:, 1])) < 1e-4 * np.ptp(s[:, 1])  # from position 0
        if k == 0:
            assert s[:, 1].max() <= 1e-4 * np.ptp(s[:, 1])  # position 0 is its high end
        scale = 1e-3 if members[k].kind == "slider" else np.pi / 180  # drawn in mm or degrees
        slope = (s[2:, 1] - s[:-2, 1]) * scale / (phi[2:] - phi[:-2]) * omega
        np.testing.assert_allclose(slope, v[1:-1, 1], atol=1e-3 * np.abs(v[:, 1]).max())  # φ grows with time
        dv = (v[2:, 1] - v[:-2, 1]) / (phi[2:] - phi[:-2]) * omega
        np.testing.assert_allclose(dv, a[1:-1, 1], atol=2e-3 * np.abs(a[:, 1]).max())


@pytest.mark.parametrize("name", ["shears-slider-crank", "four-bar"])
def test_the_mean_torque_of_a_machine_whose_loads_do_no_work_is_written_as_zero(name):
    """Gravity and the inertia forces do no work over a turn at uniform speed (the energy theorem): the mean
    driving torque is zero, and the diagram's legend says 0, not the round-off (-1.3e-11 N m) of its samples; a
    file with a process load keeps its mean (the double-cut shears' cut: 7.5 kJ a turn, 1.19 kN m)."""
    f = lw.forces(name, steps=360)
    assert abs(float(np.nanmean(f.driving_torque))) < 1e-9 * float(np.nanmax(np.abs(f.driving_torque)))
    (mean,) = [
        t.get_text() for t in figures.torque_diagram(f).axes[0].get_legend().get_texts() if "mean" in t.get_text()
    ]
    assert mean.endswith(" 0"), mean
    cut = figures.torque_diagram(lw.forces("double-cut-shears", steps=360))
    (mean,) = [t.get_text() for t in cut.axes[0].get_legend().get_texts() if "mean" in t.get_text()]
    assert float(mean.split()[-1]) == pytest.approx(7.5e3 / (2 * np.pi) / 1e3, rel=2e-3), mean
