"""Where a dyad's assembly mode changes along the samples: the change points its motion passes through.

Where the two assembly modes of a dyad cross (the isosceles slider-crank at 0 and 180 deg, a parallelogram
laid flat) the mode that keeps the velocities continuous has the other sign on the far side.
:func:`change_points` finds the samples where the mode flips, from the rate of the drive where there is one
(:func:`_crossings`) or by extrapolation where there is none (:func:`_extrapolated`).
"""

from __future__ import annotations

import numpy as np
from numpy.polynomial import polynomial as poly

from linkwork.motion.closure import Closure, Singular, mode_point
from linkwork.motion.state import Flip, State, Vec, norm, sub


def change_points(state: State, closure: Closure, branch: np.ndarray) -> list[Flip]:
    """Follow the motion through change points, along the angles in the order given.

    Where the two modes of a dyad cross (the isosceles slider-crank at 0 and
    180 deg, a parallelogram laid flat, a rhombus with its crank on the
    frame) the mode that keeps the velocities continuous has the other sign
    on the far side: from the sample nearest the assembly pose, forwards and
    then backwards, the mode changes between two samples that lie on either
    side of a crossing, and nowhere else (:func:`_crossings`), however fast X
    swings and whatever the samples (one on the crossing itself counts on
    the side its motion gives it).  Without the rate of a single drive, each
    sample where the modes nearly meet takes the mode whose X lies nearer
    the extrapolation from the two samples before it instead
    (:func:`_extrapolated`).  ``branch`` is changed in place.
    """
    x_p, x_m = mode_point(closure, branch), mode_point(closure, -branch)
    if branch.shape[1] < 3:
        return []
    gap = norm(sub(x_p, x_m))  # (V, A)
    near = _modes_near(state, x_p, x_m, gap)
    if not near.any():
        return []
    rate = state.rate
    if rate is not None and bool(np.all(np.isfinite(rate) & (rate != 0))):
        return _crossings(state, closure, branch, rate)
    return _extrapolated(state, np.stack(x_p, -1), np.stack(x_m, -1), near, gap, branch)


def _modes_near(state: State, x_p: Vec, x_m: Vec, gap: np.ndarray) -> np.ndarray:
    """Where the gap between the two modes' X is within twice the step X takes (in either mode) to or
    from a neighbouring sample: ``(V, A)``."""
    step = np.fmax(
        norm((np.diff(x_p[0], axis=1), np.diff(x_p[1], axis=1))),
        norm((np.diff(x_m[0], axis=1), np.diff(x_m[1], axis=1))),
    )  # (V, A - 1), either mode
    move = np.empty_like(gap)
    move[:, 0], move[:, -1] = step[:, 0], step[:, -1]
    np.fmax(step[:, :-1], step[:, 1:], out=move[:, 1:-1])
    with np.errstate(invalid="ignore"):
        near: np.ndarray = gap <= 2 * move + 1e-12 * (1 + float(np.abs(state.local).max()))
    return near


def _extrapolated(
    state: State, xp: np.ndarray, xm: np.ndarray, near: np.ndarray, gap: np.ndarray, branch: np.ndarray
) -> list[Flip]:
    """The mode of each sample where the modes nearly meet (``near``) whose X (``xp`` in the mode
    ``branch``, ``xm`` in the other, ``(V, A, 2)``) lies nearer the extrapolation from the two samples
    before it, walking from the sample nearest the assembly pose forwards and then backwards."""
    drive = state.drive
    n = branch.shape[1]
    flips = []
    start = state.start_index
    for v in np.unique(np.nonzero(near)[0]):
        flipped = np.zeros(n, dtype=bool)  # samples now in the mode opposite to the first solution

        def at(i: int, other: bool = False, v: int = v, flipped: np.ndarray = flipped) -> np.ndarray:
            return xm[v, i] if flipped[i] != other else xp[v, i]

        for direction in (1, -1):
            order = np.arange(start, n) if direction > 0 else np.arange(start, -1, -1)
            for k in range(2, len(order)):
                here = order[k]
                if not near[v, here]:
                    continue
                p1, p2 = order[k - 1], order[k - 2]
                span = drive[p1] - drive[p2]
                t = (drive[here] - drive[p1]) / span if span != 0 else 1.0
                guess = at(p1) + (at(p1) - at(p2)) * t
                tol = 1e-12 * (1 + np.abs(guess).max())
                if np.hypot(*(at(here, True) - guess)) < np.hypot(*(at(here) - guess)) - tol:
                    branch[v, order[k:]] *= -1
                    flipped[order[k:]] = ~flipped[order[k:]]
                    touch = int(order[k - 1] if gap[v, order[k - 1]] < gap[v, here] else here)
                    flips.append(Flip(int(v), int(here), touch))
    return flips


