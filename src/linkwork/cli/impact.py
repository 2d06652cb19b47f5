"""``linkwork impact``: the blow of a file's ``impact:`` section, whole mechanism and reduced model."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Annotated, Any

import typer

from linkwork.cli.app import FileOrExample, app, check_options, compile_or_exit, echo_json, fail
from linkwork.errors import LinkworkError
from linkwork.limits import MAX_BLOWS, whole

if TYPE_CHECKING:
    from linkwork.impulse import Blow, Impact, Phase, RockerImpact, WorkingCycle
    from linkwork.motion.analysis import CrankAngles
    from linkwork.structure.model import Mechanism
    from linkwork.structure.records import ImpactRecord


def _xy(v: Any) -> dict[str, float]:
    return {"x": float(v[0]), "y": float(v[1])}


@app.command()
def impact(
    file_or_example: FileOrExample,
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON object")] = False,
    cycle: Annotated[
        bool,
        typer.Option(
            "--cycle",
            help="run the working cycle with the file's machine: and the impact: section's tool: every blow, "
            "the rebounds and the contact phase, until the steady cycle",
        ),
    ] = False,
    blows: Annotated[
        int | None, typer.Option("--blows", help="with --cycle: at most this many blows (default 200)")
    ] = None,
) -> None:
    """Impulses of a blow in the pose of the file: on the striker, in every joint, the speed after,
    the energy lost, the ideal centre of mass; and the reduced model of seed 004 beside them.
    With --cycle: the machine's working cycle, blow after blow."""
    if blows is not None and not cycle:
        fail(LinkworkError("--blows: only with --cycle"))
    check_options(whole(blows, "--blows", 3, MAX_BLOWS, "number of blows") if blows is not None else None)
    mech = compile_or_exit(file_or_example)
    blow = mech.blow
    if blow is None:
        fail(LinkworkError('the mechanism has no blow: give an "impact:" section (at, normal, omega, restitution)'))
    if cycle:
        _cycle(mech, as_json, blows)
    else:
        _blow(mech, blow, as_json)


def _blow(mech: Mechanism, blow: ImpactRecord, as_json: bool) -> None:
    """``linkwork impact``: the file's blow (``blow``, the mechanism's) on the whole mechanism and on seed 004's
    reduced model."""
    from linkwork.impulse import impact as solve
    from linkwork.impulse import reduced_model

    striker = blow.at.split(".", 1)[0]
    try:
        whole = solve(mech)
        model = None
        if blow.rod_joint is not None:
            own = float(whole.velocities_before[mech.link_names.index(striker), 2])
            kw = dict(normal=(math.cos(blow.normal), math.sin(blow.normal)), restitution=blow.restitution)
            model = reduced_model(
                mech, at=blow.at, rod_joint=blow.rod_joint, omega_before=own, friction=blow.friction, **kw
            )
    except LinkworkError as exc:
        fail(exc)
    out = _blow_json(mech, whole, blow.link or striker)
    if model is not None:
        out["model"] = {"striker": striker, **model.as_dict()}
    if as_json:
        echo_json(out)
    else:
        _print_blow(mech, blow, whole, out, model)


def _blow_json(mech: Mechanism, whole: Impact, link: str) -> dict[str, Any]:
    """The JSON object of ``linkwork impact --json`` (``link``: whose angular speed it gives)."""
    from linkwork.impulse.mechanism import joint_links

    i = mech.link_names.index(link)
    joints = {name: {"on": b, "from": a, **_xy(whole.joints[name])} for name, (a, b) in joint_links(mech).items()}
    return {
        "name": mech.name,
        "units": {"impulse": "N s", "omega": "rad/s", "energy": "J", "length": "m"},
        "convention": "impulses in global axes; support_impulse: what each joint's first-named link "
        "exerts on the second ('from' on 'on')",
        "link": link,
        "impulse": _xy(whole.impulse),
        "support_impulse": joints,
        "omega_before": float(whole.velocities_before[i, 2]),
        "omega_after": float(whole.velocities_after[i, 2]),
        "crank_speed_before": whole.speed_before,
        "crank_speed_after": whole.speed_after,
        "energy_loss": whole.energy_loss,
        "ideal_com": _xy(whole.ideal_com) if whole.ideal_com is not None else None,
        "drive_impulse": whole.drive_impulse,
        "sliding_reverses": whole.sliding_reverses,
    }


