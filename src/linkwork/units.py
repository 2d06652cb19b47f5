"""Units at the edges: parse numbers with units into SI floats.

A value in a mechanism file is either a string with a unit, such as
``"100 mm"``, ``"30 rpm"`` or ``"12 deg"``, or a bare number.  Inside
linkwork everything is SI: metres, kilograms, seconds, newtons and radians.

The rule for bare numbers (:func:`bare_unit`) is one that cannot surprise:

* a length, mass, time or angle is read in the file's declared unit of its
  kind (``units:``; by default m, kg, s and deg);
* any other kind (a force, moment, moment of inertia, speed, angular speed,
  acceleration, power) is read in the unit the file declares for that kind,
  if it declares one; else in its SI unit, but only where the units of what
  it is made of are SI (m, kg, s and rad, and N where the file declares the
  unit of forces); else it needs its unit, and a bare number other than 0 is
  refused with a message that says what it would have been read as.
"""

from __future__ import annotations

import math
import re
from functools import lru_cache
from typing import Any

import numpy as np

from linkwork.errors import UnitParseError
from linkwork.limits import MAX_QUANTITY, echo, quote

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
    "stiffness": ("a stiffness", "N/m", "[force]/[length]"),
    "torsion_stiffness": ("a torsional stiffness", "N*m/rad", "[force]*[length]"),
    "damping": ("a damping coefficient", "N*s/m", "[force]*[time]/[length]"),
}

#: Base kinds, read bare in the file's declared unit, and their defaults (angles in degrees).
DEFAULT_UNITS: dict[str, str] = {
    "length": "m",
    "mass": "kg",
    "time": "s",
    "angle": "deg",
}

#: The units of a description given in SI (built in code, or written out in SI).
SI_UNITS: dict[str, str] = {"length": "m", "mass": "kg", "time": "s", "force": "N", "angle": "rad"}

#: What each derived kind is made of: its bare numbers are SI only where these units are.
MADE_OF: dict[str, tuple[str, ...]] = {
    "force": ("length", "mass", "time"),
    "moment": ("force", "length"),
    "inertia": ("mass", "length"),
    "speed": ("length", "time"),
    "angular_speed": ("angle", "time"),
    "acceleration": ("length", "time"),
    "power": ("force", "length", "time"),
    "stiffness": ("force", "length"),
    "torsion_stiffness": ("force", "length", "angle"),
    "damping": ("force", "time", "length"),
}

#: Kinds whose unit a file may declare in ``units:``: the base kinds and every derived kind.
DECLARABLE: tuple[str, ...] = (*DEFAULT_UNITS, *MADE_OF)

# What a bare number of a derived kind would be in the file's declared units (for messages).
_IN_FILE_UNITS = {
    "force": "{force}",
    "inertia": "{mass}*{length}**2",
    "moment": "{force}*{length}",
    "speed": "{length}/{time}",
    "angular_speed": "{angle}/{time}",
    "acceleration": "{length}/{time}**2",
    "power": "{force}*{length}/{time}",
    "stiffness": "{force}/{length}",
    "torsion_stiffness": "{force}*{length}/{angle}",
    "damping": "{force}*{time}/{length}",
}

# A unit to propose for a derived kind written without one.
_PROPOSED = {"angular_speed": "rpm"}

_PLURAL = {"length": "lengths", "mass": "masses", "time": "times", "angle": "angles", "force": "forces"}


@lru_cache(maxsize=1)
def registry() -> Any:
    """The shared pint unit registry (built on first use)."""
    import pint

    ureg: Any = pint.UnitRegistry(autoconvert_offset_to_baseunit=True)
    ureg.define("rev = revolution")
    return ureg


def bare_unit(kind: str, declared: dict[str, str]) -> str | None:
    """The unit in which a bare number of ``kind`` is read, or None where it needs its unit (but 0).

    ``declared`` holds the units the file declares (missing base kinds take
    :data:`DEFAULT_UNITS`); see the module's docstring for the rule.
    """
    if kind in declared:
        return declared[kind]
    if kind in DEFAULT_UNITS:
        return DEFAULT_UNITS[kind]
    return None if _not_si(kind, declared) else KINDS[kind][1]


