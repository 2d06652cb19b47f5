"""Angles: the one wrap and the one NaN-aware unwrap every part of linkwork uses.

A wrapped angle lies in ``(-pi, pi]``, the range of ``arctan2``: ``pi`` and ``-pi`` are both written
``pi``, so two routes to the same direction never differ by a turn.  An unwrapped series of angles is
continuous along its samples, also across samples where the quantity has no value (NaN, where a
mechanism does not assemble): every finite sample is kept, turned by whole turns so that it follows the
last finite sample before it.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

#: A whole turn, rad.
TWO_PI = 2 * math.pi


def wrap(angle: Any) -> Any:
    """Angles (rad; a float or an array) wrapped to ``(-pi, pi]``; NaN stays NaN."""
    if isinstance(angle, float | int):
        return math.pi - (math.pi - angle) % TWO_PI
    return math.pi - np.mod(math.pi - np.asarray(angle, dtype=float), TWO_PI)


def unwrap(angle: np.ndarray) -> np.ndarray:
    """Angles ``(..., A)`` (rad) unwrapped along the last axis: each step between consecutive finite samples
    taken as the one within half a turn (a step of half a turn kept as it is), across NaN samples (which
    stay NaN) as across none."""
    angle = np.asarray(angle, dtype=float)
    ok = np.isfinite(angle)
    whole = bool(ok.all())  # nothing to fill
    if whole:
        filled = angle
    else:  # each NaN replaced by the last finite value before it
        idx = np.maximum.accumulate(np.where(ok, np.arange(angle.shape[-1]), 0), axis=-1)
        filled = np.take_along_axis(angle, idx, -1)
    step = filled[..., 1:] - filled[..., :-1]
    with np.errstate(invalid="ignore"):
        jump = np.where(np.abs(step) >= math.pi, wrap(step) - step, 0.0)
    turns = np.zeros(angle.shape)
    np.cumsum(jump, axis=-1, out=turns[..., 1:])
    return angle + turns if whole else np.where(ok, angle + turns, np.nan)
