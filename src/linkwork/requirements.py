"""What each kind of synthesis takes: one typed record per kind, the one home of its requirements.

Each field of a record is a requirement (or a choice of how the file makes its mechanism) with its kind of
quantity, its default (none: required), whether it sets the mechanism's scale and a one-line help.  From the
records follow the names ``lw.synthesize`` accepts and requires, the units it reads strings in, the options of
``linkwork synthesize`` and their help, the names a file's ``requirements:`` may carry for each kind
(:mod:`linkwork.spec.requirements`) and the manual's table of them (:func:`table`).  The kinds' ``synthesize``
functions take their record (:mod:`linkwork.synthesis.kinds`).

This module imports nothing heavy: the command line reads it to build its options.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any

from linkwork.limits import MAX_MAGNITUDE

#: Density of steel (kg/m^3), and the default bar section (m): every link a steel bar of this section.
STEEL = 7850.0
BAR = (0.040, 0.020)

#: The kinds of quantity a requirement carries with its unit (a bare number refused); ``ratio`` a plain number.
UNITS = ("length", "angle", "force", "moment")

#: An example of each kind of quantity, as a message suggesting its unit writes it.
EXAMPLES = {"length": "400 mm", "angle": "60 deg", "force": "20 kN", "moment": "500 N*m"}

#: The other kinds of field as the manual's table names them.
SHOWN = {
    "ratio": "ratio (a plain number)",
    "word": "word",
    "angular_speed": "angular speed, e.g. `60 rpm`",
    "section": "width and height (m); `40mm x 20mm` on the command line",
    "density": "density (kg/m^3)",
    "mass": "mass (kg)",
}

#: The command's own options of the fields of how the file is made (a speed kept as written, a section of two).
OWN_OPTIONS = {"angular_speed": "--speed", "section": "--section"}

#: How a field says what it is: a ``word`` (``criterion``) is an option but no quantity; the fields of how the
#: file makes its mechanism (``angular_speed``, ``section``, ``density``, ``mass``) are no requirement a file
#: carries, and the command line gives them options of its own (``--speed``, ``--section``) or none.
MAKING = ("angular_speed", "section", "density", "mass")


#: A range a file's requirement lies in (SI): (low, high, low included, high included).
Range = tuple[float, float, bool, bool]
ANY: Range = (-MAX_MAGNITUDE, MAX_MAGNITUDE, True, True)
POSITIVE: Range = (0.0, MAX_MAGNITUDE, False, True)
#: A time ratio: the slower stroke's time over the faster.
SLOWER: Range = (1.0, MAX_MAGNITUDE, True, True)
#: A bound on the pressure angle, and a least transmission angle.
PRESSURE: Range = (0.0, math.pi / 2, False, False)
TRANSMISSION: Range = (0.0, math.pi / 2, False, True)
#: A swing.
SWING: Range = (0.0, math.pi, False, False)
#: A slider-crank's time ratio: its crank turns theta = asin(e / (l - r)) - asin(e / (l + r)) < 90 deg between its
#: limit positions, so K = (180 + theta) / (180 - theta) < 3.
CRANK_SLIDER: Range = (1.0, 3.0, True, False)


@dataclass(frozen=True)
class Need:
    """What a field of a requirements record is: its kind of ``quantity`` (:data:`UNITS`, ``"ratio"``, ``"word"`` or
    one of :data:`MAKING`), its ``help`` (one line), whether it sets the mechanism's ``scale`` (the step its
    file is dimensioned to: :func:`~linkwork.synthesis.common.dimensioned`) and the range a file's
    ``requirements:`` may give it in (``within``, SI: :func:`linkwork.spec.requirements.requirement_problem`)."""

    quantity: str
    help: str
    scale: bool = False
    within: Range = ANY

    @property
    def carried(self) -> bool:
        """Whether a file's ``requirements:`` carries it (a quantity or a ratio: not how the file is made)."""
        return self.quantity in UNITS or self.quantity == "ratio"

    @property
    def option(self) -> bool:
        """Whether ``linkwork synthesize`` offers it as a generated ``--NAME`` option."""
        return self.carried or self.quantity == "word"

    def flag(self, name: str) -> str:
        """The option of ``linkwork synthesize`` that gives the field ``name`` (``""``: none)."""
        return f"--{name.replace('_', '-')}" if self.option else OWN_OPTIONS.get(self.quantity, "")

    @property
    def shown(self) -> str:
        """Its kind of quantity as the manual's table says it, with an example of its unit."""
        if self.quantity in EXAMPLES:
            return f"{self.quantity}, e.g. `{EXAMPLES[self.quantity]}`"
        return SHOWN[self.quantity]


