"""The work of the loads over a turn (``Reduced.work``, the motor's mean load) is bounded in time and memory.

A load known only to a few units of rounding (near a singular position the solved kinematics carry a noise of
about 1e-13 of the load) never lets the halves of a span agree to ``AGREE``; the integral used to halve every such
span each round, doubling the spans 60 times (6,106,752 spans at the slider-crank shears, past 16 GB).  Here the
loads are closed forms plus a deterministic noise, so the exact work is known.
"""

from __future__ import annotations

import numpy as np
import pytest

from linkwork.machine.reduction import HALVINGS, SPANS, SPANS_LEAST, Reduced

A = 88.29  # N m, the amplitude of the load (the slider-crank shears' gravity moment)
NOISE = 1e-11  # of A: far above AGREE, as near a singular position


def _noise(psi: np.ndarray) -> np.ndarray:
    """A deterministic noise in [-0.5, 0.5) that does not shrink with the span."""
    return np.modf(np.abs(psi) * 1.2345678901e9)[0] - 0.5


def _reduced(load, k: int = 360) -> tuple[Reduced, list[int]]:
    """A :class:`Reduced` of ``k`` steps whose loads between the points are ``load(psi)``; the list counts the
    evaluations of the loads (raises past ten times the bound, so that an unbounded integral fails fast)."""
    calls = [0]
    bound = 12 * k + 16 * HALVINGS * max(k // SPANS, SPANS_LEAST)

    def between(psi: np.ndarray) -> Reduced:
        calls[0] += len(psi)
        if calls[0] > 10 * bound:
            raise AssertionError(f"{calls[0]} evaluations of the loads: the integral is not bounded")
        n = np.zeros_like(psi)
        return Reduced(psi, psi, n + 1.0, n, load(psi))

    psi = 2 * np.pi * np.arange(k) / k
    grid = between(psi)
    calls[0] = 0
    import dataclasses

    return dataclasses.replace(grid, between=between), calls


def test_a_noisy_load_is_integrated_within_the_bound_to_its_noise():
    red, calls = _reduced(lambda p: A * np.sin(p) + A * NOISE * _noise(p))
    bound = 12 * 360 + 16 * HALVINGS * max(360 // SPANS, SPANS_LEAST)
    work = red.work()[-1]  # exactly 0 for the sine; the noise adds at most A NOISE / 2 a radian
    assert abs(work) <= A * NOISE * np.pi
    assert calls[0] <= bound
    assert red.mean_load == pytest.approx(0.0, abs=A * NOISE)


def test_a_jump_of_the_load_is_still_integrated_to_rounding_among_noisy_spans():
    a, b = 1.2345, 4.321  # between the points of the grid: the load switches on and off there
    red, calls = _reduced(lambda p: A * ((p >= a) & (p < b)) + A * NOISE * _noise(p))
    exact = A * (b - a)
    assert red.work()[-1] == pytest.approx(exact, abs=A * NOISE * 2 * np.pi + 1e-12 * exact)


def test_sizing_the_slider_crank_shears_is_bounded():
    """The issue's case: the motor's mean load of the slider-crank shears (gravity only: its work a turn is 0)."""
    import linkwork as lw
    from linkwork.machine.reduction import reduced

    red = reduced(lw.compile("shears-slider-crank"))
    assert abs(red.mean_load) <= 1e-9 * float(np.max(np.abs(red.load)))
