"""The position the plans are drawn at when the file names none: on the working stroke (the slower stroke of
a quick return), where no two letters of the velocity plan fall on one point."""

from __future__ import annotations

import numpy as np
import pytest

import linkwork as lw
from linkwork.motion.analysis import working
from linkwork.scene.positions import best_position, position_angles


def _synthesized(tmp_path, kind, *args):
    from typer.testing import CliRunner

    import linkwork.cli.synthesize  # noqa: F401  (registers the command)
    from linkwork.cli.main import app

    path = tmp_path / f"{kind}.yaml"
    result = CliRunner().invoke(app, ["synthesize", kind, "--out", str(path), *args])
    assert result.exit_code == 0, result.output
    return lw.compile(lw.load(path))


def test_a_quick_return_is_drawn_on_its_slow_working_stroke(tmp_path):
    mech = _synthesized(tmp_path, "slotted-lever", "--stroke", "400mm", "--time-ratio", "1.6")
    (ram,) = [out for out in working(mech)][:1]
    name = mech.point_names[ram.point]
    # the two strokes' times at uniform crank speed: the share of a fine turn's samples moving each way
    turn = lw.kinematics(mech, steps=3600)
    u = np.diff(turn.position(name), axis=0).mean(0)  # any fixed direction along the guide
    u = np.array([1.0, 0.0]) if np.hypot(*u) < 1e-12 else u / np.hypot(*u)
    along = turn.velocity(name) @ u
    slow = 1.0 if np.mean(along > 0) > np.mean(along < 0) else -1.0
    assert max(np.mean(along > 0), np.mean(along < 0)) / min(np.mean(along > 0), np.mean(along < 0)) > 1.5
    twelve = lw.kinematics(mech, position_angles(mech))
    k = best_position(twelve)
    assert slow * (twelve.velocity(name)[k] @ u) > 0


@pytest.mark.parametrize("kind", ["toggle-press", "slotted-lever", "four-bar", "percussion-rocker"])
def test_no_two_letters_of_the_chosen_velocity_plan_coincide(tmp_path, kind):
    if kind == "toggle-press":
        mech = _synthesized(
            tmp_path, kind, "--stroke", "100mm", "--force", "100kN", "--before", "5mm", "--torque", "5kN*m"
        )
    elif kind == "slotted-lever":
        mech = _synthesized(tmp_path, kind, "--stroke", "400mm", "--time-ratio", "1.6")
    else:
        mech = lw.compile(lw.example(kind))
    twelve = lw.kinematics(mech, position_angles(mech))
    k = best_position(twelve)
    joints = sorted({int(p) for pair in mech.pair_points for p in pair if p >= 0 and mech.point_link[p] != 0})
    v = np.array([twelve.velocity(mech.point_names[p])[k] for p in joints])
    moving = np.hypot(*v.T) > 1e-12
    longest = np.hypot(*v.T).max()
    # points that are one physical joint share a letter: keep one of each place
    xy = np.array([twelve.position(mech.point_names[p])[k] for p in joints])
    distinct = [i for i in range(len(joints)) if not any(np.hypot(*(xy[i] - xy[j])) < 1e-9 for j in range(i))]
    for a in distinct:
        assert not moving[a] or np.hypot(*v[a]) >= 0.05 * longest
        for b in distinct:
            if a < b and moving[a] and moving[b]:  # the pivots at rest are the pole
                assert np.hypot(*(v[a] - v[b])) >= 0.05 * longest, (
                    mech.point_names[joints[a]],
                    mech.point_names[joints[b]],
                )