def need(
    quantity: str,
    help: str,  # noqa: A002
    default: Any = dataclasses.MISSING,
    scale: bool = False,
    within: Range | None = None,
) -> Any:
    """A field of a requirements record: required unless ``default`` is given; a length, force or moment is
    positive and a ratio a time ratio unless ``within`` says otherwise."""
    if within is None:
        within = POSITIVE if quantity in ("length", "force", "moment") else SLOWER if quantity == "ratio" else ANY
    return dataclasses.field(default=default, metadata={"need": Need(quantity, help, scale, within)})


_RATIO = "K >= 1: the longer stroke's time over the shorter"
_RULE = "the least transmission angle of every dyad over the turn (the design rule, 40 deg unless given)"
_SPEED = "the crank's speed written in the file"
_SECTION = "the steel bars' section (width, height)"
_DENSITY = "the bars' density"
_CRITERION = "how the member is picked from the family: 'pressure' (the default) or 'torque'"


@dataclass(frozen=True)
class SliderCrankRequirements:
    """An offset slider-crank's requirements (SI): :func:`linkwork.synthesis.slider_crank.synthesize`."""

    stroke: float = need("length", "the ram's stroke", scale=True)
    time_ratio: float = need("ratio", "1 <= K < 3: the longer stroke's time over the shorter", within=CRANK_SLIDER)
    rod_ratio: float | None = need("ratio", "r/l (or the offset)", None, within=POSITIVE)
    offset: float | None = need(
        "length", "the guide's offset from the crank pivot (or the rod ratio)", None, within=ANY
    )
    max_pressure_angle: float | None = need("angle", "a bound on the largest pressure angle", None, within=PRESSURE)
    min_transmission_angle: float | None = need("angle", _RULE, None, within=TRANSMISSION)
    speed: str = need("angular_speed", _SPEED, "60 rpm")
    section: tuple[float, float] = need("section", _SECTION, BAR)
    density: float = need("density", _DENSITY, STEEL)
    ram_mass: float | None = need("mass", "the ram's mass (the rod's unless given)", None)
    force: float | None = need("force", "the working load, over the last 'working' of the downward stroke", None)
    working: float | None = need(
        "length", "the last part of the stroke the load acts over (the whole unless given)", None
    )
    criterion: str = need("word", _CRITERION, "pressure")


@dataclass(frozen=True)
class CrankRockerRequirements:
    """A crank-rocker's requirements (SI): :func:`linkwork.synthesis.crank_rocker.synthesize`."""

    swing: float = need("angle", "the rocker's swing", within=SWING)
    time_ratio: float = need("ratio", _RATIO)
    rocker: float | None = need("length", "the rocker's length (or the frame)", None, scale=True)
    frame: float | None = need("length", "the frame's length (or the rocker)", None, scale=True)
    min_transmission_angle: float | None = need("angle", _RULE, None, within=TRANSMISSION)
    speed: str = need("angular_speed", _SPEED, "60 rpm")
    section: tuple[float, float] = need("section", _SECTION, BAR)
    density: float = need("density", _DENSITY, STEEL)


@dataclass(frozen=True)
class SlottedLeverRequirements:
    """A slotted-lever quick return's requirements (SI): :func:`linkwork.synthesis.slotted_lever.synthesize`."""

    stroke: float = need("length", "the ram's stroke", scale=True)
    time_ratio: float = need("ratio", "K > 1: the longer stroke's time over the shorter")
    frame: float | None = need(
        "length", "the frame, crank pivot to lever pivot (or the crank; else the greatest)", None, scale=True
    )
    crank: float | None = need("length", "the crank's length (or the frame)", None)
    rod: float | None = need("length", "the ram's rod's length (else the shortest meeting the bound)", None)
    max_pressure_angle: float | None = need(
        "angle", "a bound on the rod's largest pressure angle (10 deg unless given)", None, within=PRESSURE
    )
    min_transmission_angle: float | None = need("angle", _RULE, None, within=TRANSMISSION)
    speed: str = need("angular_speed", _SPEED, "60 rpm")
    section: tuple[float, float] = need("section", _SECTION, BAR)
    density: float = need("density", _DENSITY, STEEL)
    ram_mass: float | None = need("mass", "the ram's mass (the rod's unless given)", None)


@dataclass(frozen=True)
class TogglePressRequirements:
    """A knuckle-joint press's requirements (SI): :func:`linkwork.synthesis.toggle_press.synthesize`."""

    stroke: float = need("length", "the ram's stroke", scale=True)
    force: float = need("force", "the nominal force")
    before: float = need("length", "where the nominal force acts, before the bottom dead centre")
    torque: float = need("moment", "the crank's torque limit over the turn")
    swing: float | None = need("angle", "the upper toggle link's swing (45 deg unless given)", None, within=SWING)
    time_ratio: float | None = need("ratio", "the four-bar's time ratio (1.2 unless given)", None)
    min_transmission_angle: float | None = need("angle", _RULE, None, within=TRANSMISSION)
    speed: str = need("angular_speed", _SPEED, "60 rpm")
    section: tuple[float, float] = need("section", _SECTION, BAR)
    density: float = need("density", _DENSITY, STEEL)


