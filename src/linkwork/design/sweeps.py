"""Design sweeps: many variants of one mechanism, in chunks, in this process or on a Dask cluster.

>>> import linkwork as lw
>>> t = lw.sweep("four-bar", {"links.crank.length": ("90 mm", "110 mm", 5)}, ["swing", "time_ratio"])
>>> len(t), t.columns["swing"].shape
(5, (5,))
"""

from __future__ import annotations

import math
import os
import sys
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np

from linkwork.api import MechanismLike, mechanism_of
from linkwork.design.cluster import NO_PAGES, connect, probe_scheduler, scheduler_problems  # noqa: F401 - read here
from linkwork.design.evaluate import evaluate
from linkwork.design.metrics import MetricRequest, parse_metrics
from linkwork.design.plan import Ranges, SweepPlan, Vary, make_plan, read_varies
from linkwork.design.store import (
    FORMAT,
    cannot_write,
    chunk_files,
    chunk_range,
    mechanism_hash,
    parts_dir,
    prepare,
    read_chunks,
    remove_parts,
    to_arrow,
    write_chunk,
    write_table,
)
from linkwork.errors import DesignError, MissingDependencyError
from linkwork.limits import (
    MAX_ANGLES,
    MAX_BATCH,
    MAX_SEED,
    MAX_VARIANTS,
    QUOTE_PATH,
    TURN_STEPS,
    WORKERS_PER_CORE,
    excerpt,
    max_workers,
    whole,
)
from linkwork.optional import require
from linkwork.structure.model import Mechanism
from linkwork.threads import set_threads
from linkwork.units import KINDS

#: Samples (variants x crank angles) per chunk by default: the arrays of a chunk stay some hundred MB.
CHUNK_SAMPLES = 1 << 19

#: Sweeps of up to this many variants run in this process unless workers or a scheduler are given.
IN_PROCESS = 20_000

#: The columns of one chunk: column name -> ``(rows,)``.
Columns = dict[str, np.ndarray]


@dataclass(frozen=True)
class SweepTable:
    """A table with a row per variant.

    Attributes
    ----------
    columns : dict
        ``variant`` (int), the varied dimensions by path (SI) and the metrics by name, each ``(n,)``.
    units : dict
        The SI unit of every column.
    meta : dict
        The plan, the metrics, the crank steps and the mechanism's content hash.
    """

    columns: dict[str, np.ndarray]
    units: dict[str, str]
    meta: dict[str, Any] = field(default_factory=dict)

    def __len__(self) -> int:
        return len(self.columns["variant"])

    def __getitem__(self, name: str) -> np.ndarray:
        return self.columns[name]

    def _repr_html_(self) -> str:
        """A notebook's view: the rows, and each column's range with its unit."""
        from linkwork.display import number, table

        rows: list[tuple[str, object]] = [("variants", len(self))]
        for name, values in self.columns.items():
            if name != "variant":
                low, high = float(np.nanmin(values)), float(np.nanmax(values))
                rows.append((name, f"{number(low)} to {number(high, self.units.get(name, ''))}"))
        return table("Sweep", rows)

    def to_arrow(self) -> Any:
        """A pyarrow Table (units in each field's metadata)."""
        return to_arrow(self.columns, self.units, self.meta)

    def to_pandas(self) -> Any:
        """A pandas DataFrame indexed by variant."""
        pd = require("pandas", purpose="SweepTable.to_pandas")

        return pd.DataFrame(self.columns).set_index("variant")


class ChunkTask(NamedTuple):
    """One chunk of a sweep, as a worker evaluates it.

    Attributes
    ----------
    mech : Mechanism
    paths : list of str
        The varied parameters.
    values : ndarray, shape (rows, len(paths))
        Their values in the chunk's variants, SI.
    metrics : list of str
        The metrics' columns, as asked for.
    steps : int
        Crank angles over the turn.
    first : int
        The chunk's first variant.
    chunk : int
        The chunk's number.
    """

    mech: Mechanism
    paths: list[str]
    values: np.ndarray
    metrics: list[str]
    steps: int
    first: int
    chunk: int


def _set_threads(threads: int) -> None:
    """Threads of the compiled kernels in this process: one in a process of a cluster of one thread each,
    where the kernels' own pool would only compete with the other workers for the cores."""
    set_threads(threads)


