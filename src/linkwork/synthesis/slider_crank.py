"""Synthesis of an (offset) slider-crank from its stroke H, time ratio K and one more requirement.

The theory (derived here; the classical construction of the limit positions):

* At the limit positions of the ram B the crank and the rod are in line: |OB1| = l + r (stretched) and
  |OB2| = l - r (folded).  The crank's directions there differ by pi - theta, where theta is the angle
  B1 O B2, so the strokes take pi + theta and pi - theta of the turn: K = (pi + theta) / (pi - theta).
* O therefore sees the chord B1 B2 = H under the angle theta: it lies on the circle through B1 and B2 of
  radius H / (2 sin theta).  With beta the angle O B1 B2 (the free parameter of the family), the law of
  sines gives l + r = H sin(theta + beta) / sin theta, l - r = H sin(beta) / sin theta and the offset
  e = (l + r) sin(beta) = H sin(beta) sin(theta + beta) / sin theta.
* Both limit positions lie on the same side of the foot of the perpendicular from O onto the guide, so the
  angle at B2 is obtuse: 0 < beta < pi/2 - theta, hence theta < pi/2 and K < 3.  At beta = pi/2 - theta,
  l - r = e: the folded rod stands square to the guide (a dead point).
* The pressure angle alpha (between the rod and the guide) has sin(alpha) = (r sin(phi) + e) / l over the
  crank angle phi from the guide's direction: its largest value is arcsin((r + e) / l), with the crank square
  to the guide on the side away from the guide.
* Closed forms for the third requirement: the rod ratio lambda = r / l gives
  tan(beta) = sin(theta) / ((1 + lambda) / (1 - lambda) - cos(theta)), feasible for
  tan^2(theta / 2) < lambda < 1; the offset gives cos(theta + 2 beta) = cos(theta) - 2 e sin(theta) / H,
  feasible for 0 <= e < H cot(theta).  Without either, beta minimises the largest pressure angle (a function of
  beta and theta only) by Brent's method on the closed form.
* K = 1 (theta = 0): the central slider-crank, r = H / 2, e = 0, l from the rod ratio or the bound on the
  pressure angle (l = r / sin(alpha)): the largest pressure angle falls without bound as l grows.

Layout of the file: crank pivot O at the origin, the guide vertical through (-e, 0) pointing down, the crank
turning counter-clockwise, so the ram's slow (working) stroke is downward.
"""

from __future__ import annotations

import math

import numpy as np

from linkwork.errors import SynthesisError
from linkwork.requirements import SliderCrankRequirements
from linkwork.synthesis.common import (
    LEAST_TRANSMISSION,
    Family,
    Synthesis,
    bar_mass,
    below_rule,
    confirm,
    crank_angle_between_limits,
    deg,
    degrees,
    down,
    file_of,
    given,
    keep_rule,
    least_allowed,
    mm,
    newtons,
    proportions,
    rounded,
    step,
    up,
)
from linkwork.synthesis.rounding import measure_written

KIND = "slider-crank"

#: Members of the family whose peak driving torque is computed before the pick is refined.
TORQUE_MEMBERS = 24

#: Largest time ratio of a slider-crank (theta < 90 deg), exclusive.
K_LIMIT = 3.0


def dimensions(stroke: float, theta: float, beta: np.ndarray | float) -> tuple:
    """(r, l, e) (m) of the family member ``beta`` (rad, the angle O B1 B2) for the stroke and theta."""
    s = stroke / math.sin(theta)
    far, near = s * np.sin(theta + beta), s * np.sin(beta)
    return (far - near) / 2.0, (far + near) / 2.0, far * np.sin(beta)


def largest_pressure_angle(r: np.ndarray | float, ell: np.ndarray | float, e: np.ndarray | float) -> np.ndarray:
    """The largest pressure angle (rad) over the turn of a slider-crank: arcsin((r + |e|) / l); NaN where the
    crank cannot turn (r + |e| >= l)."""
    ratio = (np.asarray(r) + np.abs(e)) / np.asarray(ell)
    with np.errstate(invalid="ignore"):
        return np.where(ratio < 1.0, np.arcsin(np.minimum(ratio, 1.0)), np.nan)


def _alpha(theta: float, beta: float) -> float:
    return float(np.nan_to_num(largest_pressure_angle(*dimensions(1.0, theta, beta)), nan=math.pi / 2))