def _lead(test: Singular) -> np.ndarray:
    """Time from the extremum (scalar) or the meeting (vector) of a quantity, to first order: positive
    after it.  (V, A)"""
    if len(test.y) == 1:
        return test.v[0] / test.a[0]
    return sum(y * v for y, v in zip(test.y, test.v, strict=True)) / sum(v * v for v in test.v)


def _crossings(state: State, closure: Closure, branch: np.ndarray, rate: np.ndarray) -> list[Flip]:
    """The mode flips between consecutive samples on either side of a crossing of the two modes.

    Which side of a crossing a sample lies on is the sign of its time from the extremum of the
    quantity whose target is the singular position (the distance of the outer joints, of a circle's
    centre from a line), from its first two derivatives there (so also a sample on the crossing, to
    rounding, is on one side); whether the extremum reaches the target between the samples, or goes
    beyond it (where the dyad cannot assemble: then nothing is crossed), is :func:`_reach`.
    """
    drive = state.drive
    start = state.start_index
    later = np.sign(np.diff(drive) * rate[:-1])  # +1 where the next sample comes later
    with np.errstate(invalid="ignore", divide="ignore"):
        times = [_lead(t) for t in closure.singular]
    # the side of each sample (a time of zero counts as after, as the limit direction of joined joints)
    leads = [np.where(np.isfinite(t), np.where(t < 0, -1.0, 1.0), 0.0) for t in times]
    if not leads:
        return []
    # where a lead changes sign from one sample to the next (an extremum between, or on one of them)
    # within reach of its target from either end
    dt = np.abs(np.diff(drive) / rate[:-1])
    changes = np.logical_or.reduce(
        [(s[:, 1:] != s[:, :-1]) & _within_reach(t, dt) for s, t in zip(leads, closure.singular, strict=True)]
    )
    flips = []
    for v, i in np.argwhere(changes):
        prev, here = (i, i + 1) if i >= start else (i + 1, i)  # walked away from the assembly pose
        ahead = later[i] if here > prev else -later[i]  # +1: the walk goes forward in time
        crossed = [
            (_reach(test, drive, rate, v, prev, here), time)
            for test, lead, time in zip(closure.singular, leads, times, strict=True)
            if lead[v, prev] * ahead < 0 < lead[v, here] * ahead  # before at prev, after at here
            and not _flat_touch(test, v, prev, here)
        ]
        if not crossed or any(verdict < 0 for verdict, _ in crossed) or all(verdict == 0 for verdict, _ in crossed):
            continue  # nothing crossed, or a gap where the dyad cannot assemble
        branch[v, slice(here, None) if here > prev else slice(None, here + 1)] *= -1
        time = next(t for verdict, t in crossed if verdict > 0)
        flips.append(Flip(int(v), int(here), int(prev if abs(time[v, prev]) < abs(time[v, here]) else here)))
    return flips


#: :func:`_flat_touch`: the order ratio ``u u'' / u'^2`` above which a touch is flat (1/2 at a change point, 3/4 at a
#: flat touch).
FLAT = 5 / 8


def _flat_touch(test: Singular, v: int, i: int, j: int) -> bool:
    """Whether a scalar quantity touches its target between samples ``i`` and ``j`` at an extremum of higher order
    (its distance from the target ``u ~ tau^4`` about it, ``tau`` the time from it), where no mode is crossed.

    At a change point ``u ~ tau^2``: the half gap between the two modes, ``h ~ sqrt(u) ~ |tau|``, goes on as
    ``h ~ tau`` through it, the other mode.  Where the dyad's outer joints themselves come to rest there (a toggle
    press whose upper link ends its swing on the line of the guide: the rocker's dead point on the dyad's change
    point) ``u ~ tau^4``, ``h ~ tau^2`` keeps its sign, and the motion keeps its mode (and, where the extremum
    falls short of the target or passes it by a rounding, the modes do not meet or meet twice: the same mode after
    either way).  The order is read off the sample farther from the target, from ``u u'' / u'^2 = (m - 1) / m``
    for ``u ~ tau^m``: 1/2 or 3/4, told apart at :data:`FLAT`."""
    if len(test.y) != 1:
        return False
    target = test.target[0]
    goal = float(target[v, 0]) if isinstance(target, np.ndarray) and target.ndim else float(target)
    u = [goal - test.y[0][v, k] for k in (i, j)]
    k = (i, j)[int(abs(u[1]) > abs(u[0]))]
    rate, turn = test.v[0][v, k], test.a[0][v, k]
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        ratio = np.float64(-(goal - test.y[0][v, k]) * turn) / np.float64(rate * rate)
    return bool(np.isfinite(ratio) and ratio > FLAT)


