"""The requirements a mechanism file carries (``requirements:``, written by ``linkwork synthesize``) and what the
mechanism achieves, as the analysis measures it: the rows of the report's requirements section.

A requirement of motion (a stroke, a swing, a time ratio, a bound on the pressure or transmission angle, the
knives' strokes, overlap and opening) is measured on a whole turn of the crank by the same functions the
analysis reports (:mod:`linkwork.motion.analysis`, the design metrics for the knives); a requirement of
dimensions or loads (a rod ratio, an offset, a frame, a force) is stated as the file carries it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from linkwork.synthesis.measuring import measure

if TYPE_CHECKING:
    from linkwork.motion.kinematic_analysis import Kinematics
    from linkwork.spec.schema import Spec

#: The requirements the analysis measures, and how they are compared: "equal" or a bound.
MEASURED = {
    "stroke": "equal",
    "swing": "equal",
    "time_ratio": "equal",
    "max_pressure_angle": "at most",
    "min_transmission_angle": "at least",
    "upper_stroke": "equal",
    "lower_stroke": "equal",
    "overlap": "equal",
    "opening": "equal",
}

#: Relative agreement of an equality the report calls met, for a file that states no tolerance of its own (a
#: synthesised file states the one its lengths' rounding implies:
#: :func:`~linkwork.synthesis.rounding.measure_written`).
MET = 1e-6

#: The suffix of a requirement's tolerance in a file's ``requirements:`` (``stroke_tolerance: "0.012 mm"``).
SUFFIX = "_tolerance"


@dataclass(frozen=True)
class Row:
    """One requirement: its ``name``, the ``asked`` value (SI), what the mechanism ``achieves`` (SI; None where
    the analysis does not measure it), its ``kind`` of quantity, ``sense`` (``"equal"``, ``"at most"``,
    ``"at least"`` or ``"given"``) and whether it is ``met`` (None where not measured)."""

    name: str
    asked: float
    achieved: float | None
    kind: str
    sense: str
    met: bool | None
    tolerance: float | None = None


def requirement_rows(kin: Kinematics, spec: Spec | None) -> tuple[str, list[Row]] | None:
    """(kind, rows) of the requirements of the mechanism file ``spec`` over the whole turn ``kin`` of its
    mechanism, as :func:`~linkwork.synthesis.measuring.measure` measures it (the synthesis's verification's
    measurement); None where the file carries none."""
    from linkwork.requirements import QUANTITIES
    from linkwork.units import parse_quantity

    given: dict[str, Any] | None = getattr(spec, "requirements", None) if spec is not None else None
    if not given or spec is None:
        return None
    from linkwork.synthesis.kinds import KINDS

    kind = str(given.get("kind", ""))
    (measured, *_) = measure(kin, spec, KINDS[kind].measure if kind in KINDS else None)
    rows = []

    def si(name: str, value: Any) -> float:
        quantity = QUANTITIES.get(name.removesuffix(SUFFIX), "ratio")
        return float(value) if quantity == "ratio" or not isinstance(value, str) else parse_quantity(value, quantity)

    for name, value in given.items():
        if name in ("kind", "criterion") or name.endswith(SUFFIX):
            continue
        asked, got = si(name, value), measured.get(name)
        tol = si(name + SUFFIX, given[name + SUFFIX]) if name + SUFFIX in given else None
        sense = MEASURED.get(name, "given") if got is not None else "given"
        met = None if got is None else _met(sense, asked, got, tol)
        rows.append(Row(name, asked, got, QUANTITIES.get(name, "ratio"), sense, met, tol))
    return kind, rows


def _met(sense: str, asked: float, got: float, tolerance: float | None = None) -> bool:
    """Whether ``got`` meets ``asked`` in ``sense`` within ``tolerance`` (SI; else :data:`MET` relative)."""
    tol = MET * max(abs(asked), 1e-12) if tolerance is None else tolerance
    if sense == "at most":
        return got <= asked + tol
    if sense == "at least":
        return got >= asked - tol
    return abs(got - asked) <= tol


def written(
    kind: str,
    requirements: dict[str, float],
    extra: dict[str, str] | None = None,
    tolerances: dict[str, float] | None = None,
) -> dict[str, Any]:
    """The ``requirements:`` mapping a synthesised file carries: its kind, then each requirement (SI) in the
    unit people read it in (mm, deg, N, N*m; ratios bare), 12 significant digits, each measured one followed by
    its ``<name>_tolerance`` from ``tolerances`` (SI) where given, 3 significant digits rounded up."""
    from linkwork.requirements import QUANTITIES
    from linkwork.synthesis.common import up

    units = {"length": (1e3, "mm"), "angle": (180 / math.pi, "deg"), "force": (1.0, "N"), "moment": (1.0, "N*m")}
    out: dict[str, Any] = {"kind": kind}

    def text(name: str, value: float, digits: int = 12) -> Any:
        quantity = QUANTITIES.get(name)
        shown = f"{value:.{digits}g}" if digits == 12 else up(value, digits)
        if quantity in units:
            factor, unit = units[quantity]
            shown = f"{value * factor:.12g}" if digits == 12 else up(value * factor, digits)
            return f"{shown} {unit}"
        return float(shown)

    for name, value in requirements.items():
        out[name] = text(name, value)
        if tolerances and name in tolerances and name in MEASURED:
            out[name + SUFFIX] = text(name, tolerances[name], 3)
    return out | (extra or {})


def family_members(spec: Any, lang: str = "en") -> dict[str, Any] | None:
    """The one-parameter family a synthesised file's requirements leave, as edits of the file's named
    parameters, for the viewer's slider: ``parameter`` and ``unit`` of the free parameter, its ``values``,
    each member's ``overrides`` (SI), ``quantity`` (the criterion's angle) and its ``quantity_values`` (deg),
    ``picked``, the member of the file, and a ``note`` on which members are offered.  A slider-crank whose
    requirements leave rod ratio and offset free, a crank-rocker, a slotted lever whose frame and crank are left
    free, double-cut shears whose crank is left free
    (solved again, seconds, once a set of requirements); None for any other file.  Its texts in ``lang``."""
    given: dict[str, Any] = (getattr(spec, "requirements", None) if spec is not None else None) or {}
    from linkwork.synthesis.kinds import KINDS

    kind = KINDS.get(str(given.get("kind")))
    return _said(kind.family(spec, given), lang) if kind is not None and kind.family is not None else None


def _said(family: dict[str, Any] | None, lang: str) -> dict[str, Any] | None:
    """``family`` with its texts (``parameter``, ``quantity``, ``note``: keys of :mod:`linkwork.lang`'s catalogues
    as the families give them) and its unit in ``lang``."""
    if family is None:
        return None
    from linkwork.lang import t

    said = {key: t(family[key], lang) for key in ("parameter", "quantity", "note")}
    units = {"unit_shown": family["unit"], "quantity_unit_shown": family.get("quantity_unit", "deg")}
    return {**family, **said, **{key: t(f"family.unit.{unit}", lang) for key, unit in units.items()}}