def best_beta(theta: float) -> float:
    """beta (rad) of the family's member with the least largest pressure angle (Brent on the closed form)."""
    from scipy.optimize import minimize_scalar

    top = math.pi / 2 - theta
    res = minimize_scalar(
        lambda b: _alpha(theta, b),
        bounds=(top * 1e-9, top * (1 - 1e-9)),
        method="bounded",
        options={"xatol": 1e-12 * top},
    )
    return float(res.x)


def least_pressure_angle(time_ratio: float) -> float:
    """The least largest pressure angle (rad) any slider-crank of time ratio K has (0 for K = 1)."""
    theta = crank_angle_between_limits(time_ratio)
    return 0.0 if theta == 0.0 else _alpha(theta, best_beta(theta))


def largest_time_ratio(pressure_angle: float) -> float:
    """The largest K a slider-crank reaches with its largest pressure angle at most ``pressure_angle`` (rad)."""
    from scipy.optimize import brentq

    return float(brentq(lambda k: least_pressure_angle(k) - pressure_angle, 1.0, K_LIMIT - 1e-9, xtol=1e-13))


def family(stroke: float, time_ratio: float, count: int = 201) -> Family:
    """The family over beta in (0, pi/2 - theta) with r, l, e and the largest pressure angle."""
    theta = crank_angle_between_limits(time_ratio)
    beta = np.linspace(0.0, math.pi / 2 - theta, count + 2)[1:-1]
    r, ell, e = dimensions(stroke, theta, beta)
    columns = {"crank": r, "rod": ell, "offset": e, "largest_pressure_angle": largest_pressure_angle(r, ell, e)}
    return Family("angle O B1 B2", "rad", beta, columns, "least largest pressure angle")


def _check_ratio(time_ratio: float) -> float:
    if not 1.0 <= time_ratio < K_LIMIT:
        raise SynthesisError(
            f"time ratio K = {time_ratio:g}: a slider-crank gives 1 <= K < 3 (the crank's angle between the limit "
            "positions theta = 180 deg (K - 1) / (K + 1) stays under 90 deg)"
        )
    return crank_angle_between_limits(time_ratio)


def _central(
    stroke: float, rod_ratio: float | None, offset: float | None, bound: float | None, floor: float = LEAST_TRANSMISSION
) -> tuple:
    if offset:
        raise SynthesisError(f"time ratio K = 1 needs a zero offset; the offset {offset * 1e3:g} mm gives K > 1")
    r = stroke / 2.0
    if rod_ratio is not None:
        if not 0 < rod_ratio < 1:
            raise SynthesisError(
                f"rod ratio r/l = {rod_ratio:g}: a rod as long as the crank or shorter cannot follow it round (the "
                f"crank turns for r/l under 1; a least transmission angle of {math.degrees(floor):.4g} deg needs "
                f"r/l <= {down(math.cos(floor))})"
            )
        return r, r / rod_ratio, 0.0, f"rod ratio r/l = {rod_ratio:g}"
    if bound is not None:
        return r, r / math.sin(bound), 0.0, f"the shortest rod with the largest pressure angle {deg(bound)}"
    raise SynthesisError(
        "time ratio K = 1 leaves the rod's length free (the pressure angle falls as it grows): give the rod "
        "ratio or the largest pressure angle"
    )


def _offset_member(stroke: float, time_ratio: float, theta: float, rod_ratio: float | None, offset: float | None):
    if rod_ratio is not None:
        low = math.tan(theta / 2) ** 2
        if not low < rod_ratio < 1.0:
            raise SynthesisError(
                f"rod ratio r/l = {rod_ratio:g} with time ratio K = {time_ratio:g}: the rod ratio must lie in "
                f"({low:.6g}, 1) (tan^2(theta / 2) < r/l < 1)"
            )
        g = (1 + rod_ratio) / (1 - rod_ratio)
        return math.atan2(math.sin(theta), g - math.cos(theta)), f"rod ratio r/l = {rod_ratio:g}"
    if offset is not None:
        top = stroke / math.tan(theta)
        if not 0.0 < offset < top:
            raise SynthesisError(
                f"offset {offset * 1e3:g} mm with stroke {stroke * 1e3:g} mm and time ratio K = {time_ratio:g}: "
                f"the offset must be over 0 (a central slider-crank has K = 1) and under H cot(theta) = "
                f"{top * 1e3:.6g} mm"
            )
        return (math.acos(math.cos(theta) - 2 * offset * math.sin(theta) / stroke) - theta) / 2, "the offset"
    return best_beta(theta), "the least largest pressure angle"


