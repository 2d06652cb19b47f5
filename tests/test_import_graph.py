"""The import graph of the package reads top-down: no cycles between packages or between modules, the
imports made inside functions included, and the core never imports the edge, nor reaches it through another module.

Built from the source with ``ast`` (every ``import`` and ``from ... import`` anywhere in a module, and every
module named as text to be imported: ``importlib.import_module("...")``, a table of ``(module, name)`` pairs).
Between packages every import counts, those under ``if TYPE_CHECKING:`` included: a type a module names is a
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


def _function_nodes(tree: ast.AST) -> set[int]:
    """The nodes inside a function's body (imports made when it is called)."""
    inside: set[int] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
            inside |= {id(n) for stmt in node.body for n in ast.walk(stmt)}
    return inside


def _named_module(node: ast.AST) -> ast.AST | None:
    """The string that names a module to import: the argument of ``importlib.import_module(...)``, or the first
    item of a ``(module, name)`` pair of a table that is looked up and imported when called."""
    if isinstance(node, ast.Call) and ast.unparse(node.func).endswith("import_module") and node.args:
        return node.args[0]
    if isinstance(node, ast.Tuple) and len(node.elts) == 2 and all(isinstance(e, ast.Constant) for e in node.elts):
        return node.elts[0]
    return None


def _targets(node: ast.AST, package: str, modules: dict[str, Path]) -> list[str]:
    """The linkwork names an import statement imports, or the module a string names to be imported: an import by
    a name written as text (``importlib.import_module("linkwork.io.x")``, a table of ``(module, name)`` pairs
    looked up when called) is an import all the same."""
    if isinstance(node, ast.Import):
        return [a.name for a in node.names]
    if isinstance(node, ast.ImportFrom):
        base = node.module or ""
        if node.level:
            up = package.rsplit(".", node.level - 1)[0] if node.level > 1 else package
            base = f"{up}.{base}" if base else up
        return [f"{base}.{a.name}" for a in node.names]
    named = _named_module(node)
    if isinstance(named, ast.Constant) and isinstance(named.value, str) and named.value in modules:
        return [named.value]
    return []


def _edges(
    modules: dict[str, Path], deferred: set[tuple[str, str]] | None = None, type_checking: bool = True
) -> dict[str, set[str]]:
    """Module -> the linkwork modules it imports (a name imported from a package that is a module of
    its own counts as that module), inside functions too; ``deferred`` collects the edges that only a function
    makes (when it is called, never when the module is imported); with ``type_checking`` False, those imported
    only under ``if TYPE_CHECKING:`` left out."""

    def known(name: str) -> str:
        while name not in modules and "." in name:
            name = name.rsplit(".", 1)[0]
        return name

    edges: dict[str, set[str]] = defaultdict(set)
    at_import: dict[str, set[str]] = defaultdict(set)
    for name, path in modules.items():
        tree = ast.parse(path.read_text(encoding="utf-8"))
        skip = set() if type_checking else _type_checking_nodes(tree)
        inside = _function_nodes(tree)
        package = name if path.name == "__init__.py" else name.rsplit(".", 1)[0]
        for node in ast.walk(tree):
            if id(node) in skip:
                continue
            targets = _targets(node, package, modules)
            if name == "linkwork" and not isinstance(node, ast.Import | ast.ImportFrom):
                continue  # the package's lazy names (``lw.forces``): found when a user asks, imported by nothing
            if id(node) not in inside:
                at_import[name] |= {known(t) for t in targets if t.startswith("linkwork")}
            for target in targets:
                if target.startswith("linkwork"):
                    found = known(target)
                    if found != name:
                        edges[name].add(found)
    if deferred is not None:
        deferred |= {(a, b) for a, targets in edges.items() for b in targets if b not in at_import[a]}
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


#: The imports made inside a method of a result that close a loop of modules: the result's tables (``to_xarray``,
#: ``to_pandas``) are built from the analyses of the result's own package, which solve the mechanism again (φ's
#: position 0).  A deferred call within one package, never an import when the module is imported.
DEFERRED = {("linkwork.motion.kinematic_analysis", "linkwork.motion.tables")}


