"""The metrics of a design sweep: one number per variant, each vectorised over the variants.

A metric is asked for by name, some with an argument after a colon:
``stroke:guide_E`` (the slider of that prismatic joint), ``time_ratio:rocker``.
Every metric is computed over one whole turn of the crank, from arrays
``(n_variants, n_angles)``; a variant that does not assemble at every angle
gets NaN in every metric but ``assembles``.  Values are SI; :data:`METRICS`
gives each metric's unit.  The motion metrics (strokes, swings, time ratios,
transmission angles) are those of :mod:`linkwork.motion.analysis`, as the
report, the viewer and the command line give them.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from linkwork.design.evaluate import Evaluation
from linkwork.did_you_mean import suggest
from linkwork.errors import DesignError
from linkwork.kinetostatics.peaks import foundation_peak, torque_peak
from linkwork.motion.analysis import (
    Output,
    Range,
    find_output,
    output_range,
    outputs,
    sampled_range,
    slopes,
    transmission,
)
from linkwork.motion.groups import KINDS, TRANSMISSION
from linkwork.structure.model import Mechanism, one_crank
from linkwork.structure.records import ExternalLoad


@dataclass(frozen=True)
class Metric:
    """One metric of the registry.

    Attributes
    ----------
    name : str
    unit : str
        SI unit of its values (``"1"`` for ratios and flags).
    kind : str or None
        Kind of quantity (:data:`linkwork.units.KINDS`) in which a constraint's bound is read; None: a pure number.
    forces : bool
        Whether it needs the kinetostatics (reactions), not only the kinematics.
    compute : callable
        ``compute(ev, arg) -> ndarray (V,)`` over an :class:`~linkwork.design.evaluate.Evaluation`.
    applies : callable
        ``applies(mech, arg) -> str or None``: why the metric does not apply to a mechanism, or None.
    doc : str
    """

    name: str
    unit: str
    kind: str | None
    forces: bool
    compute: Callable[[Evaluation, str | None], np.ndarray]
    applies: Callable[[Mechanism, str | None], str | None]
    doc: str


def _output(mech: Mechanism, arg: str | None, kind: str) -> Output | str:
    """The slider (its prismatic joint ``arg``) or rocker (its link ``arg``), or the first; a message if none."""
    found = find_output(mech, arg, kind)
    if found is not None:
        return found
    names = [out.name for out in outputs(mech) if out.kind == kind]
    if arg is None:
        return (
            "the mechanism has no slider on a frame guide"
            if kind == "slider"
            else "the mechanism has no link pivoted on the frame besides the crank"
        )
    if kind == "slider":
        return f'no slider on a frame guide in joint "{arg}"{suggest(arg, names)}' + (
            f"; the sliders' joints are: {', '.join(names)}" if names else ""
        )
    return f'no link "{arg}" pivoted on the frame{suggest(arg, names)}' + (
        f"; they are: {', '.join(names)}" if names else ""
    )


def _one_revolute_drive(mech: Mechanism) -> str | None:
    return None if one_crank(mech) else "it needs one revolute drive turning a whole cycle"


# ---------------------------------------------------------------- strokes, swings, time ratios


def _range(ev: Evaluation, arg: str | None, kind: str) -> Range:
    out = _output(ev.kin.mechanism, arg, kind)
    assert isinstance(out, Output)  # parse_metrics refused the metric otherwise
    return output_range(ev.kin, out)


def _either(ev: Evaluation, arg: str | None) -> Range:
    """The range of the slider ``arg`` (a prismatic joint), else of the rocker ``arg``; default the first slider,
    else the first rocker."""
    mech = ev.kin.mechanism
    slider = find_output(mech, arg, "slider")
    return output_range(ev.kin, slider) if slider is not None else _range(ev, arg, "rocker")


def _stroke(ev: Evaluation, arg: str | None) -> np.ndarray:
    return _range(ev, arg, "slider").stroke


def _swing(ev: Evaluation, arg: str | None) -> np.ndarray:
    return _range(ev, arg, "rocker").stroke


def _time_ratio(ev: Evaluation, arg: str | None) -> np.ndarray:
    return _either(ev, arg).time_ratio


def _forward_time_ratio(ev: Evaluation, arg: str | None) -> np.ndarray:
    return _either(ev, arg).forward_time_ratio


def _applies(kind: str) -> Callable[[Mechanism, str | None], str | None]:
    def applies(mech: Mechanism, arg: str | None) -> str | None:
        out = _output(mech, arg, kind)
        return out if isinstance(out, str) else _one_revolute_drive(mech)

    return applies


def _applies_time_ratio(mech: Mechanism, arg: str | None) -> str | None:
    if find_output(mech, arg, "slider") is not None or (arg is not None and arg in mech.pair_joint):
        return _applies("slider")(mech, arg)
    if arg is None and find_output(mech, None, "rocker") is None:
        return "the mechanism has no slider on a frame guide and no rocker"
    return _applies("rocker")(mech, arg)


# ---------------------------------------------------------------- transmission


def _min_transmission(ev: Evaluation, arg: str | None) -> np.ndarray:
    angles = np.stack(list(transmission(ev.kin).values()))  # (dyads, V, A)
    return np.min(angles, axis=(0, 2))


def _applies_transmission(mech: Mechanism, arg: str | None) -> str | None:
    if any(KINDS[step.kind].transmission for step in mech.program):
        return None
    return f"the mechanism has no dyad solved in closed form ({', '.join(TRANSMISSION)})"


# ---------------------------------------------------------------- forces


def _peak_torque(ev: Evaluation, arg: str | None) -> np.ndarray:
    """The largest size of the driving torque, refined between the samples (:func:`linkwork.kinetostatics.torque_peak`,
    as every route gives it)."""
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        return np.abs(torque_peak(ev.forces).value)


def _peak_foundation(ev: Evaluation, arg: str | None) -> np.ndarray:
    """The largest size of the force on the foundation, refined between the samples."""
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        return foundation_peak(ev.forces).value


def _applies_forces(mech: Mechanism, arg: str | None) -> str | None:
    if mech.structure.redundant:
        return "the mechanism has redundant constraints: its reactions are statically indeterminate"
    if mech.n_drives != 1:
        return "it needs a mechanism with one drive"
    return _one_revolute_drive(mech)


# ---------------------------------------------------------------- knives


def _knives(mech: Mechanism, arg: str | None) -> ExternalLoad | str:
    """The process load with two tools (named ``arg``, or the first); a message if there is none."""
    loads = [load for load in mech.loads if load.kind == "process" and len(load.points) == 2]
    if arg is not None:
        loads = [load for load in loads if load.name == arg]
    if not loads:
        what = f' named "{arg}"' if arg is not None else ""
        return f"the mechanism has no process load with two tools (knives){what}"
    return loads[0]


def _gap(ev: Evaluation, arg: str | None) -> Range:
    """Extremes of the gap between the two tools along the load's axis (positive while open), m."""
    kin = ev.kin
    load = _knives(kin.mechanism, arg)
    assert isinstance(load, ExternalLoad)  # parse_metrics refused the metric otherwise
    one, two = (kin.motion_of(kin.mechanism.point_names[p]) for p in load.points[:2])
    gap, rate, accel = (np.sum((x1 - x2) * np.asarray(load.vector), axis=-1) for x1, x2 in zip(one, two, strict=True))
    return sampled_range(gap, kin.angles, slopes(kin, rate, accel))


