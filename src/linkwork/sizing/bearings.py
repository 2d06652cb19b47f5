"""Bearings at every pair: rolling bearings by ISO 281, plain bushes by p, v and pv, guides by their normal force.

**Rolling bearings.**  A bearing's basic rating life is ``L10 = (C / P)^p`` million revolutions under a
constant load ``P`` (``p = 3`` for ball bearings, ``10/3`` for roller bearings): each revolution under the load
``F`` uses up the share ``F^p / C^p`` of ``10^6`` revolutions (the Palmgren-Miner rule).  Over a cycle in which
the load ``F`` changes as the two rings turn through ``d theta`` relative to each other, the share used is
``int F^p |d theta| / (2 pi 10^6 C^p)``; the constant load that uses up the same in the same revolutions,
``P^p int |d theta| = int F^p |d theta|``, is the equivalent dynamic load

    P = (int F^p |omega_rel| dt / int |omega_rel| dt)^(1/p),

the cubic mean of ISO 281 weighted by the relative turning (each sample by its relative speed ``omega_rel``:
at a uniform crank speed ``dt`` is the same for each sample).  A pair that only rocks (a rocker's pivot, a rod's
end) is the same formula: it turns through ``4 gamma`` a full swing of amplitude ``gamma`` there and back, which
is the oscillation rule of the bearing makers, the equivalent speed ``n_osc 2 gamma / 180 deg`` (``gamma`` in
degrees); a rod that swings twice a cycle is counted twice.  The revolutions per hour are ``3600 n_eq`` with
``n_eq = mean |omega_rel| / (2 pi)`` (rev/s), so the life ``L10h`` hours asked needs

    C = P (3600 n_eq L10h / 10^6)^(1/p).

For rocking with a swing smaller than the angle between two rolling elements the formula is not valid (the
rolling elements do not roll over the whole track; false brinelling): the table gives the swing to check.

**Plain bushes** of diameter ``d`` and width ``b``: the pressure ``p = F / (d b)``, the sliding speed
``v = |omega_rel| d / 2`` and their product, each mean and peak over the cycle; without a diameter, the least
``d`` (at ``b = k d``) that keeps the peak ``p`` and the mean ``pv`` under the bush's limits:
``d = max(sqrt(F_max / (k p_allow)), mean(F |omega_rel|) / (2 k pv_allow))``.

**Guides**: the normal force's peak and mean, the sliding speed, and, for a guide (shoe) of length ``L`` centred
on the slider's point, the pressure per unit length of a linear distribution with the resultant ``N`` and the
moment ``M``: ``q = N / L + 6 |M| / L^2`` at its more loaded end.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from linkwork.errors import LinkworkError
from linkwork.limits import WIDTH_RATIOS
from linkwork.sizing.common import Table
from linkwork.sizing.pairs import Pair

#: The life exponent of ISO 281 by the kind of rolling bearing.
EXPONENT = {"ball": 3.0, "roller": 10.0 / 3.0}


def width_ratio_problem(ratio: float, name: str) -> str | None:
    """Why ``ratio`` is not a width / diameter of a pin or bush (:data:`WIDTH_RATIOS`), or None."""
    low, high = WIDTH_RATIOS
    if low <= ratio <= high:
        return None
    return f"{name}: the width / diameter of the pins and bushes, from {low:g} to {high:g}, got {ratio:g}"


def equivalent_load(force: np.ndarray, turning: np.ndarray, p: float = 3.0) -> float:
    """ISO 281's equivalent dynamic load of samples of the load ``force`` (N) and the relative speed ``turning``
    (rad/s) at equal steps of time: ``(sum F^p |w| / sum |w|)^(1/p)``; NaN where the pair never turns."""
    w = np.abs(np.asarray(turning, dtype=float))
    total = float(np.sum(w))
    if not total > 0:
        return math.nan
    return float((np.sum(np.abs(force) ** p * w) / total) ** (1.0 / p))


def rating_needed(load: float, revs_per_s: float, hours: float, p: float = 3.0) -> float:
    """The basic dynamic load rating C (N) for a basic rating life of ``hours`` at ``revs_per_s`` under the
    equivalent load ``load`` (N): ``load (3600 n L10h / 1e6)^(1/p)``."""
    return load * (3600.0 * revs_per_s * hours / 1e6) ** (1.0 / p)


def life_hours(rating: float, load: float, revs_per_s: float, p: float = 3.0) -> float:
    """The basic rating life L10h (h) of a bearing of rating ``rating`` (N) under ``load`` (N) at ``revs_per_s``."""
    return (rating / load) ** p * 1e6 / (3600.0 * revs_per_s)


@dataclass(frozen=True)
class Bush:
    """A plain bush's limits (SI): pressure ``p`` (Pa), sliding speed ``v`` (m/s), ``pv`` (Pa m/s)."""

    name: str
    p: float
    v: float
    pv: float


