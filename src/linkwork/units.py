"""Units at the edges: parse numbers with units into SI floats.

A value in a mechanism file is either a bare number, read in the file's
declared unit for its kind of quantity, or a string with a unit such as
``"100 mm"``, ``"30 rpm"`` or ``"12 deg"``.  Inside linkwork everything is SI:
metres, kilograms, seconds, newtons and radians.
"""

from __future__ import annotations

import math
import re
from functools import lru_cache
from typing import Any

#: Kinds of quantity: (phrase for messages, SI unit, pint dimensionality).
KINDS: dict[str, tuple[str, str, str]] = {
    "length": ("a length", "m", "[length]"),
    "angle": ("an angle", "rad", ""),
    "mass": ("a mass", "kg", "[mass]"),
    "inertia": ("a moment of inertia", "kg*m**2", "[mass]*[length]**2"),
    "time": ("a time", "s", "[time]"),
    "force": ("a force", "N", "[force]"),
    "moment": ("a moment", "N*m", "[force]*[length]"),
    "speed": ("a speed", "m/s", "[length]/[time]"),
    "angular_speed": ("an angular speed", "rad/s", "1/[time]"),
    "acceleration": ("an acceleration", "m/s**2", "[length]/[time]**2"),
    "power": ("a power", "W", "[power]"),
}

#: Base kinds a file may declare, with their SI defaults (angles in degrees).
DEFAULT_UNITS: dict[str, str] = {
    "length": "m",
    "mass": "kg",
    "time": "s",
    "force": "N",
    "angle": "deg",
}

#: The base units of a description given in SI (built in code, or written out in SI).
SI_UNITS: dict[str, str] = {"length": "m", "mass": "kg", "time": "s", "force": "N", "angle": "rad"}

# Units of derived kinds, built from the declared base units.
_DERIVED = {
    "inertia": "{mass}*{length}**2",
    "moment": "{force}*{length}",
    "speed": "{length}/{time}",
    "angular_speed": "{angle}/{time}",
    "acceleration": "{length}/{time}**2",
    "power": "{force}*{length}/{time}",
}


class UnitParseError(ValueError):
    """A value could not be read as the expected kind of quantity.

    ``reason`` says why a unit was refused, when there is more to say than its kind.
    """

    def __init__(self, message: str, reason: str = ""):
        super().__init__(message)
        self.reason = reason


@lru_cache(maxsize=1)
def registry() -> Any:
    """The shared pint unit registry (built on first use)."""
    import pint

    ureg = pint.UnitRegistry(autoconvert_offset_to_baseunit=True)
    ureg.define("rev = revolution")
    return ureg


def unit_for(kind: str, declared: dict[str, str]) -> str:
    """The unit in which a bare number of ``kind`` is read."""
    if kind in _DERIVED:
        return _DERIVED[kind].format(**declared)
    return declared[kind]


@lru_cache(maxsize=256)
def _factor(unit: str, kind: str) -> float:
    """SI value of one ``unit`` of ``kind``; raises UnitParseError."""
    ureg = registry()
    phrase = KINDS[kind][0]
    unknown = f"unknown unit {_quote(unit)}"
    if not _UNIT_TEXT.match(unit):
        raise UnitParseError(unknown, unknown)
    try:
        units = ureg.parse_units(unit)
        q = ureg.Quantity(1.0, units)
    except Exception as exc:  # pint raises several types for bad units
        raise UnitParseError(unknown, unknown) from exc
    names = set(units._units)
    if kind == "angle" and not names <= ANGLE_UNITS:
        raise UnitParseError(f"expected {phrase}, got {_quote(unit)}", "use deg, rad or rev")
    if kind not in ("angle", "angular_speed") and names & ANGLE_UNITS:
        raise UnitParseError(f"expected {phrase}, got {_quote(unit)}", "an angle unit in it")
    return _to_si(q, kind, unit)