def unit_for(kind: str, declared: dict[str, str]) -> str:
    """The unit to show values of ``kind`` in for a file: the unit of its bare numbers, else SI."""
    return bare_unit(kind, declared) or KINDS[kind][1]


def written(si: float, kind: str, declared: dict[str, str], digits: int = 10) -> float | str:
    """An SI value of ``kind`` as a file with ``declared`` units reads it back.

    A bare number in the file's unit of that kind where it has one, else a
    string with the SI unit (``"0.0125 kg*m^2"``); ``digits`` significant digits.
    """
    unit = bare_unit(kind, declared)
    if unit is None:
        return f"{si:.{digits}g} {_show_unit(KINDS[kind][1])}"
    return float(f"{si / si_factor(unit, kind):.{digits}g}")


def _not_si(kind: str, declared: dict[str, str]) -> list[str]:
    """What makes a bare number of a derived ``kind`` ambiguous: ``["lengths are in mm", ...]``."""
    out: list[str] = []
    for part in MADE_OF[kind]:
        unit = declared.get(part, DEFAULT_UNITS.get(part))
        if unit is None:
            out += _not_si(part, declared)
        elif abs(si_factor(unit, part) - 1.0) > 1e-12:
            out.append(f"{_PLURAL[part]} are in {unit}")
    return list(dict.fromkeys(out))


def _needs_unit(number: float, kind: str, declared: dict[str, str]) -> str:
    """The message for a bare number of a kind that needs its unit in this file."""
    phrase, si, _ = KINDS[kind]
    text = f"{number:.15g}"
    naive = _IN_FILE_UNITS[kind].format(**{"force": "N", **DEFAULT_UNITS, **declared})
    factor = si_factor(naive, kind)
    examples = [f'"{text} {_show_unit(_PROPOSED.get(kind, si))}"']
    if abs(factor - 1.0) > 1e-12:
        examples.append(f'"{text} {_show_unit(naive)}" (= {number * factor:.6g} {_show_unit(si)})')
    noun = phrase.split(" ", 1)[1]
    return (
        f"a bare {text} is not read as {phrase} where {' and '.join(_not_si(kind, declared))}: write its unit, "
        f"e.g. {' or '.join(examples)}, or declare one for every {noun} of the file, "
        f"e.g. units: {{{kind}: {_show_unit(naive)}}}"
    )


def _show_unit(unit: str) -> str:
    return unit.replace("**", "^")


#: The SI value of one of the common units of each kind, by kind and the unit as written: read without pint,
#: whose registry takes about half a second to build (the values are pint's, which a test checks to the bit).
COMMON_UNITS: dict[str, dict[str, float]] = {
    "length": {"m": 1.0, "mm": 0.001, "cm": 0.01, "km": 1000.0},
    "mass": {"kg": 1.0, "g": 0.001, "t": 1000.0},
    "time": {"s": 1.0, "ms": 0.001, "min": 60.0, "h": 3600.0},
    "angle": {"deg": 0.017453292519943295, "rad": 1.0},
    "force": {"N": 1.0, "kN": 1000.0, "MN": 1000000.0},
    "moment": {"N*m": 1.0, "N m": 1.0, "kN*m": 1000.0, "kN m": 1000.0},
    "inertia": {"kg*m^2": 1.0, "kg*m**2": 1.0, "kg m^2": 1.0, "kg*mm^2": 1e-06},
    "speed": {"m/s": 1.0, "mm/s": 0.001},
    "angular_speed": {"rad/s": 1.0, "rpm": 0.10471975511965977, "deg/s": 0.017453292519943295},
    "acceleration": {"m/s^2": 1.0, "m/s**2": 1.0},
    "power": {"W": 1.0, "kW": 1000.0},
    "stiffness": {"N/m": 1.0, "N/mm": 1000.0, "kN/m": 1000.0},
    "torsion_stiffness": {"N*m/rad": 1.0, "N m/rad": 1.0},
    "damping": {"N*s/m": 1.0, "N s/m": 1.0},
}


