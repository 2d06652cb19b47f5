"""Design sweeps: many variants of one mechanism, in chunks, in this process or on a Dask cluster.

>>> import linkwork as lw
>>> t = lw.sweep("four-bar", {"links.crank.length": ("90 mm", "110 mm", 5)}, ["swing", "time_ratio"])
>>> len(t), t.columns["swing"].shape
(5, (5,))
"""

from __future__ import annotations

import math
import os
import re
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from linkwork.design.evaluate import evaluate
from linkwork.design.metrics import MetricRequest, parse_metrics
from linkwork.design.plan import Plan, Vary, make_plan, parse_varies
from linkwork.errors import DesignError, MissingDependencyError
from linkwork.optional import require

#: Samples (variants x crank angles) per chunk by default: the arrays of a chunk stay some hundred MB.
CHUNK_SAMPLES = 1 << 19

#: Sweeps of up to this many variants run in this process unless workers or a scheduler are given.
IN_PROCESS = 20_000


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

    def to_arrow(self) -> Any:
        """A pyarrow Table (units in each field's metadata)."""
        from linkwork.design.store import to_arrow

        return to_arrow(self.columns, self.units, self.meta)

    def to_pandas(self) -> Any:
        """A pandas DataFrame indexed by variant."""
        pd = require("pandas", purpose="SweepTable.to_pandas")

        return pd.DataFrame(self.columns).set_index("variant")


def _source(mechanism: Any) -> tuple[Any, Any]:
    """(compiled mechanism, its description or None) of a file, an example name, a spec or a compiled
    mechanism (:mod:`linkwork.api`)."""
    from linkwork.api import mechanism_of

    mech = mechanism_of(mechanism, "mechanism")
    return mech, mech.spec


def _declared(spec: Any) -> dict[str, str]:
    """The units bare numbers of the description are read in (SI without a description)."""
    from linkwork.units import DEFAULT_UNITS, SI_UNITS

    if spec is None:
        return dict(SI_UNITS)
    return {**DEFAULT_UNITS, **spec.units.model_dump(exclude_none=True)}


def _varies(vary: Any, mech: Any, spec: Any, count_required: bool | None = True) -> list[Vary]:
    """``--vary`` texts, or a dict ``path -> (start, stop[, count])`` (numbers in the file's units or with units).

    A range far from the file's value (see :func:`~linkwork.design.plan.scale_warnings`) gives a
    :class:`~linkwork.design.plan.DesignWarning`."""
    import warnings

    from linkwork.design.plan import scale_warnings
    from linkwork.errors import DesignWarning

    if isinstance(vary, dict):
        texts = []
        for path, rng in vary.items():
            parts = [str(x) for x in (rng if isinstance(rng, tuple | list) else (rng,))]
            texts.append(f"{path}={':'.join(parts)}")
        vary = texts
    out = parse_varies(list(vary), mech, _declared(spec), count_required)
    for line in scale_warnings(out, mech, _declared(spec)):
        warnings.warn(line, DesignWarning, stacklevel=3)
    return out


def _units(plan: Plan, requests: list[MetricRequest]) -> dict[str, str]:
    from linkwork.units import KINDS

    units = {"variant": "1"}
    units.update({v.path: KINDS[v.kind][1] for v in plan.varies})
    units.update({r.column: r.metric.unit for r in requests})
    return units


def _set_threads(threads: int) -> None:
    """Threads of the compiled kernels in this process: one in a process of a cluster of one thread each,
    where the kernels' own pool would only compete with the other workers for the cores."""
    from linkwork.kinetostatics import fast as kfast
    from linkwork.motion import fast as mfast

    mfast.THREADS = kfast.THREADS = max(1, int(threads))


def chunk_task(
    mech: Any,
    paths: list[str],
    values: np.ndarray,
    metrics: list[str],
    steps: int,
    first: int,
    chunk: int,
    threads: int | None = None,
    attempts: str | None = None,
) -> tuple[int, dict[str, np.ndarray]]:
    """Evaluate one chunk (the function a Dask worker runs): ``(chunk, columns)``.

    ``attempts``: a directory where each evaluation appends a line ``chunk pid`` to
    ``attempts-<pid>.txt``, for auditing retries.
    """
    if threads is not None:
        _set_threads(threads)
    if attempts is not None:
        with open(Path(attempts) / f"attempts-{os.getpid()}.txt", "a", encoding="utf-8") as fh:
            fh.write(f"{chunk} {os.getpid()}\n")
    requests = parse_metrics(metrics, mech)
    out = {"variant": np.arange(first, first + len(values), dtype=np.int64)}
    out.update({p: np.asarray(values[:, j], dtype=float) for j, p in enumerate(paths)})
    out.update(evaluate(mech, paths, values, requests, steps))
    return chunk, out


