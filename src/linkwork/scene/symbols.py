"""The conventional symbols of a kinematic scheme, as outlines in the axes of the link that carries them.

Sizes are in units of ``r``, the radius of a pivot's circle (1.2 % of the drawing's size): a support
is a triangle 3.2 r wide and 2.8 r high on a hatched base; a slider block is 4 r by 2 r; a guide runs
1.3 r beside its slider's centre line, hatched on the far side.

The points and directions a symbol is drawn from are pairs of floats, and its corners are worked out a
coordinate at a time in Python's floats: the arithmetic of NumPy's on arrays of two, in the same order,
without its cost per call (a scheme draws some ninety items on every edit of the viewer).  A direction
turned a quarter counter-clockwise, ``(-y, x)``, is :func:`~linkwork.structure.constraints.perp`.
"""

from __future__ import annotations

from itertools import accumulate
from typing import NamedTuple

import numpy as np

from linkwork.structure.constraints import perp

#: A point or a direction, ``(x, y)``.
XY = tuple[float, float]


class Hatch(NamedTuple):
    """A line hatched on one side: from ``a`` to ``b``, the strokes slanting out towards the unit direction
    ``out``."""

    a: XY
    b: XY
    out: XY


def support(apex: XY, down: XY, r: float) -> tuple[np.ndarray, Hatch]:
    """A hinge on the frame at ``apex``, standing towards the unit direction ``down``.

    Returns
    -------
    triangle : ndarray, shape (3, 2)
        Apex first.
    base : Hatch
        Hatched on its far side (:func:`hatches`).
    """
    (ax, ay), (dx, dy) = apex, down
    fx, fy = ax + 2.8 * r * dx, ay + 2.8 * r * dy  # the middle of the base
    hx, hy, wx, wy = 1.6 * r * -dy, 1.6 * r * dx, 2.6 * r * -dy, 2.6 * r * dx  # half the triangle's, the base's width
    triangle = np.array([[ax, ay], [fx - hx, fy - hy], [fx + hx, fy + hy]])
    return triangle, Hatch((fx - wx, fy - wy), (fx + wx, fy + wy), down)


def hatches(lines: list[Hatch], r: float) -> list[np.ndarray]:
    """The strokes of each of ``lines``, every 0.8 r from its start: ``(H, 2, 2)`` each.

    The strokes of all the lines are worked out together, each line's numbers repeated for its strokes."""
    if not lines:
        return []
    lengths = np.hypot([b[0] - a[0] for a, b, _ in lines], [b[1] - a[1] for a, b, _ in lines]).tolist()
    along, per = [], []  # the strokes' places along each line; each line's start, direction and slant
    for (a, b, (ox, oy)), length in zip(lines, lengths, strict=True):
        ux, uy = ((b[0] - a[0]) / length, (b[1] - a[1]) / length) if length > 0 else (-oy, ox)
        along.append(np.arange(0.0, length + 1e-9 * max(length, 1.0), 0.8 * r))
        per.append((a[0], a[1], ux, uy, 0.8 * r * ox, 0.8 * r * oy, 0.6 * r * ux, 0.6 * r * uy))
    counts = [len(s) for s in along]
    s = np.concatenate(along)
    ax, ay, ux, uy, ox, oy, bx, by = np.repeat(np.array(per), counts, axis=0).T
    strokes = np.empty((len(s), 2, 2))
    x0, y0, x1, y1 = strokes.reshape(-1, 4).T  # views of the strokes' ends
    x0[:], y0[:] = ax + s * ux, ay + s * uy
    x1[:], y1[:] = x0 + ox - bx, y0 + oy - by
    ends = list(accumulate(counts))
    return [strokes[i:j] for i, j in zip([0, *ends], ends, strict=False)]


def block(centre: XY, u: XY, r: float) -> np.ndarray:
    """A slider block ``(4, 2)`` about ``centre``, 4 r long along the unit direction ``u`` and 2 r across."""
    (cx, cy), (ux, uy) = centre, u
    lx, ly, wx, wy = 2 * r * ux, 2 * r * uy, r * -uy, r * ux  # half its length along u, half its width across
    return np.array(
        [
            [cx - lx - wx, cy - ly - wy],
            [cx + lx - wx, cy + ly - wy],
            [cx + lx + wx, cy + ly + wy],
            [cx - lx + wx, cy - ly + wy],
        ]
    )