@pytest.fixture(scope="module")
def deferred():
    out: set[tuple[str, str]] = set()
    _edges(_modules(), out, type_checking=False)
    return out


@pytest.fixture(scope="module")
def edges():
    """Every import, those under ``if TYPE_CHECKING:`` included."""
    return _edges(_modules())


def test_no_module_imports_another_that_imports_it_back(deferred):
    assert DEFERRED <= deferred, "each loop let through is an import made inside a function only"
    assert all(_package(a) == _package(b) for a, b in DEFERRED)
    running = _edges(_modules(), type_checking=False)
    kept = {a: {b for b in targets if (a, b) not in DEFERRED} for a, targets in running.items()}
    assert _cycles(kept) == []


def _reach(edges: dict[str, set[str]], start: str) -> set[str]:
    """Every module ``start`` imports, directly or through others, at import time or when a function runs; not
    through the package's ``__init__`` (``linkwork``), whose lazy names are the user's entry, not an import."""
    seen: set[str] = set()
    todo = [start]
    while todo:
        for b in edges.get(todo.pop(), ()):
            if b not in seen and b != "linkwork":
                seen.add(b)
                todo.append(b)
    return seen


def test_no_core_module_reaches_the_edge_through_any_module(edges):
    """Not even through a module outside the packages (``linkwork.display``) or an import made when a method
    is called (a result's ``to_xarray``): the core's tables are its own, and io writes them."""
    wrong = []
    for a in edges:
        if _package(a) in CORE:
            reached = sorted(_reach(edges, a))
            wrong += [f"{a} -> ... -> {b}" for b in reached if _package(b) in EDGE or b == "linkwork.api"]
    assert wrong == []


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
    wrong = [
        f"{a} -> {b}"
        for a, targets in edges.items()
        if _package(a) == "synthesis"
        for b in targets
        if _package(b) in above
    ]
    assert wrong == []
    assert any(_package(b) == "synthesis" for a, t in edges.items() if _package(a) == "cli" for b in t)


def test_structure_imports_neither_the_examples_nor_the_file_writer(edges):
    """Variant arithmetic is structure's; editing and writing a mechanism file is the file format's (``spec``)."""
    wrong = [
        f"{a} -> {b}"
        for a, targets in edges.items()
        if _package(a) == "structure"
        for b in targets
        if b in ("linkwork.examples", "linkwork.atomic")
    ]
    assert wrong == []


def test_the_checks_can_fail(tmp_path):
    """A graph with a cycle is found to have one; a module named as text and an import inside a function are
    imports, the second a deferred one; a module reached through another is reached."""
    assert _cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]
    (tmp_path / "core.py").write_text("def f():\n    from linkwork.hub import g\n")
    (tmp_path / "hub.py").write_text("TABLE = {'x': ('linkwork.edge', 'f')}\nRUN = ['-m', 'linkwork.core']\n")
    (tmp_path / "edge.py").write_text("")
    modules = {f"linkwork.{n}": tmp_path / f"{n}.py" for n in ("core", "hub", "edge")}
    out: set[tuple[str, str]] = set()
    edges = _edges(modules, out)
    assert edges == {"linkwork.core": {"linkwork.hub"}, "linkwork.hub": {"linkwork.edge"}}
    assert out == {("linkwork.core", "linkwork.hub")}
    assert _reach(edges, "linkwork.core") == {"linkwork.hub", "linkwork.edge"}


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


def test_the_analyses_do_not_import_the_file_format(edges):
    """Motion, kinetostatics, machine and impulse read the compiled records, never the file's objects: what turns
    the file into records is the compile's (``linkwork.stage_records``), and did-you-mean lives below both
    (``linkwork.did_you_mean``)."""
    analyses = {"motion", "kinetostatics", "machine", "impulse"}
    wrong = [
        f"{a} -> {b}"
        for a, targets in edges.items()
        if _package(a) in analyses
        for b in targets
        if _package(b) == "spec"
    ]
    assert wrong == []
