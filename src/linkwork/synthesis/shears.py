"""Synthesis of the bundled double-cut shears (seed 002) for the knives' strokes, their overlap when closed (or
the opening) and the time ratio K, keeping the bundled file's structure.

No closed form: the design package meets the requirements as equality constraints
(:func:`linkwork.design.equalities.meet`, Newton's method on the same metrics a sweep or an optimisation
reports) over named parameters of the bundled file:

* ``frame.points.O1.x`` (the crank's pivot along the rocker's arm): K, the time of the knives closing over
  that of their opening (the metric ``working_time_ratio``);
* ``links.rocker.points.D.x`` and ``links.rocker.points.C.x`` (the rocker's arms to the knives' rods): the upper
  and the lower knife's strokes (``stroke:guide_E``, ``stroke:guide_F``);
* both knives' edges, lengthened by s / 2 each towards the other (``links.knife_upper.points.edge.y``,
  ``links.knife_lower.points.edge.y``): the overlap (``knife_overlap``).

The crank's length is left free: the requirements leave a one-parameter family, solved by continuation from
the bundled crank outwards, and the member is picked by a criterion: the greatest least transmission angle
over the turn (the least largest pressure angle) by default, or the least peak driving torque under the file's
loads (the cutting force), refined between the samples (:func:`linkwork.kinetostatics.torque_peak`).

The knives are each driven through a rod from the rocker, monotone in the rocker's angle, so both reach their
extremes with the rocker: the gap between the edges sweeps both strokes, and overlap + opening = upper stroke +
lower stroke.  Hence the overlap and the opening are one requirement: give either (both only if they agree).

Masses, inertias, loads and the drive are the bundled file's (an override keeps the values the file gives).
"""

from __future__ import annotations

import math

import numpy as np

from linkwork.errors import SynthesisError
from linkwork.synthesis.common import TOLERANCE, VERIFY_STEPS, Family, Synthesis, given

KIND = "double-cut-shears"

#: The named parameters the unknowns and the family's crank length set.
CRANK = "links.crank.length"
PATHS = [
    CRANK,
    "frame.points.O1.x",
    "links.rocker.points.D.x",
    "links.rocker.points.C.x",
    "links.knife_upper.points.edge.y",
    "links.knife_lower.points.edge.y",
]

#: The metrics each unknown meets, in the unknowns' order (the requirements' names beside them).
EQUALITIES = {
    "working_time_ratio": "time_ratio",
    "stroke:guide_E": "upper_stroke",
    "stroke:guide_F": "lower_stroke",
    "knife_overlap": "overlap",
}

#: The family's crank lengths, relative to the bundled crank.
SPAN = (0.5, 2.0)
MEMBERS = 16

#: Steps from the bundled file's metrics to the requirements for the first member.
HOMOTOPY = 8

#: The criteria a member is picked by: metric, sense, words.
CRITERIA = {
    "pressure": ("min_transmission_angle", -1.0, "the greatest least transmission angle"),
    "torque": ("peak_driving_torque", 1.0, "the least peak driving torque under the file's loads"),
}


def _requirements(upper: float, lower: float, ratio: float, overlap: float | None, opening: float | None) -> float:
    """The overlap the requirements ask for (from the opening where only it is given); raises where they
    conflict or are out of range."""
    for name, value in (("upper stroke", upper), ("lower stroke", lower)):
        if not 0 < value < math.inf:
            raise SynthesisError(f"{name} {value!r} m: expected a positive length")
    if not 0 < ratio < math.inf:
        raise SynthesisError(f"time ratio K = {ratio!r}: expected a positive number")
    total = upper + lower
    if overlap is None and opening is None:
        raise SynthesisError("double-cut-shears: give the knives' overlap when closed or the opening")
    if overlap is not None and opening is not None and abs(overlap + opening - total) > TOLERANCE * total:
        raise SynthesisError(
            f"overlap {overlap * 1e3:g} mm + opening {opening * 1e3:g} mm must equal the strokes together "
            f"{total * 1e3:g} mm (the gap between the knives sweeps both strokes): give one of them"
        )
    want = overlap if overlap is not None else total - opening  # type: ignore[operator]
    if not 0 <= want < total:
        raise SynthesisError(
            f"{'overlap' if overlap is not None else 'opening'}: the knives' gap sweeps the two strokes, "
            f"{total * 1e3:g} mm; the overlap must lie in [0, {total * 1e3:g}) mm and the opening in "
            f"(0, {total * 1e3:g}] mm"
        )
    return want


