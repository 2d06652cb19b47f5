"""What happens along the cycle: no assembly, singular (dead-point) positions."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np


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


def _runs(mask: np.ndarray) -> list[tuple[int, int]]:
    """Index ranges [i, j] of consecutive True entries."""
    if not mask.any():
        return []
    d = np.diff(np.concatenate([[0], mask.astype(int), [0]]))
    return list(zip(np.flatnonzero(d == 1), np.flatnonzero(d == -1) - 1, strict=True))


@dataclass
class _Window:
    """The samples ``lo`` to ``hi`` (inclusive) of a state's records of its steps."""

    step_valid: list[np.ndarray]
    step_det: list[np.ndarray]
    step_slack: list[np.ndarray]
    step_flips: list[list[tuple[int, int, int]]]
    step_jumps: list[list[tuple[int, int]]]
    step_trouble: np.ndarray | None
    valid: np.ndarray

    @classmethod
    def of(cls, state: Any, lo: int, hi: int) -> _Window:
        cut = slice(lo, hi + 1)
        return cls(
            [x[:, cut] for x in state.step_valid],
            [x[:, cut] for x in state.step_det],
            [x[:, cut] for x in state.step_slack],
            [[(v, j, i - lo) for v, j, i in f if lo <= i <= hi] for f in state.step_flips],
            [[(v, j - lo) for v, j in f if lo <= j < hi] for f in state.step_jumps],
            state.step_trouble,
            state.valid[:, cut],
        )


def find(
    steps: Any,
    state: Any,
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
    if within is not None:
        lo, hi = within
        state, angles = _Window.of(state, lo, hi), angles[lo : hi + 1]
    events: list[Event] = []
    unit = "deg" if revolute else "m"

    def show(x: float) -> str:
        return f"{math.degrees(x) % 360:.1f}" if revolute else f"{x:.4g}"

    n_var = min(state.valid.shape[0], max_variants)
    before = np.ones(state.valid.shape, dtype=bool)
    n = len(angles)
    trouble = state.step_trouble
    for k, (step, ok, det, slack, flips, jumps) in enumerate(
        zip(steps, state.step_valid, state.step_det, state.step_slack, state.step_flips, state.step_jumps, strict=True)
    ):
        if step.kind in ("crank", "slide"):
            continue  # a driving link always assembles and is never singular
        if trouble is not None and not trouble[k, :n_var].any() and not (jumps or flips):
            continue  # the compiled kernel saw it assemble everywhere, away from singular positions
        fails = before & ~ok
        head = det[:n_var]
        quiet = not (
            fails[:n_var].any()
            or jumps
            or flips
            or (np.abs(head) < 1e-9).any()
            or (np.signbit(head[:, 1:]) != np.signbit(head[:, :-1])).any()
        )
        for v in range(0 if quiet else n_var):
            tag = f" (variant {v})" if state.valid.shape[0] > 1 else ""

            def limit(i: int, j: int, margin: np.ndarray = slack[v]) -> float:
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

            for i, j in _runs(fails[v]):
                a = limit(i - 1, i) if i > 0 and before[v, i - 1] else float(angles[i])
                b = limit(j + 1, j) if j + 1 < n and before[v, j + 1] else float(angles[j])
                span = f"{show(a)} {unit}" if i == j else f"{show(a)} to {show(b)} {unit}"
                events.append(
                    Event(
                        "no-assembly",
                        step.label,
                        a,
                        b,
                        v,
                        f"group {step.label}: no assembly (no intersection) for crank "
                        f"{'angle' if i == j else 'angles'} {span}{tag}",
                    )
                )
                for x, inside in ((a, i > 0), (b, j + 1 < n)):
                    if inside:
                        events.append(
                            Event(
                                "dead-point",
                                step.label,
                                x,
                                x,
                                v,
                                f"group {step.label}: limit (dead) position near crank angle {show(x)} {unit}{tag}",
                            )
                        )
            d = np.where(before[v] & ok[v], det[v], np.nan)
            zero = np.flatnonzero(np.abs(d) < 1e-9)
            cross = np.flatnonzero(np.isfinite(d[:-1]) & np.isfinite(d[1:]) & (np.sign(d[:-1]) * np.sign(d[1:]) < 0))
            cross = cross[~np.isin(cross, zero) & ~np.isin(cross + 1, zero)]
            for i in cross:
                t = d[i] / (d[i] - d[i + 1])
                x = angles[i] + t * (angles[i + 1] - angles[i])
                events.append(
                    Event(
                        "singular",
                        step.label,
                        x,
                        x,
                        v,
                        f"group {step.label}: singular position (dead point) near crank angle {show(x)} {unit}{tag}",
                    )
                )
            for i in zero:
                events.append(
                    Event(
                        "singular",
                        step.label,
                        angles[i],
                        angles[i],
                        v,
                        f"group {step.label}: singular position (dead point) at crank angle "
                        f"{show(angles[i])} {unit}{tag}",
                    )
                )
            for jv, j in jumps:
                if jv == v:
                    events.append(
                        Event(
                            "branch-jump",
                            step.label,
                            angles[j],
                            angles[j + 1],
                            v,
                            f"group {step.label}: the solution jumps between crank angles "
                            f"{show(angles[j])} and {show(angles[j + 1])} {unit}: it may have changed "
                            f"assembly mode there; check with finer steps{tag}",
                        )
                    )
            for fv, _, i in flips:
                if fv == v:
                    events.append(
                        Event(
                            "change-point",
                            step.label,
                            angles[i],
                            angles[i],
                            v,
                            f"group {step.label}: its two assembly modes meet near crank angle "
                            f"{show(angles[i])} {unit}; the motion goes on smoothly in the other "
                            f"mode{tag}",
                        )
                    )
        before &= ok
    return events
