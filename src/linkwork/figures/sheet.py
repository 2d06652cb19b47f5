"""A figure laid out around a drawing of known extent: one axes without frame or ticks, in proportion
to the drawing, so that lengths of the drawing map to a known number of points and text can be set
to a size given in the drawing's own units (as the scene places it)."""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, cast

import numpy as np

from linkwork.lang import numbers, t
from linkwork.scene.geometry import text_runs
from linkwork.scene.style import Style
from linkwork.units import turn_deg

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

#: Widest and tallest drawing area, inches.
WIDTH, HEIGHT = 6.4, 7.0


@dataclass(frozen=True)
class Sheet:
    """A figure, its drawing axes and the points of the figure per unit of the drawing."""

    fig: Figure
    ax: Axes
    points_per_unit: float

    def font(self, em: float) -> float:
        """The font size (points) of text ``em`` units of the drawing high."""
        return em * self.points_per_unit

    def width(self, style: Style) -> float:
        """A line width (points) of ``style``."""
        return style.width


def mathtext(text: str) -> str:
    """A label's text for matplotlib: its subscripts (:func:`~linkwork.scene.geometry.text_runs`) as mathtext
    subscripts in the text's own upright font (``n_ba`` -> ``n$_\\mathregular{ba}$``), its dollar signs
    escaped."""
    out = []
    for run, sub in text_runs(text):
        run = run.replace("$", r"\$")
        out.append(f"$_{{\\mathregular{{{run}}}}}$" if sub else run)
    return "".join(out)


def sheet(
    extent: np.ndarray,
    top: float = 0.5,
    bottom: float = 0.2,
    width: float = WIDTH,
    height: float = HEIGHT,
    ax: Axes | None = None,
    least: float = 5.0,
) -> Sheet:
    """A figure for a drawing of ``extent`` ``[x0, y0, x1, y1]``, ``top`` and ``bottom`` inches kept for the
    title and legend; or, with ``ax``, that axes, its limits set to hold the drawing at equal scales.

    The drawing is at most ``width`` by ``height`` inches, the figure at least ``least`` inches wide (for
    its title); 3 % of the drawing's size is kept clear around it.
    """
    x0, y0, x1, y1 = (float(v) for v in extent)
    pad = 0.03 * max(x1 - x0, y1 - y0, 1e-12)
    x0, y0, x1, y1 = x0 - pad, y0 - pad, x1 + pad, y1 + pad
    if ax is not None:
        return _into(ax, (x0, y0, x1, y1))
    from matplotlib.figure import Figure

    scale = min(width / (x1 - x0), height / (y1 - y0))  # inches per unit
    w_in, h_in = (x1 - x0) * scale, (y1 - y0) * scale
    fig_w, fig_h = max(w_in + 0.3, least), h_in + top + bottom
    fig = Figure(figsize=(fig_w, fig_h))
    ax = fig.add_axes((((fig_w - w_in) / 2) / fig_w, bottom / fig_h, w_in / fig_w, h_in / fig_h))
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal", adjustable="box")
    ax.set_axis_off()
    return Sheet(fig, ax, scale * 72.0)


def _into(ax: Axes, box: tuple[float, float, float, float]) -> Sheet:
    """``ax`` (of a figure laid out elsewhere) holding ``box`` at equal scales."""
    x0, y0, x1, y1 = box
    fig = cast("Figure", ax.figure)  # a figure's own axes, not a subfigure's
    pos = ax.get_position()
    w_in, h_in = pos.width * fig.get_figwidth(), pos.height * fig.get_figheight()
    scale = min(w_in / (x1 - x0), h_in / (y1 - y0))
    cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
    ax.set_xlim(cx - w_in / scale / 2, cx + w_in / scale / 2)
    ax.set_ylim(cy - h_in / scale / 2, cy + h_in / scale / 2)
    ax.set_aspect("equal", adjustable="box")
    ax.set_axis_off()
    return Sheet(fig, ax, scale * 72.0)


#: A thin drawing (a plan, a lever nearly in one line) is made larger than its usual size, up to :data:`LARGEST`
#: inches, as far as its short side (across its longest direction) needs to print :data:`SHORT` inches wide.
LARGEST, SHORT = (7.5, 10.0), 10.0 / 25.4


def room(extent: np.ndarray, points: np.ndarray, usual: tuple[float, float]) -> tuple[float, float]:
    """The widest and tallest (inches) a drawing of ``extent`` ``[x0, y0, x1, y1]`` may take: ``usual``, more (up
    to :data:`LARGEST`) where the short side of its ``points`` ``(K, 2)`` (:func:`short_side`) would print under
    :data:`SHORT`."""
    span = np.asarray(extent[2:], dtype=float) - np.asarray(extent[:2], dtype=float)
    need = SHORT / max(short_side(points), 1e-12)  # inches per unit of the drawing
    base = min(usual[0] / span[0], usual[1] / span[1]) if np.all(span > 0) else 0.0
    if not need > base:
        return usual
    wide = float(np.clip(span[0] * need, usual[0], max(LARGEST[0], usual[0])))
    return wide, float(np.clip(span[1] * need, usual[1], max(LARGEST[1], usual[1])))


