"""``linkwork forces`` and ``linkwork balance``."""

from __future__ import annotations

import functools
import math
from pathlib import Path
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
    echo_json,
    explain_nulls,
    fail,
    make_console,
    make_table,
    out_files,
    show,
)
from linkwork.cli.motion import NOT_ASSEMBLED, _where, check_angles, study_of
from linkwork.limits import MAX_ANGLES, MAX_NAME, TURN_STEPS, quote, whole
from linkwork.units import parse_quantity

# what a command needs is imported when it runs, so that the command line starts fast
if TYPE_CHECKING:
    from rich.console import Console
    from rich.table import Table

    from linkwork.kinetostatics.balancing import Balance
    from linkwork.kinetostatics.reaction_forces import Forces
    from linkwork.study import Study


#: Why the values of ``linkwork forces --json`` may be null.
#: Why the forces have no value at a sample: as the kinematics, and where friction locks the mechanism.
NOT_MOVING = f"{NOT_ASSEMBLED}, or friction locks it there (efficiency.friction.problems)"

FORCES_NULLS = {
    "joints": "the reactions of a group are indeterminate at its dead or change points (singular), and have "
    "no value where the mechanism does not assemble or friction locks it",
    "driving_torque": NOT_MOVING,
    "foundation": NOT_MOVING,
    "shaking": NOT_ASSEMBLED,
    "loads": NOT_ASSEMBLED,
    "bolts.speed_for_pull_rad_s": "the machine's inertia never pulls the bolts that hard, at any crank speed",
}

#: Why the values of ``linkwork balance --json`` may be null.
BALANCE_NULLS = {
    "before": "the forces of the mechanism have no value at any angle",
    "after": "the forces of the mechanism with its counterweights have no value at any angle (a counterweight "
    "too heavy or too far out to compute)",
}


def _torque_peak(f: Forces) -> tuple[float, float]:
    """The peak driving torque and its drive angle, refined between the samples
    (:func:`linkwork.kinetostatics.torque_peak`)."""
    from linkwork.kinetostatics.peaks import torque_peak

    peak = torque_peak(f)
    return float(peak.value[0]), float(peak.at[0])


@app.command()
def forces(
    file_or_example: FileOrExample,
    steps: Steps = None,
    angles: Angles = None,
    speed: Speed = None,
    pull: Annotated[
        str | None,
        typer.Option(help='also find the crank speed at which the pull on the bolts reaches this force, e.g. "5 kN"'),
    ] = None,
    out: Annotated[
        str | None,
        typer.Option(help="folder for forces.csv and forces.json, or a file ending in .csv or .json for it alone"),
    ] = None,
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON object")] = False,
) -> None:
    """Joint reactions, driving torque, foundation and bolt loads over the cycle, with the checks."""
    from linkwork.errors import LinkworkError
    from linkwork.io.force_tables import to_json
    from linkwork.kinetostatics.tables import CONVENTION, pair_labels

    check_angles(steps, angles)
    files = out_files(out, ("forces.csv", "forces.json")) if out is not None else []
    mech = compile_or_exit(file_or_example)
    study = study_of(mech, steps, angles, speed)
    target = _force(pull)
    try:
        f = study.forces
        lift = _lift(study, target) if target is not None else None
    except LinkworkError as exc:
        fail(exc)
    data = to_json(f)
    if lift is not None:
        data["bolts"]["pull_target"] = target
        data["bolts"]["speed_for_pull_rad_s"] = lift if math.isfinite(lift) else None
    data = explain_nulls(data, FORCES_NULLS)
    written = _write(f, data, out, files) if out is not None else []
    if as_json:
        echo_json(data)
        return
    _report(f, pair_labels(mech), CONVENTION, data["groups"])
    if lift is not None:
        text = (
            f"{lift:.6g} rad/s ({lift * 30 / math.pi:.6g} rpm)"
            if math.isfinite(lift)
            else "none: the machine's inertia never lifts it"
        )
        typer.echo(f"  crank speed at which the pull on the bolts reaches {target:.6g} N: {text}")
    for path in written:
        typer.echo(f"  wrote {path}")


