"""The solve program: the Assur groups of a compiled mechanism as kernel steps.

Each group of the structural decomposition becomes one step, solved in the
order of the decomposition: a driving link (``crank`` or ``slide``), a
class II dyad in closed form (``RRR``, ``RRP``, ``PRP`` through their inner
joint, ``RPR`` through its common angle, ``RPP`` through its known angle),
or any other group by a vectorised Newton method (``newton``).  The
assembly mode of each closed-form step is its ``branch`` (+1 or -1), read
off the assembly pose, so the hints of the file decide it.
"""

from __future__ import annotations

import dataclasses

from linkwork.structure.model import AssurGroup, Mechanism, PairType
from linkwork.structure.records import Arm, Step

#: The kinds of step solved in closed form: each has a NumPy kernel (:mod:`linkwork.motion.kernels`) and its
#: twin in machine code (:data:`linkwork.motion.kernels_numba.CODES`).
CLOSED_FORM = ("crank", "slide", "RRR", "RRP", "PRP", "RPR", "RPP")
#: Every kind of step: the closed-form ones and ``newton`` (any other group; NumPy only).
KINDS = (*CLOSED_FORM, "newton")


def _other(mech: Mechanism, k: int, link: int) -> int:
    a, b = (int(v) for v in mech.pair_links[k])
    return b if a == link else a


def _r_arm(mech: Mechanism, link: int, k: int) -> Arm:
    a = int(mech.pair_links[k, 0])
    own = int(mech.pair_points[k, 0 if a == link else 1])
    src = int(mech.pair_points[k, 1 if a == link else 0])
    return Arm("R", link, k, own=own, src=src)


def _p_arm(mech: Mechanism, link: int, k: int) -> Arm:
    guide, slider = (int(v) for v in mech.pair_links[k])
    return Arm(
        "P",
        link,
        k,
        carrier=_other(mech, k, link),
        own_is_slider=slider == link,
        slider_point=int(mech.pair_points[k, 1]),
    )


def _arm(mech: Mechanism, link: int, k: int) -> Arm:
    return _r_arm(mech, link, k) if mech.pair_type[k] == PairType.REVOLUTE else _p_arm(mech, link, k)


def build(mech: Mechanism) -> list[Step]:
    """The steps of the solve program of a mechanism's structural model, one per Assur group, their
    branches not yet read (:func:`linkwork.motion.kernels.with_branches` reads them off the assembly
    pose)."""
    driven = {int(k): d for d, k in enumerate(mech.drive_pair)}
    steps = []
    for g in mech.structure.groups:
        step = None
        if g.klass == 1 and len(g.links) == 1 and len(g.pairs) == 1 and g.pairs[0] in driven:
            step = _driving(mech, g, driven[g.pairs[0]])
        elif g.klass == 2 and not g.driven:
            step = _dyad(mech, g)
        steps.append(step or Step("newton", g, g.links))
    return steps


def _driving(mech: Mechanism, g: AssurGroup, drive: int) -> Step | None:
    """A link driven by its pair with a placed link: a crank (revolute pair), a slide (the slider of a
    prismatic pair); None for a driven guide (Newton's method)."""
    k, link = g.pairs[0], g.links[0]
    if mech.pair_type[k] == PairType.REVOLUTE:
        sign = 1.0 if int(mech.pair_links[k, 1]) == link else -1.0
        return Step("crank", g, g.links, arms=(_r_arm(mech, link, k),), drive=drive, pair=k, sign=sign)
    if int(mech.pair_links[k, 1]) == link:
        return Step("slide", g, g.links, arms=(_p_arm(mech, link, k),), drive=drive, pair=k)
    return None


def _dyad(mech: Mechanism, g: AssurGroup) -> Step | None:
    """A class II group of one inner pair and one outer pair on each link, in closed form: RRR, RRP
    and PRP through their inner joint, RPR through its common angle, RPP through its known angle;
    None for any other (Newton's method)."""
    inner = [k for k in g.pairs if set(map(int, mech.pair_links[k])) <= set(g.links)]
    outer: dict[int, list[int]] = {}
    for k in g.pairs:
        if k not in inner:
            outer.setdefault(next(i for i in g.links if i in map(int, mech.pair_links[k])), []).append(k)
    if len(inner) != 1 or not all(len(v) == 1 for v in outer.values()):
        return None
    a, b = g.links
    ka, kb, ki = outer[a][0], outer[b][0], inner[0]
    if mech.pair_type[ki] == PairType.REVOLUTE:
        xa = int(mech.pair_points[ki, 0 if int(mech.pair_links[ki, 0]) == a else 1])
        xb = int(mech.pair_points[ki, 0 if int(mech.pair_links[ki, 0]) == b else 1])
        return Step(g.kind, g, g.links, arms=(_arm(mech, a, ka), _arm(mech, b, kb)), x_local=(xa, xb))
    if mech.pair_type[ka] == PairType.REVOLUTE and mech.pair_type[kb] == PairType.REVOLUTE:
        guide, slider = (int(v) for v in mech.pair_links[ki])
        arm_s = _r_arm(mech, slider, kb if guide == a else ka)
        arm_s = dataclasses.replace(arm_s, slider_point=int(mech.pair_points[ki, 1]))
        return Step("RPR", g, g.links, arms=(_r_arm(mech, guide, ka if guide == a else kb), arm_s), inner=ki)
    pinned, other = (a, b) if mech.pair_type[ka] == PairType.REVOLUTE else (b, a)
    kp, ko = (ka, kb) if pinned == a else (kb, ka)
    if mech.pair_type[kp] == PairType.REVOLUTE and mech.pair_type[ko] == PairType.PRISMATIC:
        arms = (_r_arm(mech, pinned, kp), _p_arm(mech, other, ki), _p_arm(mech, other, ko))
        return Step("RPP", g, g.links, arms=arms, inner=ki, x_local=(-1, -1))
    return None
