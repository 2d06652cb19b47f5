"""What a mechanism argument is: the one resolver every ``linkwork.*`` analysis calls.

An analysis takes its mechanism as any of

- a path to a mechanism file (``str`` or :class:`os.PathLike`, ``.yaml``/``.yml``),
- the name of a bundled example (``"four-bar"``; ``linkwork examples`` lists them),
- a :class:`~linkwork.spec.schema.Spec` (from :func:`linkwork.load` or :class:`linkwork.MechanismBuilder`),
- a compiled :class:`~linkwork.structure.model.Mechanism` (from :func:`linkwork.compile`).

Anything else is a :class:`TypeError` that says what is expected.
"""

from __future__ import annotations

import os
from typing import Any

#: What a mechanism argument may be, for messages.
EXPECTED = (
    "a mechanism file path, the name of a bundled example, a Spec (linkwork.load) or a Mechanism (linkwork.compile)"
)


def _is_mechanism(x: Any) -> bool:
    from linkwork.structure.model import Mechanism

    return isinstance(x, Mechanism)


def spec_of(mechanism: Any, what: str = "mechanism") -> Any:
    """The description of ``mechanism``: loaded from a file or example, given, or the one a
    compiled mechanism was compiled from (None for a mechanism assembled in code without one).

    Raises
    ------
    TypeError
        For anything but a path, an example name, a Spec or a Mechanism.
    SpecError
        For a file or example with problems, or a name that is neither.
    """
    from linkwork.spec.schema import Spec

    if isinstance(mechanism, Spec):
        return mechanism
    if _is_mechanism(mechanism):
        return mechanism.spec
    if isinstance(mechanism, str | os.PathLike):
        from linkwork.examples import resolve

        return resolve(os.fspath(mechanism))
    raise TypeError(f"{what}: expected {EXPECTED}, got {type(mechanism).__name__}")


def mechanism_of(mechanism: Any, what: str = "mechanism") -> Any:
    """The compiled :class:`~linkwork.structure.model.Mechanism` of ``mechanism`` (compiled here
    when it is a path, an example name or a Spec; returned as it is when compiled already).

    Raises
    ------
    TypeError
        For anything but a path, an example name, a Spec or a Mechanism.
    SpecError, StructureError, UnassemblableError
        From loading and compiling.
    """
    if _is_mechanism(mechanism):
        return mechanism
    from linkwork.structure.compile import compile

    return compile(spec_of(mechanism, what))
