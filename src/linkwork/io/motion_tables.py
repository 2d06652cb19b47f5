"""Tables of a kinematic result: rows of plain data, CSV, NetCDF (xarray), JSON."""

from __future__ import annotations

import csv
import math
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from linkwork.atomic import write_atomic
from linkwork.optional import require
from linkwork.structure.model import point_labels

if TYPE_CHECKING:
    from linkwork.motion.analysis import Extremes
    from linkwork.motion.kinematics import Kinematics
    from linkwork.structure.model import Mechanism


def moving_links(mech: Mechanism) -> list[tuple[str, int]]:
    return [(n, i) for i, n in enumerate(mech.link_names) if i > 0 and not mech.link_virtual[i]]


def _single(kin: Kinematics) -> None:
    if kin.variants:
        from linkwork.errors import LinkworkError

        raise LinkworkError("this table holds one mechanism; for design variants use to_dataset (NetCDF)")


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
    events = [e.as_dict() for e in kin.events]
    events += [{**e.as_dict(), "what": e.kind, "kind": "stroke"} for e in extremes]
    return {
        "name": mech.name,
        "units": {
            "length": "m",
            "speed": "m/s",
            "acceleration": "m/s^2",
            "angle": "rad",
            "omega": "rad/s",
            "epsilon": "rad/s^2",
            "angles_deg": "deg",
        },
        "angles_deg": arr(np.degrees(kin.angles)),
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
        ("angle [deg]", np.degrees(kin.angles)),
        ("valid", np.asarray(kin.valid, dtype=int)),
    ]
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


#: A table of NetCDF: its variables, name -> (dimensions, values, attributes), in the file's order.
Table = dict[str, tuple[tuple[str, ...], np.ndarray, dict[str, str | float]]]


def _table(kin: Kinematics) -> tuple[Table, Table, dict[str, str]]:
    """The NetCDF table of a result: its data variables (variant x angle x point, and link), its coordinates
    (angle in degrees, the points' labels, the links' names) and its attributes, for :func:`to_dataset` and
    :func:`write_netcdf` alike."""
    mech = kin.mechanism
    labels = point_labels(mech)
    links = moving_links(mech)
    pos = np.stack([kin._point(mech.point_names[p])[0] for _, p in labels], axis=2)  # (V, A, P, 2)
    vel = np.stack([kin._point(mech.point_names[p])[1] for _, p in labels], axis=2)
    acc = np.stack([kin._point(mech.point_names[p])[2] for _, p in labels], axis=2)
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
    coords: Table = {
        "angle": (("angle",), np.degrees(kin.angles), {"units": "deg"}),
        "point": (("point",), np.array([label for label, _ in labels]), {}),
        "link": (("link",), np.array([n for n, _ in links]), {}),
    }
    return data, coords, {"mechanism": mech.name, "source": "linkwork kinematics"}


def to_dataset(kin: Kinematics) -> Any:
    """An xarray Dataset with dimensions variant x angle x point (and link)."""
    xr = require("xarray", purpose="NetCDF tables of the kinematics")
    data, coords, attrs = _table(kin)
    return xr.Dataset(data, coords=coords, attrs=attrs)


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
    ``string<longest>``; the coordinates first."""
    from scipy.io import netcdf_file

    encoded: Table = {}
    for name, (dims, values, attributes) in {**coords, **data}.items():
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
