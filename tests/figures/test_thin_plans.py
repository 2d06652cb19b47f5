"""A thin velocity plan (the double-cut shears at position 9, its vectors from the pole nearly on one line) drawn
as large as a page allows (10 inches tall), so that its short side prints 10 mm wide or as near as that allows,
read back from the drawn vectors; its letters clear of each other."""

from __future__ import annotations

import numpy as np
import pytest

import linkwork as lw
from drawing_checks import overlaps
from linkwork.scene.positions import position_angles

pytest.importorskip("matplotlib")

from linkwork import figures  # noqa: E402


@pytest.mark.parametrize("lang", ["en", "ru"])
def test_a_thin_velocity_plan_prints_its_short_side_readable(lang):
    mech = lw.kinematics("double-cut-shears", steps=4).mechanism
    kin = lw.kinematics(mech, position_angles(mech))
    fig = figures.velocity_plan(kin, 9, position=9, lang=lang)
    assert overlaps(fig) == []  # draws it
    ax = fig.axes[0]
    ends = np.concatenate([np.column_stack(line.get_data()) for line in ax.lines if ":" in str(line.get_gid())])
    px = ax.transData.transform(ends[np.isfinite(ends).all(-1)])
    centred = px - px.mean(0)
    axes = np.linalg.svd(centred, full_matrices=False)[2]
    along = centred @ axes.T
    short_mm = float(np.min(along.max(0) - along.min(0))) / fig.dpi * 25.4
    # 3.1 mm on the sheet across 111.5 mm along it: on a drawing 10 inches tall at most, 6.6 mm (4.0 at 6 inches)
    assert short_mm >= 6.0, short_mm
