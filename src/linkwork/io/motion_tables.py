"""Files of a kinematic result: CSV, NetCDF and JSON (the tables themselves are :mod:`linkwork.motion.tables`'s)."""

from __future__ import annotations

import csv
import math
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from linkwork.atomic import write_atomic
from linkwork.motion.tables import Table, drive_columns, drive_record, drive_units, kinematics_table, moving_links
from linkwork.structure.model import point_labels

if TYPE_CHECKING:
    from linkwork.motion.analysis import Extremes
    from linkwork.motion.kinematic_analysis import Kinematics
    from linkwork.structure.model import Mechanism


def _single(kin: Kinematics) -> None:
    if kin.variants:
        from linkwork.errors import LinkworkError

        raise LinkworkError("this table holds one mechanism; for design variants use to_dataset (NetCDF)")


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


def write_netcdf(kin: Kinematics, path: str | Path) -> Path:
    """Write the table of :func:`to_dataset` to ``path`` as NetCDF 3 (64-bit offsets), encoded as xarray
    encodes it (``xr.open_dataset`` reads it back as that Dataset), through SciPy's writer: xarray and pandas
    are not imported, nor the Dask that xarray looks for on every write (most of a second in all)."""
    data, coords, attrs = kinematics_table(kin)
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
