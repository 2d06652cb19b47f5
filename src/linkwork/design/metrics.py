"""The metrics of a design sweep: one number per variant, each vectorised over the variants.

A metric is asked for by name, some with an argument after a colon:
``stroke:guide_E`` (the slider of that prismatic joint), ``time_ratio:rocker``.
Every metric is computed over one whole turn of the crank, from arrays
``(n_variants, n_angles)``; a variant that does not assemble at every angle
gets NaN in every metric but ``assembles``.  Values are SI; :data:`METRICS`
gives each metric's unit.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from linkwork.structure.constraints import PRISMATIC, REVOLUTE


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
    compute: Callable[[Any, str | None], np.ndarray]
    applies: Callable[[Any, str | None], str | None]
    doc: str


def _frame_sliders(mech: Any) -> list[int]:
    """Prismatic pairs whose guide is the frame (the drive excluded), in pair order."""
    driven = {int(k) for k in mech.drive_pair}
    return [
        k
        for k in range(mech.n_pairs)
        if mech.pair_type[k] == PRISMATIC and int(mech.pair_links[k, 0]) == 0 and k not in driven
        and not mech.link_virtual[int(mech.pair_links[k, 1])]
    ]  # fmt: skip


def _frame_rockers(mech: Any) -> list[int]:
    """Links pivoted on the frame by a revolute pair that is not driven (candidates for rockers)."""
    driven = {int(k) for k in mech.drive_pair}
    driven_links = {int(mech.pair_links[k, 1]) for k in driven}
    out = []
    for k in range(mech.n_pairs):
        b = int(mech.pair_links[k, 1])
        if mech.pair_type[k] == REVOLUTE and int(mech.pair_links[k, 0]) == 0 and k not in driven:
            if b not in driven_links and not mech.link_virtual[b] and b not in out:
                out.append(b)
    return out


def _slider(mech: Any, arg: str | None) -> int | str:
    """The pair of the slider ``arg`` names (a prismatic joint), or the first; a message if there is none."""
    sliders = _frame_sliders(mech)
    if arg is None:
        return sliders[0] if sliders else "the mechanism has no slider on a frame guide"
    for k in sliders:
        if mech.pair_joint[k] == arg:
            return k
    from linkwork.spec.checks import suggest

    names = [mech.pair_joint[k] for k in sliders]
    return f'no slider on a frame guide in joint "{arg}"{suggest(arg, names)}' + (
        f"; the sliders' joints are: {', '.join(names)}" if names else ""
    )


def _rocker(mech: Any, arg: str | None) -> int | str:
    rockers = _frame_rockers(mech)
    if arg is None:
        return rockers[0] if rockers else "the mechanism has no link pivoted on the frame besides the crank"
    names = [mech.link_names[b] for b in rockers]
    if arg in names:
        return rockers[names.index(arg)]
    from linkwork.spec.checks import suggest

    return f'no link "{arg}" pivoted on the frame{suggest(arg, names)}' + (
        f"; they are: {', '.join(names)}" if names else ""
    )


def _one_revolute_drive(mech: Any) -> str | None:
    if mech.n_drives != 1 or mech.pair_type[mech.drive_pair[0]] != REVOLUTE:
        return "it needs one revolute drive turning a whole cycle"
    return None


# ---------------------------------------------------------------- extremes, vectorised


def _peak(values: np.ndarray, angles: np.ndarray, lowest: bool) -> tuple[np.ndarray, np.ndarray]:
    """Extreme of periodic samples ``(V, A)`` over a uniform turn, refined by a parabola through the
    extreme sample and its two neighbours: the value and the drive angle, ``(V,)`` each."""
    y = -values if lowest else values
    n = y.shape[1]
    filled = np.where(np.isfinite(y), y, -np.inf)
    i = np.argmax(filled, axis=1)
    rows = np.arange(y.shape[0])
    y0, y1, y2 = y[rows, (i - 1) % n], y[rows, i], y[rows, (i + 1) % n]
    den = y0 - 2 * y1 + y2
    with np.errstate(invalid="ignore", divide="ignore"):
        t = np.where(den != 0, 0.5 * (y0 - y2) / den, 0.0)
    t = np.clip(np.nan_to_num(t), -1.0, 1.0)
    step = angles[1] - angles[0] if n > 1 else 0.0
    peak = y1 - 0.25 * (y0 - y2) * t
    at = angles[i] + t * step
    return (-peak if lowest else peak), at


def _stroke_values(ev: Any, k: int) -> np.ndarray:
    """Position of the slider of pair ``k`` along its guide (V, A), m."""
    mech = ev.kin.mechanism
    p = int(mech.pair_points[k, 1])
    x = ev.kin.position(mech.point_names[p])  # (V, A, 2)
    origin = ev.kin.origin[k, :, :, 0].T[:, None, :]  # (V, 1, 2)
    axis = ev.kin.axis[k, :, :, 0].T[:, None, :]
    return np.sum((x - origin) * axis, axis=-1)


def _rocker_values(ev: Any, b: int) -> np.ndarray:
    q = ev.kin.q[b, 2]  # (V, A)
    return np.unwrap(q, axis=1)


def _range(values: np.ndarray, angles: np.ndarray) -> np.ndarray:
    high, _ = _peak(values, angles, lowest=False)
    low, _ = _peak(values, angles, lowest=True)
    return high - low


def _rising(values: np.ndarray, angles: np.ndarray) -> np.ndarray:
    """Crank angle (in the drive's direction, rad) over which ``values`` rise from their lowest to their
    highest, ``(V,)``: the time of that stroke at uniform crank speed, times the speed."""
    _, at_high = _peak(values, angles, lowest=False)
    _, at_low = _peak(values, angles, lowest=True)
    sign = 1.0 if angles[1] > angles[0] else -1.0
    return (sign * (at_high - at_low)) % (2 * math.pi)


def _ratio(values: np.ndarray, angles: np.ndarray) -> np.ndarray:
    """Time of the stroke in which ``values`` rise over the time of the one in which they fall."""
    rise = _rising(values, angles)
    with np.errstate(divide="ignore"):
        return rise / (2 * math.pi - rise)


def _stroke(ev: Any, arg: str | None) -> np.ndarray:
    return _range(_stroke_values(ev, int(_slider(ev.kin.mechanism, arg))), ev.kin.angles)


def _swing(ev: Any, arg: str | None) -> np.ndarray:
    return _range(_rocker_values(ev, int(_rocker(ev.kin.mechanism, arg))), ev.kin.angles)


def _time_ratio(ev: Any, arg: str | None) -> np.ndarray:
    mech = ev.kin.mechanism
    k = _slider(mech, arg) if arg is None or arg in mech.pair_joint else "-"
    if isinstance(k, int):
        return _ratio(_stroke_values(ev, k), ev.kin.angles)
    b = _rocker(mech, arg)
    return _ratio(_rocker_values(ev, int(b)), ev.kin.angles)


def _applies_slider(mech: Any, arg: str | None) -> str | None:
    k = _slider(mech, arg)
    return k if isinstance(k, str) else _one_revolute_drive(mech)


def _applies_rocker(mech: Any, arg: str | None) -> str | None:
    b = _rocker(mech, arg)
    return b if isinstance(b, str) else _one_revolute_drive(mech)


def _applies_time_ratio(mech: Any, arg: str | None) -> str | None:
    if arg is not None and arg in mech.pair_joint:
        return _applies_slider(mech, arg)
    if arg is None and _frame_sliders(mech):
        return _one_revolute_drive(mech)
    if arg is None and not _frame_rockers(mech):
        return "the mechanism has no slider on a frame guide and no rocker"
    return _applies_rocker(mech, arg)


# ---------------------------------------------------------------- transmission


def _dyads(mech: Any) -> list[int]:
    return [i for i, step in enumerate(mech.program) if step.kind in ("RRR", "RRP", "PRP", "RPR")]


def _min_transmission(ev: Any, arg: str | None) -> np.ndarray:
    dets = [np.abs(ev.kin.step_det[i]) for i in _dyads(ev.kin.mechanism)]
    smallest = np.min(np.stack(dets), axis=0)  # (V, A)
    return np.arcsin(np.clip(np.min(smallest, axis=1), 0.0, 1.0))


def _applies_transmission(mech: Any, arg: str | None) -> str | None:
    return None if _dyads(mech) else "the mechanism has no dyad solved in closed form (RRR, RRP, PRP, RPR)"


# ---------------------------------------------------------------- forces


def _finite_max(values: np.ndarray) -> np.ndarray:
    """Largest finite value of each row ``(V, A) -> (V,)``; NaN for a row with none."""
    finite = np.isfinite(values)
    top = np.max(np.where(finite, values, -np.inf), axis=1)
    return np.where(finite.any(axis=1), top, np.nan)


def _peak_torque(ev: Any, arg: str | None) -> np.ndarray:
    return _finite_max(np.abs(ev.driving_torque))


def _peak_foundation(ev: Any, arg: str | None) -> np.ndarray:
    f = ev.foundation
    return _finite_max(np.hypot(f[..., 0], f[..., 1]))


def _applies_forces(mech: Any, arg: str | None) -> str | None:
    if mech.structure.redundant:
        return "the mechanism has redundant constraints: its reactions are statically indeterminate"
    if mech.n_drives != 1:
        return "it needs a mechanism with one drive"
    return _one_revolute_drive(mech)


# ---------------------------------------------------------------- knives


def _knives(mech: Any, arg: str | None) -> Any:
    """The process load with two tools (named ``arg``, or the first); a message if there is none."""
    loads = [load for load in mech.loads if load.kind == "process" and len(load.points) == 2]
    if arg is not None:
        loads = [load for load in loads if load.name == arg]
    if not loads:
        what = f' named "{arg}"' if arg is not None else ""
        return f"the mechanism has no process load with two tools (knives){what}"
    return loads[0]


def _gap(ev: Any, arg: str | None) -> np.ndarray:
    """Gap between the two tools along the load's axis (V, A), m: positive while open."""
    mech = ev.kin.mechanism
    load = _knives(mech, arg)
    p1 = ev.kin.position(mech.point_names[load.points[0]])
    p2 = ev.kin.position(mech.point_names[load.points[1]])
    return np.sum((p1 - p2) * np.asarray(load.vector), axis=-1)


def _overlap(ev: Any, arg: str | None) -> np.ndarray:
    return -_peak(_gap(ev, arg), ev.kin.angles, lowest=True)[0]


def _clearance(ev: Any, arg: str | None) -> np.ndarray:
    return _peak(_gap(ev, arg), ev.kin.angles, lowest=False)[0]


def _applies_knives(mech: Any, arg: str | None) -> str | None:
    load = _knives(mech, arg)
    return load if isinstance(load, str) else None


def _working_ratio(ev: Any, arg: str | None) -> np.ndarray:
    """Time of the working stroke (the tools closing: their gap falling) over that of the return stroke."""
    closing = 2 * math.pi - _rising(_gap(ev, arg), ev.kin.angles)
    with np.errstate(divide="ignore"):
        return closing / (2 * math.pi - closing)


def _applies_working_ratio(mech: Any, arg: str | None) -> str | None:
    return _applies_knives(mech, arg) or _one_revolute_drive(mech)


def _assembles(ev: Any, arg: str | None) -> np.ndarray:
    return ev.kin.valid_all.all(axis=1).astype(float)


def _always(mech: Any, arg: str | None) -> str | None:
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
            _applies_slider,
            "Stroke of a slider on a frame guide (stroke:JOINT for its prismatic joint; default the first): "
            "the distance between its extreme positions along the guide, refined between samples.",
        ),
        Metric(
            "swing",
            "rad",
            "angle",
            False,
            _swing,
            _applies_rocker,
            "Swing of a link pivoted on the frame (swing:LINK; default the first besides the crank).",
        ),
        Metric(
            "time_ratio",
            "1",
            None,
            False,
            _time_ratio,
            _applies_time_ratio,
            "Time ratio of the strokes of a slider (time_ratio:JOINT) or a rocker (time_ratio:LINK) at uniform "
            "crank speed, in the drive's direction of rotation: the time of the stroke in which the slider moves "
            "in the + direction of its guide's axis (the rocker turns counter-clockwise) over the time of the "
            "other stroke; below 1 where that stroke is the faster one.",
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
            "(see linkwork.motion.analysis.transmission_angles): the smallest sampled value, not refined "
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
            "with gravity, inertia and the file's loads.",
        ),
        Metric(
            "peak_foundation_force",
            "N",
            "force",
            True,
            _peak_foundation,
            _applies_forces,
            "Largest magnitude of the force the machine puts on its foundation over the turn "
            "(the weights, the frame's included, inertia and loads).",
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
    )  # fmt: skip
}


@dataclass(frozen=True)
class MetricRequest:
    """A metric asked for: its column name (as written), the metric and its argument."""

    column: str
    metric: Metric
    arg: str | None


def parse_metrics(names: list[str], mech: Any) -> list[MetricRequest]:
    """Read metric names (``NAME`` or ``NAME:ARG``); raises DesignError listing every problem."""
    from linkwork.design.plan import DesignError
    from linkwork.spec.checks import suggest

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
