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

Variants are refined together, each at its own angles, in one solve a round
(:func:`linkwork.motion.solve.run_each`: the NumPy kernels, the dyads in the modes of the assembly
pose); a variant whose re-solve does not meet its own best sample (another mode past a change point)
keeps the peak of its samples, as do variants with a group solved by Newton's method.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from linkwork.kinetostatics.forces import Forces, forces_of
from linkwork.motion.kinematics import Kinematics, kinematics
from linkwork.motion.solve import run_each
from linkwork.structure.parameters import Geometry

#: The zoom stops where the values at the ends of the bracket are within this fraction of the peak.
TOLERANCE = 1e-13
#: Angles evaluated in each round of the zoom (the bracket shrinks by (points + 1) / 2 a round): for one mechanism,
#: and for variants (few rounds where a round costs a solve's fixed time, few angles where it costs samples).
POINTS = (32, 8)
#: Rounds at most.
ROUNDS = 40


@dataclass(frozen=True)
class Peak:
    """Refined peaks of a quantity, ``(V,)`` each (NaN where no sample is finite).

    Attributes
    ----------
    value : ndarray
        The quantity's value there (with its sign).
    at : ndarray
        The drive coordinate (rad) where it occurs.
    """

    value: np.ndarray
    at: np.ndarray


def refine(
    samples: np.ndarray,
    angles: np.ndarray,
    quantity: Callable[[np.ndarray], np.ndarray],
    kind: str = "abs",
    points: int = POINTS[1],
) -> Peak:
    """The peak of a quantity sampled ``(V, A)`` at the drive angles ``angles`` ``(A,)``, refined.

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
    return Peak(np.where(none, np.nan, value), np.where(none, np.nan, at))


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


def forces_at(f: Forces) -> Callable[[np.ndarray], Forces | None]:
    """``solve(at)``: the :class:`~linkwork.kinetostatics.Forces` of the variants of ``f`` at their own drive angles
    ``at`` ``(V, K)``, at the uniform speed of ``f``: for one mechanism at its angles (:func:`linkwork.kinematics`),
    for variants in one solve (NumPy kernels, :func:`linkwork.motion.solve.run_each`); None where the variants
    have a group solved by Newton's method (their peaks then stay those of the samples)."""
    kin = f.kinematics
    mech, rate = kin.mechanism, float(kin.rates[0, 0])

    def solve(at: np.ndarray) -> Forces | None:
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            if not kin.variants:
                return forces_of(kinematics(mech, at[0], speed=rate))
            geom = Geometry(*(np.ascontiguousarray(x.transpose(2, 3, 0, 1)) for x in (kin.local, kin.origin, kin.axis)))
            state = run_each(mech, geom, at, rate)
            if state is None:
                return None
            made = Kinematics._made(
                mechanism=mech, drive=at[0][:, None], rates=np.full((at.shape[1], 1), rate), q=state.q, v=state.v,
                a=state.a, cos=state.cos, sin=state.sin, local=state.local, axis=state.axis, origin=state.origin,
                valid_all=state.valid, events=(), variants=True, masses=kin.masses,
            )  # fmt: skip
            return forces_of(made)

    return solve


def peak_of(f: Forces, pick: Callable[[Forces], np.ndarray], kind: str = "abs") -> Peak:
    """The refined peak of the quantity ``pick(forces) -> (V, A)`` of every variant of ``f`` (see :func:`refine`)."""
    solve = forces_at(f)

    def quantity(at: np.ndarray) -> np.ndarray:
        g = solve(at)
        return np.full(at.shape, np.nan) if g is None else pick(g)

    points = POINTS[1] if f.kinematics.variants else POINTS[0]
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        return refine(pick(f), f.angles, quantity, kind, points)


def driving_torque(f: Forces) -> np.ndarray:
    """The driving torque of the (first) drive, ``(V, A)``, N m (from the power balance at singular samples)."""
    return f._torque_all[..., 0]


def foundation_force(f: Forces) -> np.ndarray:
    """The size of the force on the foundation, ``(V, A)``, N (from the momentum theorem at singular samples)."""
    found = f._foundation_filled
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


def peaks_of(f: Forces, pick: Callable[[Forces], np.ndarray], kind: str = "abs") -> Peak:
    """The refined peaks of several quantities of one mechanism (``f`` without variants) at once: ``pick(forces) ->
    (Q, A)``, one row a quantity; each row's angles are solved together in one solve a round.  ``(Q,)``."""
    kin = f.kinematics
    if kin.variants:
        raise ValueError("peaks_of: one mechanism (no variants); peak_of refines variants")
    mech, rate = kin.mechanism, float(kin.rates[0, 0])

    def quantity(at: np.ndarray) -> np.ndarray:
        rows, k = at.shape
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            values = pick(forces_of(kinematics(mech, at.ravel(), speed=rate)))  # (Q, Q K)
        return values.reshape(rows, rows, k)[np.arange(rows), np.arange(rows)]

    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        return refine(pick(f), f.angles, quantity, kind, POINTS[0])


def pair_force_peaks(f: Forces, pairs: list[int]) -> Peak:
    """The largest size of the force in each of ``pairs`` (N) of one mechanism and where, refined: ``(len(pairs),)``."""

    def sizes(g: Forces) -> np.ndarray:
        return np.stack([np.hypot(*g.pair_force(k)[0].T) for k in pairs]) if pairs else np.empty((0, len(g.angles)))

    return peaks_of(f, sizes, "max")
