"""The links' masses from their sized sections, to a fixed point with the loads they cause.

A link's inertia loads its joints and itself, and its section is sized from those loads: the mass a sizing
starts from is a guess (a file's, or the default rule of a synthesised file: every link a 40 x 20 mm steel bar).
With ``masses="sized"``, each link that is a bar (two or more joints) takes the mass of its sized section, ``rho A
L`` (steel, ``rho`` = :data:`STEEL`; ``A`` the least round bar's, or the file's section; ``L`` its length between
its joints farthest apart), the loads are computed again with those masses, and so on until no mass changes by
more than :data:`AGREE` of itself (at most :data:`ROUNDS` rounds).  A bar is no slenderer than a round bar of
``L / d =`` :data:`SLENDER` (buckling is not checked: a link whose loads are only its own weight and inertia
would otherwise shrink towards nothing).  Each link's moment of inertia follows its
mass by the file's rule (a uniform rod's ``m L^2 / 12`` where the file gives none), as the same edit of the file
would.

A link with one revolute joint and a sliding pair (a ram, a slider, a sliding block, a knife) is a steel block
(:func:`block_mass`): it carries its pin of the diameter ``d`` that governs its joint (the larger of the pin's
least for strength and the plain bush's least for its pressure, ``sqrt(F / (k p))``; :mod:`~linkwork.sizing.governing`)
in an eye across the guide ``w = 2 d`` wide (a wall of ``d / 2`` each side of the pin) and ``t = k d`` thick (the
pin's width), and bears on its guide over a length ``l`` at the bush's pressure ``p``: the largest normal force
``N`` and moment ``M`` of its guide give ``p t >= N / l + 6 M / l^2``, so ``l = (N + sqrt(N^2 + 24 M p t)) /
(2 p t)``, at least ``w`` (a block no shorter than it is wide).  Its pin is no thinner than the bar it carries
(the round bar of that bar's section): a block whose joint carries only its own inertia would otherwise shrink
towards nothing, as a bar would without its slenderness bound.  Its mass is ``rho w t l``; the pin's eye governs a
block whose guide presses lightly, the bearing length one whose guide carries the load.  Any other link that is no
bar keeps the file's mass: the sizing says so.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from linkwork.errors import LinkworkError
from linkwork.sizing.links import Bars
from linkwork.sizing.pairs import Pair
from linkwork.structure.model import Mechanism

#: Density of the links' steel, kg/m^3.
STEEL = 7850.0
#: Relative change of every sized mass at which the iteration stops.
AGREE = 1e-3
#: Rounds at most.
ROUNDS = 12
#: The slenderest bar whose mass is taken: a round bar of this length over diameter.
SLENDER = 20.0


def bar_mass(area: float, length: float) -> float:
    """The mass (kg) of a steel bar of section ``area`` (m^2) and ``length`` (m), at least a round bar of
    :data:`SLENDER` (see the module)."""
    least = np.pi * (length / SLENDER) ** 2 / 4
    return STEEL * max(area, least) * length


@dataclass(frozen=True)
class Block:
    """A block of the module's rule (SI): its pin's diameter, its width across the guide, thickness and length
    along the guide (m), and its mass (kg)."""

    pin: float
    width: float
    thickness: float
    length: float

    @property
    def mass(self) -> float:
        return STEEL * self.width * self.thickness * self.length


def block_of(pin: float, width_ratio: float, normal: float, moment: float, pressure: float) -> Block:
    """The steel block carrying a pin of diameter ``pin`` (m) at the width ``width_ratio`` x ``pin`` and bearing on
    its guide at ``pressure`` (Pa) under the guide's largest ``normal`` force (N) and ``moment`` (N m): ``w = 2 d``,
    ``t = k d`` and the bearing length ``l`` of the module, at least ``w``."""
    w, t = 2 * pin, width_ratio * pin
    a = pressure * t
    length = max(w, (normal + math.sqrt(normal**2 + 24 * abs(moment) * a)) / (2 * a))
    return Block(pin, w, t, length)


def block_mass(pin: float, width_ratio: float, normal: float, moment: float, pressure: float) -> float:
    """The mass (kg) of :func:`block_of`'s block: ``rho w t l``."""
    return block_of(pin, width_ratio, normal, moment, pressure).mass


def block_masses(
    pairs: list[Pair], bars: Bars, pin_of: Callable[[float], float], width_ratio: float, pressure: float
) -> dict[str, float]:
    """The mass (kg) of each block of :func:`blocks`."""
    return {link: b.mass for link, b in blocks(pairs, bars, pin_of, width_ratio, pressure).items()}


