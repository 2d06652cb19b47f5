"""What the analysis measures of a mechanism for the requirements of its kind (:func:`measure`): the one measurement
that a synthesised file's verification, its rounding tolerances and the report's requirements section read.

Over a solved turn of the crank: the working member's stroke or swing and the time ratio
(:func:`linkwork.motion.analysis.extremes`, refined between the samples by the quintic through the values and
both derivatives), and the least transmission angle of the dyads over the turn
(:func:`linkwork.motion.analysis.transmission`), refined between the samples by solving the mechanism again
(:func:`linkwork.kinetostatics.peaks.refine`) about every sampled local least that could be the least of the
turn, so that neither the grid nor the closed form's idea of where the extreme lies decides the value; then the
kind's own measurement (the shears' knives, :func:`knives`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from linkwork.motion.kinematic_analysis import Kinematics
    from linkwork.spec.schema import Spec

#: A kind's own measurement of a solved turn, beside what :func:`measure` measures of every kind: ``own(kin, spec)
#: -> {name: (V,) array}`` over the variants of ``kin`` (:attr:`linkwork.synthesis.kinds.Kind.measure`: the shears'
#: :func:`knives`); ``spec`` is the file ``kin`` solves.
Own = Callable[["Kinematics", "Spec"], dict[str, np.ndarray]]

#: The sampled local leasts of a transmission angle refined at most, the lowest first (two for a crank-rocker whose
#: extremes at the crank in line with the frame are made equal, four for a slotted lever's rod).
CANDIDATES = 6


def measure(kin: Kinematics, spec: Spec, own: Own | None = None) -> list[dict[str, float]]:
    """What the analysis measures of the mechanism ``spec`` solved over a whole turn in ``kin``, for the requirements
    of its kind: one mapping per variant of ``kin``.

    Parameters
    ----------
    kin : Kinematics
        A whole turn of the crank in equal steps (``steps=``), any variants.
    spec : Spec
        The file ``kin`` solves (the kind's ``own`` measurement reads its parts' names).
    own : callable, optional
        The kind's own measurement beside the common one (:data:`Own`).

    Returns
    -------
    list of dict
        Per variant: ``stroke`` (m) or ``swing`` (rad) of the working member and its ``time_ratio``; the
        ``max_pressure_angle`` (rad: 90 deg less the least transmission angle of the dyads driving a slider, else
        of all) and the ``min_transmission_angle`` (rad, of every dyad); then the kind's own quantities.
    """
    from linkwork.motion.analysis import extremes, transmission, working

    n = kin.valid_all.shape[0]
    out: list[dict[str, float]] = [{} for _ in range(n)]
    members = working(kin.mechanism)
    for v in range(n):
        found = {e.name: e for e in extremes(kin, v)}
        if members and members[0].name in found:
            e = found[members[0].name]
            out[v]["stroke" if e.kind == "slider" else "swing"] = e.stroke
            out[v]["time_ratio"] = e.time_ratio
    labels = list(transmission(kin))
    if labels:
        sliding = [k for k in labels if k.endswith("RRP")] or labels
        least = least_transmission(kin, [sliding, labels])
        for v in range(n):
            out[v]["max_pressure_angle"] = math.pi / 2 - float(least[0, v])
            out[v]["min_transmission_angle"] = float(least[1, v])
    if own is not None:
        for name, values in own(kin, spec).items():
            for v in range(n):
                out[v][name] = float(values[v])
    return out


def least_transmission(kin: Kinematics, groups: list[list[str]]) -> np.ndarray:
    """The least over the turn of ``kin`` of the least transmission angle of each group of dyads (labels of
    :func:`~linkwork.motion.analysis.transmission`), for every variant, rad, ``(G, V)``.

    Each sampled local least within the largest step between two samples of the global one (where the curve
    between the samples can dip below it) is refined by solving the mechanism again between its neighbours
    (:func:`~linkwork.kinetostatics.peaks.refine`, the value to about 1e-13 of it); the least of them is the value."""
    from linkwork.kinetostatics.peaks import POINTS, refine
    from linkwork.motion.analysis import transmission

    mu = {k: np.atleast_2d(v) for k, v in transmission(kin).items()}
    samples = np.stack([np.min(np.stack([mu[k] for k in g]), axis=0) for g in groups])  # (G, V, A)
    rows = [(g, v, i) for g in range(len(groups)) for v in range(samples.shape[1]) for i in _leasts(samples[g, v])]
    out = np.full(samples.shape[:2], np.nan)
    if not rows:  # no dyad assembles anywhere on the turn
        return out
    n = samples.shape[-1]
    windows = np.full((len(rows), n), np.nan)
    for r, (g, v, i) in enumerate(rows):
        near = [(i - 1) % n, i, (i + 1) % n]
        windows[r, near] = samples[g, v, near]
    variants = np.array([v for _, v, _ in rows], dtype=np.intp)

    def quantity(at: np.ndarray) -> np.ndarray:
        again = kin.at(at, variants)
        if again is None:
            return np.full(at.shape, np.nan)
        m = transmission(again)
        return np.stack([np.min([m[k][r] for k in groups[g]], axis=0) for r, (g, _, _) in enumerate(rows)])

    points = POINTS[1] if samples.shape[1] > 1 else POINTS[0]
    with np.errstate(invalid="ignore"):
        peak = refine(windows, np.asarray(kin.angles, dtype=float), quantity, "min", points)
    for r, (g, v, _) in enumerate(rows):
        out[g, v] = np.fmin(out[g, v], peak.value[r])
    return out


def _leasts(s: np.ndarray) -> list[int]:
    """Indices of the sampled local leasts of the periodic samples ``s`` ``(A,)`` whose curve may hold the least
    of the turn: within the largest step between neighbouring samples of the least sample, at most
    :data:`CANDIDATES`, the lowest first (the least sample alone where the samples are flat)."""
    if not np.isfinite(s).any():
        return []
    low = np.where(np.isfinite(s), s, np.inf)
    before, after = np.roll(low, 1), np.roll(low, -1)
    with np.errstate(invalid="ignore"):
        band = float(np.nanmax(np.abs(np.diff(np.append(s, s[0])))))
    local = np.flatnonzero((low <= before) & (low <= after) & (low <= np.min(low) + band))
    order = local[np.argsort(low[local], kind="stable")][:CANDIDATES]
    return [int(i) for i in order] or [int(np.argmin(low))]


def knives(kin: Kinematics, spec: Spec) -> dict[str, np.ndarray]:
    """The knives' strokes, K, overlap and opening of the shears ``spec`` solved in ``kin`` as the design metrics
    measure them, each knife's stroke along its guide as the file names it
    (:func:`~linkwork.spec.shears.shears_parts`): ``(V,)`` each, over the variants of ``kin``."""
    from linkwork.design.evaluate import Evaluation
    from linkwork.design.metrics import METRICS
    from linkwork.errors import SynthesisError
    from linkwork.spec.shears import shears_parts

    found = shears_parts(spec)
    if isinstance(found, str):
        raise SynthesisError(f"double-cut shears: the mechanism's file has no {found}")
    upper, lower = found.guides
    ev = Evaluation(kin)

    def one(name: str, arg: str | None = None) -> np.ndarray:
        return np.ravel(METRICS[name].compute(ev, arg))

    return {
        "upper_stroke": one("stroke", upper),
        "lower_stroke": one("stroke", lower),
        "time_ratio": one("working_time_ratio"),
        "overlap": one("knife_overlap"),
        "opening": one("knife_clearance"),
    }