@dataclass(frozen=True)
class JointBearing:
    """The bearing figures of one revolute pair (SI; see the module)."""

    label: str
    links: tuple[str, str]
    motion: str  # "turns" or "rocks"
    swing: float  # rad, the relative angle's range over the cycle (rocking)
    force_max: float
    force_max_phi: float
    force_mean: float
    revs_per_s: float
    load: float  # the equivalent dynamic load P
    rating: float  # C needed
    diameter: float  # the bush's (given, or the least)
    width: float
    diameter_given: bool
    p_mean: float
    p_max: float
    v_max: float
    pv_mean: float
    pv_max: float


@dataclass(frozen=True)
class GuideFigures:
    """The figures of one prismatic pair (SI): normal force, moment, sliding speed, pressure per length."""

    label: str
    links: tuple[str, str]
    force_max: float
    force_max_phi: float
    force_mean: float
    moment_max: float
    speed_max: float
    length: float  # NaN where none is given
    pressure_max: float  # N/m, NaN without a length


@dataclass(frozen=True)
class Bearings:
    """The bearings at every pair: rolling (ISO 281) and plain (p, v, pv) for every revolute pair, the
    normal force for every prismatic pair, with the inputs they were sized for."""

    joints: tuple[JointBearing, ...]
    guides: tuple[GuideFigures, ...]
    life_h: float
    kind: str
    crank_rpm: float
    bush: Bush
    width_ratio: float

    def over(self, j: JointBearing) -> str:
        """What of the bush's limits joint ``j`` exceeds: its peak p, its peak v, its mean pv ("none" for none); "not
        known" where a figure is not (a load that is not finite over the cycle: a singular position)."""
        figures = (j.p_max, j.v_max, j.pv_mean)
        if not all(math.isfinite(v) for v in figures):
            return "not known: the load is not finite over the cycle"
        over = [
            name
            for name, value, limit in (
                ("p max", j.p_max, self.bush.p),
                ("v max", j.v_max, self.bush.v),
                ("pv mean", j.pv_mean, self.bush.pv),
            )
            if value > limit * (1 + 1e-9)
        ]
        return ", ".join(over) or "none"

    def tables(self) -> list[Table]:
        rows = tuple(
            (
                j.label,
                j.motion,
                math.degrees(j.swing),
                j.force_max / 1e3,
                j.force_max_phi,
                j.force_mean / 1e3,
                j.revs_per_s * 60,
                j.load / 1e3,
                j.rating / 1e3,
            )
            for j in self.joints
        )
        rolling = Table(
            f"Rolling bearings (ISO 281, {self.kind}: p = {EXPONENT[self.kind]:.4g}) for L10h = {self.life_h:g} h "
            f"at {self.crank_rpm:.4g} rpm of the crank",
            (
                "joint",
                "motion",
                "swing [deg]",
                "F max [kN]",
                "at phi [deg]",
                "F mean [kN]",
                "n eq [rpm]",
                "P [kN]",
                "C needed [kN]",
            ),
            rows,
            "rolling",
        )
        plain = Table(
            f"Plain bushes ({self.bush.name}: p <= {self.bush.p / 1e6:g} MPa, v <= {self.bush.v:g} m/s, "
            f"pv <= {self.bush.pv / 1e6:g} MPa m/s; least diameter at b = {self.width_ratio:g} d)",
            (
                "joint",
                "d [mm]",
                "b [mm]",
                "d given",
                "p mean [MPa]",
                "p max [MPa]",
                "v max [m/s]",
                "pv mean [MPa m/s]",
                "pv max [MPa m/s]",
                "over the limits",
            ),
            tuple(
                (
                    j.label,
                    j.diameter * 1e3,
                    j.width * 1e3,
                    "yes" if j.diameter_given else "least",
                    j.p_mean / 1e6,
                    j.p_max / 1e6,
                    j.v_max,
                    j.pv_mean / 1e6,
                    j.pv_max / 1e6,
                    self.over(j),
                )
                for j in self.joints
            ),
            "plain",
        )
        guides = Table(
            "Guides (prismatic pairs)",
            (
                "joint",
                "N max [kN]",
                "at phi [deg]",
                "N mean [kN]",
                "M max [kN m]",
                "v max [m/s]",
                "L [mm]",
                "q max [kN/m]",
            ),
            tuple(
                (
                    g.label,
                    g.force_max / 1e3,
                    g.force_max_phi,
                    g.force_mean / 1e3,
                    g.moment_max / 1e3,
                    g.speed_max,
                    g.length * 1e3,
                    g.pressure_max / 1e3,
                )
                for g in self.guides
            ),
            "guides",
        )
        return [rolling, plain, guides] if self.guides else [rolling, plain]

    def record(self) -> dict[str, Any]:
        tables = self.tables()
        out: dict[str, Any] = {
            "life_h": self.life_h,
            "kind": self.kind,
            "exponent": EXPONENT[self.kind],
            "crank_rpm": self.crank_rpm,
            "bush": {
                "name": self.bush.name,
                "p_MPa": self.bush.p / 1e6,
                "v_m_s": self.bush.v,
                "pv_MPa_m_s": self.bush.pv / 1e6,
            },
            "width_ratio": self.width_ratio,
            "rolling": tables[0].record(),
            "plain": tables[1].record(),
        }
        if self.guides:
            out["guides"] = tables[2].record()
        return out


