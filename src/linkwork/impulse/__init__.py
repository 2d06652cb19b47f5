"""Impact: impulses of a blow, the support's impulse, the centre of percussion.

>>> from linkwork.impulse import rocker_impact
>>> r = rocker_impact(inertia=0.3, mass=6.0, com=(0.05, 0.0), impact_point=(0.3, 0.0),
...                   omega_before=-30.0, restitution=0.4, normal=(0.0, 1.0))
>>> round(float(r.ideal_com[0]), 6)   # the centre of percussion J / (m x_K)
0.166667
"""

from __future__ import annotations

from linkwork.errors import SlidingReversal
from linkwork.impulse.contact import Tool
from linkwork.impulse.cycle import Blow, Phase, WorkingCycle, simulate_blows
from linkwork.impulse.impact_map import Strike, strike
from linkwork.impulse.mechanism import Impact, impact, reduced_model
from linkwork.impulse.rocker import RockerImpact, rocker_impact

__all__ = [
    "Blow",
    "Impact",
    "Phase",
    "RockerImpact",
    "SlidingReversal",
    "Strike",
    "Tool",
    "WorkingCycle",
    "impact",
    "reduced_model",
    "rocker_impact",
    "simulate_blows",
    "strike",
]