@lru_cache(maxsize=256)
def si_factor(unit: str, kind: str) -> float:
    """SI value of one ``unit`` of a kind of quantity.

    Parameters
    ----------
    unit : str
        A unit as written in a file or an option (``"mm"``, ``"rpm"``, ``"kN"``).
    kind : str
        A kind of :data:`KINDS` (``"length"``, ``"speed"``...).

    Returns
    -------
    float
        The value in SI units of one ``unit`` (``si_factor("mm", "length")`` is 0.001).

    Raises
    ------
    UnitParseError
        Where ``unit`` is unknown or not a unit of ``kind``.
    """
    common = COMMON_UNITS[kind].get(unit)
    return common if common is not None else _pint_factor(unit, kind)


def _pint_factor(unit: str, kind: str) -> float:
    """SI value of one ``unit`` of ``kind`` by pint; raises UnitParseError."""
    phrase = KINDS[kind][0]
    unknown = f"unknown unit {_quote(unit)}"
    if len(unit) > MAX_QUANTITY or not _UNIT_TEXT.match(unit):
        raise UnitParseError(unknown, unknown)
    if _POWER_OF_POWER.search(unit):  # m^9^9^9 is m^(9^387420489): pint would work that number out
        why = f"{unknown}: one small power per unit (m^2), not a power of a power"
        raise UnitParseError(why, why)
    ureg = registry()
    try:
        units = ureg.parse_units(unit)
        q = ureg.Quantity(1.0, units)
    except Exception as exc:  # pint raises several types for bad units
        raise UnitParseError(unknown, unknown) from exc
    names = set(units._units)
    if kind == "angle" and not names <= ANGLE_UNITS:
        raise UnitParseError(f"expected {phrase}, got {_quote(unit)}", "use deg, rad or rev")
    if kind not in ("angle", "angular_speed", "torsion_stiffness") and names & ANGLE_UNITS:
        raise UnitParseError(f"expected {phrase}, got {_quote(unit)}", "an angle unit in it")
    return _to_si(q, kind, unit)


#: What a unit expression may contain: names, *, /, ^ or ** with small integer powers, spaces.  Each
#: quantifier is possessive and no two of them can take the same characters, so that a match takes
#: time linear in the text, whatever it holds.
_UNIT_TEXT = re.compile(
    r"^[A-Za-z_][A-Za-z0-9_]*+(?: ++[A-Za-z_][A-Za-z0-9_]*+)*+"
    r"(?:\s*+(?:\*\*|\^|\*|/)\s*+(?:[A-Za-z_][A-Za-z0-9_]*+(?: ++[A-Za-z_][A-Za-z0-9_]*+)*+|-?\d))*+\s*+$"
)


#: A power raised to a power (``m^9^9``), which :data:`_UNIT_TEXT` lets through and whose size has no bound.
_POWER_OF_POWER = re.compile(r"(?:\*\*|\^)\s*+-?\d\s*+(?:\*\*|\^)")


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
    si_factor(unit, kind)