def bearings(
    pairs: list[Pair],
    phi: np.ndarray,
    crank_speed: float,
    *,
    life_h: float = 20000.0,
    kind: str = "ball",
    bush: Bush,
    pins: Mapping[str, tuple[float, float]] | None = None,
    width_ratio: float = 1.0,
    guides: Mapping[str, float] | None = None,
) -> Bearings:
    """The bearings of ``pairs`` (:func:`~linkwork.sizing.pairs.pairs_of`) over a cycle sampled at the crank
    angles ``phi`` (deg from position 0) at a uniform ``crank_speed`` (rad/s): see the module.  ``pins``: the
    diameter and width (m) of the pin of a joint (by its label), else the least diameter for ``bush`` at the
    width ``width_ratio`` times it; ``guides``: the length (m) of a prismatic pair's guide.

    Raises
    ------
    LinkworkError
        An unknown kind, life or ratio out of range, or a pin or guide named that is no such pair.
    """
    if kind not in EXPONENT:
        raise LinkworkError(f'bearing kind: "ball" or "roller", got "{kind}"')
    if not 0 < life_h < math.inf:
        raise LinkworkError(f"life: expected a positive number of hours, got {life_h} h")
    why = width_ratio_problem(width_ratio, "width ratio")
    if why is not None:
        raise LinkworkError(why)
    pins, guides = dict(pins or {}), dict(guides or {})
    labels = {p.label: p.kind for p in pairs}
    wrong = [
        f'pin "{n}": no revolute joint of that name ({", ".join(k for k, v in labels.items() if v == "revolute")})'
        for n in pins
        if labels.get(n) != "revolute"
    ]
    wrong += [f'guide "{n}": no prismatic joint of that name' for n in guides if labels.get(n) != "prismatic"]
    if wrong:
        raise LinkworkError("\n".join(wrong))
    p = EXPONENT[kind]
    with np.errstate(invalid="ignore", over="ignore", divide="ignore"):  # an unbounded force: its figures inf, NaN
        joints = tuple(
            _joint(pair, phi, life_h, p, bush, pins.get(pair.label), width_ratio)
            for pair in pairs
            if pair.kind == "revolute"
        )
        figures = tuple(
            _guide(pair, phi, guides.get(pair.label, math.nan)) for pair in pairs if pair.kind == "prismatic"
        )
    return Bearings(joints, figures, life_h, kind, crank_speed * 30 / math.pi, bush, width_ratio)


def _joint(
    pair: Pair, phi: np.ndarray, life_h: float, p: float, bush: Bush, pin: tuple[float, float] | None, ratio: float
) -> JointBearing:
    f, w = pair.force, np.abs(pair.turning)
    peak, at = pair.force_max(phi)
    load = equivalent_load(f, w, p)
    revs = float(np.mean(w)) / (2 * math.pi)
    net = abs(float(np.mean(pair.turning)))
    motion = "turns" if net > 0.01 * float(np.mean(w)) else "rocks"
    swing = float(np.ptp(pair.relative)) if motion == "rocks" else 2 * math.pi
    if pin is not None:
        d, b = pin
    else:
        d = max(math.sqrt(peak / (ratio * bush.p)), float(np.mean(f * w)) / (2 * ratio * bush.pv))
        b = ratio * d
    pressure = f / (d * b)
    speed = w * d / 2
    return JointBearing(
        pair.label,
        pair.links,
        motion,
        swing,
        peak,
        at,
        float(np.mean(f)),
        revs,
        load,
        rating_needed(load, revs, life_h, p),
        d,
        b,
        pin is not None,
        float(np.mean(pressure)),
        max(float(np.max(pressure)), peak / (d * b)),
        float(np.max(speed)),
        float(np.mean(pressure * speed)),
        float(np.max(pressure * speed)),
    )


def _guide(pair: Pair, phi: np.ndarray, length: float) -> GuideFigures:
    f, m = pair.force, np.abs(pair.moment)
    peak, at = pair.force_max(phi)
    q = f / length + 6 * m / length**2 if math.isfinite(length) else np.full_like(f, math.nan)
    q = np.append(q, peak / length + 6 * float(np.max(m)) / length**2)  # the refined peak with the largest moment
    return GuideFigures(
        pair.label,
        pair.links,
        peak,
        at,
        float(np.mean(f)),
        float(np.max(m)),
        float(np.max(pair.sliding)),
        length,
        float(np.max(q)),
    )
