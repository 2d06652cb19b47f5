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
    value = quantity_option(text, kind, option, example)
    if not math.isfinite(value) or abs(value) > 1e9:
        fail(LinkworkError(f'{option}: expected a finite value of a machine\'s size, got "{text}"'))
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
    from linkwork.machine.timerun import simulate as run

    length = _quantity(until, "time", "--until", "30 ms")
    assert length is not None
    if not length > 0:
        fail(LinkworkError(f'--until: expected a positive time, got "{until}"'))
    start = _quantity(angle, "angle", "--angle", "30 deg")
    rate = _quantity(speed, "angular_speed", "--speed", "50 rpm")
    if not 2 <= samples <= 100_000:
        fail(LinkworkError(f"--samples: expected 2 to 100000, got {samples}"))
    files = out_files(out, ("simulate.csv", "simulate.json")) if out is not None else []
    mech = compile_or_exit(file_or_example)
    try:
        result = run(
            mech, length, angle=start, speed=rate or 0.0, times=np.linspace(0, length, samples), motor=not no_motor
        )
        data = to_json(result)
    except LinkworkError as exc:
        fail(exc)
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
