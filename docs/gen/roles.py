"""griffe extensions for the API pages: the docstrings' Sphinx roles (``:func:`parameters```,
``:class:`~linkwork.errors.SpecError```) written as code, the name the reader knows (the last part after
``~``), instead of the role's raw text; a pydantic model's fields as its signature and Parameters."""

from __future__ import annotations

import importlib
import importlib.util
import re
from pathlib import Path
from typing import Any

import griffe

ROLE = re.compile(r":(?:py:)?(?:mod|func|class|data|meth|attr|obj|exc|const):`(~?)([^`]+)`")


def _code(m: re.Match[str]) -> str:
    target = m.group(2)
    return f"`{target.rsplit('.', 1)[-1] if m.group(1) else target}`"


class SphinxRoles(griffe.Extension):
    def on_instance(self, *, obj: griffe.Object, **kwargs: Any) -> None:
        if obj.docstring is not None:
            obj.docstring.value = ROLE.sub(_code, obj.docstring.value)


def _fields() -> Any:
    """``fields.py`` beside this file (mkdocstrings loads this one by its path, not as a package's module)."""
    spec = importlib.util.spec_from_file_location("linkwork_docs_fields", Path(__file__).with_name("fields.py"))
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _python(words: str) -> str:
    """A type in words as the signature writes it: ``Gravity or float or str (an acceleration)`` is
    ``Gravity | float | str``."""
    return re.sub(r" \([^)]*\)", "", words).replace(" or ", " | ")


class ModelFields(griffe.Extension):
    """A pydantic model's page (``lw.Spec``): its keyword-only signature and its Parameters, one per field."""

    def __init__(self) -> None:
        self.fields = _fields()

    def on_class_instance(self, *, cls: griffe.Class, **kwargs: Any) -> None:
        try:
            model = getattr(importlib.import_module(cls.module.path), cls.name)
        except (ImportError, AttributeError):
            return
        if not isinstance(getattr(model, "model_fields", None), dict) or not model.model_fields:
            return
        rows = self.fields.model_parameters(model)
        keyword = griffe.ParameterKind.keyword_only
        params = [griffe.Parameter(n, annotation=_python(k), kind=keyword, default=d) for n, k, d, _ in rows]
        self_ = griffe.Parameter("self", kind=griffe.ParameterKind.positional_or_keyword)
        init = griffe.Function("__init__", parameters=griffe.Parameters(self_, *params), returns="None", parent=cls)
        cls.set_member("__init__", init)
        text = (cls.docstring.value if cls.docstring else "") + "\n\n" + self.fields.parameters_section(rows)
        cls.docstring = griffe.Docstring(text, parent=cls)
