"""The table of a kinetostatic result as data: variant x angle x joint, for xarray and pandas.

:meth:`Forces.to_xarray <linkwork.kinetostatics.reaction_forces.Forces.to_xarray>` and ``to_pandas`` build it
here; :mod:`linkwork.io.force_tables` writes the files (CSV, JSON) with the same labels of the pairs
(:func:`pair_labels`) and the same moments of the prismatic pairs (:func:`pair_moment`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from linkwork.errors import LinkworkError
from linkwork.motion.tables import LONG, Table, drive_columns, frame
from linkwork.optional import require
from linkwork.structure.model import PairType
from linkwork.zeros import snap_zeros

if TYPE_CHECKING:
    from linkwork.kinetostatics.reaction_forces import Forces
    from linkwork.structure.model import Mechanism

#: How the table's forces and moments are signed, and of what on what.
CONVENTION = (
    "joints: the force the first-named link exerts on the second, in the order of the file's joint and of "
    "'links' (x, y, N); a compound hinge is a pair from the link that carries the pin to each other link; "
    "for a prismatic pair (guide first) also its moment on the slider (N m) about the slider's point; driving torque: "
    "what the drive puts on its driven link, counter-clockwise positive; foundation: the force and "
    "the moment about the origin that the machine puts on its foundation, y up (positive y pulls the bolts)"
)


def pair_labels(mech: Mechanism) -> list[tuple[str, int]]:
    """One label per pair a table reports: the joint's name, with ``:link`` for each pair of a compound
    hinge (the link other than the one that carries the pin).  A pin in a slot is reported once, by its
    slot's pair: through the massless block, the pin's pair with the block carries the same force."""
    shown = [
        k
        for k in range(mech.n_pairs)
        if not (mech.pair_type[k] == PairType.REVOLUTE and mech.link_virtual[mech.pair_links[k]].any())
    ]
    joints = [mech.pair_joint[k] for k in shown]
    out = []
    for k, joint in zip(shown, joints, strict=True):
        several = joints.count(joint) > 1
        out.append((f"{joint}:{mech.link_names[int(mech.pair_links[k, 1])]}" if several else joint, k))
    return out


def pair_kind(mech: Mechanism, k: int) -> str:
    """``revolute``, ``prismatic`` (which carries a moment) or ``pin-in-slot`` (the pairs of its block)."""
    if mech.link_virtual[mech.pair_links[k]].any():
        return "pin-in-slot"
    return "revolute" if mech.pair_type[k] == PairType.REVOLUTE else "prismatic"


def pair_moment(f: Any, k: int) -> np.ndarray:
    """The moment (N m, ``(A,)``) of prismatic pair ``k`` on its slider about the slider's point, 0.0 where it
    is the round-off of a zero: below :data:`~linkwork.zeros.ZERO` times the pair's force at that angle
    times the mechanism's size (the quantities it is computed from).  What the table, the CSV and the JSON
    show."""
    return pair_moment_all(f, k)[0]


def pair_moment_all(f: Any, k: int) -> np.ndarray:
    """:func:`pair_moment` of every variant, ``(V, A)``."""
    mech = f.mechanism
    size = float(np.ptp(np.asarray(mech.points0()), axis=0).max())
    force = f.pair_force(k)
    return snap_zeros(f.multipliers[..., 2 * k], scale=np.hypot(force[..., 0], force[..., 1]) * size)


def forces_table(f: Forces) -> tuple[Table, Table, dict[str, str]]:
    """The table of a kinetostatic result over variant x angle: each reported pair's force (joint x
    component: the link named first on the second, as ``forces.csv`` and the JSON give it, :func:`pair_labels`)
    and a prismatic pair's moment (NaN for the others), the driving torque, the foundation's and the shaking
    loads, ``singular``; coordinates ``angle`` (φ from position 0 with one crank, as :mod:`linkwork.motion.tables`),
    ``joint`` (with the links ``first`` and ``second`` and the pair's ``kind``), ``component`` (x, y)."""
    mech = f.mechanism
    pairs = pair_labels(mech)
    force = np.stack([mech.pair_sign[k] * f.pair_force(k) for _, k in pairs], axis=2)  # (V, A, J, 2)
    nan = np.full(force.shape[:2], np.nan)
    moment = np.stack([pair_moment_all(f, k) if pair_kind(mech, k) == "prismatic" else nan for _, k in pairs], 2)
    members = [[mech.link_names[int(i)] for i in mech.pair_members[k]] for _, k in pairs]
    over: tuple[str, ...] = ("variant", "angle", "drive")
    torque = f.driving_torque_all  # (V, A, D): each drive's
    if mech.n_drives == 1:
        torque, over = torque[..., 0], over[:2]
    found = f.foundation_filled_all
    linear = mech.pair_type[mech.drive_pair[0]] != PairType.REVOLUTE
    joint, comp = ("variant", "angle", "joint"), ("variant", "angle", "component")
    data: Table = {
        "force": ((*joint, "component"), force, {"units": "N", "long_name": "the first link's force on the second"}),
        "moment": (joint, moment, {"units": "N m", "long_name": "a prismatic pair's moment on its slider"}),
        "driving_torque": (over, torque, {"units": "N" if linear else "N m"}),
        "foundation_force": (comp, found[..., :2], {"units": "N"}),
        "foundation_moment": (("variant", "angle"), found[..., 2], {"units": "N m"}),
        "shaking_force": (comp, f.shaking_force_all, {"units": "N"}),
        "shaking_moment": (("variant", "angle"), f.shaking_moment_all, {"units": "N m"}),
        "singular": (("variant", "angle"), f.singular_all.astype("int8"), {}),
    }
    (first, (unit, values)), *others = drive_columns(mech, f.angles).items()
    for name, (other_unit, other) in others:
        data[name] = (("angle",), other, {"units": other_unit, "long_name": LONG[name]})
    coords: Table = {
        "angle": (("angle",), values, {"units": unit, "long_name": LONG[first]}),
        "joint": (("joint",), np.array([label for label, _ in pairs]), {}),
        "first": (("joint",), np.array([m[0] for m in members]), {}),
        "second": (("joint",), np.array([m[1] for m in members]), {}),
        "kind": (("joint",), np.array([pair_kind(mech, k) for _, k in pairs]), {}),
        "component": (("component",), np.array(["x", "y"]), {}),
    }
    if mech.n_drives > 1:
        coords["drive"] = (("drive",), np.array([mech.pair_joint[k] for k in mech.drive_pair]), {})
    return data, coords, {"mechanism": mech.name, "source": "linkwork forces", "convention": CONVENTION}


def to_dataset(f: Forces) -> Any:
    """The table of a kinetostatic result (:func:`forces_table`) as an xarray Dataset (``Forces.to_xarray``)."""
    xr = require("xarray", purpose="Forces.to_xarray")
    data, coords, attrs = forces_table(f)
    return xr.Dataset(data, coords=coords, attrs=attrs)


def to_frame(f: Forces, by: str = "joint") -> Any:
    """The table of a kinetostatic result as a pandas DataFrame (``Forces.to_pandas``): ``by="joint"``, a row
    per variant x angle x joint, the force's ``x`` and ``y`` and the ``moment``; ``by="angle"``, a row per
    variant x angle, the driving torque, the foundation's and the shaking loads (``_x``, ``_y``, ``moment``).
    The units in ``attrs["units"]``."""
    data, coords, attrs = forces_table(f)
    dims: tuple[str, ...] = ("variant", "angle", "joint")
    if by == "joint":
        (d, force, meta) = data.pop("force")
        data = {"x": (dims, force[..., 0], meta), "y": (dims, force[..., 1], meta), "moment": data["moment"]}
    elif by == "angle":
        dims = ("variant", "angle")
        for name in ("foundation_force", "shaking_force"):
            d, values, meta = data.pop(name)
            for i, c in enumerate("xy"):
                data[f"{name.removesuffix('_force')}_{c}"] = (dims, values[..., i], meta)
    else:
        raise LinkworkError(f'Forces.to_pandas takes by="joint" or by="angle", not "{by}"')
    return frame(data, coords, attrs, dims, purpose="Forces.to_pandas")