#: What a unit expression may contain: names, *, /, ^ or ** with small integer powers, spaces.
_UNIT_TEXT = re.compile(r"^[A-Za-z_][A-Za-z0-9_ ]*(?:\s*(?:\*\*|\^|\*|/)\s*(?:[A-Za-z_][A-Za-z0-9_]*|-?\d))*\s*$")


def _to_si(q: Any, kind: str, text: str) -> float:
    phrase, si, dim = KINDS[kind]
    ureg = registry()
    if kind == "angle":
        ok = q.dimensionless
    else:
        ok = q.dimensionality == ureg.get_dimensionality(dim)
    if kind == "angular_speed" and ok and "hertz" in str(q.units):
        raise UnitParseError(f"expected {phrase}, got {_quote(text)}", "write rpm, rev/s or rad/s, not Hz")
    if not ok:
        raise UnitParseError(f"expected {phrase}, got {_quote(text)}")
    return float(q.to(si).magnitude)


def check_unit(unit: str, kind: str) -> None:
    """Raise UnitParseError unless ``unit`` is a unit of ``kind``."""
    _factor(unit, kind)


def parse_quantity(value: Any, kind: str, declared: dict[str, str] | None = None) -> float:
    """Read ``value`` as a quantity of ``kind`` and return it in SI units.

    Parameters
    ----------
    value : float, int or str
        A bare number (read in the declared unit of its kind) or a string
        with a unit, e.g. ``"100 mm"``.
    kind : str
        One of :data:`KINDS`.
    declared : dict, optional
        Declared units of the file (``length``, ``mass``, ``time``, ``force``,
        ``angle``); defaults to :data:`DEFAULT_UNITS`.

    Returns
    -------
    float
        The value in SI (angles in radians).

    Raises
    ------
    UnitParseError
        With a message such as ``expected a length, got "12 kg"``.
    """
    declared = declared or DEFAULT_UNITS
    phrase = KINDS[kind][0]
    if isinstance(value, bool) or value is None:
        raise UnitParseError(f"expected {phrase}, got {_show(value)}")
    if isinstance(value, int | float):
        try:
            number = float(value)
        except OverflowError:
            raise UnitParseError(f"expected {phrase}, got a number too large to use") from None
        if not math.isfinite(number):
            raise UnitParseError(f"expected {phrase}, got {value!r}")
        return number * _factor(unit_for(kind, declared), kind)
    if not isinstance(value, str):
        raise UnitParseError(f"expected {phrase}, got {_show(value)}")
    text = value.strip()
    try:
        number = float(text)
    except ValueError:
        pass
    else:
        return parse_quantity(number, kind, declared)
    match = _NUMBER_UNIT.match(text)
    if match is None:
        raise UnitParseError(f'expected {phrase}, got {_quote(value)} (write a number and a unit, e.g. "100 mm")')
    number, unit = float(match.group(1)), match.group(2)
    if not math.isfinite(number):
        raise UnitParseError(f"expected {phrase}, got {_quote(value)}")
    try:
        factor = _factor(unit, kind)
    except UnitParseError as exc:
        tail = f" ({exc.reason})" if exc.reason else ""
        raise UnitParseError(f"expected {phrase}, got {_quote(value)}{tail}", exc.reason) from None
    result = number * factor
    if not math.isfinite(result):
        raise UnitParseError(f"expected {phrase}, got {_quote(value)} (out of range)")
    return result


#: A plain decimal number followed by a unit expression: nothing is evaluated but the unit.
_NUMBER_UNIT = re.compile(r"^([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*([A-Za-z_].*)$")

#: Units an angle may be written in (pint's canonical names).
ANGLE_UNITS = {"radian", "degree", "revolution", "turn", "arcminute", "arcsecond", "gradian"}


def _show(value: Any) -> str:
    if isinstance(value, list):
        return "a list"
    if isinstance(value, dict):
        return "a mapping"
    if value is None:
        return "nothing"
    if isinstance(value, bool):
        return "true" if value else "false"
    return repr(value)


def _quote(text: str) -> str:
    return '"' + text.replace('"', '\\"') + '"'
