"""Tables of a kinematic result: rows of plain data, CSV, NetCDF (xarray), JSON."""

from __future__ import annotations

import csv
import math
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from linkwork.atomic import write_atomic
from linkwork.optional import require
from linkwork.structure.model import PairType, point_labels

if TYPE_CHECKING:
    from linkwork.motion.analysis import Extremes
    from linkwork.motion.kinematic_analysis import Kinematics
    from linkwork.structure.model import Mechanism


def moving_links(mech: Mechanism) -> list[tuple[str, int]]:
    return [(n, i) for i, n in enumerate(mech.link_names) if i > 0 and not mech.link_virtual[i]]


def _single(kin: Kinematics) -> None:
    if kin.variants:
        from linkwork.errors import LinkworkError

        raise LinkworkError("this table holds one mechanism; for design variants use to_dataset (NetCDF)")


#: The unit of each kind of drive column: its CSV heading ``name [unit]``, its JSON key ``name_unit``.
_UNITS = {"deg": "deg", "m": "m"}


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


def crank_keys(record: dict[str, Any], keys: tuple[str, ...], mech: Mechanism) -> dict[str, Any]:
    """``record`` with each of its ``keys`` (``start_deg`` or ``shear_angle_deg``: a drive angle in degrees)
    given as φ (``start_phi_deg``, ``shear_phi_deg``) and as the angle to x (``start_to_x_deg``), both in
    [0, 360), where the mechanism has one crank; as it is otherwise."""
    from linkwork.motion.analysis import CrankAngles, to_x_deg

    crank = CrankAngles.of(mech)
    if crank is None:
        return record
    out = {}
    for key, value in record.items():
        if key in keys:
            stem = key.removesuffix("_deg").removesuffix("_angle")
            rad = math.radians(value)
            out[f"{stem}_phi_deg"] = float(crank.phi(rad))
            out[f"{stem}_to_x_deg"] = float(to_x_deg(rad))
        else:
            out[key] = value
    return out


def to_json(kin: Kinematics, extremes: list[Extremes]) -> dict[str, Any]:
    """The ``linkwork kinematics --json`` object (one mechanism, no variants)."""
    _single(kin)
    mech = kin.mechanism

    def arr(a: np.ndarray) -> list[float | None]:
        return [None if not math.isfinite(float(x)) else float(x) for x in np.asarray(a).ravel()]

    points = {}
    for label, p in point_labels(mech):
        name = mech.point_names[p]
        x, v, a = kin.position(name), kin.velocity(name), kin.acceleration(name)
        points[label] = {
            "x": arr(x[:, 0]),
            "y": arr(x[:, 1]),
            "vx": arr(v[:, 0]),
            "vy": arr(v[:, 1]),
            "ax": arr(a[:, 0]),
            "ay": arr(a[:, 1]),
        }
    links = {
        n: {"angle": arr(kin.angle(i)), "omega": arr(kin.omega(i)), "epsilon": arr(kin.epsilon(i))}
        for n, i in moving_links(mech)
    }
    events = [crank_keys(e.as_dict(), ("start_deg", "end_deg"), mech) for e in kin.events]
    events += [
        crank_keys({**e.as_dict(), "what": e.kind, "kind": "stroke"}, ("at_low_deg", "at_high_deg"), mech)
        for e in extremes
    ]
    return {
        "name": mech.name,
        "units": {
            "length": "m",
            "speed": "m/s",
            "acceleration": "m/s^2",
            "angle": "rad",
            "omega": "rad/s",
            "epsilon": "rad/s^2",
            **drive_units(mech),
        },
        **{k: arr(v) if isinstance(v, np.ndarray) else v for k, v in drive_record(mech, kin.angles).items()},
        "points": points,
        "links": links,
        "valid": [bool(x) for x in np.asarray(kin.valid).ravel()],
        "events": events,
    }


def write_csv(kin: Kinematics, path: str | Path) -> Path:
    """One row per angle, one column per quantity, units in the header (one mechanism, no variants)."""
    _single(kin)
    mech = kin.mechanism
    cols: list[tuple[str, np.ndarray]] = [
        (f"{name} [{unit}]", values) for name, (unit, values) in drive_columns(mech, kin.angles).items()
    ]
    cols.append(("valid", np.asarray(kin.valid, dtype=int)))
    for label, p in point_labels(mech):
        name = mech.point_names[p]
        x, v, a = kin.position(name), kin.velocity(name), kin.acceleration(name)
        for q, unit, data in (
            ("x", "m", x[:, 0]),
            ("y", "m", x[:, 1]),
            ("vx", "m/s", v[:, 0]),
            ("vy", "m/s", v[:, 1]),
            ("ax", "m/s^2", a[:, 0]),
            ("ay", "m/s^2", a[:, 1]),
        ):
            cols.append((f"{label}.{q} [{unit}]", data))
    for n, i in moving_links(mech):
        cols += [
            (f"{n}.angle [rad]", kin.angle(i)),
            (f"{n}.omega [rad/s]", kin.omega(i)),
            (f"{n}.epsilon [rad/s^2]", kin.epsilon(i)),
        ]

    def writer(tmp: Path) -> None:
        with open(tmp, "w", newline="", encoding="utf-8") as fh:
            w = csv.writer(fh)
            w.writerow([c[0] for c in cols])
            for row in zip(*(c[1] for c in cols), strict=True):
                w.writerow([repr(float(x)) if not isinstance(x, np.integer | int) else int(x) for x in row])

    return write_atomic(path, writer)


