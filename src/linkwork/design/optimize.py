"""Optimisation of a design: the best variant in the ranges, under constraints on the metrics.

Differential evolution (:func:`scipy.optimize.differential_evolution`), the
whole population evaluated at once as a batch of design variants
(``vectorized=True, updating="deferred"``).  The constraints are one
:class:`~scipy.optimize.NonlinearConstraint`, the sum of the relative
violations of all of them (a variant that does not assemble over the whole
turn violates it too), so that a feasible design always beats an infeasible
one and infeasible ones are ranked by how far they are from feasibility.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from linkwork.design.evaluate import evaluate
from linkwork.design.metrics import MetricRequest, parse_metrics
from linkwork.design.plan import Vary
from linkwork.design.sweep import SweepTable, _declared, _source, _varies
from linkwork.errors import DesignError
from linkwork.units import KINDS


@dataclass(frozen=True)
class Constraint:
    """``metric >= bound`` or ``metric <= bound`` (SI)."""

    text: str
    column: str
    sense: str  # ">=" or "<="
    bound: float

    def violation(self, value: np.ndarray) -> np.ndarray:
        """Relative violation, >= 0; large where the metric is NaN."""
        scale = abs(self.bound) if self.bound != 0 else 1.0
        gap = (self.bound - value) if self.sense == ">=" else (value - self.bound)
        return np.where(np.isnan(value), 1e3, np.maximum(gap, 0.0) / scale)


_CONSTRAINT = re.compile(r"^\s*([A-Za-z_][A-Za-z0-9_:.\-]*)\s*(>=|<=|>|<)\s*(.+?)\s*$")


def parse_constraints(texts: list[str], mech: Any, declared: dict[str, str]) -> list[Constraint]:
    """Read ``"METRIC>=VALUE"`` / ``"METRIC<=VALUE"`` (VALUE with a unit, or in the file's units)."""
    from linkwork.design.metrics import METRICS
    from linkwork.errors import UnitParseError
    from linkwork.units import parse_quantity

    problems, out = [], []
    for text in texts:
        m = _CONSTRAINT.match(text)
        if m is None:
            problems.append(
                f'--constraint "{text}": expected METRIC>=VALUE or METRIC<=VALUE, e.g. "knife_overlap>=5mm"'
            )
            continue
        column, sense, value = m.group(1), m.group(2), m.group(3)
        metric = METRICS.get(column.partition(":")[0])
        try:
            if metric is not None and metric.kind is not None:
                bound = parse_quantity(value, metric.kind, declared)
            else:
                bound = float(value)
                if not math.isfinite(bound):
                    raise ValueError
        except (UnitParseError, ValueError) as exc:
            why = str(exc) if isinstance(exc, UnitParseError) else f'expected a number, got "{value}"'
            problems.append(f'--constraint "{text}": {why}')
            continue
        out.append(Constraint(text, column, ">=" if sense.startswith(">") else "<=", bound))
    if problems:
        raise DesignError(problems)
    return out


@dataclass(frozen=True)
class Optimum:
    """The best design found.

    Attributes
    ----------
    values : dict
        Path -> value (SI) of each varied dimension.
    metrics : dict
        Column -> value (SI) of the objective, the constrained metrics and any others asked for.
    units : dict
        SI unit of every value and metric.
    objective : str
    feasible : bool
        Whether every constraint holds (and it assembles over the whole turn).
    initial : dict
        The metrics of the file's own design (where it lies in the ranges; else empty).
    evaluations : int
        Number of designs evaluated.
    generations : int
    converged : bool
        Whether differential evolution met its tolerance; False where it stopped at its generation limit
        (``maxiter``): the best design found then, not necessarily the optimum.
    message : str
        The optimiser's.
    out : Path or None
        The mechanism file written with the best values.
    evaluated : SweepTable or None
        Every design the optimiser evaluated, in order: ``variant`` (its number), the values, the
        metrics and ``violation`` (the sum of the relative violations of the constraints; 0: feasible).
    """

    values: dict[str, float]
    metrics: dict[str, float]
    units: dict[str, str]
    objective: str
    feasible: bool
    initial: dict[str, float]
    evaluations: int
    generations: int
    message: str
    out: Path | None = None
    converged: bool = True
    evaluated: SweepTable | None = None

    def as_dict(self) -> dict[str, Any]:
        return {
            "objective": self.objective,
            "feasible": self.feasible,
            "values": self.values,
            "metrics": self.metrics,
            "initial": self.initial,
            "units": self.units,
            "evaluations": self.evaluations,
            "generations": self.generations,
            "converged": self.converged,
            "message": self.message,
            "out": str(self.out) if self.out is not None else None,
        }


def optimize(
    mechanism: Any,
    vary: Any,
    objective: str,
    constraints: list[str] = (),  # type: ignore[assignment]
    *,
    maximize: bool = False,
    metrics: list[str] = (),  # type: ignore[assignment]
    steps: int = 360,
    seed: int = 0,
    popsize: int = 15,
    maxiter: int = 100,
    tol: float = 1e-3,
    out: str | Path | None = None,
) -> Optimum:
    """The design in the ranges with the smallest (or largest) objective under the constraints.

    Parameters
    ----------
    mechanism : str, Path, Spec or Mechanism
        A mechanism file, a bundled example, a description or a compiled mechanism
        (:mod:`linkwork.api`); writing ``out`` needs its description.
    vary : dict or list of str
        Ranges as for :func:`linkwork.sweep`; a COUNT, if given, is ignored.
    objective : str
        A metric (:data:`~linkwork.design.metrics.METRICS`).
    constraints : list of str
        ``"knife_overlap>=5mm"``, ``"peak_foundation_force<=20kN"``: bounds with units, or bare
        numbers in the file's units (SI for metrics without a unit in the file, such as torques).
    maximize : bool
        Largest objective instead of smallest.
    metrics : list of str
        More metrics to report for the best design.
    steps : int
        Crank angles over the turn for every evaluation.
    seed, popsize, maxiter, tol
        Of :func:`scipy.optimize.differential_evolution`.
    out : str or Path, optional
        Write the mechanism file with the best values here (the original file, its comments kept).

    Returns
    -------
    Optimum
    """
    from scipy.optimize import NonlinearConstraint, differential_evolution

    mech, spec = _source(mechanism)
    problems: list[str] = []
    varies: list[Vary] = []
    cons: list[Constraint] = []
    requests: list[MetricRequest] = []
    try:
        varies = _varies(vary, mech, spec, count_required=False)
    except DesignError as exc:
        problems += exc.problems
    try:
        cons = parse_constraints(list(constraints), mech, _declared(spec))
    except DesignError as exc:
        problems += exc.problems
    names = [objective, *(c.column for c in cons), *metrics, "assembles"]
    try:
        requests = parse_metrics(list(dict.fromkeys(names)), mech)
    except DesignError as exc:
        problems += exc.problems
    for v in varies:
        if v.start == v.stop:
            problems.append(f'--vary "{v.path}": START equals STOP; nothing to optimise over')
    if out is not None and spec is None:
        problems.append("writing the optimised file needs the mechanism's description (a file, an example or a Spec)")
    elif out is not None:
        from linkwork.design.store import cannot_write

        why = cannot_write(out)
        if why:
            problems.append(f'--out "{out}": {why}')
    if problems:
        raise DesignError(problems)
    paths = [v.path for v in varies]
    bounds = [(v.start, v.stop) for v in varies]
    cache: dict[bytes, dict[str, float]] = {}
    count = [0]
    history: list[tuple[np.ndarray, dict[str, np.ndarray]]] = []

    def metrics_of(x: np.ndarray) -> list[dict[str, float]]:
        pop = np.atleast_2d(np.asarray(x, dtype=float).T)  # (S, k)
        keys = [row.tobytes() for row in pop]
        new = [i for i, key in enumerate(keys) if key not in cache]
        if new:
            if len(cache) > 50_000:
                cache.clear()
            cols = evaluate(mech, paths, pop[new], requests, steps)
            count[0] += len(new)
            history.append((pop[new], cols))
            for j, i in enumerate(new):
                cache[keys[i]] = {c: float(v[j]) for c, v in cols.items()}
        return [cache[key] for key in keys]

    def violation(cols: dict[str, np.ndarray]) -> np.ndarray:
        """Sum of the relative violations, (S,); a design that does not assemble violates by 1000."""
        total = 1e3 * (1.0 - np.asarray(cols["assembles"], dtype=float))
        for c in cons:
            total = total + c.violation(np.asarray(cols[c.column], dtype=float))
        return total

    def columns(rows: list[dict[str, float]]) -> dict[str, np.ndarray]:
        return {name: np.array([r[name] for r in rows]) for name in rows[0]}

    sign = -1.0 if maximize else 1.0

    def fun(x: np.ndarray) -> np.ndarray:
        rows = metrics_of(x)
        f = sign * np.array([r[objective] for r in rows])
        return np.where(np.isnan(f), 1e300, f)

    start = np.array([_file_value(mech, p) for p in paths])
    inside = bool(np.all((start >= [b[0] for b in bounds]) & (start <= [b[1] for b in bounds])))
    with np.errstate(invalid="ignore"):
        result = differential_evolution(
            fun,
            bounds,
            constraints=NonlinearConstraint(lambda x: violation(columns(metrics_of(x)))[None], -np.inf, 0.0),
            vectorized=True,
            updating="deferred",
            rng=seed,
            popsize=popsize,
            maxiter=maxiter,
            tol=tol,
            polish=False,
            x0=start if inside else None,
        )
    best = np.atleast_1d(result.x)
    row = evaluate(mech, paths, best[None], requests, steps)
    found = {c: float(v[0]) for c, v in row.items()}
    initial = {}
    if inside:
        initial = {c: float(v[0]) for c, v in evaluate(mech, paths, start[None], requests, steps).items()}
    feasible = bool(violation(row)[0] == 0)
    units = {v.path: KINDS[v.kind][1] for v in varies} | {r.column: r.metric.unit for r in requests}
    written = None
    if out is not None:
        from linkwork.structure.parameters import write_file

        try:
            written = write_file(mech, dict(zip(paths, best.tolist(), strict=True)), out)
        except OSError as exc:
            raise DesignError([f'--out "{out}": cannot write ({exc})']) from None
    table = None
    if history:
        values = np.concatenate([h[0] for h in history])
        cols = {"variant": np.arange(len(values), dtype=np.int64)}
        cols.update({p: values[:, j] for j, p in enumerate(paths)})
        for r in requests:
            cols[r.column] = np.concatenate([h[1][r.column] for h in history])
        cols["violation"] = violation(cols)
        table = SweepTable(cols, {"variant": "1", "violation": "1", **units}, {"objective": objective})
    return Optimum(
        dict(zip(paths, best.tolist(), strict=True)),
        found,
        units,
        objective,
        feasible,
        initial,
        count[0],
        int(getattr(result, "nit", 0)),
        str(result.message),
        out=written,
        evaluated=table,
        converged=bool(result.success),
    )


def _file_value(mech: Any, path: str) -> float:
    from linkwork.structure.parameters import parameter

    return parameter(mech, path).value
