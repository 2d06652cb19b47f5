"""Pins in double shear at every revolute joint, from the peak force the joint carries over the cycle.

A pin through a fork (the link between the fork's cheeks) is cut in two sections, each carrying half the force
``F``: the shear stress ``tau = F / (2 pi d^2 / 4) = 2 F / (pi d^2)``.  The pin bends as a beam of span ``b``
(the width of the eye, between the middle planes of the cheeks) under the force spread evenly over it:
``M = F b / 8``, ``sigma = 32 M / (pi d^3) = 4 F b / (pi d^3)``.  The bearing pressure in the eye is
``p = F / (d b)``.  The allowable stresses from the steel's yield strength and the safety factor ``S``:
``sigma_allow = R_e / S`` and ``tau_allow = R_e / (2 S)`` (Tresca).  Without a diameter, the least ``d`` (at
``b = k d``) for both: ``d = max(sqrt(2 F / (pi tau_allow)), sqrt(4 k F / (pi sigma_allow)))``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from linkwork.sizing.common import Table
from linkwork.sizing.pairs import Pair


@dataclass(frozen=True)
class Steel:
    """A steel grade (SI): yield strength, tensile strength, endurance limit in reversed bending, Pa."""

    name: str
    yield_strength: float
    tensile: float
    endurance: float


@dataclass(frozen=True)
class Pin:
    """One pin (SI): the peak force and where it is, the diameter and width, the stresses."""

    label: str
    force: float
    phi: float
    diameter: float
    width: float
    given: bool
    shear: float
    bending: float
    pressure: float


@dataclass(frozen=True)
class Pins:
    pins: tuple[Pin, ...]
    steel: Steel
    safety: float
    width_ratio: float

    @property
    def shear_allowed(self) -> float:
        return self.steel.yield_strength / (2 * self.safety)

    @property
    def bending_allowed(self) -> float:
        return self.steel.yield_strength / self.safety

    def table(self) -> Table:
        return Table(
            f"Pins in double shear ({self.steel.name}, S = {self.safety:g}: tau <= {self.shear_allowed / 1e6:.4g} MPa, "
            f"sigma <= {self.bending_allowed / 1e6:.4g} MPa; least diameter at b = {self.width_ratio:g} d)",
            (
                "joint",
                "F max [kN]",
                "at phi [deg]",
                "d [mm]",
                "b [mm]",
                "d given",
                "tau [MPa]",
                "sigma bending [MPa]",
                "p [MPa]",
            ),
            tuple(
                (
                    p.label,
                    p.force / 1e3,
                    p.phi,
                    p.diameter * 1e3,
                    p.width * 1e3,
                    "yes" if p.given else "least",
                    p.shear / 1e6,
                    p.bending / 1e6,
                    p.pressure / 1e6,
                )
                for p in self.pins
            ),
            "pins",
        )

    def record(self) -> dict[str, Any]:
        return {
            "steel": self.steel.name,
            "yield_MPa": self.steel.yield_strength / 1e6,
            "safety": self.safety,
            "shear_allowed_MPa": self.shear_allowed / 1e6,
            "bending_allowed_MPa": self.bending_allowed / 1e6,
            "width_ratio": self.width_ratio,
            "pins": self.table().record(),
        }


def least_diameter(force: float, shear_allowed: float, bending_allowed: float, width_ratio: float) -> float:
    """The least pin diameter (m) in double shear for ``force`` (N): the larger of the shear's and the bending's
    (at the width ``width_ratio`` d); see the module."""
    shear = math.sqrt(2 * force / (math.pi * shear_allowed))
    bending = math.sqrt(4 * width_ratio * force / (math.pi * bending_allowed))
    return max(shear, bending)


def pins(
    pairs: list[Pair],
    phi: np.ndarray,
    steel: Steel,
    *,
    safety: float = 2.0,
    sizes: Mapping[str, tuple[float, float]] | None = None,
    width_ratio: float = 1.0,
) -> Pins:
    """The pin of every revolute pair: ``sizes`` gives a joint's diameter and width (m), else the least diameter."""
    sizes = dict(sizes or {})
    out = []
    tau, sigma = steel.yield_strength / (2 * safety), steel.yield_strength / safety
    for pair in pairs:
        if pair.kind != "revolute":
            continue
        f, at = pair.force_max(phi)
        given = pair.label in sizes
        d, b = sizes[pair.label] if given else (least_diameter(f, tau, sigma, width_ratio), math.nan)
        if not given:
            b = width_ratio * d
        out.append(
            Pin(
                pair.label,
                f,
                at,
                d,
                b,
                given,
                2 * f / (math.pi * d**2),
                4 * f * b / (math.pi * d**3),
                f / (d * b),
            )
        )
    return Pins(tuple(out), steel, safety, width_ratio)
