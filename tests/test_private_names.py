"""No private name crosses a package: what one package needs of another is public, with a name and a docstring.

Read from the source with ``ast``: every ``from linkwork.x import _y`` (inside functions too) and every attribute
``obj._y`` where ``_y`` is a private name that only other packages define (a method, a function, a class
attribute).  A package here is a subpackage of linkwork (``motion``, ``cli``...) or a top-level module
(``linkwork.units``).
"""

from __future__ import annotations

import ast
import functools
import re
from collections import defaultdict
from pathlib import Path

SRC = Path(__file__).resolve().parents[1] / "src" / "linkwork"


def _private(name: str) -> bool:
    return name.startswith("_") and not name.startswith("__")


def _package(path: Path) -> str:
    """The package a source file belongs to: its subpackage of linkwork, or its own name at the top."""
    parts = path.relative_to(SRC).with_suffix("").parts
    return parts[0]


@functools.cache
@functools.cache
def _trees() -> dict[Path, ast.AST]:
    return {path: ast.parse(path.read_text(encoding="utf-8")) for path in sorted(SRC.rglob("*.py"))}


def private_imports(trees: dict[Path, ast.AST]) -> list[str]:
    """``from linkwork.x import _y`` where ``x`` is another package than the importing module's."""
    out = []
    for path, tree in trees.items():
        own = _package(path)
        for node in ast.walk(tree):
            if not isinstance(node, ast.ImportFrom) or node.level or not (node.module or "").startswith("linkwork"):
                continue
            parts = (node.module or "").split(".")
            source = parts[1] if len(parts) > 1 else None
            for alias in node.names:
                if _private(alias.name) and source != own:
                    out.append(f"{path.relative_to(SRC)}:{node.lineno}: from {node.module} import {alias.name}")
    return out


def _defined(tree: ast.AST) -> set[str]:
    """Private names a module defines as functions, methods, classes or (class or self) attributes."""
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef) and _private(node.name):
            out.add(node.name)
        elif isinstance(node, ast.Attribute) and isinstance(node.ctx, ast.Store) and _private(node.attr):
            out.add(node.attr)
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name) and _private(node.target.id):
            out.add(node.target.id)
    return out


def private_attributes(trees: dict[Path, ast.AST]) -> list[str]:
    """``obj._y`` (``obj`` not ``self`` or ``cls``) where ``_y`` is defined in other packages only."""
    defined: dict[str, set[str]] = defaultdict(set)
    for path, tree in trees.items():
        for name in _defined(tree):
            defined[name].add(_package(path))
    out = []
    for path, tree in trees.items():
        own = _package(path)
        for node in ast.walk(tree):
            if not isinstance(node, ast.Attribute) or not _private(node.attr) or node.attr not in defined:
                continue
            if isinstance(node.value, ast.Name) and node.value.id in ("self", "cls"):
                continue
            if own not in defined[node.attr]:
                where = ", ".join(sorted(defined[node.attr]))
                out.append(f"{path.relative_to(SRC)}:{node.lineno}: {ast.unparse(node)} (defined in {where})")
    return out


def test_no_private_name_is_imported_from_another_package():
    assert private_imports(_trees()) == []


def test_no_private_attribute_of_another_package_is_used():
    assert private_attributes(_trees()) == []


def test_the_checks_can_fail():
    """A private import across packages and a private method called from another package are found; the same
    within one package are not."""
    trees = {
        SRC / "io" / "a.py": ast.parse("from linkwork.motion.plans import _scale\nkin._point('E')\nx._mine()"),
        SRC / "motion" / "b.py": ast.parse(
            "from linkwork.motion.kernels import _ok\n"
            "class K:\n    def _point(self): ...\n    def f(self): self._point()"
        ),
        SRC / "io" / "c.py": ast.parse("def _mine(): ..."),
    }
    assert [line.split(": ", 1)[1] for line in private_imports(trees)] == ["from linkwork.motion.plans import _scale"]
    assert [line.split(": ", 1)[1] for line in private_attributes(trees)] == ["kin._point (defined in motion)"]


def test_a_public_class_name_means_one_thing():
    """``Plan`` (a velocity plan, not a sweep's variants: :class:`~linkwork.design.plan.SweepPlan`), ``Cycle`` (the
    viewer's, not the report's: ``ReportCycle``) and ``Event`` (of the motion, not of an integration:
    :class:`~linkwork.machine.simulation.IntegrationEvent`), ``Drive`` (a joint's, not the motor and gear:
    ``MotorGear``), ``Arrow`` (of a plan, not the viewer's ``SchemeForce``), ``Element`` (drawn, not the force
    element's protocol ``ForceElement``) and ``PairFriction`` (compiled, not the file's ``FrictionLaw``) are each
    defined once: no public class name is defined twice."""
    where: dict[str, list[str]] = defaultdict(list)
    for path in sorted(SRC.rglob("*.py")):  # a class of the module's own: "class NAME" from the line's start
        for name in re.findall(r"^class ([A-Za-z]\w*)\s*[(:]", path.read_text(encoding="utf-8"), re.MULTILINE):
            where[name].append(str(path.relative_to(SRC)))
    twice = {name: places for name, places in where.items() if len(places) > 1}
    assert twice == {}
