"""The tutorial notebooks (``docs/notebooks/*.ipynb``) as pages of the manual, run when the site is built:
each code cell run in order in one namespace, in an empty folder, its printed text and the value of its last
line shown under it as Jupyter would show them (a result's HTML table, a figure as SVG, else its repr).

:func:`run` is also what ``tests/test_manual.py`` runs each notebook with: a cell that raises fails the test
and the build alike.  No Jupyter is needed (the notebook is read as the JSON it is).
"""

from __future__ import annotations

import ast
import contextlib
import io
import json
import os
import tempfile
from dataclasses import dataclass
from pathlib import Path

NOTEBOOKS = Path(__file__).resolve().parents[1] / "notebooks"


@dataclass
class Cell:
    """A cell of a notebook and, for a code cell, what running it showed."""

    kind: str  # "markdown" or "code"
    source: str
    printed: str = ""
    html: str = ""  # the last line's value: its _repr_html_, or a figure's SVG
    text: str = ""  # the last line's value as text, where it has no HTML


def cells(path: Path) -> list[Cell]:
    """The cells of a notebook file, in order."""
    nb = json.loads(path.read_text(encoding="utf-8"))
    return [Cell(c["cell_type"], "".join(c["source"])) for c in nb["cells"] if c["cell_type"] in ("markdown", "code")]


def _show(value: object, cell: Cell) -> None:
    if value is None:
        return
    if hasattr(value, "savefig"):  # a matplotlib figure
        buf = io.StringIO()
        value.savefig(buf, format="svg")
        cell.html = buf.getvalue()
    elif hasattr(value, "_repr_html_"):
        cell.html = value._repr_html_()
    else:
        cell.text = repr(value)


def run(path: Path, namespace: dict | None = None) -> list[Cell]:
    """Run the code cells of the notebook ``path`` in order, in one namespace (``namespace``, which keeps the
    names the cells define; default a new one), in a new empty folder; an error of a cell is raised with the
    cell's number in its traceback's file name."""
    os.environ.setdefault("MPLBACKEND", "agg")
    out = cells(path)
    namespace = {} if namespace is None else namespace
    namespace.setdefault("__name__", "__main__")
    here = Path.cwd()
    with tempfile.TemporaryDirectory() as folder:
        os.chdir(folder)
        try:
            for number, cell in enumerate(out):
                if cell.kind == "code":
                    _run_cell(cell, f"{path.name}[{number}]", namespace)
        finally:
            os.chdir(here)
    return out


def _run_cell(cell: Cell, where: str, namespace: dict) -> None:
    tree = ast.parse(cell.source, where)
    last = tree.body.pop() if tree.body and isinstance(tree.body[-1], ast.Expr) else None
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed):
        exec(compile(tree, where, "exec"), namespace)  # noqa: S102 - the manual's own notebook
        value = eval(compile(ast.Expression(last.value), where, "eval"), namespace) if last else None  # noqa: S307
    cell.printed = printed.getvalue()
    _show(value, cell)


def page(path: Path, ran: list[Cell]) -> tuple[str, dict[str, str]]:
    """The Markdown page of a notebook that has run, and its figures by file name."""
    lines, figures = [], {}
    for number, cell in enumerate(ran):
        if cell.kind == "markdown":
            lines += [cell.source, ""]
            if number == 0:
                lines += [f"[Download the notebook]({path.name}) (it runs in Jupyter as it is).", ""]
            continue
        lines += ["```python", cell.source, "```", ""]
        if cell.printed:
            lines += ["```", cell.printed.rstrip("\n"), "```", ""]
        if cell.html.lstrip().startswith(("<?xml", "<svg")):
            name = f"{path.stem}-{number}.svg"
            figures[name] = cell.html
            lines += [f"![Output of the cell]({name})", ""]
        elif cell.html:
            lines += ['<div class="notebook-output" markdown="0">', cell.html, "</div>", ""]
        elif cell.text:
            lines += ["```", cell.text, "```", ""]
    return "\n".join(lines), figures


def main() -> None:
    import mkdocs_gen_files

    for path in sorted(NOTEBOOKS.glob("*.ipynb")):
        text, figures = page(path, run(path))
        with mkdocs_gen_files.open(f"notebooks/{path.stem}.md", "w") as f:
            f.write(text)
        for name, svg in figures.items():
            with mkdocs_gen_files.open(f"notebooks/{name}", "w") as f:
                f.write(svg)


if __name__ in ("__main__", "<run_path>"):
    main()