def _write(f: Forces, data: dict[str, Any], out: str, files: list[Path]) -> list[Path]:
    """Write the ``files`` of ``--out`` (:func:`~linkwork.cli.app.out_files`): ``forces.csv`` and
    ``forces.json`` (``data``); the paths written."""
    from linkwork.atomic import write_atomic
    from linkwork.errors import LinkworkError
    from linkwork.io.force_tables import write_csv
    from linkwork.io.jsonout import dumps

    written = []
    try:
        for path in files:
            if path.suffix.lower() == ".json":
                text = dumps(data)
                written.append(write_atomic(path, functools.partial(Path.write_text, data=text, encoding="utf-8")))
            else:
                written.append(write_csv(f, path))
    except OSError as exc:
        fail(LinkworkError(f"--out {out}: cannot write ({exc.strerror or exc})"))
    return written


def _force(text: str | None) -> float | None:
    """The force of ``--pull`` in SI."""
    from linkwork.errors import LinkworkError, UnitParseError

    if text is None:
        return None
    try:
        value = parse_quantity(text, "force")
    except UnitParseError as exc:
        fail(LinkworkError(f"--pull: {exc}"))
    if value < 0:
        fail(LinkworkError(f'--pull: expected a force from 0 up, got "{text}"'))
    return value


def _lift(study: Study, pull: float) -> float:
    """The crank speed (rad/s) at which the pull on the bolts reaches ``pull`` (N)
    (:meth:`~linkwork.study.Study.bolt_speed`)."""
    from linkwork.errors import LinkworkError
    from linkwork.structure.model import PairType

    mech = study.mech
    if mech.pair_type[mech.drive_pair[0]] != PairType.REVOLUTE:
        raise LinkworkError("--pull needs a crank (a revolute drive) turning uniformly")
    return study.bolt_speed(pull)


def _report(f: Forces, labels: list[tuple[str, int]], convention: str, groups: list[dict[str, Any]]) -> None:
    """The report of ``linkwork forces`` on the terminal: the driving torque, the largest pair forces (one
    row per pair in ``labels``), the free bodies of the ``groups``, the foundation and the checks."""
    from rich.markup import escape

    from linkwork.structure.model import PairType

    mech, phi = f.mechanism, f.angles
    out = make_console()
    rate = float(f.kinematics.rates[0, 0])
    revolute = mech.pair_type[mech.drive_pair[0]] == PairType.REVOLUTE
    speed = f"{abs(rate) * 30 / math.pi:.6g} rpm" if revolute else f"{abs(rate):.6g} m/s"
    ok = np.isfinite(f.driving_torque)
    out.print(f"{escape(mech.name)}: {len(phi)} positions at {speed}, {int(ok.sum())} solved")
    where = _where(mech)
    if not ok.all():
        out.print(
            f"  reactions indeterminate (singular or unassembled) at {int((~ok).sum())} positions, "
            f"e.g. {', '.join(where(a) for a in phi[~ok][:6])}"
        )
    if not ok.any():
        return
    unit = "N m" if revolute else "N"
    from linkwork.kinetostatics.crosschecks import cross_checks
    from linkwork.kinetostatics.peaks import UNBOUNDED

    t, at = _torque_peak(f)
    if math.isinf(t):
        out.print(f"  driving torque: {UNBOUNDED}, at {where(at)}", soft_wrap=True)
    else:
        out.print(f"  driving torque: peak {t:.6g} {unit} at {where(at)}")
    table, note = _pair_table(f, labels)
    show(out, table)
    if note is not None:
        out.print(note, soft_wrap=True)
    for g in groups:
        out.print(
            f"  {escape(g['group'])}: held by {escape(', '.join(g['external']))}"
            + (f"; inner {escape(', '.join(g['internal']))}" if g["internal"] else "")
            + f"; balance of the free body {g['residual']:.1e}"
        )
    _report_foundation(f, out)
    _report_efficiency(f, out)
    checks = ", ".join(f"{k.replace('_', ' ')} {v:.1e}" for k, v in cross_checks(f).items() if math.isfinite(v))
    out.print(f"  checks (relative discrepancy): {checks}", soft_wrap=True)
    out.print(f"  {escape(convention)}", soft_wrap=True)


