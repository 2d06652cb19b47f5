"""The tables of a kinematic result as data: variant x angle x point (and link), for xarray, pandas and NetCDF.

:meth:`Kinematics.to_xarray <linkwork.motion.kinematic_analysis.Kinematics.to_xarray>` and ``to_pandas`` build
them here; :mod:`linkwork.io.motion_tables` writes them (CSV, NetCDF, JSON).  The columns that say where each
sample is (φ from position 0 with one crank, :func:`drive_columns`) are every table's.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from linkwork.optional import require
from linkwork.structure.model import PairType, point_labels

if TYPE_CHECKING:
    from linkwork.motion.kinematic_analysis import Kinematics
    from linkwork.structure.model import Mechanism


def moving_links(mech: Mechanism) -> list[tuple[str, int]]:
    """The links a table reports, ``(name, index)``: every moving link that is not a virtual block."""
    return [(n, i) for i, n in enumerate(mech.link_names) if i > 0 and not mech.link_virtual[i]]


def drive_columns(mech: Mechanism, angles: np.ndarray) -> dict[str, tuple[str, np.ndarray]]:
    """The columns that say where each sample of a table is, by name: ``name -> (unit, values)``.

    With one crank, φ turned from position 0 (``phi``, deg in [0, 360),
    :class:`~linkwork.motion.analysis.CrankAngles`) and the crank's angle to the frame's x axis
    (``crank_angle_to_x``, deg in [0, 360)); otherwise the first drive's coordinate, ``crank_angle_to_x``
    (deg) of a revolute drive or ``drive`` (m) of a linear one."""
    from linkwork.motion.analysis import TO_X, CrankAngles, to_x_deg

    crank = CrankAngles.of(mech)
    if crank is not None:
        return {name: ("deg", values) for name, values in crank.columns(angles).items()}
    if mech.pair_type[mech.drive_pair[0]] == PairType.REVOLUTE:
        return {TO_X: ("deg", np.asarray(to_x_deg(angles)))}
    return {"drive": ("m", np.asarray(angles, dtype=float))}


def drive_record(mech: Mechanism, angles: np.ndarray) -> dict[str, Any]:
    """The JSON keys of :func:`drive_columns` (``phi_deg``, ``crank_angle_to_x_deg``, or ``drive_m``) and,
    with one crank, ``position_0_deg`` and ``direction``; ``units`` names each key's unit."""
    from linkwork.motion.analysis import CrankAngles

    cols = drive_columns(mech, angles)
    out: dict[str, Any] = {f"{name}_{unit}": values for name, (unit, values) in cols.items()}
    crank = CrankAngles.of(mech)
    if crank is not None:
        out.update(crank.record())
    return out


def drive_units(mech: Mechanism) -> dict[str, str]:
    """The ``units`` entries of :func:`drive_record`'s keys."""
    return {f"{name}_{unit}": unit for name, (unit, _) in drive_columns(mech, np.zeros(0)).items()}


#: What the angles of a NetCDF table are (their ``long_name``).
LONG = {
    "phi": "phi, the crank angle turned from position 0 in the drive's direction",
    "crank_angle_to_x": "the crank's angle to the frame's x axis, counter-clockwise",
    "drive": "the drive's coordinate",
}

#: A table of NetCDF: its variables, name -> (dimensions, values, attributes), in the file's order.
Table = dict[str, tuple[tuple[str, ...], np.ndarray, dict[str, str | float]]]