def chunk_task(task: ChunkTask, threads: int | None = None, attempts: str | None = None) -> tuple[int, Columns]:
    """Evaluate one chunk (the function a Dask worker runs): ``(chunk, columns)``.

    ``attempts``: a directory where each evaluation appends a line ``chunk pid`` to
    ``attempts-<pid>.txt``, for auditing retries.
    """
    if threads is not None:
        _set_threads(threads)
    if attempts is not None:
        with open(Path(attempts) / f"attempts-{os.getpid()}.txt", "a", encoding="utf-8") as fh:
            fh.write(f"{task.chunk} {os.getpid()}\n")
    requests = parse_metrics(task.metrics, task.mech)
    out = {"variant": np.arange(task.first, task.first + len(task.values), dtype=np.int64)}
    out.update({p: np.asarray(task.values[:, j], dtype=float) for j, p in enumerate(task.paths)})
    out.update(evaluate(task.mech, task.paths, task.values, requests, task.steps))
    return task.chunk, out


def sweep(
    mechanism: MechanismLike,
    vary: Ranges,
    metrics: list[str],
    *,
    sampling: str = "grid",
    samples: int | None = None,
    seed: int = 0,
    steps: int = TURN_STEPS,
    chunk_size: int | None = None,
    out: str | Path | None = None,
    resume: bool = False,
    workers: int | None = None,
    scheduler: str | None = None,
    progress: bool = False,
    on_chunk: Callable[[int, int, int], None] | None = None,
    attempts: str | Path | None = None,
    keep_parts: bool = False,
    connect_timeout: float = 30.0,
    dashboard: bool = False,
) -> SweepTable:
    """Metrics of many design variants of one mechanism, a row per variant.

    Parameters
    ----------
    mechanism : str, Path, Spec or Mechanism
        A mechanism file, the name of a bundled example, a spec or a compiled mechanism.
    vary : dict or list of str
        ``{"links.crank.length": ("90 mm", "110 mm", 50)}`` or ``["links.crank.length=90mm:110mm:50"]``:
        each dimension's range and, for a grid only, its number of values; bare numbers in the file's units.
    metrics : list of str
        Names from :data:`linkwork.design.metrics.METRICS`, some with an argument (``stroke:guide_E``).
    sampling : {"grid", "random", "lhs"}
        Every combination of the ranges' values, or a uniform random or Latin-hypercube sample of
        ``samples`` variants from ``seed`` (the ranges then without a count).
    samples : int, optional
        Variants of a ``random`` or ``lhs`` sampling (a grid's count is its ranges').
    seed : int, default 0
        Seed of the random generator of a ``random`` or ``lhs`` sampling: the same seed, the same variants.
    steps : int
        Crank angles over the turn.
    chunk_size : int, optional
        Variants per chunk (default: about half a million samples, variants x angles).
    out : str or Path, optional
        The table to write (``.parquet`` or ``.nc``); the chunks go to ``OUT.parts/`` as they finish.
    resume : bool
        Finish a sweep whose chunks are in ``OUT.parts/``: the plan must be the same; chunks on disk that
        prove themselves intact and of this plan are not computed again, any other is (with a
        :class:`~linkwork.design.plan.DesignWarning` naming it).
    workers : int, optional
        Worker processes of an embedded local Dask cluster (one thread each); 0 runs in this process.
        Default: this process for up to :data:`IN_PROCESS` variants, else one worker per core.  A script
        that starts a local cluster needs the ``if __name__ == "__main__":`` guard (the workers are
        started as fresh Python processes that import the script's main module).
    scheduler : str, optional
        The address of a running Dask scheduler (``tcp://host:8786``) or its scheduler file.
    progress : bool
        Show a progress bar (on stderr).
    on_chunk : callable, optional
        ``on_chunk(chunk, done, total)`` after each chunk is stored.
    attempts : str or Path, optional
        A directory in which every evaluation of a chunk is logged (see :func:`chunk_task`).
    keep_parts : bool
        Keep ``OUT.parts/`` once the table is written (by default it is removed then).
    connect_timeout : float
        Seconds to wait for the scheduler at ``scheduler``.
    dashboard : bool
        Serve Dask's dashboard of a local cluster on 127.0.0.1:8787 (its link on stderr); without it none of its
        pages is served (they answer any host name: a page open in a browser on this machine could read them).

    Returns
    -------
    SweepTable

    Raises
    ------
    DesignError
        Bad ranges, paths or metrics (every problem in one message), a resume of another plan or of an
        unreadable manifest, or a chunk on disk that changed during the run.

    Examples
    --------
    >>> import linkwork as lw
    >>> table = lw.sweep("four-bar", {"links.crank.length": ("90 mm", "110 mm", 3)}, ["swing"], steps=36)
    >>> table.to_pandas()["swing"].round(3).tolist()  # rad
    [0.879, 0.983, 1.09]
    """
    mech = mechanism_of(mechanism, "mechanism")
    options = _Options(sampling, samples, seed, steps, chunk_size, workers, scheduler, connect_timeout)
    varies, requests = _checked(mech, vary, metrics, options, out)
    job = _Job.of(mech, make_plan(varies, sampling, samples, seed), requests, steps, chunk_size)
    chunks = _Chunks(job, out, resume, on_chunk, progress)
    try:
        _run_chunks(job, chunks, options, str(attempts) if attempts is not None else None, dashboard)
    except BaseException:
        chunks.abandon()
        raise
    finally:
        chunks.bar.close()
    return SweepTable(chunks.table(out, keep_parts), job.units, job.meta)


