"""Checks of drawn figures, read back through the Agg renderer: what a reader would see as texts on top of
each other, a text under another axes or legend, axes on top of axes, a text cut off by the edge."""

from __future__ import annotations

from typing import Any

#: Pixels by which two boxes must overlap (in both directions) to count as covering each other.
TOLERANCE = 1.0


def drawn_texts(fig: Any) -> list[Any]:
    """The texts that drawing ``fig`` with Agg renders (non-empty, visible, inside their axes' view),
    in drawing order, multi-line texts and the figure's suptitle among them; the figure is drawn once.

    A text is the one whose ``draw`` is running when the renderer draws a string: matplotlib draws a text of
    several lines line by line without naming the text (``mtext`` is None), so it is not read from there."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.text import Text

    canvas = fig.canvas if isinstance(fig.canvas, FigureCanvasAgg) else FigureCanvasAgg(fig)
    renderer = canvas.get_renderer()
    seen: dict[int, Any] = {}
    drawing: list[Any] = []
    draw_text, draw = renderer.draw_text, Text.draw

    def record(gc: Any, x: float, y: float, s: str, prop: Any, angle: float, ismath: Any = False, mtext: Any = None):
        if drawing and s.strip():
            seen.setdefault(id(drawing[-1]), drawing[-1])
        return draw_text(gc, x, y, s, prop, angle, ismath=ismath, mtext=mtext)

    def drawn(self: Any, renderer: Any) -> Any:
        drawing.append(self)
        try:
            return draw(self, renderer)
        finally:
            drawing.pop()

    renderer.draw_text = record
    Text.draw = drawn  # type: ignore[method-assign]
    try:
        fig.draw(renderer)
    finally:
        Text.draw = draw  # type: ignore[method-assign]
        del renderer.draw_text
    return list(seen.values())


def _owners(fig: Any) -> dict[int, Any]:
    """The axes each text of an axes belongs to (its tick labels, axis labels, title, legend), by id."""
    from matplotlib.text import Text

    return {id(t): ax for ax in fig.axes for t in ax.findobj(Text)}


def _axes_name(ax: Any) -> str:
    return f"axes '{ax.get_title() or ax.get_ylabel() or ax.get_label()}'"


def _name(text: Any, owner: Any) -> str:
    return f"{text.get_text()!r} ({'figure' if owner is None else _axes_name(owner)})"


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
    owners = _owners(fig)
    owner = [owners.get(id(t)) for t in texts]
    names = [_name(t, o) for t, o in zip(texts, owner, strict=True)]
    boxes = [t.get_window_extent(renderer) for t in texts]
    axes = [ax for ax in fig.axes if ax.get_visible()]
    frames = [ax.get_window_extent(renderer) for ax in axes]
    legends = [leg for leg in [*fig.legends, *(ax.get_legend() for ax in axes)] if leg is not None]
    out = []
    for i, (a, box) in enumerate(zip(texts, boxes, strict=True)):
        out += [f"text {names[i]} covers text {names[j]}" for j in range(i + 1, len(texts)) if _covers(box, boxes[j])]
        for ax, frame in zip(axes, frames, strict=True):
            mine = owner[i] is not None and (owner[i] is ax or _twins(owner[i], ax))
            if not mine and _covers(box, frame):
                out.append(f"text {names[i]} is under {_axes_name(ax)}")
        for leg in legends:
            if not _in_legend(a, leg) and _covers(box, leg.get_window_extent(renderer)):
                out.append(f"text {names[i]} is under a legend")
        edge = fig.bbox
        if min(box.x0 - edge.x0, box.y0 - edge.y0, edge.x1 - box.x1, edge.y1 - box.y1) < -TOLERANCE:
            out.append(f"text {names[i]} reaches beyond the figure")
    for i, (a, fa) in enumerate(zip(axes, frames, strict=True)):
        for b, fb in zip(axes[i + 1 :], frames[i + 1 :], strict=True):
            if not _twins(a, b) and _covers(fa, fb):
                out.append(f"{_axes_name(a)} covers {_axes_name(b)}")
    return out