#: What the angles of a NetCDF table are (their ``long_name``).
LONG = {
    "phi": "phi, the crank angle turned from position 0 in the drive's direction",
    "crank_angle_to_x": "the crank's angle to the frame's x axis, counter-clockwise",
    "drive": "the drive's coordinate",
}

#: A table of NetCDF: its variables, name -> (dimensions, values, attributes), in the file's order.
Table = dict[str, tuple[tuple[str, ...], np.ndarray, dict[str, str | float]]]


def _table(kin: Kinematics) -> tuple[Table, Table, dict[str, str]]:
    """The NetCDF table of a result: its data variables (variant x angle x point, and link; with one crank
    ``crank_angle_to_x`` over the angles), its coordinates (``angle``: φ turned from position 0 in degrees
    with one crank, :func:`drive_columns`; the points' labels, the links' names) and its attributes, for
    :func:`to_dataset` and :func:`write_netcdf` alike."""
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
    :func:`write_netcdf` writes (``Kinematics.to_xarray``)."""
    xr = require("xarray", purpose="Kinematics.to_xarray (NetCDF tables of the kinematics)")
    data, coords, attrs = _table(kin)
    return xr.Dataset(data, coords=coords, attrs=attrs)


def to_frame(kin: Kinematics, by: str = "point") -> Any:
    """The variables of :func:`to_dataset` over ``by`` (``"point"``: x, y, vx, vy, ax, ay; ``"link"``: theta,
    omega, epsilon) as a pandas DataFrame indexed by variant x angle x ``by``, each variable's unit in
    ``attrs["units"]`` (``Kinematics.to_pandas``)."""
    if by not in ("point", "link"):
        from linkwork.errors import LinkworkError

        raise LinkworkError(f'to_pandas takes by="point" or by="link", not "{by}"')
    data, coords, attrs = _table(kin)
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


def write_netcdf(kin: Kinematics, path: str | Path) -> Path:
    """Write the table of :func:`to_dataset` to ``path`` as NetCDF 3 (64-bit offsets), encoded as xarray
    encodes it (``xr.open_dataset`` reads it back as that Dataset), through SciPy's writer: xarray and pandas
    are not imported, nor the Dask that xarray looks for on every write (most of a second in all)."""
    data, coords, attrs = _table(kin)
    return write_atomic(path, lambda tmp: _write_netcdf3(tmp, data, coords, attrs))


def _attribute(value: Any) -> Any:
    """An attribute as the NetCDF writer takes it: text as its UTF-8 bytes (NetCDF's characters, which
    xarray and netCDF4 read back as the text; SciPy's writer would take only ASCII), the rest as it is."""
    return value.encode("utf-8") if isinstance(value, str) else value


def _write_netcdf3(path: Path, data: Table, coords: Table, attrs: dict[str, str]) -> None:
    """Data variables, coordinates and global ``attrs`` to a NetCDF 3 file, in xarray's encoding and order:
    floats with a NaN ``_FillValue``, strings as arrays of characters (UTF-8) over a dimension
    ``string<longest>``; created as xarray creates them, the data variables first (SciPy writes the larger
    shapes first, and variables of one shape in the order they were created)."""
    from scipy.io import netcdf_file

    encoded: Table = {}
    for name, (dims, values, attributes) in {**data, **coords}.items():  # as xarray hands them to SciPy
        if values.dtype.kind == "U":
            chars = np.char.encode(values, "utf-8")
            width = max(chars.dtype.itemsize, 1)
            values = chars.astype(f"S{width}").view("S1").reshape(*chars.shape, width)
            dims, attributes = (*dims, f"string{width}"), {**attributes, "_Encoding": "utf-8"}
        elif values.dtype.kind == "f":
            attributes = {**attributes, "_FillValue": np.float64(np.nan)}
        encoded[name] = (dims, values, attributes)
    sizes: dict[str, int] = {}
    for name in [*data, *coords]:  # the data's dimensions, then those of the coordinates' strings
        dims, values, _ = encoded[name]
        sizes.update(zip(dims, values.shape, strict=True))
    with netcdf_file(path, "w", version=2) as f:
        for key, value in attrs.items():
            setattr(f, key, _attribute(value))
        for dim, size in sizes.items():
            f.createDimension(dim, size)
        for name, (dims, values, attributes) in encoded.items():
            var = f.createVariable(name, values.dtype, dims)
            var[...] = values
            for key, attribute in attributes.items():
                setattr(var, key, _attribute(attribute))
