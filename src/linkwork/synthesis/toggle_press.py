"""Synthesis of a knuckle-joint (toggle) press from the ram's stroke, the nominal force at a distance before the
bottom dead centre and the crank's torque limit.

The family (stated): a symmetric toggle, the upper link P K and the lower link K R of one length a, the upper
link pivoted on the frame at P on the ram's vertical guide; the knuckle K driven by a crank-rocker O A K P whose
folded limit position (crank and rod overlapping) holds the toggle straight (the bottom dead centre) and whose
stretched limit position swings the upper link by psi from the vertical (the top).

The theory (derived here):

* With the upper link at beta from the downward vertical, K = a (sin beta, -cos beta) and the ram
  y_R = -2 a cos beta: the ram's height above the bottom dead centre is s = 2 a (1 - cos beta), monotone in beta
  over [0, psi], so the ram is at its ends when the upper link is and H = 2 a (1 - cos psi).
* The four-bar is the crank-rocker of :mod:`linkwork.synthesis.crank_rocker` for the swing psi and the time
  ratio K (its member with the greatest least transmission angle), turned so that its folded limit position
  points straight down.
* Virtual work: F v_R + T omega = 0 for a load F against the ram's descent, so the driving torque at the
  nominal point is |T| = F rho, rho = -v_R / |omega| = 2 a sin(beta_n) omega_4 / |omega| (clockwise) with cos(beta_n) =
  1 - s_n / (2 a) and omega_4 / omega from the four-bar's velocities: (omega_4 k x K) . (K - A) =
  (omega k x (A - O)) . (K - A).  Near the bottom, s ~ (phi - phi_0)^4, so rho ~ s^(3/4): the toggle's gain.
* What the requirements leave free: psi and K.  They are stated defaults (psi = 45 deg, so a = H / (2 - sqrt 2),
  1.707 H, the lower link at most 45 deg to the ram's guide and the four-bar's least transmission angle 44.6 deg,
  both within the 40 deg design rule; K = 1.2);
  the torque limit is then a bound: T = F rho at most the limit, else the message gives the largest nominal
  force the limit allows.

Layout of the file: P at the origin, the guide vertical through P pointing down, the crank turning clockwise,
so that the ram's down (working) stroke is the slow one, pi + theta of the turn.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from linkwork.errors import SynthesisError
from linkwork.requirements import TogglePressRequirements
from linkwork.synthesis import crank_rocker
from linkwork.synthesis.common import (
    PROPORTION,
    VERIFY_STEPS,
    Making,
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
from linkwork.synthesis.rounding import measure_written, rounding_variants, spread

KIND = "toggle-press"

#: The upper link's swing and the four-bar's time ratio unless given.
SWING = math.radians(45.0)
TIME_RATIO = 1.2


def _cross(v: np.ndarray) -> np.ndarray:
    """k x v."""
    return np.array([-v[1], v[0]])


def geometry(stroke: float, swing: float, time_ratio: float) -> dict:
    """The toggle's link a, the crank pivot O (P at the origin), crank r, rod b (m), and the four-bar's least
    transmission angle (rad)."""
    theta = crank_angle_between_limits(time_ratio)
    if not theta > 0:
        raise SynthesisError("toggle-press: the time ratio K must be over 1")
    t, side, mu = crank_rocker.best(swing, theta)
    m = {k: v[0] for k, v in crank_rocker.members(swing, theta, np.array([t]), side).items()}
    half = swing / 2  # the unit rocker's limits are symmetric about -y: turn B_f onto -y
    turn = np.array([[math.cos(half), -math.sin(half)], [math.sin(half), math.cos(half)]])
    a = stroke / (2 * (1 - math.cos(swing)))
    return {
        "toggle": a,
        "O": turn @ m["O2"] * a,
        "crank": float(m["crank"]) * a,
        "rod": float(m["coupler"]) * a,
        "least_transmission_angle": float(mu),
    }


def nominal(geo: dict, before: float) -> tuple[float, float]:
    """(drive angle, rho = -v_R / |omega| (m)) at the nominal point on the ram's way down, the crank turning
    clockwise (omega < 0)."""
    a, r, b = rounded(geo["toggle"]), rounded(geo["crank"]), rounded(geo["rod"])
    o = np.array([rounded(float(x)) for x in geo["O"]])
    beta = math.acos(1 - before / (2 * a))
    k = a * np.array([math.sin(beta), -math.cos(beta)])
    d = k - o
    dd = float(np.linalg.norm(d))
    along = (r * r - b * b + dd * dd) / (2 * dd)
    u = d / dd
    for s in (1.0, -1.0):
        pin = o + along * u + s * math.sqrt(max(r * r - along * along, 0.0)) * _cross(u)
        w4 = float(np.dot(_cross(pin - o), k - pin) / np.dot(_cross(k), k - pin))
        rho = 2 * a * math.sin(beta) * w4  # y_R = -2 a cos(beta), d(beta)/dt = w4 omega, omega = -|omega|
        if rho > 0:
            return math.atan2(pin[1] - o[1], pin[0] - o[0]), rho
    raise SynthesisError("toggle-press: the nominal point is not on the ram's way down")  # pragma: no cover


def synthesize(asked: TogglePressRequirements) -> Synthesis:
    """A knuckle-joint press for the ram's stroke (m), the nominal ``force`` (N) at ``before`` (m) before the
    bottom dead centre and the crank's ``torque`` limit (N m); the upper link's ``swing`` (rad, 45 deg) and the
    four-bar's ``time_ratio`` (1.2) unless given.  The file carries the nominal force as a process load; the
    stroke and the torque at the nominal point are verified by ``lw.kinematics`` and ``lw.forces``.  ``asked``: the
    requirements, SI."""
    stroke, force, before, torque = asked.stroke, asked.force, asked.before, asked.torque
    swing, time_ratio, min_transmission_angle = asked.swing, asked.time_ratio, asked.min_transmission_angle
    speed, section, density = asked.speed, asked.section, asked.density
    for name, value in (("stroke", stroke), ("force", force), ("before", before), ("torque", torque)):
        if not 0 < value < math.inf:
            raise SynthesisError(f"toggle-press: {name} {value!r}: expected a positive finite value (SI)")
    if not before < stroke:
        raise SynthesisError(
            f"nominal point {before * 1e3:g} mm before the bottom: it must lie within the stroke {stroke * 1e3:g} mm"
        )
    if before < step():
        raise SynthesisError(
            f"nominal point {before * 1e3:g} mm before the bottom: the file is dimensioned to {step() * 1e3:g} mm; "
            "give at least that"
        )
    psi = SWING if swing is None else swing
    k = TIME_RATIO if time_ratio is None else time_ratio
    if not 0 < psi < math.pi / 2:
        raise SynthesisError(f"toggle swing {deg(psi)}: expected between 0 and 90 deg")
    if 1 - math.cos(psi) < 1 / (2 * PROPORTION):  # a = H / (2 (1 - cos psi)) more than PROPORTION strokes long
        raise SynthesisError(
            f"toggle swing {deg(psi)} gives toggle links over {PROPORTION:g} times the stroke: a swing of at least "
            f"{up(math.degrees(math.acos(1 - 1 / (2 * PROPORTION))))} deg keeps them in proportion"
        )
    floor = least_allowed(min_transmission_angle)
    if math.pi / 2 - psi < floor:  # the lower link and the ram's guide at the top
        raise below_rule(
            f"toggle swing {deg(psi)} (the lower link at {deg(psi)} to the ram's guide at the top)",
            math.pi / 2 - psi,
            floor,
            f"a swing of at most {down(90 - math.degrees(floor))} deg meets it",
        )
    geo = geometry(stroke, psi, k)
    proportions(KIND, {"stroke": stroke, "before": before, **{n: geo[n] for n in ("toggle", "crank", "rod")}})
    if geo["least_transmission_angle"] < floor:
        raise below_rule(
            f"the four-bar of swing {deg(psi)} and time ratio K = {k:g}",
            geo["least_transmission_angle"],
            floor,
            crank_rocker.nearest(psi, k, floor),
        )
    angle, rho = nominal(geo, before)
    requirements = given(
        stroke=stroke,
        force=force,
        before=before,
        torque=torque,
        swing=swing,
        time_ratio=time_ratio,
        min_transmission_angle=floor,
    )
    written = file_of(*_file(geo, stroke, force, before, psi, k, Making(speed, section, density)))
    spec = written.spec
    got, tol = measure_written(written.mech, spec)  # the ram's stroke
    measured = {"stroke": got["stroke"], "torque_at_nominal": -_torque(spec, angle)}  # clockwise
    predicted = {"stroke": stroke, "torque_at_nominal": force * rho}
    tol = tol | {"torque_at_nominal": spread(_torque(spec, angle, rounding_variants(written.mech)))}
    confirm(measured, predicted, geo["least_transmission_angle"], tol)
    keep_rule(got["min_transmission_angle"], floor, tol["min_transmission_angle"])
    measured["peak_torque"] = _within_limit(spec, angle, force, before, torque)
    dims = {key: float(v) for key, v in geo.items() if key != "O" and key != "least_transmission_angle"}
    dims.update(frame_x=float(geo["O"][0]), frame_y=float(geo["O"][1]))
    return Synthesis(
        KIND,
        requirements,
        dims,
        predicted,
        measured,
        spec,
        "",
        None,
        f"picked by the stated swing {deg(psi)} and time ratio K = {k:g}",
        tolerances=tol,
        tree=written.tree,
    )


def _within_limit(spec, angle: float, force: float, before: float, torque: float) -> float:  # noqa: ANN001
    """The peak size of the driving torque (N m) over the turn as :func:`linkwork.forces` measures it on the written
    file (the process load, gravity and inertia; refined between the samples), checked against the ``torque``
    limit; over it, a :class:`SynthesisError` naming the limit the request needs and the largest nominal force the
    limit allows (forces are linear in the loads: the file's torque with the force scaled, searched on the samples
    and the angle where the load takes hold, rounded down)."""
    from linkwork.api import forces
    from linkwork.kinetostatics.peaks import torque_peak

    peak = torque_peak(forces(spec, steps=VERIFY_STEPS))
    value = abs(float(peak.value[0]))
    if value <= torque * (1 + 1e-12):
        return value
    angles = np.concatenate([np.linspace(0.0, 2 * math.pi, VERIFY_STEPS, endpoint=False), [angle - 1e-9]])
    idle = np.ravel(forces(spec.model_copy(update={"loads": {}}), angles).driving_torque)
    load = np.ravel(forces(spec, angles).driving_torque) - idle
    lo, hi = 0.0, 1.0
    for _ in range(60):
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if np.max(np.abs(mid * load + idle)) <= torque else (lo, mid)
    if lo == 0.0:
        raise SynthesisError(
            f"the press's own links (their weight and inertia at the file's speed) need a crank torque of "
            f"{up(float(np.max(np.abs(idle))))} N m before any force: the limit {torque:g} N m allows none; raise "
            "--torque, or lower --speed or --section"
        )
    raise SynthesisError(
        f"nominal force {force / 1e3:g} kN from {before * 1e3:g} mm before the bottom needs a crank torque of "
        f"{up(value)} N m at its peak over the turn (the forces analysis of the file); the limit "
        f"{torque:g} N m allows at most {down(force * lo * (1 - 1e-6) / 1e3)} kN: raise --torque or lower --force"
    )


def _torque(spec, angle: float, variants: dict | None = None) -> Any:  # noqa: ANN001
    """The driving torque of the process load alone at the drive ``angle``, the nominal point, where the file's
    load takes hold: lw.forces with the load's workpiece reaching over the whole stroke (the force is the
    table's one value inside it) less lw.forces without loads (forces are linear in the loads; gravity and
    inertia cancel); counter-clockwise positive.  With ``variants`` (named parameters, as
    :func:`linkwork.kinematics` takes them): the array of the variants' torques."""
    from linkwork.api import forces

    (name, load), stroke = next(iter(spec.loads.items())), -2 * float(spec.links["upper"].length)
    deeper = load.model_copy(update={"workpiece": [stroke, 0.0]})
    spec = spec.model_copy(update={"loads": {name: deeper}})
    with_load = forces(spec, np.array([angle]), variants=variants).driving_torque
    idle = forces(spec.model_copy(update={"loads": {}}), np.array([angle]), variants=variants).driving_torque
    torque = np.ravel(with_load) - np.ravel(idle)
    return torque if variants is not None else float(torque[0])


