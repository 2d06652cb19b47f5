"""``linkwork simulate``: the machine unit run in time from any state."""

from __future__ import annotations

import functools
import math
from pathlib import Path
from typing import Annotated, Any

import typer

from linkwork.cli.app import FileOrExample, app, compile_or_exit, echo_json, fail, out_files, quantity_option
from linkwork.errors import LinkworkError


def _quantity(text: str | None, kind: str, option: str, example: str) -> float | None:
    """The value (SI) of an option that needs its unit (:func:`~linkwork.cli.app.quantity_option`) and is of a
    machine's size; exit code 2 with one line otherwise."""
    if text is None:
        return None
    from linkwork.limits import MAX_MAGNITUDE, angle_problem

    value = quantity_option(text, kind, option, example)
    problem = angle_problem(math.degrees(value), option) if kind == "angle" else None
    if problem:
        fail(LinkworkError(problem))
    if not math.isfinite(value) or abs(value) > MAX_MAGNITUDE:
        size = f"a finite value of a machine's size (at most {MAX_MAGNITUDE:g} in SI)"
        fail(LinkworkError(f'{option}: expected {size}, got "{text}"'))
    return value


@app.command()
def simulate(
    file_or_example: FileOrExample,
    until: Annotated[str, typer.Option(help='length of the run, with its unit, e.g. "30 ms"')],
    angle: Annotated[
        str | None, typer.Option(help='crank angle to the x axis at the start, e.g. "30 deg" (default: assembly)')
    ] = None,
    speed: Annotated[
        str | None, typer.Option(help='crank speed at the start, counter-clockwise positive, e.g. "-50 rpm"; default 0')
    ] = None,
    samples: Annotated[int, typer.Option(help="equal time steps kept, ends included")] = 201,
    no_motor: Annotated[bool, typer.Option("--no-motor", help="leave the file's motor out: free motion")] = False,
    out: Annotated[
        str | None,
        typer.Option(help="folder for simulate.csv and simulate.json, or a file ending in .csv or .json for it alone"),
    ] = None,
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON object")] = False,
) -> None:
    """The machine unit run in time from a crank angle and speed: motor, loads, springs and dampers."""
    import numpy as np

    from linkwork.io.run_tables import csv_text, to_json
    from linkwork.limits import run_time_problem
    from linkwork.machine.timerun import simulate as run

    length = quantity_option(until, "time", "--until", "30 ms")
    problem = run_time_problem(length, "--until")
    if problem:
        fail(LinkworkError(problem))
    start = _quantity(angle, "angle", "--angle", "30 deg")
    rate = _quantity(speed, "angular_speed", "--speed", "50 rpm")
    if not 2 <= samples <= 100_000:
        fail(LinkworkError(f"--samples: expected 2 to 100000, got {samples}"))
    files = out_files(out, ("simulate.csv", "simulate.json")) if out is not None else []
    mech = compile_or_exit(file_or_example)
    bar = _Bar(length)
    try:
        result = run(
            mech,
            length,
            angle=start,
            speed=rate or 0.0,
            times=np.linspace(0, length, samples),
            motor=not no_motor,
            progress=bar.show,
        )
        data = to_json(result)
    except LinkworkError as exc:
        bar.close()
        fail(exc)
    bar.close()
    paths = _write(out, files, data, csv_text(result)) if out is not None else []
    if as_json:
        echo_json(data)
        return
    s = data["samples"]
    typer.echo(f"{mech.name}: run in time, {length:.6g} s ({result.evaluations} exact poses, rtol {result.rtol:g})")
    typer.echo(
        f"  end: crank at {s['crank_angle_to_x'][-1]:.4f} deg to x (phi {s['phi'][-1]:.4f} deg), turned "
        f"{s['turned'][-1]:.6g} deg, {result.speed[-1]:.9g} rad/s, {result.acceleration[-1]:.6g} rad/s^2"
    )
    for event in result.events:
        typer.echo(f"  {event.describe()}")
    for path in paths:
        typer.echo(f"  wrote {path}")


def _write(out: str, files: list[Path], data: dict[str, Any], csv: str) -> list[Path]:
    """The ``files`` of ``--out``: ``simulate.csv`` (the samples) and ``simulate.json`` (``data``)."""
    from linkwork.atomic import write_atomic
    from linkwork.io.jsonout import dumps

    bodies = {".json": dumps(data), ".csv": csv}
    try:
        return [
            write_atomic(p, functools.partial(Path.write_text, data=bodies[p.suffix.lower()], encoding="utf-8"))
            for p in files
        ]
    except OSError as exc:
        fail(LinkworkError(f"--out {out}: cannot write ({exc.strerror or exc})"))


class _Bar:
    """A progress bar of the simulated time on stderr where stderr is a terminal (rich), shown once the run has
    taken :data:`AFTER` seconds; nothing where stderr goes to a file or a program."""

    #: Seconds of work before the bar shows: a short run prints nothing more.
    AFTER = 1.0

    def __init__(self, until: float) -> None:
        import time

        from linkwork.cli.terminal import console

        self.until, self.begun = until, time.monotonic()
        self.bar: Any = None
        self.console = console(stderr=True)
        self.task: Any = None

    def show(self, t: float) -> None:
        """The run has reached ``t`` (s)."""
        import time

        if self.bar is None:
            if not self.console.is_terminal or time.monotonic() - self.begun < self.AFTER:
                return
            from rich.progress import BarColumn, Progress, TextColumn, TimeRemainingColumn

            self.bar = Progress(
                TextColumn("simulate"),
                BarColumn(),
                TextColumn("{task.completed:.4g} of {task.total:.4g} s"),
                TimeRemainingColumn(),
                console=self.console,
                transient=True,
            )
            self.bar.start()
            self.task = self.bar.add_task("simulate", total=self.until)
        self.bar.update(self.task, completed=t)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.stop()