def _print_blow(
    mech: Mechanism, blow: ImpactRecord, whole: Impact, out: dict[str, Any], model: RockerImpact | None
) -> None:
    """The report of ``linkwork impact`` on the mechanism's blow ``blow``, from its JSON object ``out``."""
    typer.echo(f"{mech.name}: blow of {blow.at}, R = {blow.restitution:g}, f = {blow.friction:g}")
    typer.echo(
        f"  whole mechanism: impulse on the striker ({whole.impulse[0]:.6g}, {whole.impulse[1]:.6g}) N s; "
        f"{out['link']} {out['omega_before']:.6g} -> {out['omega_after']:.6g} rad/s; energy lost "
        f"{whole.energy_loss:.6g} J"
    )
    for name, j in out["support_impulse"].items():
        typer.echo(f"    joint {name}: {j['from']} on {j['on']} ({j['x']:.6g}, {j['y']:.6g}) N s")
    if whole.ideal_com is not None:
        striker = blow.at.split(".", 1)[0]
        typer.echo(f"    ideal centre of mass of {striker}: ({whole.ideal_com[0]:.6g}, {whole.ideal_com[1]:.6g}) m")
    if whole.sliding_reverses:
        typer.echo(
            "    note: with R > 0 the striker's sliding on the surface reverses within the blow; friction is "
            "taken one way throughout, as in seed 004's model"
        )
    if model is not None:
        typer.echo(
            f"  reduced model (rod as a point mass at {blow.rod_joint}): impulse ({model.impulse[0]:.6g}, "
            f"{model.impulse[1]:.6g}) N s, support ({model.support_impulse[0]:.6g}, {model.support_impulse[1]:.6g}) "
            f"N s; ideal centre of mass ({model.ideal_com[0]:.6g}, {model.ideal_com[1]:.6g}) m, without the rod "
            f"({model.ideal_com_without_rod[0]:.6g}, {model.ideal_com_without_rod[1]:.6g}) m"
        )


def _blow_dict(b: Blow, crank: CrankAngles) -> dict[str, Any]:
    """A blow of the working cycle; its crank angle as φ from position 0 and as the angle to x, deg."""
    from linkwork.motion.analysis import to_x_deg

    return {
        "time": b.time,
        "phi_deg": float(crank.phi(b.angle)),
        "crank_angle_to_x_deg": float(to_x_deg(b.angle)),
        "crank_speed_before": b.crank_speed_before,
        "crank_speed_after": b.crank_speed_after,
        "omega_before": b.omega_before,
        "omega_after": b.omega_after,
        "impact_speed": b.impact_speed,
        "striker_speed": b.striker_speed,
        "tool_speed": b.tool_speed,
        "impulse": _xy(b.impulse),
        "support_impulse": {
            name: {"on": b.joint_links[name][1], "from": b.joint_links[name][0], **_xy(v)}
            for name, v in b.joints.items()
        },
        "drive_impulse": b.drive_impulse,
        "energy_before": b.energy_before,
        "energy_lost": b.energy_lost,
        "energy_to_tool": b.energy_to_tool,
        "rebounds": b.rebounds,
        "rebound_loss": b.rebound_loss,
        "work_on_work": b.work_on_work,
        "penetration": b.penetration,
    }


def _cycle(mech: Mechanism, as_json: bool, blows: int | None) -> None:
    """``linkwork impact --cycle``: the working cycle, report or JSON (``blows``: None for the default)."""
    from linkwork.impulse.cycle import simulate_blows

    try:
        run = simulate_blows(mech) if blows is None else simulate_blows(mech, blows=blows)
    except LinkworkError as exc:
        fail(exc)
    if as_json:
        echo_json(_cycle_json(mech, run))
        return
    _print_cycle_blow(mech, run)
    _print_cycle_phases(run)


def _phase_dict(p: Phase, since: float) -> dict[str, Any]:
    """A phase of the last cycle, its start from the blow at ``since`` (s)."""
    return {
        "kind": p.kind,
        "freedom": p.freedom,
        "start": p.start - since,
        "duration": p.duration,
        "crank_turn": math.degrees(p.psi_end - p.psi_start),
    }


def _cycle_json(mech: Mechanism, run: WorkingCycle) -> dict[str, Any]:
    """The JSON object of ``linkwork impact --cycle --json``."""
    tool, loads = run.tool, run.contact
    return {
        "name": mech.name,
        "units": {
            "time": "s",
            "angle": "deg",
            "omega": "rad/s",
            "speed": "m/s",
            "impulse": "N s",
            "energy": "J",
            "length": "m",
            "power": "W",
            "force": "N",
        },
        "convention": "impulses in global axes; support_impulse: what each joint's first-named link exerts on "
        "the second ('from' on 'on'); crank speeds in the drive's direction; phases of the last cycle, "
        "start from its blow; mean_power: the motor's at its shaft, drive_power: the crank's after the "
        "gear; energy, cycle_energy: motor (at its shaft) = gear (lost in it) + drive (on the crank); "
        "drive + loads = kinetic + feed + blows + rebounds + seat + work + friction",
        "tool": {"mass": tool.mass, "feed": tool.feed, "resistance": tool.resistance},
        "steady": run.steady,
        "blows_per_minute": run.blows_per_minute,
        "period": run.period,
        "mean_power": run.mean_power,
        "drive_power": run.drive_power,
        "blows": [_blow_dict(b, _crank(mech)) for b in run.blows],
        "phases": [_phase_dict(p, run.last.time) for p in run.cycle_phases()],
        "contact": {
            "force_max": float(loads.force.max()) if len(loads.t) else None,
            "peak": {name: {"time": loads.peak(name)[0], **_xy(loads.peak(name)[1])} for name in loads.joints}
            if len(loads.t)
            else {},
        },
        "cycle_energy": {k: float(v) for k, v in run.cycle_energy.items()},
        "energy": {k: float(v) for k, v in run.energy.items()},
    }


