"""The bars of the package's shape, read from the source with ``ast``: no module over 700 lines, no function over
100 lines, and few functions with more than 8 parameters (arguments that travel together go as one record).

The compiled twins (``*_numba.py``, and their NumPy twins of the same name beside them) are left out of the last
count: a numba kernel takes its arrays one by one.
"""

from __future__ import annotations

import ast
import functools
from pathlib import Path

SRC = Path(__file__).resolve().parents[1] / "src" / "linkwork"

#: The most lines of a module and of a function (its signature and docstring included).
MODULE_LINES = 700
FUNCTION_LINES = 100
#: The most parameters a function takes before its arguments go as a record, and how many functions may still
#: take more (the public entry points whose keywords users call, and the commands whose options typer reads; the
#: kinds of synthesis take their requirements as a record); the bar is 15.
PARAMETERS = 8
MANY_PARAMETERS = 13


@functools.cache
def _trees() -> dict[Path, ast.Module]:
    return {path: ast.parse(path.read_text(encoding="utf-8")) for path in sorted(SRC.rglob("*.py"))}


def _functions() -> list[tuple[Path, ast.FunctionDef | ast.AsyncFunctionDef]]:
    return [
        (path, node)
        for path, tree in _trees().items()
        for node in ast.walk(tree)
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef)
    ]


def parameters(node: ast.FunctionDef | ast.AsyncFunctionDef) -> int:
    """A function's parameters, ``*args`` and ``**kwargs`` one each, a method's ``self`` or ``cls`` not counted."""
    a = node.args
    count = len(a.posonlyargs) + len(a.args) + len(a.kwonlyargs) + (a.vararg is not None) + (a.kwarg is not None)
    first = (a.posonlyargs + a.args)[:1]
    return count - (1 if first and first[0].arg in ("self", "cls") else 0)


def _where(path: Path, node: ast.AST) -> str:
    return f"{path.relative_to(SRC)}:{getattr(node, 'lineno', 0)}"


def test_no_module_is_over_700_lines():
    long = {_where(p, t): len(p.read_text(encoding="utf-8").splitlines()) for p, t in _trees().items()}
    assert {k: n for k, n in long.items() if n > MODULE_LINES} == {}


def test_no_function_is_over_100_lines():
    long = {f"{_where(p, f)} {f.name}": (f.end_lineno or f.lineno) - f.lineno + 1 for p, f in _functions()}
    assert {k: n for k, n in long.items() if n > FUNCTION_LINES} == {}


def _twins() -> set[tuple[Path, str]]:
    """The numba kernels and their NumPy twins: each function of a ``NAME_numba.py`` module, and the function of the
    same name in ``NAME.py`` beside it (the two take the same arrays, one by one)."""
    compiled = {(p.with_name(p.name.removesuffix("_numba.py") + ".py"), f.name) for p, f in _functions()}
    return {(p, f.name) for p, f in _functions() if p.name.endswith("_numba.py") or (p, f.name) in compiled}


def test_few_functions_take_more_than_8_parameters():
    twins = _twins()
    many = sorted(
        f"{_where(p, f)} {f.name} ({parameters(f)})"
        for p, f in _functions()
        if (p, f.name) not in twins and parameters(f) > PARAMETERS
    )
    assert len(many) <= MANY_PARAMETERS, "\n".join(many)


def test_the_counts_count_what_they_say():
    """The counting itself, on a function of each shape: ``self`` left out, ``*args`` and ``**kwargs`` counted."""
    tree = ast.parse(
        "class A:\n    def m(self, a, b, /, c, *d, e, **f): pass\n"
        "def g(a, b, c, d, e, f, g, h, i):\n    '''doc'''\n    return 1\n"
    )
    found = {n.name: n for n in ast.walk(tree) if isinstance(n, ast.FunctionDef)}
    assert parameters(found["m"]) == 6
    assert parameters(found["g"]) == 9
    assert found["g"].end_lineno - found["g"].lineno + 1 == 3
