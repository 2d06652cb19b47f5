"""Every value of a mechanism file as it was read: its path, line, text, SI value and unit.

The walk follows the :class:`~linkwork.spec.schema.Quantity` marks of the
format's models over the file's raw data, and reads each value by the same
:func:`~linkwork.units.parse_quantity` that validation used, so what it
lists is what the spec holds.  Plain numbers (ratios, coefficients) are
listed too, with no unit.
"""

from __future__ import annotations

import types
import typing
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

from pydantic import BaseModel

from linkwork.spec.schema import Quantity, Spec, stiffness_kind
from linkwork.spec.yamlsource import Path, dotted
from linkwork.units import KINDS, parse_quantity


@dataclass(frozen=True)
class ValueRead:
    """One value of the file.

    Attributes
    ----------
    path : str
        Its place, e.g. ``links.crank.length`` or ``frame.points.O4[0]``.
    line : int or None
        Its line in the file.
    text : float, int or str
        As the file gives it: a bare number or a string with a unit.
    value : float
        In SI (angles in rad).
    unit : str
        The SI unit of ``value`` (``""`` for a plain number).
    kind : str or None
        Its kind (:data:`linkwork.units.KINDS`), None for a plain number.
    """

    path: str
    line: int | None
    text: float | int | str
    value: float
    unit: str
    kind: str | None

    def as_dict(self) -> dict[str, Any]:
        return {
            "path": self.path,
            "line": self.line,
            "text": self.text,
            "value": self.value,
            "unit": self.unit,
            "kind": self.kind,
        }


def values_read(spec: Spec) -> list[ValueRead]:
    """Every number of the file ``spec`` was read from, in the order of its lines.

    Empty for a spec with no source (made by ``Spec.model_validate``); a
    builder's values have no line.
    """
    src = spec.source
    if src is None or not isinstance(src.data, dict):
        return []
    declared = spec.units.model_dump(exclude_none=True)
    drive_kinds = _drive_kinds(spec)
    out = []
    for path, raw, kind in _walk(Spec, src.data, ()):
        if kind in ("drive_speed", "drive_coordinate"):
            kind = drive_kinds.get(path[1], ("", ""))[kind == "drive_coordinate"]
        elif kind == "load_stiffness":
            kind = stiffness_kind(spec.loads[str(path[1])].type)
        if kind is None:
            value, unit = float(raw), ""
        else:
            value, unit = parse_quantity(raw, kind, declared), KINDS[kind][1].replace("**", "^")
        out.append(ValueRead(dotted(path), src.line(path), raw, value, unit, kind))
    return sorted(out, key=lambda v: v.line if v.line is not None else 0)


def _drive_kinds(spec: Spec) -> dict[Any, tuple[str, str]]:
    """(speed kind, coordinate kind) of each drive, by its index."""
    out = {}
    for i, drive in enumerate(spec.drives):
        rot = spec.joints[drive.joint].type == "revolute"
        out[i] = ("angular_speed", "angle") if rot else ("speed", "length")
    return out


def _is_number(x: Any) -> bool:
    return isinstance(x, int | float) and not isinstance(x, bool)


def _walk(tp: Any, raw: Any, path: Path, meta: tuple[Any, ...] = ()) -> Iterator[tuple[Path, Any, str | None]]:
    """(path, raw value, kind) of every quantity and plain number in ``raw`` described by the type ``tp``."""
    if typing.get_origin(tp) is typing.Annotated:
        yield from _walk(typing.get_args(tp)[0], raw, path, (*meta, *tp.__metadata__))
        return
    mark = next((m for m in meta if isinstance(m, Quantity)), None)
    if mark is not None:
        yield from _leaf(mark, raw, path)
        return
    origin = typing.get_origin(tp)
    if origin in (typing.Union, types.UnionType):
        for arg in typing.get_args(tp):
            if arg is not type(None) and _fits(arg, raw):
                yield from _walk(arg, raw, path, meta)
                return
    elif origin is list and isinstance(raw, list | tuple):
        for i, item in enumerate(raw):
            yield from _walk(typing.get_args(tp)[0], item, path + (i,))
    elif origin is dict and isinstance(raw, dict):
        for key, item in raw.items():
            yield from _walk(typing.get_args(tp)[1], item, path + (key,))
    elif isinstance(tp, type) and issubclass(tp, BaseModel) and isinstance(raw, dict):
        for name, field in tp.model_fields.items():
            if name in raw and raw[name] is not None:
                yield from _walk(field.annotation, raw[name], path + (name,), tuple(field.metadata))
    elif tp is float and _is_number(raw):
        yield path, raw, None


def _fits(tp: Any, raw: Any) -> bool:
    """Whether ``raw`` is the data of the member ``tp`` of a union."""
    base = typing.get_args(tp)[0] if typing.get_origin(tp) is typing.Annotated else tp
    if isinstance(base, type) and issubclass(base, BaseModel):
        return isinstance(raw, dict)
    return True


def _leaf(mark: Quantity, raw: Any, path: Path) -> Iterator[tuple[Path, Any, str | None]]:
    if mark.shape == "point_or_name" and isinstance(raw, str):
        return  # a point's name
    if mark.shape in ("point", "point_or_name", "table") and isinstance(raw, list | tuple):  # a tuple: from_dict
        for i, item in enumerate(raw):
            yield path + (i,), item, mark.kind
    else:
        yield path, raw, mark.kind
