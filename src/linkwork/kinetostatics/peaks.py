"""Peaks of forces, torques and powers over the crank angle, refined between the samples by one rule.

A peak read off the samples of a cycle depends on the grid: the double-cut shears' driving torque peaks
where the knives' force stops rising, between two samples of any grid.  :func:`refine` takes the best
sample and evaluates the true quantity (kinematics and forces solved again) at angles between its two
neighbours, zooming in on the best of them until the values around it agree to :data:`TOLERANCE`:
every route (the command line, the report, the viewer, the sweeps) gets the same number whatever its
grid.  The zoom needs no smoothness: at a kink (a load that stops rising) it converges to the kink, and
at a jump (a load that switches on) to the limit from the high side, the supremum.  A peak of the
samples at an end of a range that is not a whole turn stays within the range.  Only the neighbourhood
of the best sample is refined: of two nearly equal maxima more than a step apart, the grid picks one.
The value is found to about ``TOLERANCE``; the angle of a kink or a jump to about 1e-12 rad, that of a
smooth maximum only to the square root of the values' precision (about 1e-7 rad), as from any values.

Variants (and the quantities of one mechanism) are refined together, each at its own angles, in one solve a round
(:meth:`linkwork.motion.Kinematics.at`: the NumPy kernels, each angle in the assembly modes of the samples
around it, a group solved by Newton's method started from the nearer sample's pose; between two samples in
different modes, on either side of the change point located between them, in that side's mode), and a variant
whose re-solve does not meet its own best sample keeps the peak of its samples.  A quantity that grows without
bound towards a singular position (the reactions next to a change point), or towards a position where friction
locks the mechanism, has no peak: it is reported as unbounded there (:func:`refine`, :attr:`Peak.unbounded`).
This module solves nothing itself: the forces it refines are solved again by
:meth:`linkwork.kinetostatics.Forces.at`, so that :class:`Forces` refines its own extremes
(:meth:`~linkwork.kinetostatics.Forces.bolts`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from linkwork.kinetostatics.reaction_forces import Forces

#: The zoom stops where the values at the ends of the bracket are within this fraction of the peak.
TOLERANCE = 1e-13
#: Angles evaluated in each round of the zoom (the bracket shrinks by (points + 1) / 2 a round): for one mechanism,
#: and for variants (few rounds where a round costs a solve's fixed time, few angles where it costs samples).
POINTS = (32, 8)
#: Rounds at most.
ROUNDS = 40
#: Distances (rad) from a refined peak at which the quantity is probed for growth without bound (:func:`refine`).
PROBES = 10.0 ** -np.arange(2.0, 7.0)
#: The least growth, decade on decade of those distances, of a quantity that grows without bound: as the distance
#: to the power -1/4 (a force near a singular position grows as its inverse, or its inverse square root).
GROWTH = 10.0**0.25
#: The normalised Jacobian determinant of some group at or below which a position is singular, for that rule.
NEAR_SINGULAR = 1e-6
#: Why a peak is unbounded, as the command line, the JSON and the report say it.
UNBOUNDED = (
    "unbounded: it grows without bound as the crank nears a singular position (a dead or change point) or one where "
    "friction locks the mechanism"
)


@dataclass(frozen=True)
class Peak:
    """Refined peaks of a quantity, ``(V,)`` each (NaN where no sample is finite).

    Attributes
    ----------
    value : ndarray
        The quantity's value there (with its sign); infinite where it grows without bound towards a singular
        position (:attr:`unbounded`).
    at : ndarray
        The drive coordinate (rad) where it occurs.
    """

    value: np.ndarray
    at: np.ndarray

    @property
    def unbounded(self) -> np.ndarray:
        """Where the quantity grows without bound towards the singular position at :attr:`at` (:func:`refine`):
        no peak, whatever a grid's samples give, ``(V,)``."""
        return np.isinf(self.value)


