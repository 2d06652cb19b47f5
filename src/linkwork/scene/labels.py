"""Where the labels of a drawing go: beside their points, clear of each other and of the lines drawn.

Each label is a box of text centred at a point chosen among candidates around its anchor (twelve
directions at six distances, the farther ones weighed only where the nearer are all taken).  A
candidate costs more the more it covers: another label (never accepted where any candidate is free), a
line of the drawing, a pivot; then the farther it is and the farther from the label's preferred
direction.  Labels are placed one after the other in the order
given (the first ones choose first), each at every sample at once: the choice along the samples is
the cheapest path in which a label changes place only where that saves more than a small penalty, so
that labels do not flicker while the mechanism moves (a Viterbi pass over the samples).  Deterministic:
the same drawing always gets the same labels.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: Directions of the candidates (counter-clockwise from +x, starting up-right) and their distances from
#: the anchor in units of the label's gap.
DIRECTIONS = np.radians(np.array([45, 135, 315, 225, 90, 0, 270, 180, 60, 120, 300, 240]))
RINGS = (1.0, 2.0, 3.2, 4.6, 6.5, 9.0)

#: Costs: covering another label, a line, a pivot; each ring farther out; turning away from the
#: preferred direction (at most); changing place from one sample to the next.
COVER_LABEL, COVER_LINE, COVER_PIVOT, FARTHER, TURNED, SWITCH = 1000.0, 25.0, 25.0, 3.0, 2.0, 1.5

#: Cost of each further alternative anchor.
SLIDE = 1.0


@dataclass(frozen=True)
class Obstacles:
    """What labels should not cover, at every sample (NaN where absent).

    Attributes
    ----------
    segments : ndarray, shape (A, S, 2, 2)
        Lines of the drawing, end to end.
    circles : ndarray, shape (A, C, 3)
        Pivots and dots: centre x, y and radius.
    """

    segments: np.ndarray
    circles: np.ndarray


def place_labels(
    anchors: np.ndarray,
    sizes: np.ndarray,
    gaps: np.ndarray,
    obstacles: Obstacles,
    prefer: np.ndarray | None = None,
    pad: float = 0.0,
    taken: np.ndarray | None = None,
    directions: np.ndarray = DIRECTIONS,
) -> np.ndarray:
    """Centres of the labels' boxes, one label after the other.

    Parameters
    ----------
    anchors : ndarray, shape (A, L, 2) or (A, L, M, 2)
        The points labelled; NaN where a label is not drawn at a sample.  With M alternatives for each
        (e.g. points along a link, for its number), the first preferred, each further one costing
        :data:`SLIDE` more.
    sizes : ndarray, shape (A, L, 2) or (L, 2)
        Width and height of each label's box.
    gaps : ndarray, shape (L,)
        Least distance from a label's anchor to its box.
    obstacles : Obstacles
        Lines and pivots to keep clear of.
    prefer : ndarray, shape (A, L, 2), optional
        Unit direction each label prefers (e.g. away from the links at its point); default up and right.
    pad : float
        Clearance kept between two labels' boxes.
    taken : ndarray, shape (A, B, 4), optional
        Boxes ``[x0, y0, x1, y1]`` of texts placed before, to keep clear of as of the labels.
    directions : ndarray
        The directions of the candidates, rad (default :data:`DIRECTIONS`; more of them for a crowded drawing
        of few samples, such as the plan of positions).

    Returns
    -------
    ndarray, shape (A, L, 2)
        NaN where the anchor is.
    """
    n_samples, n_labels = anchors.shape[:2]
    alternatives = anchors if anchors.ndim == 4 else anchors[:, :, None, :]
    sizes = np.broadcast_to(sizes, (n_samples, n_labels, 2))
    if prefer is None:
        prefer = np.broadcast_to(np.array([np.sqrt(0.5), np.sqrt(0.5)]), (n_samples, n_labels, 2))
    placed = np.full((n_samples, 0, 4), np.nan) if taken is None else np.asarray(taken, dtype=float)
    out = np.full((n_samples, n_labels, 2), np.nan)
    for j in range(n_labels):
        centres, boxes = _place_one(
            alternatives[:, j], sizes[:, j], float(gaps[j]), prefer[:, j], placed, obstacles, pad, directions
        )
        out[:, j] = centres
        placed = np.concatenate([placed, boxes[:, None]], 1)
    return out


def _place_one(
    alts: np.ndarray,
    size: np.ndarray,
    gap: float,
    prefer: np.ndarray,
    placed: np.ndarray,
    obstacles: Obstacles,
    pad: float,
    directions: np.ndarray = DIRECTIONS,
) -> tuple[np.ndarray, np.ndarray]:
    """The centre ``(A, 2)`` and box ``(A, 4)`` of one label with alternative anchors ``alts`` ``(A, M, 2)``.

    The candidates are weighed ring by ring and anchor by anchor, in the order of their preference; a
    sample stops being weighed once a candidate covers nothing (the others stay out of its choice).
    """
    n, m = alts.shape[:2]
    per = len(directions)
    centres = np.concatenate([_candidates(alts[:, a], size, gap, directions) for a in range(m)], 1)  # (A, M*R*D, 2)
    boxes = _boxes(centres, size[:, None, :])
    base = np.tile(_preference(prefer, directions), m) + np.repeat(SLIDE * np.arange(m), per * len(RINGS))
    cost = np.full(base.shape, 1e6)
    todo = np.isfinite(alts).all(-1).any(-1)
    for _, a, ring in sorted((ring * FARTHER + a * SLIDE, a, ring) for a in range(m) for ring in range(len(RINGS))):
        rows = np.flatnonzero(todo)
        if not len(rows):
            break
        cols = slice((a * len(RINGS) + ring) * per, (a * len(RINGS) + ring + 1) * per)
        sub = boxes[rows, cols]
        near = _near(Obstacles(obstacles.segments[rows], obstacles.circles[rows]), sub)
        covered = np.where(np.isfinite(sub).all(-1), _cost(sub, placed[rows], near, pad), np.inf)
        cost[rows, cols] = covered + base[rows, cols]
        todo[rows] &= ~(covered.min(1) == 0)
    pick = _smooth(np.where(np.isfinite(cost), cost, 1e9))
    return (
        np.take_along_axis(centres, pick[:, None, None], 1)[:, 0],
        np.take_along_axis(boxes, pick[:, None, None], 1)[:, 0],
    )


def _candidates(anchor: np.ndarray, size: np.ndarray, gap: float, directions: np.ndarray = DIRECTIONS) -> np.ndarray:
    """Centres ``(A, K, 2)``: the box's edge ``gap * ring`` from the anchor along each direction."""
    d = np.stack([np.cos(directions), np.sin(directions)], -1)  # (D, 2)
    half = size[:, None, :] / 2  # (A, 1, 2)
    with np.errstate(divide="ignore"):
        to_edge = np.min(half / np.maximum(np.abs(d)[None], 1e-12), axis=-1)  # (A, D)
    out = [anchor[:, None, :] + d[None] * (gap * ring + to_edge)[..., None] for ring in RINGS]
    return np.concatenate(out, 1)


