"""Synthesis of a slotted-lever quick return (crank-shaper) from the ram's stroke H and the time ratio K.

The mechanism: the crank O1 A turns about O1; a block on the crank pin A slides in the slot of the lever O2 C,
pivoted on the frame at O2 at the distance d below O1; the rod C D drives the ram D along a horizontal guide.

The theory (derived here):

* The lever is at its limit positions where its slot line is tangent to the crank circle (radius r about
  O1): there the block's distance from O2 is extreme in angle, the crank O1 A stands square to the lever,
  and sin(psi / 2) = r / d, psi the lever's swing (the angle between the two tangents from O2).
* The two tangent radii O1 A make the angle pi - psi at O1 (the quadrilateral O2 A' O1 A'' has right angles
  at the tangent points), so the crank turns pi + psi on one stroke and pi - psi on the other: theta = psi and
  K = (pi + psi) / (pi - psi), r = d sin(theta / 2); any K > 1 can be met, K = 1 needs r = 0.
* The lever's tip C (|O2 C| = L) at angle phi from the vertical is at (L sin phi, L cos phi); the ram
  x_D = L sin phi + sqrt(l^2 - (h - L cos phi)^2) for the rod l and the guide's height h above O2.  Its height
  term is even in phi, so the ram's stroke is H = 2 L sin(psi / 2) for every h and l, and the ram is at its
  ends exactly when the lever is (dx_D / dphi = L cos(phi + alpha) / cos(alpha) keeps its sign while
  |phi| + |alpha| < pi / 2): the ram's K is the lever's.
* The rod's pressure angle alpha (between the rod and the guide) has sin(alpha) = (h - L cos phi) / l, and
  L cos phi sweeps [L cos(psi / 2), L] over the swing: the largest |h - L cos phi| is least with the guide
  halfway down the arc's sagitta, h = L (1 + cos(psi / 2)) / 2, giving sin(alpha_max) = L (1 - cos(psi / 2))
  / (2 l), reached at both limit positions and with the lever upright.
* What H and K leave free: the scale d of the crank and frame (the family; the lever's angular motion, hence
  the driving torque for a given ram force, does not depend on it) and the rod's length l.  The pick: the
  greatest d that keeps the block's pin a tenth of the lever from its end, d + r = 0.9 L (:data:`BLOCK_MARGIN`:
  the block as far from O2 as the slot holds it, for the least force in the slot), unless the crank or the frame
  is given (then refused past 0.9 L); the shortest rod whose largest pressure
  angle is ``max_pressure_angle`` (10 deg unless given), unless the rod is given.

Layout of the file: the lever's pivot O2 at the origin, the crank's pivot O1 at (0, d), the ram's guide at the
height h pointing along +x, the rod reaching to +x of the lever; the crank turns counter-clockwise, so the slow
(working) stroke of the ram runs toward -x.
"""

from __future__ import annotations

import math

import numpy as np

from linkwork.errors import SynthesisError
from linkwork.requirements import SlottedLeverRequirements
from linkwork.synthesis.common import (
    LEAST_TRANSMISSION,
    Family,
    Making,
    Synthesis,
    bar_mass,
    below_rule,
    confirm,
    crank_angle_between_limits,
    deg,
    down,
    file_of,
    given,
    keep_rule,
    least_allowed,
    mm,
    proportions,
    rounded,
    up,
)
from linkwork.synthesis.rounding import measure_written

KIND = "slotted-lever"

#: The largest pressure angle of the ram's rod when neither it nor the rod is given (rad).
PRESSURE_ANGLE = math.radians(10.0)


#: The design rule of the block's reach: its pin comes no nearer the lever's end than this share of the lever,
#: d + r <= (1 - BLOCK_MARGIN) L.  The block is half its length beyond its pin and the lever's end carries the
#: pin C of the rod; with the block's pin at the tip (d + r = L) the block would run off the slot and into C.  A
#: tenth of the lever leaves a slot end of 0.1 L (70 mm on a 700 mm lever) past the block's pin at its reach.
BLOCK_MARGIN = 0.1


