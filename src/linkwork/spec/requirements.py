"""The ``requirements:`` section of a mechanism file: what a synthesised mechanism was made for.

``linkwork synthesize`` writes it; the report, ``analyze`` and the viewer's family read it.  A file edited by
hand is checked here, with the rest of the file (``linkwork check``, and every command that reads the file), so
that what reads it later has nothing to fail on:

- ``kind``: one of :data:`KINDS`; the file has the names that kind's analysis and family read
  (:data:`STRUCTURE`: a slider-crank's crank, rod and guide...; the shears' knives, guides, rods and rocker);
- every other key a requirement of that kind (:data:`KINDS`), or ``criterion`` (:data:`CRITERIA`);
- a length, an angle, a force or a moment with its unit (``"400 mm"``, ``"60 deg"``): a bare number would be read
  in a unit nobody said; a ratio a plain number;
- ``<name>_tolerance`` (``stroke_tolerance: "0.021 mm"``): how far the analysis may measure the requirement
  ``name`` from it and the report still call it met, in its unit, at least zero (a synthesised file states the
  one the rounding of its lengths implies); without it, 1e-6 of the requirement;
- every value finite and within its range (each field's ``within`` in its kind's record,
  :mod:`linkwork.requirements`): a stroke is positive, a pressure angle below 90 deg, a time ratio at least 1
  (the slower stroke's time over the faster; a slider-crank's below 3), at most
  :data:`~linkwork.limits.MAX_MAGNITUDE` in SI.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

from linkwork.errors import UnitParseError
from linkwork.limits import MAX_MAGNITUDE, echo, quote
from linkwork.requirements import EXAMPLES, QUANTITIES, RECORDS, carried, needs
from linkwork.spec.shears import shears_parts

#: The requirements each kind carries (those ``linkwork synthesize`` writes for it), besides ``kind`` and
#: ``criterion``: the quantities and ratios of the kind's record (:mod:`linkwork.requirements`).
KINDS: dict[str, tuple[str, ...]] = {kind: carried(kind) for kind in RECORDS}

#: The suffix of a requirement's tolerance (``stroke_tolerance``).
TOLERANCE = "_tolerance"

#: How a family is picked (``criterion``): the least largest pressure angle, or the least peak driving torque.
CRITERIA = ("pressure", "torque")

#: The kind of quantity of each requirement (:data:`linkwork.units.KINDS`); the others are plain ratios.
QUANTITY = QUANTITIES

_DEG = math.pi / 180

#: What the analysis and the family of a kind read from the file: links, joints (and their type), frame points (the
#: names the closed-form kinds write in their own files), and for the shears their parts, read from the file's
#: structure whatever it names them (:func:`~linkwork.spec.shears.shears_parts`).
STRUCTURE: dict[str, dict[str, Any]] = {
    "slider-crank": {"links": ("crank", "rod"), "joints": {"guide": "prismatic"}},
    "crank-rocker": {"links": ("crank", "coupler", "rocker"), "points": ("O4",)},
    "slotted-lever": {"links": ("crank",), "points": ("O1",)},
    "toggle-press": {},
    "double-cut-shears": {"shears": True},
}

Report = Callable[[tuple[Any, ...], str], None]


def check_requirements(bad: Report, data: dict[str, Any]) -> None:
    """Report every problem of the raw ``requirements:`` of ``data`` (a file's mapping) through ``bad(path,
    message)``: its kind, the file's structure for it, each requirement's name, unit and range."""
    given = data.get("requirements")
    if not isinstance(given, dict):
        return  # none, or not a mapping: the schema's
    path = ("requirements",)
    kind = given.get("kind")
    if kind is None:
        bad(path, f'missing field "kind" (the kind synthesised: {", ".join(KINDS)})')
        return
    if not isinstance(kind, str) or kind not in KINDS:
        bad(path + ("kind",), f"expected one of {', '.join(KINDS)}, got {echo(kind)}")
        return
    _check_structure(bad, data, kind)
    for name, value in given.items():
        if name == "kind":
            continue
        where = path + (name,)
        if name == "criterion":
            if value not in CRITERIA:
                bad(where, f"expected one of {', '.join(CRITERIA)}, got {echo(value)}")
        elif name.endswith(TOLERANCE) and name.removesuffix(TOLERANCE) in KINDS[kind]:
            problem = requirement_problem(kind, name, value)
            if problem:
                bad(where, problem)
        elif name not in KINDS[kind]:
            bad(where, f"{quote(name)} is no requirement of a {kind}; expected {', '.join(KINDS[kind])}, criterion")
        else:
            problem = requirement_problem(kind, name, value)
            if problem:
                bad(where, problem)


def requirement_problem(kind: str, name: str, value: Any) -> str | None:
    """Why ``value`` is not the requirement ``name`` (or its ``<name>_tolerance``) of a ``kind`` as a file gives
    it, or None."""
    base = name.removesuffix(TOLERANCE)
    got = requirement_value(base, value)
    if isinstance(got, str):
        return got
    low, high, with_low, with_high = (0.0, MAX_MAGNITUDE, True, True) if base != name else needs(kind)[name].within
    inside = (low < got or (with_low and low == got)) and (got < high or (with_high and got == high))
    if math.isfinite(got) and inside:
        return None
    unit, scale = (" deg", 1 / _DEG) if QUANTITY.get(base) == "angle" else (_si_unit(base), 1.0)
    span = f"{'[' if with_low else '('}{low * scale:g}, {high * scale:g}{']' if with_high else ')'}"
    return f"expected a finite value in {span}{unit}, got {echo(value)}"


def _si_unit(name: str) -> str:
    from linkwork.units import KINDS as UNITS

    kind = QUANTITY.get(name)
    return f" {UNITS[kind][1]}" if kind else ""


def requirement_value(name: str, value: Any) -> float | str:
    """The requirement ``name`` of a file in SI, or why it is not one: a quantity with its unit (a bare number
    refused), a ratio a plain number."""
    from linkwork.units import parse_quantity

    kind = QUANTITY.get(name)
    if isinstance(value, bool) or not isinstance(value, str | int | float):
        return f"expected {'a quantity with its unit' if kind else 'a number'}, got {echo(value)}"
    if kind is None:
        if isinstance(value, str):
            return f"a ratio is a plain number, got {echo(value)}"
        return float(value)
    if not isinstance(value, str) or _plain(value):
        return f'give the unit, e.g. "{EXAMPLES[kind]}", got {echo(value)}'
    try:
        return parse_quantity(value, kind)
    except UnitParseError as exc:
        return str(exc)


def _plain(text: str) -> bool:
    """Whether ``text`` is a number without a unit."""
    try:
        float(text)
    except ValueError:
        return False
    return True


def _check_structure(bad: Report, data: dict[str, Any], kind: str) -> None:
    """Report the names a ``kind``'s requirements need of the file that it does not have."""
    need = STRUCTURE[kind]
    links, joints, frame = (_mapping(data.get(key)) for key in ("links", "joints", "frame"))
    points = _mapping(frame.get("points"))
    missing = [f"link {quote(n)}" for n in need.get("links", ()) if n not in links]
    for joint, type_ in need.get("joints", {}).items():
        j = joints.get(joint)
        if not isinstance(j, dict) or j.get("type") != type_:
            missing.append(f"{type_} joint {quote(joint)}")
    missing += [f"frame point {quote(n)}" for n in need.get("points", ()) if n not in points]
    if need.get("shears") and isinstance(lacks := shears_parts(data), str):
        missing.append(lacks)
    if missing:
        bad(
            ("requirements", "kind"),
            f"the requirements of a {kind} are measured on its structure, and this file has no {', no '.join(missing)}",
        )


def _mapping(value: Any) -> dict[str, Any]:
    return value if isinstance(value, dict) else {}
