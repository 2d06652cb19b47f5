"""What happens along the cycle: no assembly, singular (dead-point) positions."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from linkwork.motion.groups import KINDS
from linkwork.motion.state import Flip, Jump, State, StepRecord
from linkwork.structure.records import Step
from linkwork.units import turn_deg


@dataclass(frozen=True)
class Event:
    """Something an engineer must know about a range of crank angles.

    Attributes
    ----------
    kind : str
        ``"no-assembly"`` (a range), ``"dead-point"`` (a limit of such a
        range), ``"singular"`` (the group's Jacobian is singular inside the
        assembled range), ``"change-point"`` (the two assembly modes meet
        and the motion goes on in the other one) or ``"branch-jump"`` (a
        group solved by Newton's method jumps between two samples).
    group : str
        The group, e.g. ``II(4,5) RRP``.
    start, end : float
        Drive coordinates (rad or m) of the range; equal for a single position.
    variant : int
        Design-variant index.
    message : str
    """

    kind: str
    group: str
    start: float
    end: float
    variant: int
    message: str

    def as_dict(self) -> dict[str, Any]:
        return {
            "kind": self.kind,
            "group": self.group,
            "start_deg": math.degrees(self.start),
            "end_deg": math.degrees(self.end),
            "variant": self.variant,
            "message": self.message,
        }


def runs(mask: np.ndarray) -> list[tuple[int, int]]:
    """Index ranges [i, j] of consecutive True entries of ``mask`` ``(A,)``."""
    if not mask.any():
        return []
    d = np.diff(np.concatenate([[0], mask.astype(int), [0]]))
    return [(int(i), int(j)) for i, j in zip(np.flatnonzero(d == 1), np.flatnonzero(d == -1) - 1, strict=True)]


class _Scale:
    """How drive coordinates are written in messages: degrees of a turn to the x axis (a revolute drive; φ
    from position 0 is not known here: finding it solves the cycle) or metres."""

    def __init__(self, revolute: bool) -> None:
        self.revolute = revolute
        self.unit = "deg to the x axis" if revolute else "m"

    def show(self, x: float) -> str:
        return f"{turn_deg(x):.1f}" if self.revolute else f"{x:.4g}"


def find(
    steps: tuple[Step, ...],
    state: State,
    angles: np.ndarray,
    revolute: bool,
    max_variants: int = 20,
    within: tuple[int, int] | None = None,
) -> list[Event]:
    """Events of every step for the first ``max_variants`` variants.

    ``angles`` is the drive coordinate of drive 0 at each sample, in the order given.  ``within``:
    the first and last sample to look at (the span of the angles asked for, in a path that reaches
    them from the assembly pose), so that no event is reported outside it; default all.
    """
    if state.quiet and not any(r.jumps or r.flips for r in state.steps):
        return []  # the compiled kernels saw every step assemble everywhere, away from singular positions
    records, valid = state.steps, state.valid
    if within is not None:
        lo, hi = within
        records = [r.window(lo, hi) for r in records]
        valid, angles = valid[:, lo : hi + 1], angles[lo : hi + 1]
    n_var = min(valid.shape[0], max_variants)
    trouble = state.step_trouble
    if trouble is not None and not trouble[:, :n_var].any() and not any(r.jumps or r.flips for r in records):
        return []  # the compiled kernels saw every step assemble everywhere, away from singular positions
    events: list[Event] = []
    scale = _Scale(revolute)
    before = np.ones(valid.shape, dtype=bool)
    for k, (step, record) in enumerate(zip(steps, records, strict=True)):
        if KINDS[step.kind].driving:
            continue  # a driving link always assembles and is never singular
        if trouble is not None and not trouble[k, :n_var].any() and not (record.jumps or record.flips):
            continue  # the compiled kernel saw it assemble everywhere, away from singular positions
        fails = before & ~record.valid
        if not _quiet(record, fails, n_var):
            for v in range(n_var):
                tag = f" (variant {v})" if valid.shape[0] > 1 else ""
                at = _Events(step.label, v, angles, scale, tag)
                at.no_assembly(fails[v], before[v], record.slack[v])
                at.singular(np.where(before[v] & record.valid[v], record.det[v], np.nan))
                at.jumps([j for j in record.jumps if j.variant == v])
                at.change_points([f for f in record.flips if f.variant == v])
                events += at.found
        before &= record.valid
    return events


def _quiet(record: StepRecord, fails: np.ndarray, n_var: int) -> bool:
    """Whether a step has nothing to report for the first ``n_var`` variants: it assembles wherever the
    steps before it do, has no jumps or change points, and its determinant neither comes near zero
    nor changes sign."""
    head = record.det[:n_var]
    return not (
        fails[:n_var].any()
        or record.jumps
        or record.flips
        or (np.abs(head) < 1e-9).any()
        or (np.signbit(head[:, 1:]) != np.signbit(head[:, :-1])).any()
    )


def _limit(angles: np.ndarray, margin: np.ndarray, i: int, j: int) -> float:
    """Drive value where the assembly margin crosses zero between samples i (valid) and j:
    a parabola through i, j and the sample beyond i, else a straight line."""
    s0, s1 = margin[i], margin[j]
    if not (np.isfinite(s0) and np.isfinite(s1)) or s0 == s1:
        return float(angles[j])
    linear = float(angles[i] + s0 / (s0 - s1) * (angles[j] - angles[i]))
    k = i - (j - i)
    if 0 <= k < len(margin) and np.isfinite(margin[k]):
        x = np.array([angles[k], angles[i], angles[j]], dtype=float)
        c = np.polyfit(x - x[1], [margin[k], s0, s1], 2)
        roots = np.roots(c) + x[1] if np.any(c) else []
        lo, hi = sorted((float(angles[i]), float(angles[j])))
        inside = [float(r.real) for r in roots if abs(r.imag) < 1e-12 and lo <= r.real <= hi]
        if inside:
            return min(inside, key=lambda r: abs(r - linear))
    return linear


class _Events:
    """The events of one group of one variant along the samples at drive coordinates ``angles``."""

    def __init__(self, label: str, variant: int, angles: np.ndarray, scale: _Scale, tag: str) -> None:
        self.label, self.variant, self.angles, self.tag = label, variant, angles, tag
        self.show, self.unit = scale.show, scale.unit
        self.found: list[Event] = []

    def add(self, kind: str, start: float, end: float, message: str) -> None:
        self.found.append(Event(kind, self.label, start, end, self.variant, f"group {self.label}: {message}{self.tag}"))

    def no_assembly(self, fails: np.ndarray, before: np.ndarray, margin: np.ndarray) -> None:
        """Ranges where the group does not assemble though the groups before it do (``fails``), and the
        dead points at their ends inside the samples, refined by the assembly ``margin``."""
        angles, n, show, unit = self.angles, len(self.angles), self.show, self.unit
        for i, j in runs(fails):
            a = _limit(angles, margin, i - 1, i) if i > 0 and before[i - 1] else float(angles[i])
            b = _limit(angles, margin, j + 1, j) if j + 1 < n and before[j + 1] else float(angles[j])
            span = f"{show(a)} {unit}" if i == j else f"{show(a)} to {show(b)} {unit}"
            which = "angle" if i == j else "angles"
            self.add("no-assembly", a, b, f"no assembly (no intersection) for crank {which} {span}")
            for x, inside in ((a, i > 0), (b, j + 1 < n)):
                if inside:
                    self.add("dead-point", x, x, f"limit (dead) position near crank angle {show(x)} {unit}")

    def singular(self, d: np.ndarray) -> None:
        """Singular positions: where the determinant ``d`` (NaN where the group is not assembled) changes
        sign between samples, and samples where it is zero to rounding."""
        angles = self.angles
        zero = np.flatnonzero(np.abs(d) < 1e-9)
        cross = np.flatnonzero(np.isfinite(d[:-1]) & np.isfinite(d[1:]) & (np.sign(d[:-1]) * np.sign(d[1:]) < 0))
        cross = cross[~np.isin(cross, zero) & ~np.isin(cross + 1, zero)]
        for i in cross:
            t = d[i] / (d[i] - d[i + 1])
            x = angles[i] + t * (angles[i + 1] - angles[i])
            self.add("singular", x, x, f"singular position (dead point) near crank angle {self.show(x)} {self.unit}")
        for i in zero:
            x = angles[i]
            self.add("singular", x, x, f"singular position (dead point) at crank angle {self.show(x)} {self.unit}")

    def jumps(self, jumps: list[Jump]) -> None:
        """Jumps of a Newton-solved group between samples."""
        angles, show = self.angles, self.show
        for _, j in jumps:
            self.add(
                "branch-jump",
                angles[j],
                angles[j + 1],
                f"the solution jumps between crank angles {show(angles[j])} and {show(angles[j + 1])} "
                f"{self.unit}: it may have changed assembly mode there; check with finer steps",
            )

    def change_points(self, flips: list[Flip]) -> None:
        """Change points the motion was followed through."""
        for _, _, i in flips:
            x = self.angles[i]
            self.add(
                "change-point",
                x,
                x,
                f"its two assembly modes meet near crank angle {self.show(x)} {self.unit}; the motion goes "
                "on smoothly in the other mode",
            )