def dimensions(stroke: float, theta: float, frame: float | None = None, crank: float | None = None) -> dict:
    """lever L, frame d, crank r and the guide's height h (m) for the stroke H and the swing theta (rad): the
    greatest frame whose block keeps :data:`BLOCK_MARGIN` of the lever beyond its pin (d + r = (1 - BLOCK_MARGIN) L)
    unless ``frame`` or ``crank`` is given."""
    s, c = math.sin(theta / 2), math.cos(theta / 2)
    lever = stroke / (2 * s)
    d = frame if frame is not None else crank / s if crank is not None else (1 - BLOCK_MARGIN) * lever / (1 + s)
    return {"lever": lever, "frame": d, "crank": d * s, "guide_height": lever * (1 + c) / 2}


def largest_pressure_angle(lever: float, theta: float, rod: float) -> float:
    """The largest pressure angle (rad) of the ram's rod with the guide at the sagitta's middle."""
    return math.asin(lever * (1 - math.cos(theta / 2)) / (2 * rod))


def family(stroke: float, time_ratio: float, count: int = 201) -> Family:
    """The family over the frame d in (0, (1 - BLOCK_MARGIN) L / (1 + sin(theta / 2))]: crank r and the least
    distance d - r of the block from the lever's pivot (the greatest force in the slot per lever torque goes as
    1 / (d - r))."""
    theta = crank_angle_between_limits(time_ratio)
    top = dimensions(stroke, theta)["frame"]
    d = np.linspace(0.0, top, count + 1)[1:]
    s = math.sin(theta / 2)
    columns = {"crank": d * s, "least_block_distance": d * (1 - s)}
    return Family("frame d", "m", d, columns, "greatest frame d (the block as far from the lever's pivot as it goes)")


def _check(stroke: float, time_ratio: float, frame: float | None, crank: float | None, rod: float | None) -> float:
    if not 0 < stroke < math.inf:
        raise SynthesisError(f"stroke {stroke!r} m: expected a positive length")
    if not 1.0 < time_ratio < math.inf:
        raise SynthesisError(
            f"time ratio K = {time_ratio:g}: a slotted lever gives any finite K > 1 (K = 1 needs a crank of zero "
            "length, r = d sin(theta / 2))"
        )
    if frame is not None and crank is not None:
        raise SynthesisError("give one of the frame and the crank: with K either fixes the other")
    for name, value in (("frame", frame), ("crank", crank), ("rod", rod)):
        if value is not None and not 0 < value < math.inf:
            raise SynthesisError(f"{name} {value!r} m: expected a positive length")
    return crank_angle_between_limits(time_ratio)


