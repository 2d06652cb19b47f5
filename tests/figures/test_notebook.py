"""A mechanism in a notebook: ``%load_ext linkwork.figures.notebook`` registers its scheme as its SVG display,
by name, so that the core imports no drawing package."""

from __future__ import annotations

import re
import subprocess
import sys

import pytest

import linkwork as lw

pytest.importorskip("matplotlib")


class _Formatter:
    """What IPython's SVG formatter offers the extension: printers registered by module and class name."""

    def __init__(self) -> None:
        self.deferred_printers: dict[tuple[str, str], object] = {}
        self.type_printers: dict[type, object] = {}

    def for_type_by_name(self, module: str, name: str, func: object) -> None:
        self.deferred_printers[(module, name)] = func


class _Shell:
    def __init__(self) -> None:
        self.display_formatter = type("Display", (), {"formatters": {"image/svg+xml": _Formatter()}})()


def test_a_mechanism_is_shown_as_its_scheme_naming_its_links():
    from linkwork.figures import notebook

    shell = _Shell()
    notebook.load_ipython_extension(shell)
    formatter = shell.display_formatter.formatters["image/svg+xml"]
    show = formatter.deferred_printers[("linkwork.structure.model", "Mechanism")]
    mech = lw.compile("double-cut-shears")
    assert type(mech).__module__ == "linkwork.structure.model" and type(mech).__name__ == "Mechanism"
    svg = show(mech)
    assert svg.lstrip().startswith("<?xml") and "<svg" in svg and svg.rstrip().endswith("</svg>")
    texts = re.findall(r"<text[^>]*>([^<]*)</text>", svg)
    key = next(t for t in texts if t.startswith("1 "))
    words = key.split()
    numbers, names = words[::2], words[1::2]
    assert names == ["crank", "rod", "rocker", "rod_DE", "knife_upper", "rod_CF", "knife_lower"]  # the file's links
    assert numbers == list("1234567")  # as the file numbers them (its comments, the paper)
    assert set(numbers) <= set(texts)  # each number of the key is drawn beside its link
    notebook.unload_ipython_extension(shell)
    assert formatter.deferred_printers == {}


def test_the_core_imports_no_drawing_package():
    code = "import sys, linkwork as lw; lw.compile('four-bar'); print('matplotlib' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "False"
