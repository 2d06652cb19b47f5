"""``linkwork sweep``, ``linkwork optimize`` and ``linkwork parameters``: design over many variants."""

from __future__ import annotations

import math
import warnings
from typing import TYPE_CHECKING, Annotated, Any

import typer

from linkwork.cli.app import FileOrExample, app, check_options, compile_or_exit, echo_json, fail, needs
from linkwork.errors import DesignError, DesignWarning, LinkworkError
from linkwork.limits import (
    MAX_ANGLES,
    MAX_BATCH,
    MAX_GENERATIONS,
    MAX_OPTION,
    MAX_SEED,
    QUOTE_PATH,
    excerpt,
    quote,
    whole,
)

if TYPE_CHECKING:
    from linkwork.design.sweeps import SweepTable

Vary = Annotated[
    list[str],
    typer.Option(
        "--vary",
        help='PATH=START:STOP:COUNT, e.g. "links.crank.length=90mm:110mm:50" (bare numbers in the file\'s units, '
        "as `linkwork parameters` lists them); PATH=START:STOP for --sample random or lhs and for optimize; "
        "repeat for more dimensions",
    ),
]


def _text_problems(**options: list[str]) -> list[str]:
    """Each text of the options (``--vary``, ``--metric``, ``--constraint``) longer than
    :data:`~linkwork.limits.MAX_OPTION` characters: one line each."""
    return [
        f"--{name}: expected at most {MAX_OPTION:,} characters, got {quote(text)}"
        for name, texts in options.items()
        for text in texts
        if len(text) > MAX_OPTION
    ]


def _show(value: float, unit: str) -> str:
    if not math.isfinite(value):
        return str(value)
    if unit == "rad":
        return f"{math.degrees(value):.6g} deg"
    return f"{value:.6g} {unit}" if unit != "1" else f"{value:.6g}"


@app.command()
def parameters(file_or_example: FileOrExample) -> None:
    """List the named parameters (dimensions, masses, moments of inertia) a sweep may vary, with the file's
    values in the file's units (the units in which bare numbers of --vary are read)."""
    from linkwork.design.plan import in_file_units
    from linkwork.spec.reader import described
    from linkwork.structure.parameters import file_units, parameter_list

    mech = compile_or_exit(file_or_example)
    declared = file_units(described(mech.description))
    for p in parameter_list(mech):
        shown, unit = in_file_units(p.value, p.kind, declared)
        note = f"  ({p.note})" if p.note and p.kind == "inertia" and not p.note.endswith("centre of mass") else ""
        typer.echo(f"{p.name:40s} {shown:.10g} {unit}{note}")


class _Warnings:
    """Design warnings raised inside, printed as one line each on stderr."""

    def __enter__(self) -> None:
        self.catcher = warnings.catch_warnings(record=True)
        self.caught = self.catcher.__enter__()
        warnings.simplefilter("always", DesignWarning)

    def __exit__(self, *exc: Any) -> None:
        self.catcher.__exit__(*exc)
        for w in self.caught:
            if issubclass(w.category, DesignWarning):
                typer.echo(f"warning: {w.message}", err=True)


