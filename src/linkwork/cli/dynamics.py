"""``linkwork dynamics``: reduced inertia, the run of the machine unit, the flywheel."""

from __future__ import annotations

import functools
import math
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Any

import numpy as np
import typer

from linkwork.cli.app import (
    FileOrExample,
    app,
    check_options,
    compile_or_exit,
    echo_json,
    explain_nulls,
    fail,
    out_files,
)
from linkwork.errors import LinkworkError
from linkwork.limits import DYNAMICS_STEPS, MAX_ANGLES, delta_problem, whole
from linkwork.units import turn_deg

if TYPE_CHECKING:
    from linkwork.machine import Dynamics
    from linkwork.structure.model import Mechanism


@app.command()
def dynamics(
    file_or_example: FileOrExample,
    delta: Annotated[
        float | None, typer.Option(help="size a flywheel for this coefficient of speed fluctuation, e.g. 0.05")
    ] = None,
    steps: Annotated[int, typer.Option(help="crank angles over a turn for the reduced quantities")] = DYNAMICS_STEPS,
    out: Annotated[
        str | None,
        typer.Option(help="folder for dynamics.csv and dynamics.json, or a file ending in .csv or .json for it alone"),
    ] = None,
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON object")] = False,
) -> None:
    """Reduced inertia and loads, the run of the machine unit from rest to its steady cycle, the flywheel."""
    from linkwork.io.dynamics_tables import to_json
    from linkwork.study import DynamicsOptions, Study

    check_options(whole(steps, "--steps", 1, MAX_ANGLES), delta_problem(delta, "--delta"))
    files = out_files(out, ("dynamics.csv", "dynamics.json")) if out is not None else []
    mech = compile_or_exit(file_or_example)
    try:
        result = Study(mech, dynamics=DynamicsOptions(delta=delta, steps=steps)).dynamics
    except LinkworkError as exc:
        fail(exc)
    data = explain_nulls(to_json(mech, result), {})
    paths = _write(out, files, data) if out is not None else []
    if as_json:
        echo_json(data)
        return
    _print_report(mech, result, data)
    for path in paths:
        typer.echo(f"  wrote {path}")


def _write(out: str, files: list[Path], data: dict[str, Any]) -> list[Path]:
    """The ``files`` of ``--out`` (:func:`~linkwork.cli.app.out_files`): ``dynamics.csv`` (the steady
    cycle) and ``dynamics.json`` (``data``)."""
    from linkwork.atomic import write_atomic
    from linkwork.io.jsonout import dumps
    from linkwork.machine.tables import CYCLE_COLUMNS

    cycle = data["cycle"]
    rows = [",".join(CYCLE_COLUMNS[key] for key in cycle)]
    rows += [",".join(repr(v) for v in row) for row in zip(*cycle.values(), strict=True)]
    text = dumps(data)
    try:
        bodies = {".json": text, ".csv": "\n".join(rows) + "\n"}
        paths = [
            write_atomic(p, functools.partial(Path.write_text, data=bodies[p.suffix.lower()], encoding="utf-8"))
            for p in files
        ]
    except OSError as exc:
        fail(LinkworkError(f"--out {out}: cannot write ({exc.strerror or exc})"))
    return paths


def _print_report(mech: Mechanism, result: Dynamics, data: dict[str, Any]) -> None:
    """The report of ``linkwork dynamics`` (``data``: its JSON record, for the crank angles of the cycle)."""
    from linkwork.motion.kinematic_analysis import direction

    rpm = 30 / math.pi
    red = result.reduced
    typer.echo(f"{mech.name}: machine dynamics")
    typer.echo(
        f"  reduced inertia of the mechanism {red.inertia.min():.6g} to {red.inertia.max():.6g} kg m^2; "
        f"mean load moment {red.mean_load:.6g} N m ({-red.mean_load * 2 * math.pi:.6g} J a turn)"
    )
    if result.flywheel is not None:
        f = result.flywheel
        beside = "" if f.shaft == "crank" else f" ({f.on_crank:.6g} kg m^2 reduced to the crank)"
        typer.echo(
            f"  flywheel for delta = {f.delta:g} at {f.omega_mean * rpm:.4g} rpm (Wittenbauer): energy swing "
            f"{f.energy_swing:.6g} J, constant inertia {f.inertia:.6g} kg m^2 on the crank; the flywheel "
            f"{f.flywheel:.6g} kg m^2 on the {f.shaft} shaft{beside}"
        )
    last = result.motion.last
    typer.echo(
        f"  steady cycle: crank {last.omega_mean * rpm:.4g} rpm mean, {last.omega_min * rpm:.4g} to "
        f"{last.omega_max * rpm:.4g} rpm, delta = {last.delta:.4g}"
        + ("" if result.motion.steady else " (not yet steady)")
    )
    _, psi, omega = result.motion.cycle()
    i = int(np.argmin(omega))
    angle = turn_deg(float(red.angle[0]) + direction(mech) * (result.motion.cycle_start + float(psi[i])))
    typer.echo(
        f"  lowest speed at {data['cycle']['phi_deg'][i]:.1f} deg from position 0 "
        f"(the crank at {angle:.1f} deg to the x axis)"
    )
    typer.echo(
        f"  mean power of the motor {result.mean_power:.6g} W at its shaft, of the drive {result.drive_power:.6g} W "
        f"on the crank; start-up {result.startup_time:.3g} s (idle, where the file has process loads)"
    )
    need = result.mean_power
    rated = getattr(result.drive.motor, "power", None)
    line = f"  motor: at least {need:.6g} W of continuous rating (its mean power over the cycle)"
    if rated:
        line += f"; the rated {rated:.6g} W is loaded to {need / rated:.0%}"
    typer.echo(line)