def _values(base: dict[str, float], cranks: np.ndarray):  # noqa: ANN202
    """``values_of`` for :func:`~linkwork.design.equalities.meet`: unknowns (O1.x, D.x, C.x, s) of the
    members -> the values of :data:`PATHS`."""
    upper, lower = base["links.knife_upper.points.edge.y"], base["links.knife_lower.points.edge.y"]

    def values_of(u: np.ndarray, member: np.ndarray) -> np.ndarray:
        return np.column_stack([cranks[member], u[:, 0], u[:, 1], u[:, 2], upper - u[:, 3] / 2, lower + u[:, 3] / 2])

    return values_of


def family(mech, targets: dict[str, float], cranks: np.ndarray, metrics: list[str]) -> tuple:  # noqa: ANN001
    """Solve the members of the crank lengths ``cranks`` (m, increasing) by continuation: the middle one from
    the bundled file (a homotopy from its metrics to the requirements), then outwards both ways, each from the
    last solved member of its side.  Returns (unknowns (M, 4), NaN rows unsolved; metric column -> (M,) at the
    solutions)."""
    from linkwork.design.equalities import meet
    from linkwork.design.evaluate import evaluate
    from linkwork.design.metrics import parse_metrics
    from linkwork.structure.parameters import parameter_values

    base = parameter_values(mech)
    scales = np.full(4, base[CRANK])
    unknowns = np.full((len(cranks), 4), np.nan)

    def solve(members: list[int], starts: list[np.ndarray], goal: dict[str, float] = targets) -> None:
        met = meet(mech, PATHS, _values(base, cranks[members]), np.array(starts), goal, scales=scales, steps=360)
        unknowns[members] = met.unknowns

    # the first member: from the bundled file's own metrics to the requirements in steps (a homotopy)
    first = len(cranks) // 2
    start = np.array([base[p] for p in PATHS[1:4]] + [0.0])
    own = evaluate(
        mech,
        PATHS,
        _values(base, cranks[[first]])(start[None], np.zeros(1, int)),
        parse_metrics(list(targets), mech),
        360,
    )
    for t in np.linspace(0.0, 1.0, HOMOTOPY + 1)[1:]:
        solve([first], [start], {c: (1 - t) * own[c][0] + t * v for c, v in targets.items()})
        if np.isnan(unknowns[first, 0]):
            return unknowns, {}
        start = unknowns[first].copy()
    sides = [list(range(first + 1, len(cranks))), list(range(first - 1, -1, -1))]
    for step in range(max(map(len, sides))):
        members = [side[step] for side in sides if step < len(side)]
        starts = [_last_solved(unknowns, [first, *side[:step]]) for side in sides if step < len(side)]
        solve(members, starts)
    ok = np.flatnonzero(~np.isnan(unknowns[:, 0]))
    values = _values(base, cranks[ok])(unknowns[ok], np.arange(len(ok)))
    cols = evaluate(mech, PATHS, values, parse_metrics([*targets, *metrics], mech), VERIFY_STEPS)
    found = {c: np.full(len(cranks), np.nan) for c in cols}
    for c, v in cols.items():
        found[c][ok] = v
    return unknowns, found


def solved_family(
    upper_stroke: float, lower_stroke: float, time_ratio: float, overlap: float, crank: float | None = None
) -> tuple[np.ndarray, np.ndarray, dict[str, np.ndarray]]:
    """(crank lengths (M,), unknowns (M, 4), metric columns) of the family for the requirements (SI; the overlap
    when closed), the members over :data:`SPAN` of the crank that meets the strokes nearest the bundled file's
    proportions (the one ``crank`` where it is given): :func:`family` on the bundled file."""
    from linkwork.api import mechanism_of
    from linkwork.structure.parameters import parameter_values

    mech = mechanism_of(KIND, "mechanism")
    base = parameter_values(mech)
    targets = {
        "working_time_ratio": time_ratio,
        "stroke:guide_E": upper_stroke,
        "stroke:guide_F": lower_stroke,
        "knife_overlap": overlap,
    }
    # the knives' strokes grow with the rocker's swing, nearly as the crank: the family is centred there
    guess = base[CRANK] * max(upper_stroke / _own(mech, "stroke:guide_E"), lower_stroke / _own(mech, "stroke:guide_F"))
    cranks = np.array([crank]) if crank is not None else guess * np.geomspace(*SPAN, MEMBERS)
    unknowns, found = family(mech, targets, cranks, [m for m, _, _ in CRITERIA.values()])
    return cranks, unknowns, found


