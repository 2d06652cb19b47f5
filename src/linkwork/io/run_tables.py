"""The table and JSON object of a run in time (``linkwork simulate --json/--out``, the report).

One row per sample: ``t`` (s); the crank's ``phi`` (deg in [0, 360), turned from position 0 in the drive's
direction, :class:`linkwork.motion.analysis.CrankAngles`), its angle to the x axis ``crank_angle_to_x``
(deg in [0, 360)), ``turned`` the angle it has turned since the start (deg, counter-clockwise positive,
whole turns and turns back counted), its speed ``omega`` (rad/s) and angular acceleration ``epsilon``
(rad/s^2), counter-clockwise positive; the motor's moment on the crank ``drive_moment`` (N m); every
moving link's angle (deg, unwrapped along the run), angular speed and acceleration; every point's x, y (m).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from linkwork.machine.timerun import Run


def _list(a: Any) -> list[float | None]:
    return [None if not math.isfinite(float(x)) else float(x) for x in np.asarray(a, dtype=float).ravel()]


def columns(run: Run) -> dict[str, np.ndarray]:
    """The table of a run, by column heading with its unit."""
    from linkwork.motion.analysis import CrankAngles, to_x_deg
    from linkwork.structure.model import point_labels

    mech, kin = run.mechanism, run.kinematics
    crank = CrankAngles.of(mech)
    assert crank is not None  # a run in time needs one crank
    out = {
        "t [s]": run.time,
        "phi [deg]": np.asarray(crank.phi(run.angle), dtype=float),
        "crank_angle_to_x [deg]": np.asarray(to_x_deg(run.angle), dtype=float),
        "turned [deg]": np.degrees(run.angle - run.angle[0]),
        "omega [rad/s]": run.speed,
        "epsilon [rad/s^2]": run.acceleration,
        "drive_moment [N m]": run.drive_moment,
    }
    for i, name in enumerate(mech.link_names):
        if i == 0 or mech.link_virtual[i]:
            continue
        out[f"{name}.angle [deg]"] = np.degrees(np.unwrap(kin.pose[0, :, i, 2]))
        out[f"{name}.omega [rad/s]"] = kin.vel[0, :, i, 2]
        out[f"{name}.epsilon [rad/s^2]"] = kin.acc[0, :, i, 2]
    for label, p in point_labels(mech):
        xy = kin.position(mech.point_names[p])
        out[f"{label}.x [m]"], out[f"{label}.y [m]"] = xy[:, 0], xy[:, 1]
    return out


def csv_text(run: Run) -> str:
    """The table of :func:`columns` as CSV."""
    table = columns(run)
    rows = [",".join(table)]
    rows += [",".join(repr(float(v)) for v in row) for row in zip(*table.values(), strict=True)]
    return "\n".join(rows) + "\n"


def to_json(run: Run) -> dict[str, Any]:
    """The ``linkwork simulate --json`` object: the run's settings, its events, the columns of :func:`columns`
    (by their names without the unit) and the joint reactions along the run (N, on the joint's second link
    from its first, as ``linkwork forces`` gives them) with the driving torque the drive's pair carries."""
    from linkwork.errors import LinkworkError
    from linkwork.motion.analysis import CrankAngles

    mech = run.mechanism
    crank = CrankAngles.of(mech)
    assert crank is not None
    table = {heading.split(" [", 1)[0]: _list(values) for heading, values in columns(run).items()}
    f = run.forces()
    reactions = {}
    for joint in mech.joint_names:
        try:
            r = f.reaction(joint)
        except (LinkworkError, KeyError, ValueError):  # a joint whose reaction is not one force
            continue
        reactions[joint] = {"x": _list(r[:, 0]), "y": _list(r[:, 1])}
    return {
        "name": mech.name,
        "units": {
            "time": "s",
            "angle": "deg",
            "omega": "rad/s",
            "epsilon": "rad/s^2",
            "moment": "N m",
            "length": "m",
            "force": "N",
        },
        **crank.record(),
        "rtol": run.rtol,
        "atol": run.atol,
        "evaluations": run.evaluations,
        "events": [e.as_dict() for e in run.events],
        "samples": table,
        "driving_torque": _list(f.driving_torque),
        "reactions": reactions,
    }
