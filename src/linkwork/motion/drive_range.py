"""Over which range of its drive a mechanism assembles, and Grashof's class of a four-bar.

:func:`drive_range` solves the positions over a whole turn of a single
revolute drive, from the assembly pose in the drive's direction, and reads
the intervals where every group assembles; their limits (the limit, or dead,
positions) are refined between samples by :func:`linkwork.motion.events.find`.
The interval that holds the assembly pose is the one the mechanism moves in;
others, where it would assemble too, it cannot reach without coming apart.

:func:`grashof` classifies a four-bar (the frame and three links joined by
four revolute pairs) by the closed form: with s and l the shortest and the
longest of the four lengths between pivots and p, q the other two, a link
turns fully relative to its neighbours only if s + l <= p + q, and then the
shortest one does.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from linkwork.angles import TWO_PI, wrap
from linkwork.motion.events import Event, find, runs
from linkwork.motion.groups import KINDS
from linkwork.motion.solve import run_numpy
from linkwork.structure.model import Mechanism, PairType
from linkwork.structure.parameters import apply

#: Samples of the turn that :func:`drive_range` solves (0.5 deg apart).
STEPS = 720


@dataclass(frozen=True)
class Grashof:
    """Grashof's class of a four-bar.

    Attributes
    ----------
    links : tuple of str
        ``(frame, input, coupler, output)``: the frame, the link the drive
        turns (of the two joined to the frame), the coupler and the other
        link joined to the frame.
    lengths : tuple of float
        Their lengths between pivots, m, in the same order.
    s_plus_l, p_plus_q : float
        The shortest plus the longest, and the sum of the other two, m.
    kind : str
        ``"crank-rocker"`` (s + l < p + q, a link joined to the frame is the
        shortest: it is the crank), ``"double-crank"`` (the frame is the
        shortest), ``"double-rocker"`` (the coupler is the shortest: it turns
        fully, the links joined to the frame rock), ``"triple-rocker"``
        (s + l > p + q: no link turns fully relative to another) or
        ``"change-point"`` (s + l = p + q: the links can fold into a line).
    cranks : tuple of str
        The links that turn fully relative to the frame.
    drive_turns : bool
        Whether the driven joint can make full turns.
    """

    links: tuple[str, str, str, str]
    lengths: tuple[float, float, float, float]
    s_plus_l: float
    p_plus_q: float
    kind: str
    cranks: tuple[str, ...]
    drive_turns: bool

    def as_dict(self) -> dict[str, Any]:
        return {
            "class": self.kind,
            "links": dict(zip(("frame", "input", "coupler", "output"), self.links, strict=True)),
            "lengths": dict(zip(self.links, self.lengths, strict=True)),
            "s_plus_l": self.s_plus_l,
            "p_plus_q": self.p_plus_q,
            "cranks": list(self.cranks),
            "drive_turns": self.drive_turns,
        }

    def describe(self) -> str:
        """One line: the sums, the class and whether the drive turns fully."""
        rel = "=" if self.kind == "change-point" else (">" if self.kind == "triple-rocker" else "<")
        if self.cranks:
            turns = f"{' and '.join(self.cranks)} {'turns' if len(self.cranks) == 1 else 'turn'} fully"
        else:
            turns = "no link joined to the frame turns fully"
        return f"s + l = {self.s_plus_l:.6g} m {rel} p + q = {self.p_plus_q:.6g} m: {self.kind}, {turns}"


@dataclass(frozen=True)
class DriveRange:
    """The range of a revolute drive over which the mechanism assembles.

    Attributes
    ----------
    joint : str
        The driven joint.
    start : float
        The drive angle of the assembly pose, rad.
    full_turn : bool
        Whether it assembles at every sample of the turn.
    reach : tuple of float
        ``(low, high)``, rad, counter-clockwise, with its middle in
        ``(-pi, pi]``: the interval of drive angles that holds the assembly
        pose, between its limit positions; a whole turn from the assembly
        angle when ``full_turn``.
    others : tuple of tuple of float
        Further intervals (same convention) where it would assemble, which it
        cannot reach from the assembly pose.
    steps : int
        Samples of the turn solved.
    grashof : Grashof or None
        For a four-bar.
    """

    joint: str
    start: float
    full_turn: bool
    reach: tuple[float, float]
    others: tuple[tuple[float, float], ...]
    steps: int
    grashof: Grashof | None = None
    singular: str | None = None  # a dyad on a singular position in the assembly pose (:func:`singular_start`)

    def as_dict(self) -> dict[str, Any]:
        return {
            "joint": self.joint,
            "full_turn": self.full_turn,
            "start_deg": math.degrees(self.start),
            "reach_deg": [math.degrees(x) for x in self.reach],
            "others_deg": [[math.degrees(x) for x in iv] for iv in self.others],
            "steps": self.steps,
            "grashof": None if self.grashof is None else self.grashof.as_dict(),
        }

    def describe(self) -> list[str]:
        """Lines: a full turn, or the interval the drive moves in (and those out of reach)."""
        if self.full_turn:
            return [f"full turn of {self.joint} (assembles at all {self.steps} angles)"]
        lines = [f"{self.joint} from {_deg(self.reach)}, between its limit positions"]
        lines += [f"(it assembles also from {_deg(iv)}, out of its reach)" for iv in self.others]
        return lines

    def warning(self) -> str | None:
        """The warning for a drive that cannot make a full turn, or None."""
        if self.full_turn:
            return None
        return f"{self.joint} cannot make a full turn: it moves from {_deg(self.reach)} only"

    def warnings(self) -> list[str]:
        """Every warning of ``check`` on the drive's range: :meth:`warning` and :attr:`singular`."""
        return [w for w in (self.warning(), self.singular) if w]


