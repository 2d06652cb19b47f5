"""What every kind of synthesis shares: the crank's angle between the limit positions, the result, the family,
the mass rule, the file's text and the verification by the analysis itself."""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np

from linkwork.errors import SynthesisError
from linkwork.requirements import BAR, STEEL
from linkwork.spec.schema import Spec

#: The analysis's own resolution, relative: added to the tolerance the rounding of the lengths implies
#: (:func:`~linkwork.synthesis.rounding.measure_written`), which the written file's measured stroke (swing),
#: time ratio and pressure (transmission) angle must reach with the requirements and the closed forms.
TOLERANCE = 1e-9

#: The step every synthesised file writes its lengths and point coordinates to (m): 0.1 mm, as a designer
#: dimensions a machine's drawing.  A written length is within STEP / 2 of the exact one; the tolerance of each
#: requirement follows from it (:func:`~linkwork.synthesis.rounding.measure_written`).  A mechanism whose
#: scale (its stroke, rocker or frame asked) is under 100 steps (10 mm) is dimensioned to the power of ten that
#: keeps 100 steps on it (:func:`dimensioned`), as a drawing of an instrument's linkage is.
STEP = 1e-4

_STEP: ContextVar[float] = ContextVar("step", default=STEP)


def step() -> float:
    """The step (m) the file being written is dimensioned to (:data:`STEP` unless :func:`dimensioned` says)."""
    return _STEP.get()


@contextmanager
def dimensioned(*lengths: float) -> Iterator[float]:
    """Write the files within to :data:`STEP`, or to the power of ten at most a hundredth of the shortest nonzero
    of ``lengths`` (m, the requirements that set the scale) where that is finer; yields the step."""
    shortest = min((abs(x) for x in lengths if x and math.isfinite(x)), default=1.0)
    fine = STEP if shortest >= 100 * STEP else 10.0 ** math.floor(math.log10(shortest / 100))
    token = _STEP.set(fine)
    try:
        yield fine
    finally:
        _STEP.reset(token)


#: The names the kinds' closed forms give the quantities of the requirements they predict.
ALIASES = {"largest_pressure_angle": "max_pressure_angle", "least_transmission_angle": "min_transmission_angle"}

#: The lengths a request may give (m): from a micrometre to a kilometre (beyond, the products of the closed forms
#: overflow, and no mechanism a press or shears designer asks for comes near).
LENGTHS = (1e-6, 1e3)

#: The largest time ratio a request may give: the return stroke then takes 360 / 101 = 3.6 deg of the turn.
TIME_RATIOS = 100.0

#: The largest ratio of a synthesised mechanism's longest length to its shortest (its links, offsets, the
#: stroke): beyond, the analysis cannot tell the short ones from a point at the long ones' scale (its tolerances
#: are relative to the mechanism's size), and no shop makes a link a thousandth of its neighbour.
PROPORTION = 1e3


#: The design rule every kind keeps unless the request lowers it (``min_transmission_angle``): the least
#: transmission angle of every dyad of the written file over the turn, at least 40 deg (rad).  Nearer a dead point
#: the force in a dyad grows as 1 / sin(mu) for the force it passes on (1.56 times at 40 deg, 31 times at
#: 1.86 deg), and friction in the pairs can jam it; 40 deg is the classical bound for a linkage of
#: general machinery.
LEAST_TRANSMISSION = math.radians(40.0)

#: Crank samples of the verification's turn (the analysis refines extremes between them).
VERIFY_STEPS = 720


def crank_angle_between_limits(time_ratio: float) -> float:
    """theta (rad): the crank's angle between its two limit positions for the time ratio K >= 1,
    theta = pi (K - 1) / (K + 1), since the strokes take pi + theta and pi - theta of the turn."""
    return math.pi * (time_ratio - 1.0) / (time_ratio + 1.0)


def time_ratio_of(theta: float) -> float:
    """K of the crank's angle theta (rad) between the limit positions: (pi + theta) / (pi - theta)."""
    return (math.pi + theta) / (math.pi - theta)


@dataclass(frozen=True)
class Family:
    """The one-parameter family the requirements leave: ``values`` of the free ``parameter`` (its ``unit``),
    and for each the mechanism's ``columns`` (name -> array of the same length, SI); NaN where the
    mechanism of a value cannot run."""

    parameter: str
    unit: str
    values: np.ndarray
    columns: dict[str, np.ndarray]
    criterion: str


