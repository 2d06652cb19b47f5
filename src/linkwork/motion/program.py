"""The steps of the solve program: how each kind of group is recognised and what its step holds.

Each group of the structural decomposition becomes one step, solved in the
order of the decomposition: a driving link (``crank`` or ``slide``), a
class II dyad in closed form (``RRR``, ``RRP``, ``PRP`` through their inner
joint, ``RPR`` through its common angle, ``RPP`` through its known angle),
or any other group by a vectorised Newton method (``newton``).  Each function
here is the ``build`` of one kind of :mod:`linkwork.motion.groups` (which
tries them in its order: :func:`linkwork.motion.groups.build`).  The
assembly mode of each closed-form step is its ``branch`` (+1 or -1), read
off the assembly pose, so the hints of the file decide it.
"""

from __future__ import annotations

import dataclasses

from linkwork.structure.model import AssurGroup, Mechanism, PairType
from linkwork.structure.records import Arm, Step


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


def crank(mech: Mechanism, g: AssurGroup, driven: dict[int, int]) -> Step | None:
    """A link driven by its revolute pair with a placed link (``driven``: the drive of each driven pair)."""
    k = _driving_pair(g, driven)
    if k is None or mech.pair_type[k] != PairType.REVOLUTE:
        return None
    link = g.links[0]
    sign = 1.0 if int(mech.pair_links[k, 1]) == link else -1.0
    return Step("crank", g, g.links, arms=(_r_arm(mech, link, k),), drive=driven[k], pair=k, sign=sign)


def slide(mech: Mechanism, g: AssurGroup, driven: dict[int, int]) -> Step | None:
    """The slider of a driven prismatic pair with a placed link (None for a driven guide: Newton's method)."""
    k = _driving_pair(g, driven)
    if k is None or mech.pair_type[k] == PairType.REVOLUTE or int(mech.pair_links[k, 1]) != g.links[0]:
        return None
    return Step("slide", g, g.links, arms=(_p_arm(mech, g.links[0], k),), drive=driven[k], pair=k)


def _driving_pair(g: AssurGroup, driven: dict[int, int]) -> int | None:
    """The driven pair of a group of one link and that one pair, or None."""
    if g.klass == 1 and len(g.links) == 1 and len(g.pairs) == 1 and g.pairs[0] in driven:
        return int(g.pairs[0])
    return None


def joint_dyad(kind: str, mech: Mechanism, g: AssurGroup, driven: dict[int, int]) -> Step | None:
    """A dyad of the ``kind`` RRR, RRP or PRP, closed at its inner revolute joint X."""
    pairs = _dyad_pairs(mech, g)
    if pairs is None or g.kind != kind or mech.pair_type[pairs[2]] != PairType.REVOLUTE:
        return None
    a, b = g.links
    ka, kb, ki = pairs
    xa = int(mech.pair_points[ki, 0 if int(mech.pair_links[ki, 0]) == a else 1])
    xb = int(mech.pair_points[ki, 0 if int(mech.pair_links[ki, 0]) == b else 1])
    return Step(g.kind, g, g.links, arms=(_arm(mech, a, ka), _arm(mech, b, kb)), x_local=(xa, xb))


def rpr(mech: Mechanism, g: AssurGroup, driven: dict[int, int]) -> Step | None:
    """A dyad of an inner prismatic pair between two links pinned at their outer joints: through the common
    angle of its guide and slider."""
    pairs = _dyad_pairs(mech, g)
    if pairs is None:
        return None
    a, b = g.links
    ka, kb, ki = pairs
    if mech.pair_type[ki] == PairType.REVOLUTE or not (
        mech.pair_type[ka] == PairType.REVOLUTE and mech.pair_type[kb] == PairType.REVOLUTE
    ):
        return None
    guide, slider = (int(v) for v in mech.pair_links[ki])
    arm_s = _r_arm(mech, slider, kb if guide == a else ka)
    arm_s = dataclasses.replace(arm_s, slider_point=int(mech.pair_points[ki, 1]))
    return Step("RPR", g, g.links, arms=(_r_arm(mech, guide, ka if guide == a else kb), arm_s), inner=ki)


def rpp(mech: Mechanism, g: AssurGroup, driven: dict[int, int]) -> Step | None:
    """A dyad of an inner prismatic pair, one link pinned and the other on a guide: every angle is that guide's."""
    pairs = _dyad_pairs(mech, g)
    if pairs is None:
        return None
    a, b = g.links
    ka, kb, ki = pairs
    if mech.pair_type[ki] == PairType.REVOLUTE:
        return None
    pinned, other = (a, b) if mech.pair_type[ka] == PairType.REVOLUTE else (b, a)
    kp, ko = (ka, kb) if pinned == a else (kb, ka)
    if mech.pair_type[kp] != PairType.REVOLUTE or mech.pair_type[ko] != PairType.PRISMATIC:
        return None
    arms = (_r_arm(mech, pinned, kp), _p_arm(mech, other, ki), _p_arm(mech, other, ko))
    return Step("RPP", g, g.links, arms=arms, inner=ki, x_local=(-1, -1))


def newton(mech: Mechanism, g: AssurGroup, driven: dict[int, int]) -> Step:
    """Any group, solved by Newton's method: the kind that takes every group the others leave."""
    return Step("newton", g, g.links)


def _dyad_pairs(mech: Mechanism, g: AssurGroup) -> tuple[int, int, int] | None:
    """A class II group (not driven) of one inner pair and one outer pair on each link: its outer pair on its
    first link, on its second, and its inner pair; None for any other group."""
    if g.klass != 2 or g.driven:
        return None
    inner = [k for k in g.pairs if set(map(int, mech.pair_links[k])) <= set(g.links)]
    outer: dict[int, list[int]] = {}
    for k in g.pairs:
        if k not in inner:
            outer.setdefault(next(i for i in g.links if i in map(int, mech.pair_links[k])), []).append(k)
    if len(inner) != 1 or not all(len(v) == 1 for v in outer.values()):
        return None
    a, b = g.links
    return outer[a][0], outer[b][0], inner[0]
