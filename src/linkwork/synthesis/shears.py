"""Synthesis of the bundled double-cut shears (seed 002) for the knives' strokes, their overlap when closed (or
the opening) and the time ratio K, keeping the bundled file's structure.

No closed form: the design package meets the requirements as equality constraints
(:func:`linkwork.design.equalities.meet`, Newton's method on the same metrics a sweep or an optimisation
reports) over named parameters of the bundled file (named here as the bundled file names its parts; the
synthesis reads the names from the file, :mod:`linkwork.spec.shears`):

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

import functools
import math
from typing import Any

import numpy as np

from linkwork.errors import SynthesisError
from linkwork.requirements import ShearsRequirements
from linkwork.spec.shears import ShearsParts, shears_parts
from linkwork.synthesis.common import (
    TOLERANCE,
    VERIFY_STEPS,
    Draft,
    Family,
    Synthesis,
    below_rule,
    draft,
    given,
    keep_rule,
    least_allowed,
    rounded,
)
from linkwork.synthesis.measuring import knives
from linkwork.synthesis.rounding import measure_written

KIND = "double-cut-shears"


@functools.cache
def bundled() -> ShearsParts:
    """The names of the bundled file's parts (:func:`parts`); its
    :attr:`~linkwork.spec.shears.ShearsParts.paths` are the named parameters the unknowns and the
    family's crank length set."""
    from linkwork.api import spec_of

    return parts(spec_of(KIND))


