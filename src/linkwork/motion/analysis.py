"""What an engineer reads off the motion, over design variants x crank angles: the sliders and
rockers of the frame, their strokes, swings and time ratios, the guides' directions, the transmission
angles and the instantaneous centres.

This module is the one home of these quantities: the sweeps' metrics, the report, the viewer and the
command line call it.  Arrays are ``(V, A)`` (variants, angles) as in :class:`~linkwork.motion.Kinematics`'
state, ``(V,)`` for a quantity of the whole turn.

Two time ratios, at uniform crank speed, from the crank angles turned during the two strokes between
the extreme positions:

* ``time_ratio``: the classical coefficient K, the longer stroke's time over the shorter's (>= 1),
  whatever the direction of rotation;
* ``forward_time_ratio``: the time of the stroke in which the slider moves in the + direction of its
  guide's axis (the rocker turns counter-clockwise) over the time of the other stroke; it turns into
  its reciprocal when the crank turns the other way.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from linkwork.angles import TWO_PI, unwrap, wrap
from linkwork.motion.groups import KINDS
from linkwork.motion.kinematic_analysis import Kinematics, cycle, kinematics
from linkwork.structure.model import Mechanism, PairType, per_mechanism
from linkwork.units import turn_deg

# ---------------------------------------------------------------- the frame's sliders and rockers


@dataclass(frozen=True)
class Output:
    """A slider on a guide of the frame, or a link pivoted on the frame: an output whose extremes are read.

    Attributes
    ----------
    kind : str
        ``"slider"`` (its coordinate in m along the guide's axis) or ``"rocker"`` (its angle, rad).
    name : str
        The prismatic joint of a slider, the link of a rocker.
    pair : int
        The pair on the frame (the prismatic one of a slider, the pivot of a rocker).
    link : int
        The moving link.
    point : int
        The slider's point on the guide; -1 for a rocker.
    """

    kind: str
    name: str
    pair: int
    link: int
    point: int = -1


def outputs(mech: Mechanism) -> tuple[Output, ...]:
    """The sliders on frame guides and the links pivoted on the frame, in the order of their pairs.

    A slider is the moving link of a prismatic pair whose guide is the frame's (the frame named first);
    a rocker is a link joined to the frame by a revolute pair, named first or second.  Drives, the links
    they move and the massless blocks of pin-in-slot joints are left out.  Whether a pivoted link swings
    or turns fully depends on the dimensions: see :attr:`Range.turns`.
    """
    driven = {int(k) for k in mech.drive_pair}
    driven_links = {_moving(mech, k) for k in driven}
    out: list[Output] = []
    seen: set[int] = set()
    for k in range(mech.n_pairs):
        a, b = (int(x) for x in mech.pair_links[k])
        if k in driven or 0 not in (a, b):
            continue
        link = _moving(mech, k)
        if mech.link_virtual[link] or link in seen:
            continue
        if mech.pair_type[k] == PairType.PRISMATIC and a == 0:
            out.append(Output("slider", str(mech.pair_joint[k]), k, link, int(mech.pair_points[k, 1])))
        elif mech.pair_type[k] == PairType.REVOLUTE and link not in driven_links:
            out.append(Output("rocker", str(mech.link_names[link]), k, link))
        else:
            continue
        seen.add(link)
    return tuple(out)


def _moving(mech: Mechanism, k: int) -> int:
    """The link of pair ``k`` other than the frame (the second one when neither is the frame)."""
    a, b = (int(x) for x in mech.pair_links[k])
    return a if b == 0 else b


def find_output(mech: Mechanism, name: str | None, kind: str) -> Output | None:
    """The output of ``kind`` named ``name`` (a slider's joint or a rocker's link), or the first; None if none."""
    for out in outputs(mech):
        if out.kind == kind and (name is None or out.name == name):
            return out
    return None


def guide_lines(kin: Kinematics, pairs: npt.ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """The guide lines of the prismatic pairs ``pairs`` ``(K,)`` of every variant at every angle, in the frame's
    axes: the one home of carrying a guide with the link that carries it (the plans, the scheme, the forces and the
    viewer's charts read their guides here).

    Returns
    -------
    origin, direction : ndarray, shape (K, 2, V, A)
        A point of each line (m) and its unit direction (the joint's ``origin`` and ``axis``, the variant's,
        turned and moved with the link that carries the guide, the pair's first).
    """
    pairs = np.asarray(pairs, dtype=np.intp)
    q = kin.q[kin.mechanism.pair_links[pairs, 0]]  # (K, 3, V, A)
    c, s = np.cos(q[:, 2]), np.sin(q[:, 2])
    ox, oy, ux, uy = kin.origin[pairs, 0], kin.origin[pairs, 1], kin.axis[pairs, 0], kin.axis[pairs, 1]  # (K, V, 1)
    origin = np.stack([q[:, 0] + c * ox - s * oy, q[:, 1] + s * ox + c * oy], 1)
    return origin, np.stack([c * ux - s * uy, s * ux + c * uy], 1)


def guide(kin: Kinematics, k: int) -> tuple[np.ndarray, np.ndarray]:
    """The guide line of prismatic pair ``k`` of every variant at every angle, in the frame's axes
    (:func:`guide_lines`).

    Returns
    -------
    origin, direction : ndarray, shape (V, A, 2)
        A point of the line (m) and its unit direction.
    """
    origin, direction = guide_lines(kin, [k])
    return np.ascontiguousarray(np.moveaxis(origin[0], 0, -1)), np.ascontiguousarray(np.moveaxis(direction[0], 0, -1))


def coordinate(kin: Kinematics, out: Output) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The coordinate of an output and its first and second time derivatives, ``(V, A)`` each.

    A slider's position along its guide's axis from the guide's origin (m, m/s, m/s^2), on the variant's
    guide (:func:`slider_coordinates`); a rocker's angle (rad, unwrapped along the samples that assemble),
    angular velocity and acceleration.
    """
    if out.kind == "rocker":
        return unwrap(kin.q[out.link, 2]), kin.v[out.link, 2], kin.a[out.link, 2]
    s, v, a = slider_coordinates(kin, [out])[0]
    return s, v, a


def slider_coordinates(kin: Kinematics, sliders: Sequence[Output]) -> np.ndarray:
    """The coordinate of each of ``sliders`` along its guide (:func:`guide_lines`) from the guide's origin and its
    first and second time derivatives, ``(S, 3, V, A)`` (m, m/s, m/s^2), all at once."""
    if not sliders:
        return np.zeros((0, 3) + kin.q.shape[2:])
    origin, u = guide_lines(kin, [o.pair for o in sliders])  # (S, 2, V, A)
    motion = np.array([kin.motion_of(kin.mechanism.point_names[o.point]) for o in sliders])  # (S, 3, V, A, 2)
    motion[:, 0, ..., 0] -= origin[:, 0]
    motion[:, 0, ..., 1] -= origin[:, 1]
    # + 0.0: a sum of x and y that is -0.0 reads 0.0, as a sum along an axis gives it
    return motion[..., 0] * u[:, None, 0] + motion[..., 1] * u[:, None, 1] + 0.0


# ---------------------------------------------------------------- extremes over the turn


@dataclass(frozen=True)
class Range:
    """The extremes of a quantity sampled over a whole turn of the crank, for every variant: ``(V,)`` arrays.

    Attributes
    ----------
    low, high : ndarray
        Extreme values, refined between the samples (see :func:`sampled_range`; NaN where no sample
        assembles or a rocker turns fully).
    at_low, at_high : ndarray
        Drive coordinates (rad) at which they occur.
    whole : ndarray of bool
        Every sample of the turn assembles: the time ratios need the whole turn (NaN otherwise).
    sign : float
        +1 for samples in increasing drive angle (counter-clockwise), -1 for decreasing.
    turns : ndarray of bool
        A rocker that turns fully about its pivot (no swing, no extremes); False for anything else.
    """

    low: np.ndarray
    high: np.ndarray
    at_low: np.ndarray
    at_high: np.ndarray
    whole: np.ndarray
    sign: float
    turns: np.ndarray

    @property
    def stroke(self) -> np.ndarray:
        """``high - low``: a slider's stroke (m) or a rocker's swing (rad)."""
        return self.high - self.low

    @property
    def rising(self) -> np.ndarray:
        """Crank angle (rad, in the drive's direction) turned from the low extreme to the high one:
        the time of that stroke at uniform crank speed, times the speed; NaN without the whole turn."""
        rise = (self.sign * (self.at_high - self.at_low)) % TWO_PI
        return np.where(self.whole & ~self.turns, rise, np.nan)

    @property
    def falling(self) -> np.ndarray:
        """Crank angle turned from the high extreme back to the low one (rad)."""
        return TWO_PI - self.rising

    @property
    def time_ratio(self) -> np.ndarray:
        """The coefficient K of the strokes' times: the longer over the shorter, >= 1."""
        rise, fall = self.rising, self.falling
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.maximum(rise, fall) / np.minimum(rise, fall)

    @property
    def forward_time_ratio(self) -> np.ndarray:
        """The time of the rising stroke (the + direction) over the time of the falling one."""
        with np.errstate(divide="ignore", invalid="ignore"):
            return self.rising / self.falling


def sampled_range(values: np.ndarray, angles: np.ndarray, slopes: tuple[np.ndarray, np.ndarray] | None = None) -> Range:
    """Extremes of periodic samples ``(V, A)`` over a whole turn at equally spaced drive angles ``(A,)``.

    With ``slopes``, the first and second derivatives of the values with respect to the drive angle
    ``(V, A)`` each (velocity over crank speed, acceleration over its square at uniform speed), each
    extreme is refined between its two samples by the quintic through the values and both derivatives
    there (errors of the order of the sixth power of the step); without them, or where they are not
    finite, by a parabola through the extreme sample and its two neighbours.  Samples that are NaN (the
    mechanism does not assemble there) are left out of the extremes; the time ratios then are NaN.
    """
    values = np.asarray(values, dtype=float)
    angles = np.asarray(angles, dtype=float)
    low, at_low = _peak(-values, angles, None if slopes is None else (-slopes[0], -slopes[1]))
    high, at_high = _peak(values, angles, slopes)
    sign = 1.0 if len(angles) < 2 or angles[1] > angles[0] else -1.0
    whole = np.isfinite(values).all(axis=-1)
    return Range(-low, high, at_low, at_high, whole, sign, np.zeros(values.shape[:-1], dtype=bool))


def _peak(
    y: np.ndarray, angles: np.ndarray, slopes: tuple[np.ndarray, np.ndarray] | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """Largest value of periodic samples ``(V, A)`` and its drive angle, refined between samples (see
    :func:`sampled_range`); NaN for a row without a finite sample."""
    n = y.shape[-1]
    finite = np.isfinite(y)
    i = np.argmax(np.where(finite, y, -np.inf), axis=-1)[..., None]
    y0, y1, y2 = (np.take_along_axis(y, (i + d) % n, -1)[..., 0] for d in (-1, 0, 1))
    den = y0 - 2 * y1 + y2
    with np.errstate(invalid="ignore", divide="ignore"):
        t = np.where(np.isfinite(den) & (den != 0), 0.5 * (y0 - y2) / den, 0.0)
    t = np.clip(t, -1.0, 1.0) if n > 2 else np.zeros_like(t)
    step = angles[1] - angles[0] if n > 1 else 0.0
    peak = np.where(t != 0, y1 - 0.25 * (y0 - y2) * t, y1)
    at = angles[i[..., 0]] + t * step
    if slopes is not None and n > 2:
        peak, t = _quintic(y, slopes, i, step, peak, t)
        at = angles[i[..., 0]] + t * step
    none = ~finite.any(axis=-1)
    return np.where(none, np.nan, peak), np.where(none, np.nan, at)


def _quintic(
    y: np.ndarray, slopes: tuple[np.ndarray, np.ndarray], i: np.ndarray, step: float, peak: np.ndarray, t: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """The maximum of the quintic Hermite interpolant between the largest sample ``i`` ``(V, 1)`` and the
    neighbour the slope rises towards: ``(value, offset in steps from i)``; ``peak`` and ``t`` (the parabola's)
    where a derivative is not finite or the maximum is not inside the interval."""
    n = y.shape[-1]
    d1, d2 = (np.asarray(d, dtype=float) * f for d, f in zip(slopes, (step, step * step), strict=True))
    ahead = np.take_along_axis(d1, i, -1) > 0  # (V, 1): the maximum lies between i and i + 1
    j = np.where(ahead, i, i - 1) % n
    a, b = (np.take_along_axis(y, k, -1)[..., 0] for k in (j, (j + 1) % n))
    da, db = (np.take_along_axis(d1, k, -1)[..., 0] for k in (j, (j + 1) % n))
    sa, sb = (np.take_along_axis(d2, k, -1)[..., 0] for k in (j, (j + 1) % n))
    c3 = 10 * (b - a) - 6 * da - 4 * db - 1.5 * sa + 0.5 * sb
    c4 = -15 * (b - a) + 8 * da + 7 * db + 1.5 * sa - sb
    c5 = 6 * (b - a) - 3 * da - 3 * db - 0.5 * sa + 0.5 * sb
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        u = np.clip(np.where(da != db, da / (da - db), 0.5), 0.0, 1.0)  # the slope's zero, linearly
        for _ in range(4):  # Newton on the quintic's slope
            slope = da + u * (sa + u * (3 * c3 + u * (4 * c4 + u * 5 * c5)))
            curve = sa + u * (6 * c3 + u * (12 * c4 + u * 20 * c5))
            u = np.clip(u - np.where(curve < 0, slope / curve, 0.0), 0.0, 1.0)
        value = a + u * (da + u * (0.5 * sa + u * (c3 + u * (c4 + u * c5))))
    offset = np.where(ahead[..., 0], u, u - 1.0)
    top = np.take_along_axis(y, i, -1)[..., 0]
    good = np.isfinite(value) & (value >= top)  # the interpolant passes through the largest sample
    return np.where(good, value, peak), np.where(good, offset, t)


def slopes(kin: Kinematics, rate: np.ndarray, accel: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """First and second derivatives ``(V, A)`` with respect to the crank angle of a quantity whose time
    derivatives are ``rate`` and ``accel``, the crank turning uniformly (as :func:`linkwork.kinematics`
    solves a turn)."""
    speed = kin.rates[:, 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        return rate / speed, accel / (speed * speed)


def output_range(kin: Kinematics, out: Output) -> Range:
    """The extremes of an output over a whole turn (:func:`linkwork.kinematics` with ``steps=``), ``(V,)``:
    a slider's stroke along its variant's guide, a rocker's swing; NaN for a rocker that turns fully."""
    values, rate, accel = coordinate(kin, out)
    r = sampled_range(values, kin.angles, slopes(kin, rate, accel))
    if out.kind != "rocker":
        return r
    turns = _turns(values, r.whole)
    low, high, at_low, at_high = (np.where(turns, np.nan, x) for x in (r.low, r.high, r.at_low, r.at_high))
    return Range(low, high, at_low, at_high, r.whole, r.sign, turns)


def _turns(angle: np.ndarray, whole: np.ndarray) -> np.ndarray:
    """Whether an unwrapped angle ``(V, A)`` turns fully: over a whole turn of samples, it does not come back
    to its first value; over a part of the turn, it spans a full turn."""
    last_to_first = angle[..., 0] - angle[..., -1]
    winding = wrap(last_to_first) - last_to_first
    ok = np.isfinite(angle)
    with np.errstate(invalid="ignore"):
        span = np.max(np.where(ok, angle, -np.inf), -1) - np.min(np.where(ok, angle, np.inf), -1)
        return np.where(whole, np.abs(winding) > math.pi, span >= TWO_PI - 1e-6)


@dataclass(frozen=True)
class Extremes:
    """Extreme positions of one output of one variant (a view of :func:`output_range`).

    Attributes
    ----------
    name : str
        The joint (slider) or link (rocker).
    kind : str
        ``"slider"`` (values in m along the guide axis) or ``"rocker"`` (rad).
    low, high : float
        Extreme values, refined between samples (see :func:`sampled_range`).
    at_low, at_high : float
        Drive coordinates (rad) at which they occur.
    stroke : float
        ``high - low``.
    forward, backward : float
        Drive angles of the stroke from low to high and back, in the direction of rotation.
    time_ratio : float
        The coefficient K: the longer stroke's time over the shorter's, >= 1 (uniform crank speed).
    forward_time_ratio : float
        ``forward / backward``: the stroke in the + direction (the rocker turning counter-clockwise) over
        the other.
    """

    name: str
    kind: str
    low: float
    high: float
    at_low: float
    at_high: float
    stroke: float
    forward: float
    backward: float
    time_ratio: float
    forward_time_ratio: float

    def as_dict(self) -> dict[str, Any]:
        unit = "m" if self.kind == "slider" else "rad"
        return {
            "name": self.name,
            "kind": self.kind,
            "unit": unit,
            "low": self.low,
            "high": self.high,
            "stroke": self.stroke,
            "at_low_deg": math.degrees(self.at_low),
            "at_high_deg": math.degrees(self.at_high),
            "forward_deg": math.degrees(self.forward),
            "backward_deg": math.degrees(self.backward),
            "time_ratio": self.time_ratio,
            "forward_time_ratio": self.forward_time_ratio,
        }


def extremes(kin: Kinematics, variant: int = 0) -> list[Extremes]:
    """Strokes of the sliders on frame guides and swings of the rockers pivoted on the frame, of one variant.

    Meaningful for a whole cycle of a crank (``steps=`` or equally spaced angles over a turn); the time
    ratios assume a uniform drive speed.  Links pivoted on the frame that turn fully are left out.
    """
    rows = []
    for out in outputs(kin.mechanism):
        r = output_range(kin, out)
        if r.turns[variant]:
            continue
        values = (r.low, r.high, r.at_low, r.at_high, r.stroke, r.rising, r.falling, r.time_ratio, r.forward_time_ratio)
        rows.append(Extremes(out.name, out.kind, *(float(v[variant]) for v in values)))
    return rows


def working(mech: Mechanism) -> tuple[Output, ...]:
    """The working members, whose motion the kinematic diagrams show and whose extreme is position 0: the
    sliders on frame guides (knives, rams, tools), else the rockers pivoted on the frame in the last Assur
    group that has one (the output rocker; both legs of a triad that has two); none for a mechanism with
    neither."""
    found = outputs(mech)
    sliders = tuple(out for out in found if out.kind == "slider")
    if sliders:
        return sliders
    group = {link: i for i, g in enumerate(mech.structure.groups) for link in g.links}
    last = max((group.get(out.link, -1) for out in found), default=-1)
    return tuple(out for out in found if group.get(out.link, -1) == last)


@per_mechanism
def zero_angle(mech: Mechanism) -> float:
    """Crank angle (rad) of position 0: the first working member (:func:`working`) at the high end of its
    stroke or swing (for shears: the upper knife up, the knives open), else the assembly angle.  Found once
    a mechanism."""
    members = working(mech)
    if members:
        r = output_range(kinematics(mech, steps=360), members[0])
        if np.isfinite(r.at_high[0]) and not r.turns[0]:
            return float(r.at_high[0])
    return float(mech.drive_start[0])


def from_position_0(angles: np.ndarray, zero: float, direction: float) -> np.ndarray:
    """The crank angle turned from position 0 (drive angle ``zero``, rad) in the drive's direction
    (``direction`` +1 counter-clockwise, -1 clockwise), rad in [0, 2 pi), the shape of ``angles`` (drive
    angles, rad).  The abscissa of every diagram over the cycle and the angle of every table of the report,
    as the 12 positions number the cycle from position 0."""
    turned = np.mod(direction * (np.asarray(angles, dtype=float) - zero), TWO_PI)
    return np.where(TWO_PI - turned < 1e-9, 0.0, turned)


#: Decimals of the crank angles in degrees that tables and JSON write: 1e-9 deg (2e-11 rad), below any
#: sampling, and an angle that is a whole or decimal number of degrees is written as that number.
ANGLE_DECIMALS = 9

#: The names of the crank's two angles in tables (CSV headings, NetCDF coordinates: ``phi [deg]``) and in
#: JSON (``phi_deg``): φ turned from position 0, and the crank's angle to the frame's x axis.
PHI, TO_X = "phi", "crank_angle_to_x"


def phi_deg(angles: npt.ArrayLike, zero: float, direction: float, digits: int = ANGLE_DECIMALS) -> Any:
    """φ of drive angles (rad): the crank angle turned from position 0 (drive angle ``zero``, rad) in the
    drive's ``direction`` (+1 or -1), in degrees in [0, 360) to ``digits`` decimals, as every table, JSON
    and printed line writes it (:func:`from_position_0`, :func:`~linkwork.units.turn_deg`)."""
    return turn_deg(from_position_0(np.asarray(angles, dtype=float), zero, direction), digits)


def to_x_deg(angles: npt.ArrayLike, digits: int = ANGLE_DECIMALS) -> Any:
    """The crank's angle to the frame's x axis of drive angles (rad), counter-clockwise, in degrees in
    [0, 360) to ``digits`` decimals: the angle of the tables' ``crank_angle_to_x`` column."""
    return turn_deg(np.asarray(angles, dtype=float), digits)


@dataclass(frozen=True)
class CrankAngles:
    """How the crank angles of a mechanism with one crank are written: φ from position 0 (``zero``, the
    drive angle of position 0, rad, :func:`zero_angle`; ``direction`` +1 or -1, the drive's) and the angle
    to x.  Design variants share the mechanism's position 0: φ is one coordinate of the samples."""

    zero: float
    direction: float

    @classmethod
    def of(cls, mech: Mechanism, zero: float | None = None) -> CrankAngles | None:
        """The crank angles of ``mech`` (position 0 at ``zero``, rad, default :func:`zero_angle`); None
        unless it has one crank (a linear drive, or several drives, have no φ)."""
        from linkwork.structure.model import one_crank

        if not one_crank(mech):
            return None
        from linkwork.motion.kinematic_analysis import direction

        return cls(zero_angle(mech) if zero is None else float(zero), direction(mech))

    def phi(self, angles: npt.ArrayLike, digits: int = ANGLE_DECIMALS) -> Any:
        """φ of drive angles (rad), degrees in [0, 360) (:func:`phi_deg`)."""
        return phi_deg(angles, self.zero, self.direction, digits)

    def columns(self, angles: npt.ArrayLike) -> dict[str, np.ndarray]:
        """The two angles of drive angles (rad) as a table's first columns, by their names (:data:`PHI`,
        :data:`TO_X`), degrees."""
        a = np.asarray(angles, dtype=float)
        return {PHI: np.asarray(self.phi(a)), TO_X: np.asarray(to_x_deg(a))}

    def record(self) -> dict[str, float]:
        """What a JSON record says of position 0: ``position_0_deg`` (the crank's angle to x there) and
        ``direction`` (+1 counter-clockwise, -1 clockwise)."""
        return {"position_0_deg": float(to_x_deg(self.zero)), "direction": self.direction}


def position_angles(mech: Mechanism, count: int = 12, zero: float | None = None) -> np.ndarray:
    """Drive angles (rad) of ``count`` positions evenly over a turn from position 0 (``zero``, default
    :func:`zero_angle`), in the drive's direction: the positions 0, 1, ... of the plan of positions."""
    return cycle(mech, count, start=zero_angle(mech) if zero is None else zero)


# ---------------------------------------------------------------- transmission angles, instant centres


def transmission(kin: Kinematics) -> dict[str, np.ndarray]:
    """Transmission angle of every closed-form dyad (the kinds with ``transmission`` in
    :data:`linkwork.motion.groups.KINDS`: RRR, RRP, PRP, RPR), rad in [0, pi/2]: ``(V, A)`` each.

    The angle between the directions in which the two links of the dyad would move the joint X where
    they meet (for an RRR dyad, the angle between coupler and rocker; for an RRP dyad, between the rod
    and the normal to the guide), folded into [0, 90] deg: 90 deg transmits best, 0 is a dead point.
    It is the arcsine of the dyad's normalised Jacobian determinant.
    """
    out = {}
    for step, det in zip(kin.mechanism.program, kin.step_det, strict=True):
        if KINDS[step.kind].transmission:
            out[step.label] = np.arcsin(np.clip(np.abs(det), 0.0, 1.0))
    return out


def transmission_angles(kin: Kinematics) -> dict[str, np.ndarray]:
    """:func:`transmission` without the variant axis for a result without variants: ``(..., n_angles)``."""
    return {label: kin._out(mu) for label, mu in transmission(kin).items()}


def instant_centre(kin: Kinematics, link: str | int, relative_to: str | int = 0) -> np.ndarray:
    """Instantaneous centre of velocity of ``link`` (relative to another link; default the frame).

    The point where both links have the same velocity: ``(..., n_angles, 2)``,
    NaN where their angular velocities are equal (the centre is at infinity,
    e.g. a slider relative to its guide).
    """
    i, j = kin.link_index(link), kin.link_index(relative_to)
    qi, vi, qj, vj = kin.q[i], kin.v[i], kin.q[j], kin.v[j]
    dw = vi[2] - vj[2]
    # v_Oi + w_i perp(P - O_i) = v_Oj + w_j perp(P - O_j)  =>  dw perp(P) = rhs
    rx = vj[0] - vi[0] - vi[2] * qi[1] + vj[2] * qj[1]
    ry = vj[1] - vi[1] + vi[2] * qi[0] - vj[2] * qj[0]
    with np.errstate(divide="ignore", invalid="ignore"):
        px, py = ry / dw, -rx / dw
    scale = np.maximum(np.abs(vi[2]), np.abs(vj[2]))
    far = np.abs(dw) <= 1e-12 * np.maximum(scale, 1e-300)
    px, py = np.where(far, np.nan, px), np.where(far, np.nan, py)
    return kin._out(np.stack([px, py], -1))
