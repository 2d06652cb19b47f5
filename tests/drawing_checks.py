"""Checks of a drawn matplotlib figure, read back through the Agg renderer: texts that cover other texts
or are cut by the figure's edge, axes that cover other axes.

Only what is drawn counts: the figure's and every axes' texts, titles and legends, and the labels and
tick labels of the axes that show their axis; empty and invisible texts are left out.  Two boxes
cover each other where they overlap by more than :data:`SLACK` pixels both across and up (anti-aliased
edges that touch do not count).
"""

from __future__ import annotations

from itertools import combinations

from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.text import Text
from matplotlib.transforms import Bbox

#: Overlap in pixels (at the figure's dpi) below which two boxes are taken as touching, not covering.
SLACK = 0.5


def drawn_texts(fig: Figure) -> list[Text]:
    """The texts the figure draws."""
    texts: list[Text] = list(fig.texts)
    for legend in fig.legends:
        texts += legend.get_texts()
    texts += [t for t in (getattr(fig, "_suptitle", None), getattr(fig, "_supxlabel", None),
                          getattr(fig, "_supylabel", None)) if t is not None]  # fmt: skip
    for ax in fig.axes:
        if not ax.get_visible():
            continue
        texts += ax.texts + [ax.title, ax._left_title, ax._right_title]
        if ax.get_legend() is not None:
            texts += ax.get_legend().get_texts()
        if ax.axison:
            for axis in (ax.xaxis, ax.yaxis):
                if axis.get_visible():
                    texts += [axis.label, axis.get_offset_text()] + _shown_ticklabels(ax, axis)
    unique = list({id(t): t for t in texts}.values())  # a suptitle is among the figure's texts too
    return [t for t in unique if t.get_visible() and t.get_text().strip()]


def _shown_ticklabels(ax, axis) -> list[Text]:
    """Tick labels inside the axis' view (those outside are not drawn)."""
    lo, hi = sorted(axis.get_view_interval())
    out = []
    for tick in axis.get_major_ticks():
        if lo - 1e-9 * abs(hi - lo) <= tick.get_loc() <= hi + 1e-9 * abs(hi - lo):
            out += [label for label in (tick.label1, tick.label2) if label.get_visible()]
    return out


def _cover(a: Bbox, b: Bbox) -> bool:
    return min(a.x1, b.x1) - max(a.x0, b.x0) > SLACK and min(a.y1, b.y1) - max(a.y0, b.y0) > SLACK


def overlaps(fig: Figure) -> list[str]:
    """Every pair of drawn texts whose boxes cover each other, every text the figure's edge cuts and every pair
    of axes that cover each other, in words (empty for a clean figure)."""
    canvas = fig.canvas if isinstance(fig.canvas, FigureCanvasAgg) else FigureCanvasAgg(fig)
    canvas.draw()
    renderer = canvas.get_renderer()
    texts = drawn_texts(fig)
    boxes = [t.get_window_extent(renderer) for t in texts]
    out = [
        f"text {texts[i].get_text()!r} covers {texts[j].get_text()!r}"
        for i, j in combinations(range(len(texts)), 2)
        if _cover(boxes[i], boxes[j])
    ]
    edge = fig.bbox
    out += [
        f"text {t.get_text()!r} is cut by the figure's edge"
        for t, box in zip(texts, boxes, strict=True)
        if box.x0 < edge.x0 - SLACK or box.y0 < edge.y0 - SLACK or box.x1 > edge.x1 + SLACK or box.y1 > edge.y1 + SLACK
    ]
    axes = [ax for ax in fig.axes if ax.get_visible()]
    out += [
        f"axes {i} ({a.get_title()!r}) covers axes {j} ({b.get_title()!r})"
        for (i, a), (j, b) in combinations(enumerate(axes), 2)
        if _cover(a.get_window_extent(renderer), b.get_window_extent(renderer))
    ]
    return out