@dataclass(frozen=True)
class Synthesis:
    """A synthesised mechanism.

    Attributes
    ----------
    kind : str
        ``"slider-crank"`` or ``"crank-rocker"``.
    requirements : dict
        The requirements as given, SI (m, rad, ratios).
    dimensions : dict
        The derived dimensions, SI.
    predicted : dict
        What the closed forms give the mechanism (stroke or swing, time ratio, extreme pressure or
        transmission angle), SI.
    measured : dict
        The same quantities as :func:`linkwork.kinematics` measures them on the written text.
    spec : Spec
        The mechanism, read back from :attr:`text`.
    text : str
        The mechanism file, each derived dimension with the requirement it meets as a comment, and its
        ``requirements:``.
    family : Family or None
        The family the requirements left, where they left one; the pick is :attr:`criterion`'s.
    criterion : str
        How the mechanism was picked from the family (or that the requirements fixed it).
    notes : list of str
        What else the synthesis found (the criteria of the pick).
    tolerances : dict
        The tolerance (SI) of each requirement the analysis measures, implied by the lengths written to
        :data:`STEP` (:func:`~linkwork.synthesis.rounding.measure_written`).
    tree : object
        The file's round-trip YAML tree as a kind wrote it, before :func:`linkwork.synthesis.synthesize` adds its
        ``requirements:`` and writes :attr:`text` (and reads :attr:`spec` from it) once; None once written.
    """

    kind: str
    requirements: dict[str, float]
    dimensions: dict[str, float]
    predicted: dict[str, float]
    measured: dict[str, float]
    spec: Spec
    text: str
    family: Family | None = None
    criterion: str = ""
    notes: list[str] = field(default_factory=list)
    tolerances: dict[str, float] = field(default_factory=dict)
    tree: Any = field(default=None, repr=False, compare=False)

    def write(self, out: str | Path) -> Path:
        """Write :attr:`text` to ``out`` atomically; returns the path."""
        from linkwork.atomic import write_atomic

        return write_atomic(out, lambda tmp: tmp.write_text(self.text, encoding="utf-8"))


def proportions(kind: str, lengths: dict[str, float], nearest: str = "") -> None:
    """Raise :class:`SynthesisError` where the longest of ``lengths`` (m, by name; zeros ignored) is more than
    :data:`PROPORTION` times the shortest, or any is not finite: naming both, and the ``nearest`` request that
    keeps them in proportion where the kind knows it."""
    sizes = {name: abs(float(v)) for name, v in lengths.items() if v != 0}
    bad = [name for name, v in sizes.items() if not math.isfinite(v)]
    if bad:
        raise SynthesisError(f"{kind}: the request gives an infinite {bad[0]}{'; ' + nearest if nearest else ''}")
    long, short = max(sizes, key=sizes.__getitem__), min(sizes, key=sizes.__getitem__)
    if sizes[long] > PROPORTION * sizes[short]:
        raise SynthesisError(
            f"{kind}: the request gives a {long} of {sizes[long] * 1e3:.4g} mm and a {short} of "
            f"{sizes[short] * 1e3:.4g} mm, more than {PROPORTION:g} times apart: no mechanism to make or analyse"
            f"{'; ' + nearest if nearest else ''}"
        )


def least_allowed(min_transmission_angle: float | None) -> float:
    """The least transmission angle (rad) the written mechanism must keep: the one asked for, else the rule
    :data:`LEAST_TRANSMISSION`; raises :class:`SynthesisError` for a bound outside (0, 90) deg."""
    if min_transmission_angle is None:
        return LEAST_TRANSMISSION
    if not 0 < min_transmission_angle < math.pi / 2:
        raise SynthesisError(
            f"least transmission angle {deg(min_transmission_angle)}: expected a bound between 0 and 90 deg"
        )
    return min_transmission_angle


def below_rule(what: str, least: float, bound: float, nearest: str) -> SynthesisError:
    """The refusal of a mechanism whose least transmission angle ``least`` (rad) is under ``bound``: what gives
    it, the bound (the rule's or the one asked), the ``nearest`` request that meets it, and the bound that would
    accept this one (rounded down, so that it does)."""
    rule = "the design rule" if bound == LEAST_TRANSMISSION else "the bound asked"
    return SynthesisError(
        f"{what} gives a least transmission angle of {down(math.degrees(least))} deg, under {rule}'s "
        f"{math.degrees(bound):.4g} deg; {nearest} (or lower --min-transmission-angle to "
        f"{down(math.degrees(least))} deg)"
    )


def keep_rule(least: float, bound: float, tolerance: float | None = None) -> float:
    """``least``, the least transmission angle (rad) of every dyad of the written file over the turn as the analysis
    measures it (:func:`~linkwork.synthesis.measuring.measure`); raises :class:`SynthesisError` where it is under
    ``bound`` by more than ``tolerance`` (rad; what the lengths' rounding implies, else :data:`TOLERANCE`
    relative): a closed form let through what the file does not keep."""
    if least < bound - (TOLERANCE * bound if tolerance is None else tolerance):
        raise SynthesisError(
            f"the written mechanism measures a least transmission angle of {down(math.degrees(least))} deg, under "
            f"{math.degrees(bound):.4g} deg"
        )
    return least


def need(value: float | None, ok: bool, message: str) -> None:
    """Raise :class:`SynthesisError` with ``message`` unless ``ok`` (for a given ``value``)."""
    if value is not None and not ok:
        raise SynthesisError(message)


def given(**requirements: float | None) -> dict[str, float]:
    """The requirements that were given (not None), in the order named."""
    return {name: value for name, value in requirements.items() if value is not None}


def deg(angle: float) -> str:
    """An angle (rad) as the messages write it: degrees, 4 significant digits."""
    return f"{math.degrees(angle):.4g} deg"