def _near(obstacles: Obstacles, boxes: np.ndarray) -> Obstacles:
    """The obstacles that come within the reach of ``boxes`` ``(A, K, 4)`` at some sample."""
    finite = np.isfinite(boxes)
    lo = np.min(np.where(finite, boxes, np.inf)[..., :2], axis=1)[:, None, :]  # (A, 1, 2)
    hi = np.max(np.where(finite, boxes, -np.inf)[..., 2:], axis=1)[:, None, :]
    with np.errstate(invalid="ignore"):
        seg = obstacles.segments
        s_lo, s_hi = np.minimum(seg[:, :, 0], seg[:, :, 1]), np.maximum(seg[:, :, 0], seg[:, :, 1])
        seg_near = ((s_hi >= lo) & (s_lo <= hi)).all(-1).any(0)  # (S,)
        c = obstacles.circles
        circ_near = ((c[..., :2] + c[..., 2:] >= lo) & (c[..., :2] - c[..., 2:] <= hi)).all(-1).any(0)
    return Obstacles(seg[:, seg_near], c[:, circ_near])


def _boxes(centres: np.ndarray, size: np.ndarray) -> np.ndarray:
    """``[x0, y0, x1, y1]`` ``(..., 4)`` of boxes of ``size`` about ``centres``."""
    return np.concatenate([centres - size / 2, centres + size / 2], -1)


def _preference(prefer: np.ndarray, directions: np.ndarray = DIRECTIONS) -> np.ndarray:
    """Cost ``(A, K)`` of distance (ring) and direction away from ``prefer`` ``(A, 2)``."""
    d = np.stack([np.cos(directions), np.sin(directions)], -1)
    turned = TURNED * (1 - prefer @ d.T) / 2  # (A, D)
    return np.concatenate([turned + FARTHER * i for i in range(len(RINGS))], 1)