def short_side(points: np.ndarray) -> float:
    """The extent of ``points`` ``(K, 2)`` across their longest direction: the smaller side of the least rectangle
    along their principal axes that holds the finite ones."""
    pts = np.asarray(points, dtype=float).reshape(-1, 2)
    pts = pts[np.isfinite(pts).all(-1)]
    if len(pts) < 2:
        return 0.0
    centred = pts - pts.mean(0)
    along = centred @ np.linalg.svd(centred, full_matrices=False)[2].T
    return float(np.min(along.max(0) - along.min(0)))


def add_line(ax: Axes, x: Any, y: Any, **style: Any) -> Any:
    """A ``Line2D`` through ``x``, ``y`` (data units) of ``style``, added to ``ax`` as it is: a sheet's limits are
    set, so the axes' data limits are not updated (``ax.plot`` would, at a cost per line)."""
    from matplotlib.lines import Line2D

    return ax.add_artist(Line2D(x, y, **style))


def add_patch(ax: Axes, patch: Any) -> Any:
    """``patch`` added to ``ax`` without updating the axes' data limits (see :func:`add_line`)."""
    return ax.add_artist(patch)


def round_length(span: float) -> float:
    """A length from the 1-2-5 series near a fifth of ``span``, for a scale bar."""
    raw = span / 5
    exp = np.floor(np.log10(raw))
    for m in (1, 2, 5, 10):
        if m * 10**exp >= raw:
            return float(m * 10**exp)
    return float(10 ** (exp + 1))


def dashes(style: Style) -> Any:
    """The matplotlib line style of ``style``."""
    return (0, style.dash) if style.dash else "solid"


def text_width(text: str, size: float, dpi: float = 100.0) -> float:
    """Width (points) of one line of ``text`` set in matplotlib's font at ``size`` points, as Agg draws it at
    ``dpi`` (the glyphs' hinting makes text relatively wider at fewer pixels)."""
    from matplotlib.backends.backend_agg import RendererAgg
    from matplotlib.font_manager import FontProperties

    pixels = RendererAgg(1, 1, dpi).get_text_width_height_descent(text, FontProperties(size=size), False)[0]
    return float(pixels) * 72.0 / dpi


def decimal_commas(fig: Figure, lang: str) -> Figure:
    """``fig`` with the tick labels of every axes (and their offsets) written with the decimal sign of ``lang``: a
    comma in Russian (``0,5``; ``0{,}5`` in mathtext, which would space a bare comma), as they are in English."""
    if lang != "ru":
        return fig
    commas = _commas()
    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis):
            if not isinstance(axis.get_major_formatter(), commas):
                axis.set_major_formatter(commas(axis.get_major_formatter()))
            if not isinstance(axis.get_minor_formatter(), commas):
                axis.set_minor_formatter(commas(axis.get_minor_formatter()))
    return fig


def _comma(text: str) -> str:
    """``text`` with a decimal comma between digits (``{,}`` inside mathtext)."""
    import re

    return re.sub(r"(?<=\d)\.(?=\d)", "{,}" if "$" in text else ",", text)


@functools.cache
def _commas() -> type:
    """The tick formatter that writes what another writes with decimal commas (:func:`_comma`), made once
    matplotlib is imported."""
    from matplotlib.ticker import Formatter

    class Commas(Formatter):
        def __init__(self, inner: Any) -> None:
            self.inner = inner

        def __call__(self, x: float, pos: int | None = None) -> str:
            return _comma(self.inner(x, pos))

        def set_axis(self, axis: Any) -> None:
            super().set_axis(axis)
            self.inner.set_axis(axis)

        def set_locs(self, locs: Any) -> None:
            self.inner.set_locs(locs)

        def get_offset(self) -> str:
            return _comma(self.inner.get_offset())

        def format_ticks(self, values: Any) -> list[str]:
            self.set_locs(values)
            return [_comma(v) for v in self.inner.format_ticks(values)]

        def format_data_short(self, value: float) -> str:
            return _comma(self.inner.format_data_short(value))

    return Commas


def where(angle: float, position: int | str | None, lang: str) -> str:
    """The line under a drawing's title: ``position 9, crank at 178.8°`` (``crank at 178.8°`` without a
    ``position``), the crank's drive ``angle`` (rad) to the x axis, in ``lang``."""
    deg = numbers(f"{turn_deg(angle):.1f}", lang)
    return (
        t("drawing.crank", lang, angle=deg)
        if position is None
        else t("drawing.position", lang, position=position, angle=deg)
    )