def refine(
    samples: np.ndarray,
    angles: np.ndarray,
    quantity: Callable[[np.ndarray], np.ndarray],
    kind: str = "abs",
    points: int = POINTS[1],
    singular: Callable[[np.ndarray], np.ndarray] | None = None,
    locked: Callable[[np.ndarray], np.ndarray] | None = None,
) -> Peak:
    """The peak of a quantity sampled ``(V, A)`` at the drive angles ``angles`` ``(A,)``, refined.

    Next to a singular position some quantities (the reactions in the pairs) grow without bound: the peak of the
    samples then only says how near to it a sample fell.  Where the refined peak lies at a singular position
    (``singular``) and the quantity keeps growing as the distance to it shrinks (from the peak, at each of
    :data:`PROBES`, by :data:`GROWTH` or more from decade to decade), it is unbounded: infinite, with its sign,
    at that position.

    Parameters
    ----------
    samples : ndarray, shape (V, A)
    angles : ndarray, shape (A,)
        Equally spaced over a whole turn (the ends are then neighbours), or any increasing or decreasing
        angles of a range.
    quantity : callable
        ``quantity(at) -> (V, K)``: the true value of every variant at its own angles ``at`` ``(V, K)``.
    kind : str
        ``"abs"``: the largest size ``|x|`` (the value returned keeps its sign); ``"max"``; ``"min"``.
    points : int
        Angles a round.  A row stops where its values agree; what the other rows do does not change it (a sweep's
        chunks give the numbers of the whole batch, bit for bit).
    singular : callable, optional
        ``singular(at) -> (V, K)`` bool: where the mechanism is at a singular position; without it no peak is
        unbounded there.
    locked : callable, optional
        ``locked(at) -> (V, K)`` bool: where friction locks the mechanism.  A refined peak within
        ``PROBES[-1]`` of a locked position is unbounded too: the forces grow without bound towards a lock, and the
        value at its edge is only where :data:`linkwork.kinetostatics.friction.LOCKING` draws the line.
    """
    sign = {"abs": 1.0, "max": 1.0, "min": -1.0}[kind]

    def objective(x: np.ndarray) -> np.ndarray:
        g = np.abs(x) if kind == "abs" else sign * x
        return np.where(np.isfinite(g), g, -np.inf)

    samples = np.atleast_2d(np.asarray(samples, dtype=float))
    g = objective(samples)
    rows = np.arange(len(g))
    i = np.argmax(g, axis=1)
    a, b, ga, gb = _bracket(g, np.asarray(angles, dtype=float), i)
    best, at, value = g[rows, i], np.asarray(angles, dtype=float)[i], samples[rows, i]
    none = ~np.isfinite(best)
    a, b = np.where(none, at, a), np.where(none, at, b)
    t = np.arange(1, points + 1) / (points + 1)
    done = none.copy()
    trusted = None
    for _ in range(ROUNDS):
        xs = a[:, None] + (b - a)[:, None] * t
        if trusted is None:  # the first round checks that the re-solve meets the cycle's own best sample
            raw = quantity(np.concatenate([xs, at[:, None]], axis=1))
            scale = np.max(np.where(np.isfinite(samples), np.abs(samples), 0.0), axis=1)
            trusted = np.abs(raw[:, -1] - value) <= 1e-9 * scale
            raw = raw[:, :-1]
        else:
            raw = quantity(xs)
        gv = np.where(trusted[:, None], objective(raw), -np.inf)
        X = np.concatenate([a[:, None], xs, b[:, None]], axis=1)
        G = np.concatenate([ga[:, None], gv, gb[:, None]], axis=1)
        j = np.argmax(G, axis=1)
        better = ~done & (G[rows, j] > best) & (j > 0) & (j < points + 1)
        best = np.where(better, G[rows, j], best)
        at = np.where(better, X[rows, j], at)
        value = np.where(better, raw[rows, np.clip(j - 1, 0, points - 1)], value)
        lo, hi = np.maximum(j - 1, 0), np.minimum(j + 1, points + 1)
        a, b = np.where(done, a, X[rows, lo]), np.where(done, b, X[rows, hi])
        ga, gb = np.where(done, ga, G[rows, lo]), np.where(done, gb, G[rows, hi])
        done |= ~trusted | (best - np.minimum(ga, gb) <= TOLERANCE * np.abs(best)) | (np.abs(b - a) <= 1e-15)
        if done.all():
            break
    endless = np.zeros(len(at), dtype=bool)
    if singular is not None:
        endless |= _unbounded(at, best, trusted & ~none, objective, quantity, singular)
    if locked is not None:
        endless |= ~none & np.asarray(locked(at[:, None] + [-PROBES[-1], PROBES[-1]])).any(axis=1)
    value = np.where(endless, sign * np.inf, value)
    value = np.where(np.isinf(value) & (kind == "abs"), np.copysign(np.inf, samples[rows, i]), value)
    return Peak(np.where(none, np.nan, value), np.where(none, np.nan, at))