def _cost(boxes: np.ndarray, placed: np.ndarray, obstacles: Obstacles, pad: float) -> np.ndarray:
    """Cost ``(A, K)`` of what each candidate box covers."""
    grown = boxes + np.array([-pad, -pad, pad, pad])
    cost = COVER_LABEL * _boxes_hit(grown, placed)
    cost += COVER_LINE * segments_hit(grown, obstacles.segments)
    cost += COVER_PIVOT * _circles_hit(grown, obstacles.circles)
    return cost


def _boxes_hit(boxes: np.ndarray, others: np.ndarray) -> np.ndarray:
    """How many of ``others`` ``(A, B, 4)`` each of ``boxes`` ``(A, K, 4)`` overlaps, ``(A, K)``."""
    if not others.shape[1]:
        return np.zeros(boxes.shape[:2])
    a, b = boxes[:, :, None, :], others[:, None, :, :]
    hit = (a[..., 0] < b[..., 2]) & (b[..., 0] < a[..., 2]) & (a[..., 1] < b[..., 3]) & (b[..., 1] < a[..., 3])
    return hit.sum(-1)


def segments_hit(boxes: np.ndarray, segments: np.ndarray) -> np.ndarray:
    """How many of ``segments`` ``(A, S, 2, 2)`` cross or touch each box of ``boxes`` ``(A, K, 4)``, ``(A, K)``.

    A segment meets a box where their extents overlap on both axes and the box's corners are not all on
    one side of the segment's line (the separating axes of a segment and a box).
    """
    return ends_hit(boxes, segments.reshape(*segments.shape[:2], 4).transpose(2, 0, 1))


def ends_hit(boxes: np.ndarray, ends: np.ndarray) -> np.ndarray:
    """:func:`segments_hit` of the segments given by the coordinates of their ends ``ends`` ``(4, A, S)`` (``x0, y0,
    x1, y1``), each coordinate weighed apart (NumPy is slow over short axes)."""
    n_boxes, n_segments = boxes.shape[1], ends.shape[2]
    if not n_segments:
        return np.zeros(boxes.shape[:2])
    x0, y0, x1, y1 = ends[:, :, None, :]  # (A, 1, S) each
    bx0, by0, bx1, by1 = boxes.transpose(2, 0, 1)[..., None]  # (A, K, 1) each
    overlap = (np.maximum(x0, x1) >= bx0) & (np.minimum(x0, x1) <= bx1)
    overlap &= (np.maximum(y0, y1) >= by0) & (np.minimum(y0, y1) <= by1)
    box, s = np.divmod(np.flatnonzero(overlap), n_segments)  # the few pairs whose extents overlap
    px, py, qx, qy = ends[:, box // n_boxes, s]
    corners = boxes.reshape(-1, 4)[box].T  # x0, y0, x1, y1 of each pair's box
    cx, cy = corners[[0, 2, 2, 0]], corners[[1, 1, 3, 3]]  # its corners (x0, y0), (x1, y0), (x1, y1), (x0, y1)
    sides = (qx - px) * (cy - py) - (qy - py) * (cx - px)  # (4, pairs): which side of the segment's line
    crossed = box[~((sides.min(0) > 0) | (sides.max(0) < 0))]
    return np.bincount(crossed, minlength=boxes.shape[0] * n_boxes).reshape(boxes.shape[:2]).astype(float)


def _circles_hit(boxes: np.ndarray, circles: np.ndarray) -> np.ndarray:
    """How many of ``circles`` ``(A, C, 3)`` each box of ``boxes`` ``(A, K, 4)`` overlaps, ``(A, K)``."""
    if not circles.shape[1]:
        return np.zeros(boxes.shape[:2])
    cx, cy, r = circles[:, None, :, 0], circles[:, None, :, 1], circles[:, None, :, 2]
    nx = np.clip(cx, boxes[:, :, None, 0], boxes[:, :, None, 2])
    ny = np.clip(cy, boxes[:, :, None, 1], boxes[:, :, None, 3])
    return ((nx - cx) ** 2 + (ny - cy) ** 2 < r * r).sum(-1)


def _smooth(cost: np.ndarray) -> np.ndarray:
    """The candidate ``(A,)`` of least total cost along the samples, with :data:`SWITCH` for each change."""
    n = len(cost)
    total = cost[0].copy()
    back = np.zeros(cost.shape, dtype=int)
    for a in range(1, n):
        best = int(np.argmin(total))
        stay = total <= total[best] + SWITCH
        back[a] = np.where(stay, np.arange(cost.shape[1]), best)
        total = cost[a] + np.where(stay, total, total[best] + SWITCH)
    pick = np.empty(n, dtype=int)
    pick[-1] = int(np.argmin(total))
    for a in range(n - 1, 0, -1):
        pick[a - 1] = back[a, pick[a]]
    return pick
