"""The manual's code runs as written: every page's blocks in order, in an empty folder of the page's own.

- ```python blocks run in one namespace per page; a ``print(...)`` whose line has a comment prints what the
  comment says (its first line, up to any "...").
- ```bash blocks: each line that is a ``linkwork`` command runs (through the application) and succeeds.
- ```console blocks: each ``$ linkwork ...`` line runs; the lines shown after it are what it prints (in order;
  a line ``...`` stands for lines left out), and a command whose output shows ``error:`` exits with code 2.
- a block after ``<!-- file: NAME -->`` is written to NAME first; one after ``<!-- not run: why -->`` is left
  out (the reason names the test that runs it).
The tutorial notebooks (``docs/notebooks/*.ipynb``) run too, every code cell in order, as the site's build
runs them to show their output (``docs/gen/notebooks.py``).
Blocks without a language are synopses (``[--steps N]``) and program output; they are not run.

The internal links of the pages and the anchors they name are checked here too, in the Markdown sources
(``mkdocs build --strict`` in ``.ci/run`` checks the built site).
"""

from __future__ import annotations

import contextlib
import io
import re
import shlex
import subprocess
from pathlib import Path

import pytest

from commandline import linkwork
from manual import DOCS, ROOT, marked_blocks, pages

RUN = ("python", "bash", "console")


def runnable() -> list[Path]:
    return [p for p in pages() if any(lang in RUN and not mark for lang, _, _, mark in _blocks(p))]


def _blocks(path: Path):
    return [b for b in marked_blocks(path.read_text(encoding="utf-8")) if not (b[3] and b[3][0] == "not run")]


def _name(path: Path) -> str:
    return str(path.relative_to(ROOT))


def _linkwork(line: str, cwd: Path) -> subprocess.CompletedProcess:
    """The command of a line, through the application in this process (:mod:`commandline`: the same
    application, without a second of interpreter start a command); what only a process of its own shows is
    tested elsewhere."""
    args = shlex.split(line.split("  #")[0])
    assert args[0] == "linkwork", line
    return linkwork(*args[1:], cwd=cwd)


def _console(code: str, where: str, cwd: Path) -> None:
    for chunk in re.split(r"^\$ ", code, flags=re.M)[1:]:
        command, *shown = chunk.rstrip("\n").split("\n")
        while command.endswith("\\") and shown:  # a command continued on the next line
            command = command[:-1] + shown.pop(0)
        proc = _linkwork(command, cwd)
        said = proc.stdout + proc.stderr
        assert proc.returncode == (2 if any("error:" in s for s in shown) else 0), f"{where}: {command}\n{said}"
        got = iter(line.rstrip() for line in said.splitlines())
        for expected in (s.rstrip() for s in shown if s.strip() != "..."):
            assert any(line == expected for line in got), f"{where}: {command}: no line {expected!r} in\n{said}"


def _python(code: str, where: str, namespace: dict) -> None:
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed):
        exec(compile(code, where, "exec"), namespace)  # noqa: S102 - the manual's own code
    shown = iter(printed.getvalue().splitlines())
    for source in code.splitlines():
        if source.lstrip().startswith("print(") and "#" in source:
            said = source.split("#", 1)[1].split("...")[0].strip()
            assert next(shown).startswith(said), f"{where}: {source}"