def _unbounded(
    at: np.ndarray,
    best: np.ndarray,
    rows: np.ndarray,
    objective: Callable[[np.ndarray], np.ndarray],
    quantity: Callable[[np.ndarray], np.ndarray],
    singular: Callable[[np.ndarray], np.ndarray],
) -> np.ndarray:
    """Where the refined peaks ``at`` (their objective ``best``) of the ``rows`` ``(V,)`` lie at a singular position
    towards which the quantity grows without bound (:func:`refine`): ``(V,)``."""
    out = np.zeros(len(at), dtype=bool)
    if not rows.any():
        return out
    there = rows & np.asarray(singular(at[:, None]))[:, 0]
    if not there.any():
        return out
    near = np.concatenate([at[:, None] - PROBES, at[:, None] + PROBES], axis=1)
    g = objective(np.asarray(quantity(near)))
    g = np.maximum(g[:, : len(PROBES)], g[:, len(PROBES) :])  # (V, P): the larger side at each distance
    grows = np.all(g[:, 1:] >= GROWTH * g[:, :-1], axis=1) & np.all(g > 0, axis=1)
    return there & grows & (best >= g[:, -1])


def _bracket(g: np.ndarray, angles: np.ndarray, i: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The neighbours of the best samples ``i`` ``(V,)`` and the objective there: ``(a, b, g(a), g(b))``; over a
    whole turn of equal steps the ends are neighbours; a side without a neighbour (an end of a range) is the
    best sample itself."""
    n = len(angles)
    rows = np.arange(len(g))
    if n < 2:
        return angles[i], angles[i], g[rows, i], g[rows, i]
    step = angles[1] - angles[0]
    whole = n >= 3 and abs(abs(n * step) - 2 * np.pi) <= 1e-9
    if whole:
        below, above = (i - 1) % n, (i + 1) % n
        return angles[i] - step, angles[i] + step, g[rows, below], g[rows, above]
    below, above = np.maximum(i - 1, 0), np.minimum(i + 1, n - 1)
    return angles[below], angles[above], g[rows, below], g[rows, above]


def peaks(
    f: Forces,
    pick: Callable[[Forces], np.ndarray],
    kind: str = "abs",
    which: np.ndarray | None = None,
    variants: np.ndarray | None = None,
) -> Peak:
    """The refined peaks (see :func:`refine`) of quantities of the forces ``f``: ``pick(forces) -> (Q, V, A)``, the
    quantities of every variant at every sample; row ``r`` is quantity ``which[r]`` of variant ``variants[r]``
    (default: the one quantity of every variant).  The rows are solved again together, each at its own angles
    (:meth:`Forces.at <linkwork.kinetostatics.Forces.at>`).  ``(R,)``."""
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        values = np.asarray(pick(f))
    n_q, n_v, _ = values.shape
    variants = np.arange(n_v) if variants is None else np.asarray(variants, dtype=np.intp)
    which = np.zeros(len(variants), dtype=np.intp) if which is None else np.asarray(which, dtype=np.intp)
    rows = np.arange(len(which))

    def quantity(at: np.ndarray) -> np.ndarray:
        g = f.at(at, variants)
        if g is None:
            return np.full(at.shape, np.nan)
        return np.asarray(pick(g))[which, rows]

    def singular(at: np.ndarray) -> np.ndarray:
        kin = f.kinematics.at(at, variants)
        if kin is None or not kin.step_det:
            return np.zeros(at.shape, dtype=bool)
        with np.errstate(invalid="ignore"):
            return np.any([np.abs(d) <= NEAR_SINGULAR for d in kin.step_det], axis=0)

    def locked(at: np.ndarray) -> np.ndarray:
        g = f.at(at, variants)
        return np.zeros(at.shape, dtype=bool) if g is None or g.friction is None else g.friction.locked

    points = POINTS[1] if f.kinematics.variants else POINTS[0]
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        rough = f.friction is not None
        return refine(values[which, variants], f.angles, quantity, kind, points, singular, locked if rough else None)


def peak_of(f: Forces, pick: Callable[[Forces], np.ndarray], kind: str = "abs") -> Peak:
    """The refined peak of the quantity ``pick(forces) -> (V, A)`` of every variant of ``f`` (see :func:`refine`)."""
    return peaks(f, lambda g: pick(g)[None], kind)


def driving_torque(f: Forces) -> np.ndarray:
    """The driving torque of the (first) drive, ``(V, A)``, N m (from the power balance at singular samples)."""
    return f.driving_torque_all[..., 0]


def foundation_force(f: Forces) -> np.ndarray:
    """The size of the force on the foundation, ``(V, A)``, N (from the momentum theorem at singular samples)."""
    found = f.foundation_filled_all
    return np.hypot(found[..., 0], found[..., 1])


def torque_peak(f: Forces) -> Peak:
    """The peak driving torque (largest size, with its sign) of every variant of ``f``, refined: ``(V,)``; found once
    per result (the command line, its JSON and the report ask for it more than once)."""
    found = f.__dict__.get("_torque_peak")
    if found is None:
        found = peak_of(f, driving_torque)
        object.__setattr__(f, "_torque_peak", found)  # frozen: kept as the result's cached values are
    return found


def foundation_peak(f: Forces) -> Peak:
    """The peak size of the force on the foundation of every variant of ``f``, refined: ``(V,)``."""
    return peak_of(f, foundation_force, "max")


def _first(f: Forces, pick: Callable[[Forces], np.ndarray], count: int, kind: str) -> Peak:
    """The refined peaks of ``count`` quantities ``pick(forces) -> (Q, V, A)`` of the first variant of ``f``."""
    return peaks(f, pick, kind, which=np.arange(count), variants=np.zeros(count, dtype=np.intp))


def pair_force_peaks(f: Forces, pairs: list[int]) -> Peak:
    """The largest size of the force in each of ``pairs`` (N) of the first variant and where, refined:
    ``(len(pairs),)``."""

    def sizes(g: Forces) -> np.ndarray:
        return np.stack([np.hypot(*np.moveaxis(g.pair_force(k), -1, 0)) for k in pairs])

    return _first(f, sizes, len(pairs), "max") if pairs else Peak(np.empty(0), np.empty(0))


def pair_moment_peaks(f: Forces, pairs: list[int]) -> Peak:
    """The moment of largest size (with its sign, N m) that each of the prismatic ``pairs`` puts on its slider, of
    the first variant, and where, refined: ``(len(pairs),)``."""

    def moments(g: Forces) -> np.ndarray:
        return np.stack([g.multipliers[..., 2 * k] for k in pairs])

    return _first(f, moments, len(pairs), "abs") if pairs else Peak(np.empty(0), np.empty(0))


def shaking_peaks(f: Forces) -> Peak:
    """The largest size of the shaking force (N) and the shaking moment of largest size (with its sign, N m) of the
    first variant, and where, refined: ``(2,)``."""

    def both(g: Forces) -> np.ndarray:
        force = g.shaking_force_all
        return np.stack([np.hypot(force[..., 0], force[..., 1]), g.shaking_moment_all])

    return _first(f, both, 2, "abs")  # a size is its own largest size