def _report_efficiency(f: Forces, out: Console) -> None:
    """With friction in the pairs: how the friction in proportion to the forces was solved and where it has no
    solution, the power lost in each joint over the samples, the instantaneous and the cycle's efficiency."""
    from rich.markup import escape

    from linkwork.io.force_tables import has_losses
    from linkwork.kinetostatics.friction import TOLERANCE

    if not has_losses(f):
        return
    if f.friction is not None:
        fr = f.friction
        out.print(
            f"  friction in proportion to the pair forces: solved to {TOLERANCE:.0e} in {fr.iterations} Newton "
            f"steps (largest residual {fr.residual:.1e})"
        )
        for problem in fr.problems:
            out.print(f"  warning: {escape(str(problem))}", soft_wrap=True)
    e = f.efficiency
    drive = float(e.work(e.drive))
    lost = ", ".join(f"{escape(j)} {float(w):.6g} J" for j, w in zip(e.joints, e.work(e.losses), strict=True))
    out.print(
        f"  work over the samples: drive {drive:.6g} J, useful loads {float(e.work(e.useful)):.6g} J; "
        f"lost to friction: {lost}",
        soft_wrap=True,
    )
    eta = e.instantaneous
    eta = np.where(np.abs(eta) < 1e-9, 0.0, eta)  # a drive that gives just the friction's power: 0, not its rounding
    span = (
        f"from {np.nanmin(eta):.4g} to {np.nanmax(eta):.4g} where the drive gives power"
        if np.isfinite(eta).any()
        else "none (the drive never gives power)"
    )
    cycle = float(e.cycle)
    of_cycle = f"{cycle:.4g} (useful work / drive work)" if math.isfinite(cycle) else "none"
    out.print(f"  efficiency: of the cycle {of_cycle}; instantaneous {span}", soft_wrap=True)


def _pair_table(f: Forces, labels: list[tuple[str, int]]) -> tuple[Table, str | None]:
    """The largest force of each pair of ``labels`` (label, pair) over the cycle, where it is, and a prismatic
    pair's largest moment; and a line that says why some are unbounded (None where none is)."""
    from rich.markup import escape

    from linkwork.kinetostatics.peaks import UNBOUNDED, pair_force_peaks, pair_moment_peaks
    from linkwork.kinetostatics.tables import pair_kind, pair_moment
    from linkwork.structure.model import one_crank
    from linkwork.zeros import snap_zeros

    mech = f.mechanism
    at = _where(mech, named=False)
    tab = make_table("largest pair forces over the cycle")
    head = "at phi" if one_crank(mech) else "at"
    for col in ("joint", "first on second", "|F| max, N", head, "moment max, N m"):
        tab.add_column(col)
    refined = pair_force_peaks(f, [k for _, k in labels])  # refined between the samples, as the report gives them
    peaks = [(float(v), float(a)) for v, a in zip(refined.value, refined.at, strict=True)]
    values = snap_zeros(np.array([value for value, _ in peaks]))
    prismatic = [pair_kind(mech, k) == "prismatic" for _, k in labels]
    guides = [k for (_, k), p in zip(labels, prismatic, strict=True) if p]
    largest = dict(zip(guides, pair_moment_peaks(f, guides).value.tolist(), strict=True))  # refined, as the forces
    # a moment that is zero at every sample (its round-off snapped to zero) stays a zero
    moments = [
        (largest[k] if np.any(np.abs(pair_moment(f, k)) > 0) else 0.0) if p else np.nan
        for (_, k), p in zip(labels, prismatic, strict=True)
    ]
    for (label, k), value, (_, where), moment, p in zip(labels, values, peaks, moments, prismatic, strict=True):
        a, b = (mech.link_names[int(i)] for i in mech.pair_members[k])
        shown = _size(moment) if p else "-"
        tab.add_row(escape(label), escape(f"{a} on {b}"), _size(value), at(where), shown)
    note = f"  {UNBOUNDED}; its angle is given" if np.isinf(values).any() or np.isinf(moments).any() else None
    return tab, note


def _size(value: float) -> str:
    """A largest force or moment as the table shows it: ``unbounded`` where it grows without bound towards a
    singular position (:func:`linkwork.kinetostatics.peaks.refine`)."""
    return "unbounded" if math.isinf(value) else f"{value:.6g}"


