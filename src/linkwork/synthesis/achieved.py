"""The requirements a mechanism file carries (``requirements:``, written by ``linkwork synthesize``) and what the
mechanism achieves, as the analysis measures it: the rows of the report's requirements section.

A requirement of motion (a stroke, a swing, a time ratio, a bound on the pressure or transmission angle, the
knives' strokes, overlap and opening) is measured on a whole turn of the crank by the same functions the
analysis reports (:mod:`linkwork.motion.analysis`, the design metrics for the knives); a requirement of
dimensions or loads (a rod ratio, an offset, a frame, a force) is stated as the file carries it.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from linkwork.synthesis.rounding import measure

if TYPE_CHECKING:
    from linkwork.motion.kinematic_analysis import Kinematics

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
#: :func:`~linkwork.synthesis.rounding.rounding_tolerances`).
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


def requirement_rows(kin: Kinematics) -> tuple[str, list[Row]] | None:
    """(kind, rows) of the requirements of ``kin``'s mechanism file over the whole turn ``kin``; None where
    the file carries none."""
    from linkwork.synthesis.common import QUANTITIES
    from linkwork.units import parse_quantity

    spec = kin.mechanism.spec
    given: dict[str, Any] | None = getattr(spec, "requirements", None) if spec is not None else None
    if not given:
        return None
    kind = str(given.get("kind", ""))
    measured = measure(kin, kind)
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
    from linkwork.synthesis.common import QUANTITIES, up

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


#: Members of a family the viewer's slider offers.
FAMILY_MEMBERS = 41

#: The least transmission angle of a crank-rocker member the slider offers: nearer a dead point the stretched
#: and folded positions are ill-conditioned and the measured swing and time ratio lose digits.
LEAST_OFFERED = math.radians(10.0)


def family_members(spec: Any, lang: str = "en") -> dict[str, Any] | None:
    """The one-parameter family a synthesised file's requirements leave, as edits of the file's named
    parameters, for the viewer's slider: ``parameter`` and ``unit`` of the free parameter, its ``values``,
    each member's ``overrides`` (SI), ``quantity`` (the criterion's angle) and its ``quantity_values`` (deg),
    ``picked``, the member of the file, and a ``note`` on which members are offered.  A slider-crank whose
    requirements leave rod ratio and offset free, a crank-rocker, a slotted lever whose frame and crank are left
    free, double-cut shears whose crank is left free
    (solved again, seconds, once a set of requirements); None for any other file.  Its texts in ``lang``."""
    given: dict[str, Any] = (getattr(spec, "requirements", None) if spec is not None else None) or {}
    kind = given.get("kind")
    if kind == "slider-crank":
        return _said(_slider_crank_family(spec, given), lang)
    if kind == "crank-rocker":
        return _said(_crank_rocker_family(spec, given), lang)
    if kind == "double-cut-shears":
        return _said(_shears_family(spec, given), lang)
    if kind == "slotted-lever":
        return _said(_slotted_lever_family(spec, given), lang)
    return None


def _said(family: dict[str, Any] | None, lang: str) -> dict[str, Any] | None:
    """``family`` with its texts (``parameter``, ``quantity``, ``note``: keys of :mod:`linkwork.lang`'s catalogues
    as the families give them) and its unit in ``lang``."""
    if family is None:
        return None
    from linkwork.lang import t

    said = {key: t(family[key], lang) for key in ("parameter", "quantity", "note")}
    units = {"unit_shown": family["unit"], "quantity_unit_shown": family.get("quantity_unit", "deg")}
    return {**family, **said, **{key: t(f"family.unit.{unit}", lang) for key, unit in units.items()}}


def _si(given: dict[str, Any], name: str, kind: str) -> float | None:
    """The requirement ``name`` (SI), None where the file does not give it."""
    from linkwork.units import parse_quantity

    value = given.get(name)
    if value is None:
        return None
    return parse_quantity(value, kind) if isinstance(value, str) else float(value)


def _slider_crank_family(spec: Any, given: dict[str, Any]) -> dict[str, Any] | None:
    """The slider-crank's family over the angle O B1 B2 (stroke and time ratio without rod ratio or offset)."""
    from linkwork.synthesis.common import crank_angle_between_limits
    from linkwork.synthesis.slider_crank import family

    if "rod_ratio" in given or "offset" in given:
        return None
    stroke = _si(given, "stroke", "length")
    ratio = float(given.get("time_ratio", 1.0))
    if stroke is None or crank_angle_between_limits(ratio) <= 0:
        return None
    f = family(stroke, ratio, count=FAMILY_MEMBERS)
    c = f.columns
    ok = np.isfinite(c["largest_pressure_angle"])
    crank = next((float(link.length) for name, link in spec.links.items() if name == "crank"), math.nan)
    members = [
        {"links.crank.length": float(r), "links.rod.length": float(ell), "joints.guide.through.x": -float(e)}
        for r, ell, e in zip(c["crank"][ok], c["rod"][ok], c["offset"][ok], strict=True)
    ]
    picked = int(np.argmin(np.abs(c["crank"][ok] - crank))) if math.isfinite(crank) else 0
    return {
        "parameter": "family.parameter.angle_OB1B2",
        "unit": "deg",
        "values": np.degrees(f.values[ok]).tolist(),
        "overrides": members,
        "quantity": "synth.quantity.largest_pressure_angle",
        "quantity_values": np.degrees(c["largest_pressure_angle"][ok]).tolist(),
        "picked": picked,
        "note": "family.note.every_member",
    }