def _crank(mech: Mechanism) -> CrankAngles:
    """The crank angles of a machine with a working cycle (one crank)."""
    from linkwork.motion.analysis import CrankAngles

    crank = CrankAngles.of(mech)
    assert crank is not None  # a working cycle needs one crank
    return crank


def _print_cycle_blow(mech: Mechanism, run: WorkingCycle) -> None:
    """The head of the report of ``linkwork impact --cycle``: the run and its last blow."""
    last, tool = run.last, run.tool
    state = "steady" if run.steady else f"not steady after {len(run.blows)} blows"
    typer.echo(
        f"{mech.name}: working cycle, {run.blows_per_minute:.6g} blows per minute ({state} after "
        f"{len(run.blows)} blows); tool {tool.mass:g} kg, feed {tool.feed:g} N, resistance of the work "
        f"{tool.resistance:g} N"
    )
    crank = _crank(mech)
    typer.echo(
        f"  the blow at phi = {crank.phi(last.angle, 2):.2f} deg: crank {last.crank_speed_before:.6g} -> "
        f"{last.crank_speed_after:.6g} rad/s, striker {last.impact_speed:.6g} m/s onto the tool "
        f"(speed {last.striker_speed:.6g} m/s), rocker {last.omega_before:.6g} -> {last.omega_after:.6g} rad/s, "
        f"tool {last.tool_speed:.6g} m/s"
    )
    typer.echo(
        f"    energy: {last.energy_before:.6g} J in the machine, {last.energy_lost:.6g} J lost in the blow, "
        f"{last.energy_to_tool:.6g} J to the tool; {last.rebounds} rebounds ({last.rebound_loss:.6g} J); "
        f"{last.work_on_work:.6g} J done on the work, the tool {1000 * last.penetration:.6g} mm into it"
    )
    typer.echo(f"    impulse on the striker ({last.impulse[0]:.6g}, {last.impulse[1]:.6g}) N s")
    for name, v in last.joints.items():
        a, b = last.joint_links[name]
        typer.echo(f"    joint {name}: {a} on {b} ({v[0]:.6g}, {v[1]:.6g}) N s")
    typer.echo(f"    drive on the crank {last.drive_impulse:.6g} N m s")


def _print_cycle_phases(run: WorkingCycle) -> None:
    """The rest of the report of ``linkwork impact --cycle``: the phases, the contact's loads, the energy."""
    typer.echo("  phases of the cycle (degrees of freedom of machine and tool):")
    for p in (_phase_dict(p, run.last.time) for p in run.cycle_phases()):
        typer.echo(
            f"    {p['kind']:8s} W = {p['freedom']}  from {1000 * p['start']:9.3f} ms  for {1000 * p['duration']:9.3f} "
            f"ms  ({p['crank_turn']:.2f} deg of the crank)"
        )
    loads = run.contact
    if len(loads.t):
        typer.echo(
            f"  striker and tool together: contact force {loads.force.min():.6g} to {loads.force.max():.6g} N; "
            "largest joint forces:"
        )
        for name in loads.joints:
            at, f = loads.peak(name)
            a, b = loads.joint_links[name]
            typer.echo(
                f"    joint {name}: {a} on {b} ({f[0]:.6g}, {f[1]:.6g}) N, |F| = {math.hypot(*f):.6g} N "
                f"at {1000 * at:.3f} ms"
            )
    e = run.cycle_energy
    typer.echo(
        f"  energy of the cycle: motor {e['motor']:.6g} J at its shaft ({run.mean_power:.6g} W) - gear "
        f"{e['gear']:.6g} J = drive {e['drive']:.6g} J on the crank ({run.drive_power:.6g} W) = blow "
        f"{e['blows']:.6g} + rebounds {e['rebounds']:.6g} + seat {e['seat']:.6g} + work {e['work']:.6g} + friction "
        f"{e['friction']:.6g} "
        f"+ kinetic {e['kinetic']:.3g} - loads {e['loads']:.3g} J"
    )