def solve(
    stroke: float,
    time_ratio: float,
    rod_ratio: float | None = None,
    offset: float | None = None,
    max_pressure_angle: float | None = None,
    floor: float = LEAST_TRANSMISSION,
) -> tuple[float, float, float, str]:
    """(r, l, e, what picked the member) (m) for the requirements (SI); raises :class:`SynthesisError`."""
    if not 0 < stroke < math.inf:
        raise SynthesisError(f"stroke {stroke!r} m: expected a positive length")
    if max_pressure_angle is not None and not 0 < max_pressure_angle < math.pi / 2:
        raise SynthesisError(f"largest pressure angle {deg(max_pressure_angle)}: expected a bound between 0 and 90 deg")
    if rod_ratio is not None and offset is not None:
        raise SynthesisError("give one of the rod ratio and the offset: with H and K either fixes the mechanism")
    theta = _check_ratio(time_ratio)
    if theta == 0.0:
        r, ell, e, why = _central(stroke, rod_ratio, offset, max_pressure_angle, floor)
    else:
        beta, why = _offset_member(stroke, time_ratio, theta, rod_ratio, offset)
        r, ell, e = (float(x) for x in dimensions(stroke, theta, beta))
    alpha = float(largest_pressure_angle(r, ell, e))
    if max_pressure_angle is not None and not alpha <= max_pressure_angle * (1 + 1e-12):
        least = least_pressure_angle(time_ratio)
        if least > max_pressure_angle:
            raise SynthesisError(
                f"time ratio K = {time_ratio:g} needs a largest pressure angle of at least "
                f"{up(math.degrees(least))} deg; at most {deg(max_pressure_angle)} gives K <= "
                f"{down(largest_time_ratio(max_pressure_angle))}"
            )
        raise SynthesisError(
            f"{why} with K = {time_ratio:g} gives a largest pressure angle of {deg(alpha)}, over the bound "
            f"{deg(max_pressure_angle)}; the least for K = {time_ratio:g} is {up(math.degrees(least))} deg (leave the "
            "rod ratio and offset out to get it)"
        )
    return r, ell, e, why


def synthesize(asked: SliderCrankRequirements) -> Synthesis:
    """An offset slider-crank for the stroke H (m), time ratio K, and the rod ratio r/l or the offset e (m),
    else the family's member picked by ``criterion``: ``"pressure"``, the least largest pressure angle, or
    ``"torque"``, the least peak driving torque under the working load (refined between the samples,
    :func:`linkwork.kinetostatics.torque_peak`) among the members meeting ``max_pressure_angle`` (rad), a bound
    it must meet.  ``force`` (N): the working load, resisting the ram over the last ``working`` (m; default the
    whole stroke) of its working (downward) stroke, written in the file as a process load.  Links are
    steel bars of ``section`` (m x m) and ``density``; the ram's mass is the rod's unless given.  Verified
    by the analysis of the written file (:func:`~linkwork.synthesis.measuring.measure`): ``asked``, SI."""
    stroke, time_ratio, rod_ratio, offset = asked.stroke, asked.time_ratio, asked.rod_ratio, asked.offset
    force, working, criterion = asked.force, asked.working, asked.criterion
    speed, section, density, ram_mass = asked.speed, asked.section, asked.density, asked.ram_mass
    max_pressure_angle, min_transmission_angle = asked.max_pressure_angle, asked.min_transmission_angle
    load = _load(stroke, force, working, criterion)
    floor = least_allowed(min_transmission_angle)
    r, ell, e, why = solve(stroke, time_ratio, rod_ratio, offset, max_pressure_angle, floor)
    proportions(KIND, {"stroke": stroke, "crank": r, "rod": ell, "offset": e})
    theta = crank_angle_between_limits(time_ratio)
    free = theta > 0 and rod_ratio is None and offset is None
    _keeps_rule(r, ell, e, time_ratio, floor, why)
    if criterion == "torque" and free:  # within the bound asked and the rule's: the least torque runs to a dead point
        bound = min(max_pressure_angle or math.pi / 2, math.pi / 2 - floor)
        beta, why = _least_torque(stroke, time_ratio, bound, load, speed, section, density, ram_mass)
        r, ell, e = (float(x) for x in dimensions(stroke, theta, beta))
    alpha = float(largest_pressure_angle(r, ell, e))
    requirements = given(
        stroke=stroke,
        time_ratio=time_ratio,
        rod_ratio=rod_ratio,
        offset=offset,
        max_pressure_angle=max_pressure_angle,
        min_transmission_angle=floor,
        force=force,
        working=working,
    )
    written = file_of(
        *_file((r, ell, e), (stroke, time_ratio), theta, alpha, why, speed, (section, density, ram_mass), load)
    )
    got, tol = measure_written(written.mech, written.spec)
    measured = {
        "stroke": got["stroke"],
        "time_ratio": got["time_ratio"],
        "largest_pressure_angle": got["max_pressure_angle"],
    }
    predicted = {"stroke": stroke, "time_ratio": time_ratio, "largest_pressure_angle": alpha}
    confirm(measured, predicted, math.pi / 2 - alpha, tol)
    keep_rule(got["min_transmission_angle"], floor, tol["min_transmission_angle"])
    return Synthesis(
        KIND,
        requirements,
        {"crank": r, "rod": ell, "offset": e},
        predicted,
        measured,
        written.spec,
        "",
        family(stroke, time_ratio) if free else None,
        f"picked by {why}",
        tolerances=tol,
        tree=written.tree,
    )


