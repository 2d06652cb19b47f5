"""The pages of the manual (``docs/``) and the README, for the tests that run or quote them."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"


def pages() -> list[Path]:
    """The README and every Markdown page of the manual, the README first."""
    return [ROOT / "README.md", *sorted(DOCS.rglob("*.md"))]


def page(name: str) -> str:
    """The text of one page, by its path under ``docs/`` (``"how-to/viewer.md"``) or ``"README.md"``."""
    return (ROOT / name if name == "README.md" else DOCS / name).read_text(encoding="utf-8")


def blocks(text: str) -> list[tuple[str, str, int]]:
    """The fenced code blocks of a page: ``(language, code, number of the block's first line of code)``."""
    return [
        (m.group(1), m.group(2), text[: m.start()].count("\n") + 2)
        for m in re.finditer(r"^```([\w-]*)[^\n]*\n(.*?)^```[ \t]*$", text, re.S | re.M)
    ]


#: An HTML comment right before a block: ``<!-- not run: why -->`` leaves it out of the tests (the reason names
#: the test that runs it instead), ``<!-- file: NAME -->`` writes it to NAME in the page's folder before the
#: blocks after it run.
MARK = re.compile(r"<!--\s*(not run|file):\s*(.*?)\s*-->\s*$")


def marked_blocks(text: str) -> list[tuple[str, str, int, tuple[str, str] | None]]:
    """:func:`blocks` with the mark of each (``("not run", why)``, ``("file", name)`` or None)."""
    lines = text.splitlines()
    out = []
    for lang, code, line in blocks(text):
        before = next((s for s in reversed(lines[: line - 2]) if s.strip()), "")
        m = MARK.match(before.strip())
        out.append((lang, code, line, (m.group(1), m.group(2)) if m else None))
    return out
