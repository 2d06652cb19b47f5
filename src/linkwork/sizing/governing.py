"""What governs each revolute joint: the pin, the plain bush and the rolling bearing side by side.

A joint's pin is one part: its diameter must hold the force in double shear and bending (the pin's least
diameter, :mod:`~linkwork.sizing.pin_shear`) and, turning in a plain bush, keep the bush's pressure and ``pv``
within its limits (the bush's least diameter, :mod:`~linkwork.sizing.bearings`), both at the width ``b = k d``.
The diameter to make is the larger, and the table says which rule gives it: a pin sized for strength alone
presses its eye at ``p = F / (k d^2) = pi sigma_allow / (4 k^2)`` (133.5 MPa for C45 at S = 2 and k = 1, nine
times a bronze bush's 15 MPa), so with a plain bush the bush governs wherever its pressure is the tighter rule.

A rolling bearing is the other choice: the rating ``C`` it needs for the life asked (ISO 281).  Where the joint
only rocks through a swing smaller than the angle between two rolling elements (``360 deg / Z``), the elements
do not roll over the track (false brinelling, and the life formula does not hold): the table flags it, and the
plain bush is the part to use.  ``Z`` is a stated default of the common series (:data:`ROLLING_ELEMENTS`).
"""

from __future__ import annotations

import math

from linkwork.sizing.bearings import Bearings, JointBearing
from linkwork.sizing.common import Table
from linkwork.sizing.pin_shear import Pin, Pins, Steel, least_diameter

#: Rolling elements in a bearing of the common series, by kind (the angle between two is 360 deg / Z).
ROLLING_ELEMENTS = {"ball": 10, "roller": 14}


def pitch_angle(kind: str) -> float:
    """The angle between two rolling elements of a bearing of ``kind``, rad (:data:`ROLLING_ELEMENTS`)."""
    return 2 * math.pi / ROLLING_ELEMENTS[kind]


def pin_rule(pin: Pin, pins: Pins) -> tuple[float, str]:
    """The pin's least diameter for strength (m) at the width ratio of the sizing, and the rule that gives it."""
    k = pins.width_ratio
    shear = math.sqrt(2 * pin.force / (math.pi * pins.shear_allowed))
    bending = math.sqrt(4 * k * pin.force / (math.pi * pins.bending_allowed))
    return (bending, "pin bending") if bending >= shear else (shear, "pin shear")


def governing_diameter(force: float, steel: Steel, safety: float, width_ratio: float, bush_pressure: float) -> float:
    """The diameter (m) a pin carrying ``force`` (N) is made to: the larger of its least for strength (double
    shear and bending, :func:`~linkwork.sizing.pin_shear.least_diameter`) and its plain bush's least for the
    pressure ``bush_pressure`` (Pa), ``sqrt(F / (k p))``, at the width ratio ``k`` (the bush's ``pv`` rule needs
    the joint's motion and is left to the joints' table)."""
    tau, sigma = steel.yield_strength / (2 * safety), steel.yield_strength / safety
    return max(least_diameter(force, tau, sigma, width_ratio), math.sqrt(force / (width_ratio * bush_pressure)))


def bush_rule(j: JointBearing, bearings: Bearings) -> tuple[float, str]:
    """The bush's least diameter (m) at the width ratio of the sizing (the peak pressure's and the mean pv's
    larger), and the rule that gives it.  ``mean(F |w|) = 2 b pv_mean`` whatever the bush's own diameter."""
    k, bush = bearings.width_ratio, bearings.bush
    pressure = math.sqrt(j.force_max / (k * bush.p))
    pv = j.width * j.pv_mean / (k * bush.pv)
    return (pressure, "bush p") if pressure >= pv else (pv, "bush pv")


def rolling_note(j: JointBearing, kind: str) -> str:
    """Whether a rolling bearing can serve joint ``j``: "ok", or why not (a swing below the pitch angle)."""
    pitch = pitch_angle(kind)
    if j.motion == "rocks" and j.swing < pitch:
        return f"no: swings {math.degrees(j.swing):.3g} < {math.degrees(pitch):.3g} deg between its elements"
    return "ok"


def made_diameters(pins: Pins, bearings: Bearings) -> dict[str, float]:
    """The diameter (m) each joint's pin is made to (by the bearings' label: a shaft's bearings ``joint/1``,
    ``joint/2``): the governing one of :func:`governing_table`; NaN where its force has no bound."""
    return {row[0]: row[7] / 1e3 if math.isfinite(row[1]) else math.nan for row in _rows(pins, bearings)}


def governing_table(pins: Pins, bearings: Bearings) -> Table:
    """One row a revolute joint: the force, the pin's and the bush's least diameters with their rules, the
    diameter to make and what governs it (the file's diameter where it gives one, checked against both), the
    rolling bearing's rating and whether one can serve."""
    rows = _rows(pins, bearings)
    return Table(
        f"Joints: what governs (the pin and its bush are one diameter d at b = {bearings.width_ratio:g} d; "
        f"a {bearings.kind} bearing of C for L10h = {bearings.life_h:g} h instead of the bush)",
        (
            "joint",
            "F max [kN]",
            "at phi [deg]",
            "pin d [mm]",
            "pin by",
            "bush d [mm]",
            "bush by",
            "d to make [mm]",
            "governs",
            "rolling C [kN]",
            "rolling bearing",
        ),
        tuple(rows),
        "joints",
    )


def _rows(pins: Pins, bearings: Bearings) -> list[tuple]:
    by_label = {p.label: p for p in pins.pins}
    rows = []
    for j in bearings.joints:
        pin = by_label.get(j.label, by_label.get(j.label.rsplit("/", 1)[0]))  # a shaft's bearing: its journal
        if pin is None:
            continue
        d_pin, pin_by = pin_rule(pin, pins)
        d_bush, bush_by = bush_rule(j, bearings)
        if pin.given:
            d, governs = pin.diameter, "given" if pin.diameter >= max(d_pin, d_bush) else "given too small"
        else:
            d, governs = (d_bush, bush_by) if d_bush >= d_pin else (d_pin, pin_by)
        if not math.isfinite(j.force_max):
            governs = "not sized: unbounded"
        rows.append(
            (
                j.label,
                j.force_max / 1e3,
                j.force_max_phi,
                d_pin * 1e3,
                pin_by,
                d_bush * 1e3,
                bush_by,
                d * 1e3,
                governs,
                j.rating / 1e3,
                rolling_note(j, bearings.kind),
            )
        )
    return rows
