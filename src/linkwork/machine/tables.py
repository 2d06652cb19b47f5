"""The tables of a machine-dynamics result as data (``Dynamics.to_xarray``, ``Dynamics.to_pandas``): over the
reduced grid's φ and over the steady cycle's time; the JSON of ``linkwork dynamics`` (:mod:`linkwork.io`) takes
its steady-cycle columns and its φ from here."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from linkwork.motion.tables import LONG, Table, frame

if TYPE_CHECKING:
    from linkwork.machine.steady_cycle import Dynamics
    from linkwork.motion.analysis import CrankAngles
    from linkwork.structure.model import Mechanism


#: The columns of the steady cycle's table (``dynamics.csv``): the keys of ``cycle`` and their headings.
CYCLE_COLUMNS = {
    "psi_deg": "psi [deg]",
    "t": "t [s]",
    "omega": "omega [rad/s]",
    "motor_torque": "motor_torque [N m]",
    "motor_power": "motor_power [W]",
    "phi_deg": "phi [deg]",
}


def dynamics_crank(result: Dynamics, mech: Mechanism | None = None, zero: float | None = None) -> CrankAngles:
    """Where φ of ``result`` counts from: position 0 at ``zero`` (rad) where given, else the result's own
    (:func:`dynamics` gives it the mechanism's), else the mechanism's (:func:`linkwork.motion.analysis.zero_angle`)."""
    from linkwork.errors import LinkworkError
    from linkwork.motion.analysis import CrankAngles

    crank = CrankAngles.of(mech, zero) if mech is not None and (zero is not None or result.crank is None) else None
    crank = crank or result.crank
    if crank is None:
        raise LinkworkError("this dynamics result does not say where position 0 is: run it with linkwork.dynamics")
    return crank


def cycle_columns(result: Dynamics, crank: CrankAngles) -> dict[str, np.ndarray]:
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


def dynamics_table(result: Dynamics) -> tuple[Table, Table, dict[str, Any]]:
    """The tables of a dynamics result (:func:`to_json`'s arrays): over ``angle`` (φ of the reduced grid) and
    over ``time`` (the steady cycle); their coordinates and the result's figures as attributes."""
    from linkwork.motion.analysis import to_x_deg

    red, last = result.reduced, result.motion.last
    crank = dynamics_crank(result)
    cycle = cycle_columns(result, crank)
    over_angle = {
        "crank_angle_to_x": np.asarray(to_x_deg(red.angle), dtype=float),
        "inertia": red.inertia,
        "inertia_slope": red.inertia_slope,
        "load": red.load,
        "work": red.work()[:-1],
    }
    over_time = {
        "psi": cycle["psi_deg"],
        "phi": cycle["phi_deg"],
        "omega": cycle["omega"],
        "motor_torque": cycle["motor_torque"],
        "motor_power": cycle["motor_power"],
    }
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
    """The tables of a dynamics result (:func:`dynamics_table`) as an xarray Dataset (``Dynamics.to_xarray``)."""
    from linkwork.optional import require

    xr = require("xarray", purpose="Dynamics.to_xarray")
    data, coords, attrs = dynamics_table(result)
    return xr.Dataset(data, coords=coords, attrs=attrs)


def to_frame(result: Dynamics, by: str = "angle") -> Any:
    """The variables over ``by`` (``"angle"``: the reduced quantities; ``"time"``: the steady cycle) as a pandas
    DataFrame indexed by that coordinate (``Dynamics.to_pandas``), the units in ``attrs["units"]``."""

    if by not in ("angle", "time"):
        from linkwork.errors import LinkworkError

        raise LinkworkError(f'Dynamics.to_pandas takes by="angle" or by="time", not "{by}"')
    data, coords, attrs = dynamics_table(result)
    return frame(data, coords, attrs, (by,), purpose="Dynamics.to_pandas")