def member_values(cranks: np.ndarray, unknowns: np.ndarray) -> list[dict[str, float]]:
    """The values of :data:`PATHS` (SI) of the members ``cranks`` with their ``unknowns``: edits of the bundled
    file, or of a file synthesised from it."""
    from linkwork.api import mechanism_of
    from linkwork.structure.parameters import parameter_values

    base = parameter_values(mechanism_of(KIND, "mechanism"))
    rows = _values(base, cranks)(unknowns, np.arange(len(cranks)))
    return [dict(zip(PATHS, row.tolist(), strict=True)) for row in rows]


def _last_solved(unknowns: np.ndarray, chain: list[int]) -> np.ndarray:
    """The unknowns of the last solved member of ``chain``."""
    return next(unknowns[i] for i in reversed(chain) if not np.isnan(unknowns[i, 0]))


def synthesize(
    upper_stroke: float,
    lower_stroke: float,
    time_ratio: float,
    overlap: float | None = None,
    opening: float | None = None,
    crank: float | None = None,
    criterion: str = "pressure",
    speed: str | None = None,
) -> Synthesis:
    """The bundled double-cut shears with the upper and lower knives' strokes (m), the time ratio K (the knives closing
    over opening), and the overlap when closed or the opening (m); ``crank`` (m) fixes the family's free crank length,
    else the member is picked by ``criterion`` (``"pressure"``: the least largest pressure angle, the greatest least
    transmission angle; ``"torque"``: the least peak driving torque under the file's cutting load).  ``speed`` replaces
    the file's crank speed.  Verified by the analysis of the written file."""
    from linkwork.api import mechanism_of

    want = _requirements(upper_stroke, lower_stroke, time_ratio, overlap, opening)
    if criterion not in CRITERIA:
        raise SynthesisError(f"criterion {criterion!r}: expected one of {', '.join(CRITERIA)}")
    if crank is not None and not 0 < crank < math.inf:
        raise SynthesisError(f"crank {crank!r} m: expected a positive length")
    mech = mechanism_of(KIND, "mechanism")
    cranks, unknowns, found = solved_family(upper_stroke, lower_stroke, time_ratio, want, crank)
    metric, sense, words = CRITERIA[criterion]
    score = sense * found.get(metric, np.full(len(cranks), np.nan))
    if not np.isfinite(score).any():
        raise SynthesisError(_infeasible(mech, upper_stroke, lower_stroke, time_ratio, want, crank))
    pick = int(np.nanargmin(score))
    (values,) = member_values(cranks[[pick]], unknowns[[pick]])
    why = f"crank {cranks[pick] * 1e3:.6g} mm as given" if crank is not None else f"picked by {words}"
    requirements = given(
        upper_stroke=upper_stroke,
        lower_stroke=lower_stroke,
        time_ratio=time_ratio,
        overlap=overlap,
        opening=opening,
        crank=crank,
    )
    text, spec = _file(mech, values, requirements, want, why, speed)
    measured = measure(spec)
    predicted = {
        "upper_stroke": upper_stroke,
        "lower_stroke": lower_stroke,
        "time_ratio": time_ratio,
        "overlap": want,
        "opening": upper_stroke + lower_stroke - want,
    }
    confirm(measured, predicted)
    columns = {
        "crank": cranks,
        "O1.x": unknowns[:, 0],
        "D.x": unknowns[:, 1],
        "C.x": unknowns[:, 2],
        "edges_lengthened_by": unknowns[:, 3] / 2,
        **{m: found[m] for m, _, _ in CRITERIA.values() if m in found},
    }
    fam = None if crank is not None else Family("crank length", "m", cranks, columns, words)
    dims = dict(zip(["crank", "O1.x", "D.x", "C.x", "upper_edge.y", "lower_edge.y"], values.values(), strict=True))
    notes = [f"{m}: {found[m][pick]:.6g}" for m, _, _ in CRITERIA.values() if m in found]
    return Synthesis(KIND, requirements, dims, predicted, measured, spec, text, fam, why, notes)


def _own(mech, metric: str) -> float:  # noqa: ANN001
    """A metric of the bundled file as it is."""
    from linkwork.design.evaluate import evaluate
    from linkwork.design.metrics import parse_metrics

    return float(evaluate(mech, [], np.zeros((1, 0)), parse_metrics([metric], mech), 360)[metric][0])


