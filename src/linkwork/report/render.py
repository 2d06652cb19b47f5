"""Figures to files: each figure laid out once and written as SVG (text kept as text) and PNG."""

from __future__ import annotations

from pathlib import Path
from typing import Any

#: Resolution of the PNG files (the report embeds them, shown at :data:`SCREEN`), dots per inch: fine enough to
#: print.
DPI = 200

#: The resolution at which the report shows the PNG files, dots per inch of the figure (a pixel of the page at
#: 100 dpi, as matplotlib lays a figure out).
SCREEN = 100


def shown_width(png: bytes) -> int:
    """The width (pixels of the page) at which the report shows a PNG written at :data:`DPI`: its width read
    from its header, at :data:`SCREEN` dots per inch."""
    return round(int.from_bytes(png[16:20], "big") * SCREEN / DPI)


def save(fig: Any, stem: Path) -> tuple[Path, Path]:
    """Write ``fig`` to ``STEM.png`` and ``STEM.svg``; returns the two paths.

    The figure's layout engine is run once, at the PNG's resolution, and then taken off, the axes kept where
    it put them: each file is then one drawing of the figure.  (Saved with its engine on, a figure is drawn
    once more, unseen, before each file, for the layout's sake.)  The SVG's texts are SVG text: selectable,
    editable, and quicker to write than glyph outlines."""
    import matplotlib

    png, svg = stem.with_suffix(".png"), stem.with_suffix(".svg")
    lay_out(fig)
    fig.savefig(png, dpi=DPI, pil_kwargs={"compress_level": 1})
    with matplotlib.rc_context({"svg.fonttype": "none", "svg.hashsalt": "linkwork"}):
        fig.savefig(svg, metadata={"Date": None})
    return png, svg


def lay_out(fig: Any) -> None:
    """Run ``fig``'s layout engine at :data:`DPI` and take it off, so that the axes stay where it put them."""
    engine = fig.get_layout_engine()
    if engine is None:
        return
    fig.set_dpi(DPI)
    engine.execute(fig)
    fig.set_layout_engine(None)
