"""A kinematics result solved again between its samples, in the assembly modes the samples give.

:meth:`Kinematics.at <linkwork.motion.kinematic_analysis.Kinematics.at>` reads off the samples around each asked
drive coordinate the mode of every dyad (:func:`modes_at`); where the two samples around one are in different modes,
the change point between them is located (:func:`_change_point`) and the angle is solved in the mode of its side
(:func:`solved`).  Used by the refinement of peaks between samples (:mod:`linkwork.kinetostatics.peaks`) and by the
integrators that read a cycle at their own times.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from linkwork.motion.groups import KINDS
from linkwork.motion.solve import SINGULAR, run_each
from linkwork.structure.parameters import Geometry, Masses

if TYPE_CHECKING:
    from linkwork.motion.kinematic_analysis import Kinematics


def modes_at(
    kin: Kinematics, angles: np.ndarray, variants: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray, list[np.ndarray | None], np.ndarray] | None:
    """The assembly modes this result has at other drive coordinates ``angles`` ``(R, K)``, as ``Kinematics.at`` solves
    them: the variant of each row ``(R,)``, the angles (NaN where a change point between the samples around one
    cannot be located), each dyad's mode ``(R, K)`` (None for the other steps) and the sample nearer each angle
    ``(R, K)``; None but for one drive.  On a whole turn the angles are taken to whole turns."""
    mech = kin.mechanism
    if mech.n_drives != 1:
        return None
    angles = np.asarray(angles, dtype=float)
    if not kin.variants:
        variants = np.zeros(len(angles), dtype=np.intp)
    rows = np.arange(len(angles)) if variants is None else np.asarray(variants, dtype=np.intp)
    lost = ~np.isfinite(angles)  # no angle (a trial of an integrator): not solved
    lo, hi, near, frac = _around(kin.angles, np.where(lost, kin.angles[0], angles))
    modes: list[np.ndarray | None] = []
    none = (None,) * len(mech.program)
    for k, (step, branch, det) in enumerate(
        zip(mech.program, kin.step_branch or none, kin.step_det or none, strict=True)
    ):
        if branch is None or not KINDS[step.kind].changes_mode:
            modes.append(None)
            continue
        own = branch[rows]
        below, above = np.take_along_axis(own, lo, 1), np.take_along_axis(own, hi, 1)
        if det is not None:  # a sample on the singular position has the modes of both sides: the other end's
            lone = np.abs(det[rows]) < SINGULAR
            on_lo, on_hi = np.take_along_axis(lone, lo, 1), np.take_along_axis(lone, hi, 1)
            below, above = np.where(on_lo & ~on_hi, above, below), np.where(on_hi & ~on_lo, below, above)
        apart = below != above
        if not apart.any():
            modes.append(np.where(near == lo, below, above))
            continue
        tau = np.full(angles.shape, np.nan)
        tau[apart] = _change_point(kin, k, rows[np.nonzero(apart)[0]], lo[apart], hi[apart])
        first = frac < tau  # on the side of the sample below
        lost |= apart & np.isnan(tau)
        near = np.where(apart, np.where(first, lo, hi), near)
        modes.append(np.where(apart, np.where(first, below, above), np.where(near == lo, below, above)))
    return rows, np.where(lost, np.nan, angles), modes, near


def solved(
    kin: Kinematics, rows: np.ndarray, each: np.ndarray, modes: list[np.ndarray | None], near: np.ndarray
) -> Kinematics | None:
    """Variant ``rows[r]`` solved at the drive coordinates ``each[r]`` in the assembly ``modes`` (per step of the
    program, ``(R, K)`` or None), a group solved by Newton's method started from the samples ``near``; see
    :meth:`Kinematics.at`."""
    mech = kin.mechanism
    rate = float(kin.rates[0, 0])
    arrays = (kin.local, kin.origin, kin.axis)
    geom = Geometry(*(np.ascontiguousarray(x.transpose(2, 3, 0, 1)[rows]) for x in arrays))
    start = kin.q[:, :, rows[:, None], near]  # (N, 3, R, K)
    state = run_each(mech, geom, each, rate, modes=modes, start=start)
    if state is None:
        return None
    m = kin.masses
    masses = None if m is None else Masses(m.mass[rows], m.com[rows], m.inertia[rows])
    rates = np.full((each.shape[1], 1), rate)
    return type(kin)._of_state(mech, state, each[0][:, None], rates, variants=True, masses=masses, each=each)


def _change_point(kin: Kinematics, step: int, rows: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """Where the change point of dyad ``step`` lies between the samples ``lo`` and ``hi`` ``(U,)`` (in
    different modes) of the variants ``rows``: the fraction of the way from ``lo`` to ``hi``, ``(U,)``; NaN where
    it is not found.  Found once per result (kept by step, variant and sample).

    Where the two modes meet, every link's pose is the same in both: the squared distance between the two
    solutions, each point of the links and the tip of each link's x axis, has a double root there and its rate
    of change changes sign (:func:`_parting`); that root is bracketed by the two samples and found by false
    position safeguarded by bisection, to rounding.  The other dyads keep the modes of ``lo``.
    """
    known: dict[tuple[int, int, int], float] = kin.__dict__.setdefault("_change_points", {})
    keys = [(step, v, i) for v, i in zip(rows.tolist(), lo.tolist(), strict=True)]
    first: dict[tuple[int, int, int], int] = {}
    for place, key in enumerate(keys):
        if key not in known:
            first.setdefault(key, place)
    todo = sorted(first)
    if todo:
        _, v, i = (np.array(x, dtype=np.intp) for x in zip(*todo, strict=True))
        j = np.array([int(hi[first[key]]) for key in todo], dtype=np.intp)
        for key, tau in zip(todo, _located(kin, step, v, i, j).tolist(), strict=True):
            known[key] = tau
    return np.array([known[key] for key in keys])


def _located(kin: Kinematics, step: int, rows: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """The root finding of :func:`_change_point` for distinct ``(rows, lo, hi)`` ``(U,)``."""
    n = len(kin.angles)
    width = kin.angles[hi] - kin.angles[lo]
    if n >= 3 and abs(abs(n * (kin.angles[1] - kin.angles[0])) - 2 * np.pi) <= 1e-9:
        width = np.full(len(lo), kin.angles[1] - kin.angles[0])  # a whole turn: hi follows lo
    base = kin.angles[lo]
    fixed = [None if b is None else b[rows, lo] for b in kin.step_branch]
    branch = kin.step_branch[step]
    assert branch is not None  # a dyad whose modes differ between the samples
    mine, other = branch[rows, lo], branch[rows, hi]

    def parting(tau: np.ndarray) -> np.ndarray:
        k = tau.shape[1]
        x = np.tile(base[:, None] + tau * width[:, None], 2)
        modes = [None if b is None else np.repeat(b[:, None], 2 * k, 1) for b in fixed]
        modes[step] = np.concatenate([np.repeat(mine[:, None], k, 1), np.repeat(other[:, None], k, 1)], 1)
        near = np.repeat(lo[:, None], 2 * k, 1)
        found = solved(kin, rows, x, modes, near)
        return np.full(tau.shape, np.nan) if found is None else _parting(found, k)

    a, b = np.zeros(len(lo)), np.ones(len(lo))
    ga, gb = parting(np.stack([a, b], 1)).T
    found = np.isfinite(ga) & np.isfinite(gb) & (np.sign(ga) * np.sign(gb) < 0)
    tol = 4 * np.finfo(float).eps * np.maximum(1.0, np.abs(base)) / np.abs(width)
    for _ in range(80):
        busy = found & (b - a > tol)
        if not busy.any():
            break
        with np.errstate(invalid="ignore", divide="ignore"):
            false = (a * gb - b * ga) / (gb - ga)
        mid = 0.5 * (a + b)
        false = np.where(np.isfinite(false) & (false > a) & (false < b), false, mid)
        p = np.sort(np.stack([false, mid], 1), axis=1)
        gp = parting(p)
        xs, gs = np.column_stack([a, p, b]), np.column_stack([ga, gp, gb])
        change = np.sign(gs[:, :-1]) * np.sign(gs[:, 1:]) <= 0
        j = np.argmax(change, axis=1)
        rows_u = np.arange(len(a))
        keep = busy & change.any(axis=1)
        found &= ~busy | keep
        a, b = np.where(keep, xs[rows_u, j], a), np.where(keep, xs[rows_u, j + 1], b)
        ga, gb = np.where(keep, gs[rows_u, j], ga), np.where(keep, gs[rows_u, j + 1], gb)
    return np.where(found, 0.5 * (a + b), np.nan)


def _around(samples: np.ndarray, x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The samples around each drive coordinate ``x`` ``(R, K)`` among ``samples`` ``(A,)`` (equally spaced over a
    whole turn: its ends are neighbours; else any monotonic range, the ends standing for what lies beyond them):
    ``(below, above, nearer)`` indices, ``(R, K)`` each, all three the sample itself where ``x`` is one, to
    rounding; and the fraction of the way from ``below`` to ``above`` ``x`` lies at."""
    n = len(samples)
    if n < 2:
        zero = np.zeros(x.shape, dtype=np.intp)
        return zero, zero, zero, np.zeros(x.shape)
    step = samples[1] - samples[0]
    if n >= 3 and abs(abs(n * step) - 2 * np.pi) <= 1e-9:
        k = np.mod(x - samples[0], n * step) / step  # within the turn (an integrator's trial may be far off)
        k = np.where(np.abs(k - np.round(k)) <= 1e-9, np.round(k), k)
        first = np.floor(k)
        below, above = first.astype(np.intp) % n, (first.astype(np.intp) + 1) % n
        on = k == first
        nearer = np.where(k - first <= 0.5, below, above)
        return below, np.where(on, below, above), nearer, k - first
    order = np.argsort(samples)
    s = samples[order]
    tol = 1e-9 * max(1.0, float(np.abs(s).max()))
    pos = np.clip(np.searchsorted(s, x + tol, side="right") - 1, 0, n - 1)
    on = (np.abs(x - s[pos]) <= tol) | (x <= s[0]) | (pos == n - 1)
    up = np.where(on, pos, np.minimum(pos + 1, n - 1))
    nearer = np.where(np.abs(x - s[pos]) <= np.abs(s[up] - x), pos, up)
    with np.errstate(invalid="ignore", divide="ignore"):
        frac = np.where(up == pos, 0.0, (x - s[pos]) / (s[up] - s[pos]))
    return order[pos], order[up], order[nearer], frac


def _parting(k: Kinematics, m: int) -> np.ndarray:
    """The rate of change of half the squared distance between two solutions of the same angles, columns ``:m`` and
    ``m:`` of ``k`` ``(R, 2 m)``: of every link's origin and the tip of its unit x axis, ``(R, m)``; zero where the
    two meet at a change point, and of opposite signs on its two sides (:meth:`Kinematics._change_point`)."""

    def d(x: np.ndarray) -> np.ndarray:
        return x[..., :m] - x[..., m:]

    omega = k.v[:, 2]
    terms = (
        d(k.q[:, 0]) * d(k.v[:, 0])
        + d(k.q[:, 1]) * d(k.v[:, 1])
        + d(k.cos) * d(-k.sin * omega)
        + d(k.sin) * d(k.cos * omega)
    )
    out: np.ndarray = terms.sum(axis=0)
    return out
