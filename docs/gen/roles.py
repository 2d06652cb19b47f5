"""A griffe extension for the API pages: the docstrings' Sphinx roles (``:func:`parameters```,
``:class:`~linkwork.errors.SpecError```) written as code, the name the reader knows (the last part after
``~``), instead of the role's raw text."""

from __future__ import annotations

import re
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