# ---------------------------------------------------------------- the plan and the options, checked


class _Options(NamedTuple):
    """The options of a sweep besides its ranges, metrics and table (those of :func:`sweep`)."""

    sampling: str
    samples: int | None
    seed: int
    steps: int
    chunk_size: int | None
    workers: int | None
    scheduler: str | None
    connect_timeout: float


def _checked(
    mech: Mechanism, vary: Ranges, metrics: list[str], options: _Options, out: str | Path | None
) -> tuple[list[Vary], list[MetricRequest]]:
    """The ranges and the metrics of a sweep, read; every problem of them and of the options (their
    bounds those of :mod:`linkwork.limits`) in one :class:`DesignError`."""
    problems: list[str] = []
    varies: list[Vary] = []
    requests: list[MetricRequest] = []
    try:
        varies = read_varies(vary, mech, True if options.sampling == "grid" else None, stacklevel=3)
    except DesignError as exc:
        problems += exc.problems
    try:
        requests = parse_metrics(list(metrics), mech)
    except DesignError as exc:
        problems += exc.problems
    problems += _option_problems(options.steps, options.workers, options.chunk_size)
    problems += _size_problems(varies, options)
    if out is not None:
        problems += _out_problems(out)
    if options.scheduler is not None:
        problems += scheduler_problems(options.scheduler, options.connect_timeout)
    if problems:
        raise DesignError(problems)
    return varies, requests


def _option_problems(steps: Any, workers: Any, chunk_size: int | None) -> list[str]:
    """What is wrong with the crank steps, the number of workers and the chunk size."""
    problems = [whole(steps, "steps", 3, MAX_ANGLES, "number of crank angles")]
    bad = isinstance(workers, bool) or not isinstance(workers, int) or not 0 <= workers <= max_workers()
    if workers is not None and bad:
        problems.append(
            f"workers: expected 0 or more (0: in this process), at most {max_workers()} ({WORKERS_PER_CORE} per "
            f"core of this machine), got {workers!r}"
        )
    if chunk_size is not None and chunk_size < 1:
        problems.append(f"chunk size: expected 1 or more, got {chunk_size}")
    return [p for p in problems if p is not None]


def _size_problems(varies: list[Vary], options: _Options) -> list[str]:
    """What makes a sweep too large (:data:`~linkwork.limits.MAX_VARIANTS` variants, chunks of at most
    :data:`~linkwork.limits.MAX_BATCH` samples) or its seed out of range."""
    problems = [whole(options.seed, "seed", 0, MAX_SEED)]
    n = options.samples
    if options.sampling == "grid" and varies and all(v.count for v in varies):
        n = math.prod(v.count or 1 for v in varies)
        if n > MAX_VARIANTS:
            problems.append(
                f"--vary: the grid has {n:,} variants (the product of the COUNTs), more than the {MAX_VARIANTS:,} "
                "a sweep may have: split it into sweeps of parts of the ranges"
            )
    elif isinstance(n, int) and n > MAX_VARIANTS:
        problems.append(f"--samples: expected at most {MAX_VARIANTS:,} variants in a sweep, got {n:,}")
    steps, size = options.steps, options.chunk_size
    if isinstance(steps, int) and isinstance(size, int) and 0 < steps <= MAX_ANGLES and size > 0:
        rows = min(size, n) if isinstance(n, int) and n > 0 else size
        if rows * steps > MAX_BATCH:
            problems.append(
                f"chunk size: {rows:,} variants x {steps:,} crank angles is {rows * steps:,} samples a chunk, more "
                f"than the {MAX_BATCH:,} solved at once: at most {MAX_BATCH // steps:,} variants a chunk"
            )
    return [p for p in problems if p is not None]


