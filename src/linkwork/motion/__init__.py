"""Kinematics: positions, velocities and accelerations of every point and link.

>>> import linkwork as lw
>>> mech = lw.compile(lw.load("double-cut-shears"))
>>> kin = lw.kinematics(mech, steps=360)
>>> kin.position("E").shape
(360, 2)

Every numeric kernel has two twins that give the same numbers (to rounding): the NumPy kernels
(:mod:`linkwork.motion.kernels`, the reference: whole arrays of variants x angles) and the same arithmetic
compiled with numba (:mod:`linkwork.motion.kernels_numba`, one sample at a time; when it runs is
:mod:`linkwork.jit`'s to say).  The reactions have the same pair in :mod:`linkwork.kinetostatics`
(``reactions`` and ``reactions_numba``); the threads the compiled twins share are :mod:`linkwork.threads`',
and a point's motion (:func:`linkwork.motion.points.point_motion`) picks its twin for every reading.

The kinds of group (cranks, slides, the class II dyads in closed form, Newton's method for the rest) are one
registry, :data:`linkwork.motion.groups.KINDS`: each kind's step, both kernels, its code in the compiled table and
its construction of the plans side by side, read by every dispatch.  Adding a kind is one record there plus its
kernels and its tests: the manual's development page says how (``docs/development.md``, "Adding a kind of group").
"""

from __future__ import annotations

from linkwork.motion.events import Event
from linkwork.motion.kinematic_analysis import Kinematics, cycle, kinematics
from linkwork.structure.parameters import Geometry, Masses

__all__ = ["Event", "Geometry", "Kinematics", "Masses", "cycle", "kinematics"]
