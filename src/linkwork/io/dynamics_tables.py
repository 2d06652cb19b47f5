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

from linkwork.io.motion_tables import Table

if TYPE_CHECKING:
    from linkwork.machine.dynamics import Dynamics
    from linkwork.motion.analysis import CrankAngles
    from linkwork.structure.model import Mechanism


def _list(a: Any) -> list[float | None]:
    return [None if not math.isfinite(float(x)) else float(x) for x in np.asarray(a, dtype=float).ravel()]


#: The columns of the steady cycle's table (``dynamics.csv``): the keys of ``cycle`` and their headings.
CYCLE_COLUMNS = {
    "psi_deg": "psi [deg]",
    "t": "t [s]",
    "omega": "omega [rad/s]",
    "motor_torque": "motor_torque [N m]",
    "motor_power": "motor_power [W]",
    "phi_deg": "phi [deg]",
}


def _crank(result: Dynamics, mech: Mechanism | None = None, zero: float | None = None) -> CrankAngles:
    """Where φ counts from: position 0 at ``zero`` (rad) where given, else the result's own (:func:`dynamics`
    gives it the mechanism's), else the mechanism's (:func:`linkwork.motion.analysis.zero_angle`)."""
    from linkwork.errors import LinkworkError
    from linkwork.motion.analysis import CrankAngles

    crank = CrankAngles.of(mech, zero) if mech is not None and (zero is not None or result.crank is None) else None
    crank = crank or result.crank
    if crank is None:
        raise LinkworkError("this dynamics result does not say where position 0 is: run it with linkwork.dynamics")
    return crank


def _cycle(result: Dynamics, crank: CrankAngles) -> dict[str, np.ndarray]:
    """The steady cycle's samples by the keys of :data:`CYCLE_COLUMNS`."""
    red, drive = result.reduced, result.drive
    t, psi, omega = result.motion.cycle()
    turn = red.angle[0] + crank.direction * (result.motion.cycle_start + psi)  # drive angles of the steady turn
    motor_speed = drive.ratio * omega
    motor_torque = drive.motor(motor_speed)
    return {
        "psi_deg": np.degrees(psi),
        "t": t,
        "omega": omega,
        "motor_torque": motor_torque,
        "motor_power": motor_torque * motor_speed,
        "phi_deg": np.asarray(crank.phi(turn), dtype=float),
    }


def to_json(mech: Mechanism, result: Dynamics, zero: float | None = None) -> dict[str, Any]:
    """The ``linkwork dynamics --json`` object; ``zero``: the drive angle of position 0 (rad, default
    :func:`linkwork.motion.analysis.zero_angle`)."""
    from linkwork.machine import wittenbauer
    from linkwork.motion.analysis import to_x_deg

    red, drive, last = result.reduced, result.drive, result.motion.last
    crank = _crank(result, mech, zero)
    cycle = _cycle(result, crank)
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


#: The units of the variables of :func:`to_dataset`, by name.
UNITS = {
    "crank_angle_to_x": "deg",
    "inertia": "kg m^2",
    "inertia_slope": "kg m^2/rad",
    "load": "N m",
    "work": "J",
    "psi": "deg",
    "phi": "deg",
    "omega": "rad/s",
    "motor_torque": "N m",
    "motor_power": "W",
}


def _table(result: Dynamics) -> tuple[Table, Table, dict[str, Any]]:
    """The tables of a dynamics result (:func:`to_json`'s arrays): over ``angle`` (φ of the reduced grid) and
    over ``time`` (the steady cycle); their coordinates and the result's figures as attributes."""
    from linkwork.io.motion_tables import LONG
    from linkwork.motion.analysis import to_x_deg

    red, last = result.reduced, result.motion.last
    crank = _crank(result)
    cycle = _cycle(result, crank)
    over_angle = {
        "crank_angle_to_x": np.asarray(to_x_deg(red.angle), dtype=float),
        "inertia": red.inertia,
        "inertia_slope": red.inertia_slope,
        "load": red.load,
        "work": red.work()[:-1],
    }
    over_time = {"psi": cycle["psi_deg"], "phi": cycle["phi_deg"], "omega": cycle["omega"],
                 "motor_torque": cycle["motor_torque"], "motor_power": cycle["motor_power"]}  # fmt: skip
    data: Table = {name: (("angle",), v, {"units": UNITS[name]}) for name, v in over_angle.items()}
    data.update({name: (("time",), v, {"units": UNITS[name]}) for name, v in over_time.items()})
    data["crank_angle_to_x"][2]["long_name"] = LONG["crank_angle_to_x"]
    data["phi"][2]["long_name"] = LONG["phi"]
    coords: Table = {
        "angle": (
            ("angle",),
            np.asarray(crank.phi(red.angle), dtype=float),
            {"units": "deg", "long_name": LONG["phi"]},
        ),
        "time": (("time",), cycle["t"], {"units": "s", "long_name": "time from the start of the steady cycle"}),
    }
    attrs: dict[str, Any] = {
        "mechanism": result.name,
        "source": "linkwork dynamics",
        **crank.record(),
        "delta": last.delta,
        "omega_mean": last.omega_mean,
        "mean_power": result.mean_power,
        "drive_power": result.drive_power,
        "startup_time": result.startup_time,
        "flywheel_inertia": result.drive.flywheel,
        "flywheel_on": result.drive.flywheel_on,
    }
    return data, coords, attrs


def to_dataset(result: Dynamics) -> Any:
    """The tables of a dynamics result (:func:`_table`) as an xarray Dataset (``Dynamics.to_xarray``)."""
    from linkwork.optional import require

    xr = require("xarray", purpose="Dynamics.to_xarray")
    data, coords, attrs = _table(result)
    return xr.Dataset(data, coords=coords, attrs=attrs)


def to_frame(result: Dynamics, by: str = "angle") -> Any:
    """The variables over ``by`` (``"angle"``: the reduced quantities; ``"time"``: the steady cycle) as a pandas
    DataFrame indexed by that coordinate (``Dynamics.to_pandas``), the units in ``attrs["units"]``."""
    from linkwork.io.motion_tables import frame

    if by not in ("angle", "time"):
        from linkwork.errors import LinkworkError

        raise LinkworkError(f'Dynamics.to_pandas takes by="angle" or by="time", not "{by}"')
    data, coords, attrs = _table(result)
    return frame(data, coords, attrs, (by,), purpose="Dynamics.to_pandas")