def _out_problems(out: str | Path) -> list[str]:
    """What keeps the table ``out`` from being written: its suffix, its folder, a missing package."""
    shown = excerpt(out, QUOTE_PATH)
    if Path(out).suffix not in (".parquet", ".nc"):
        return [f'--out "{shown}": expected a .parquet or .nc file']
    problems = []
    why = cannot_write(out)
    if why:
        problems.append(f'--out "{shown}": {why}')
    try:
        require("pyarrow", *(["xarray"] if Path(out).suffix == ".nc" else []), purpose=f'--out "{shown}"')
    except MissingDependencyError as exc:
        problems.append(str(exc))
    return problems


# ---------------------------------------------------------------- the job: its chunks and its table's layout


@dataclass(frozen=True)
class _Job:
    """What a sweep computes, in chunks of ``meta["chunk_size"]`` variants.

    Attributes
    ----------
    mech : Mechanism
    plan : SweepPlan
    metrics : list of str
        The metrics' columns.
    steps : int
    units : dict
        The SI unit of every column of the table.
    meta : dict
        The plan, the metrics, the crank steps, the chunks and the mechanism's content hash: what the
        manifest of the parts records and the table carries.
    unit : ndarray or None
        The plan's sample in the unit cube (:meth:`SweepPlan.unit_sample`), drawn once.
    """

    mech: Mechanism
    plan: SweepPlan
    metrics: list[str]
    steps: int
    units: dict[str, str]
    meta: dict[str, Any]
    unit: np.ndarray | None

    @classmethod
    def of(
        cls, mech: Mechanism, plan: SweepPlan, requests: list[MetricRequest], steps: int, chunk_size: int | None
    ) -> _Job:
        size = int(chunk_size or max(1, CHUNK_SAMPLES // steps))
        metrics = [r.column for r in requests]
        units = {"variant": "1"}
        units.update({v.path: KINDS[v.kind][1] for v in plan.varies})
        units.update({r.column: r.metric.unit for r in requests})
        meta = {
            "format": FORMAT,
            "mechanism": mech.name,
            "mechanism_sha256": mechanism_hash(mech),
            "plan": plan.as_dict(),
            "metrics": metrics,
            "steps": steps,
            "chunk_size": size,
            "n_chunks": math.ceil(plan.n_variants / size),
        }
        return cls(mech, plan, metrics, steps, units, meta, plan.unit_sample())

    @property
    def n_chunks(self) -> int:
        return int(self.meta["n_chunks"])

    def task(self, chunk: int) -> ChunkTask:
        """The chunk ``chunk`` to evaluate."""
        lo, hi = chunk_range(self.meta, chunk)
        values = self.plan.values(lo, hi, self.unit)
        return ChunkTask(self.mech, self.plan.paths, values, self.metrics, self.steps, lo, chunk)


# ---------------------------------------------------------------- the chunks stored, resumed, and the table


class _Chunks:
    """Where the chunks of a job go as they finish: the parts folder of ``out`` (a manifest and a file
    per chunk, resumed where ``resume`` is set; :mod:`linkwork.design.store`), or memory without ``out``;
    a progress bar of them where ``progress`` is set."""

    def __init__(
        self,
        job: _Job,
        out: str | Path | None,
        resume: bool,
        on_chunk: Callable[[int, int, int], None] | None,
        progress: bool,
    ) -> None:
        self.job = job
        self.parts = parts_dir(out) if out is not None else None
        self.done: set[int] = prepare(out, job.meta, resume) if out is not None else set()
        self.memory: dict[int, Columns] = {}
        self.on_chunk = on_chunk
        self.bar = _Progress(job.n_chunks, len(self.done), progress)

    def todo(self) -> list[int]:
        """The chunks not done yet, in order."""
        return [c for c in range(self.job.n_chunks) if c not in self.done]

    def store(self, chunk: int, cols: Columns) -> None:
        """Keep a finished chunk (a file and its record in the manifest, or in memory)."""
        if self.parts is not None:
            write_chunk(self.parts, chunk, cols, self.job.units)
        else:
            self.memory[chunk] = cols
        self.done.add(chunk)
        self.bar.advance()
        if self.on_chunk is not None:
            self.on_chunk(chunk, len(self.done), self.job.n_chunks)

    def abandon(self) -> None:
        """After a failure: remove a parts folder that holds nothing to resume."""
        if self.parts is not None and not chunk_files(self.parts):
            remove_parts(self.parts)

    def table(self, out: str | Path | None, keep_parts: bool) -> Columns:
        """The table of every chunk in variant order; with ``out``, read back from the parts, each chunk
        proven and the whole checked (:func:`~linkwork.design.store.read_chunks`), then written to ``out``
        (the parts then removed unless ``keep_parts``)."""
        if self.parts is None or out is None:
            n, memory = self.job.n_chunks, self.memory
            return {k: np.concatenate([memory[c][k] for c in range(n)]) for k in memory[0]} if memory else {}
        cols = read_chunks(self.parts)
        try:
            write_table(out, cols, self.job.units, self.job.meta)
        except OSError as exc:
            why = f'--out "{out}": cannot write the table ({exc}); the chunks are in {self.parts}'
            raise DesignError([why]) from None
        if not keep_parts:
            remove_parts(self.parts)
        return cols


# ---------------------------------------------------------------- the chunks on Dask


def _run_chunks(job: _Job, chunks: _Chunks, options: _Options, log: str | None, dashboard: bool) -> None:
    """The chunks left to do, in this process (up to :data:`IN_PROCESS` variants by default, or ``workers=0``) or
    on Dask (a local cluster, or the scheduler of ``options``), each stored as it comes back."""
    workers, scheduler = options.workers, options.scheduler
    if scheduler is None and (workers == 0 or (workers is None and job.plan.n_variants <= IN_PROCESS)):
        for c in chunks.todo():
            chunks.store(*chunk_task(job.task(c), attempts=log))
    elif chunks.todo():
        _on_dask(job, chunks.todo(), chunks.store, connect(workers, scheduler, options.connect_timeout, dashboard), log)


def _on_dask(
    job: _Job,
    todo: list[int],
    store: Callable[[int, Columns], None],
    connection: tuple[Any, Any],
    attempts: str | None,
) -> None:
    """Run the chunks ``todo`` on the Dask cluster of ``connection`` (:func:`~linkwork.design.cluster.connect`),
    which is closed at the end.

    A chunk whose worker dies is given to another worker by the scheduler; each result is stored
    by this process as it comes back, so nothing done is lost if this process stops.  Workers of one
    thread each run the compiled kernels on one thread.
    """
    from distributed import as_completed

    client, cluster = connection
    futures = []
    try:
        threads = 1
        if cluster is None:
            info = client.scheduler_info()["workers"].values()
            threads = max([w.get("nthreads", 1) for w in info] or [1])
        one = 1 if threads == 1 else None
        futures = [client.submit(chunk_task, job.task(c), threads=one, attempts=attempts, pure=False) for c in todo]
        for fut in as_completed(futures):
            store(*fut.result())
            fut.release()
    finally:
        for fut in futures:
            if not fut.done():
                fut.cancel()
        client.close()
        if cluster is not None:
            cluster.close()


class _Progress:
    """A progress bar of chunks on stderr (rich) where stderr is a terminal, or nothing (stderr piped to a
    file or a program is left clean)."""

    def __init__(self, total: int, done: int, show: bool):
        self.bar = None
        from rich.console import Console

        console = Console(stderr=True, file=getattr(sys.stderr, "unescaped", None))  # the bar's moves as they are
        if show and total and console.is_terminal:
            from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeRemainingColumn

            self.bar = Progress(
                TextColumn("sweep"),
                BarColumn(),
                MofNCompleteColumn(),
                TextColumn("chunks"),
                TimeRemainingColumn(),
                console=console,
            )
            self.bar.start()
            self.task = self.bar.add_task("sweep", total=total, completed=done)

    def advance(self) -> None:
        if self.bar is not None:
            self.bar.advance(self.task)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.stop()
