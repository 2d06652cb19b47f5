"""Plane geometry of the drawings: link axes to the frame's, outlines, and the size of a label's text.

Everything is vectorised over samples: a shape given in a link's own axes ``(K, 2)`` is placed at the
link's poses ``(A, 3)`` as ``(A, K, 2)``.
"""

from __future__ import annotations

import re

import numpy as np

#: Advance widths of the printable ASCII characters (32 to 126) in DejaVu Sans, the default font of
#: matplotlib, in thousandths of the font size (em).
_ADVANCE = (
    318,
    401,
    460,
    838,
    636,
    950,
    780,
    275,
    390,
    390,
    500,
    838,
    318,
    361,
    318,
    337,
    636,
    636,
    636,
    636,
    636,
    636,
    636,
    636,
    636,
    636,
    337,
    337,
    838,
    838,
    838,
    531,
    1000,
    684,
    686,
    698,
    770,
    631,
    575,
    775,
    752,
    295,
    295,
    656,
    557,
    863,
    748,
    787,
    603,
    787,
    695,
    635,
    611,
    732,
    684,
    989,
    685,
    611,
    685,
    390,
    337,
    390,
    838,
    500,
    500,
    613,
    635,
    550,
    635,
    615,
    352,
    635,
    634,
    278,
    279,
    579,
    278,
    974,
    634,
    611,
    635,
    635,
    412,
    521,
    392,
    634,
    592,
    818,
    592,
    592,
    525,
    637,
    337,
    636,
    838,
)

#: Height of a line of text (ascent and descent of DejaVu Sans) in ems.
LINE = 1.17

#: Width of a character outside printable ASCII (Cyrillic, Greek), in ems: as wide as the widest letters.
WIDE = 0.8


#: Size of a subscript in ems of its label's text.
SUBSCRIPT = 0.7

#: A word of a label that has a subscript: a letter (with primes) and ``_`` and its subscript (``n_ba``,
#: ``k'_a``), or a capital letter and its number (``O1``, ``R12``, the inertia force ``Φ2`` and the inertia
#: moment's forces ``MΦ2'`` as the textbook writes them, Φ₂, as mathtext does).
#: The viewer's page reads the pattern from the payload (one rule for every renderer).
SUBSCRIPTED = r"(?<![0-9A-Za-z])(?:([A-Za-zα-ωπ]'*)_([^\s,_]+)|((?:MΦ|[A-ZΦ])'*)([0-9]+)(?![0-9A-Za-z_.]))"
_SUBSCRIPTED = re.compile(SUBSCRIPTED)


def text_runs(text: str) -> list[tuple[str, bool]]:
    """The runs of a label's text, each with whether it is a subscript: ``"a, n_ba"`` is ``[("a, n", False),
    ("ba", True)]``; ``"O1"`` is ``[("O", False), ("1", True)]``.  Every renderer draws these (matplotlib's
    mathtext, the viewer's SVG tspans, DXF's MTEXT stacks), so that no label shows a raw underscore."""
    runs: list[tuple[str, bool]] = []
    at = 0
    for m in _SUBSCRIPTED.finditer(text):
        base, sub = (m.group(1), m.group(2)) if m.group(1) else (m.group(3), m.group(4))
        runs.append((text[at : m.start()] + base, False))
        runs.append((sub, True))
        at = m.end()
    runs.append((text[at:], False))
    return [(run, sub) for run, sub in runs if run]


def text_size(text: str, em: float) -> tuple[float, float]:
    """Width and height of one line of ``text`` set at font size ``em`` (in the units of ``em``), its
    subscripts (:func:`text_runs`) :data:`SUBSCRIPT` as large.

    The widths are those of DejaVu Sans; characters outside printable ASCII count as :data:`WIDE`,
    which is wider than most, so that a box made from this size holds the text as drawn.
    """
    width = sum(_width(run) * (SUBSCRIPT if sub else 1.0) for run, sub in text_runs(text))
    return width * em, LINE * em


def _width(text: str) -> float:
    """Width of ``text`` in ems of DejaVu Sans."""
    return sum(_ADVANCE[ord(c) - 32] / 1000 if 32 <= ord(c) < 127 else WIDE for c in text)


def place(poses: np.ndarray, xy: np.ndarray) -> np.ndarray:
    """Points given in a link's axes, placed at its poses.

    Parameters
    ----------
    poses : ndarray, shape (A, 3)
        The link's poses (x, y in m, angle in rad).
    xy : ndarray, shape (K, 2)
        The points in the link's axes, m.

    Returns
    -------
    ndarray, shape (A, K, 2)
    """
    c, s = np.cos(poses[:, 2])[:, None], np.sin(poses[:, 2])[:, None]
    x, y = xy[None, :, 0], xy[None, :, 1]
    return np.stack([poses[:, None, 0] + c * x - s * y, poses[:, None, 1] + s * x + c * y], -1)


def hull(xy: np.ndarray) -> np.ndarray:
    """Indices of the convex hull of ``xy`` ``(K, 2)``, counter-clockwise (Andrew's monotone chain);
    points on an edge are left out, so that collinear points give the two ends only."""
    order = np.lexsort((xy[:, 1], xy[:, 0]))
    pts = xy.tolist()  # the turns weighed in Python's floats (the same arithmetic, without NumPy's cost per call)

    def chain(seq: list[int]) -> list[int]:
        out: list[int] = []
        for i in seq:
            while len(out) >= 2:
                a, b, c = pts[out[-2]], pts[out[-1]], pts[i]
                if (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]) > 1e-12:
                    break
                out.pop()
            out.append(i)
        return out

    seq = order.tolist()
    lower, upper = chain(seq), chain(seq[::-1])
    return np.array(lower[:-1] + upper[:-1] if len(order) > 2 else seq, dtype=int)


def collinear(xy: np.ndarray, tol: float = 1e-3) -> bool:
    """Whether the points ``(K, 2)`` lie on one line, to ``tol`` of their spread."""
    if len(xy) < 3:
        return True
    centred = xy - xy.sum(0) / len(xy)  # minus their mean
    s = np.linalg.svd(centred, compute_uv=False)
    return bool(s[1] <= tol * max(s[0], 1e-300))


def bounds(*arrays: np.ndarray) -> np.ndarray:
    """``[x0, y0, x1, y1]`` of the finite points of ``arrays`` ``(..., 2)``; a unit box if there are none."""
    pts = np.concatenate(
        [np.asarray(a, dtype=float).reshape(-1, 2) for a in arrays if np.size(a)] or [np.zeros((0, 2))]
    )
    x, y = pts[:, 0], pts[:, 1]  # each coordinate apart (NumPy is slow over short axes)
    finite = np.isfinite(x) & np.isfinite(y)
    if not finite.any():
        return np.array([-1.0, -1.0, 1.0, 1.0])
    x, y = x[finite], y[finite]
    return np.array([x.min(), y.min(), x.max(), y.max()])
