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
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from linkwork.api import MechanismLike, mechanism_of
from linkwork.design.evaluate import evaluate
from linkwork.design.metrics import METRICS, MetricRequest, parse_metrics
from linkwork.design.plan import Ranges, Vary, read_varies
from linkwork.design.store import cannot_write
from linkwork.design.sweeps import Columns, SweepTable
from linkwork.errors import DesignError, UnitParseError
from linkwork.limits import TURN_STEPS
from linkwork.spec.edit import write_text
from linkwork.spec.reader import described
from linkwork.structure.model import Mechanism
from linkwork.structure.parameters import file_text, file_units, parameter
from linkwork.units import KINDS, parse_quantity


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


def parse_constraints(texts: list[str], mech: Mechanism, declared: dict[str, str]) -> list[Constraint]:
    """Read ``"METRIC>=VALUE"`` / ``"METRIC<=VALUE"`` (VALUE with a unit, or in the file's units)."""
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
    mechanism: MechanismLike,
    vary: Ranges,
    objective: str,
    constraints: Sequence[str] = (),
    *,
    maximize: bool = False,
    metrics: Sequence[str] = (),
    steps: int = TURN_STEPS,
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

    Examples
    --------
    >>> import linkwork as lw
    >>> best = lw.optimize("four-bar", {"links.crank.length": ("90 mm", "110 mm")}, "swing",
    ...                    maximize=True, steps=36, maxiter=3, popsize=4)  # doctest: +SKIP

    Returns
    -------
    Optimum
    """
    mech = mechanism_of(mechanism, "mechanism")
    problem = _Problem.of(mech, vary, objective, constraints, metrics, maximize, steps, out)
    designs = _Designs(problem)
    start = np.array([parameter(problem.mech, p).value for p in problem.paths])
    lo, hi = np.array(problem.bounds).T
    inside = bool(np.all((start >= lo) & (start <= hi)))
    result = _run(problem, designs, start if inside else None, seed=seed, popsize=popsize, maxiter=maxiter, tol=tol)
    best = np.atleast_1d(result.x)
    row = evaluate(problem.mech, problem.paths, best[None], problem.requests, problem.steps)
    initial = {}
    if inside:
        initial = _first(evaluate(problem.mech, problem.paths, start[None], problem.requests, problem.steps))
    written = _write(problem, best, out) if out is not None else None
    return Optimum(
        values=dict(zip(problem.paths, best.tolist(), strict=True)),
        metrics=_first(row),
        units=problem.units,
        objective=objective,
        feasible=bool(problem.violation(row)[0] == 0),
        initial=initial,
        evaluations=designs.count,
        generations=int(getattr(result, "nit", 0)),
        message=str(result.message),
        out=written,
        converged=bool(result.success),
        evaluated=designs.table(),
    )


# ---------------------------------------------------------------- the problem


@dataclass(frozen=True)
class _Problem:
    """An optimisation, read and checked.

    Attributes
    ----------
    mech : Mechanism
    varies : list of Vary
        The ranges searched.
    requests : list of MetricRequest
        The objective, the constrained metrics, the others asked for and ``assembles``.
    constraints : list of Constraint
    objective : str
    sign : float
        1 to minimise the objective, -1 to maximise it.
    steps : int
    """

    mech: Mechanism
    varies: list[Vary]
    requests: list[MetricRequest]
    constraints: list[Constraint]
    objective: str
    sign: float
    steps: int

    @classmethod
    def of(
        cls,
        mech: Mechanism,
        vary: Ranges,
        objective: str,
        constraints: Sequence[str],
        metrics: Sequence[str],
        maximize: bool,
        steps: int,
        out: str | Path | None,
    ) -> _Problem:
        """Read the ranges, the constraints and the metrics; every problem of them and of ``out`` in one
        :class:`DesignError`."""
        problems: list[str] = []
        varies: list[Vary] = []
        cons: list[Constraint] = []
        requests: list[MetricRequest] = []
        try:
            varies = read_varies(vary, mech, count_required=False, stacklevel=3)
        except DesignError as exc:
            problems += exc.problems
        try:
            cons = parse_constraints(list(constraints), mech, file_units(described(mech.description)))
        except DesignError as exc:
            problems += exc.problems
        names = [objective, *(c.column for c in cons), *metrics, "assembles"]
        try:
            requests = parse_metrics(list(dict.fromkeys(names)), mech)
        except DesignError as exc:
            problems += exc.problems
        problems += [
            f'--vary "{v.path}": START equals STOP; nothing to optimise over' for v in varies if v.start == v.stop
        ]
        problems += _out_problems(mech, out)
        if problems:
            raise DesignError(problems)
        return cls(mech, varies, requests, cons, objective, -1.0 if maximize else 1.0, steps)

    @property
    def paths(self) -> list[str]:
        return [v.path for v in self.varies]

    @property
    def bounds(self) -> list[tuple[float, float]]:
        return [(v.start, v.stop) for v in self.varies]

    @property
    def units(self) -> dict[str, str]:
        """The SI unit of each varied value and metric."""
        return {v.path: KINDS[v.kind][1] for v in self.varies} | {r.column: r.metric.unit for r in self.requests}

    def violation(self, cols: Mapping[str, np.ndarray]) -> np.ndarray:
        """Sum of the relative violations, (S,); a design that does not assemble violates by 1000."""
        total = 1e3 * (1.0 - np.asarray(cols["assembles"], dtype=float))
        for c in self.constraints:
            total = total + c.violation(np.asarray(cols[c.column], dtype=float))
        return total


def _out_problems(mech: Mechanism, out: str | Path | None) -> list[str]:
    """What keeps the optimised file ``out`` from being written."""
    if out is None:
        return []
    if mech.description is None:
        return ["writing the optimised file needs the mechanism's description (a file, an example or a Spec)"]
    why = cannot_write(out)
    return [f'--out "{out}": {why}'] if why else []


# ---------------------------------------------------------------- the objective and the constraint


@dataclass
class _Designs:
    """The designs evaluated for the optimiser, each once: its objective and constraint functions over a
    population, and the table of every design evaluated, in order.

    Attributes
    ----------
    problem : _Problem
    cache : dict
        The metrics of each design evaluated, by the bytes of its values (cleared past 50,000).
    count : int
        Designs evaluated.
    history : list
        ``(values (S, k), columns)`` of each batch evaluated.
    """

    problem: _Problem
    cache: dict[bytes, dict[str, float]] = field(default_factory=dict)
    count: int = 0
    history: list[tuple[np.ndarray, Columns]] = field(default_factory=list)

    def metrics_of(self, x: np.ndarray) -> list[dict[str, float]]:
        """The metrics of the designs ``x``, ``(k, S)`` or ``(k,)`` as the optimiser gives them: one dict each."""
        pop = np.atleast_2d(np.asarray(x, dtype=float).T)  # (S, k)
        keys = [row.tobytes() for row in pop]
        new = [i for i, key in enumerate(keys) if key not in self.cache]
        if new:
            if len(self.cache) > 50_000:
                self.cache.clear()
            p = self.problem
            cols = evaluate(p.mech, p.paths, pop[new], p.requests, p.steps)
            self.count += len(new)
            self.history.append((pop[new], cols))
            for j, i in enumerate(new):
                self.cache[keys[i]] = {c: float(v[j]) for c, v in cols.items()}
        return [self.cache[key] for key in keys]

    def objective(self, x: np.ndarray) -> np.ndarray:
        """The objective to minimise of the designs ``x``, ``(S,)``: 1e300 where it has no value."""
        f = self.problem.sign * np.array([r[self.problem.objective] for r in self.metrics_of(x)])
        return np.where(np.isnan(f), 1e300, f)

    def violation(self, x: np.ndarray) -> np.ndarray:
        """The constraint of the designs ``x``: their sum of relative violations, ``(1, S)``, <= 0 to hold."""
        rows = self.metrics_of(x)
        return self.problem.violation({name: np.array([r[name] for r in rows]) for name in rows[0]})[None]

    def table(self) -> SweepTable | None:
        """Every design evaluated: ``variant``, the values, the metrics and ``violation``; None before any."""
        if not self.history:
            return None
        p = self.problem
        values = np.concatenate([h[0] for h in self.history])
        cols = {"variant": np.arange(len(values), dtype=np.int64)}
        cols.update({path: values[:, j] for j, path in enumerate(p.paths)})
        for r in p.requests:
            cols[r.column] = np.concatenate([h[1][r.column] for h in self.history])
        cols["violation"] = p.violation(cols)
        return SweepTable(cols, {"variant": "1", "violation": "1", **p.units}, {"objective": p.objective})


# ---------------------------------------------------------------- the run, the result, the file


def _run(
    problem: _Problem, designs: _Designs, x0: np.ndarray | None, *, seed: int, popsize: int, maxiter: int, tol: float
) -> Any:
    """Differential evolution over the whole population at once, from ``x0`` where given: its result."""
    from scipy.optimize import NonlinearConstraint, differential_evolution

    with np.errstate(invalid="ignore"):
        return differential_evolution(
            designs.objective,
            problem.bounds,
            constraints=NonlinearConstraint(designs.violation, -np.inf, 0.0),
            vectorized=True,
            updating="deferred",
            rng=seed,
            popsize=popsize,
            maxiter=maxiter,
            tol=tol,
            polish=False,
            x0=x0,
        )


def _first(cols: Columns) -> dict[str, float]:
    """The first row of ``cols``."""
    return {c: float(v[0]) for c, v in cols.items()}


def _write(problem: _Problem, best: np.ndarray, out: str | Path) -> Path:
    """The mechanism file with the values ``best``, written to ``out``
    (:func:`~linkwork.structure.parameters.file_text`, :func:`~linkwork.spec.edit.write_text`)."""
    try:
        return write_text(file_text(problem.mech, dict(zip(problem.paths, best.tolist(), strict=True))), out)
    except OSError as exc:
        raise DesignError([f'--out "{out}": cannot write ({exc})']) from None
