"""What an engineer reads off the motion: strokes, time ratio, transmission angles,
instantaneous centres."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from linkwork.structure.constraints import PRISMATIC, REVOLUTE


@dataclass(frozen=True)
class Extremes:
    """Extreme positions of a slider (along its guide) or a rocker (its angle).

    Attributes
    ----------
    name : str
        The joint (slider) or link (rocker).
    kind : str
        ``"slider"`` (values in m along the guide axis) or ``"rocker"`` (rad).
    low, high : float
        Extreme values, refined between samples by a parabola.
    at_low, at_high : float
        Drive coordinates (rad) at which they occur.
    stroke : float
        ``high - low``.
    forward, backward : float
        Drive angles of the stroke from low to high and back, in the direction of rotation.
    time_ratio : float
        Time ratio of the strokes at uniform drive speed: the longer over the shorter, >= 1.
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
        }


def _refine(values: np.ndarray, angles: np.ndarray, i: int) -> tuple[float, float]:
    """Extreme of a sampled periodic function near sample i, by a parabola through i-1, i, i+1."""
    n = len(values)
    y0, y1, y2 = values[(i - 1) % n], values[i], values[(i + 1) % n]
    if not (np.isfinite(y0) and np.isfinite(y2)):
        return float(y1), float(angles[i])
    den = y0 - 2 * y1 + y2
    t = 0.0 if den == 0 or not np.isfinite(den) else 0.5 * (y0 - y2) / den
    t = float(np.clip(t, -1, 1))
    step = (angles[(i + 1) % n] - angles[(i - 1) % n]) / 2 if n > 2 else 0.0
    if n > 2 and (i == 0 or i == n - 1):
        step = angles[1] - angles[0]
    return float(y1 - 0.25 * (y0 - y2) * t), float(angles[i] + t * step)


def extremes(kin: Any, variant: int = 0) -> list[Extremes]:
    """Strokes of the sliders on frame guides and swings of the rockers pivoted on the frame.

    Meaningful for a whole cycle of a crank (``steps=`` or equally spaced
    angles over a turn); the time ratio assumes a uniform drive speed.
    """
    mech = kin.mechanism
    angles = kin.angles
    sign = 1.0 if len(angles) < 2 or angles[1] > angles[0] else -1.0
    out = []
    driven = set(int(k) for k in mech.drive_pair)
    pose = kin.pose[variant]
    for k in range(mech.n_pairs):
        a, b = (int(x) for x in mech.pair_links[k])
        if mech.link_virtual[b] or a != 0 or k in driven:
            continue
        if mech.pair_type[k] == PRISMATIC:
            p = mech.pair_points[k, 1]
            x = kin.position(mech.point_names[p]) if not kin.variants else kin.position(mech.point_names[p])[variant]
            values = (x - mech.pair_origin[k]) @ mech.pair_axis[k]
            out.append(_extremes(mech.pair_joint[k], "slider", values, angles, sign))
        elif mech.pair_type[k] == REVOLUTE and b not in {int(mech.pair_links[d, 1]) for d in driven}:
            values = pose[:, b, 2].copy()
            ok = np.isfinite(values)
            values[ok] = np.unwrap(values[ok])
            if np.nanmax(values) - np.nanmin(values) < 2 * math.pi - 1e-6:
                out.append(_extremes(mech.link_names[b], "rocker", values, angles, sign))
    return out


def _extremes(name: str, kind: str, values: np.ndarray, angles: np.ndarray, sign: float) -> Extremes:
    """Extremes over the samples that assembled; the time ratio only where the whole turn did."""
    if not np.isfinite(values).any():
        nan = math.nan
        return Extremes(name, kind, nan, nan, nan, nan, nan, nan, nan, nan)
    lo_i, hi_i = int(np.nanargmin(values)), int(np.nanargmax(values))
    low, at_low = _refine(values, angles, lo_i)
    high, at_high = _refine(-values, angles, hi_i)
    high = -high
    forward = (sign * (at_high - at_low)) % (2 * math.pi)
    backward = 2 * math.pi - forward
    ratio = max(forward, backward) / min(forward, backward) if min(forward, backward) > 0 else math.inf
    if not np.isfinite(values).all():  # part of the turn does not assemble: no strokes to compare
        forward = backward = ratio = math.nan
    return Extremes(name, kind, low, high, at_low, at_high, high - low, forward, backward, ratio)


def transmission_angles(kin: Any) -> dict[str, np.ndarray]:
    """Transmission angle of every closed-form dyad over the samples, rad in [0, pi/2].

    The angle between the directions in which the two links of the dyad
    would move the joint X where they meet (for an RRR dyad, the angle
    between coupler and rocker; for an RRP dyad, between the rod and the
    normal to the guide), folded into [0, 90] deg: 90 deg transmits best,
    0 is a dead point.  Shape ``(..., n_angles)``.
    """
    out = {}
    for step, det in zip(kin.mechanism.program, kin.step_det, strict=True):
        if step.kind in ("RRR", "RRP", "PRP", "RPR"):
            out[step.label] = kin._out(np.arcsin(np.clip(np.abs(det), 0, 1)))
    return out


def instant_centre(kin: Any, link: str | int, relative_to: str | int = 0) -> np.ndarray:
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


def zero_angle(mech: Any) -> float:
    """Crank angle of position 0: the first slider on a frame guide at the high end of its stroke
    (for shears: the knives fully open), else the first rocker at its high extreme, else the assembly angle."""
    from linkwork.motion import kinematics as solve

    ext = extremes(solve(mech, steps=3600))
    for kind in ("slider", "rocker"):
        for e in ext:
            if e.kind == kind:
                return e.at_high
    return float(mech.drive_start[0])
