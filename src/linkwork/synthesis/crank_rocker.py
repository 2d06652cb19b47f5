"""Synthesis of a crank-rocker four-bar from the rocker's swing psi, the time ratio K and a length.

The theory (derived here; the classical circle construction):

* The rocker O4 B is at its extremes B_e and B_f where the crank O2 A and the coupler A B are in line:
  |O2 B_e| = b + a (stretched) and |O2 B_f| = b - a (folded).  The crank's directions there differ by
  pi - theta, theta the angle B_e O2 B_f, so K = (pi + theta) / (pi - theta) as for the slider-crank.
* With the rocker c and the swing psi the chord B_e B_f = 2 c sin(psi / 2) is fixed, and O2 sees it under
  theta: O2 lies on a circle through B_e and B_f (for theta = 0 on their line).  The free parameter of the
  family is t = |O2 B_f| = b - a; then |O2 B_e| = t cos(theta) + sqrt(s^2 - t^2 sin^2(theta)), a and b their
  half difference and half sum, and the frame d = |O2 O4|.
* The member is a crank-rocker with those limit positions when the crank is the shortest link and
  s + l < p + q (Grashof), and B_e and B_f lie on the same side of the line O2 O4: the stretched and the
  folded positions then belong to one assembly mode (both dyads B A O4 have the sign of the triangle
  O2 B O4).
* The transmission angle mu (between coupler and rocker, folded into [0, 90] deg) is extreme with the
  crank along the frame: cos mu = (b^2 + c^2 - (d -+ a)^2) / (2 b c); the least over the turn is the smaller
  of the two folded values.
* The scale is fixed by the rocker c or the frame d (lengths of the family scale with it); the member
  maximises the least transmission angle (Brent on the closed form, on the feasible interval of t).

Layout of the file: crank pivot O2 at the origin, rocker pivot O4 on +x, the crank turning counter-clockwise.
"""

from __future__ import annotations

import math

import numpy as np

from linkwork.errors import SynthesisError
from linkwork.requirements import CrankRockerRequirements
from linkwork.synthesis.common import (
    Family,
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
    proportions,
    time_ratio_of,
)
from linkwork.synthesis.rounding import measure_written

KIND = "crank-rocker"

#: Largest |O2 B_f| of the family for K = 1 (the pivot on the line of B_e B_f), in rocker lengths.
FAR = 50.0


def _limits(swing: float) -> tuple[np.ndarray, np.ndarray]:
    """B_e and B_f for a unit rocker pivoted at the origin, symmetric about -y (the swing below O4)."""
    half = swing / 2
    return np.array([math.sin(half), -math.cos(half)]), np.array([-math.sin(half), -math.cos(half)])


def members(swing: float, theta: float, t: np.ndarray, side: float) -> dict[str, np.ndarray]:
    """The family's members ``t`` (|O2 B_f|, unit rocker) on ``side`` (+1, -1) of the chord: a, b, c = 1, d,
    O2 (``(..., 2)``), the least transmission angle and whether it is a crank-rocker with these limits."""
    be, bf = _limits(swing)
    s = float(np.linalg.norm(be - bf))
    t = np.asarray(t, dtype=float)
    root = np.sqrt(np.maximum(s * s - (t * math.sin(theta)) ** 2, 0.0))
    x = t * math.cos(theta) + root  # |O2 B_e|
    a, b = (x - t) / 2, (x + t) / 2
    # O2 at distance t from B_f and x from B_e (circle intersection), on ``side`` of the chord B_f -> B_e; its
    # distance from the chord from t^2 - along^2 = (t - along) (t + along), t + along = (t + s - x) (t + s + x)
    # / 2s written without the difference t + s - x (0 for theta = 0, where the pivot is on the chord's line)
    u = (be - bf) / s
    along = (t * t - x * x + s * s) / (2 * s)
    near = (t * math.sin(theta)) ** 2 / (s + root) + 2 * t * math.sin(theta / 2) ** 2  # t + s - x
    across = (x - t + s) * (x + t - s) / (2 * s) * near * (t + s + x) / (2 * s)
    off = side * np.sqrt(np.maximum(across, 0.0))
    o2 = bf + along[..., None] * u + off[..., None] * np.array([-u[1], u[0]])
    d = np.linalg.norm(o2, axis=-1)
    mu = least_transmission_angle(a, b, 1.0, d)
    lengths = np.stack([a, b, np.ones_like(a), d])
    longest = lengths.max(axis=0)
    grashof = (a < lengths[1:].min(axis=0)) & (a + longest < lengths.sum(axis=0) - a - longest)
    # B_e and B_f on one side of the line O4 -> O2 (O4 at the origin)
    same = (o2[..., 0] * be[1] - o2[..., 1] * be[0]) * (o2[..., 0] * bf[1] - o2[..., 1] * bf[0]) > 0
    return {
        "crank": a,
        "coupler": b,
        "rocker": np.ones_like(a),
        "frame": d,
        "O2": o2,
        "least_transmission_angle": mu,
        "valid": grashof & same & (t > 0) & (x > t),
    }


