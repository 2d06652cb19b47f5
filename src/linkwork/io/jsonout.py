"""The one JSON writer of the command line (``--json`` and the ``.json`` files it writes).

Numbers are written the way an engineer reads them, and always as valid JSON:

* every float to :data:`DIGITS` significant digits (``29.999999999999996`` is written ``30.0``);
* a float is written as ``0.0`` where its magnitude is below :data:`ZERO` times the typical magnitude
  of its own quantity (:func:`magnitude`: the magnitude below which nine tenths of the non-zero finite
  numbers of its array lie, together with those of the other components of the same vector in its
  object: keys that
  differ only in a final ``x`` or ``y``, ``x`` beside ``y``, ``vx`` beside ``vy``, ``fx`` beside
  ``fy``), so the round-off of a quantity that is zero (``-2e-12`` beside ``250``) is written as the
  zero it is, and ``-0.0`` as ``0.0``; a number is never compared with another quantity (a position
  with an acceleration), and a value that is far larger than the rest of its array (at a dead point
  where a speed has no finite limit) is written as it is and zeroes nothing beside it;
* a number that stands alone (not in an array nor a vector) is written as it is;
* NaN and infinities are written as ``null`` (an angle at which the mechanism does not
  assemble, a stroke that has no value); the record says why where it is not plain.
"""

from __future__ import annotations

import json
import math
from typing import Any

import numpy as np

from linkwork.zeros import SHARE, ZERO, magnitude

#: Significant digits of the floats written.
DIGITS = 12


def dumps(data: Any, *, indent: int | None = None) -> str:
    """``data`` (dicts, lists, tuples, numbers, strings, NumPy arrays and scalars) as JSON text."""
    return json.dumps(_clean(data, None), indent=indent, allow_nan=False)


def _is_float(v: Any) -> bool:
    return isinstance(v, float | np.floating)


def _array(x: Any) -> np.ndarray | None:
    """``x`` as a 1-D float array where it is an array of numbers (floats, or None for no value, at least
    one float; a float alone as one entry), else None (ints, bools, strings and nesting keep their kind)."""
    if _is_float(x):
        return np.array([x], dtype=float)
    if isinstance(x, np.ndarray):
        return x.astype(float) if x.dtype.kind == "f" and x.ndim == 1 else None
    if isinstance(x, list | tuple) and any(_is_float(v) for v in x) and all(v is None or _is_float(v) for v in x):
        return np.array([np.nan if v is None else v for v in x], dtype=float)
    return None


def _components(record: dict[Any, Any]) -> dict[Any, float]:
    """The scale of each key of ``record`` that is a component of a vector (keys that differ only in a
    final ``x`` or ``y`` whose values are numbers or arrays of numbers): the :func:`magnitude` of the
    components together."""
    scales: dict[Any, float] = {}
    for kx in record:
        ky = kx[:-1] + "y" if isinstance(kx, str) and kx.endswith("x") else None
        if ky is None or ky not in record:
            continue
        ax, ay = _array(record[kx]), _array(record[ky])
        if ax is not None and ay is not None:
            scales[kx] = scales[ky] = magnitude(np.concatenate([ax, ay]))
    return scales


def _clean(x: Any, scale: float | None) -> Any:
    """``x`` with its floats rounded and snapped; ``scale``: the typical magnitude of the vector ``x`` is a
    component of (None: ``x``'s own, that of its array; a float alone is never snapped)."""
    if isinstance(x, dict):
        scales = _components(x)
        return {str(k): _clean(v, scales.get(k)) for k, v in x.items()}
    if _is_float(x):  # a number alone, or a component of a vector of numbers
        return _few([float(x)], 0.0 if scale is None else scale)[0]
    if isinstance(x, list | tuple) and len(x) <= SMALL and all(_is_float(v) or v is None for v in x):
        if any(v is not None for v in x):  # a point's coordinates: at once in Python, not through NumPy
            return _few([None if v is None else float(v) for v in x], scale)
    a = _array(x)
    if a is not None:
        own = 0.0 if _is_float(x) else magnitude(a)
        values = _floats(a, own if scale is None else scale)
        return values[0] if _is_float(x) else values
    if isinstance(x, np.ndarray):
        x = list(x) if x.ndim > 1 else x.tolist()
    if isinstance(x, list | tuple):
        alike = _records(x)
        return alike if alike is not None else [_clean(v, None) for v in x]
    if isinstance(x, bool | np.bool_):
        return bool(x)
    if isinstance(x, int | np.integer):
        return int(x)
    return x