def _overlap(ev: Evaluation, arg: str | None) -> np.ndarray:
    return -_gap(ev, arg).low


def _clearance(ev: Evaluation, arg: str | None) -> np.ndarray:
    return _gap(ev, arg).high


def _applies_knives(mech: Mechanism, arg: str | None) -> str | None:
    load = _knives(mech, arg)
    return load if isinstance(load, str) else None


def _working_ratio(ev: Evaluation, arg: str | None) -> np.ndarray:
    """Time of the working stroke (the tools closing: their gap falling) over that of the return stroke."""
    gap = _gap(ev, arg)
    with np.errstate(divide="ignore", invalid="ignore"):
        return gap.falling / gap.rising


def _applies_working_ratio(mech: Mechanism, arg: str | None) -> str | None:
    return _applies_knives(mech, arg) or _one_revolute_drive(mech)


def _assembles(ev: Evaluation, arg: str | None) -> np.ndarray:
    return ev.kin.valid_all.all(axis=1).astype(float)


def _always(mech: Mechanism, arg: str | None) -> str | None:
    return None


METRICS: dict[str, Metric] = {
    m.name: m
    for m in (
        Metric(
            "assembles",
            "1",
            None,
            False,
            _assembles,
            _always,
            "1 where the mechanism assembles at every crank angle of the turn, else 0.",
        ),
        Metric(
            "stroke",
            "m",
            "length",
            False,
            _stroke,
            _applies("slider"),
            "Stroke of a slider on a frame guide (stroke:JOINT for its prismatic joint; default the first): "
            "the distance between its extreme positions along the guide, refined between samples.",
        ),
        Metric(
            "swing",
            "rad",
            "angle",
            False,
            _swing,
            _applies("rocker"),
            "Swing of a link pivoted on the frame (swing:LINK; default the first besides the crank).",
        ),
        Metric(
            "time_ratio",
            "1",
            None,
            False,
            _time_ratio,
            _applies_time_ratio,
            "Time ratio (coefficient K) of the strokes of a slider (time_ratio:JOINT) or a rocker "
            "(time_ratio:LINK; default the first slider, else the first rocker) at uniform crank speed: the "
            "longer stroke's time over the shorter's, >= 1, whatever the direction of rotation.",
        ),
        Metric(
            "forward_time_ratio",
            "1",
            None,
            False,
            _forward_time_ratio,
            _applies_time_ratio,
            "Directional time ratio of a slider (forward_time_ratio:JOINT) or a rocker (forward_time_ratio:LINK) "
            "at uniform crank speed in the drive's direction of rotation: the time of the stroke in which the "
            "slider moves in the + direction of its guide's axis (the rocker turns counter-clockwise) over the "
            "time of the other stroke; below 1 where that stroke is the faster one, its reciprocal when the "
            "crank turns the other way.",
        ),
        Metric(
            "working_time_ratio",
            "1",
            None,
            False,
            _working_ratio,
            _applies_working_ratio,
            "Time ratio of a machine with a process load on two tools (working_time_ratio:LOAD): the time of "
            "the working stroke (the tools closing, their gap along the load's axis falling) over the time of "
            "the return stroke (the tools opening), at uniform crank speed in the drive's direction.",
        ),
        Metric(
            "min_transmission_angle",
            "rad",
            "angle",
            False,
            _min_transmission,
            _applies_transmission,
            "Smallest transmission angle of all closed-form dyads over the turn, in [0, pi/2] "
            "(see linkwork.motion.analysis.transmission): the smallest sampled value, not refined "
            "between samples (more steps for a finer one).",
        ),
        Metric(
            "peak_driving_torque",
            "N*m",
            "moment",
            True,
            _peak_torque,
            _applies_forces,
            "Largest absolute driving torque on the crank over the turn, at the file's crank speed, "
            "with gravity, inertia and the file's loads; refined between the samples (the same whatever the steps).",
        ),
        Metric(
            "peak_foundation_force",
            "N",
            "force",
            True,
            _peak_foundation,
            _applies_forces,
            "Largest magnitude of the force the machine puts on its foundation over the turn "
            "(the weights, the frame's included, inertia and loads); refined between the samples.",
        ),
        Metric(
            "knife_overlap",
            "m",
            "length",
            False,
            _overlap,
            _applies_knives,
            "How far the blade edges pass each other when the knives are closed: the largest overlap of the two "
            "tools of a process load along its axis (knife_overlap:LOAD); negative if they never meet.",
        ),
        Metric(
            "knife_clearance",
            "m",
            "length",
            False,
            _clearance,
            _applies_knives,
            "The largest gap between the blade edges over the turn (the knives fully open), along the axis of "
            "the process load: what the workpiece must pass through (knife_clearance:LOAD).",
        ),
    )
}


@dataclass(frozen=True)
class MetricRequest:
    """A metric asked for: its column name (as written), the metric and its argument."""

    column: str
    metric: Metric
    arg: str | None


def parse_metrics(names: list[str], mech: Mechanism) -> list[MetricRequest]:
    """Read metric names (``NAME`` or ``NAME:ARG``); raises DesignError listing every problem."""
    problems: list[str] = []
    out: list[MetricRequest] = []
    for text in names:
        name, _, arg = text.partition(":")
        metric = METRICS.get(name)
        if metric is None:
            problems.append(f'metric "{name}": unknown{suggest(name, METRICS)}; the metrics are: {", ".join(METRICS)}')
            continue
        why = metric.applies(mech, arg or None)
        if why:
            problems.append(f'metric "{text}" does not apply to {mech.name}: {why}')
            continue
        if any(r.column == text for r in out):
            continue
        out.append(MetricRequest(text, metric, arg or None))
    if not names:
        problems.append(f"give at least one --metric; the metrics are: {', '.join(METRICS)}")
    if problems:
        raise DesignError(problems)
    return out