def blocks(
    pairs: list[Pair], bars: Bars, pin_of: Callable[[float], float], width_ratio: float, pressure: float
) -> dict[str, Block]:
    """The block of each link of ``pairs`` that is no bar of ``bars`` and has one revolute pair and a sliding
    one (see the module): its pin ``pin_of(F)`` (m) for its joint's peak force ``F`` (N), its guide's largest
    normal force and moment; a joint whose force has no bound leaves the link out."""
    bar_links = {b.link for b in bars.bars}
    thick = {b.link: math.sqrt(4 * max(b.area, math.pi * (b.length / SLENDER) ** 2 / 4) / math.pi) for b in bars.bars}
    by_link: dict[str, list[Pair]] = {}
    for pair in pairs:
        for link in pair.links:
            by_link.setdefault(link, []).append(pair)
    out = {}
    for link, own in by_link.items():
        turning = [p for p in own if p.kind == "revolute"]
        sliding = [p for p in own if p.kind == "prismatic"]
        if link in bar_links or link == "frame" or len(turning) != 1 or not sliding:
            continue
        force = _peak(turning[0])
        normal = max(_peak(p) for p in sliding)
        moment = max(float(np.max(np.abs(p.moment))) for p in sliding)
        carried = [thick[other] for other in turning[0].links if other in thick and np.isfinite(thick[other])]
        if math.isfinite(force) and math.isfinite(normal):
            pin = max([pin_of(force), *carried])
            if pin > 0:
                out[link] = block_of(pin, width_ratio, normal, moment, pressure)
    return out


def _peak(pair: Pair) -> float:
    return pair.peak if not math.isnan(pair.peak) else float(np.max(pair.force))


@dataclass(frozen=True)
class SizedMasses:
    """The fixed point: the mechanism with the sized masses, the masses (kg, by link), the rounds it took, whether
    it converged, and the links that kept the file's mass (no bars)."""

    mechanism: Mechanism
    masses: dict[str, float]
    rounds: int
    converged: bool
    kept: tuple[str, ...]
    blocks: tuple[str, ...] = ()

    def said(self) -> str:
        """The sentence of the sizing's inputs that says where the masses come from."""
        how = f"to a fixed point in {self.rounds} rounds" if self.converged else f"not settled in {self.rounds} rounds"
        blocks = (
            f"; {', '.join(self.blocks)} steel blocks carrying their governing pin (2d x k d) over the length their "
            "guide's bush pressure asks"
            if self.blocks
            else ""
        )
        kept = f"; the file's for {', '.join(self.kept)} (no bars, no blocks)" if self.kept else ""
        return (
            f"links' masses from their sized steel sections (at least a round bar of L/d = {SLENDER:g}){blocks}, "
            f"{how}{kept}"
        )


def sized_masses(
    mech: Mechanism,
    bars_of: Callable[[Mechanism], Bars],
    compile_spec: Callable[[Any], Mechanism],
    *,
    rounds: int = ROUNDS,
    blocks_of: Callable[[Mechanism, Bars], dict[str, float]] | None = None,
) -> SizedMasses:
    """Iterate ``mech``'s bar masses with the sizing ``bars_of(mechanism) -> Bars`` (see the module), and its
    blocks' with ``blocks_of(mechanism, bars) -> {link: kg}``, each edited file compiled by ``compile_spec``
    (:func:`linkwork.compile`).

    Raises
    ------
    LinkworkError
        A mechanism without its file (the masses are written into it, as a hand edit would).
    """
    from linkwork.structure.parameters import edited_spec

    if mech.description is None:
        raise LinkworkError("sized masses: the mechanism has no file to write the masses into")
    current, masses, settled = mech, _masses(mech), False
    bars = bars_of(current)
    blocks: dict[str, float] = {}
    for done in range(1, rounds + 1):
        new = {b.link: bar_mass(b.area, b.length) for b in bars.bars if np.isfinite(b.area)}
        blocks = blocks_of(current, bars) if blocks_of is not None else {}
        new |= blocks
        settled = all(abs(new[k] - masses.get(k, 0.0)) <= AGREE * new[k] for k in new)
        masses.update(new)
        if settled and done > 1:
            return SizedMasses(current, masses, done - 1, True, _kept(mech, new), tuple(blocks))
        current = compile_spec(edited_spec(mech, {f"links.{k}.mass": v for k, v in new.items()}))
        bars = bars_of(current)
    return SizedMasses(current, masses, rounds, settled, _kept(mech, masses), tuple(blocks))


def _masses(mech: Mechanism) -> dict[str, float]:
    return {n: float(mech.link_mass[i]) for i, n in enumerate(mech.link_names) if i and not mech.link_virtual[i]}


def _kept(mech: Mechanism, sized: Mapping[str, Any]) -> tuple[str, ...]:
    return tuple(n for n in _masses(mech) if n not in sized)
