"""The report as a PDF (``linkwork analyze --pdf``): a title page, then each section's paragraphs and tables set
on A4 pages, then the figures, a page each.

The sections' texts and tables are read back from the HTML the report writes of them (:mod:`linkwork.report.build`
makes it: ``<p>`` paragraphs and ``<table>`` tables of plain cells, a cell's lines split by ``<br>``), so that the
PDF says what the page says.
"""

from __future__ import annotations

import html
import re
import textwrap
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from matplotlib.figure import Figure

#: A4, inches; the margins, inches; the text's size, points; a table's largest font and the least it shrinks to.
PAGE, MARGIN, TEXT, TABLE, SMALLEST = (8.27, 11.69), 0.6, 9.0, 8.0, 5.0

#: The widest a table's cell of running text is set, in ems of its font (wider ones are wrapped): at the smallest
#: size a column of it and a column of names fit across the page.
CELL = 60.0

_PART = re.compile(r"<p>(.*?)</p>|<table>(.*?)</table>|<h3>(.*?)</h3>", re.S)
_ROW = re.compile(r"<tr>(.*?)</tr>", re.S)
_CELL = re.compile(r"<t[hd][^>]*>(.*?)</t[hd]>", re.S)


def parts(body: list[str]) -> list[tuple[str, Any]]:
    """The paragraphs (``("p", text)``) and tables (``("table", rows)``, the heading row first, each cell's lines
    joined by a newline) of a section's HTML, in order; anything else left out."""
    out: list[tuple[str, Any]] = []
    for m in _PART.finditer("".join(body)):
        if m.group(2) is not None:
            rows = [[_text(c) for c in _CELL.findall(r)] for r in _ROW.findall(m.group(2))]
            if rows:
                out.append(("table", rows))
        else:
            text = _text(m.group(1) if m.group(1) is not None else m.group(3))
            if text:
                out.append(("p", text))
    return out


def _text(fragment: str) -> str:
    """Plain text of an HTML fragment: ``<br>`` a newline, other tags dropped, entities read."""
    return html.unescape(re.sub(r"<[^>]+>", "", re.sub(r"<br\s*/?>", "\n", fragment))).strip()


class Pages:
    """A4 pages filled from the top: paragraphs wrapped, tables as wide as the page at most (their font shrunk
    to fit, down to :data:`SMALLEST` points), a table too long for a page continued on the next with its head."""

    def __init__(self) -> None:
        self.pages: list[Figure] = []
        self.y = 0.0

    def _new(self) -> None:
        from matplotlib.figure import Figure

        self.pages.append(Figure(figsize=PAGE))
        self.y = PAGE[1] - MARGIN

    def _room(self, height: float) -> None:
        if not self.pages or self.y - height < MARGIN:
            self._new()

    def heading(self, text: str) -> None:
        self._room(0.6)
        self.y -= 0.3
        self.pages[-1].text(MARGIN / PAGE[0], self.y / PAGE[1], text, fontsize=13, weight="bold", va="baseline")
        self.y -= 0.15

    def paragraph(self, text: str) -> None:
        lines = textwrap.wrap(text, width=int((PAGE[0] - 2 * MARGIN) * 72 / (0.66 * TEXT))) or [""]
        step = 1.35 * TEXT / 72
        for line in lines:
            self._room(step)
            self.y -= step
            self.pages[-1].text(MARGIN / PAGE[0], self.y / PAGE[1], line, fontsize=TEXT, va="baseline")
        self.y -= 0.5 * step

    def table(self, rows: list[list[str]]) -> None:
        # a cell of running text (a sentence of the sizing's inputs) in lines of at most CELL ems, not one line
        # wider than the page
        body = [[cell if _width(cell) <= CELL else _wrapped(cell, CELL, bold=False) for cell in r] for r in rows[1:]]
        columns = max(len(r) for r in rows)
        # each column as wide as its widest cell and its heading's longest word (bold: a tenth wider), in ems
        width = [
            max([_width(r[c]) for r in body if c < len(r)] + [1.1 * _width(w) for w in rows[0][c].split()]) + 1.0
            if c < len(rows[0])
            else 1.0
            for c in range(columns)
        ]
        size = max(min(TABLE, (PAGE[0] - 2 * MARGIN) * 72 / sum(width)), SMALLEST)
        head = [_wrapped(h, width[c] - 1.0) for c, h in enumerate(rows[0])]
        lines = [max(cell.count("\n") + 1 for cell in r) for r in (head, *body)]
        step = 1.3 * size / 72
        at = 0
        while at < len(body) or not body:
            self._room(step * (lines[0] + min(3, max(1, len(body) - at))) + 0.1)
            fits = at
            height = step * lines[0]
            while fits < len(body) and self.y - height - step * lines[fits + 1] >= MARGIN:
                height += step * lines[fits + 1]
                fits += 1
            self._draw([head, *body[at:fits]], [lines[0], *lines[at + 1 : fits + 1]], width, size, step)
            if not body or fits == at:
                break
            at = fits

    def _draw(self, rows: list[list[str]], lines: list[int], width: list[float], size: float, step: float) -> None:
        fig, x0 = self.pages[-1], MARGIN
        edges = [x0 + sum(width[:c]) * size / 72 for c in range(len(width) + 1)]
        top = self.y
        for r, row in enumerate(rows):
            for c, cell in enumerate(row):
                fig.text(
                    (edges[c] + 0.4 * size / 72) / PAGE[0],
                    (self.y - 0.95 * size / 72) / PAGE[1],
                    cell,
                    fontsize=size,
                    va="top",
                    linespacing=1.25,
                    weight="bold" if r == 0 else "normal",
                )
            self.y -= step * lines[r]
            fig.add_artist(_rule(edges[0], edges[-1], self.y, 0.8 if r == 0 else 0.3))
        fig.add_artist(_rule(edges[0], edges[-1], top, 0.8))
        self.y -= 0.15


def _wrapped(text: str, ems: float, bold: bool = True) -> str:
    """A heading's (``bold``: a tenth wider) or a cell's words in lines at most ``ems`` wide, a word longer than
    that on a line of its own."""
    lines: list[str] = []
    wider = 1.1 if bold else 1.0
    for word in text.split():
        if lines and wider * _width(f"{lines[-1]} {word}") <= ems:
            lines[-1] = f"{lines[-1]} {word}"
        else:
            lines.append(word)
    return "\n".join(lines)


def _rule(x0: float, x1: float, y: float, width: float) -> Any:
    """A horizontal line across a table at ``y`` (inches)."""
    from matplotlib.lines import Line2D

    return Line2D([x0 / PAGE[0], x1 / PAGE[0]], [y / PAGE[1]] * 2, lw=width, color="#444444")


def _width(cell: str) -> float:
    """Width of a cell's widest line in ems of the font (DejaVu Sans, :func:`~linkwork.scene.geometry.text_size`)."""
    from linkwork.scene.geometry import text_size

    return max(text_size(line, 1.0)[0] for line in cell.split("\n"))