def guide(origin: XY, u: XY, span: XY, side: float, r: float) -> Hatch:
    """A guide along the unit direction ``u`` through ``origin``, from ``span[0]`` to ``span[1]`` along it,
    drawn 1.3 r to the ``side`` (+1 left of ``u``, -1 right) and hatched farther out (:func:`hatches`)."""
    (px, py), (ux, uy) = origin, u
    w = (side * -uy, side * ux)
    bx, by = 1.3 * r * w[0], 1.3 * r * w[1]
    return Hatch((px + span[0] * ux + bx, py + span[0] * uy + by), (px + span[1] * ux + bx, py + span[1] * uy + by), w)


def blade(edge: XY, d: XY, r: float) -> tuple[np.ndarray, np.ndarray]:
    """A knife or tool whose working edge is at ``edge``, facing the unit direction ``d``.

    Returns
    -------
    body : ndarray, shape (4, 2)
        5 r wide across ``d`` and 2.5 r deep behind the edge.
    line : ndarray, shape (2, 2)
        The working edge.
    """
    (ex, ey), (dx, dy) = edge, d
    hx, hy, bx, by = 2.5 * r * -dy, 2.5 * r * dx, 2.5 * r * dx, 2.5 * r * dy  # half its width, its depth
    left, right = (ex - hx, ey - hy), (ex + hx, ey + hy)
    body = np.array([left, right, (right[0] - bx, right[1] - by), (left[0] - bx, left[1] - by)])
    return body, body[:2]


def anvil(face: np.ndarray, normal: np.ndarray, r: float) -> np.ndarray:
    """A body at rest whose face through ``face`` has the outward unit ``normal`` (the tool a striker hits):
    ``(4, 2)``, 4 r wide and 7 r deep."""
    w = perp(normal)
    return np.array(
        [face - 2 * r * w, face + 2 * r * w, face + 2 * r * w - 7 * r * normal, face - 2 * r * w - 7 * r * normal]
    )


#: Half-teeth of a spring's zigzag, and the share of its length either lead takes.
TEETH, LEAD = 8, 0.2


def force_element(kind: str, r: float) -> tuple[np.ndarray, ...]:
    """The strokes of a spring (a zigzag between two straight leads) or a damper (a rod and a piston in an open
    cylinder) between two points ``a`` and ``b``, as rows ``(f, s, c)``: the vertex ``a + f (b - a) + s u + c n``,
    ``u`` the unit direction from ``a`` to ``b`` and ``n`` it turned a quarter counter-clockwise (``s``, ``c`` in
    m), so that the ends follow the two points at every pose (:meth:`SchemeScene.element_strokes
    <linkwork.scene.scheme.SchemeScene.element_strokes>`).  The zigzag is ``1.5 r`` to either side, stretched
    with the length; the damper's symbol keeps its size, centred."""
    w = 1.5 * r
    if kind == "spring":
        f = LEAD + (1 - 2 * LEAD) * (2 * np.arange(TEETH) + 1) / (2 * TEETH)
        c = w * np.where(np.arange(TEETH) % 2 == 0, 1.0, -1.0)
        rows = np.concatenate([[[0, 0, 0], [LEAD, 0, 0]], np.stack([f, 0 * f, c], 1), [[1 - LEAD, 0, 0], [1, 0, 0]]])
        return (rows,)
    rod = np.array([[0, 0, 0], [0.5, 0, 0]], dtype=float)
    piston = np.array([[0.5, 0, -w], [0.5, 0, w]])
    h, side = 1.5 * r, 1.3 * w
    cylinder = np.array([[0.5, -h, side], [0.5, h, side], [0.5, h, -side], [0.5, -h, -side]])
    tail = np.array([[0.5, h, 0], [1, 0, 0]])
    return rod, piston, cylinder, tail
