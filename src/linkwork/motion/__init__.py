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

Adding a kind of group solved in closed form, to both twins:

1. :mod:`~linkwork.motion.program`: its name in ``CLOSED_FORM``; ``build`` makes its ``Step``
   (links, arms, the points where it closes).
2. :mod:`~linkwork.motion.kernels`: its NumPy kernel (positions, velocities, accelerations and the
   step's record of assembly margin and determinant); ``with_branches`` reads its assembly mode off
   the assembly pose, if it has two.  A dyad's loci and where they meet are
   :mod:`~linkwork.motion.closure`'s, where its mode flips along the samples
   :mod:`~linkwork.motion.change_points`'.
3. :mod:`~linkwork.motion.solve`: ``run_numpy`` calls that kernel for the kind.
4. :mod:`~linkwork.motion.compiled_program`: a code in ``CODES``, its columns of the program's table and
   ``encode``; :mod:`~linkwork.motion.kernels_numba`: its scalar kernel called from ``_step`` (the same
   arithmetic, in the same order), every new scalar function named in ``_INLINE``.
5. :mod:`~linkwork.motion.plans`: its velocity and acceleration plans, where the report draws them.
6. The reactions need nothing: both twins solve any statically determinate group from its constraint
   rows (:mod:`linkwork.kinetostatics.reactions_numba` has closed solves for one link and a dyad,
   Gaussian elimination for the rest).
7. A mechanism with the group in ``tests/mechanisms.py`` (``SOLVED``): ``tests/motion/test_twins.py``
   then checks that the kind has both twins and that they agree.
"""

from __future__ import annotations

from linkwork.motion.events import Event
from linkwork.motion.kinematic_analysis import Kinematics, cycle, kinematics
from linkwork.structure.parameters import Geometry, Masses

__all__ = ["Event", "Geometry", "Kinematics", "Masses", "cycle", "kinematics"]
