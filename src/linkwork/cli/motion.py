"""``linkwork kinematics`` and ``linkwork positions``."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING, Annotated, Any

import numpy as np
import typer

from linkwork.cli.app import (
    Angles,
    FileOrExample,
    Speed,
    Steps,
    app,
    check_options,
    compile_or_exit,
    drive_speed,
    echo_json,
    fail,
    make_console,
    make_table,
    needs,
    out_files,
    show,
)
from linkwork.errors import LinkworkError
from linkwork.lang import kind_named
from linkwork.limits import MAX_ANGLES, TURN_STEPS, angle_problem, quote, whole
from linkwork.units import turn_deg

if TYPE_CHECKING:
    from linkwork.structure.model import Mechanism
    from linkwork.study import Study

#: Why a quantity at an angle has no value (``nulls`` of the ``--json`` records).
NOT_ASSEMBLED = "the mechanism does not assemble at these angles (valid is false there)"

#: Why the values of ``linkwork kinematics --json`` may be null.
KINEMATICS_NULLS = {
    "points": NOT_ASSEMBLED,
    "links": NOT_ASSEMBLED,
    "events": "a stroke, its extreme positions and the time ratios are found over a whole turn only, "
    "where the mechanism assembles at every angle of it (the angles asked are not one, or it does not)",
}


def check_angles(steps: int | None, angles: str | None) -> list[float] | None:
    """The bounds of ``--steps`` and ``--angles`` (at most :data:`~linkwork.limits.MAX_ANGLES` angles,
    each within :data:`~linkwork.limits.MAX_TURNS` turns), checked before any work: exit code 2 with one
    line where they are passed.  Returns the numbers of ``--angles``, or None."""
    if steps is not None:
        check_options(whole(steps, "--steps", 1, MAX_ANGLES))
    if angles is None:
        return None
    try:
        values = [float(a) for a in angles.replace(" ", "").split(",") if a]
    except ValueError:
        fail(LinkworkError(f"--angles: expected numbers in degrees separated by commas, got {quote(angles)}"))
    if len(values) > MAX_ANGLES:
        fail(LinkworkError(f"--angles: expected at most {MAX_ANGLES:,} angles, got {len(values):,}"))
    return values


def _angles(mech: Mechanism, steps: int | None, angles: str | None) -> dict[str, Any]:
    """Keyword arguments of lw.kinematics from the options; crank angles in degrees, or slider
    positions in mm for a linear drive."""
    from linkwork.structure.model import one_crank

    given = check_angles(steps, angles)
    if mech.n_drives != 1:
        fail(
            LinkworkError(
                f"the command line drives one input; this mechanism has {mech.n_drives} drives "
                "(use linkwork.kinematics in Python with angles of shape (n, drives))"
            )
        )
    revolute = one_crank(mech)
    if steps is not None and angles is not None:
        fail(LinkworkError("give either --steps or --angles, not both"))
    if given is not None:
        unit = "degrees" if revolute else "mm"
        if not given:
            fail(LinkworkError("--angles: no angles given"))
        if not all(math.isfinite(v) for v in given):
            fail(LinkworkError(f"--angles: expected finite numbers in {unit}, got {quote(angles)}"))
        if revolute:
            check_options(angle_problem(max(given, key=abs), "--angles"))
        return {"angles": np.radians(given) if revolute else np.array(given) / 1000}
    if not revolute:
        fail(
            LinkworkError(
                "--steps needs a crank (a revolute drive); for a linear drive give --angles as positions in mm"
            )
        )
    return {"steps": steps or TURN_STEPS}


def study_of(mech: Mechanism, steps: int | None, angles: str | None, speed: str | None) -> Study:
    """The study (:class:`~linkwork.study.Study`) of the cycle the options ask for: the ``--angles`` (degrees; a
    linear drive's positions, mm), or ``--steps`` equal steps of a turn from the assembly pose (as
    :func:`linkwork.kinematics`'s ``steps``), at ``--speed``; exit code 2 with one line where they are wrong
    (:func:`_angles`, :func:`~linkwork.cli.app.drive_speed`)."""
    from linkwork.study import Study

    where = _angles(mech, steps, angles)
    rate = drive_speed(mech, speed)
    if "angles" in where:
        return Study(mech, angles=where["angles"], speed=rate)
    return Study(mech, where["steps"], start=float(mech.drive_start[0]), speed=rate)


def _where(mech: Mechanism, named: bool = True) -> Callable[[float], str]:
    """How the command writes where a value is: φ turned from position 0 with one crank (``phi = 102.0 deg``,
    as the report; ``102.0 deg`` unless ``named``, in a column headed "at phi"), else the first drive's
    coordinate (its angle to x, or a linear drive's mm)."""
    from linkwork.motion.analysis import CrankAngles
    from linkwork.structure.model import PairType

    crank = CrankAngles.of(mech)
    if crank is not None:
        name = "phi = " if named else ""
        return lambda angle: f"{name}{crank.phi(angle, 1):.1f} deg"
    if mech.pair_type[mech.drive_pair[0]] == PairType.REVOLUTE:
        return lambda angle: f"{turn_deg(angle):.1f} deg to x"
    return lambda position: f"{position * 1000:.6g} mm"


@app.command()
def kinematics(
    file_or_example: FileOrExample,
    steps: Steps = None,
    angles: Angles = None,
    speed: Speed = None,
    out: Annotated[
        str | None,
        typer.Option(help="folder for kinematics.csv and kinematics.nc, or a file ending in .csv or .nc for it alone"),
    ] = None,
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON object")] = False,
) -> None:
    """Positions, velocities and accelerations of every point and link over the cycle."""
    from linkwork.io.motion_tables import to_json, write_csv, write_netcdf
    from linkwork.motion.analysis import extremes, transmission_angles

    check_angles(steps, angles)
    files = out_files(out, ("kinematics.csv", "kinematics.nc")) if out is not None else []
    if any(p.suffix.lower() == ".nc" for p in files):
        needs("xarray", purpose=f"--out {out}: kinematics.nc (NetCDF)")
    mech = compile_or_exit(file_or_example)
    study = study_of(mech, steps, angles, speed)
    try:
        kin = study.kin
    except LinkworkError as exc:
        fail(exc)
    ext = extremes(kin) if angles is None else []
    written = []
    if files:
        try:
            written += [(write_netcdf if p.suffix.lower() == ".nc" else write_csv)(kin, p) for p in files]
        except OSError as exc:
            fail(LinkworkError(f"--out {out}: cannot write ({exc.strerror or exc})"))
    if as_json:
        echo_json(to_json(kin, ext), why=KINEMATICS_NULLS)
        return
    n_ok = int(np.sum(kin.valid))
    typer.echo(f"{mech.name}: {len(kin.angles)} positions, {n_ok} assembled")
    where = _where(mech)
    for e in ext:
        ratios = f"time ratio K {e.time_ratio:.4f} (+ stroke over the other {e.forward_time_ratio:.4f})"
        if e.kind == "slider":
            typer.echo(
                f"  {kind_named('slider', e.name)}: stroke {e.stroke * 1000:.2f} mm, from {e.low * 1000:.2f} to "
                f"{e.high * 1000:.2f} mm (at {where(e.at_low)} and {where(e.at_high)}), {ratios}"
            )
        else:
            typer.echo(f"  {kind_named('rocker', e.name)}: swing {math.degrees(e.stroke):.3f} deg, {ratios}")
    for label, mu in transmission_angles(kin).items():
        if np.any(np.isfinite(mu)):
            i = int(np.nanargmin(mu))
            least = math.degrees(mu[i])
            typer.echo(f"  {label}: least transmission angle {least:.2f} deg at {where(kin.angles[i])}")
    for event in kin.events:
        typer.echo(f"  {event.kind}: {event.message}")
    for path in written:
        typer.echo(f"  wrote {path}")


def _mm(value: float) -> str:
    """A coordinate in mm to 0.1 mm, without the sign of a zero ("0.0", not "-0.0")."""
    return f"{round(value, 1) + 0.0:.1f}"


@app.command()
def positions(
    file_or_example: FileOrExample,
    count: Annotated[int, typer.Option(help="number of positions over the turn")] = 12,
    zero: Annotated[
        float | None,
        typer.Option(
            help="crank angle of position 0, deg (default: the working "
            "slider at the top of its stroke, e.g. the knives open)"
        ),
    ] = None,
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON object")] = False,
) -> None:
    """The plan of positions: coordinates of the points at COUNT crank positions (mm)."""
    from linkwork.motion import analysis, cycle
    from linkwork.motion import kinematics as solve
    from linkwork.structure.model import point_labels

    check_options(
        whole(count, "--count", 1, MAX_ANGLES, "number of positions"),
        angle_problem(zero, "--zero") if zero is not None else None,
    )
    mech = compile_or_exit(file_or_example)
    try:
        sign = 1.0 if cycle(mech, 2)[1] > cycle(mech, 2)[0] else -1.0  # checks for a crank first
        start = math.radians(zero) if zero is not None else analysis.zero_angle(mech)
        values = start + sign * 2 * math.pi * np.arange(count) / count
        kin = solve(mech, values)
    except LinkworkError as exc:
        fail(exc)
    labels = point_labels(mech)
    crank = analysis.CrankAngles(start, sign)
    names = [label for label, _ in labels]
    mm = [np.round(kin.position(mech.point_names[p]) * 1000, 3) for _, p in labels]
    phi = np.asarray(crank.phi(values), dtype=float)
    to_x = np.asarray(analysis.to_x_deg(values), dtype=float)
    columns = [phi.tolist(), to_x.tolist(), *(c.tolist() for c in mm)]
    rows: list[dict[str, Any]] = [
        {"position": k, "phi_deg": a, "crank_angle_to_x_deg": x, **dict(zip(names, points, strict=True))}
        for k, (a, x, *points) in enumerate(zip(*columns, strict=True))
    ]
    for k in np.flatnonzero(np.isnan(np.stack(mm, axis=1)).any(axis=(1, 2))):  # None in the JSON, "-" in the table
        rows[k].update({n: [None if c != c else c for c in rows[k][n]] for n in names})
    if as_json:
        echo_json({"name": mech.name, "unit": "mm", "positions": rows}, why={"positions": NOT_ASSEMBLED})
        return
    from rich.markup import escape

    tab = make_table(f"{escape(mech.name)}: {count} positions (coordinates in mm)")
    tab.add_column("pos")
    tab.add_column("phi, deg")
    tab.add_column("crank to x, deg")
    for label, _ in labels:
        tab.add_column(escape(label))
    for row in rows:
        cells = ["-" if row[label][0] is None else ", ".join(_mm(c) for c in row[label]) for label, _ in labels]
        tab.add_row(str(row["position"]), f"{row['phi_deg']:.1f}", f"{row['crank_angle_to_x_deg']:.1f}", *cells)
    show(make_console(), tab, keep=2)
