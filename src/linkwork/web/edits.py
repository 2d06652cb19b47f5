"""Edits of a mechanism's parameters by name, as the viewer takes them.

An edit is a mapping of named values in SI, the names of
:func:`linkwork.parameters` (``links.crank.length``, ``frame.points.O1.y``,
``joints.guide_E.axis`` in radians, ``links.rod.mass``, ``links.rod.inertia``).
It means what the same edit of the file means
(:func:`linkwork.structure.parameters.edited_spec`): the values are written
into the description and the whole of it is validated and compiled again, so a
bad value gets the file's own message with its line, and a mechanism that no
longer assembles gets the compile error that names the group and the crank
angle.  Nothing is evaluated.  Beyond the rules of each parameter, the viewer
bounds the size of what it accepts (:data:`LIMITS`).
"""

from __future__ import annotations

import math
from typing import Any

from linkwork.errors import ParameterError
from linkwork.structure.parameters import Parameter, edited_spec, parameter, parameter_list

#: Most overrides one edit may carry.
MAX_OVERRIDES = 256

#: Largest magnitude of a value the viewer accepts, by kind of quantity (m, rad, kg, kg m^2).
LIMITS = {"length": 100.0, "angle": 100.0, "mass": 1e6, "inertia": 1e6}


def editable(mech: Any) -> list[Parameter]:
    """The parameters of ``mech`` an edit may set (those of the description it was compiled from)."""
    return parameter_list(mech) if mech.spec is not None else []


def check_value(p: Parameter, value: float) -> None:
    """Raise :class:`ParameterError` when ``value`` breaks ``p``'s rule or the viewer's bound."""
    wrong = p.check(value)
    if wrong is not None:
        raise ParameterError(wrong)
    limit = LIMITS[p.kind]
    if abs(value) <= limit:
        return
    if p.positive:
        raise ParameterError(f"{p.name}: expected a positive {p.kind} up to {limit:g} {p.unit}, got {value:g}")
    low = 0 if p.kind == "inertia" else -limit
    raise ParameterError(f"{p.name}: expected a value from {low:g} to {limit:g} {p.unit}, got {value:g}")


def apply(mech: Any, overrides: dict[str, float]) -> Any:
    """The description of ``mech`` with ``overrides`` (SI) applied, validated again.

    Raises
    ------
    ParameterError
        An unknown name (with the closest known one), too many overrides, a value out of range.
    SpecError
        The edited description fails validation (the file's message, with its line).
    """
    if len(overrides) > MAX_OVERRIDES:
        raise ParameterError(f"at most {MAX_OVERRIDES} overrides in one edit, got {len(overrides)}")
    if mech.spec is None:
        raise ParameterError("this viewer shows a compiled mechanism without its description: it cannot be edited")
    known = {p.name: p for p in parameter_list(mech)}
    for name, value in overrides.items():
        check_value(parameter(mech, name, known), float(value))
    return edited_spec(mech, {name: float(v) for name, v in overrides.items() if math.isfinite(float(v))})