def parse_quantity(value: Any, kind: str, declared: dict[str, str] | None = None) -> float:
    """Read ``value`` as a quantity of ``kind`` and return it in SI units.

    Parameters
    ----------
    value : float, int or str
        A string with a unit, e.g. ``"100 mm"``, or a bare number, read in
        :func:`bare_unit` (refused where that is None).
    kind : str
        One of :data:`KINDS`.
    declared : dict, optional
        Units the file declares, by kind (any of :data:`DECLARABLE`); base
        kinds it leaves out take :data:`DEFAULT_UNITS`.

    Returns
    -------
    float
        The value in SI (angles in radians).

    Raises
    ------
    UnitParseError
        With a message such as ``expected a length, got "12 kg"``, or for a
        bare number that needs its unit, what it would be read as and how to
        write it.
    """
    declared = declared or DEFAULT_UNITS
    phrase = KINDS[kind][0]
    if isinstance(value, bool) or value is None or not isinstance(value, int | float | str):
        raise UnitParseError(f"expected {phrase}, got {echo(value)}")
    if isinstance(value, int | float):
        return _bare(value, kind, declared)
    number = _number(value)
    return _with_unit(value, kind) if number is None else _bare(number, kind, declared)


def _number(text: str) -> float | None:
    """``text`` as a plain number (a bare number written as a string), or None."""
    try:
        return float(text.strip())
    except ValueError:
        return None


def _bare(value: float, kind: str, declared: dict[str, str]) -> float:
    """A bare number of ``kind`` in SI, read in :func:`bare_unit`; raises UnitParseError."""
    phrase = KINDS[kind][0]
    try:
        number = float(value)
    except OverflowError:
        raise UnitParseError(f"expected {phrase}, got a number too large to use") from None
    if not math.isfinite(number):
        raise UnitParseError(f"expected {phrase}, got {echo(value)}")
    unit = bare_unit(kind, declared)
    if unit is None and number == 0:
        return 0.0  # zero in any unit
    if unit is None:
        raise UnitParseError(_needs_unit(number, kind, declared))
    return number * si_factor(unit, kind)


def _with_unit(value: str, kind: str) -> float:
    """A number with its unit (``"100 mm"``) of ``kind`` in SI; raises UnitParseError."""
    phrase = KINDS[kind][0]
    if len(value) > MAX_QUANTITY:
        raise UnitParseError(
            f"expected {phrase}, got {_quote(value)} (a number with its unit is at most {MAX_QUANTITY} characters)"
        )
    match = _NUMBER_UNIT.match(value.strip())
    if match is None:
        raise UnitParseError(f'expected {phrase}, got {_quote(value)} (write a number and a unit, e.g. "100 mm")')
    number, unit = float(match.group(1)), match.group(2)
    if not math.isfinite(number):
        raise UnitParseError(f"expected {phrase}, got {_quote(value)}")
    try:
        factor = si_factor(unit, kind)
    except UnitParseError as exc:
        tail = f" ({exc.reason})" if exc.reason else ""
        raise UnitParseError(f"expected {phrase}, got {_quote(value)}{tail}", exc.reason) from None
    result = number * factor
    if not math.isfinite(result):
        raise UnitParseError(f"expected {phrase}, got {_quote(value)} (out of range)")
    return result


#: A plain decimal number followed by a unit expression: nothing is evaluated but the unit.  Possessive,
#: and the number's digits split one way only, so that a match takes time linear in the text.
_NUMBER_UNIT = re.compile(r"^([-+]?+(?:\d++(?:\.\d*+)?+|\.\d++)(?:[eE][-+]?+\d++)?+)\s*+([A-Za-z_].*+)$")

#: Units an angle may be written in (pint's canonical names).
ANGLE_UNITS = {"radian", "degree", "revolution", "turn", "arcminute", "arcsecond", "gradian"}


def _quote(text: str) -> str:
    return quote(text)


def turn_deg(angle: Any, digits: int = 1) -> Any:
    """An angle (rad, a number or an array) as it is shown or written: degrees in [0, 360), rounded to
    ``digits`` decimals, and wrapped again after rounding, so that -1e-9 rad reads 0.0 and not 360.0.

    The turn is wrapped before rounding (``fmod`` is exact), so each value is the double nearest a number
    of ``digits`` decimals: 627.5 deg and -92.5 deg are written ``267.5``, without the noise of a
    subtraction after the rounding."""
    deg = np.round(np.degrees(angle) % 360.0, digits) % 360.0
    return float(deg) if np.ndim(deg) == 0 else deg