def _within_reach(test: Singular, dt: np.ndarray) -> np.ndarray:
    """Whether a quantity can come within its tolerance of its target between consecutive samples
    ``dt`` apart (A - 1,), by twice the first two terms of its Taylor expansion from either end:
    (V, A - 1)."""
    with np.errstate(invalid="ignore"):
        off = np.sqrt(sum((y - t) ** 2 for y, t in zip(test.y, test.target, strict=True)))
        speed = np.sqrt(sum(v * v for v in test.v))
        turn = np.sqrt(sum(a * a for a in test.a))
        ends = [
            off[:, k] - 2 * (speed[:, k] * dt + turn[:, k] * dt * dt) - test.tol
            for k in (slice(None, -1), slice(1, None))
        ]
        return (ends[0] <= 0) | (ends[1] <= 0)


def _reach(test: Singular, drive: np.ndarray, rate: np.ndarray, v: int, i: int, j: int) -> int:
    """Whether a quantity reaches its singular position between samples ``i`` and ``j``: 1 if it
    does, -1 if it goes beyond (a scalar whose dyad cannot assemble there), 0 if not.

    The quantity is followed by the quintic through its values and first two time derivatives at
    both samples, within its tolerance widened by how far the quintic is from the cubic through the
    values and first derivatives (a bound on its own error).
    """
    dt = (drive[j] - drive[i]) / rate[i]
    target = np.array([c[v, 0] if isinstance(c, np.ndarray) and c.ndim else c for c in test.target], dtype=float)
    if np.isnan(target).any():
        return 0  # a position this dyad never takes
    y, vel, acc = (np.array([[c[v, i], c[v, j]] for c in x]) for x in (test.y, test.v, test.a))
    y0, y1 = y[:, 0] - target, y[:, 1] - target
    v0, v1 = vel[:, 0] * dt, vel[:, 1] * dt
    a0, a1 = acc[:, 0] * dt * dt, acc[:, 1] * dt * dt
    if not np.isfinite(np.concatenate([y0, y1, v0, v1, a0, a1])).all():
        return 0
    # on [0, 1]: y0 + v0 t + a0 t^2 / 2 + c3 t^3 + c4 t^4 + c5 t^5 with the values at 1
    big_a, big_b, big_c = y1 - y0 - v0 - a0 / 2, v1 - v0 - a0, a1 - a0
    quintic = np.stack(
        [y0, v0, a0 / 2, 10 * big_a - 4 * big_b + big_c / 2, -15 * big_a + 7 * big_b - big_c]
        + [6 * big_a - 3 * big_b + big_c / 2],
        -1,
    )
    cubic = np.stack([y0, v0, 3 * (y1 - y0) - 2 * v0 - v1, 2 * (y0 - y1) + v0 + v1, 0 * y0, 0 * y0], -1)
    grid = np.linspace(0.0, 1.0, 17)
    tol = (
        test.tol[v, 0] + np.sqrt(sum(poly.polyval(grid, q - c) ** 2 for q, c in zip(quintic, cubic, strict=True))).max()
    )
    if len(quintic) == 1:  # the extreme excursion towards (and beyond) the target
        path = quintic[0] * test.beyond
        slope = poly.polyder(path)
        t = poly.polyroots(slope).real if np.any(slope) else np.zeros(0)
        top = poly.polyval(np.concatenate([[0.0, 1.0], np.clip(t, 0.0, 1.0)]), path).max()
        return -1 if top > tol else (1 if top >= -tol else 0)
    square = np.zeros(1)
    for c in quintic:  # |y(t) - target|^2
        square = poly.polyadd(square, poly.polymul(c, c))
    slope = poly.polyder(square)
    t = poly.polyroots(slope).real if np.any(slope) else np.zeros(0)
    low = poly.polyval(np.concatenate([[0.0, 1.0], np.clip(t, 0.0, 1.0)]), square).min()
    return 1 if np.sqrt(max(low, 0.0)) <= tol else 0