def _infeasible(mech, upper: float, lower: float, ratio: float, want: float, crank: float | None) -> str:  # noqa: ANN001
    own = {m: _own(mech, m) for m in ("stroke:guide_E", "stroke:guide_F", "working_time_ratio", "knife_overlap")}
    where = f"with the crank {crank * 1e3:g} mm" if crank is not None else "for any crank length tried"
    return (
        f"upper stroke {upper * 1e3:g} mm, lower stroke {lower * 1e3:g} mm, time ratio K = {ratio:g} and overlap "
        f"{want * 1e3:g} mm: no double-cut shears of the bundled structure meet them together {where} (the "
        f"knives' rods cannot reach their guides, or the rocker's four-bar cannot give K); the bundled file has "
        f"{own['stroke:guide_E'] * 1e3:.4g} and {own['stroke:guide_F'] * 1e3:.4g} mm, K = "
        f"{own['working_time_ratio']:.4g} and {own['knife_overlap'] * 1e3:.4g} mm: ask for values nearer those"
    )


def measure(spec) -> dict[str, float]:  # noqa: ANN001
    """The knives' strokes, K, overlap and opening of ``spec`` as :func:`linkwork.kinematics` and the design
    metrics of that result measure them."""
    from linkwork.api import kinematics
    from linkwork.design.evaluate import Evaluation
    from linkwork.design.metrics import METRICS

    ev = Evaluation(kinematics(spec, steps=VERIFY_STEPS))

    def one(name: str, arg: str | None = None) -> float:
        return float(np.squeeze(METRICS[name].compute(ev, arg)))

    return {
        "upper_stroke": one("stroke", "guide_E"),
        "lower_stroke": one("stroke", "guide_F"),
        "time_ratio": one("working_time_ratio"),
        "overlap": one("knife_overlap"),
        "opening": one("knife_clearance"),
    }


def confirm(measured: dict[str, float], predicted: dict[str, float]) -> None:
    """Raise where the written file measures a requirement away from it by more than :data:`TOLERANCE`
    (relative to the strokes for the overlap and opening)."""
    scale = predicted["upper_stroke"] + predicted["lower_stroke"]
    for key, wanted in predicted.items():
        size = scale if key in ("overlap", "opening") else abs(wanted)
        if not abs(measured[key] - wanted) <= TOLERANCE * size:
            raise SynthesisError(
                f"{key.replace('_', ' ')}: the written shears measure {measured[key]!r}, expected {wanted!r}"
            )


def _file(mech, values: dict[str, float], requirements: dict, want: float, why: str, speed: str | None) -> tuple:  # noqa: ANN001
    """The bundled file's text with ``values`` written in (the one writer), a comment beside each derived
    dimension, and the Spec read back."""
    from linkwork.spec.edit import round_trip_yaml, yaml_text
    from linkwork.spec.reader import loads
    from linkwork.structure.parameters import file_text

    data = round_trip_yaml().load(file_text(mech, values))
    k, up, low = requirements["time_ratio"], requirements["upper_stroke"], requirements["lower_stroke"]
    data["description"] = (
        f"Double-cut shears of the bundled structure (seed 002) synthesised for the knives' strokes "
        f"{up * 1e3:.6g} mm (upper) and {low * 1e3:.6g} mm (lower), overlap {want * 1e3:.6g} mm when closed "
        f"(opening {(up + low - want) * 1e3:.6g} mm) and time ratio K = {k:.6g} (closing over opening); the "
        f"crank's length {why}.  Masses, loads and drive as in the bundled file.\n"
    )
    data["links"]["crank"].yaml_add_eol_comment(f"# the family's free length: {why}", "length")
    data["frame"]["points"].yaml_add_eol_comment(f"# O1.x: time ratio K = {k:.6g}", "O1")
    data["links"]["rocker"].yaml_add_eol_comment(
        f"# D.x: upper stroke {up * 1e3:.6g} mm; C.x: lower stroke {low * 1e3:.6g} mm", "points"
    )
    for knife in ("knife_upper", "knife_lower"):
        data["links"][knife].yaml_add_eol_comment(f"# edge: overlap {want * 1e3:.6g} mm when closed", "points")
    if speed is not None:
        data["drives"][0]["speed"] = speed
    text = yaml_text(data)
    return text, loads(text, "<synthesised>")
