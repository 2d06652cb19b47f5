"""The one-parameter family a synthesised file's requirements leave, for the viewer's slider: each kind's members
as edits of the file's named parameters (:attr:`linkwork.synthesis.kinds.Kind.family`)."""

from __future__ import annotations

import functools
import math
from typing import Any

import numpy as np

#: Members of a family the viewer's slider offers.
FAMILY_MEMBERS = 41

#: The least transmission angle of a crank-rocker member the slider offers: nearer a dead point the stretched
#: and folded positions are ill-conditioned and the measured swing and time ratio lose digits.
LEAST_OFFERED = math.radians(10.0)


def _si(given: dict[str, Any], name: str, kind: str) -> float | None:
    """The requirement ``name`` (SI), None where the file does not give it."""
    from linkwork.units import parse_quantity

    value = given.get(name)
    if value is None:
        return None
    return parse_quantity(value, kind) if isinstance(value, str) else float(value)


def slider_crank_family(spec: Any, given: dict[str, Any]) -> dict[str, Any] | None:
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


def crank_rocker_family(spec: Any, given: dict[str, Any]) -> dict[str, Any] | None:
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


def slotted_lever_family(spec: Any, given: dict[str, Any]) -> dict[str, Any] | None:
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


def shears_family(spec: Any, given: dict[str, Any]) -> dict[str, Any] | None:
    """The double-cut shears' family over the crank length (no ``crank`` requirement): the members the
    synthesis's continuation solves, as edits of the named parameters it sets."""
    from linkwork.errors import SynthesisError
    from linkwork.spec.shears import shears_parts
    from linkwork.synthesis.shears import _requirements, bundled

    upper, lower = _si(given, "upper_stroke", "length"), _si(given, "lower_stroke", "length")
    names = shears_parts(spec)
    if isinstance(names, str) or "crank" in given or upper is None or lower is None or names.paths != bundled().paths:
        return None  # the members are edits of the bundled file's parameters: of a file with its names
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
        "picked": int(np.argmin(np.abs(np.array(cranks) - float(spec.links[names.crank].length)))),
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
