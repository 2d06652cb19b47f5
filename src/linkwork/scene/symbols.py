"""The conventional symbols of a kinematic scheme, as outlines in the axes of the link that carries them.

Sizes are in units of ``r``, the radius of a pivot's circle (1.2 % of the drawing's size): a support
is a triangle 3.2 r wide and 2.8 r high on a hatched base; a slider block is 4 r by 2 r; a guide runs
1.3 r beside its slider's centre line, hatched on the far side.
"""

from __future__ import annotations

import numpy as np

from linkwork.structure.constraints import perp


def support(apex: np.ndarray, down: np.ndarray, r: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A hinge on the frame at ``apex``, standing towards the unit direction ``down``.

    Returns
    -------
    triangle : ndarray, shape (3, 2)
        Apex first.
    base : ndarray, shape (2, 2)
    hatch : ndarray, shape (H, 2, 2)
        Short strokes on the far side of the base.
    """
    w = perp(down)
    triangle = np.array([apex, apex + 2.8 * r * down - 1.6 * r * w, apex + 2.8 * r * down + 1.6 * r * w])
    base = np.array([apex + 2.8 * r * down - 2.6 * r * w, apex + 2.8 * r * down + 2.6 * r * w])
    return triangle, base, _hatch(base[0], base[1], down, r)


def _hatch(a: np.ndarray, b: np.ndarray, out: np.ndarray, r: float) -> np.ndarray:
    """Strokes every 0.8 r along the line from ``a`` to ``b``, slanting out towards ``out``: ``(H, 2, 2)``."""
    length = float(np.hypot(*(b - a)))
    u = (b - a) / length if length > 0 else perp(out)
    s = np.arange(0.0, length + 1e-9 * max(length, 1.0), 0.8 * r)
    starts = a + s[:, None] * u
    ends = starts + 0.8 * r * out - 0.6 * r * u
    return np.stack([starts, ends], 1)


def block(centre: np.ndarray, u: np.ndarray, r: float) -> np.ndarray:
    """A slider block ``(4, 2)`` about ``centre``, 4 r long along the unit direction ``u`` and 2 r across."""
    w = perp(u)
    return np.array([centre + cu * 2 * r * u + cw * r * w for cu, cw in ((-1, -1), (1, -1), (1, 1), (-1, 1))])


def guide(
    origin: np.ndarray, u: np.ndarray, span: tuple[float, float], side: float, r: float
) -> tuple[np.ndarray, np.ndarray]:
    """A guide along the unit direction ``u`` through ``origin``, from ``span[0]`` to ``span[1]`` along it,
    drawn 1.3 r to the ``side`` (+1 left of ``u``, -1 right) and hatched farther out.

    Returns
    -------
    line : ndarray, shape (2, 2)
    hatch : ndarray, shape (H, 2, 2)
    """
    w = side * perp(u)
    a, b = origin + span[0] * u + 1.3 * r * w, origin + span[1] * u + 1.3 * r * w
    return np.array([a, b]), _hatch(a, b, w, r)


def blade(edge: np.ndarray, d: np.ndarray, r: float) -> tuple[np.ndarray, np.ndarray]:
    """A knife or tool whose working edge is at ``edge``, facing the unit direction ``d``.

    Returns
    -------
    body : ndarray, shape (4, 2)
        5 r wide across ``d`` and 2.5 r deep behind the edge.
    line : ndarray, shape (2, 2)
        The working edge.
    """
    w = perp(d)
    body = np.array(
        [edge - 2.5 * r * w, edge + 2.5 * r * w, edge + 2.5 * r * w - 2.5 * r * d, edge - 2.5 * r * w - 2.5 * r * d]
    )
    return body, body[:2]


def anvil(face: np.ndarray, normal: np.ndarray, r: float) -> np.ndarray:
    """A body at rest whose face through ``face`` has the outward unit ``normal`` (the tool a striker hits):
    ``(4, 2)``, 4 r wide and 7 r deep."""
    w = perp(normal)
    return np.array(
        [face - 2 * r * w, face + 2 * r * w, face + 2 * r * w - 7 * r * normal, face - 2 * r * w - 7 * r * normal]
    )


def section(corners: np.ndarray, step: float) -> np.ndarray:
    """Section hatching of a rectangle ``(4, 2)`` (corners in order): strokes at 45 degrees ``(H, 2, 2)``
    ``step`` apart, clipped to it."""
    lo, hi = corners.min(0), corners.max(0)
    offsets = np.arange(lo[0] - hi[1], hi[0] - lo[1], step) + step / 2  # lines x - y = c
    out = []
    for c in offsets:
        x0, x1 = max(lo[0], lo[1] + c), min(hi[0], hi[1] + c)
        if x1 > x0:
            out.append([[x0, x0 - c], [x1, x1 - c]])
    return np.array(out, dtype=float).reshape(-1, 2, 2)