def _keeps_rule(r: float, ell: float, e: float, time_ratio: float, floor: float, why: str) -> None:
    """Raise where the slider-crank's least transmission angle, 90 deg less its largest pressure angle, is under
    ``floor`` (rad), with the nearest request that meets it (``why``: what picked the member)."""
    least = math.pi / 2 - float(largest_pressure_angle(r, ell, e))
    if least >= floor:
        return
    best = math.pi / 2 - least_pressure_angle(time_ratio)
    if e == 0.0:  # central: the rod's length alone
        nearest = f"a rod ratio r/l <= {down(math.cos(floor))} meets it"
    elif best >= floor:
        nearest = f"leave the rod ratio and offset out: K = {time_ratio:g} reaches {down(math.degrees(best))} deg"
    else:
        nearest = f"K <= {down(largest_time_ratio(math.pi / 2 - floor))} meets it"
    raise below_rule(f"time ratio K = {time_ratio:g} with {why}", least, floor, nearest)


def _load(stroke: float, force: float | None, working: float | None, criterion: str) -> tuple[float, float] | None:
    """(force N, working length m) of the working load, or None; raises where the criterion or load is wrong."""
    if criterion not in ("pressure", "torque"):
        raise SynthesisError(f"criterion {criterion!r}: expected pressure or torque")
    if force is None:
        if criterion == "torque" or working is not None:
            raise SynthesisError("the least peak driving torque is under the working load: give the force")
        return None
    if not 0 < force < math.inf:
        raise SynthesisError(f"force {force!r} N: expected a positive force")
    length = stroke if working is None else working
    if not 0 < length <= stroke:
        raise SynthesisError(f"working length {length * 1e3:g} mm: expected more than 0, at most the stroke")
    if length < step():
        raise SynthesisError(
            f"working length {length * 1e3:g} mm: the file is dimensioned to {step() * 1e3:g} mm; give at least that"
        )
    return force, length


def peak_torques(
    stroke: float,
    time_ratio: float,
    beta: np.ndarray,
    load: tuple[float, float],
    speed: str,
    section: tuple[float, float],
    density: float,
    ram_mass: float | None,
) -> np.ndarray:
    """The peak driving torque (N m, its size, refined between the samples) of the family's members ``beta``
    under the working load, each from its own file (its masses by the bar rule)."""
    from linkwork.api import forces
    from linkwork.kinetostatics.peaks import torque_peak

    theta = crank_angle_between_limits(time_ratio)
    out = np.full(np.shape(beta), np.nan)
    for i, b in enumerate(np.atleast_1d(beta)):
        r, ell, e = (float(x) for x in dimensions(stroke, theta, b))
        mech = file_of(
            *_file((r, ell, e), (stroke, time_ratio), theta, 0.0, "", speed, (section, density, ram_mass), load)
        ).mech
        out.flat[i] = abs(float(np.ravel(torque_peak(forces(mech, steps=360)).value)[0]))
    return out


