"""Checks of drawn figures, read back through the Agg renderer: what a reader would see as texts on top of
each other, a text under another axes or legend, axes on top of axes, a text cut off by the edge."""

from __future__ import annotations

from typing import Any

#: Pixels by which two boxes must overlap (in both directions) to count as covering each other.
TOLERANCE = 1.0


def drawn_texts(fig: Any) -> list[Any]:
    """The texts that drawing ``fig`` with Agg renders (non-empty, visible, inside their axes' view),
    in drawing order; the figure is drawn once."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    canvas = fig.canvas if isinstance(fig.canvas, FigureCanvasAgg) else FigureCanvasAgg(fig)
    renderer = canvas.get_renderer()
    seen: dict[int, Any] = {}
    draw_text = renderer.draw_text

    def record(gc: Any, x: float, y: float, s: str, prop: Any, angle: float, ismath: Any = False, mtext: Any = None):
        if mtext is not None and s.strip():
            seen.setdefault(id(mtext), mtext)
        return draw_text(gc, x, y, s, prop, angle, ismath=ismath, mtext=mtext)

    renderer.draw_text = record
    try:
        fig.draw(renderer)
    finally:
        del renderer.draw_text
    return list(seen.values())


def _name(text: Any) -> str:
    where = (
        "figure" if text.axes is None else f"axes '{text.axes.get_label() or text.axes.get_title() or id(text.axes)}'"
    )
    return f"{text.get_text()!r} ({where})"


def _covers(a: Any, b: Any) -> bool:
    """Whether two display boxes overlap by more than :data:`TOLERANCE` in both directions."""
    return min(a.x1, b.x1) - max(a.x0, b.x0) > TOLERANCE and min(a.y1, b.y1) - max(a.y0, b.y0) > TOLERANCE


def _twins(a: Any, b: Any) -> bool:
    return a in b._twinned_axes.get_siblings(b)


def _in_legend(text: Any, legend: Any) -> bool:
    return text in legend.get_texts() or text is legend.get_title()


def overlaps(fig: Any) -> list[str]:
    """Every problem a reader would see in ``fig``, one line each (empty when there is none):

    * two texts whose boxes cover each other;
    * a text covered by an axes that is not its own (nor its twin), or by a legend it is not in;
    * two axes (not twins) that cover each other;
    * a text that reaches beyond the figure's edge.
    """
    texts = drawn_texts(fig)
    renderer = fig.canvas.get_renderer()
    boxes = [t.get_window_extent(renderer) for t in texts]
    axes = [ax for ax in fig.axes if ax.get_visible()]
    frames = [ax.get_window_extent(renderer) for ax in axes]
    legends = [leg for leg in [*fig.legends, *(ax.get_legend() for ax in axes)] if leg is not None]
    out = []
    for i, (a, box) in enumerate(zip(texts, boxes, strict=True)):
        out += [
            f"text {_name(a)} covers text {_name(b)}"
            for b, other in zip(texts[i + 1 :], boxes[i + 1 :], strict=True)
            if _covers(box, other)
        ]
        for ax, frame in zip(axes, frames, strict=True):
            mine = a.axes is not None and (a.axes is ax or _twins(a.axes, ax))
            if not mine and _covers(box, frame):
                out.append(f"text {_name(a)} is under axes '{ax.get_label() or ax.get_title()}'")
        for leg in legends:
            if not _in_legend(a, leg) and _covers(box, leg.get_window_extent(renderer)):
                out.append(f"text {_name(a)} is under a legend")
        edge = fig.bbox
        if (
            box.x0 < edge.x0 - TOLERANCE
            or box.y0 < edge.y0 - TOLERANCE
            or box.x1 > edge.x1 + TOLERANCE
            or (box.y1 > edge.y1 + TOLERANCE)
        ):
            out.append(f"text {_name(a)} reaches beyond the figure")
    for i, (a, fa) in enumerate(zip(axes, frames, strict=True)):
        for b, fb in zip(axes[i + 1 :], frames[i + 1 :], strict=True):
            if not _twins(a, b) and _covers(fa, fb):
                out.append(f"axes '{a.get_title()}' covers axes '{b.get_title()}'")
    return out
