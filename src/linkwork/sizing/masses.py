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
would.  A link that is no bar (a slider, a block) keeps the file's mass: the sizing says so.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from linkwork.errors import LinkworkError
from linkwork.sizing.links import Bars
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
class SizedMasses:
    """The fixed point: the mechanism with the sized masses, the masses (kg, by link), the rounds it took, whether
    it converged, and the links that kept the file's mass (no bars)."""

    mechanism: Mechanism
    masses: dict[str, float]
    rounds: int
    converged: bool
    kept: tuple[str, ...]

    def said(self) -> str:
        """The sentence of the sizing's inputs that says where the masses come from."""
        how = f"to a fixed point in {self.rounds} rounds" if self.converged else f"not settled in {self.rounds} rounds"
        kept = f"; the file's for {', '.join(self.kept)} (no bars)" if self.kept else ""
        return f"links' masses from their sized steel sections (at least a round bar of L/d = {SLENDER:g}), {how}{kept}"


def sized_masses(
    mech: Mechanism,
    bars_of: Callable[[Mechanism], Bars],
    compile_spec: Callable[[Any], Mechanism],
    *,
    rounds: int = ROUNDS,
) -> SizedMasses:
    """Iterate ``mech``'s bar masses with the sizing ``bars_of(mechanism) -> Bars`` (see the module), each edited
    file compiled by ``compile_spec`` (:func:`linkwork.compile`).

    Raises
    ------
    LinkworkError
        A mechanism without its file (the masses are written into it, as a hand edit would).
    """
    from linkwork.structure.parameters import edited_spec

    if mech.spec is None:
        raise LinkworkError("sized masses: the mechanism has no file to write the masses into")
    current, masses, settled = mech, _masses(mech), False
    bars = bars_of(current)
    for done in range(1, rounds + 1):
        new = {b.link: bar_mass(b.area, b.length) for b in bars.bars if np.isfinite(b.area)}
        settled = all(abs(new[k] - masses.get(k, 0.0)) <= AGREE * new[k] for k in new)
        masses.update(new)
        if settled and done > 1:
            return SizedMasses(current, masses, done - 1, True, _kept(mech, new))
        current = compile_spec(edited_spec(mech, {f"links.{k}.mass": v for k, v in new.items()}))
        bars = bars_of(current)
    return SizedMasses(current, masses, rounds, settled, _kept(mech, masses))


def _masses(mech: Mechanism) -> dict[str, float]:
    return {n: float(mech.link_mass[i]) for i, n in enumerate(mech.link_names) if i and not mech.link_virtual[i]}


def _kept(mech: Mechanism, sized: Mapping[str, Any]) -> tuple[str, ...]:
    return tuple(n for n in _masses(mech) if n not in sized)
