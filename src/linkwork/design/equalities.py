"""Designs that meet metrics exactly: Newton's method on equality constraints over named parameters.

The optimiser (:mod:`linkwork.design.optimizer`) bounds metrics by inequalities and stops at its tolerance;
synthesis needs a stroke or a time ratio met to the last digits.  Here ``k`` unknowns map onto the values of
named parameters, and ``k`` metrics (:data:`~linkwork.design.metrics.METRICS`, the same columns a sweep or an
optimisation reports) must equal their targets.  Many designs (the members of a family) are solved at once:
each Newton step evaluates every member and its ``k`` finite-difference neighbours in one batch of variants
(:func:`~linkwork.design.evaluate.evaluate`).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from linkwork.design.evaluate import evaluate
from linkwork.design.metrics import MetricRequest, parse_metrics
from linkwork.structure.model import Mechanism

#: Relative residual at which a member counts as solved.
SOLVED = 1e-12


@dataclass(frozen=True)
class Met:
    """Solutions of :func:`meet`.

    Attributes
    ----------
    unknowns : ndarray, shape (M, k)
        The unknowns of each member; NaN rows where it did not converge.
    values : ndarray, shape (M, P)
        The parameters' values (SI) of each member, as ``values_of`` maps the unknowns.
    metrics : dict
        Column -> (M,) of the equalities' metrics and the others asked for, at the solution.
    residual : ndarray, shape (M,)
        The largest relative residual of each member's equalities.
    solved : ndarray of bool, shape (M,)
    """

    unknowns: np.ndarray
    values: np.ndarray
    metrics: dict[str, np.ndarray]
    residual: np.ndarray
    solved: np.ndarray


#: Newton steps at most of :func:`meet`.
ITERATIONS = 40


def meet(
    mech: Mechanism,
    paths: Sequence[str],
    values_of: Callable[[np.ndarray, np.ndarray], np.ndarray],
    start: np.ndarray,
    equalities: Mapping[str, np.ndarray | float],
    *,
    scales: np.ndarray,
    metrics: Sequence[str] = (),
    steps: int = 720,
) -> Met:
    """Unknowns with ``metric == target`` for every equality, by Newton's method from ``start``.

    Parameters
    ----------
    mech : Mechanism
    paths : list of str
        The named parameters (:func:`linkwork.parameters`) the unknowns set.
    values_of : callable
        ``values_of(u, member)``: unknowns ``(N, k)`` of the members ``member`` (``(N,)`` indices into
        ``start``) -> the parameters' values ``(N, len(paths))``, SI.
    start : ndarray, shape (M, k)
        Where each member's iteration starts.
    equalities : dict
        Metric column (``"stroke:guide_E"``, ``"knife_overlap"``) -> its target (SI), a number or ``(M,)``;
        ``k`` of them.
    scales : ndarray, shape (k,)
        A typical size of each unknown (its finite-difference step is 1e-7 of it, its Newton step at most 0.5
        of it).
    metrics : list of str
        More metrics to evaluate at the solutions.
    steps : int
        Crank angles of the turn.  Newton's method takes :data:`ITERATIONS` steps at most.

    Returns
    -------
    Met
    """
    columns = list(equalities)
    requests = parse_metrics(columns, mech)
    extra = parse_metrics(list(dict.fromkeys([*columns, *metrics, "assembles"])), mech)
    start = np.atleast_2d(np.asarray(start, dtype=float))
    m, k = start.shape
    if len(columns) != k:
        raise ValueError(f"{k} unknowns need {k} equalities, got {len(columns)}")
    target = np.stack([np.broadcast_to(np.asarray(equalities[c], dtype=float), (m,)) for c in columns], axis=1)
    size = np.maximum(np.abs(target), 1e-300)
    scales = np.asarray(scales, dtype=float)
    problem = _Problem(mech, paths, values_of, scales, requests, steps)
    u = start.copy()
    last = np.full_like(u, np.nan)  # the last point that assembled, and the step taken from it
    step = np.zeros_like(u)
    active = np.ones(m, dtype=bool)
    residual = np.full((m, k), np.nan)
    for _ in range(ITERATIONS):
        rows = np.flatnonzero(active)
        if not len(rows):
            break
        r, jac = _linearised(problem, u[rows], rows, target[rows], size[rows])
        residual[rows] = r
        done = np.all(np.abs(r) <= SOLVED, axis=1)
        bad = ~np.all(np.isfinite(jac), axis=(1, 2)) | ~np.all(np.isfinite(r), axis=1)
        # a step that left the mechanism unassembled: back to the last point, half the step; give up past 1/1000
        back = bad & np.isfinite(last[rows, 0]) & (np.max(np.abs(step[rows]) / scales, axis=1) > 1e-4)
        step[rows[back]] /= 2.0
        u[rows[back]] = last[rows[back]] + step[rows[back]]
        active[rows[done | (bad & ~back)]] = False
        go = ~(done | bad)
        if go.any():
            du = _newton(jac[go], r[go])
            du = du / np.maximum(np.max(np.abs(du) / (0.5 * scales), axis=1, initial=0.0), 1.0)[:, None]
            du = np.where(np.isfinite(du), du, 0.0)
            last[rows[go]], step[rows[go]] = u[rows[go]], du
            u[rows[go]] += du
    worst = np.max(np.abs(residual), axis=1)
    solved = worst <= 10 * SOLVED
    u = np.where(solved[:, None], u, np.nan)
    values = values_of(np.where(solved[:, None], u, start), np.arange(m))
    final = evaluate(mech, list(paths), values, extra, steps)
    final = {c: np.where(solved, v, np.nan) for c, v in final.items()}
    return Met(u, values, final, worst, solved)


class _Problem(NamedTuple):
    """What every linearisation of :func:`meet` evaluates: the mechanism, the paths of the unknowns, how their
    values make variants, their scales, the metrics asked and the crank angles of a turn."""

    mech: Mechanism
    paths: Sequence[str]
    values_of: Callable[[np.ndarray, np.ndarray], np.ndarray]
    scales: np.ndarray
    requests: list[MetricRequest]
    steps: int


def _linearised(problem: _Problem, u, rows, target, size) -> tuple:  # noqa: ANN001
    """The relative residuals ``(n, k)`` of the members ``rows`` at ``u`` and their Jacobian ``(n, k, k)``
    by forward differences: every member and its ``k`` neighbours in one batch of variants."""
    mech, paths, values_of, scales, requests, steps = problem
    n, k = u.shape
    probe = np.repeat(u, k + 1, axis=0).reshape(n, k + 1, k)
    probe[:, 1:, :] += np.eye(k) * scales * 1e-7
    cols = evaluate(mech, list(paths), values_of(probe.reshape(-1, k), np.repeat(rows, k + 1)), requests, steps)
    got = np.stack([cols[r.column] for r in requests[:k]], axis=1).reshape(n, k + 1, k)
    r = (got[:, 0, :] - target) / size
    jac = (got[:, 1:, :] - got[:, :1, :]).transpose(0, 2, 1) / (scales * 1e-7) / size[:, :, None]
    return r, jac


def _newton(jac: np.ndarray, r: np.ndarray) -> np.ndarray:
    """The Newton steps ``(n, k)`` of the linearisations ``jac`` ``(n, k, k)``, ``r`` ``(n, k)`` (least squares
    where a Jacobian is singular)."""
    out = np.full(r.shape, np.nan)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        for i, (j, x) in enumerate(zip(jac, r, strict=True)):
            out[i] = np.linalg.lstsq(j, -x, rcond=None)[0]
    return out