@pytest.mark.parametrize("path", runnable(), ids=_name)
def test_the_code_of_a_page_runs_as_written(path, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    namespace: dict = {"__name__": "manual"}
    for lang, code, line, mark in _blocks(path):
        where = f"{_name(path)}:{line}"
        if mark and mark[0] == "file":
            (tmp_path / mark[1]).write_text(code, encoding="utf-8")
        elif lang == "python":
            _python(code, where, namespace)
        elif lang == "bash":
            for command in (c for c in code.splitlines() if c.startswith("linkwork ")):
                proc = _linkwork(command, tmp_path)
                assert proc.returncode == 0, f"{where}: {command}\n{proc.stderr}"
        elif lang == "console":
            _console(code, where, tmp_path)


def test_the_manual_has_its_code():
    """The pages that teach by example keep their examples (a page emptied by an edit fails here)."""
    names = {_name(p) for p in runnable()}
    assert {"README.md", "docs/getting-started/first-mechanism.md", "docs/how-to/kinematics.md"} <= names


def _anchors(text: str) -> set[str]:
    """The anchors of a page's headings, as the site's table of contents makes them."""
    from markdown.extensions.toc import slugify

    text = re.sub(r"^```.*?^```", "", text, flags=re.S | re.M)
    return {slugify(re.sub(r"[`*]", "", h), "-") for h in re.findall(r"^#{1,6} (.+?)\s*$", text, flags=re.M)}


def test_every_internal_link_of_the_manual_finds_its_page_and_anchor():
    """Each relative link of a page (and of the README, whose links go into docs/) names a file that exists and,
    after ``#``, an anchor of that page's headings.  Generated pages (reference/cli.md ...) are left to the
    strict build."""
    generated = {"reference/cli.md", "reference/schema.md", "reference/api"}
    broken = []
    for path in pages():
        text = re.sub(r"^```.*?^```", "", path.read_text(encoding="utf-8"), flags=re.S | re.M)
        for target in re.findall(r"\]\(([^)\s]+)\)", text):
            if re.match(r"[a-z]+:", target):
                continue
            file, _, anchor = target.partition("#")
            dest = (path.parent / file).resolve() if file else path
            rel = dest.relative_to(DOCS).as_posix() if dest.is_relative_to(DOCS) else None
            if rel in generated or (rel or "").startswith(("gallery/", "reference/api/", "notebooks/", "pictures/")):
                continue
            if not dest.exists():
                broken.append(f"{_name(path)}: {target} (no such file)")
            elif anchor and dest.suffix == ".md" and anchor not in _anchors(dest.read_text(encoding="utf-8")):
                broken.append(f"{_name(path)}: {target} (no such anchor)")
    assert not broken, "\n".join(broken)


def test_the_manual_gives_the_sign_of_a_process_load_as_the_code_applies_it():
    """The double-cut shears' cutting load has ``axis: 90 deg`` and the upper knife as its first tool: while it
    cuts, the force on the upper knife points up (+axis) and the one on the lower knife down, equal and
    opposite; the manual says so."""
    import numpy as np

    import linkwork as lw
    from manual import page

    f = lw.forces("double-cut-shears", steps=360)
    applied = f.loads.external
    cutting = applied.magnitude["cutting"][0] > 0
    assert cutting.sum() > 10
    mech = f.mechanism
    upper, lower = applied.forces[0], applied.forces[1]
    assert mech.link_names[upper.link] == "knife_upper" and mech.link_names[lower.link] == "knife_lower"
    assert np.all(upper.force[0, cutting, 1] > 0) and np.all(np.abs(upper.force[0, cutting, 0]) < 1e-9)
    np.testing.assert_array_equal(lower.force, -upper.force)
    said = " ".join(page("reference/file-format.md").split())
    assert "the workpiece pushes the first tool toward +`axis`" in said
    assert "`axis: 90 deg` for an upper knife that comes down" in said


def test_the_manual_names_the_point_of_a_sliding_joint():
    from manual import page

    assert "`point:` is the slider's point that runs on that line" in " ".join(page("reference/file-format.md").split())


def test_every_public_name_has_a_documented_object_for_its_api_page():
    """docs/gen/reference.py gives each name of ``linkwork.__all__`` a page rendered from the docstring of the
    object it names (the stage's own function where ``lw.NAME`` wraps it): each has one, with a summary."""
    import inspect

    import linkwork

    for name in linkwork.__all__:
        if name != "__version__":
            target = inspect.unwrap(getattr(linkwork, name))
            assert (inspect.getdoc(target) or "").strip(), name


def _notebook_runner():
    """``docs/gen/notebooks.py``, which the site's build runs each notebook with."""
    import importlib.util
    import sys

    if "manual_notebooks" not in sys.modules:
        spec = importlib.util.spec_from_file_location("manual_notebooks", DOCS / "gen" / "notebooks.py")
        assert spec is not None and spec.loader is not None
        sys.modules["manual_notebooks"] = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(sys.modules["manual_notebooks"])
    return sys.modules["manual_notebooks"]


NOTEBOOKS = sorted((DOCS / "notebooks").glob("*.ipynb"))


@pytest.mark.parametrize("path", NOTEBOOKS, ids=_name)
def test_every_cell_of_a_notebook_runs_in_order(path, monkeypatch):
    """Each code cell runs after the ones before it, in one namespace; a cell that raises fails here.  The
    first mechanism notebook ends with its results as tables: the rocker's speed in the Dataset is the
    kinematics' own, and the driving torque's table has its unit."""
    import numpy as np

    monkeypatch.setenv("MPLBACKEND", "agg")
    names: dict = {}
    ran = _notebook_runner().run(path, names)
    code = [c for c in ran if c.kind == "code"]
    assert code and all(c.kind in ("markdown", "code") for c in ran)
    if path.stem == "first-mechanism":
        printed = "".join(c.printed for c in code)
        assert "I(0,1) -> II(2,3)" in printed and "W = 1" in printed
        assert any(c.html.lstrip().startswith(("<?xml", "<svg")) for c in code)  # the figure
        assert any("Kinematics of four-bar" in c.html for c in code)  # a result shows itself
        assert "N m" in code[-1].printed and "driving_torque" in code[-1].html
        rocker = names["ds"]["omega"].sel(link="rocker").isel(variant=0).values
        np.testing.assert_array_equal(rocker, names["kin"].omega("rocker"))
        assert names["ds"]["omega"].attrs["units"] == "rad/s"


def test_a_cell_that_raises_fails_the_notebook(tmp_path):
    import json

    nb = {"cells": [{"cell_type": "code", "source": ["x = 1\n"]}, {"cell_type": "code", "source": ["1 / (x - 1)"]}]}
    path = tmp_path / "broken.ipynb"
    path.write_text(json.dumps(nb), encoding="utf-8")
    with pytest.raises(ZeroDivisionError):
        _notebook_runner().run(path)


QUOTED = "<!-- quoted from the Russian report"


def _report_rows(html_text: str) -> tuple[list[list[str]], str]:
    """The rows of a report's tables (each a list of its cells' texts) and its text, spaces collapsed."""
    import html

    def text(fragment: str) -> str:
        return " ".join(html.unescape(re.sub(r"<[^>]+>", " ", fragment)).split())

    rows = [
        [text(c) for c in re.findall(r"<t[dh][^>]*>(.*?)</t[dh]>", row, flags=re.S)]
        for row in re.findall(r"<tr[^>]*>(.*?)</tr>", html_text, flags=re.S)
    ]
    return rows, text(re.sub(r"<(script|style|svg|pre)[^>]*>.*?</\1>", " ", html_text, flags=re.S))


def _has_run(row: list[str], rows: list[list[str]]) -> bool:
    n = len(row)
    return any(r[i : i + n] == row for r in rows for i in range(len(r) - n + 1))


@pytest.mark.slow
@pytest.mark.parametrize("name", ["shears-slider-crank", "double-cut-shears", "percussion-rocker"])
def test_the_russian_tutorials_quote_the_russian_report_as_it_is(name, tmp_path, sketched_figures):
    """Each table row and quotation that a Russian tutorial marks as quoted from ``linkwork analyze NAME
    --lang ru`` is in that report: a row as consecutive cells of one of its tables, a quotation in its text (the
    page read, its figures not drawn)."""
    from manual import page

    proc = linkwork("analyze", name, "--out", str(tmp_path / "r"), "--lang", "ru", "--no-animation", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    rows, said = _report_rows((tmp_path / "r" / "report.html").read_text(encoding="utf-8"))
    chunks = page(f"ru/{name}.md").split(QUOTED)[1:]
    assert chunks, name
    missing = []
    for chunk in chunks:
        lines = chunk.split("-->", 1)[1].strip("\n").split("\n\n", 1)[0].splitlines()
        for line in lines:
            if line.startswith("> "):
                if " ".join(line[2:].split()) not in said:
                    missing.append(line)
            elif line.startswith("|") and not line.startswith("|---"):
                if not _has_run([c.strip() for c in line.strip().strip("|").split("|")], rows):
                    missing.append(line)
    assert not missing, "\n".join(missing)