def _report_foundation(f: Forces, out: Console) -> None:
    """The extremes of the foundation loads and of the shaking force and moment, with their angles, refined between
    the samples (:meth:`~linkwork.kinetostatics.Forces.bolts`, :func:`~linkwork.kinetostatics.peaks.shaking_peaks`)."""
    from linkwork.kinetostatics.peaks import shaking_peaks

    at = _where(f.mechanism)
    bolts = f.bolts()
    pull = f"{bolts.pull:.6g} N at {at(bolts.pull_angle)}" if bolts.pull > 0 else "none (the machine never lifts)"
    out.print(f"  foundation: horizontal (bolt shear) max {bolts.shear:.6g} N at {at(bolts.shear_angle)}")
    out.print(f"              pull on the bolts max {pull}")
    out.print(f"              push on the foundation max {bolts.push:.6g} N at {at(bolts.push_angle)}")
    out.print(f"              moment about the origin max {bolts.moment:.6g} N m at {at(bolts.moment_angle)}")
    shaking = shaking_peaks(f)
    (s, m), (s_at, m_at) = shaking.value.tolist(), shaking.at.tolist()
    out.print(f"  shaking force max {s:.6g} N at {at(s_at)}, shaking moment max {abs(m):.6g} N m at {at(m_at)}")


@app.command()
def balance(
    file_or_example: FileOrExample,
    links: Annotated[str, typer.Option(help="links for counterweights, e.g. crank,rocker")],
    first_harmonic: Annotated[
        bool, typer.Option("--first-harmonic", help="cancel the first harmonic of the shaking force only")
    ] = False,
    radius: Annotated[
        str | None, typer.Option(help='distance of the counterweights from their pivots, e.g. "120 mm"')
    ] = None,
    steps: Annotated[int, typer.Option(help="equal steps over one turn of the crank")] = TURN_STEPS,
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON object")] = False,
) -> None:
    """Counterweights that cancel the shaking force (or its first harmonic), with the figures before and after."""
    from linkwork.errors import LinkworkError, UnitParseError
    from linkwork.study import Study

    names = [n.strip() for n in links.split(",") if n.strip()]
    check_options(
        whole(steps, "--steps", 1, MAX_ANGLES),
        *(
            f"--links: no link is named {quote(n)}: names are at most {MAX_NAME} characters"
            for n in names
            if len(n) > MAX_NAME
        ),
    )
    mech = compile_or_exit(file_or_example)
    r = None
    if radius is not None:
        try:
            r = parse_quantity(radius, "length")
        except UnitParseError as exc:
            fail(LinkworkError(f"--radius: {exc}"))
    study = Study(mech, steps, start=float(mech.drive_start[0]))  # the turn from the assembly pose, as lw.balance's
    try:
        result = study.balance(names, harmonic=1 if first_harmonic else None, radius=r)
    except LinkworkError as exc:
        fail(exc)
    if as_json:
        from linkwork.kinetostatics.peaks import UNBOUNDED

        summary = result.summary()
        out = {
            "name": mech.name,
            "mode": "first harmonic" if first_harmonic else "full",
            "counterweights": [w.as_dict() for w in result.counterweights],
            **summary,
        }
        endless = {f"{k}.pair_force_peak": UNBOUNDED for k, v in summary.items() if math.isinf(v["pair_force_peak"])}
        echo_json(out, why=endless | BALANCE_NULLS)
        return
    _report_balance(mech.name, result, first_harmonic)


def _report_balance(name: str, result: Balance, first_harmonic: bool) -> None:
    """The report of ``linkwork balance`` on the terminal: the counterweights and the figures before and after."""
    summary = result.summary()
    mode = "first harmonic of the shaking force" if first_harmonic else "shaking force"
    typer.echo(f"{name}: counterweights against the {mode}")
    for w in result.counterweights:
        typer.echo(
            f"  {w.link}: m r = {w.mass_radius:.6g} kg m at {math.degrees(w.angle):.2f} deg from the link's axis "
            f"about {w.pivot}; {w.mass:.6g} kg at {w.radius * 1000:.6g} mm"
        )
    rows = [
        ("shaking force, peak", "shaking_force_peak", "N"),
        ("shaking force, rms", "shaking_force_rms", "N"),
        ("shaking moment, peak", "shaking_moment_peak", "N m"),
        ("driving torque, peak", "driving_torque_peak", "N m"),
        ("largest pin force", "pair_force_peak", "N"),
    ]
    typer.echo(f"  {'':24s} {'before':>14s} {'after':>14s}")
    for text, key, unit in rows:
        before, after = (_size(summary[k][key]) for k in ("before", "after"))
        typer.echo(f"  {text + ', ' + unit:24s} {before:>14s} {after:>14s}")
