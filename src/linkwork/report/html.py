"""The pieces of the report's page: a section, its paragraphs and tables as HTML, numbers as the tables show them."""

from __future__ import annotations

import html
import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np


@dataclass
class Section:
    """One section of the report: a title, paragraphs and tables (HTML), figures (names)."""

    key: str
    title: str
    body: list[str] = field(default_factory=list)
    figures: list[str] = field(default_factory=list)


def cell(x: Any) -> str:
    """A table's cell: a number to 4 significant digits, a tuple one line each (a point's x over its y)."""
    if isinstance(x, tuple):
        return "<br>".join(cell(v) for v in x)
    if isinstance(x, float | np.floating):
        return "-" if not math.isfinite(x) else f"{x:.4g}"
    return html.escape(str(x))


def fixed(values: Any, significant: int = 4) -> list[str]:
    """A column of numbers with one number of decimals: ``significant`` digits of its largest."""
    a = np.asarray(values, dtype=float)
    big = float(np.nanmax(np.abs(a))) if np.isfinite(a).any() else 0.0
    decimals = 0 if big == 0 else max(0, significant - 1 - math.floor(math.log10(big)))
    return ["-" if not math.isfinite(x) else f"{round(x, decimals) + 0.0:.{decimals}f}" for x in a]


def ratio(x: float) -> str:
    return "-" if not math.isfinite(x) else f"{x:.6g}"


def table(head: list[str], rows: list[list[Any]]) -> str:
    out = ["<table><thead><tr>" + "".join(f"<th>{html.escape(h)}</th>" for h in head) + "</tr></thead><tbody>"]
    out += ["<tr>" + "".join(f"<td>{cell(x)}</td>" for x in row) + "</tr>" for row in rows]
    return "".join(out) + "</tbody></table>"


def paragraph(text: str) -> str:
    return f"<p>{html.escape(text)}</p>"


def deg(x: float) -> str:
    return "-" if not math.isfinite(x) else f"{x:.1f}"
