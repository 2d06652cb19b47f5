"""The package's public names are typed for the user's type checker and IDE, though ``__init__.py`` loads them
lazily: ``__init__.pyi`` names each one where it lives, and ``dir(linkwork)`` lists only them."""

from __future__ import annotations

import ast
import importlib
import subprocess
import sys
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src"


def _stub_names() -> dict[str, tuple[str, str]]:
    """The names ``__init__.pyi`` imports: name -> (module, attribute)."""
    tree = ast.parse((SRC / "linkwork" / "__init__.pyi").read_text(encoding="utf-8"))
    out = {}
    for node in tree.body:
        if isinstance(node, ast.ImportFrom):
            for alias in node.names:
                out[alias.asname or alias.name] = (str(node.module), alias.name)
    return out


def test_the_stub_names_what_the_package_loads():
    import linkwork

    stub = _stub_names()
    assert set(stub) == set(linkwork.__all__) - {"__version__"}
    for name, (module, attr) in stub.items():
        assert getattr(importlib.import_module(module), attr) is getattr(linkwork, name), name


def test_dir_lists_the_public_names_only():
    import linkwork

    names = dir(linkwork)
    assert names == sorted(linkwork.__all__)
    assert not {"Any", "annotations", "_LAZY", "importlib"} & set(names)
    assert all(not n.startswith("_") or n == "__version__" for n in names)


@pytest.mark.slow  # mypy reads the whole package: half a minute or more
def test_mypy_sees_the_signatures_of_the_lazy_names(tmp_path):
    pytest.importorskip("mypy")
    probe = tmp_path / "probe.py"
    probe.write_text("import linkwork as lw\n\nreveal_type(lw.forces)\nreveal_type(lw.synthesize)\n", encoding="utf-8")
    command = [sys.executable, "-m", "mypy", "--no-incremental", "--follow-imports=silent"]
    command += ["--ignore-missing-imports", "--no-error-summary", str(probe)]
    done = subprocess.run(
        command, cwd=tmp_path, capture_output=True, text=True, env={"MYPYPATH": str(SRC), "PATH": ""}, check=False
    )
    revealed = [line for line in done.stdout.splitlines() if "Revealed type" in line]
    assert len(revealed) == 2, done.stdout + done.stderr
    forces, synthesize = revealed
    assert '"def (' in forces and "linkwork.kinetostatics.reaction_forces.Forces" in forces
    assert '"def (kind: str' in synthesize and "Synthesis" in synthesize
