"""The one JSON writer of the command line (``--json`` and the ``.json`` files it writes).

Numbers are written the way an engineer reads them, and always as valid JSON:

* every float to :data:`DIGITS` significant digits (``29.999999999999996`` is written ``30.0``);
* a float is written as ``0.0`` where its magnitude is below :data:`ZERO` times the largest
  magnitude among the numbers beside it: the other entries of its array, or the other values of
  its object together with the entries of that object's arrays of numbers (``x`` beside ``y``,
  ``fx`` beside ``fy``), so the round-off of a quantity that is zero (``-2e-12`` beside ``250``)
  is written as the zero it is, and ``-0.0`` as ``0.0``;
* NaN and infinities are written as ``null`` (an angle at which the mechanism does not
  assemble, a stroke that has no value); the record says why where it is not plain.
"""

from __future__ import annotations

import json
import math
from typing import Any

import numpy as np

#: Significant digits of the floats written.
DIGITS = 12
#: A float below this fraction of the largest magnitude beside it is written as zero.
ZERO = 1e-10


def dumps(data: Any, *, indent: int | None = None) -> str:
    """``data`` (dicts, lists, tuples, numbers, strings, NumPy arrays and scalars) as JSON text."""
    return json.dumps(_clean(data, 0.0), indent=indent, allow_nan=False)


def _largest(values: Any) -> float:
    """The largest finite magnitude among the numbers of a list, tuple or array (0 if none)."""
    if isinstance(values, np.ndarray) or (
        isinstance(values, list | tuple) and values and all(isinstance(v, float | np.floating) for v in values)
    ):
        a = np.abs(np.asarray(values, dtype=float).ravel())
        a = a[np.isfinite(a)]
        return float(a.max()) if a.size else 0.0
    if not isinstance(values, list | tuple):
        return 0.0
    return max((abs(float(v)) for v in values if _is_number(v) and math.isfinite(float(v))), default=0.0)


def _scale(container: Any) -> float:
    """The largest finite magnitude among the numbers beside each other in a list, or in an object
    (its values and the entries of its lists)."""
    if isinstance(container, dict):
        values = list(container.values())
        return max([_largest(values), *(_largest(v) for v in values)])
    return _largest(container)


def _is_number(v: Any) -> bool:
    return isinstance(v, float | int | np.floating | np.integer) and not isinstance(v, bool | np.bool_)


def _clean(x: Any, scale: float) -> Any:
    """``x`` with its floats rounded and snapped; ``scale``: the largest magnitude beside it (for a
    list, that of the object it is in: its entries are beside that object's numbers)."""
    if isinstance(x, np.ndarray):
        x = x.tolist()
    if isinstance(x, dict):
        group = _scale(x)
        return {str(k): _clean(v, group) for k, v in x.items()}
    if isinstance(x, list | tuple):
        group = max(scale, _scale(x))
        if x and all(isinstance(v, float | np.floating) for v in x):  # an array of numbers, at once
            return _floats(np.asarray(x, dtype=float), group)
        return [_clean(v, group) for v in x]
    if isinstance(x, bool | np.bool_):
        return bool(x)
    if isinstance(x, int | np.integer):
        return int(x)
    if isinstance(x, float | np.floating):
        return _floats(np.array([x], dtype=float), scale)[0]
    return x


def snap_zeros(a: np.ndarray, scale: float | None = None) -> np.ndarray:
    """``a`` with the values below :data:`ZERO` times ``scale`` (default: the largest finite magnitude of
    ``a``) as 0.0, ``-0.0`` included: the zero a column of a text table shows, as the JSON writes it."""
    a = np.asarray(a, dtype=float)
    if scale is None:
        finite = np.abs(a[np.isfinite(a)])
        scale = float(finite.max()) if finite.size else 0.0
    return np.where(np.abs(a) < ZERO * scale, 0.0, a) + 0.0


def _floats(a: np.ndarray, scale: float) -> list[float | None]:
    """The floats ``a`` (n,) rounded to :data:`DIGITS` significant digits, those below ``ZERO * scale``
    as 0.0, NaN and infinities as None: ``float(f"{v:.12g}")``, but a division by a power of ten
    instead of a string where the power is exact (ties may round the other way)."""
    finite = np.isfinite(a)
    zero = ~finite | (np.abs(a) < ZERO * scale) | (a == 0.0)
    v = np.where(zero, 1.0, a)
    k = DIGITS - 1 - np.floor(np.log10(np.abs(v)))
    exact = np.abs(k) <= 22  # 10**k is a double exactly
    p = 10.0 ** np.abs(np.where(exact, k, 0.0))
    out = np.where(k >= 0, np.round(v * p) / p, np.round(v / p) * p)
    out[zero] = 0.0
    values: list[float | None] = out.tolist()
    for i in np.flatnonzero(~exact & ~zero):
        values[i] = float(f"{a[i]:.{DIGITS}g}")
    for i in np.flatnonzero(~finite):
        values[i] = None
    return values