def least_transmission_angle(a, b, c, d) -> np.ndarray:  # noqa: ANN001
    """The least transmission angle (rad, folded into [0, pi/2]) of a crank-rocker over the turn."""
    with np.errstate(invalid="ignore"):
        inner = np.arccos(np.clip((b * b + c * c - (d - a) ** 2) / (2 * b * c), -1, 1))
        outer = np.arccos(np.clip((b * b + c * c - (d + a) ** 2) / (2 * b * c), -1, 1))
    fold = lambda m: np.minimum(m, np.pi - m)  # noqa: E731
    return np.minimum(fold(inner), fold(outer))


def top(theta: float, swing: float) -> float:
    """The largest t = |O2 B_f| (unit rocker) of the family: the diameter of the circle that sees the chord
    under theta, :data:`FAR` for theta = 0."""
    s = 2 * math.sin(swing / 2)
    return FAR if theta == 0 else s / (2 * math.sin(theta / 2))


def family(swing: float, time_ratio: float, count: int = 401) -> Family:
    """The family over t = |O2 B_f| (unit rocker) on both sides of the chord: the sides one after the other;
    NaN where a member is not a crank-rocker with these limit positions."""
    theta = crank_angle_between_limits(time_ratio)
    t = np.linspace(0.0, top(theta, swing), count + 2)[1:-1]
    cols: dict[str, list[np.ndarray]] = {}
    for side in (1.0, -1.0):
        m = members(swing, theta, t, side)
        for key in ("crank", "coupler", "frame", "least_transmission_angle"):
            cols.setdefault(key, []).append(np.where(m["valid"], m[key], np.nan))
        cols.setdefault("side", []).append(np.full_like(t, side))
    columns = {k: np.concatenate(v) for k, v in cols.items()}
    return Family("|O2 B_f| / rocker", "1", np.concatenate([t, t]), columns, "greatest least transmission angle")


def best(swing: float, theta: float) -> tuple[float, float, float]:
    """(t, side, least transmission angle) of the member with the greatest least transmission angle."""
    from scipy.optimize import minimize_scalar

    upper = top(theta, swing)
    t = np.linspace(0.0, upper, 2001)[1:-1]
    found = []
    for side in (1.0, -1.0):
        m = members(swing, theta, t, side)
        score = np.where(m["valid"], m["least_transmission_angle"], -np.inf)
        i = int(np.argmax(score))
        if np.isfinite(score[i]):
            lo, hi = t[max(i - 1, 0)], t[min(i + 1, len(t) - 1)]

            def f(x: float, side: float = side) -> float:
                mm_ = members(swing, theta, np.array([x]), side)
                return -float(mm_["least_transmission_angle"][0]) if mm_["valid"][0] else math.pi

            res = minimize_scalar(f, bounds=(lo, hi), method="bounded", options={"xatol": 1e-13 * upper})
            found.append((float(res.x), side, -float(res.fun)))
    if not found:
        raise SynthesisError(
            f"swing {deg(swing)} with time ratio K = {time_ratio_of(theta):.6g} (theta {deg(theta)}): no crank-rocker "
            f"has these limit positions; the swing {deg(swing)} gives K <= {down(_feasible_ratio(swing))}"
        )
    return max(found, key=lambda f: f[2])


def central(swing: float, bound: float | None) -> tuple[float, float, float]:
    """(t, side, least transmission angle) for K = 1: O2 on the line of B_e B_f, the nearest member (the
    most compact) whose least transmission angle reaches ``bound``; the angle grows toward pi/2 - psi/2 as
    O2 moves away, so the bound is needed."""
    from scipy.optimize import brentq

    limit = math.pi / 2 - swing / 2
    if bound is None:
        raise SynthesisError(
            "time ratio K = 1 leaves the frame free (the least transmission angle grows toward 90 deg - swing/2 = "
            f"{deg(limit)} as the crank pivot moves away): give the least transmission angle"
        )
    t = np.linspace(0.0, FAR, 20001)[1:]
    m = members(swing, 0.0, t, 1.0)
    ok = np.flatnonzero(m["valid"] & (m["least_transmission_angle"] >= bound))
    if len(ok) == 0 or ok[0] == 0:
        raise SynthesisError(
            f"swing {deg(swing)} with time ratio K = 1 gives a least transmission angle under {deg(limit)}; "
            f"at least {deg(bound)} cannot be met"
        )
    f = lambda x: float(members(swing, 0.0, np.array([x]), 1.0)["least_transmission_angle"][0]) - bound  # noqa: E731
    x = float(brentq(f, t[ok[0] - 1], t[ok[0]], xtol=1e-15))
    # the root to the last bit may fall a rounding short of the bound: step onto the side that meets it
    x = next((y for y in _ulps_up(x, 64) if f(y) >= 0), float(t[ok[0]]))
    return x, 1.0, bound + f(x)


