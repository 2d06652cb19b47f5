"""Sizing: the parts of a machine chosen or checked from the loads of the analyses.

One module per part: :mod:`~linkwork.sizing.motor` (the motor from a catalogue, its gear and flywheel, and the
run with them), :mod:`~linkwork.sizing.bearings` (rolling bearings by ISO 281, plain bushes, guides),
:mod:`~linkwork.sizing.pin_shear` (pins in double shear), :mod:`~linkwork.sizing.bolts` (foundation bolts);
:func:`~linkwork.sizing.machine_sizing.size` composes them.  The catalogues are CSV files in ``linkwork/sizing/data``
with the units in their headings and their sources in their comments.
"""

from __future__ import annotations

from linkwork.sizing.bearings import Bearings, equivalent_load, life_hours, rating_needed
from linkwork.sizing.bolts import BoltResult, opening_forces, size_bolts
from linkwork.sizing.common import Catalogue, Table, bundled, parse_catalogue, read_catalogue
from linkwork.sizing.machine_sizing import Sizing, size
from linkwork.sizing.motor import MotorChoice, choose_motor, motor_catalogue
from linkwork.sizing.pin_shear import Pins, least_diameter, pins

__all__ = [
    "Bearings",
    "BoltResult",
    "Catalogue",
    "MotorChoice",
    "Pins",
    "Sizing",
    "Table",
    "bundled",
    "choose_motor",
    "equivalent_load",
    "least_diameter",
    "life_hours",
    "motor_catalogue",
    "opening_forces",
    "parse_catalogue",
    "pins",
    "rating_needed",
    "read_catalogue",
    "size",
    "size_bolts",
]
