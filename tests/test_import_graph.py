"""The import graph of the package reads top-down: no cycles between packages or between modules, the
imports made inside functions included, and the core never imports the edge.

Built from the source with ``ast`` (every ``import`` and ``from ... import`` anywhere in a module).  Between
packages every import counts, those under ``if TYPE_CHECKING:`` included: a type a module names is a
dependency on its package even where the import never runs (the compiled model names no stage above it).
Between the modules of one package the imports under ``if TYPE_CHECKING:`` are left out, as they never run.
"""

from __future__ import annotations

import ast
from collections import defaultdict
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src" / "linkwork"

#: The packages of the core, bottom to top, and the edge around them.
CORE = ["spec", "structure", "motion", "kinetostatics", "machine", "impulse"]
EDGE = ["design", "synthesis", "scene", "io", "figures", "report", "web", "cli"]


def _modules() -> dict[str, Path]:
    out = {}
    for path in SRC.rglob("*.py"):
        parts = path.relative_to(SRC.parent).with_suffix("").parts
        name = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
        out[name] = path
    return out


def _type_checking_nodes(tree: ast.AST) -> set[int]:
    skip: set[int] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test):
            skip |= {id(n) for stmt in node.body for n in ast.walk(stmt)}
    return skip


def _edges(modules: dict[str, Path], type_checking: bool = True) -> dict[str, set[str]]:
    """Module -> the linkwork modules it imports (a name imported from a package that is a module of
    its own counts as that module); with ``type_checking`` False, those imported only under
    ``if TYPE_CHECKING:`` left out."""

    def known(name: str) -> str:
        while name not in modules and "." in name:
            name = name.rsplit(".", 1)[0]
        return name

    edges: dict[str, set[str]] = defaultdict(set)
    for name, path in modules.items():
        tree = ast.parse(path.read_text(encoding="utf-8"))
        skip = set() if type_checking else _type_checking_nodes(tree)
        package = name if path.name == "__init__.py" else name.rsplit(".", 1)[0]
        for node in ast.walk(tree):
            if id(node) in skip:
                continue
            if isinstance(node, ast.Import):
                targets = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                base = node.module or ""
                if node.level:
                    up = package.rsplit(".", node.level - 1)[0] if node.level > 1 else package
                    base = f"{up}.{base}" if base else up
                targets = [f"{base}.{a.name}" for a in node.names]
            else:
                continue
            for target in targets:
                if target.startswith("linkwork"):
                    found = known(target)
                    if found != name:
                        edges[name].add(found)
    return edges


def _cycles(edges: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components of more than one node (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    out: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in edges.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in list(edges):
        if v not in index:
            visit(v)
    return out


def _package(module: str) -> str:
    parts = module.split(".")
    return parts[1] if len(parts) > 2 or (len(parts) == 2 and (SRC / parts[1]).is_dir()) else module


@pytest.fixture(scope="module")
def edges():
    """Every import, those under ``if TYPE_CHECKING:`` included."""
    return _edges(_modules())


def test_no_module_imports_another_that_imports_it_back():
    assert _cycles(_edges(_modules(), type_checking=False)) == []


def test_no_package_imports_another_that_imports_it_back(edges):
    packages: dict[str, set[str]] = defaultdict(set)
    for a, targets in edges.items():
        for b in targets:
            if _package(a) != _package(b) and a != "linkwork":
                packages[_package(a)].add(_package(b))
    assert _cycles(packages) == []


def test_the_core_imports_nothing_of_the_edge_and_nothing_above_itself(edges):
    wrong = []
    for a, targets in edges.items():
        pa = _package(a)
        for b in targets:
            pb = _package(b)
            if pa in CORE and (pb in EDGE or pb == "linkwork.api"):
                wrong.append(f"{a} -> {b}")
            elif pa in CORE and pb in CORE and CORE.index(pb) > CORE.index(pa):
                wrong.append(f"{a} -> {b}")
    assert wrong == []


def test_synthesis_sits_above_the_analyses_and_below_the_drawings_reports_and_command(edges):
    """It verifies what it writes with the analyses (and may refine through ``design``); nothing it imports
    draws, reports or parses a command line."""
    above = {"scene", "io", "figures", "report", "web", "cli"}
    wrong = [f"{a} -> {b}" for a, targets in edges.items() if _package(a) == "synthesis"
             for b in targets if _package(b) in above]  # fmt: skip
    assert wrong == []
    assert any(_package(b) == "synthesis" for a, t in edges.items() if _package(a) == "cli" for b in t)


def test_the_checks_can_fail():
    """A graph with a cycle is found to have one."""
    assert _cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]


def test_an_import_for_type_checking_is_an_edge(tmp_path):
    """An import under ``if TYPE_CHECKING:`` counts between packages (the model's names of the stages above it
    were such imports), and is left out where asked."""
    (tmp_path / "low.py").write_text("from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    import linkwork.high\n")
    modules = {"linkwork.low": tmp_path / "low.py", "linkwork.high": tmp_path / "low.py"}
    assert _edges(modules)["linkwork.low"] == {"linkwork.high"}
    assert "linkwork.low" not in _edges(modules, type_checking=False)


def test_no_module_is_named_for_no_one_thing():
    """A module is named for what it holds: none is called ``fast``, ``utils`` or ``helpers`` (the numba twins
    of the kernels are ``kernels_numba`` and ``reactions_numba``)."""
    vague = {"fast", "utils", "helpers"}
    assert [name for name in _modules() if name.rsplit(".", 1)[-1] in vague] == []
