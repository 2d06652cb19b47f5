"""The graphical construction of the velocity and acceleration plans, kind by kind of group (the ``plan`` of each
kind of :mod:`linkwork.motion.groups`).

Each function draws one step of the solve program on a construction (:class:`PlanConstruction`, the one of
:mod:`linkwork.motion.plans`): its points turning with a link about a known point, and its points sliding along a
guide (with the guide's coincident point and the Coriolis component).  A kind without one (``slide``, ``RPP``,
``newton``) shows its points by their absolute vectors only.
"""

from __future__ import annotations

from typing import Protocol

import numpy as np

from linkwork.structure.model import Mechanism
from linkwork.structure.records import Arm, Step


class PlanConstruction(Protocol):
    """What the constructions below draw on (:class:`linkwork.motion.plans.Construction`)."""

    mech: Mechanism

    def turn(self, group: str, arm: Arm, p: int) -> None:
        """Point ``p`` turning with the arm's link about the arm's outer joint."""

    def sliding(self, group: str, p: int, arm: Arm, pivot: int, prime: str = "'") -> None:
        """Point ``p`` on a link sliding along a guide of the arm's carrier."""

    def pivot(self, link: int, p: int) -> int:
        """The point of ``link`` that the coincident point of ``p`` on it turns about (-1 for the frame)."""


def crank(c: PlanConstruction, step: Step) -> None:
    """Every point of the crank but its pivot turns about the pivot."""
    arm = step.arms[0]
    for p in np.flatnonzero(c.mech.point_link == arm.link):
        if p != arm.own:
            c.turn(step.label, arm, int(p))


def joint_dyad(c: PlanConstruction, step: Step) -> None:
    """A dyad closed at its inner joint X (RRR, RRP, PRP): X turns with each R arm about its outer joint, and
    slides along the guide of each P arm (the primes count the guides)."""
    xp, arms = step.x_local[0], step.arms
    for arm in arms:
        if arm.kind == "R":
            c.turn(step.label, arm, xp)
        else:
            primes = "'" * (1 + sum(1 for other in arms[: arms.index(arm)] if other.kind == "P"))
            c.sliding(step.label, xp, arm, c.pivot(arm.carrier, xp), primes)


def rpr(c: PlanConstruction, step: Step) -> None:
    """The slider turns about its pivot; the guide's coincident point turns about the guide's pivot, and the
    slider slides along the guide relative to it (with the Coriolis component)."""
    arm_g, arm_s = step.arms
    sp = arm_s.slider_point
    c.turn(step.label, arm_s, sp)
    c.sliding(step.label, sp, Arm("P", arm_s.link, step.inner, carrier=arm_g.link), arm_g.src)
