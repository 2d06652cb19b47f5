"""The one wrap and the one NaN-aware unwrap of :mod:`linkwork.angles`, and the link-angle diagram that
uses it."""

from __future__ import annotations

import math

import numpy as np
import pytest

import linkwork as lw
from linkwork.angles import unwrap, wrap


def test_wrap_gives_one_range_at_plus_and_minus_pi():
    """(-pi, pi], as arctan2: pi and -pi (and 3 pi, -3 pi) are one direction, written pi; floats as arrays."""
    for x in (math.pi, -math.pi, 3 * math.pi, -3 * math.pi):
        assert wrap(x) == math.pi == math.atan2(0.0, -1.0)
    np.testing.assert_array_equal(
        wrap(np.array([math.pi, -math.pi, 0.5, 2 * math.pi + 0.5])), [math.pi, math.pi, 0.5, 0.5]
    )
    x = np.linspace(-20, 20, 4001)
    w = wrap(x)
    assert (w > -math.pi).all() and (w <= math.pi).all()
    np.testing.assert_allclose(np.cos(w), np.cos(x), atol=1e-12)
    np.testing.assert_allclose(np.sin(w), np.sin(x), atol=1e-12)
    assert np.isnan(wrap(np.array([np.nan]))).all()


@pytest.mark.parametrize("gap", [slice(30, 31), slice(30, 45), slice(0, 5), slice(95, 100)])
def test_unwrap_keeps_every_valid_sample_and_is_continuous_across_gaps(gap):
    """A link turning steadily (three turns over 100 samples) seen wrapped, with samples missing: every
    finite sample comes back, as the turning angle itself less a whole number of turns, the same one for
    all of them (continuous across the gap: the angle turns 0.19 rad a sample, well within half a turn)."""
    true = np.linspace(0.3, 0.3 + 6 * math.pi, 100)
    seen = wrap(true)
    seen[gap] = np.nan
    got = unwrap(seen)
    ok = np.isfinite(seen)
    assert (np.isfinite(got) == ok).all()
    turns = (got[ok] - true[ok]) / (2 * math.pi)
    np.testing.assert_allclose(turns, np.round(turns[0]), atol=1e-12)
    np.testing.assert_allclose(unwrap(np.stack([seen, seen])), np.stack([got, got]))  # along the last axis


def test_the_link_angle_diagram_plots_every_valid_sample_past_a_gap():
    """The four-bar with a 300 mm crank assembles on part of the turn only: the angle panel has every sample
    the omega panel has (np.unwrap dropped all samples after the first gap), continuous in each run."""
    import matplotlib

    matplotlib.use("Agg")
    from linkwork.examples import text
    from linkwork.figures.diagrams import link_angles

    src = text("four-bar").replace("length: 100", "length: 300", 1)
    kin = lw.kinematics(lw.compile(lw.loads(src)), steps=360)
    assert not kin.valid.all()
    fig = link_angles(kin)
    angle, omega = fig.axes[0].lines, fig.axes[1].lines
    assert len(angle) == len(omega) == 2
    for a, w in zip(angle, omega, strict=True):
        ya, yw = (np.asarray(line.get_ydata(), dtype=float) for line in (a, w))
        assert (np.isfinite(ya) == np.isfinite(yw)).all()
        assert np.isfinite(ya).sum() >= kin.valid.sum()
        step = np.diff(ya)
        assert np.nanmax(np.abs(step)) < 180.0
