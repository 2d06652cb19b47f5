"""Edits of a mechanism's dimensions and masses by name, re-validated from its description.

An edit is a mapping of named values in SI: the dimensions that
:func:`linkwork.parameters` lists (``links.crank.length``,
``links.rocker.points.B.x``, ``frame.points.O1.y``, ``joints.guide_E.axis``
in radians) and the mass properties ``links.NAME.mass`` (kg) and
``links.NAME.inertia`` (kg m^2, about the centre of mass or about the
file's ``inertia_about``).  The values are written, with their SI unit,
into a copy of the description's data and the whole description is
validated and compiled again, so a bad value gets the file's own message
with its line, and a mechanism that no longer assembles gets the compile
error that names the group and the crank angle.  Nothing is evaluated.
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass
from typing import Any

from linkwork.errors import LinkworkError

#: Most overrides one edit may carry.
MAX_OVERRIDES = 256

#: Largest length or coordinate (m), mass (kg), inertia (kg m^2) and angle (rad) an edit accepts.
LIMITS = {"length": 100.0, "coordinate": 100.0, "mass": 1e6, "inertia": 1e6, "angle": 100.0}

_SI = {"length": "m", "mass": "kg", "time": "s", "force": "N", "angle": "rad"}


class EditError(LinkworkError, ValueError):
    """An override names no editable value, or its value is out of range."""


@dataclass(frozen=True)
class Parameter:
    """One editable value.

    Attributes
    ----------
    name : str
        The path in the file, e.g. ``links.crank.length``.
    kind : str
        ``length`` (positive, m), ``coordinate`` (m), ``angle`` (rad), ``mass`` (kg) or ``inertia`` (kg m^2).
    value : float
        Its value in SI.
    group : str
        ``dimensions`` or ``masses``.
    note : str
        What it means where the name does not say (``about O3`` for an inertia).
    """

    name: str
    kind: str
    value: float
    group: str
    note: str = ""

    def as_dict(self) -> dict[str, Any]:
        return {"name": self.name, "kind": self.kind, "value": self.value, "group": self.group, "note": self.note}


def _kind(name: str) -> str:
    last = name.rsplit(".", 1)[1]
    if last == "length":
        return "length"
    if last == "axis":
        return "angle"
    return "coordinate"


def editable(spec: Any, mech: Any) -> list[Parameter]:
    """The dimensions and mass properties of ``mech`` (compiled from ``spec``) an edit may set."""
    from linkwork.motion.geometry import parameters

    out = [Parameter(name, _kind(name), value, "dimensions") for name, value in parameters(mech).items()]
    for i, lname in enumerate(mech.link_names):
        if i == 0 or mech.link_virtual[i] or lname not in spec.links:
            continue
        link = spec.links[lname]
        out.append(Parameter(f"links.{lname}.mass", "mass", float(mech.link_mass[i]), "masses"))
        about = link.inertia_about if link.inertia is not None and link.inertia_about else ""
        value = float(link.inertia) if link.inertia is not None else float(mech.link_inertia[i])
        note = f"about {about}" if about else "about the centre of mass"
        out.append(Parameter(f"links.{lname}.inertia", "inertia", value, "masses", note))
    return out


def check_value(p: Parameter, value: float) -> None:
    """Raise :class:`EditError` when ``value`` is out of the range of ``p``'s kind."""
    limit = LIMITS[p.kind]
    if not math.isfinite(value):
        raise EditError(f"{p.name}: expected a finite number, got {value!r}")
    if p.kind in ("length", "mass") and not 0 < value <= limit:
        unit = "m" if p.kind == "length" else "kg"
        raise EditError(f"{p.name}: expected a positive {p.kind} up to {limit:g} {unit}, got {value:g}")
    if p.kind == "inertia" and not 0 <= value <= limit:
        raise EditError(f"{p.name}: expected a moment of inertia from 0 to {limit:g} kg m^2, got {value:g}")
    if p.kind in ("coordinate", "angle") and not abs(value) <= limit:
        unit = "m" if p.kind == "coordinate" else "rad"
        raise EditError(f"{p.name}: expected a value from -{limit:g} to {limit:g} {unit}, got {value:g}")


def _source(spec: Any) -> Any:
    """The description's raw data with its lines; for a spec built in code, its SI values."""
    from linkwork.spec.yamlsource import Source

    if spec.source is not None and isinstance(spec.source.data, dict):
        return spec.source
    data = spec.model_dump(mode="python", exclude_none=True)
    data["units"] = dict(_SI)
    for d in data.get("drives", []):
        if "law" in d:
            d["law"]["value"] = list(d["law"]["value"])
    return Source(_plain(data), {}, None, [])


def _plain(x: Any) -> Any:
    if isinstance(x, dict):
        return {k: _plain(v) for k, v in x.items()}
    if isinstance(x, list | tuple):
        return [_plain(v) for v in x]
    return x


def _write(data: dict[str, Any], name: str, kind: str, value: float) -> None:
    """Put ``value`` (SI) at the place of ``name`` in the raw data, with its unit."""
    unit = {"length": "m", "coordinate": "m", "angle": "rad", "mass": "kg", "inertia": "kg*m^2"}[kind]
    text = f"{value!r} {unit}"
    parts = name.split(".")
    if parts[-1] in ("x", "y"):
        node: Any = data
        for key in parts[:-1]:
            if not isinstance(node, dict) or key not in node:
                raise EditError(f"{name}: the description gives no such value to edit")
            node = node[key]
        if not isinstance(node, list) or len(node) != 2:
            raise EditError(f"{name}: the description gives no such value to edit")
        node[0 if parts[-1] == "x" else 1] = text
        return
    node = data
    for key in parts[:-1]:
        if not isinstance(node, dict):
            raise EditError(f"{name}: the description gives no such value to edit")
        node = node.setdefault(key, {})
    node[parts[-1]] = text


def apply(spec: Any, mech: Any, overrides: dict[str, float]) -> Any:
    """A new spec with ``overrides`` (SI) applied, validated again.

    Raises
    ------
    EditError
        An unknown name (with the closest known one), too many overrides, a value out of range.
    SpecError
        The edited description fails validation (the file's message, with its line).
    """
    from linkwork.spec.checks import suggest
    from linkwork.spec.load import validate
    from linkwork.spec.yamlsource import Source

    if len(overrides) > MAX_OVERRIDES:
        raise EditError(f"at most {MAX_OVERRIDES} overrides in one edit, got {len(overrides)}")
    known = {p.name: p for p in editable(spec, mech)}
    src = _source(spec)
    data = copy.deepcopy(src.data)
    for name, value in overrides.items():
        p = known.get(name)
        if p is None:
            raise EditError(f'no editable value "{name}"{suggest(name, list(known))}')
        check_value(p, float(value))
        _write(data, name, p.kind, float(value))
    return validate(Source(data, src.lines, src.file, []))
