"""What a sweep varies: the parameters, their ranges and how the variants are sampled.

A parameter is named by its path in the mechanism file (``links.crank.length``,
``frame.points.O1.x``, ``joints.guide_E.axis``, ``links.rod.mass``), as
:func:`linkwork.parameters` lists them; an override means what the same edit
of the file means (:mod:`linkwork.structure.parameters`).  Ranges are read with units at the edge:
``"links.crank.length=90mm:110mm:50"``; bare numbers are in the file's units.
Inside, everything is SI.
"""

from __future__ import annotations

import math
import re
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from linkwork.did_you_mean import suggest
from linkwork.errors import DesignError, DesignWarning, UnitParseError
from linkwork.spec.reader import described
from linkwork.structure.model import Mechanism
from linkwork.structure.parameters import Parameter, file_units, parameter_list, parameters_by_name
from linkwork.units import parse_quantity, si_factor, unit_for

#: How a plan samples its ranges.
SAMPLINGS = ("grid", "random", "lhs")

#: The ranges of a sweep as given: ``--vary`` texts ``PATH=START:STOP[:COUNT]``, or a dict
#: ``path -> (start, stop[, count])`` (numbers in the file's units, or with units).
Ranges = Mapping[str, Any] | Sequence[str]


@dataclass(frozen=True)
class Vary:
    """One varied dimension.

    Attributes
    ----------
    path : str
        Its path in the file, e.g. ``links.crank.length``.
    start, stop : float
        The range, SI (m, rad, kg).
    count : int or None
        Number of grid values (``None`` where only the range is given, as for optimisation).
    kind : str
        The kind of quantity: ``length``, ``angle``, ``mass`` or ``inertia``.
    """

    path: str
    start: float
    stop: float
    count: int | None
    kind: str

    def grid(self) -> np.ndarray:
        """The ``count`` equally spaced values from ``start`` to ``stop``, SI."""
        n = self.count or 1
        return self.start + (self.stop - self.start) * (np.arange(n) / (n - 1) if n > 1 else np.zeros(1))

    def as_dict(self) -> dict[str, Any]:
        return {"path": self.path, "start": self.start, "stop": self.stop, "count": self.count, "kind": self.kind}


def in_file_units(value: float, kind: str, declared: dict[str, str]) -> tuple[float, str]:
    """An SI value of ``kind`` in the file's unit of that kind: ``(value, unit)``."""
    unit = unit_for(kind, declared)
    return value / si_factor(unit, kind), unit


def scale_warnings(varies: list[Vary], mech: Mechanism, declared: dict[str, str]) -> list[str]:
    """One line for each range that lies wholly below 1/100 or above 100 times the file's value: most
    often a range written in other units than the file's (bare numbers are read in the file's units)."""
    known = {p.name: p.value for p in parameter_list(mech)}
    out = []
    for v in varies:
        file_value = abs(known.get(v.path, 0.0))
        if file_value == 0 or v.start * v.stop <= 0:
            continue
        low, high = sorted((abs(v.start), abs(v.stop)))
        if high < file_value / 100:
            where = "below 1/100 of"
        elif low > 100 * file_value:
            where = "above 100 times"
        else:
            continue
        shown = [in_file_units(x, v.kind, declared) for x in (v.start, v.stop, known[v.path])]
        unit = shown[0][1]
        out.append(
            f'--vary "{v.path}": the range {shown[0][0]:.6g}:{shown[1][0]:.6g} {unit} lies {where} the file\'s '
            f"value {shown[2][0]:.6g} {unit}; bare numbers are in the file's units ({unit})"
        )
    return out


_VARY = re.compile(r"^\s*([^=\s]+)\s*=\s*(.*)$")


