"""Kinematics: positions, velocities and accelerations of every point and link.

>>> import linkwork as lw
>>> mech = lw.compile(lw.load("double-cut-shears"))
>>> kin = lw.kinematics(mech, steps=360)
>>> kin.position("E").shape
(360, 2)
"""

from __future__ import annotations

from linkwork.motion.events import Event
from linkwork.motion.kinematic_analysis import Kinematics, cycle, kinematics
from linkwork.structure.parameters import Geometry, Masses

__all__ = ["Event", "Geometry", "Kinematics", "Masses", "cycle", "kinematics"]