def up(x: float, digits: int = 4) -> str:
    """``x`` rounded up to ``digits`` significant digits, as a message writes a least value that can be met (a
    rounded bound must itself be feasible: rounding to the nearest may fall on the wrong side)."""
    return _safe(x, digits, math.ceil)


def down(x: float, digits: int = 4) -> str:
    """``x`` rounded down to ``digits`` significant digits, as a message writes a largest value that can be met."""
    return _safe(x, digits, math.floor)


def _safe(x: float, digits: int, step: Callable[[float], int]) -> str:
    if not math.isfinite(x) or x == 0:
        return f"{x:g}"
    scale = 10.0 ** (math.floor(math.log10(abs(x))) - digits + 1)
    return f"{step(x / scale) * scale:.{digits}g}"


class Making(NamedTuple):
    """How a written file makes its mechanism: the crank's ``speed`` as written (``"60 rpm"``), and the steel bars'
    ``section`` (width and height, m) and ``density`` (kg/m^3) its links' masses are of."""

    speed: str
    section: tuple[float, float]
    density: float


def bar_mass(length: float, section: tuple[float, float] = BAR, density: float = STEEL) -> float:
    """The mass rule: a steel bar of ``section`` (width, height; m) and ``length`` (m), kg."""
    return density * section[0] * section[1] * length


def mm(x: float) -> float:
    """A length (m) in mm as every synthesised file writes it: rounded to the :func:`step` (0.1 mm), and no
    ``-0.0``."""
    decimals = max(0, -math.floor(math.log10(step() * 1e3) + 1e-9))
    return float(f"{rounded(x) * 1e3:.{decimals}f}") + 0.0


def rounded(x: float) -> float:
    """A length (m) rounded to the :func:`step`, as the files write it (m)."""
    return round(x / step()) * step() + 0.0


def degrees(x: float) -> float:
    """An angle (rad) in degrees as the file writes it: the same rule as :func:`mm`."""
    from linkwork.units import written

    return float(written(x, "angle", {"angle": "deg"}, digits=12)) + 0.0


def newtons(x: float) -> str:
    """A force (N) as the file writes it: the same rule, with its unit."""
    return f"{x:.12g} N"


def commented(data: dict[str, Any], comments: dict[tuple[str, ...], str]) -> Any:
    """``data`` as a ruamel round-trip tree with each ``comments`` key path's comment beside its value."""
    from ruamel.yaml.comments import CommentedMap, CommentedSeq

    def tree(x: Any) -> Any:
        if isinstance(x, dict):
            m = CommentedMap((k, tree(v)) for k, v in x.items())
            if all(not isinstance(v, dict | list) for v in x.values()) and len(x) <= 6:
                m.fa.set_flow_style()
            return m
        if isinstance(x, list):
            s = CommentedSeq(tree(v) for v in x)
            s.fa.set_flow_style()
            return s
        return x

    root = tree(data)
    for path, text in comments.items():
        node = root
        for key in path[:-1]:
            node = node[key]
        node.yaml_add_eol_comment(text, path[-1])
    return root


class Draft(NamedTuple):
    """A synthesised file before its ``requirements:`` are written: its YAML ``tree`` (the one writer's round-trip
    tree, a comment beside each derived dimension), and the ``spec`` and ``mech`` read and compiled from the tree's
    data, which the analysis measures (:func:`~linkwork.synthesis.rounding.measure_written`)."""

    tree: Any
    spec: Spec
    mech: Any


def draft(tree: Any) -> Draft:
    """The :class:`Draft` of a file's round-trip ``tree``: its data validated (:func:`linkwork.from_dict`) and
    compiled, once."""
    from linkwork.api import compile
    from linkwork.spec.reader import from_dict

    spec = from_dict(tree, "<synthesised>")
    return Draft(tree, spec, compile(spec))


def file_of(data: dict[str, Any], comments: dict[tuple[str, ...], str]) -> Draft:
    """The mechanism file's :class:`Draft`: ``data`` with its ``comments`` as the one YAML writer's tree."""
    return draft(commented(data, comments))


def confirm(
    measured: dict[str, float], predicted: dict[str, float], worst: float, tolerances: dict[str, float]
) -> None:
    """Raise :class:`SynthesisError` where the analysis measured a quantity of ``predicted`` away from it by
    more than its ``tolerances`` (SI, by requirement name or :data:`ALIASES`: what the lengths' rounding implies,
    :func:`~linkwork.synthesis.rounding.measure_written`); the message says how close to a dead point the
    mechanism runs (``worst``, its least transmission angle, rad), where the measures are ill-conditioned."""
    for key, wanted in predicted.items():
        got = measured[key]
        tol = tolerances.get(ALIASES.get(key, key), TOLERANCE * max(abs(wanted), 1e-300))
        if not abs(got - wanted) <= tol:
            raise SynthesisError(
                f"{key.replace('_', ' ')}: the written mechanism measures {got!r}, expected {wanted!r}; it comes "
                f"within {deg(worst)} of a dead point, where the limit positions are ill-conditioned: ask for "
                "a smaller time ratio"
            )