def solve(
    stroke: float,
    time_ratio: float,
    frame: float | None = None,
    crank: float | None = None,
    rod: float | None = None,
    max_pressure_angle: float | None = None,
    floor: float = LEAST_TRANSMISSION,
) -> tuple[dict, str]:
    """The dimensions (m; with the rod and the largest pressure angle) and what picked the frame; raises
    :class:`SynthesisError` for requirements that cannot be met.  The rod unless given: the shortest whose largest
    pressure angle meets ``max_pressure_angle`` (10 deg unless given) and leaves the transmission angle ``floor``
    (rad)."""
    theta = _check(stroke, time_ratio, frame, crank, rod)
    if max_pressure_angle is not None and not 0 < max_pressure_angle < math.pi / 2:
        raise SynthesisError(f"largest pressure angle {deg(max_pressure_angle)}: expected a bound between 0 and 90 deg")
    dims = dimensions(stroke, theta, frame, crank)
    nearer = _nearer(stroke, time_ratio, frame, crank, rod, max_pressure_angle)
    proportions(KIND, {"stroke": stroke, **{k: dims[k] for k in ("lever", "frame", "crank")}}, nearer)
    reach = dims["frame"] + dims["crank"]
    if reach >= (1 - BLOCK_MARGIN) * dims["lever"] * (1 + 1e-12) and (frame is not None or crank is not None):
        top = dimensions(stroke, theta)
        raise SynthesisError(
            f"{'frame' if frame is not None else 'crank'} {(frame or crank) * 1e3:g} mm with stroke "  # type: ignore[operator]
            f"{stroke * 1e3:g} mm and time ratio K = {time_ratio:g}: the block's pin reaches {reach * 1e3:.6g} mm "
            f"along the lever of {top['lever'] * 1e3:.6g} mm, past the rule's {(1 - BLOCK_MARGIN) * 100:g} % of it "
            f"(the block would leave the slot); the frame must be at most {down(top['frame'] * 1e3, 6)} mm "
            f"(the crank at most {down(top['crank'] * 1e3, 6)} mm)"
        )
    sag = dims["lever"] * (1 - math.cos(theta / 2)) / 2
    bound = min(PRESSURE_ANGLE if max_pressure_angle is None else max_pressure_angle, math.pi / 2 - floor)
    dims["rod"] = rod if rod is not None else sag / math.sin(bound)
    if dims["rod"] <= sag:  # a rod given too short, or a bound so near 90 deg that the rod rounds to the sagitta
        raise SynthesisError(
            f"rod {dims['rod'] * 1e3:.6g} mm: the rod must be longer than half the lever tip's sagitta, "
            f"{sag * 1e3:.6g} mm, to reach the guide"
        )
    proportions(
        KIND,
        {"stroke": stroke, **{k: dims[k] for k in ("lever", "frame", "crank", "rod")}},
        nearer,
    )
    dims["largest_pressure_angle"] = largest_pressure_angle(dims["lever"], theta, dims["rod"])
    if max_pressure_angle is not None and dims["largest_pressure_angle"] > max_pressure_angle * (1 + 1e-12):
        raise SynthesisError(
            f"rod {dims['rod'] * 1e3:g} mm gives a largest pressure angle of {deg(dims['largest_pressure_angle'])}, "
            f"over the bound {deg(max_pressure_angle)}; the bound needs a rod of at least "
            f"{up(sag / math.sin(max_pressure_angle) * 1e3, 6)} mm"
        )
    alpha = dims["largest_pressure_angle"]
    if theta / 2 + alpha >= math.pi / 2:
        raise SynthesisError(
            f"time ratio K = {time_ratio:g} with a largest pressure angle of {deg(alpha)}: the rod folds against "
            f"the lever at its limit positions (theta / 2 + alpha >= 90 deg); that angle gives K < "
            f"{down((math.pi - alpha) / alpha, 6)}"
        )
    why = "the frame given" if frame is not None else "the crank given" if crank is not None else "the greatest frame"
    return dims, why


def _nearer(stroke: float, time_ratio: float, frame, crank, rod, bound) -> str:  # noqa: ANN001
    """The time ratio nearest ``time_ratio`` whose mechanism (the rest of the request kept) keeps its lengths in
    proportion, where one is found above it (bisection; the lever shrinks and the rod grows with K)."""
    from linkwork.synthesis.common import PROPORTION

    def fits(k: float) -> bool:
        try:
            dims = dimensions(stroke, crank_angle_between_limits(k), frame, crank)
        except (ZeroDivisionError, OverflowError, TypeError):
            return False
        theta = crank_angle_between_limits(k)
        sag = dims["lever"] * (1 - math.cos(theta / 2)) / 2
        dims["rod"] = rod if rod is not None else sag / math.sin(bound or PRESSURE_ANGLE)
        sizes = [stroke, dims["lever"], dims["frame"], dims["crank"], dims["rod"]]
        return max(sizes) <= PROPORTION * min(sizes)

    if not fits(3.0):
        return "ask for other lengths"
    lo, hi = time_ratio, 3.0
    for _ in range(60):
        mid = (lo + hi) / 2
        lo, hi = (lo, mid) if fits(mid) else (mid, hi)
    return f"a time ratio K >= {up(hi)} keeps them in proportion"