def _ulps_up(x: float, count: int) -> list[float]:
    """``x`` and the ``count`` floats above it."""
    out = [x]
    for _ in range(count):
        out.append(math.nextafter(out[-1], math.inf))
    return out


def _feasible_ratio(swing: float) -> float:
    """The largest K (to 1e-4 of theta) with a crank-rocker of this swing: bisection on the feasibility of
    the family (the members sampled as :func:`best` samples them)."""
    lo, hi = 0.0, math.pi
    while hi - lo > 1e-4:
        mid = (lo + hi) / 2
        t = np.linspace(0.0, top(mid, swing), 2001)[1:-1]
        if any(members(swing, mid, t, side)["valid"].any() for side in (1.0, -1.0)):
            lo = mid
        else:
            hi = mid
    return time_ratio_of(lo)


def greatest_least_angle(swing: float, time_ratio: float) -> float:
    """The greatest least transmission angle (rad) a crank-rocker of this swing and K reaches."""
    theta = crank_angle_between_limits(time_ratio)
    if theta == 0:
        return math.pi / 2 - swing / 2
    try:
        return best(swing, theta)[2]
    except SynthesisError:
        return 0.0


def largest_time_ratio(swing: float, angle: float) -> float:
    """The largest K a crank-rocker of this swing reaches with a least transmission angle of at least
    ``angle`` (rad); 1 where even K = 1 cannot."""
    from scipy.optimize import brentq

    if greatest_least_angle(swing, 1.0) <= angle:
        return 1.0
    hi = 1.0 + 1e-3
    while hi < 1e3 and greatest_least_angle(swing, hi) >= angle:
        hi = 1 + 2 * (hi - 1)
    return float(brentq(lambda k: greatest_least_angle(swing, k) - angle, 1.0, hi, xtol=1e-12))


def nearest(swing: float, time_ratio: float, bound: float) -> str:
    """The nearest request with a least transmission angle of at least ``bound``: the largest time ratio for this
    swing, else the largest swing for this time ratio (bisection on :func:`greatest_least_angle`, rounded down)."""
    if greatest_least_angle(swing, 1.0) > bound:
        return f"K <= {down(largest_time_ratio(swing, bound))} meets it with this swing"
    lo, hi = 0.0, swing
    for _ in range(50):
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if greatest_least_angle(mid, time_ratio) > bound else (lo, mid)
    return f"a swing of at most {down(math.degrees(lo))} deg meets it with K = {time_ratio:g}"