def parts(spec: Any) -> ShearsParts:
    """The parts of the shears ``spec`` (:func:`~linkwork.spec.shears.shears_parts`); raises
    :class:`SynthesisError` naming the one it lacks."""
    found = shears_parts(spec)
    if isinstance(found, str):
        raise SynthesisError(f"double-cut shears: the file has no {found}")
    return found


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
    """``values_of`` for :func:`~linkwork.design.equalities.meet`: unknowns (the pivot's x, the rocker's arms' x,
    s) of the members -> the values of the :func:`bundled` paths."""
    upper, lower = (base[path] for path in bundled().paths[4:])

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
    paths = bundled().paths
    scales = np.full(4, base[paths[0]])
    unknowns = np.full((len(cranks), 4), np.nan)

    def solve(members: list[int], starts: list[np.ndarray], goal: dict[str, float] = targets) -> None:
        met = meet(mech, paths, _values(base, cranks[members]), np.array(starts), goal, scales=scales, steps=360)
        unknowns[members] = met.unknowns

    # the first member: from the bundled file's own metrics to the requirements in steps (a homotopy)
    first = len(cranks) // 2
    start = np.array([base[p] for p in paths[1:4]] + [0.0])
    own = evaluate(
        mech,
        paths,
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
    cols = evaluate(mech, paths, values, parse_metrics([*targets, *metrics], mech), VERIFY_STEPS)
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
    upper, lower = bundled().strokes
    targets = {"working_time_ratio": time_ratio, upper: upper_stroke, lower: lower_stroke, "knife_overlap": overlap}
    # the knives' strokes grow with the rocker's swing, nearly as the crank: the family is centred there
    guess = base[bundled().paths[0]] * max(upper_stroke / _own(mech, upper), lower_stroke / _own(mech, lower))
    cranks = np.array([crank]) if crank is not None else guess * np.geomspace(*SPAN, MEMBERS)
    unknowns, found = family(mech, targets, cranks, [m for m, _, _ in CRITERIA.values()])
    return cranks, unknowns, found


def member_values(cranks: np.ndarray, unknowns: np.ndarray) -> list[dict[str, float]]:
    """The values of the :func:`bundled` paths (SI) of the members ``cranks`` with their ``unknowns``: edits of the
    bundled file, or of a file synthesised from it."""
    from linkwork.api import mechanism_of
    from linkwork.structure.parameters import parameter_values

    base = parameter_values(mechanism_of(KIND, "mechanism"))
    rows = _values(base, cranks)(unknowns, np.arange(len(cranks)))
    return [dict(zip(bundled().paths, row.tolist(), strict=True)) for row in rows]


def _last_solved(unknowns: np.ndarray, chain: list[int]) -> np.ndarray:
    """The unknowns of the last solved member of ``chain``."""
    return next(unknowns[i] for i in reversed(chain) if not np.isnan(unknowns[i, 0]))


def synthesize(asked: ShearsRequirements) -> Synthesis:
    """The bundled double-cut shears with the upper and lower knives' strokes (m), the time ratio K (the knives closing
    over opening), and the overlap when closed or the opening (m); ``crank`` (m) fixes the family's free crank length,
    else the member is picked by ``criterion`` (``"pressure"``: the least largest pressure angle, the greatest least
    transmission angle; ``"torque"``: the least peak driving torque under the file's cutting load).  ``speed`` replaces
    the file's crank speed.  Verified by the analysis of the written file.  ``asked``: the requirements, SI."""
    upper_stroke, lower_stroke, time_ratio = asked.upper_stroke, asked.lower_stroke, asked.time_ratio
    overlap, opening, crank, criterion = asked.overlap, asked.opening, asked.crank, asked.criterion
    min_transmission_angle, speed = asked.min_transmission_angle, asked.speed
    from linkwork.api import mechanism_of

    want = _requirements(upper_stroke, lower_stroke, time_ratio, overlap, opening)
    floor = least_allowed(min_transmission_angle)
    if criterion not in CRITERIA:
        raise SynthesisError(f"criterion {criterion!r}: expected one of {', '.join(CRITERIA)}")
    if crank is not None and not 0 < crank < math.inf:
        raise SynthesisError(f"crank {crank!r} m: expected a positive length")
    mech = mechanism_of(KIND, "mechanism")
    _billet_fits(mech, upper_stroke + lower_stroke - want)
    cranks, unknowns, found = solved_family(upper_stroke, lower_stroke, time_ratio, want, crank)
    requirements = given(
        upper_stroke=upper_stroke,
        lower_stroke=lower_stroke,
        time_ratio=time_ratio,
        overlap=overlap,
        opening=opening,
        crank=crank,
        min_transmission_angle=floor,
    )
    _keeps_rule(found, cranks, floor)
    if criterion == "torque":  # each member's own file: its billet where its knives meet it
        found["peak_driving_torque"] = _member_torques(mech, cranks, unknowns, requirements, want, speed)
    else:
        found.pop("peak_driving_torque", None)  # the metric's runs keep the bundled billet
    metric, sense, words = CRITERIA[criterion]
    score = sense * found.get(metric, np.full(len(cranks), np.nan))
    score[~(found.get("min_transmission_angle", np.full(len(cranks), np.nan)) >= floor)] = np.nan
    if not np.isfinite(score).any():
        raise SynthesisError(_infeasible(mech, upper_stroke, lower_stroke, time_ratio, want, crank))
    pick = int(np.nanargmin(score))
    (exact,) = member_values(cranks[[pick]], unknowns[[pick]])
    values = {path: rounded(v) for path, v in exact.items()}  # written to 0.1 mm, as a drawing dimensions them
    names = bundled()
    why = f"crank {values[names.paths[0]] * 1e3:.6g} mm as given" if crank is not None else f"picked by {words}"
    written = _file(mech, values, requirements, want, why, speed)
    predicted = {
        "upper_stroke": upper_stroke,
        "lower_stroke": lower_stroke,
        "time_ratio": time_ratio,
        "overlap": want,
        "opening": upper_stroke + lower_stroke - want,
    }
    got, tol = measure_written(written.mech, written.spec, knives, names.paths)
    measured = {key: got[key] for key in predicted}
    confirm(measured, predicted, tol)
    keep_rule(got["min_transmission_angle"], floor, tol["min_transmission_angle"])
    columns = {
        "crank": cranks,
        f"{names.pivot}.x": unknowns[:, 0],
        f"{names.arms[0]}.x": unknowns[:, 1],
        f"{names.arms[1]}.x": unknowns[:, 2],
        "edges_lengthened_by": unknowns[:, 3] / 2,
        **{m: found[m] for m, _, _ in CRITERIA.values() if m in found},
    }
    fam = None if crank is not None else Family("crank length", "m", cranks, columns, words)
    shown = ["crank", f"{names.pivot}.x", *(f"{arm}.x" for arm in names.arms), "upper_edge.y", "lower_edge.y"]
    dims = dict(zip(shown, values.values(), strict=True))
    notes = [f"{m}: {found[m][pick]:.6g}" for m, _, _ in CRITERIA.values() if m in found]
    if "peak_driving_torque" not in found:
        notes.append(f"peak_driving_torque: {_peak_torque(written.mech):.6g}")
    return Synthesis(
        KIND, requirements, dims, predicted, measured, written.spec, "", fam, why, notes, tol, tree=written.tree
    )


def _billet_fits(mech, opening: float) -> None:  # noqa: ANN001
    """Raise where the knives' opening is not over the height of the file's billet (a two-tool process load's
    workpiece): the billet would not enter between them."""
    for load in mech.loads:
        height = load.workpiece[1] - load.workpiece[0] if load.kind == "process" and len(load.points) == 2 else 0
        if opening <= height:
            raise SynthesisError(
                f"opening {opening * 1e3:.6g} mm: the billet of the file's load {load.name!r} is {height * 1e3:.4g} mm "
                "high and would not enter between the knives; ask for a larger opening (or a smaller overlap)"
            )


def _keeps_rule(found: dict[str, np.ndarray], cranks: np.ndarray, floor: float) -> None:
    """Raise where no solved member's least transmission angle (every dyad over the turn) reaches ``floor``."""
    least = found.get("min_transmission_angle", np.full(len(cranks), np.nan))
    if np.isfinite(least).any() and not np.nanmax(least) >= floor:
        i = int(np.nanargmax(least))
        raise below_rule(
            f"the family's best member (crank {cranks[i] * 1e3:.4g} mm)",
            float(least[i]),
            floor,
            "leave the crank free, its family's best may meet it"
            if len(cranks) == 1
            else "other strokes, K or overlap",
        )


def _peak_torque(mech) -> float:  # noqa: ANN001
    """The peak size of the driving torque (N m) of ``mech`` over the turn, refined between the samples."""
    from linkwork.api import forces
    from linkwork.kinetostatics.peaks import torque_peak

    return abs(float(torque_peak(forces(mech, steps=360)).value[0]))


def _member_torques(mech, cranks, unknowns, requirements: dict, want: float, speed: str | None) -> np.ndarray:  # noqa: ANN001
    """The peak driving torque (N m) of each solved member, each from its own file as it would be written
    (:func:`_file`: its lengths to 0.1 mm, its billet placed where its knives meet it); NaN for the members not
    solved."""
    out = np.full(len(cranks), np.nan)
    for i in np.flatnonzero(np.isfinite(unknowns[:, 0])):
        (values,) = member_values(cranks[[i]], unknowns[[i]])
        written = {path: rounded(v) for path, v in values.items()}  # as its file would be written
        out[i] = _peak_torque(_file(mech, written, requirements, want, "", speed).mech)
    return out


def _own(mech, metric: str) -> float:  # noqa: ANN001
    """A metric of the bundled file as it is."""
    from linkwork.design.evaluate import evaluate
    from linkwork.design.metrics import parse_metrics

    return float(evaluate(mech, [], np.zeros((1, 0)), parse_metrics([metric], mech), 360)[metric][0])


def _infeasible(mech, upper: float, lower: float, ratio: float, want: float, crank: float | None) -> str:  # noqa: ANN001
    upper_metric, lower_metric = bundled().strokes
    own = {m: _own(mech, m) for m in (upper_metric, lower_metric, "working_time_ratio", "knife_overlap")}
    where = f"with the crank {crank * 1e3:g} mm" if crank is not None else "for any crank length tried"
    return (
        f"upper stroke {upper * 1e3:g} mm, lower stroke {lower * 1e3:g} mm, time ratio K = {ratio:g} and overlap "
        f"{want * 1e3:g} mm: no double-cut shears of the bundled structure meet them together {where} (the "
        f"knives' rods cannot reach their guides, or the rocker's four-bar cannot give K); the bundled file has "
        f"{own[upper_metric] * 1e3:.4g} and {own[lower_metric] * 1e3:.4g} mm, K = "
        f"{own['working_time_ratio']:.4g} and {own['knife_overlap'] * 1e3:.4g} mm: ask for values nearer those"
    )


def confirm(measured: dict[str, float], predicted: dict[str, float], tolerances: dict[str, float]) -> None:
    """Raise where the written file measures a requirement away from it by more than its ``tolerances`` (SI: what
    the lengths written to 0.1 mm imply, :func:`~linkwork.synthesis.rounding.measure_written`)."""
    for key, wanted in predicted.items():
        if not abs(measured[key] - wanted) <= tolerances[key]:
            raise SynthesisError(
                f"{key.replace('_', ' ')}: the written shears measure {measured[key]!r}, expected {wanted!r} within "
                f"{tolerances[key]:.3g} (the lengths written to 0.1 mm)"
            )


def _file(mech, values: dict[str, float], requirements: dict, want: float, why: str, speed: str | None) -> Draft:  # noqa: ANN001
    """The :class:`~linkwork.synthesis.common.Draft` of the bundled file with ``values`` written in (the one
    writer's tree), its cutting load's workpiece placed where the new knives meet it, its hints and the comments
    that speak of the geometry or the speed regenerated, a comment beside each derived dimension."""
    from linkwork.spec.edit import round_trip_yaml
    from linkwork.structure.parameters import file_text

    data = round_trip_yaml().load(file_text(mech, values))
    k, up, low = requirements["time_ratio"], requirements["upper_stroke"], requirements["lower_stroke"]
    data["description"] = (
        f"Double-cut shears of the bundled structure (seed 002) synthesised for the knives' strokes "
        f"{up * 1e3:.6g} mm (upper) and {low * 1e3:.6g} mm (lower), overlap {want * 1e3:.6g} mm when closed "
        f"(opening {(up + low - want) * 1e3:.6g} mm) and time ratio K = {k:.6g} (closing over opening); the "
        f"crank's length {why}.  Masses, the cutting table and the motor as in the bundled file; the billet "
        "placed where the knives meet it.\n"
    )
    names = bundled()
    data["links"][names.crank].yaml_add_eol_comment(f"# the family's free length: {why}", "length")
    data["frame"]["points"].yaml_add_eol_comment(f"# {names.pivot}.x: time ratio K = {k:.6g}", names.pivot)
    data["links"][names.rocker].yaml_add_eol_comment(
        f"# {names.arms[0]}.x: upper stroke {up * 1e3:.6g} mm; {names.arms[1]}.x: lower stroke {low * 1e3:.6g} mm",
        "points",
    )
    for knife in names.knives:
        data["links"][knife].yaml_add_eol_comment(f"# edge: overlap {want * 1e3:.6g} mm when closed", "points")
    if speed is not None:
        data["drives"][0]["speed"] = speed
    geometry = draft(data)  # before the billets, hints and comments that follow from it
    _regenerate(data, geometry.spec, geometry.mech)
    return draft(data)


def _regenerate(data, spec, mech) -> None:  # noqa: ANN001
    """Write into ``data`` what follows from the new geometry of ``spec`` (the same file, compiled: ``mech``): each
    two-tool process load's workpiece where both tools touch it at once (:func:`billets`), the hints at the assembly
    pose, and the comments on the work a cut, the speed and the drawing."""
    from linkwork.api import kinematics

    unit = _length_unit(data)
    placed = billets(mech)
    for load in mech.loads:
        if load.kind == "process" and len(load.points) == 2 and load.name not in placed:
            raise SynthesisError(
                f"the knives never open to the height of the billet of load {load.name!r}, "
                f"{(load.workpiece[1] - load.workpiece[0]) * 1e3:.4g} mm: ask for an opening of at least that"
            )
    for name, (lo, hi, work) in placed.items():
        load = data["loads"][name]
        low = _rounded(lo / unit)
        load["workpiece"][0], load["workpiece"][1] = low, round(low + (hi - lo) / unit, 12)
        _recomment(
            load,
            "workpiece",
            f"billet of height h = {(hi - lo) * 1e3:.4g} mm where both knives touch it at once (closing); "
            f"{work / 1e3:.4g} kJ a cut",
        )
    pose = kinematics(mech, np.array([float(mech.drive_start[0])]))
    for point in list(data.get("hints") or {}):
        x, y = np.ravel(pose.position(point))
        data["hints"][point] = _flow([_rounded(x / unit), _rounded(y / unit)])
    _machine_comments(data, spec, mech, sum(w for _, _, w in placed.values()))
    if "drawing" in data:
        _recomment(data, "drawing", "the plans of velocities and accelerations for these positions")


def billets(mech) -> dict[str, tuple[float, float, float]]:  # noqa: ANN001
    """Each process load with two tools: (low, high) of its workpiece (m, along its axis, its height kept) placed
    so that both tools touch it at the same crank angle on the closing stroke (where their gap equals the
    height), and the work of its table a cut (J): the height times the table's integral over the penetration the
    tools reach.  With the tools entering one after the other, the one not yet in the work would be pushed by
    the load (the penetration counts each tool from its own face)."""
    from scipy.optimize import brentq

    from linkwork.api import kinematics

    out = {}
    kin = kinematics(mech, steps=VERIFY_STEPS)
    angles = np.ravel(kin.angles)
    for load in mech.loads:
        if load.kind != "process" or len(load.points) != 2:
            continue
        u, names = np.asarray(load.vector), [mech.point_names[p] for p in load.points]
        height = load.workpiece[1] - load.workpiece[0]

        def gap(k, names=names, u=u) -> np.ndarray:  # noqa: ANN001
            return np.reshape((k.position(names[0]) - k.position(names[1])) @ u, -1)

        g = gap(kin)
        closing = np.reshape((kin.velocity(names[1]) - kin.velocity(names[0])) @ u, -1) > 0
        nxt = np.roll(np.arange(len(g)), -1)
        (hits,) = np.nonzero(((g - height) * (g[nxt] - height) <= 0) & closing & closing[nxt])
        if not len(hits):
            continue
        i = int(hits[0])
        a, b = angles[i], angles[i] + (angles[nxt[i]] - angles[i]) % (2 * np.pi)
        at = brentq(lambda x, h=height: float(gap(kinematics(mech, np.array([x])))[0]) - h, a, b, xtol=1e-13)
        low = float(np.ravel(kinematics(mech, np.array([at])).position(names[1]) @ u)[0])
        reach = min((height - float(np.min(g))) / height, float(load.table[0][-1]))
        eps = np.linspace(0.0, reach, 20001)
        out[load.name] = (low, low + height, height * float(np.trapezoid(np.interp(eps, *load.table), eps)))
    return out


def _machine_comments(data, spec, mech, work: float) -> None:  # noqa: ANN001
    """The machine's comments regenerated from the file: the cuts a minute, the work and mean power a cut (the
    process loads' :func:`billets` work), the gear's speeds (its ratio from the motor's speed to the crank's
    where ``--speed`` changed the crank's)."""
    machine = data.get("machine")
    if machine is None or spec.machine is None:
        return
    per_minute = abs(float(mech.drive_speed[0])) * 60 / (2 * math.pi)
    gear = spec.machine.gear
    motor = float(spec.machine.motor.speed) * 60 / (2 * math.pi)
    if gear is not None and "gear" in machine and "motor" not in machine:
        ratio = float(f"{motor / per_minute:.4g}")
        if abs(ratio - gear.ratio) > 1e-3 * gear.ratio:
            machine["gear"]["ratio"] = ratio
        _recomment(machine, "gear", f"{motor:.4g} rpm -> {per_minute:.4g} rpm")
    _recomment(data, "machine", f"the drive, for machine dynamics: {per_minute:.4g} cuts a minute")
    if "motor" in machine:
        power = work * per_minute / 60
        efficiency = gear.efficiency if gear is not None else 1.0
        name = _motor(machine, spec, power / efficiency)
        if gear is not None and "gear" in machine and "speed" in machine["motor"]:  # from the motor's rated speed
            from linkwork.units import parse_quantity

            speed = parse_quantity(machine["motor"]["speed"], "angular_speed")
            machine["gear"]["ratio"] = float(f"{speed * 60 / (2 * math.pi) / per_minute:.4g}")
            _recomment(machine, "gear", f"{speed * 60 / (2 * math.pi):.4g} rpm -> {per_minute:.4g} rpm")
        _recomment(
            machine,
            "motor",
            f"mean power at the crank {power / 1e3:.3g} kW ({work / 1e3:.3g} kJ a cut), "
            f"{power / efficiency / 1e3:.3g} kW at the motor; x {SERVICE:g} (service factor) = "
            f"{SERVICE * power / efficiency / 1e3:.3g} kW: {name}",
        )


#: The service factor of the shears' motor over the mean power at its shaft: a motor rated at least this many
#: times the mean (the moderate shocks of a machine whose flywheel takes the cut's peak; the motor's heating and
#: breakdown torque are then checked by ``linkwork size``, which runs the machine with it).
SERVICE = 1.25


def _motor(machine, spec, need: float) -> str:  # noqa: ANN001
    """Write into ``machine`` (the file's ``machine:``) the motor rated at least :data:`SERVICE` x ``need`` (W):
    the file's own where its rating is the catalogue's least that does (its data kept), else the bundled
    catalogue's least of the file's synchronous speed (its rated power, speed, breakdown ratio and rotor); says
    which."""
    from linkwork.sizing.motor import motor_catalogue

    cat, own = motor_catalogue(), spec.machine.motor
    if own.type != "induction" or own.power is None:
        return f"the file's {own.type} motor"
    cols = cat.columns
    same = np.isclose(cols["synchronous"], float(own.synchronous or cols["synchronous"][0]), rtol=1e-3)
    fits = np.flatnonzero(same & (cols["power"] >= SERVICE * need))
    if not len(fits):
        raise SynthesisError(
            f"the knives' cut needs {need / 1e3:.3g} kW at the motor, x {SERVICE:g} = {SERVICE * need / 1e3:.3g} kW: "
            f"more than the largest motor of the catalogue {cat.source} of its synchronous speed; ask for a lower "
            "--speed"
        )
    i = int(fits[np.argmin(cols["power"][fits])])
    row = cat.row(i)
    if math.isclose(row["power"], float(own.power), rel_tol=1e-6):
        return f"the file's {own.power / 1e3:g} kW motor, the least of the catalogue that covers it"
    motor = machine["motor"]
    motor["power"] = f"{row['power'] / 1e3:g} kW"
    motor["speed"] = f"{row['speed'] * 60 / (2 * math.pi):.6g} rpm"
    motor["breakdown"] = float(f"{row['breakdown']:.6g}")
    if "inertia" in motor:
        motor["inertia"] = f"{row['inertia']:.6g} kg*m^2"
        _recomment(motor, "inertia", "rotor, from the catalogue")
    return f"the catalogue's {cat.names[i]} ({cat.source})"


def _recomment(node, key: str, text: str) -> None:  # noqa: ANN001
    """Replace the end-of-line comment of ``key`` in ``node`` (a ruamel mapping) with ``text``."""
    node.ca.items.pop(key, None)
    node.yaml_add_eol_comment(f"# {text}", key)


def _flow(values: list[float]) -> Any:
    """``values`` as a YAML sequence written on one line."""
    from ruamel.yaml.comments import CommentedSeq

    seq = CommentedSeq(values)
    seq.fa.set_flow_style()
    return seq


def _length_unit(data) -> float:  # noqa: ANN001
    """Metres in one of the file's length unit."""
    from linkwork.units import parse_quantity

    return float(parse_quantity(f"1 {(data.get('units') or {}).get('length', 'm')}", "length"))


def _rounded(x: float) -> float:
    """A length of the file in its unit to the digits the file writes (the shears' file is in metres: 0.1 mm)."""
    return round(float(x), 4) + 0.0
