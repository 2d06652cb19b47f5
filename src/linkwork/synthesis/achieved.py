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

import numpy as np

if TYPE_CHECKING:
    from linkwork.motion.kinematics import Kinematics

#: The requirements the analysis measures, and how they are compared: "equal" or a bound.
MEASURED = {"stroke": "equal", "swing": "equal", "time_ratio": "equal", "max_pressure_angle": "at most",
            "min_transmission_angle": "at least", "upper_stroke": "equal", "lower_stroke": "equal",
            "overlap": "equal", "opening": "equal"}  # fmt: skip

#: Relative agreement of an equality the report calls met.
MET = 1e-6


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
    measured = _measured(kin, kind)
    rows = []
    for name, value in given.items():
        if name == "kind" or name == "criterion":
            continue
        quantity = QUANTITIES.get(name, "ratio")
        asked = float(value) if quantity == "ratio" or not isinstance(value, str) else parse_quantity(value, quantity)
        got = measured.get(name)
        sense = MEASURED.get(name, "given") if got is not None else "given"
        rows.append(Row(name, asked, got, quantity, sense, None if got is None else _met(sense, asked, got)))
    return kind, rows


def _met(sense: str, asked: float, got: float) -> bool:
    if sense == "at most":
        return got <= asked * (1 + MET)
    if sense == "at least":
        return got >= asked * (1 - MET)
    return abs(got - asked) <= MET * max(abs(asked), 1e-12)


def _measured(kin: Kinematics, kind: str) -> dict[str, float]:
    """What the analysis measures of the working member over ``kin``: stroke or swing, time ratio, the largest
    pressure angle (of the dyads driving a slider, else of all) and the least transmission angle; the knives'
    quantities for the shears."""
    from linkwork.motion.analysis import extremes, transmission, working

    out: dict[str, float] = {}
    members = working(kin.mechanism)
    found = {e.name: e for e in extremes(kin)}
    if members and members[0].name in found:
        e = found[members[0].name]
        out["stroke" if e.kind == "slider" else "swing"] = e.stroke
        out["time_ratio"] = e.time_ratio
    angles = transmission(kin)
    if angles:
        least = {k: float(np.nanmin(v)) for k, v in angles.items()}
        sliding = [v for k, v in least.items() if k.endswith("RRP")] or list(least.values())
        out["max_pressure_angle"] = math.pi / 2 - min(sliding)
        out["min_transmission_angle"] = min(least.values())
    if kind == "double-cut-shears":
        out.update(_knives(kin))
    return out


def _knives(kin: Kinematics) -> dict[str, float]:
    from linkwork.design.evaluate import Evaluation
    from linkwork.design.metrics import METRICS

    ev = Evaluation(kin)

    def one(name: str, arg: str | None = None) -> float:
        return float(np.squeeze(METRICS[name].compute(ev, arg)))

    return {"upper_stroke": one("stroke", "guide_E"), "lower_stroke": one("stroke", "guide_F"),
            "time_ratio": one("working_time_ratio"), "overlap": one("knife_overlap"),
            "opening": one("knife_clearance")}  # fmt: skip


def written(kind: str, requirements: dict[str, float], extra: dict[str, str] | None = None) -> dict[str, Any]:
    """The ``requirements:`` mapping a synthesised file carries: its kind, then each requirement (SI) in the
    unit people read it in (mm, deg, N, N*m; ratios bare), 12 significant digits."""
    from linkwork.synthesis.common import QUANTITIES

    units = {"length": (1e3, "mm"), "angle": (180 / math.pi, "deg"), "force": (1.0, "N"), "moment": (1.0, "N*m")}
    out: dict[str, Any] = {"kind": kind}
    for name, value in requirements.items():
        quantity = QUANTITIES.get(name)
        if quantity in units:
            factor, unit = units[quantity]
            out[name] = f"{value * factor:.12g} {unit}"
        else:
            out[name] = float(f"{value:.12g}")
    return out | (extra or {})


#: Members of a family the viewer's slider offers.
FAMILY_MEMBERS = 41


def family_members(spec: Any) -> dict[str, Any] | None:
    """The one-parameter family a synthesised slider-crank's requirements leave (stroke and time ratio without
    rod ratio or offset), as edits of the file's named parameters, for the viewer's slider: ``parameter`` and
    ``unit`` of the free parameter, its ``values``, each member's ``overrides`` (SI) and largest pressure angle
    (``alpha``, deg), and ``picked``, the member nearest the file's crank.  None for any other file."""
    from linkwork.synthesis.common import crank_angle_between_limits
    from linkwork.synthesis.slider_crank import family
    from linkwork.units import parse_quantity

    given = getattr(spec, "requirements", None) if spec is not None else None
    if not given or given.get("kind") != "slider-crank" or "rod_ratio" in given or "offset" in given:
        return None
    stroke = given.get("stroke")
    stroke = parse_quantity(stroke, "length") if isinstance(stroke, str) else float(stroke)
    ratio = float(given.get("time_ratio", 1.0))
    if crank_angle_between_limits(ratio) <= 0:
        return None
    f = family(stroke, ratio, count=FAMILY_MEMBERS)
    c = f.columns
    ok = np.isfinite(c["largest_pressure_angle"])
    crank = next((float(link.length) for name, link in spec.links.items() if name == "crank"), math.nan)
    members = [{"links.crank.length": float(r), "links.rod.length": float(ell), "joints.guide.through.x": -float(e)}
               for r, ell, e in zip(c["crank"][ok], c["rod"][ok], c["offset"][ok], strict=True)]  # fmt: skip
    picked = int(np.argmin(np.abs(c["crank"][ok] - crank))) if math.isfinite(crank) else 0
    return {"parameter": f.parameter, "unit": "deg", "values": np.degrees(f.values[ok]).tolist(),
            "overrides": members, "alpha": np.degrees(c["largest_pressure_angle"][ok]).tolist(),
            "picked": picked}  # fmt: skip