def kinematics_table(kin: Kinematics) -> tuple[Table, Table, dict[str, str]]:
    """The NetCDF table of a result: its data variables (variant x angle x point, and link; with one crank
    ``crank_angle_to_x`` over the angles), its coordinates (``angle``: φ turned from position 0 in degrees
    with one crank, :func:`drive_columns`; the points' labels, the links' names) and its attributes, for
    :func:`to_dataset` and :func:`linkwork.io.motion_tables.write_netcdf` alike."""
    mech = kin.mechanism
    labels = point_labels(mech)
    links = moving_links(mech)
    motions = [kin.motion_of(mech.point_names[p]) for _, p in labels]  # each point's (V, A, 2) three, once
    pos, vel, acc = (np.stack(each, axis=2) for each in zip(*motions, strict=True))  # (V, A, P, 2)
    idx = [i for _, i in links]
    dims3 = ("variant", "angle", "point")
    dimsl = ("variant", "angle", "link")
    data: Table = {
        "x": (dims3, pos[..., 0], {"units": "m"}),
        "y": (dims3, pos[..., 1], {"units": "m"}),
        "vx": (dims3, vel[..., 0], {"units": "m/s"}),
        "vy": (dims3, vel[..., 1], {"units": "m/s"}),
        "ax": (dims3, acc[..., 0], {"units": "m/s^2"}),
        "ay": (dims3, acc[..., 1], {"units": "m/s^2"}),
        "theta": (dimsl, np.moveaxis(kin.q[idx, 2], 0, -1), {"units": "rad"}),
        "omega": (dimsl, np.moveaxis(kin.v[idx, 2], 0, -1), {"units": "rad/s"}),
        "epsilon": (dimsl, np.moveaxis(kin.a[idx, 2], 0, -1), {"units": "rad/s^2"}),
        "valid": (("variant", "angle"), kin.valid_all.astype("int8"), {}),
    }
    (first, (unit, values)), *others = drive_columns(mech, kin.angles).items()
    for name, (other_unit, other) in others:  # the angle to x beside phi: a variable over the angles
        data[name] = (("angle",), other, {"units": other_unit, "long_name": LONG[name]})
    coords: Table = {
        "angle": (("angle",), values, {"units": unit, "long_name": LONG[first]}),
        "point": (("point",), np.array([label for label, _ in labels]), {}),
        "link": (("link",), np.array([n for n, _ in links]), {}),
    }
    attrs = {"mechanism": mech.name, "source": "linkwork kinematics"}
    record = drive_record(mech, kin.angles)
    if "position_0_deg" in record:
        attrs["angle"] = (
            f"phi, turned from position 0 (the crank at {record['position_0_deg']:.9g} deg to the x axis, "
            f"turning {'counter-clockwise' if record['direction'] > 0 else 'clockwise'}), deg in [0, 360)"
        )
    return data, coords, attrs


def to_dataset(kin: Kinematics) -> Any:
    """An xarray Dataset with dimensions variant x angle x point (and link): the table
    :func:`linkwork.io.motion_tables.write_netcdf` writes (``Kinematics.to_xarray``)."""
    xr = require("xarray", purpose="Kinematics.to_xarray (NetCDF tables of the kinematics)")
    data, coords, attrs = kinematics_table(kin)
    return xr.Dataset(data, coords=coords, attrs=attrs)


def to_frame(kin: Kinematics, by: str = "point") -> Any:
    """The variables of :func:`to_dataset` over ``by`` (``"point"``: x, y, vx, vy, ax, ay; ``"link"``: theta,
    omega, epsilon) as a pandas DataFrame indexed by variant x angle x ``by``, each variable's unit in
    ``attrs["units"]`` (``Kinematics.to_pandas``)."""
    if by not in ("point", "link"):
        from linkwork.errors import LinkworkError

        raise LinkworkError(f'to_pandas takes by="point" or by="link", not "{by}"')
    data, coords, attrs = kinematics_table(kin)
    return frame(data, coords, attrs, ("variant", "angle", by), purpose="Kinematics.to_pandas")


def frame(data: Table, coords: Table, attrs: dict[str, str], dims: tuple[str, ...], purpose: str) -> Any:
    """The variables of a table whose dimensions are ``dims`` as a pandas DataFrame: a row per combination of
    the coordinates (a dimension without one, ``variant``, numbered from 0), a column per variable, the
    index's levels named after ``dims``; the units of the columns in ``attrs["units"]``, the table's
    attributes and the angle's ``long_name`` in ``attrs`` too."""
    pd = require("pandas", purpose=purpose)
    chosen = {name: values for name, (d, values, _) in data.items() if d == dims}
    shape = next(iter(chosen.values())).shape
    levels = [coords[d][1] if d in coords else np.arange(n) for d, n in zip(dims, shape, strict=True)]
    index = pd.MultiIndex.from_product(levels, names=list(dims))
    out = pd.DataFrame({name: np.asarray(values).reshape(-1) for name, values in chosen.items()}, index=index)
    out.attrs.update(attrs)
    out.attrs["units"] = {name: str(data[name][2].get("units", "1")) for name in chosen}
    out.attrs["angle_units"] = str(coords["angle"][2].get("units", ""))
    return out