def _crank_rocker_family(spec: Any, given: dict[str, Any]) -> dict[str, Any] | None:
    """The crank-rocker's family over t = |O2 B_f| on the side of the chord B_e B_f the file's crank pivot is on
    (the members on the other side run, in the file's assembly mode, the slow stroke the other way: they need
    the other mode, which no named parameter sets), scaled as the file is (by its rocker or its frame), with a
    least transmission angle of at least :data:`LEAST_OFFERED` and the file's bound; the file's own member
    among them."""
    from linkwork.synthesis.common import crank_angle_between_limits
    from linkwork.synthesis.crank_rocker import members, top

    swing, ratio = _si(given, "swing", "angle"), float(given.get("time_ratio", 1.0))
    links = {name: float(link.length) for name, link in spec.links.items() if link.length is not None}
    if swing is None or not {"crank", "coupler", "rocker"} <= links.keys() or "O4" not in spec.frame.points:
        return None
    theta = crank_angle_between_limits(ratio)
    a, b, c = links["crank"], links["coupler"], links["rocker"]
    d = float(spec.frame.points["O4"][0])
    own = (b - a) / c
    side = min((1.0, -1.0), key=lambda s: abs(float(members(swing, theta, np.array([own]), s)["frame"][0]) - d / c))
    floor = max(LEAST_OFFERED, _si(given, "min_transmission_angle", "angle") or 0.0)
    fine = np.linspace(0.0, top(theta, swing), 2001)[1:-1]
    m = members(swing, theta, fine, side)
    ok = fine[m["valid"] & (m["least_transmission_angle"] >= floor)]
    t = np.unique(np.concatenate([np.linspace(ok.min(), ok.max(), FAMILY_MEMBERS) if len(ok) else [], [own]]))
    m = members(swing, theta, t, side)
    keep = m["valid"] & ((m["least_transmission_angle"] >= floor) | (t == own))
    t, m = t[keep], {k: v[keep] for k, v in m.items()}
    if not len(t):
        return None
    scale = c * np.ones_like(t) if "frame" not in given else d / m["frame"]
    overrides = [
        {
            "links.crank.length": float(x * s),
            "links.coupler.length": float(y * s),
            "links.rocker.length": float(s),
            "frame.points.O4.x": float(z * s),
        }
        for x, y, z, s in zip(m["crank"], m["coupler"], m["frame"], scale, strict=True)
    ]
    return {
        "parameter": "family.parameter.O2Bf",
        "unit": "mm",
        "values": (t * scale * 1e3).tolist(),
        "overrides": overrides,
        "quantity": "synth.quantity.least_transmission_angle",
        "quantity_values": np.degrees(m["least_transmission_angle"]).tolist(),
        "picked": int(np.argmin(np.abs(t - own))),
        "note": "family.note.crank_rocker_side",
    }