def _least_torque(
    stroke: float,
    time_ratio: float,
    bound: float,
    load,
    speed,
    section,
    density,  # noqa: ANN001
    ram_mass,
) -> tuple[float, str]:  # noqa: ANN001
    """beta (rad) of the member with the least peak driving torque among those whose largest pressure angle is
    at most ``bound`` (an interval of beta about the least one's, its ends by Brent on the closed form): the best
    of a grid over it, refined by Brent's method between its neighbours."""
    from scipy.optimize import brentq, minimize_scalar

    theta = crank_angle_between_limits(time_ratio)
    top, middle = math.pi / 2 - theta, best_beta(theta)
    ends = [top * 1e-9, top * (1 - 1e-9)]
    for j, end in enumerate(ends):
        if _alpha(theta, end) > bound:
            ends[j] = brentq(lambda b: _alpha(theta, b) - bound, *sorted((end, middle)), xtol=1e-15)
    betas = np.linspace(ends[0], ends[1], TORQUE_MEMBERS)
    args = (speed, section, density, ram_mass)
    torques = peak_torques(stroke, time_ratio, betas, load, *args)
    i = int(np.nanargmin(torques))
    lo, hi = betas[max(i - 1, 0)], betas[min(i + 1, len(betas) - 1)]
    res = minimize_scalar(
        lambda b: float(peak_torques(stroke, time_ratio, np.array([b]), load, *args)[0]),
        bounds=(lo, hi),
        method="bounded",
        options={"xatol": 1e-7},
    )
    best = float(res.x) if res.fun <= torques[i] else float(betas[i])
    return best, f"the least peak driving torque under the working load {load[0]:g} N"


def _file(dims, asked, theta, alpha, why, speed, masses, load=None) -> tuple:  # noqa: ANN001
    """The file's data and comments (:func:`file_of`) of the lengths ``dims`` (r, l, e; m) for the ``asked`` stroke (m)
    and time ratio, with the bars' ``masses`` (their section (m, m), density (kg/m^3) and the ram's mass, kg)."""
    (stroke, time_ratio), (section, density, ram_mass) = asked, masses
    r, ell, e = (rounded(x) for x in dims)  # as written: what follows is of the written lengths
    near = math.sqrt((ell - r) ** 2 - e**2)
    start = math.pi / 2 - math.asin(e / (ell - r))  # the folded limit position: the ram at the top
    rod = bar_mass(ell, section, density)
    data = {
        "name": "slider-crank",
        "description": f"{'Central' if e == 0 else 'Offset'} slider-crank synthesised for the stroke "
        f"{stroke * 1e3:.6g} mm and time ratio K = "
        f"{time_ratio:.6g} (theta = {math.degrees(theta):.6g} deg); {why}.  Masses: steel bars "
        f"{section[0] * 1e3:g} x {section[1] * 1e3:g} mm, {density:g} kg/m^3.",
        "units": {"length": "mm", "mass": "kg", "angle": "deg"},
        "frame": {"points": {"O": [0.0, 0.0]}},
        "links": {
            "crank": {"ends": ["O", "A"], "length": mm(r), "mass": float(f"{bar_mass(r, section, density):.6g}")},
            "rod": {"ends": ["A", "B"], "length": mm(ell), "mass": float(f"{rod:.6g}")},
            "ram": {
                "points": {"B": [0.0, 0.0]},
                "mass": float(f"{ram_mass if ram_mass is not None else rod:.6g}"),
                "inertia": 0,
            },
        },
        "joints": {
            "O": {"type": "revolute", "links": ["frame", "crank"]},
            "A": {"type": "revolute", "links": ["crank", "rod"]},
            "B": {"type": "revolute", "links": ["rod", "ram"]},
            "guide": {
                "type": "prismatic",
                "links": ["frame", "ram"],
                "point": "B",
                "through": [mm(-e), 0.0],
                "axis": -90.0,
            },
        },
        "drives": [{"joint": "O", "speed": speed, "direction": "ccw", "angle": degrees(start)}],
        "hints": {"B": [mm(-e), mm(-near)]},
    }
    if load is not None:  # resisting the ram over the last ``load[1]`` of its way down, from a step below the bottom
        bottom = math.floor(-math.sqrt((ell + r) ** 2 - e**2) / step()) * step()
        data["loads"] = {
            "working": {
                "type": "process",
                "tools": ["ram.B"],
                "axis": 90.0,
                "workpiece": [mm(bottom), mm(bottom + rounded(load[1]))],
                "penetration": [0.0, 1.0],
                "force": [newtons(load[0])] * 2,
            }
        }
    comments = {
        ("links", "crank", "length"): f"r = (|OB1| - |OB2|) / 2: stroke H = {stroke * 1e3:.6g} mm",
        ("links", "rod", "length"): f"l: {why}; largest pressure angle {math.degrees(alpha):.6g} deg",
        ("joints", "guide", "through"): f"offset e = {e * 1e3:.6g} mm: time ratio K = {time_ratio:.6g}",
        ("hints", "B"): "the ram below the crank",
    }
    if load is not None:
        comments[("loads", "working", "workpiece")] = (
            f"the last {load[1] * 1e3:.6g} mm of the ram's way down, from the bottom dead centre"
        )
    return data, comments