@app.command()
def sweep(
    file_or_example: FileOrExample,
    vary: Vary,
    metric: Annotated[list[str], typer.Option("--metric", help="a metric to compute (repeat): one of those above")],
    out: Annotated[str, typer.Option("--out", help="the table to write: .parquet or .nc")],
    sample: Annotated[str, typer.Option("--sample", help="grid, random or lhs (Latin hypercube)")] = "grid",
    samples: Annotated[int | None, typer.Option("--samples", help="variants of a random or lhs sample")] = None,
    seed: Annotated[int, typer.Option("--seed", help="seed of a random or lhs sample")] = 0,
    steps: Annotated[int, typer.Option("--steps", help="crank angles over the turn")] = 360,
    chunk_size: Annotated[int | None, typer.Option("--chunk-size", help="variants per chunk")] = None,
    workers: Annotated[
        int | None, typer.Option("--workers", help="local Dask worker processes (0: run in this process)")
    ] = None,
    scheduler: Annotated[
        str | None, typer.Option("--scheduler", help="address or scheduler file of a running Dask cluster")
    ] = None,
    resume: Annotated[bool, typer.Option("--resume", help="finish a sweep whose chunks are on disk")] = False,
    keep_parts: Annotated[
        bool, typer.Option("--keep-parts", help="keep OUT.parts/ (the chunk files) once the table is written")
    ] = False,
    connect_timeout: Annotated[
        float, typer.Option("--connect-timeout", help="seconds to wait for the scheduler of --scheduler")
    ] = 30.0,
    dashboard: Annotated[
        bool,
        typer.Option(
            "--dashboard", help="serve Dask's dashboard of the local cluster on 127.0.0.1:8787 (by default none)"
        ),
    ] = False,
    quiet: Annotated[bool, typer.Option("--quiet", help="no progress bar")] = False,
) -> None:
    """Metrics of many design variants, a row per variant, computed in chunks (here or on Dask).

    Metrics: assembles, stroke[:JOINT], swing[:LINK], time_ratio[:JOINT|LINK], forward_time_ratio[:JOINT|LINK],
    min_transmission_angle, peak_driving_torque, peak_foundation_force, knife_overlap[:LOAD],
    knife_clearance[:LOAD], working_time_ratio[:LOAD].  time_ratio: the coefficient K, the longer stroke's time
    over the shorter's (>= 1); forward_time_ratio: the time of the stroke in which the slider moves in the +
    direction of its guide's axis (the rocker turns counter-clockwise) over that of the other stroke, the crank
    turning its own way; working_time_ratio: the knives closing over opening.
    """
    from linkwork.design.store import parts_dir
    from linkwork.design.sweeps import sweep as run

    check_options(*_text_problems(vary=vary, metric=metric))
    if dashboard and scheduler is not None:
        fail(LinkworkError("--dashboard: for the local cluster only; a running cluster serves its own"))
    if scheduler is not None or (workers or 0) > 0:
        needs("distributed", purpose="a sweep on Dask (--workers, --scheduler)")
    try:
        with _Warnings():
            table = run(
                file_or_example,
                vary,
                metric,
                sampling=sample,
                samples=samples,
                seed=seed,
                steps=steps,
                chunk_size=chunk_size,
                out=out,
                resume=resume,
                workers=workers,
                scheduler=scheduler,
                progress=not quiet,
                keep_parts=keep_parts,
                connect_timeout=connect_timeout,
                dashboard=dashboard,
            )
    except (DesignError, LinkworkError) as exc:
        fail(exc)
    except KeyboardInterrupt:
        if parts_dir(out).is_dir():
            typer.echo(f"interrupted: the finished chunks are in {parts_dir(out)}; run again with --resume", err=True)
        else:
            typer.echo("interrupted before the first chunk was stored: nothing to resume", err=True)
        raise typer.Exit(130) from None
    except OSError as exc:
        where = f"the Dask scheduler at {scheduler}" if scheduler is not None else f'"{out}"'
        fail(LinkworkError(f"{where}: {exc}"))
    _print_sweep(table, steps, out)


def _print_sweep(table: SweepTable, steps: int, out: str) -> None:
    """What a sweep wrote: a line per metric with its smallest and largest value and their variants, or
    why it has none."""
    import numpy as np

    typer.echo(f"{table.meta['mechanism']}: {len(table)} variants x {steps} angles -> {out}")
    variant = table.columns["variant"]
    for name in table.meta["metrics"]:
        values = table.columns[name]
        if np.isnan(values).all():
            typer.echo(f"  {name:28s} {_why_none(table.columns)}")
            continue
        unit = table.units[name]
        lo, hi = int(np.nanargmin(values)), int(np.nanargmax(values))
        typer.echo(
            f"  {name:28s} min {_show(float(values[lo]), unit)} (variant {variant[lo]}), "
            f"max {_show(float(values[hi]), unit)} (variant {variant[hi]})"
        )