@dataclass(frozen=True)
class ShearsRequirements:
    """The double-cut shears' requirements (SI): :func:`linkwork.synthesis.shears.synthesize`."""

    upper_stroke: float = need("length", "the upper knife's stroke", scale=True)
    lower_stroke: float = need("length", "the lower knife's stroke", scale=True)
    time_ratio: float = need("ratio", "the knives' closing time over their opening time", within=POSITIVE)
    overlap: float | None = need("length", "the knives' overlap when closed (or the opening)", None, within=ANY)
    opening: float | None = need("length", "the gap between the knives when open (or the overlap)", None)
    crank: float | None = need("length", "the crank's length (else picked by the criterion)", None)
    criterion: str = need("word", _CRITERION, "pressure")
    min_transmission_angle: float | None = need("angle", _RULE, None, within=TRANSMISSION)
    speed: str | None = need(
        "angular_speed", "the crank's speed written in the file (the bundled file's unless given)", None
    )


#: The kinds synthesised, in the order they are listed, and each kind's requirements.
RECORDS: dict[str, type] = {
    "slider-crank": SliderCrankRequirements,
    "crank-rocker": CrankRockerRequirements,
    "slotted-lever": SlottedLeverRequirements,
    "toggle-press": TogglePressRequirements,
    "double-cut-shears": ShearsRequirements,
}


def needs(kind: str) -> dict[str, Need]:
    """The fields of ``kind``'s record, in order: name -> :class:`Need`."""
    return {f.name: f.metadata["need"] for f in dataclasses.fields(RECORDS[kind])}


def required(kind: str) -> list[str]:
    """The names ``kind`` cannot do without (its record's fields without a default)."""
    fields = dataclasses.fields(RECORDS[kind])
    return [f.name for f in fields if f.default is dataclasses.MISSING and f.default_factory is dataclasses.MISSING]


def defaults(kind: str) -> dict[str, Any]:
    """The defaults of ``kind``'s record: name -> value (the required fields left out)."""
    return {f.name: f.default for f in dataclasses.fields(RECORDS[kind]) if f.default is not dataclasses.MISSING}


def carried(kind: str) -> tuple[str, ...]:
    """The requirements a file's ``requirements:`` of ``kind`` may carry (besides ``kind`` and ``criterion``)."""
    return tuple(name for name, n in needs(kind).items() if n.carried)


#: The kind of quantity of each requirement that has a unit (:data:`UNITS`), over every kind.
QUANTITIES: dict[str, str] = {
    name: n.quantity for kind in RECORDS for name, n in needs(kind).items() if n.quantity in UNITS
}


def options() -> dict[str, tuple[str, str]]:
    """The ``--NAME`` options of ``linkwork synthesize``: name -> (kind of quantity, help), in the order the kinds
    first name them; the help names the kinds each text is of, and the unit a quantity is given in."""
    texts: dict[str, dict[str, list[str]]] = {}
    quantity: dict[str, str] = {}
    for kind in RECORDS:
        for name, n in needs(kind).items():
            if n.option:
                texts.setdefault(name, {}).setdefault(n.help, []).append(kind)
                quantity[name] = n.quantity
    out = {}
    for name, by_text in texts.items():
        said = "; ".join(f"{_kinds(kinds)}: {text}" for text, kinds in by_text.items())
        example = EXAMPLES.get(quantity[name])
        article = "an" if quantity[name][0] in "aeiou" else "a"
        out[name] = (quantity[name], f'{said} ({article} {quantity[name]}, e.g. "{example}")' if example else said)
    return out


def _kinds(kinds: list[str]) -> str:
    return "every kind" if len(kinds) == len(RECORDS) else ", ".join(kinds)


def table() -> str:
    """The manual's table of every kind's requirements (markdown): each field's option, kind of quantity,
    default and help."""
    rows = ["| kind | requirement | option | quantity | default | meaning |", "| --- | --- | --- | --- | --- | --- |"]
    for kind in RECORDS:
        fixed = defaults(kind)
        for name, n in needs(kind).items():
            option = f"`{n.flag(name)}`" if n.flag(name) else ""
            default = "required" if name not in fixed else "" if fixed[name] is None else f"`{fixed[name]}`"
            rows.append(f"| `{kind}` | `{name}` | {option} | {n.shown} | {default} | {n.help} |")
    return "\n".join(rows) + "\n"
