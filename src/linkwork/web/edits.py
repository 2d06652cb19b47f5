"""Edits of a mechanism's parameters by name, as the viewer takes them.

An edit is a mapping of named values in SI, the names of
:func:`linkwork.parameters` (``links.crank.length``, ``frame.points.O1.y``,
``joints.guide_E.axis`` in radians, ``links.rod.mass``, ``links.rod.inertia``).
It means what the same edit of the file means: the viewer solves it as a
variant of the compiled mechanism (:mod:`linkwork.web.cycle`), with the mass
rule of :mod:`linkwork.structure.parameters`; a bad value gets the parameter's
own message, and a file is written from it by
:func:`linkwork.structure.parameters.file_text`.  Nothing is evaluated.  Beyond
the rules of each parameter, the viewer bounds the size of what it accepts
(:data:`LIMITS`).
"""

from __future__ import annotations

import math
from typing import Any

from linkwork.errors import ParameterError
from linkwork.lang import russian_numbers, t
from linkwork.structure.model import Mechanism
from linkwork.structure.parameters import INERTIA_GIVEN, Masses, Parameter, parameter, parameter_list

#: Most overrides one edit may carry.
MAX_OVERRIDES = 256

#: Largest magnitude of a value the viewer accepts, by kind of quantity (m, rad, kg, kg m^2).
LIMITS = {"length": 100.0, "angle": 100.0, "mass": 1e6, "inertia": 1e6}

#: The unit the page shows each kind of value in, and the factor from SI to it.
DISPLAY = {"length": ("mm", 1000.0), "angle": ("deg", 180.0 / math.pi), "mass": ("kg", 1.0), "inertia": ("kg m²", 1.0)}

#: The key of each kind's unit among the page's texts (``view.unit.*`` of :mod:`linkwork.lang`; in English the units
#: of :data:`DISPLAY`).
DISPLAY_UNITS = {"length": "mm", "angle": "deg", "mass": "kg", "inertia": "kgm2"}


def editable(mech: Mechanism) -> list[Parameter]:
    """The parameters of ``mech`` an edit may set (those of the description it was compiled from)."""
    return parameter_list(mech) if mech.description is not None else []


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


def validated(mech: Mechanism, overrides: dict[str, float]) -> dict[str, float]:
    """``overrides`` checked against the parameters of ``mech`` and the viewer's bounds, as floats.

    Raises
    ------
    ParameterError
        An unknown name (with the closest known one), too many overrides, a value out of range, a
        mechanism without its description.
    """
    if len(overrides) > MAX_OVERRIDES:
        raise ParameterError(f"at most {MAX_OVERRIDES} overrides in one edit, got {len(overrides)}")
    if mech.description is None:
        raise ParameterError("this viewer shows a compiled mechanism without its description: it cannot be edited")
    out = {}
    for name, value in overrides.items():
        check_value(parameter(mech, name), float(value))
        out[name] = float(value)
    return out


def variant_parameters(
    mech: Mechanism,
    overrides: dict[str, float],
    masses: Masses,
    known: list[Parameter] | None = None,
    lang: str = "en",
) -> list[dict[str, Any]]:
    """The editable parameters of the variant ``overrides`` of ``mech`` with its values: the file's where not
    overridden, except the moments of inertia the file leaves to their default (a uniform rod, m L^2 / 12),
    which follow the variant (``masses``, of :func:`linkwork.structure.parameters.apply`), as they do in the
    file edited so.  ``known``: :func:`editable` of ``mech``, where the caller has it; the notes in ``lang``
    (:func:`note_in`)."""
    out = []
    for p in known if known is not None else editable(mech):
        item = p.as_dict()
        parts = p.name.split(".")
        if p.name in overrides:
            item["value"] = overrides[p.name]
        elif p.kind == "inertia":
            link = mech.link_names.index(parts[1])
            rule = int(mech.link_inertia_rule[link])
            if rule < 0 and rule != INERTIA_GIVEN:
                item["value"] = float(masses.inertia[0, link])
        item["note"] = note_in(item.get("note"), lang)
        out.append(item)
    return out


def note_in(note: str | None, lang: str) -> str | None:
    """A parameter's note (what a moment of inertia is taken about: ``about the centre of mass``, ``about O1``) in
    ``lang``."""
    if not note or lang == "en":
        return note
    if note == "about the centre of mass":
        return t("view.about_centre", lang)
    return t("view.about", lang, point=note.removeprefix("about ")) if note.startswith("about ") else note


def shown(mech: Mechanism, overrides: dict[str, float], lang: str = "en") -> str:
    """``overrides`` as the page shows them: ``links.crank.length = 300 mm, links.rod.mass = 90 kg``, the units in
    ``lang`` (a decimal comma and ``мм`` in Russian)."""
    kinds = {p.name: p.kind for p in editable(mech)}
    parts = []
    for name, value in overrides.items():
        kind = kinds.get(name, "length")
        number = f"{value * DISPLAY[kind][1]:.6g}"
        parts.append(f"{name} = {russian_numbers(number) if lang == 'ru' else number} {display_unit(kind, lang)}")
    return "; ".join(parts) if lang == "ru" else ", ".join(parts)


def display_unit(kind: str, lang: str = "en") -> str:
    """The unit the page shows a kind of value in (:data:`DISPLAY`), in ``lang``."""
    return t(f"view.unit.{DISPLAY_UNITS[kind]}", lang)