def _why_none(columns: dict[str, Any]) -> str:
    """Why a metric has no value in any variant, as far as the table tells."""
    if "assembles" not in columns:
        return "no value in any variant (a variant that does not assemble over the whole turn has none)"
    n = int((columns["assembles"] == 1).sum())
    if n == 0:
        return "no variant assembles over the whole turn"
    return f"no value in any variant, though {n} assemble over the whole turn"


@app.command()
def optimize(
    file_or_example: FileOrExample,
    vary: Vary,
    objective: Annotated[str, typer.Option("--objective", help="the metric to minimise (or --maximize)")],
    constraint: Annotated[
        list[str] | None, typer.Option("--constraint", help='"METRIC>=VALUE" or "METRIC<=VALUE" (repeat)')
    ] = None,
    out: Annotated[str | None, typer.Option("--out", help="write the optimised mechanism file (.yaml)")] = None,
    maximize: Annotated[bool, typer.Option("--maximize", help="the largest objective")] = False,
    metric: Annotated[list[str] | None, typer.Option("--metric", help="more metrics to report")] = None,
    steps: Annotated[int, typer.Option("--steps", help="crank angles over the turn")] = 360,
    seed: Annotated[int, typer.Option("--seed", help="seed of the optimiser")] = 0,
    popsize: Annotated[int, typer.Option("--popsize", help="population size per dimension")] = 15,
    maxiter: Annotated[
        int, typer.Option("--maxiter", help="generations at most (the report says when it stops there unconverged)")
    ] = 100,
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON object")] = False,
) -> None:
    """The best design in the ranges (differential evolution over the whole population at once)."""
    from linkwork.design.optimizer import optimize as run

    if out is not None and not out.endswith((".yaml", ".yml")):
        fail(LinkworkError(f'--out "{excerpt(out, QUOTE_PATH)}": expected a .yaml file'))
    check_options(
        *_text_problems(vary=vary, constraint=constraint or [], metric=[objective, *(metric or [])]),
        whole(steps, "--steps", 3, MAX_ANGLES, "number of crank angles"),
        whole(seed, "--seed", 0, MAX_SEED),
        whole(maxiter, "--maxiter", 0, MAX_GENERATIONS, "number of generations"),
    )
    most = max(1, MAX_BATCH // (max(1, len(vary)) * steps))  # each generation is solved at once
    if not 1 <= popsize <= most:
        fail(
            LinkworkError(
                f"--popsize: expected a positive number, at most {most:,} (a generation of popsize x {len(vary)} "
                f"designs x {steps} crank angles is solved at once, at most {MAX_BATCH:,} samples), got {popsize}"
            )
        )
    try:
        with _Warnings():
            best = run(
                file_or_example,
                vary,
                objective,
                constraint or [],
                maximize=maximize,
                metrics=metric or [],
                steps=steps,
                seed=seed,
                popsize=popsize,
                maxiter=maxiter,
                out=out,
            )
    except (DesignError, LinkworkError) as exc:
        fail(exc)
    if as_json:
        why = "the design does not assemble over the whole turn, or the metric has no value for it"
        echo_json(best.as_dict(), why={"metrics": why, "initial": why})
        return
    typer.echo(
        f"{'best design' if best.feasible else 'no design meets every constraint; the nearest'}: "
        f"{best.evaluations} designs evaluated in {best.generations} generations"
    )
    if not best.converged:
        typer.echo(f"  not converged ({best.message}): the best found so far; more --maxiter may do better")
    for path, value in best.values.items():
        typer.echo(f"  {path:36s} {_show(value, best.units[path])}")
    typer.echo("metrics" + ("  (the file's design beside)" if best.initial else ""))
    for name, value in best.metrics.items():
        before = f"   was {_show(best.initial[name], best.units[name])}" if name in best.initial else ""
        typer.echo(f"  {name:36s} {_show(value, best.units[name])}{before}")
    if best.out is not None:
        typer.echo(f"written: {best.out}")