def _deg(interval: tuple[float, float]) -> str:
    return f"{math.degrees(interval[0]):.2f} to {math.degrees(interval[1]):.2f} deg"


def drive_range(mech: Mechanism, steps: int = STEPS) -> DriveRange | None:
    """The range of the drive over which ``mech`` assembles; None unless it has one revolute drive.

    Parameters
    ----------
    mech : Mechanism
    steps : int
        Samples of the turn; an interval of no assembly narrower than
        ``2 pi / steps`` may go unseen.

    Returns
    -------
    DriveRange or None
    """
    if mech.n_drives != 1 or mech.pair_type[mech.drive_pair[0]] != PairType.REVOLUTE:
        return None
    sign = -1.0 if mech.drive_speed[0] < 0 else 1.0
    start = float(mech.drive_start[0])
    travel = 2 * np.pi * np.arange(steps + 1) / steps  # the last sample is the first, a turn later
    valid, events, dets = _solve(mech, start + sign * travel)
    gaps = _gaps(valid, travel, [e for e in events if e.kind == "no-assembly"], start, sign)
    joint = mech.pair_joint[mech.drive_pair[0]]
    near = singular_start(mech, start + sign * travel, dets)
    if not gaps:
        turn = (start, start + 2 * np.pi) if sign > 0 else (start - 2 * np.pi, start)
        return DriveRange(joint, start, True, turn, (), steps, grashof(mech), near)
    ends = [b for _, b in gaps]
    begins = [a for a, _ in gaps]
    spans = [(ends[-1] - 2 * np.pi, begins[0])] + list(zip(ends[:-1], begins[1:], strict=True))
    intervals = [_interval(start + sign * a, start + sign * b) for a, b in spans]
    return DriveRange(joint, start, False, intervals[0], tuple(intervals[1:]), steps, grashof(mech), near)


def _solve(mech: Mechanism, angles: np.ndarray) -> tuple[np.ndarray, list[Event], np.ndarray]:
    """Where the mechanism assembles at ``angles`` ``(A,)`` of its drive, the events along them, and the absolute
    normalised Jacobian determinant of each step of the program there ``(S, A)`` (zero on a singular position).

    By the NumPy kernels, as ``linkwork.kinematics`` would without numba: for a few hundred angles they
    take milliseconds, less than loading the compiled kernels into a fresh process (``check``'s case).
    """
    values = angles[:, None]
    state = run_numpy(mech, mech.program, apply(mech)[0], values, np.ones_like(values), np.zeros_like(values))
    dets = np.stack([np.abs(np.broadcast_to(r.det, state.valid.shape)[0]) for r in state.steps])
    return state.valid[0], find(mech.program, state, angles, True), dets


#: A dyad whose normalised Jacobian determinant (the sine of its transmission angle) is below this in the assembly
#: pose is on a singular position for ``check`` (:func:`singular_start`): its two assembly modes are there within
#: about a thousandth of its size of each other.
CLEAR = 1e-3


def singular_start(mech: Mechanism, angles: np.ndarray, dets: np.ndarray) -> str | None:
    """The warning for a dyad on (or within :data:`CLEAR` of) a singular position in the assembly pose, or None.

    There its two assembly modes (nearly) meet: which one the file means rests on a rounding of its hints, and a
    change point may lie at the very start of the motion.  The warning names the group, the crank angle and the
    transmission angle, and the nearest of ``angles`` ``(A,)`` (the first the assembly angle) where every dyad is
    ten times clear of it: an assembly angle to give instead.  ``dets``: :func:`_solve`'s ``(S, A)``.
    """
    dyads = [k for k, step in enumerate(mech.program) if KINDS[step.kind].changes_mode]
    on = [k for k in dyads if dets[k, 0] < CLEAR]
    if not on:
        return None
    k = on[0]
    clear = np.all(dets[dyads] >= 10 * CLEAR, axis=0)
    offset = np.abs(wrap(angles - angles[0]))
    text = (
        f"group {mech.program[k].label} is on a singular position in the assembly pose (crank at "
        f"{math.degrees(wrap(angles[0])):.4f} deg to the x axis): its transmission angle is "
        f"{math.degrees(math.asin(min(dets[k, 0], 1.0))):.2g} deg, so its two assembly modes are within a rounding "
        "of each other there and the mode the file means rests on the hints"
    )
    if clear.any():
        i = int(np.argmin(np.where(clear, offset, np.inf)))
        text += (
            f"; give the drive an assembly angle clear of it, such as {math.degrees(wrap(angles[i])):.2f} deg to "
            f"the x axis (transmission angle {math.degrees(math.asin(min(dets[k, i], 1.0))):.2g} deg there), "
            "with hints in the mode meant"
        )
    return text


