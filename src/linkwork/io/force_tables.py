"""Tables of a kinetostatic result: the JSON object of ``linkwork forces --json`` and a CSV file."""

from __future__ import annotations

import csv
import math
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from linkwork.atomic import write_atomic
from linkwork.errors import LinkworkError
from linkwork.io.motion_tables import LONG, Table, crank_keys, drive_columns, drive_record, drive_units, frame
from linkwork.kinetostatics.external import magnitude_units
from linkwork.optional import require
from linkwork.structure.model import PairType

if TYPE_CHECKING:
    from linkwork.kinetostatics.reaction_forces import Forces
    from linkwork.structure.model import Mechanism

CONVENTION = (
    "joints: the force the first-named link exerts on the second, in the order of the file's joint and of "
    "'links' (x, y, N); a compound hinge is a pair from the link that carries the pin to each other link; "
    "for a prismatic pair (guide first) also its moment on the slider (N m) about the slider's point; driving torque: "
    "what the drive puts on its driven link, counter-clockwise positive; foundation: the force and "
    "the moment about the origin that the machine puts on its foundation, y up (positive y pulls the bolts)"
)


#: The crank angles of ``bolts`` (degrees), each written as φ and as the angle to x (:func:`crank_keys`).
_BOLT_ANGLES = tuple(f"{name}_angle_deg" for name in ("shear", "pull", "push", "moment"))


def _torque_peak(f: Forces) -> dict[str, Any] | None:
    """The peak driving torque (largest size, with its sign) refined between the samples
    (:func:`linkwork.kinetostatics.torque_peak`) and where it is: ``at_phi_deg`` and ``at_to_x_deg`` with one
    crank (:func:`crank_keys`), else ``at``, the drive's coordinate in SI; None with several drives or no finite
    sample."""
    from linkwork.kinetostatics.peaks import torque_peak
    from linkwork.motion.analysis import CrankAngles

    if f.mechanism.n_drives != 1:
        return None
    peak = torque_peak(f)
    value, at = float(peak.value[0]), float(peak.at[0])
    if not math.isfinite(value):
        return None
    if CrankAngles.of(f.mechanism) is None:  # a linear drive, or a crank that is not driven by the frame
        return {"value": value, "at": at}
    return crank_keys({"value": value, "at_deg": math.degrees(at)}, ("at_deg",), f.mechanism)


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


def _named(f: Any, k: int) -> tuple[str, str, np.ndarray]:
    """The links of pair ``k`` as the file names them, and the force of the first on the second ``(A, 2)``."""
    mech = f.mechanism
    first, second = (mech.link_names[int(i)] for i in mech.pair_members[k])
    return first, second, mech.pair_sign[k] * f.pair_force(k)[0]


def pair_moment(f: Any, k: int) -> np.ndarray:
    """The moment (N m, ``(A,)``) of prismatic pair ``k`` on its slider about the slider's point, 0.0 where it
    is the round-off of a zero: below :data:`~linkwork.io.jsonout.ZERO` times the pair's force at that angle
    times the mechanism's size (the quantities it is computed from).  What the table, the CSV and the JSON
    show."""
    return pair_moment_all(f, k)[0]


def pair_moment_all(f: Any, k: int) -> np.ndarray:
    """:func:`pair_moment` of every variant, ``(V, A)``."""
    from linkwork.io.jsonout import snap_zeros

    mech = f.mechanism
    size = float(np.ptp(np.asarray(mech.points0()), axis=0).max())
    force = f.pair_force(k)
    return snap_zeros(f.multipliers[..., 2 * k], scale=np.hypot(force[..., 0], force[..., 1]) * size)


