"""Figures to files: each figure laid out once and written as SVG (text kept as text) and PNG."""

from __future__ import annotations

from pathlib import Path
from typing import Any

#: Resolution of the PNG files (the report embeds them), dots per inch.
DPI = 100


def save(fig: Any, stem: Path) -> tuple[Path, Path]:
    """Write ``fig`` to ``STEM.png`` and ``STEM.svg``; returns the two paths.

    The PNG is drawn first, with the figure's layout engine; the layout it found is then kept for the
    SVG and any later output (not computed again).  The SVG's texts are SVG text: selectable, editable,
    and quicker to write than glyph outlines."""
    import matplotlib

    png, svg = stem.with_suffix(".png"), stem.with_suffix(".svg")
    fig.savefig(png, dpi=DPI, pil_kwargs={"compress_level": 1})
    fig.set_layout_engine("none")  # keeps the axes where the layout put them
    with matplotlib.rc_context({"svg.fonttype": "none", "svg.hashsalt": "linkwork"}):
        fig.savefig(svg, metadata={"Date": None})
    return png, svg