def synthesize(asked: CrankRockerRequirements) -> Synthesis:
    """A crank-rocker for the swing psi (rad) and time ratio K, scaled by the ``rocker`` or ``frame`` length
    (m), picked with the greatest least transmission angle; ``min_transmission_angle`` (rad) a bound it must
    meet.  Links are steel bars of ``section`` and ``density``.  Verified by the analysis of the written file:
    ``asked``, SI."""
    swing, time_ratio, rocker, frame = asked.swing, asked.time_ratio, asked.rocker, asked.frame
    speed, section, density = asked.speed, asked.section, asked.density
    min_transmission_angle = asked.min_transmission_angle
    if not 0 < swing < math.pi:
        raise SynthesisError(f"swing {deg(swing)}: a crank-rocker swings between 0 and 180 deg")
    if not 1.0 <= time_ratio < math.inf:
        raise SynthesisError(
            f"time ratio K = {time_ratio:g}: expected a finite K >= 1 (the longer stroke's time over the shorter)"
        )
    if (rocker is None) == (frame is None):
        raise SynthesisError("give one of the rocker length and the frame length: it fixes the scale")
    scale_given = rocker if rocker is not None else frame
    if not (scale_given is not None and math.isfinite(scale_given) and scale_given > 0):
        raise SynthesisError(
            f"{'rocker' if rocker is not None else 'frame'} length {scale_given!r} m: expected a positive length"
        )
    bound = least_allowed(min_transmission_angle)
    theta = crank_angle_between_limits(time_ratio)
    if theta > 0:
        t, side, mu = best(swing, theta)
    elif greatest_least_angle(swing, 1.0) > bound:
        t, side, mu = central(swing, bound)
    else:
        t, side, mu = 0.0, 1.0, greatest_least_angle(swing, 1.0)
    if mu < bound:
        raise below_rule(
            f"swing {deg(swing)} with time ratio K = {time_ratio:g}"
            + (" (the crank pivot far away)" if not theta else ""),
            mu,
            bound,
            nearest(swing, time_ratio, bound),
        )
    m = {k: v[0] for k, v in members(swing, theta, np.array([t]), side).items()}
    scale = rocker if rocker is not None else frame / float(m["frame"])  # type: ignore[operator]
    dims = {k: float(m[k]) * scale for k in ("crank", "coupler", "rocker", "frame")}
    proportions(KIND, dims)
    requirements = given(swing=swing, time_ratio=time_ratio, rocker=rocker, frame=frame, min_transmission_angle=bound)
    written = file_of(*_file(dims, m, scale, swing, time_ratio, theta, mu, Making(speed, section, density)))
    got, tol = measure_written(written.mech, written.spec)
    least = got["min_transmission_angle"]  # of its one dyad
    measured = {"time_ratio": got["time_ratio"], "least_transmission_angle": least, "swing": got["swing"]}
    predicted = {"swing": swing, "time_ratio": time_ratio, "least_transmission_angle": mu}
    confirm(measured, predicted, mu, tol)
    keep_rule(least, bound, tol["min_transmission_angle"])
    why = "the greatest least transmission angle" if theta > 0 else "the nearest crank pivot meeting the bound"
    return Synthesis(
        KIND,
        requirements,
        dims,
        predicted,
        measured,
        written.spec,
        "",
        family(swing, time_ratio),
        f"picked by {why}",
        tolerances=tol,
        tree=written.tree,
    )


def _file(dims, m, scale, swing, time_ratio, theta, mu, making: Making) -> tuple:  # noqa: ANN001
    """The file's data and comments: O2 at the origin, O4 on +x, assembled in the stretched position."""
    speed, section, density = making
    o2 = m["O2"]
    be, _ = _limits(swing)
    ex = -o2 / np.linalg.norm(o2)  # the frame's x axis: O2 -> O4
    ey = np.array([-ex[1], ex[0]])
    to = lambda p: [mm(scale * float(np.dot(p - o2, ex))), mm(scale * float(np.dot(p - o2, ey)))]  # noqa: E731
    stretched = np.array(to(be)) / 1e3
    start = math.atan2(stretched[1], stretched[0])
    mass = {k: float(f"{bar_mass(v, section, density):.6g}") for k, v in dims.items()}
    data = {
        "name": "crank-rocker",
        "description": f"Crank-rocker four-bar synthesised for the swing {math.degrees(swing):.6g} deg and time "
        f"ratio K = {time_ratio:.6g} (theta = {math.degrees(theta):.6g} deg), with the greatest least transmission "
        f"angle.  Masses: steel bars {section[0] * 1e3:g} x {section[1] * 1e3:g} mm, {density:g} kg/m^3.",
        "units": {"length": "mm", "mass": "kg", "angle": "deg"},
        "frame": {"points": {"O2": [0.0, 0.0], "O4": [mm(dims["frame"]), 0.0]}},
        "links": {
            "crank": {"ends": ["O2", "A"], "length": mm(dims["crank"]), "mass": mass["crank"]},
            "coupler": {"ends": ["A", "B"], "length": mm(dims["coupler"]), "mass": mass["coupler"]},
            "rocker": {"ends": ["O4", "B"], "length": mm(dims["rocker"]), "mass": mass["rocker"]},
        },
        "joints": {
            "O2": {"type": "revolute", "links": ["frame", "crank"]},
            "A": {"type": "revolute", "links": ["crank", "coupler"]},
            "B": {"type": "revolute", "links": ["coupler", "rocker"]},
            "O4": {"type": "revolute", "links": ["frame", "rocker"]},
        },
        "drives": [{"joint": "O2", "speed": speed, "direction": "ccw", "angle": degrees(start)}],
        "hints": {"B": to(be)},
    }
    comments = {
        ("frame", "points", "O4"): f"frame d: the greatest least transmission angle, {math.degrees(mu):.6g} deg",
        ("links", "crank", "length"): f"a = (|O2 B_e| - |O2 B_f|) / 2: swing {math.degrees(swing):.6g} deg",
        ("links", "coupler", "length"): f"b = (|O2 B_e| + |O2 B_f|) / 2: time ratio K = {time_ratio:.6g}",
        ("links", "rocker", "length"): "c: the scale",
        ("hints", "B"): "the stretched limit position (crank and coupler in line)",
    }
    return data, comments
