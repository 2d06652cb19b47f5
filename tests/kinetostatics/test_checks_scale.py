"""The momentum check of the foundation's moment is measured against a moment of the machine's own scale.

The manual's slider-crank with friction has no masses and every load's line through the frame's origin: the
foundation's moment is zero but for rounding (1e-13 N m), and its check divided that by the momentum's own
rounding ("foundation moment vs momentum 6.0e-01").  Against its force times its reach (1 kN x 0.45 m) the
discrepancy is rounding; a true discrepancy of that size still shows.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

import linkwork as lw

GUIDE = Path(__file__).resolve().parents[2] / "docs" / "guide" / "friction.md"


def _friction_example(tmp_path: Path) -> Path:
    text = GUIDE.read_text(encoding="utf-8")
    body = re.search(r"<!-- file: slider-crank-friction.yaml -->\n```yaml\n(.*?)```", text, re.S)
    assert body is not None
    path = tmp_path / "slider-crank-friction.yaml"
    path.write_text(body.group(1))
    return path


def test_the_moment_check_of_a_moment_that_is_only_rounding_is_rounding(tmp_path):
    f = lw.forces(_friction_example(tmp_path), steps=360)
    assert np.nanmax(np.abs(f.foundation_all[..., 2])) < 1e-9  # the moment itself is rounding
    assert f.checks["foundation_moment_vs_momentum"] < 1e-12


def test_a_true_discrepancy_of_the_moment_still_shows(tmp_path):
    import dataclasses

    f = lw.forces(_friction_example(tmp_path), steps=360)
    found = f.foundation_all.copy()
    found[..., 2] += 45.0  # 10 % of the force times the reach (1 kN x 0.45 m)
    assert 0.05 < dataclasses.replace(f, foundation_all=found).checks["foundation_moment_vs_momentum"] < 0.2