def _file(geo, stroke, force, before, psi, k, making: Making) -> tuple:  # noqa: ANN001
    """The file's data and comments, assembled at the top (the four-bar stretched)."""
    speed, section, density = making
    a, r, b = rounded(geo["toggle"]), rounded(geo["crank"]), rounded(geo["rod"])
    o = np.array([rounded(float(x)) for x in geo["O"]])
    top = a * np.array([math.sin(psi), -math.cos(psi)])
    start = math.atan2(*(top - o)[::-1])
    mass = {key: float(f"{bar_mass(geo[key], section, density):.6g}") for key in ("crank", "rod", "toggle")}
    low, before = -2 * a, rounded(before)
    data = {
        "name": "toggle-press",
        "description": f"Knuckle-joint press synthesised for the stroke {stroke * 1e3:.6g} mm and the nominal force "
        f"{force / 1e3:.6g} kN at {before * 1e3:.6g} mm before the bottom dead centre (toggle swing "
        f"{math.degrees(psi):.6g} deg, four-bar K = {k:.6g}).  Masses: steel bars {section[0] * 1e3:g} x "
        f"{section[1] * 1e3:g} mm, {density:g} kg/m^3.",
        "units": {"length": "mm", "mass": "kg", "angle": "deg"},
        "frame": {"points": {"P": [0.0, 0.0], "O": [mm(o[0]), mm(o[1])]}},
        "links": {
            "crank": {"ends": ["O", "A"], "length": mm(r), "mass": mass["crank"]},
            "rod": {"ends": ["A", "K"], "length": mm(b), "mass": mass["rod"]},
            "upper": {"ends": ["P", "K"], "length": mm(a), "mass": mass["toggle"]},
            "lower": {"ends": ["K", "R"], "length": mm(a), "mass": mass["toggle"]},
            "ram": {"points": {"R": [0.0, 0.0]}, "mass": mass["toggle"], "inertia": 0},
        },
        "joints": {
            "O": {"type": "revolute", "links": ["frame", "crank"]},
            "A": {"type": "revolute", "links": ["crank", "rod"]},
            "K": {"type": "revolute", "links": ["rod", "upper", "lower"]},
            "P": {"type": "revolute", "links": ["frame", "upper"]},
            "R": {"type": "revolute", "links": ["lower", "ram"]},
            "guide": {
                "type": "prismatic",
                "links": ["frame", "ram"],
                "point": "R",
                "through": [0.0, 0.0],
                "axis": -90.0,
            },
        },
        "loads": {
            "pressing": {
                "type": "process",
                "tools": ["ram.R"],
                "axis": 90.0,
                "workpiece": [mm(low), mm(low + before)],
                "penetration": [0.0, 1.0],
                "force": [newtons(force)] * 2,
            },
        },
        "drives": [{"joint": "O", "speed": speed, "direction": "cw", "angle": degrees(start)}],
        "hints": {"K": [mm(top[0]), mm(top[1])], "R": [0.0, mm(-2 * a * math.cos(psi))]},
    }
    comments = {
        ("links", "upper", "length"): f"a = H / (2 (1 - cos psi)): stroke H = {stroke * 1e3:.6g} mm",
        ("links", "crank", "length"): f"the crank-rocker for the swing {math.degrees(psi):.6g} deg, K = {k:.6g}",
        ("loads", "pressing", "workpiece"): f"the nominal force from {before * 1e3:.6g} mm before the bottom",
        ("links", "rod", "length"): "the crank-rocker's coupler, the same member",
        ("links", "lower", "length"): "a, as the upper: the symmetric toggle",
        ("frame", "points", "O"): "the crank pivot: the four-bar turned so its folded limit holds the toggle straight",
        ("hints", "K"): "the knuckle at the top, the upper link at the swing from the vertical",
    }
    return data, comments