def parse_vary(
    text: str, mech: Mechanism, declared: dict[str, str], count_required: bool | None = True
) -> tuple[Vary | None, list[str]]:
    """Read ``PATH=START:STOP[:COUNT]``; returns the :class:`Vary` (or None) and the problems found.

    ``count_required``: True for a grid (COUNT needed), None for a random or Latin-hypercube sample
    (COUNT refused: ``samples`` gives the number of variants), False where it is ignored (optimisation).
    """
    match = _VARY.match(text)
    if match is None:
        return None, [f'--vary "{text}": expected PATH=START:STOP:COUNT, e.g. "links.crank.length=90mm:110mm:50"']
    path, rest = match.group(1), match.group(2)
    known = parameters_by_name(mech)
    problems: list[str] = []
    if path not in known:
        hint = suggest(path, known)
        problems.append(f'--vary "{text}": no parameter "{path}"{hint}; `linkwork parameters FILE` lists them')
    parts = [p.strip() for p in rest.split(":")]
    if len(parts) not in (2, 3) or not all(parts[:2]):
        problems.append(f'--vary "{text}": expected START:STOP:COUNT after "=", got "{rest}"')
        return None, problems
    param = known.get(path)
    kind = param.kind if param is not None else "length"
    values, found = _range(text, parts[:2], kind, declared)
    problems += found
    count, found = _count(text, parts[2] if len(parts) == 3 else None, count_required)
    problems += found
    if values is not None:
        problems += _range_problems(text, parts, values, param, kind)
    if problems or values is None:
        return None, problems
    return Vary(path, values[0], values[1], count, kind), []


def _range(
    text: str, given: list[str], kind: str, declared: dict[str, str]
) -> tuple[tuple[float, float] | None, list[str]]:
    """START and STOP of ``--vary text`` in SI, or None; and the problems of each."""
    values, problems = [], []
    for label, part in zip(("START", "STOP"), given, strict=True):
        try:
            values.append(float(parse_quantity(part, kind, declared)))
        except UnitParseError as exc:
            problems.append(f'--vary "{text}": {label}: {exc}')
    return ((values[0], values[1]) if len(values) == 2 else None), problems


def _count(text: str, given: str | None, count_required: bool | None) -> tuple[int | None, list[str]]:
    """The COUNT of ``--vary text`` (``given``; None where it has none), and what is wrong with it."""
    if given is None:
        return None, ([f'--vary "{text}": COUNT missing (PATH=START:STOP:COUNT)'] if count_required else [])
    problems = []
    count: int | None = None
    try:
        count = int(given)
        if str(count) != given.lstrip("+"):
            raise ValueError
    except ValueError:
        problems.append(f'--vary "{text}": COUNT: expected a whole number, got "{given}"')
        count = None
    else:
        if count < 1:
            problems.append(f'--vary "{text}": COUNT must be 1 or more, got {count}')
    if count_required is None:
        problems.append(
            f'--vary "{text}": COUNT is for a grid; a random or lhs sample takes PATH=START:STOP '
            "and its number of variants from --samples"
        )
    return count, problems


def _range_problems(
    text: str, parts: list[str], values: tuple[float, float], param: Parameter | None, kind: str
) -> list[str]:
    """What is wrong with the range ``values`` (SI) of ``--vary text``: reversed, or of a sign ``param`` refuses."""
    start, stop = values
    problems = []
    if start > stop:
        problems.append(f'--vary "{text}": START {parts[0]} is greater than STOP {parts[1]}')
    if param is not None and (param.positive or kind == "inertia") and param.check(start) is not None:
        what = "positive" if param.positive else "0 or more"
        problems.append(f'--vary "{text}": a {kind} must be {what}, got START {parts[0]}')
    return problems


def parse_varies(
    texts: list[str], mech: Mechanism, declared: dict[str, str], count_required: bool | None = True
) -> list[Vary]:
    """Read every ``--vary``; raises :class:`DesignError` listing every problem of them all."""
    problems: list[str] = []
    out: list[Vary] = []
    if not texts:
        problems.append("give at least one --vary PATH=START:STOP:COUNT (PATH=START:STOP for random, lhs)")
    for text in texts:
        vary, found = parse_vary(text, mech, declared, count_required)
        problems += found
        if vary is not None:
            out.append(vary)
    seen: set[str] = set()
    for v in out:
        if v.path in seen:
            problems.append(f'--vary: "{v.path}" is given twice')
        seen.add(v.path)
    if problems:
        raise DesignError(problems)
    return out


