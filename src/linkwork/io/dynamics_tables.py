"""The JSON object of a machine-dynamics result (``linkwork dynamics --json``, the report).

Angles, in degrees in [0, 360) (:class:`linkwork.motion.analysis.CrankAngles`): ``phi_deg`` is φ, the
crank angle turned from position 0 (``position_0_deg``, the crank's angle to x where the working member is
at its extreme, as ``linkwork positions`` numbers the cycle) in the drive's ``direction``, the abscissa of
the report's diagrams, at each sample of the reduced quantities; ``crank_angle_to_x_deg`` the crank's
angle to the frame's x axis there; ``cycle.phi_deg`` φ at each sample of the steady cycle, and
``cycle.psi_deg`` the angle the crank has turned since the start of the steady turn (its first sample),
which is not position 0.

``mean_power`` is the motor's at its shaft, ``drive_power`` the drive's on the crank (after the
gear), over the steady cycle, as in :class:`linkwork.machine.Dynamics` and the working cycle of
:func:`linkwork.simulate_blows`; ``flywheel_inertia`` is on the shaft ``flywheel_on``.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

from linkwork.machine.tables import cycle_columns, dynamics_crank

if TYPE_CHECKING:
    from linkwork.machine.steady_cycle import Dynamics
    from linkwork.structure.model import Mechanism


def _list(a: Any) -> list[float | None]:
    return [None if not math.isfinite(float(x)) else float(x) for x in np.asarray(a, dtype=float).ravel()]


def to_json(mech: Mechanism, result: Dynamics, zero: float | None = None) -> dict[str, Any]:
    """The ``linkwork dynamics --json`` object; ``zero``: the drive angle of position 0 (rad, default
    :func:`linkwork.motion.analysis.zero_angle`)."""
    from linkwork.machine import wittenbauer
    from linkwork.motion.analysis import to_x_deg

    red, drive, last = result.reduced, result.drive, result.motion.last
    crank = dynamics_crank(result, mech, zero)
    cycle = cycle_columns(result, crank)
    out: dict[str, Any] = {
        "name": mech.name,
        "units": {
            "angle": "deg",
            "inertia": "kg m^2",
            "moment": "N m",
            "omega": "rad/s",
            "power": "W",
            "time": "s",
        },
        **crank.record(),
        "phi_deg": _list(crank.phi(red.angle)),
        "crank_angle_to_x_deg": _list(to_x_deg(red.angle)),
        "reduced_inertia": _list(red.inertia),
        "reduced_inertia_slope": _list(red.inertia_slope),
        "reduced_load": _list(red.load),
        "work": _list(red.work()[:-1]),
        "wittenbauer": {"inertia": _list(wittenbauer(red)[0]), "energy": _list(wittenbauer(red)[1])},
        "cycle": {name: _list(values) for name, values in cycle.items()},
        "omega": _list(cycle["omega"]),
        "omega_mean": last.omega_mean,
        "omega_min": last.omega_min,
        "omega_max": last.omega_max,
        "delta": last.delta,
        "mean_power": result.mean_power,
        "drive_power": result.drive_power,
        "startup_time": result.startup_time,
        "steady": result.motion.steady,
        "flywheel_inertia": drive.flywheel,
        "flywheel_on": drive.flywheel_on,
        "gear": {"ratio": drive.ratio, "efficiency": drive.efficiency},
    }
    if result.flywheel is not None:
        from linkwork.machine import size_flywheel

        f = result.flywheel
        approx = size_flywheel(red, f.delta, f.omega_mean, drive.with_flywheel(0.0).inertia)
        out["energy_method"] = {
            "method": "Wittenbauer (tangents to the energy-inertia diagram)",
            "merkalov_inertia_on_crank": approx.inertia,
            "delta": f.delta,
            "omega_mean": f.omega_mean,
            "energy_swing": f.energy_swing,
            "inertia_on_crank": f.inertia,
            "flywheel": f.flywheel,
            "flywheel_on": f.shaft,
            "flywheel_on_crank": f.on_crank,
            "drive_moment": f.drive_moment,
        }
    return out
