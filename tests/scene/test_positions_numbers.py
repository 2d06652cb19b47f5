"""The plan of positions numbers the positions as the textbook does: each position's point marked, the numbers
along a straight stroke in a column in the order of the points (not lumped), the frame's names clear of
every position's links."""

from __future__ import annotations

import numpy as np
import pytest

import linkwork as lw
from linkwork.scene.geometry import text_size
from linkwork.scene.labels import segments_hit
from linkwork.scene.positions import TOGETHER, position_angles, positions_scene, working_point


@pytest.fixture(scope="module")
def press(tmp_path_factory):
    from typer.testing import CliRunner

    import linkwork.cli.synthesize  # noqa: F401  (registers the command)
    from linkwork.cli.main import app

    path = tmp_path_factory.mktemp("press") / "press.yaml"
    args = [
        "synthesize",
        "toggle-press",
        "--out",
        str(path),
        "--stroke",
        "100mm",
        "--force",
        "100kN",
        "--before",
        "5mm",
        "--torque",
        "5kN*m",
    ]
    result = CliRunner().invoke(app, args)
    assert result.exit_code == 0, result.output
    return lw.compile(lw.load(path))


def _scene(mech):
    twelve = lw.kinematics(mech, position_angles(mech))
    return twelve, positions_scene(twelve, cycle=lw.kinematics(mech, steps=72))


@pytest.mark.parametrize("name", ["press", "double-cut-shears"])
def test_the_working_points_numbers_stand_in_order_along_the_stroke(name, press):
    mech = press if name == "press" else lw.compile(lw.example(name))
    twelve, scene = _scene(mech)
    em = scene.scheme.em
    xy = twelve.points()[:, working_point(mech)]
    # every position's point is marked
    assert all(np.min(np.hypot(*(scene.marks - p).T)) < 1e-12 for p in xy)
    mine = [lab for lab in scene.numbers if np.min(np.hypot(*(xy - lab.at).T)) < 1e-12]
    numbers = sorted(int(n) for lab in mine for n in lab.text.split(", "))
    assert numbers == list(range(12))
    for lab in mine:  # a label names only positions whose points coincide
        named = xy[[int(n) for n in lab.text.split(", ")]]
        assert np.max(np.hypot(*(named - named[0]).T)) < TOGETHER * em
    # along the stroke (its direction: the points' spread) the numbers come in the order of their points
    u = np.linalg.svd(xy - xy.mean(0))[2][0]
    points = np.array([lab.at @ u for lab in mine])
    centres = np.array([lab.centre[0] @ u for lab in mine])
    assert np.all(np.diff(centres[np.argsort(points)]) > 0)
    # no two numbers' texts overlap
    halves = [np.array(text_size(lab.text, em)) / 2 for lab in scene.numbers]
    boxes = [
        np.concatenate([lab.centre[0] - h, lab.centre[0] + h]) for lab, h in zip(scene.numbers, halves, strict=True)
    ]
    for i, a in enumerate(boxes):
        for b in boxes[i + 1 :]:
            assert not (a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3])


def test_the_frames_names_do_not_cross_any_positions_links(press):
    for mech in (press, lw.compile(lw.example("double-cut-shears"))):
        _, scene = _scene(mech)
        s = scene.scheme
        bars = [s.placed(it) for it in s.items if it.kind == "bar"]  # (A, K, 2) each
        segments = np.concatenate([np.stack([b[:, :-1], b[:, 1:]], 2).reshape(-1, 2, 2) for b in bars])[None]
        for lab in s.labels:
            half = np.array(text_size(lab.text, s.em)) / 2
            box = np.concatenate([lab.centre[0] - half, lab.centre[0] + half])[None, None]
            assert segments_hit(box, segments)[0, 0] == 0, lab.text