def _slotted_lever_family(spec: Any, given: dict[str, Any]) -> dict[str, Any] | None:
    """The slotted lever's family over the frame d (stroke and time ratio without frame or crank): the crank
    r = d sin(theta / 2) with each d, the lever, guide and rod as the file has them (neither the stroke nor K
    depends on d while the block reaches no further than the rule allows, d + r <= 0.9 L)."""
    from linkwork.synthesis.slotted_lever import family

    stroke, ratio = _si(given, "stroke", "length"), float(given.get("time_ratio", 1.0))
    if stroke is None or "frame" in given or "crank" in given or "O1" not in spec.frame.points or ratio <= 1:
        return None
    f = family(stroke, ratio, count=FAMILY_MEMBERS)
    d, r = f.values, f.columns["crank"]
    overrides = [{"frame.points.O1.y": float(x), "links.crank.length": float(y)} for x, y in zip(d, r, strict=True)]
    own = float(spec.frame.points["O1"][1])
    return {
        "parameter": "family.parameter.frame_d",
        "unit": "mm",
        "values": (d * 1e3).tolist(),
        "overrides": overrides,
        "quantity": "family.quantity.least_block_distance",
        "quantity_unit": "mm",
        "quantity_values": (f.columns["least_block_distance"] * 1e3).tolist(),
        "picked": int(np.argmin(np.abs(d - own))),
        "note": "family.note.every_member",
    }


def _shears_family(spec: Any, given: dict[str, Any]) -> dict[str, Any] | None:
    """The double-cut shears' family over the crank length (no ``crank`` requirement): the members the
    synthesis's continuation solves, as edits of the named parameters it sets."""
    from linkwork.errors import SynthesisError
    from linkwork.synthesis.shears import _requirements

    upper, lower = _si(given, "upper_stroke", "length"), _si(given, "lower_stroke", "length")
    if "crank" in given or upper is None or lower is None or "crank" not in spec.links:
        return None
    ratio = float(given.get("time_ratio", 1.0))
    try:
        overlap = _requirements(upper, lower, ratio, _si(given, "overlap", "length"), _si(given, "opening", "length"))
    except SynthesisError:
        return None
    cranks, overrides, least = _shears_members(upper, lower, ratio, overlap)
    if not overrides:
        return None
    return {
        "parameter": "family.parameter.crank_length",
        "unit": "mm",
        "values": [c * 1e3 for c in cranks],
        "overrides": overrides,
        "quantity": "synth.quantity.least_transmission_angle",
        "quantity_values": least,
        "picked": int(np.argmin(np.abs(np.array(cranks) - float(spec.links["crank"].length)))),
        "note": "family.note.shears",
    }


@functools.lru_cache(maxsize=8)
def _shears_members(upper: float, lower: float, ratio: float, overlap: float) -> tuple[list, list, list]:
    """(crank lengths, overrides, least transmission angles (deg)) of the solved members of the shears' family."""
    from linkwork.synthesis.shears import member_values, solved_family

    cranks, unknowns, found = solved_family(upper, lower, ratio, overlap)
    ok = np.flatnonzero(np.isfinite(unknowns[:, 0]) & np.isfinite(found.get("min_transmission_angle", np.nan)))
    least = np.degrees(found["min_transmission_angle"][ok]).tolist() if len(ok) else []
    return cranks[ok].tolist(), member_values(cranks[ok], unknowns[ok]), least