def _gaps(
    valid: np.ndarray, travel: np.ndarray, events: list[Event], start: float, sign: float
) -> list[tuple[float, float]]:
    """Intervals ``(a, b)`` of no assembly, as travel (rad from the assembly pose in the drive's direction).

    Each limit is the events' refined one that lies between the last sample that assembles and the first
    that does not (that sample where there is none).
    """
    limits = np.array([x for e in events for x in (e.start, e.end)], dtype=float)
    limits = sign * (limits - start)  # as travel

    def refined(inside: int, outside: int) -> float:
        lo, hi = sorted((travel[inside], travel[outside]))
        near = limits[(limits >= lo - 1e-12) & (limits <= hi + 1e-12)]
        return float(near[np.argmin(np.abs(near - travel[outside]))]) if near.size else float(travel[inside])

    n = len(travel)
    return [
        (refined(i - 1, i) if i > 0 else 0.0, refined(j + 1, j) if j + 1 < n else float(travel[j]))
        for i, j in runs(~valid)
    ]


def _interval(a: float, b: float) -> tuple[float, float]:
    """The interval between two drive angles, low first, its middle in (-pi, pi] (:func:`~linkwork.angles.wrap`)."""
    lo, hi = sorted((a, b))
    mid, slack = (lo + hi) / 2, 1e-9 * TWO_PI  # a middle within the limits' refinement above -pi is at pi
    shift = round((mid - slack - wrap(mid - slack)) / TWO_PI) * TWO_PI  # whole turns
    return lo - shift, hi - shift


def grashof(mech: Mechanism) -> Grashof | None:
    """Grashof's class of a four-bar (frame and three links, four revolute pairs); None for other mechanisms."""
    four = _four_bar(mech)
    if four is None:
        return None
    links, lengths = four
    s, l = min(lengths), max(lengths)  # noqa: E741 - the names of the rule
    sl, pq = s + l, sum(lengths) - s - l
    tol = 1e-9 * l
    short = [i for i, x in enumerate(lengths) if x <= s + tol]
    if abs(sl - pq) <= tol:
        kind = "change-point"
    elif sl > pq:
        kind = "triple-rocker"
    else:
        kind = ("double-crank", "crank-rocker", "double-rocker", "crank-rocker")[short[0]]
    grashof_ok = sl <= pq + tol
    # in a Grashof chain a link turns fully relative to its neighbours exactly when it is the shortest
    turning = set(short) if grashof_ok else set()
    cranks = tuple(links[i] for i in (1, 3) if grashof_ok and (i in turning or 0 in turning))
    drive = set(mech.pair_links[mech.drive_pair[0]].tolist())
    index = [mech.link_names.index(name) for name in links]
    drive_turns = grashof_ok and any(index[i] in drive for i in turning)
    return Grashof(links, lengths, sl, pq, kind, cranks, drive_turns)


def _four_bar(mech: Mechanism) -> tuple[tuple[str, str, str, str], tuple[float, float, float, float]] | None:
    """The names (frame, input, coupler, output) and lengths of a four-bar, or None."""
    revolute = bool(np.all(mech.pair_type == PairType.REVOLUTE))
    if len(mech.link_names) != 4 or mech.n_pairs != 4 or mech.n_drives != 1 or not revolute:
        return None
    pivots: dict[int, list[int]] = {link: [] for link in range(4)}
    for k in range(4):
        for side in (0, 1):
            pivots[int(mech.pair_links[k, side])].append(int(mech.pair_points[k, side]))
    if any(len(p) != 2 for p in pivots.values()):
        return None
    length = {link: float(np.hypot(*(mech.point_local[p[0]] - mech.point_local[p[1]]))) for link, p in pivots.items()}
    on_frame = [int(mech.pair_links[k].sum()) for k in range(4) if 0 in mech.pair_links[k]]
    drive = mech.pair_links[mech.drive_pair[0]].tolist()
    first = next((link for link in on_frame if link in drive), on_frame[0])
    output = next(link for link in on_frame if link != first)
    coupler = ({1, 2, 3} - {first, output}).pop()
    order = (0, first, coupler, output)
    return tuple(mech.link_names[i] for i in order), tuple(length[i] for i in order)  # type: ignore[return-value]
