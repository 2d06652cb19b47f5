"""Files of a kinetostatic result: the JSON object of ``linkwork forces --json`` and a CSV file (the table itself is
:mod:`linkwork.kinetostatics.tables`'s)."""

from __future__ import annotations

import csv
import math
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from linkwork.atomic import write_atomic
from linkwork.errors import LinkworkError
from linkwork.io.motion_tables import crank_keys
from linkwork.kinetostatics.external import magnitude_units
from linkwork.kinetostatics.tables import CONVENTION, pair_kind, pair_labels, pair_moment
from linkwork.motion.tables import drive_columns, drive_record, drive_units
from linkwork.structure.model import PairType

if TYPE_CHECKING:
    from linkwork.kinetostatics.reaction_forces import Forces

#: The crank angles of ``bolts`` (degrees), each written as φ and as the angle to x (:func:`crank_keys`).
_BOLT_ANGLES = tuple(f"{name}_angle_deg" for name in ("shear", "pull", "push", "moment"))


def _torque_peak(f: Forces) -> dict[str, Any] | None:
    """The peak driving torque (largest size, with its sign) refined between the samples
    (:func:`linkwork.kinetostatics.torque_peak`) and where it is: ``at_phi_deg`` and ``at_to_x_deg`` with one
    crank (:func:`crank_keys`), else ``at``, the drive's coordinate in SI; where it grows without bound
    (:data:`~linkwork.kinetostatics.peaks.UNBOUNDED`), ``value`` null, ``unbounded`` true and the ``reason``, as the
    pairs' peaks (:func:`_largest`); None with several drives or no finite sample."""
    from linkwork.kinetostatics.peaks import UNBOUNDED, torque_peak
    from linkwork.motion.analysis import CrankAngles

    if f.mechanism.n_drives != 1:
        return None
    peak = torque_peak(f)
    value, at = float(peak.value[0]), float(peak.at[0])
    if math.isnan(value) or math.isnan(at):
        return None
    record: dict[str, Any] = {"value": _clean(value), "unbounded": math.isinf(value)}
    if math.isinf(value):
        record["reason"] = UNBOUNDED
    if CrankAngles.of(f.mechanism) is None:  # a linear drive, or a crank that is not driven by the frame
        return record | {"at": at}
    return crank_keys(record | {"at_deg": math.degrees(at)}, ("at_deg",), f.mechanism)


def _largest(f: Forces, pairs: list[int]) -> list[dict[str, Any]]:
    """The largest size of the force of each of ``pairs`` refined between the samples
    (:func:`linkwork.kinetostatics.peaks.pair_force_peaks`) and where it is (as :func:`_torque_peak`): ``value``
    (N), ``unbounded`` and, where it grows without bound towards a singular position, ``value`` null and the
    ``reason``, the angle being that position's."""
    from linkwork.kinetostatics.peaks import UNBOUNDED, pair_force_peaks

    found = pair_force_peaks(f, pairs)
    out = []
    for value, at, unbounded in zip(found.value.tolist(), found.at.tolist(), found.unbounded.tolist(), strict=True):
        record: dict[str, Any] = {"value": _clean(value), "unbounded": unbounded}
        if unbounded:
            record["reason"] = UNBOUNDED
        if math.isfinite(at):
            record |= crank_keys({"at_deg": math.degrees(at)}, ("at_deg",), f.mechanism)
        out.append(record)
    return out


def _named(f: Any, k: int) -> tuple[str, str, np.ndarray]:
    """The links of pair ``k`` as the file names them, and the force of the first on the second ``(A, 2)``."""
    mech = f.mechanism
    first, second = (mech.link_names[int(i)] for i in mech.pair_members[k])
    return first, second, mech.pair_sign[k] * f.pair_force(k)[0]


def _single(f: Any) -> None:
    if f.kinematics.variants:
        raise LinkworkError("this table holds one mechanism, not design variants")


def _arr(a: Any) -> list[float | None]:
    return [None if not math.isfinite(float(x)) else float(x) for x in np.asarray(a, dtype=float).ravel()]


def _clean(value: float) -> float | None:
    return value if math.isfinite(value) else None


def to_json(f: Any) -> dict[str, Any]:
    """The ``linkwork forces --json`` object (one mechanism)."""
    from linkwork.kinetostatics.crosschecks import cross_checks

    _single(f)
    mech = f.mechanism
    joints = {}
    labels = pair_labels(mech)
    for (label, k), largest in zip(labels, _largest(f, [k for _, k in labels]), strict=True):
        first, second, force = _named(f, k)
        kind = pair_kind(mech, k)
        entry: dict[str, Any] = {
            "type": kind,
            "links": [first, second],
            "fx": _arr(force[:, 0]),
            "fy": _arr(force[:, 1]),
            "largest": largest,
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
        "checks": {k: _clean(v) for k, v in cross_checks(f).items()},
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
            "joints": {
                p.joint: {"f": p.f, "friction_circle_m": p.coefficient if revolute(p.pair) else None} for p in fr.pairs
            },
            "tolerance": TOLERANCE,
            "max_iterations": MAX_ITERATIONS,
            "iterations": fr.iterations,
            "residual": fr.residual,
            "problems": [
                {"joint": w.joint, "kind": w.kind, "at": list(w.angles), "message": str(w)} for w in fr.problems
            ],
        }
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
    from linkwork.kinetostatics.crosschecks import free_body_residual

    mech = f.mechanism
    out = []
    for body in f.free_bodies():
        out.append(
            {
                "group": body.label,
                "links": [mech.link_names[i] for i in body.links],
                "external": sorted({c.joint + (" (drive)" if c.drive else "") for c in body.external}),
                "internal": sorted({c.joint for c in body.internal}),
                "residual": free_body_residual(body),
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