def synthesize(asked: SlottedLeverRequirements) -> Synthesis:
    """A slotted-lever quick return (crank-shaper) for the ram's stroke H (m) and time ratio K > 1, with the
    ``frame`` d or the ``crank`` r (m) else the greatest frame, the ``rod`` (m) else the shortest rod whose
    largest pressure angle is ``max_pressure_angle`` (rad; 10 deg by default).  Links are steel bars of
    ``section`` and ``density``; the ram's mass is the rod's unless given.  Verified by the analysis of the
    written file: the ram's stroke, K and the rod's largest pressure angle.  ``asked``: the requirements, SI."""
    stroke, time_ratio, frame, crank, rod = asked.stroke, asked.time_ratio, asked.frame, asked.crank, asked.rod
    max_pressure_angle, min_transmission_angle = asked.max_pressure_angle, asked.min_transmission_angle
    speed, section, density, ram_mass = asked.speed, asked.section, asked.density, asked.ram_mass
    floor = least_allowed(min_transmission_angle)
    dims, why = solve(stroke, time_ratio, frame, crank, rod, max_pressure_angle, floor)
    theta = crank_angle_between_limits(time_ratio)
    alpha = dims.pop("largest_pressure_angle")
    if math.pi / 2 - alpha < floor:  # the rod's dyad; the block's (RPR) transmits square to the slot throughout
        sag = dims["lever"] * (1 - math.cos(theta / 2)) / 2
        raise below_rule(
            f"the rod {dims['rod'] * 1e3:.6g} mm (its largest pressure angle {deg(alpha)})",
            math.pi / 2 - alpha,
            floor,
            f"a rod of at least {up(sag / math.cos(floor) * 1e3)} mm meets it",
        )
    requirements = given(
        stroke=stroke,
        time_ratio=time_ratio,
        frame=frame,
        crank=crank,
        rod=rod,
        max_pressure_angle=max_pressure_angle,
        min_transmission_angle=floor,
    )
    written = file_of(*_file(dims, stroke, time_ratio, theta, alpha, why, Making(speed, section, density), ram_mass))
    got, tol = measure_written(written.mech, written.spec)  # the ram's stroke; the pressure angle of the rod's dyad
    measured = {
        "stroke": got["stroke"],
        "time_ratio": got["time_ratio"],
        "largest_pressure_angle": got["max_pressure_angle"],
    }
    predicted = {"stroke": stroke, "time_ratio": time_ratio, "largest_pressure_angle": _written_alpha(written.spec)}
    confirm(measured, predicted, math.pi / 2 - theta / 2 - alpha, tol)  # the rod square to the lever at its limits
    keep_rule(got["min_transmission_angle"], floor, tol["min_transmission_angle"])
    fam = family(stroke, time_ratio) if frame is None and crank is None else None
    return Synthesis(
        KIND,
        requirements,
        dims,
        predicted,
        measured,
        written.spec,
        "",
        fam,
        f"picked by {why}",
        tolerances=tol,
        tree=written.tree,
    )


def _written_alpha(spec) -> float:  # noqa: ANN001
    """The rod's largest pressure angle (rad) of the lengths as the file writes them (12 digits each): near K = 1
    it is a small difference of large lengths, h - L cos(phi), which the rounding moves by more than the
    verification's 1e-9; the closed form on the written lengths is what the analysis must measure.  Over the swing
    L cos(phi) sweeps [L cos(theta / 2), L], sin(theta / 2) = r / d."""
    lever, rod = float(spec.links["lever"].length), float(spec.links["rod"].length)
    h, d, r = (
        float(spec.joints["guide"].through[1]),
        float(spec.frame.points["O1"][1]),
        float(spec.links["crank"].length),
    )
    low = lever * math.sqrt(1 - (r / d) ** 2)
    return math.asin(max(abs(h - lever), abs(h - low)) / rod)