def sweep(
    mechanism: Any,
    vary: Any,
    metrics: list[str],
    *,
    sampling: str = "grid",
    samples: int | None = None,
    seed: int = 0,
    steps: int = 360,
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

    Returns
    -------
    SweepTable

    Raises
    ------
    DesignError
        Bad ranges, paths or metrics (every problem in one message), a resume of another plan or of an
        unreadable manifest, or a chunk on disk that changed during the run.
    """
    from linkwork.design.store import (
        FORMAT,
        chunk_files,
        chunk_range,
        mechanism_hash,
        prepare,
        read_chunks,
        remove_parts,
        write_chunk,
        write_table,
    )
    from linkwork.design.store import parts_dir as _parts

    mech, spec = _source(mechanism)
    problems: list[str] = []
    varies: list[Vary] = []
    requests: list[MetricRequest] = []
    try:
        varies = _varies(vary, mech, spec, True if sampling == "grid" else None)
    except DesignError as exc:
        problems += exc.problems
    try:
        requests = parse_metrics(list(metrics), mech)
    except DesignError as exc:
        problems += exc.problems
    if isinstance(steps, bool) or not isinstance(steps, int) or steps < 3:
        problems.append(f"steps: expected a whole number of 3 or more, got {steps!r}")
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int) or workers < 0):
        problems.append(f"workers: expected 0 or more (0: in this process), got {workers!r}")
    if chunk_size is not None and chunk_size < 1:
        problems.append(f"chunk size: expected 1 or more, got {chunk_size}")
    if out is not None and Path(out).suffix not in (".parquet", ".nc"):
        problems.append(f'--out "{out}": expected a .parquet or .nc file')
    elif out is not None:
        from linkwork.design.store import cannot_write

        why = cannot_write(out)
        if why:
            problems.append(f'--out "{out}": {why}')
        try:
            require("pyarrow", *(["xarray"] if Path(out).suffix == ".nc" else []), purpose=f'--out "{out}"')
        except MissingDependencyError as exc:
            problems.append(str(exc))
    if scheduler is not None:
        problems += _scheduler_problems(scheduler, connect_timeout)
    if problems:
        raise DesignError(problems)
    plan = make_plan(varies, sampling, samples, seed)
    size = int(chunk_size or max(1, CHUNK_SAMPLES // steps))
    n_chunks = math.ceil(plan.n_variants / size)
    columns = [r.column for r in requests]
    units = _units(plan, requests)
    meta = {
        "format": FORMAT,
        "mechanism": mech.name,
        "mechanism_sha256": mechanism_hash(mech),
        "plan": plan.as_dict(),
        "metrics": columns,
        "steps": steps,
        "chunk_size": size,
        "n_chunks": n_chunks,
    }
    parts = _parts(out) if out is not None else None
    done = prepare(out, meta, resume) if out is not None else set()
    todo = [c for c in range(n_chunks) if c not in done]
    unit = plan.unit_sample()
    results: dict[int, dict[str, np.ndarray]] = {}
    bar = _Progress(n_chunks, len(done), progress)

    def store(chunk: int, cols: dict[str, np.ndarray]) -> None:
        if parts is not None:
            write_chunk(parts, chunk, cols, units)
        else:
            results[chunk] = cols
        done.add(chunk)
        bar.advance()
        if on_chunk is not None:
            on_chunk(chunk, len(done), n_chunks)

    def task_args(c: int) -> tuple[Any, list[str], np.ndarray, list[str], int, int, int]:
        lo, hi = chunk_range(meta, c)
        return mech, plan.paths, plan.values(lo, hi, unit), columns, steps, lo, c

    log = str(attempts) if attempts is not None else None
    try:
        if scheduler is None and (workers == 0 or (workers is None and plan.n_variants <= IN_PROCESS)):
            for c in todo:
                store(*chunk_task(*task_args(c), attempts=log))
        elif todo:
            _on_dask(todo, task_args, store, workers, scheduler, log, connect_timeout)
    except BaseException:
        if parts is not None and not chunk_files(parts):  # nothing to resume: leave no folder behind
            remove_parts(parts)
        raise
    finally:
        bar.close()
    if parts is not None and out is not None:
        cols = read_chunks(parts)
        try:
            write_table(out, cols, units, meta)
        except OSError as exc:
            raise DesignError([f'--out "{out}": cannot write the table ({exc}); the chunks are in {parts}']) from None
        if not keep_parts:
            remove_parts(parts)
    else:
        cols = {k: np.concatenate([results[c][k] for c in range(n_chunks)]) for k in results[0]} if results else {}
    return SweepTable(cols, units, meta)


_ADDRESS = re.compile(r"^([a-z]+://)?[^\s/:]+:\d+$|^[a-z]+://\[[0-9a-fA-F:]+\]:\d+$")


def _scheduler_problems(scheduler: str, connect_timeout: float) -> list[str]:
    """What is wrong with a ``--scheduler`` (an address or a scheduler file) before connecting."""
    out = []
    if not Path(scheduler).is_file() and not _ADDRESS.match(scheduler):
        if scheduler.endswith(".json") or "/" in scheduler.split("://")[-1]:
            out.append(f'--scheduler "{scheduler}": no such scheduler file')
        else:
            out.append(f'--scheduler "{scheduler}": expected an address tcp://HOST:PORT or a scheduler file')
    if not (isinstance(connect_timeout, int | float) and connect_timeout > 0):
        out.append(f"connect timeout: expected a positive number of seconds, got {connect_timeout!r}")
    return out


def _on_dask(
    todo: list[int],
    task_args: Callable[[int], tuple],
    store: Callable[[int, dict[str, np.ndarray]], None],
    workers: int | None,
    scheduler: str | None,
    attempts: str | None,
    connect_timeout: float = 30.0,
) -> None:
    """Run the chunks on a Dask cluster: an embedded local one, or the one at ``scheduler``.

    A chunk whose worker dies is given to another worker by the scheduler; each result is stored
    by this process as it comes back, so nothing done is lost if this process stops.
    """
    require("distributed", purpose="a sweep on Dask (--workers, --scheduler, or more than 20,000 variants)")
    from distributed import Client, LocalCluster, as_completed

    cluster = None
    if scheduler is not None:
        try:
            if Path(scheduler).is_file():
                client = Client(scheduler_file=scheduler, timeout=connect_timeout)
            else:
                client = Client(scheduler, timeout=connect_timeout)
        except (OSError, ValueError) as exc:
            from linkwork.errors import LinkworkError

            raise LinkworkError(
                f"cannot reach the Dask scheduler at {scheduler} within {connect_timeout:g} s: {exc}"
            ) from None
    else:
        n = workers or os.cpu_count() or 1
        cluster = LocalCluster(
            n_workers=n, threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address=None
        )
        client = Client(cluster)
    futures = []
    try:
        threads = 1
        if scheduler is not None:
            info = client.scheduler_info()["workers"].values()
            threads = max([w.get("nthreads", 1) for w in info] or [1])
        futures = [
            client.submit(chunk_task, *task_args(c), threads=1 if threads == 1 else None, attempts=attempts, pure=False)
            for c in todo
        ]
        for fut in as_completed(futures):
            chunk, cols = fut.result()
            store(chunk, cols)
            fut.release()
    finally:
        for fut in futures:
            if not fut.done():
                fut.cancel()
        client.close()
        if cluster is not None:
            cluster.close()


class _Progress:
    """A progress bar of chunks on stderr (rich), or nothing."""

    def __init__(self, total: int, done: int, show: bool):
        self.bar = None
        if show and total:
            from rich.console import Console
            from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeRemainingColumn

            self.bar = Progress(
                TextColumn("sweep"), BarColumn(), MofNCompleteColumn(), TextColumn("chunks"), TimeRemainingColumn(),
                console=Console(stderr=True),
            )  # fmt: skip
            self.bar.start()
            self.task = self.bar.add_task("sweep", total=total, completed=done)

    def advance(self) -> None:
        if self.bar is not None:
            self.bar.advance(self.task)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.stop()
