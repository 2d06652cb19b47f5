"""``linkwork impact``: the blow of a file's ``impact:`` section, whole mechanism and reduced model."""

from __future__ import annotations

import json
import math
from typing import Annotated, Any

import typer

from linkwork.cli.app import FileOrExample, _compile, app, fail


def _xy(v: Any) -> dict[str, float]:
    return {"x": float(v[0]), "y": float(v[1])}


@app.command()
def impact(
    file_or_example: FileOrExample,
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON object")] = False,
) -> None:
    """Impulses of a blow in the pose of the file: on the striker, in every joint, the speed after,
    the energy lost, the ideal centre of mass; and the reduced model of seed 004 beside them."""
    from linkwork.errors import LinkworkError
    from linkwork.impulse import impact as solve
    from linkwork.impulse import reduced_model

    mech = _compile(file_or_example)
    blow = mech.blow
    if blow is None:
        fail(LinkworkError('the mechanism has no blow: give an "impact:" section (at, normal, omega, restitution)'))
    normal = (math.cos(blow.normal), math.sin(blow.normal))
    kw = dict(normal=normal, restitution=blow.restitution, friction=blow.friction)
    try:
        whole = solve(mech, at=blow.at, omega_before=blow.omega, link=blow.link, **kw)
        link = blow.link or blow.at.split(".", 1)[0]
        model = None
        if blow.rod_joint is not None:
            own = float(whole.velocities_before[mech.link_names.index(blow.at.split(".", 1)[0]), 2])
            model = reduced_model(mech, at=blow.at, rod_joint=blow.rod_joint, omega_before=own, **kw)
    except LinkworkError as exc:
        fail(exc)
    striker = blow.at.split(".", 1)[0]
    i = mech.link_names.index(link)
    joints = {}
    for k, name in enumerate(mech.pair_joint):
        if name in joints:
            continue
        a, b = (mech.link_names[int(x)] for x in mech.pair_links[k])
        joints[name] = {"on": b, "from": a, **_xy(whole.forces.pair_force(k)[0, 0])}
    out: dict[str, Any] = {
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
    }
    if model is not None:
        out["model"] = {"striker": striker, **model.as_dict()}
    if as_json:
        typer.echo(json.dumps(out))
        return
    typer.echo(f"{mech.name}: blow of {blow.at}, R = {blow.restitution:g}, f = {blow.friction:g}")
    typer.echo(
        f"  whole mechanism: impulse on the striker ({whole.impulse[0]:.6g}, {whole.impulse[1]:.6g}) N s; "
        f"{link} {out['omega_before']:.6g} -> {out['omega_after']:.6g} rad/s; energy lost {whole.energy_loss:.6g} J"
    )
    for name, j in joints.items():
        typer.echo(f"    joint {name}: {j['from']} on {j['on']} ({j['x']:.6g}, {j['y']:.6g}) N s")
    if whole.ideal_com is not None:
        typer.echo(f"    ideal centre of mass of {striker}: ({whole.ideal_com[0]:.6g}, {whole.ideal_com[1]:.6g}) m")
    if model is not None:
        typer.echo(
            f"  reduced model (rod as a point mass at {blow.rod_joint}): impulse ({model.impulse[0]:.6g}, "
            f"{model.impulse[1]:.6g}) N s, support ({model.support_impulse[0]:.6g}, {model.support_impulse[1]:.6g}) "
            f"N s; ideal centre of mass ({model.ideal_com[0]:.6g}, {model.ideal_com[1]:.6g}) m, without the rod "
            f"({model.ideal_com_without_rod[0]:.6g}, {model.ideal_com_without_rod[1]:.6g}) m"
        )
