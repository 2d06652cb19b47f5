"""A pydantic model (``lw.Spec``) as its constructor takes it, for its page of the API: the type, default and
meaning of each field, read from the model itself (the fields' types, defaults and descriptions, those
``linkwork schema`` prints), so the page and the file format cannot differ.  ``roles.py``'s ``ModelFields`` puts
them in the page's signature and Parameters (griffe reads the source, where a model's constructor is pydantic's
``__init__(**data)``).
"""

from __future__ import annotations

import re
import types
import typing
from typing import Any


def _quantity(meta: list[Any]) -> str | None:
    """The kind of quantity an ``Annotated`` number carries (``Quantity(kind=...)``), if any."""
    return next((m.kind for m in meta if type(m).__name__ == "Quantity"), None)


def _words(tp: Any) -> str:
    """A type as a reader writes it: ``dict[str, Link]``, ``Gravity or float or str``; a quantity's number
    ``float or str`` (a string carries its unit)."""
    origin = typing.get_origin(tp)
    if origin is typing.Annotated:
        inner, *meta = typing.get_args(tp)
        kind = _quantity(meta)
        if kind and inner is float:
            return f"float or str ({'an' if kind[0] in 'aeiou' else 'a'} {kind})"
        return _words(inner)
    if origin in (typing.Union, types.UnionType):
        return " or ".join(dict.fromkeys(_words(a) for a in typing.get_args(tp)))
    if origin is not None:
        return f"{getattr(origin, '__name__', str(origin))}[{', '.join(_words(a) for a in typing.get_args(tp))}]"
    return "None" if tp is type(None) else getattr(tp, "__name__", str(tp))


#: What a field the model describes only by its name means (``Spec.name``, ``Spec.description``).
PLAIN = {
    "name": "The mechanism's name, any text: the reports' titles carry it (a file's name where none is given).",
    "description": "What the mechanism is, any text; the report carries it.",
}


def _meaning(name: str, field: Any) -> str:
    """A field's description, else the first line of its type's docstring (``Link``: "A rigid body ..."), else
    :data:`PLAIN`'s."""
    if field.description:  # a placeholder (``<name>_tolerance``) as code, not an HTML tag
        text = re.sub(r"(\S*<\w+>\S*)", r"`\1`", field.description)
        return text[0].upper() + text[1:]
    kinds = [field.annotation, *typing.get_args(field.annotation)]
    for tp in [t for k in kinds for t in (k, *typing.get_args(k))]:
        if isinstance(tp, type) and tp.__module__.startswith("linkwork") and tp.__doc__:
            return " ".join(tp.__doc__.strip().split("\n\n")[0].split())
    return PLAIN.get(name, "As the file format says.")


def _default(field: Any) -> str | None:
    """The default as code (``None``, ``9.81``, ``Units()``), None where the field is required."""
    if field.default_factory is not None:
        return f"{field.default_factory.__name__}()"
    return None if field.is_required() else repr(field.default)


def model_parameters(model: Any) -> list[tuple[str, str, str | None, str]]:
    """``(name, type, default or None where required, meaning)`` of each field of a pydantic model, in order."""
    return [(name, _words(f.annotation), _default(f), _meaning(name, f)) for name, f in model.model_fields.items()]


def parameters_section(rows: list[tuple[str, str, str | None, str]]) -> str:
    """The numpydoc Parameters section of :func:`model_parameters`' rows."""
    out = ["Parameters", "----------"]
    for name, kind, default, meaning in rows:
        out += [f"{name} : {kind}" + ("" if default is None else f", default {default}"), f"    {meaning}"]
    return "\n".join(out)
