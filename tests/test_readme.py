"""Every Python snippet of the README runs as written, each on its own (in a fresh namespace and an empty
folder), and prints what its comments say it prints."""

from __future__ import annotations

import contextlib
import io
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def snippets() -> list[tuple[int, str]]:
    """Each ```python block of the README: its first line's number and its text."""
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    return [(text[: m.start()].count("\n") + 2, m.group(1)) for m in re.finditer(r"```python\n(.*?)```", text, re.S)]


def test_the_readme_has_its_snippets():
    assert len(snippets()) >= 7


@pytest.mark.parametrize(("line", "code"), snippets(), ids=[f"README.md:{n}" for n, _ in snippets()])
def test_a_readme_snippet_runs_as_written(line, code, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed):
        exec(compile(code, f"README.md:{line}", "exec"), {"__name__": "readme"})  # noqa: S102 - the README's own code
    # a line that prints says what it prints in its comment: its first line, up to any "..."
    shown = iter(printed.getvalue().splitlines())
    for source in code.splitlines():
        if source.lstrip().startswith("print(") and "#" in source:
            said = source.split("#", 1)[1].split("...")[0].strip()
            assert next(shown).startswith(said), source


def test_the_readme_gives_the_sign_of_a_process_load_as_the_code_applies_it():
    """The double-cut shears' cutting load has ``axis: 90 deg`` and the upper knife as its first tool: while it
    cuts, the force on the upper knife points up (+axis) and the one on the lower knife down, equal and
    opposite; the README says so."""
    import numpy as np

    import linkwork as lw

    f = lw.forces("double-cut-shears", steps=360)
    applied = f.loads.external
    cutting = applied.magnitude["cutting"][0] > 0
    assert cutting.sum() > 10
    mech = f.mechanism
    upper, lower = applied.forces[0], applied.forces[1]
    assert mech.link_names[upper.link] == "knife_upper" and mech.link_names[lower.link] == "knife_lower"
    assert np.all(upper.force[0, cutting, 1] > 0) and np.all(np.abs(upper.force[0, cutting, 0]) < 1e-9)
    np.testing.assert_array_equal(lower.force, -upper.force)
    readme = " ".join((ROOT / "README.md").read_text(encoding="utf-8").split())
    assert "the workpiece pushes the first tool toward +`axis`" in readme
    assert "`axis: 90 deg` for an upper knife that comes down" in readme


def test_the_readme_names_the_point_of_a_sliding_joint():
    readme = " ".join((ROOT / "README.md").read_text(encoding="utf-8").split())
    assert "`point:` is the slider's point that runs on that line" in readme