def _file(dims, stroke, time_ratio, theta, alpha, why, making: Making, ram_mass) -> tuple:  # noqa: ANN001
    """The file's data and comments: assembled with the crank up and the lever upright."""
    speed, section, density = making
    lever, d, r, h, rod = (rounded(dims[k]) for k in ("lever", "frame", "crank", "guide_height", "rod"))
    mass = {k: float(f"{bar_mass(dims[k], section, density):.6g}") for k in ("crank", "lever", "rod")}
    block = float(f"{bar_mass(section[0], section, density):.6g}")
    ram = float(f"{ram_mass if ram_mass is not None else mass['rod']:.6g}")
    reach = math.sqrt(rod**2 - (h - lever) ** 2)
    data = {
        "name": "slotted-lever",
        "description": f"Slotted-lever quick return (crank-shaper) synthesised for the ram's stroke "
        f"{stroke * 1e3:.6g} mm and time ratio K = {time_ratio:.6g} (theta = lever swing = "
        f"{math.degrees(theta):.6g} deg); {why}.  Masses: steel bars {section[0] * 1e3:g} x "
        f"{section[1] * 1e3:g} mm, {density:g} kg/m^3.",
        "units": {"length": "mm", "mass": "kg", "angle": "deg"},
        "frame": {"points": {"O2": [0.0, 0.0], "O1": [0.0, mm(d)]}},
        "links": {
            "crank": {"ends": ["O1", "A"], "length": mm(r), "mass": mass["crank"]},
            "block": {"points": {"A": [0.0, 0.0]}, "mass": block, "inertia": 0},
            "lever": {"ends": ["O2", "C"], "length": mm(lever), "mass": mass["lever"]},
            "rod": {"ends": ["C", "D"], "length": mm(rod), "mass": mass["rod"]},
            "ram": {"points": {"D": [0.0, 0.0]}, "mass": ram, "inertia": 0},
        },
        "joints": {
            "O1": {"type": "revolute", "links": ["frame", "crank"]},
            "A": {"type": "revolute", "links": ["crank", "block"]},
            "slot": {"type": "prismatic", "links": ["lever", "block"], "point": "A", "through": "O2", "axis": 0.0},
            "O2": {"type": "revolute", "links": ["frame", "lever"]},
            "C": {"type": "revolute", "links": ["lever", "rod"]},
            "D": {"type": "revolute", "links": ["rod", "ram"]},
            "guide": {
                "type": "prismatic",
                "links": ["frame", "ram"],
                "point": "D",
                "through": [0.0, mm(h)],
                "axis": 0.0,
            },
        },
        "drives": [{"joint": "O1", "speed": speed, "direction": "ccw", "angle": 90.0}],
        "hints": {"A": [0.0, mm(d + r)], "C": [0.0, mm(lever)], "D": [mm(reach), mm(h)]},
    }
    comments = {
        ("frame", "points", "O1"): f"frame d: {why}; block reach d + r <= {1 - BLOCK_MARGIN:g} L",
        ("links", "crank", "length"): f"r = d sin(theta / 2): time ratio K = {time_ratio:.6g}",
        ("links", "lever", "length"): f"L = H / (2 sin(theta / 2)): stroke H = {stroke * 1e3:.6g} mm",
        ("links", "rod", "length"): f"l: largest pressure angle {math.degrees(alpha):.6g} deg",
        ("joints", "guide", "through"): "h = L (1 + cos(theta / 2)) / 2: the least largest pressure angle",
        ("hints", "D"): "the ram to +x of the lever",
    }
    return data, comments
