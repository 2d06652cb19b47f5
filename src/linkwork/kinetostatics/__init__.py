"""Kinetostatics: joint reactions, driving torque and the loads on the foundation.

Each link is held in equilibrium by its applied loads (gravity), its
d'Alembert inertia loads and the reactions of its pairs.  The reactions are
the Lagrange multipliers of the constraint equations of
:mod:`linkwork.structure.constraints`: for the constraint rows ``Phi`` and
multipliers ``lam``, the pairs put the generalised forces ``Phi_q^T lam`` on
the links, and equilibrium of every moving link is

    Phi_q^T lam = -(Q_applied + Q_inertia).

Each Assur group is statically determinate: the groups are solved one by one
in the reverse order of the solve program, each a square linear system of
its own rows (3 per link), with the reactions of the groups solved before it
as known loads.  Two independent checks come with every result: the driving
torque from the power balance (the rate of change of kinetic energy less
the power of gravity, divided by the drive speed: Zhukovsky's lever in
analytic form), and the force and moment on the foundation from the theorem
on the change of momentum (the method of seed paper 000).

A joint's ``friction: {f, radius}`` adds friction in proportion to its pairs' forces, solved with the
reactions (:mod:`linkwork.kinetostatics.friction`); :attr:`Forces.efficiency` splits the drive's power into
the useful loads', each pair's friction and the energy rates (:mod:`linkwork.kinetostatics.efficiency`).

The reactions have two twins that give the same numbers: the NumPy solves (:mod:`~linkwork.kinetostatics.reactions`,
the reference) and the same arithmetic compiled with numba (:mod:`~linkwork.kinetostatics.reactions_numba`), which
runs where the compiled kinematics ran; adding a kind of group to the twins: :mod:`linkwork.motion`'s docstring.

>>> import linkwork as lw
>>> f = lw.forces(lw.compile(lw.load("shears-slider-crank")), steps=72)
>>> f.foundation.shape
(72, 3)
"""

from __future__ import annotations

from linkwork.kinetostatics.balancing import Balance, Counterweight, balance
from linkwork.kinetostatics.bolt_lift import bolt_speed
from linkwork.kinetostatics.bolts import Bolts, bolt_loads
from linkwork.kinetostatics.efficiency import Efficiency
from linkwork.kinetostatics.force_polygons import ForcePlans, GroupPlan, PlanForce, force_plans
from linkwork.kinetostatics.free_body import FreeBody
from linkwork.kinetostatics.friction import FrictionSolution
from linkwork.kinetostatics.peaks import Peak, foundation_peak, torque_peak
from linkwork.kinetostatics.reaction_forces import Forces, forces, forces_of
from linkwork.kinetostatics.reactions import Loads
from linkwork.kinetostatics.zhukovsky import Lever, lever
from linkwork.structure.records import PairFriction

__all__ = [
    "Balance",
    "Bolts",
    "Counterweight",
    "Efficiency",
    "ForcePlans",
    "Forces",
    "FreeBody",
    "FrictionSolution",
    "GroupPlan",
    "Lever",
    "Loads",
    "PairFriction",
    "Peak",
    "PlanForce",
    "balance",
    "bolt_loads",
    "bolt_speed",
    "force_plans",
    "forces",
    "forces_of",
    "foundation_peak",
    "lever",
    "torque_peak",
]