def _table(f: Forces) -> tuple[Table, Table, dict[str, str]]:
    """The table of a kinetostatic result over variant x angle: each reported pair's force (joint x
    component: the link named first on the second, as ``forces.csv`` and the JSON give it, :func:`pair_labels`)
    and a prismatic pair's moment (NaN for the others), the driving torque, the foundation's and the shaking
    loads, ``singular``; coordinates ``angle`` (φ from position 0 with one crank, as :mod:`motion_tables`),
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
    """The table of a kinetostatic result (:func:`_table`) as an xarray Dataset (``Forces.to_xarray``)."""
    xr = require("xarray", purpose="Forces.to_xarray")
    data, coords, attrs = _table(f)
    return xr.Dataset(data, coords=coords, attrs=attrs)


def to_frame(f: Forces, by: str = "joint") -> Any:
    """The table of a kinetostatic result as a pandas DataFrame (``Forces.to_pandas``): ``by="joint"``, a row
    per variant x angle x joint, the force's ``x`` and ``y`` and the ``moment``; ``by="angle"``, a row per
    variant x angle, the driving torque, the foundation's and the shaking loads (``_x``, ``_y``, ``moment``).
    The units in ``attrs["units"]``."""
    data, coords, attrs = _table(f)
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


def _single(f: Any) -> None:
    if f.kinematics.variants:
        raise LinkworkError("this table holds one mechanism, not design variants")


def _arr(a: Any) -> list[float | None]:
    return [None if not math.isfinite(float(x)) else float(x) for x in np.asarray(a, dtype=float).ravel()]


def _clean(value: float) -> float | None:
    return value if math.isfinite(value) else None


def to_json(f: Any) -> dict[str, Any]:
    """The ``linkwork forces --json`` object (one mechanism)."""
    _single(f)
    mech = f.mechanism
    joints = {}
    for label, k in pair_labels(mech):
        first, second, force = _named(f, k)
        kind = pair_kind(mech, k)
        entry: dict[str, Any] = {
            "type": kind,
            "links": [first, second],
            "fx": _arr(force[:, 0]),
            "fy": _arr(force[:, 1]),
        }
        if kind == "prismatic":
            entry["moment"] = _arr(pair_moment(f, k))
        joints[label] = entry
    found = f.foundation
    shaking = f.shaking_force
    torque = f.driving_torque
    linear = mech.pair_type[mech.drive_pair[0]] != PairType.REVOLUTE
    return {
        "name": mech.name,
        "convention": CONVENTION,
        "units": {
            "force": "N",
            "moment": "N m",
            "driving_torque": "N" if linear else "N m",
            "loads": magnitude_units(mech),
            **drive_units(mech),
        },
        **{k: _arr(v) if isinstance(v, np.ndarray) else v for k, v in drive_record(mech, f.angles).items()},
        "driving_torque": _arr(torque),
        "driving_torque_peak": _torque_peak(f),
        "joints": joints,
        "foundation": {"fx": _arr(found[:, 0]), "fy": _arr(found[:, 1]), "moment": _arr(found[:, 2])},
        "shaking": {"fx": _arr(shaking[:, 0]), "fy": _arr(shaking[:, 1]), "moment": _arr(f.shaking_moment)},
        "loads": {name: _arr(v[0]) for name, v in f.loads.external.magnitude.items()},
        "bolts": {k: _clean(v) for k, v in crank_keys(f.bolts().as_dict(), _BOLT_ANGLES, mech).items()},
        "groups": groups(f),
        "checks": {k: _clean(v) for k, v in f.checks.items()},
        "valid": [bool(x) for x in np.asarray(f.kinematics.valid).ravel()],
        **({"efficiency": efficiency_record(f)} if has_losses(f) else {}),
    }


def has_losses(f: Any) -> bool:
    """Whether the mechanism of ``f`` has friction in a pair (constant, or in proportion to the force)."""
    return f.friction is not None or any(load.kind == "friction" for load in f.mechanism.loads)


def efficiency_record(f: Any) -> dict[str, Any]:
    """The ``efficiency`` of ``linkwork forces --json`` (:mod:`linkwork.kinetostatics.efficiency`): the powers
    of the balance (W) at each angle, the power lost in each joint, the instantaneous efficiency, the works
    (J) and the efficiency of the cycle; with friction in proportion to the forces, how it was solved."""
    from linkwork.kinetostatics.friction import MAX_ITERATIONS, TOLERANCE

    e = f.efficiency
    out: dict[str, Any] = {
        "units": {"power": "W", "work": "J", "efficiency": "1"},
        "drive_power": _arr(e.drive),
        "useful_power": _arr(e.useful),
        "friction_power": {joint: _arr(e.losses[:, j]) for j, joint in enumerate(e.joints)},
        "kinetic_energy_rate": _arr(e.kinetic),
        "potential_energy_rate": _arr(e.potential),
        "instantaneous": _arr(e.instantaneous),
        "work": {
            "drive": _clean(float(e.work(e.drive))),
            "useful": _clean(float(e.work(e.useful))),
            "friction": {joint: _clean(float(w)) for joint, w in zip(e.joints, e.work(e.losses), strict=True)},
        },
        "cycle": _clean(float(e.cycle)),
        "balance": _clean(_balance(e)),
    }
    if f.friction is not None:
        fr = f.friction

        def revolute(k: int) -> bool:
            return bool(f.mechanism.pair_type[k] == PairType.REVOLUTE)

        out["friction"] = {
            "joints": {p.joint: {"f": p.f, "friction_circle_m": p.coefficient if revolute(p.pair) else None}
                       for p in fr.pairs},
            "tolerance": TOLERANCE,
            "max_iterations": MAX_ITERATIONS,
            "iterations": fr.iterations,
            "residual": fr.residual,
            "problems": [{"joint": w.joint, "kind": w.kind, "at": list(w.angles), "message": str(w)}
                         for w in fr.problems],
        }  # fmt: skip
    return out


def _balance(e: Any) -> float:
    """The largest gap of the power balance (:attr:`~linkwork.kinetostatics.efficiency.Efficiency.imbalance`)
    relative to the largest drive power; NaN where nothing moves."""
    gap, drive = np.abs(e.imbalance), np.abs(e.drive)
    if not np.isfinite(gap).any():
        return math.nan
    top = float(np.nanmax(drive))
    return float(np.nanmax(gap)) / top if top > 0 else float(np.nanmax(gap))


def groups(f: Any) -> list[dict[str, Any]]:
    """Each Assur group's free body: its joints, and the largest residual of its balance relative to
    the largest force on it (zero for a correct solution)."""
    mech = f.mechanism
    out = []
    for body in f.free_bodies():
        scale = max([float(np.nanmax(np.abs(c.force), initial=0.0)) for c in body.external] + [1e-300])
        arm = 1.0 + max(float(np.nanmax(np.abs(c.point), initial=0.0)) for c in body.external)
        force = float(np.nanmax(np.abs(body.residual[..., :2]), initial=0.0)) / scale
        moment = float(np.nanmax(np.abs(body.residual[..., 2]), initial=0.0)) / (scale * arm)
        out.append(
            {
                "group": body.label,
                "links": [mech.link_names[i] for i in body.links],
                "external": sorted({c.joint + (" (drive)" if c.drive else "") for c in body.external}),
                "internal": sorted({c.joint for c in body.internal}),
                "residual": max(force, moment),
            }
        )
    return out


def write_csv(f: Any, path: str | Path) -> Path:
    """One row per angle: the driving torque, every pair's force (the link the file names first on
    the second, both in the header), the foundation and shaking loads, the external loads."""
    _single(f)
    mech = f.mechanism
    unit = "N" if mech.pair_type[mech.drive_pair[0]] != PairType.REVOLUTE else "N m"
    cols: list[tuple[str, np.ndarray]] = [
        (f"{name} [{u}]", values) for name, (u, values) in drive_columns(mech, f.angles).items()
    ]
    cols.append((f"driving_torque [{unit}]", f.driving_torque))
    for label, k in pair_labels(mech):
        a, b, force = _named(f, k)
        label = f"{label} ({a} on {b})"
        cols += [(f"{label}.fx [N]", force[:, 0]), (f"{label}.fy [N]", force[:, 1])]
        if pair_kind(mech, k) == "prismatic":
            cols.append((f"{label}.moment [N m]", pair_moment(f, k)))
    found = f.foundation
    cols += [("foundation.fx [N]", found[:, 0]), ("foundation.fy [N]", found[:, 1])]
    cols += [("foundation.moment [N m]", found[:, 2])]
    cols += [("shaking.fx [N]", f.shaking_force[:, 0]), ("shaking.fy [N]", f.shaking_force[:, 1])]
    cols += [("shaking.moment [N m]", f.shaking_moment)]
    units = magnitude_units(mech)
    cols += [(f"load.{name} [{units[name]}]", v[0]) for name, v in f.loads.external.magnitude.items()]
    if has_losses(f):
        e = f.efficiency
        cols += [("drive_power [W]", e.drive), ("useful_power [W]", e.useful)]
        cols += [(f"friction_power.{joint} [W]", e.losses[:, j]) for j, joint in enumerate(e.joints)]
        cols += [("efficiency [1]", e.instantaneous)]

    def writer(tmp: Path) -> None:
        with open(tmp, "w", newline="", encoding="utf-8") as fh:
            w = csv.writer(fh)
            w.writerow([c[0] for c in cols])
            for row in zip(*(c[1] for c in cols), strict=True):
                w.writerow([repr(float(x)) for x in row])

    return write_atomic(path, writer)