def read_varies(vary: Ranges, mech: Mechanism, count_required: bool | None = True, stacklevel: int = 2) -> list[Vary]:
    """``--vary`` texts, or a dict ``path -> (start, stop[, count])`` (numbers in the file's units or with
    units), read in the units of ``mech``'s description (:func:`file_units`).

    A range far from the file's value (see :func:`scale_warnings`) gives a :class:`DesignWarning`,
    ``stacklevel`` frames above this function.

    Raises
    ------
    DesignError
        Every problem of them all (:func:`parse_varies`).
    """
    if isinstance(vary, Mapping):
        texts = []
        for path, rng in vary.items():
            parts = [str(x) for x in (rng if isinstance(rng, tuple | list) else (rng,))]
            texts.append(f"{path}={':'.join(parts)}")
    else:
        texts = list(vary)
    declared = file_units(described(mech.description))
    out = parse_varies(texts, mech, declared, count_required)
    for line in scale_warnings(out, mech, declared):
        warnings.warn(line, DesignWarning, stacklevel=stacklevel + 1)
    return out


@dataclass(frozen=True)
class SweepPlan:
    """The variants of a sweep.

    Attributes
    ----------
    varies : tuple of Vary
    sampling : str
        ``grid`` (every combination of the ``count`` values, the first dimension slowest),
        ``random`` (uniform) or ``lhs`` (Latin hypercube), both from ``seed``.
    n_variants : int
    seed : int
    """

    varies: tuple[Vary, ...]
    sampling: str = "grid"
    n_variants: int = 0
    seed: int = 0

    @property
    def paths(self) -> list[str]:
        return [v.path for v in self.varies]

    def as_dict(self) -> dict[str, Any]:
        return {
            "varies": [v.as_dict() for v in self.varies],
            "sampling": self.sampling,
            "n_variants": self.n_variants,
            "seed": self.seed,
        }

    def unit_sample(self) -> np.ndarray | None:
        """The random or Latin-hypercube sample in the unit cube, ``(n_variants, n_varies)``; None for a grid."""
        k = len(self.varies)
        if self.sampling == "grid":
            return None
        if self.sampling == "random":
            return np.random.default_rng(self.seed).random((self.n_variants, k))
        from scipy.stats import qmc

        return qmc.LatinHypercube(d=k, rng=np.random.default_rng(self.seed)).random(self.n_variants)

    def values(self, start: int, stop: int, unit: np.ndarray | None = None) -> np.ndarray:
        """SI values of variants ``start`` to ``stop - 1``: ``(stop - start, n_varies)``.

        ``unit`` is :meth:`unit_sample` (computed here when not given) for the random samplings.
        """
        ids = np.arange(start, stop)
        if self.sampling == "grid":
            counts = [v.count or 1 for v in self.varies]
            index = np.unravel_index(ids, counts)
            return np.stack([v.grid()[i] for v, i in zip(self.varies, index, strict=True)], axis=-1)
        sample = self.unit_sample() if unit is None else unit
        assert sample is not None
        u = sample[start:stop]
        lo = np.array([v.start for v in self.varies])
        hi = np.array([v.stop for v in self.varies])
        return lo + (hi - lo) * u


def make_plan(varies: list[Vary], sampling: str = "grid", samples: int | None = None, seed: int = 0) -> SweepPlan:
    """A :class:`SweepPlan`; raises :class:`DesignError` for an unknown sampling or a bad sample count."""
    problems = []
    if sampling not in SAMPLINGS:
        problems.append(f'--sample "{sampling}": expected one of {", ".join(SAMPLINGS)}')
    if samples is not None and samples < 1:
        problems.append(f"--samples must be 1 or more, got {samples}")
    if sampling != "grid" and samples is None:
        problems.append(f"--sample {sampling} needs --samples N, the number of variants")
    if sampling == "grid" and samples is not None:
        problems.append("--samples is for --sample random or lhs; a grid has the product of the COUNTs")
    if sampling == "grid" and any(v.count is None for v in varies):
        problems.append("a grid needs a COUNT in every --vary")
    if problems:
        raise DesignError(problems)
    n = samples if samples is not None else math.prod(v.count or 1 for v in varies)  # a grid's
    return SweepPlan(tuple(varies), sampling, int(n), int(seed))
