"""The examples in the docstrings of the package run and show what they say (``>>>`` lines, as ``doctest`` runs
them), each module imported by its name as a user imports it."""

from __future__ import annotations

import doctest
import importlib
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src"


def _with_examples() -> list[str]:
    """The modules of linkwork whose source holds a ``>>>`` example."""
    out = []
    for path in sorted((SRC / "linkwork").rglob("*.py")):
        if ">>>" in path.read_text(encoding="utf-8"):
            parts = path.relative_to(SRC).with_suffix("").parts
            out.append(".".join(parts[:-1] if parts[-1] == "__init__" else parts))
    return out


@pytest.mark.parametrize("name", _with_examples())
def test_the_examples_of_a_docstring_run(name):
    module = importlib.import_module(name)
    tests = doctest.DocTestFinder().find(module, name)
    assert sum(len(t.examples) for t in tests) > 0, f"{name}: its examples were not found"
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    report: list[str] = []
    for test in tests:
        runner.run(test, out=report.append)
    assert runner.failures == 0, "".join(report)


def test_a_package_attribute_never_hides_a_module_of_that_name():
    """A module that shares its name with the function its package exports is the function or the module by the
    order of imports (the doctests of such a module failed with "'module' object is not callable")."""
    import pkgutil
    import types

    import linkwork

    hidden = []
    for info in pkgutil.walk_packages(linkwork.__path__, "linkwork."):
        if not info.ispkg:
            continue
        package = importlib.import_module(info.name)
        for sub in pkgutil.iter_modules(package.__path__):
            attr = getattr(package, sub.name, None)
            if attr is not None and not isinstance(attr, types.ModuleType):
                hidden.append(f"{info.name}.{sub.name}")
    assert hidden == []


def test_dir_of_the_package_shows_its_exports():
    import linkwork

    names = dir(linkwork)
    assert set(linkwork.__all__) <= set(names)
    assert {"compile", "kinematics", "forces", "Kinematics", "sweep"} <= set(names)