def _records(rows: list[Any] | tuple[Any, ...]) -> list[dict[str, Any]] | None:
    """``rows`` cleaned column by column, as :func:`_clean` cleans each, where they are many records alike
    (objects of the same keys, none a component of a vector, each column all numbers, all arrays of a few
    numbers of one length, or all ints, strings, bools and nulls); else None."""
    if len(rows) <= SMALL or type(rows[0]) is not dict or _components(rows[0]):
        return None
    keys = rows[0].keys()
    if not all(type(r) is dict and r.keys() == keys for r in rows):
        return None
    columns = []
    for key in keys:
        column = _column([r[key] for r in rows])
        if column is None:
            return None
        columns.append(column)
    names = [str(k) for k in keys]
    return [dict(zip(names, values, strict=True)) for values in zip(*columns, strict=True)]


def _column(values: list[Any]) -> list[Any] | None:
    """One column of :func:`_records` cleaned (numbers alone as they are, rounded; arrays each by its own
    :func:`magnitude`), or None where it is not of one of its kinds."""
    kinds = {type(v) for v in values}
    if kinds <= {str, int, bool, type(None)}:
        return values
    if all(issubclass(k, float | np.floating) or k is type(None) for k in kinds):
        return _floats(np.array([np.nan if v is None else v for v in values], dtype=float), 0.0)
    if kinds != {list} or not 0 < len(values[0]) <= SMALL or len({len(v) for v in values}) != 1:
        return None
    if not {type(c) for v in values for c in v} <= {float, np.float64, type(None)}:
        return None
    width = len(values[0])
    a = np.array(values, dtype=float)  # None as NaN
    cleaned = _floats(a.ravel(), np.repeat(_row_magnitudes(a), width))
    return [cleaned[i : i + width] for i in range(0, len(cleaned), width)]


def _row_magnitudes(a: np.ndarray) -> np.ndarray:
    """:func:`magnitude` of each row of ``a`` (n, w), as :func:`_few` finds it."""
    m = np.abs(a)
    m[~np.isfinite(m) | (m == 0.0)] = np.nan
    m = np.sort(m, axis=1)  # NaN last
    count = np.sum(np.isfinite(m), axis=1)
    at = SHARE * np.maximum(count - 1, 0)
    low = np.floor(at).astype(int)
    high = np.minimum(low + 1, np.maximum(count - 1, 0))
    rows = np.arange(len(m))
    lo, hi = m[rows, low], m[rows, high]
    return np.where(count > 0, lo + (at - low) * (hi - lo), 0.0)


#: Arrays of at most this many numbers are written by :func:`_few` (the same numbers, without NumPy's cost).
SMALL = 8


def _few(values: list[float | None], scale: float | None) -> list[float | None]:
    """:func:`_floats` of a few numbers (None: no value), in Python: the same rounding and snapping, the
    scale their own :func:`magnitude` unless given."""
    if scale is None:
        m = sorted(abs(v) for v in values if v is not None and math.isfinite(v) and v != 0.0)
        at = SHARE * (len(m) - 1)
        low = int(at)
        scale = m[low] + (at - low) * (m[min(low + 1, len(m) - 1)] - m[low]) if m else 0.0
    out: list[float | None] = []
    for v in values:
        if v is None or not math.isfinite(v):
            out.append(None)
        elif v == 0.0 or abs(v) < ZERO * scale:
            out.append(0.0)
        else:
            k = DIGITS - 1 - math.floor(math.log10(abs(v)))
            if abs(k) > 22:  # 10**k is no double exactly (or none at all, near 1e308)
                out.append(float(f"{v:.{DIGITS}g}"))
                continue
            p = 10.0 ** abs(k)
            out.append(round(v * p) / p if k >= 0 else round(v / p) * p)
    return out


def _floats(a: np.ndarray, scale: float | np.ndarray) -> list[float | None]:
    """The floats ``a`` (n,) rounded to :data:`DIGITS` significant digits, those below ``ZERO * scale`` (one
    scale, or one for each) as 0.0, NaN and infinities as None: ``float(f"{v:.12g}")``, but a division by a
    power of ten instead of a string where the power is exact (ties may round the other way)."""
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
