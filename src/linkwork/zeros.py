"""What counts as a zero: the round-off of a quantity that is zero, judged against the quantity's own magnitude.

One rule for the JSON writer (:mod:`linkwork.io.jsonout`), the text tables and the tables of the results
(a prismatic pair's moment that is the round-off of a zero is 0.0 in every one of them).
"""

from __future__ import annotations

from typing import Any

import numpy as np

#: A float below this fraction of the typical magnitude of its quantity is written as zero.
ZERO = 1e-10
#: The share of the non-zero numbers of a quantity below its typical magnitude (:func:`magnitude`).
SHARE = 0.9


def magnitude(a: Any) -> float:
    """The typical magnitude of the numbers ``a``: the magnitude below which :data:`SHARE` of its non-zero
    finite entries lie (linearly between two; 0 if none).  A few values far larger than the rest (a spike
    at a singular sample) do not move it, nor do the round-off zeros of one component of a vector."""
    m = np.abs(np.asarray(a, dtype=float).ravel())
    m = m[np.isfinite(m) & (m > 0.0)]
    return float(np.quantile(m, SHARE)) if m.size else 0.0


def snap_zeros(a: np.ndarray, scale: float | np.ndarray | None = None) -> np.ndarray:
    """``a`` with the values below :data:`ZERO` times ``scale`` (default: :func:`magnitude` of ``a``; an
    array: a scale for each entry) as 0.0, ``-0.0`` included: the zero a column of a text table shows, as
    the JSON writes it."""
    a = np.asarray(a, dtype=float)
    if scale is None:
        scale = magnitude(a)
    return np.where(np.abs(a) < ZERO * np.asarray(scale, dtype=float), 0.0, a) + 0.0
