"""The records of the stages after the structure, compiled from a validated file: the loads and force elements
(:class:`~linkwork.structure.records.ExternalLoad`), the friction in the pairs
(:class:`~linkwork.structure.records.PairFriction`) and the machine unit's motor and gear
(:class:`~linkwork.structure.records.MotorGear`).

This is the one place below :mod:`linkwork.api` where the file format (:mod:`linkwork.spec`) meets the analyses:
they read the records (numbers and indices), never the file's objects.  :func:`linkwork.compile` calls
:func:`compile_loads`, :func:`compile_friction` and :func:`from_spec` after the structural model.
"""

from __future__ import annotations

import math
from typing import Any, TypeVar, cast

import numpy as np

from linkwork.errors import Problem, SpecError
from linkwork.kinetostatics.elements import ELEMENTS
from linkwork.machine.drive import Characteristic, ConstantTorque, InductionMotor, LinearMotor
from linkwork.spec.schema import Load, Spec
from linkwork.spec.schema import Machine as MachineSpec
from linkwork.spec.schema import Motor as MotorSpec
from linkwork.structure.model import Mechanism, PairType
from linkwork.structure.records import ExternalLoad, MotorGear, PairFriction

T = TypeVar("T")


def compile_loads(spec: Spec, mech: Mechanism) -> tuple[ExternalLoad, ...]:
    """The :class:`ExternalLoad` records of a validated spec, for its structural model ``mech``
    (:func:`linkwork.structure.compile.structural_model`: its links, points and elementary pairs)."""
    names = _Names(mech)
    out: list[ExternalLoad] = []
    for name, load in spec.loads.items():
        if load.type == "force":
            out.append(_force(name, load, names))
        elif load.type == "friction":
            out += _friction_loads(name, load, mech)
        elif load.type == "moment":
            out.append(_moment(name, load, names))
        elif load.type in ELEMENTS:
            out.append(ExternalLoad(name, **compile_element(load, mech, name, spec)))
        else:
            out.append(_process(name, load, names))
    return tuple(out)


class _Names:
    """The links and points of a structural model by the names a file gives them."""

    def __init__(self, mech: Mechanism) -> None:
        self.links = {name: i for i, name in enumerate(mech.link_names)}
        self.points = {(int(mech.point_link[p]), name.split(".", 1)[1]): p for p, name in enumerate(mech.point_names)}

    def point(self, ref: str) -> int:
        """Index of the point ``link.point``."""
        ln, p = ref.split(".", 1)
        return self.points[(self.links[ln], p)]

    def link(self, ref: str) -> int:
        """Index of the link of the point ``link.point``."""
        return self.links[ref.split(".", 1)[0]]


def _given(value: T | None) -> T:
    """A field of a load that :mod:`linkwork.spec.checks` requires for its type."""
    assert value is not None
    return value


def _number(value: object) -> float:
    """A load's value that the checks of :mod:`linkwork.spec` make one number where it is read (no table)."""
    return float(cast(float, value))


def _table(x: list[float], y: object) -> tuple[np.ndarray, np.ndarray]:
    """A table's arguments ``x`` and values ``y``."""
    return np.array(x, dtype=float), np.array(y, dtype=float)


def _force(name: str, load: Load, names: _Names) -> ExternalLoad:
    """A force at a point: given by its components, or by a magnitude (constant or a table over the crank
    angle) along a direction."""
    at = _given(load.at)
    p, link = names.point(at), names.link(at)
    if load.force is not None:
        return ExternalLoad(name, "force", link, (p,), (load.force[0], load.force[1]), 1.0)
    direction = _number(load.direction)
    u = (math.cos(direction), math.sin(direction))
    if load.angle is None:
        return ExternalLoad(name, "force", link, (p,), u, _number(load.magnitude))
    return ExternalLoad(name, "force", link, (p,), u, table=_table(load.angle, load.magnitude))


def _friction_loads(name: str, load: Load, mech: Mechanism) -> list[ExternalLoad]:
    """Friction in every elementary pair of a joint: a moment in a revolute pair, a force in a prismatic one."""
    out: list[ExternalLoad] = []
    pairs = zip(mech.pair_joint, mech.pair_type, mech.pair_links, strict=True)
    for k, (joint, kind, (_, b)) in enumerate(pairs):
        if joint != load.joint:
            continue
        if kind == PairType.REVOLUTE and load.moment is not None:
            out.append(ExternalLoad(name, "friction", int(b), value=_number(load.moment), pair=k))
        elif kind == PairType.PRISMATIC and load.magnitude is not None:
            out.append(ExternalLoad(name, "friction", int(b), value=_number(load.magnitude), pair=k))
    return out


def _moment(name: str, load: Load, names: _Names) -> ExternalLoad:
    """A moment on a link: constant, or a table over the crank angle."""
    link = names.links[_given(load.on)]
    if load.angle is None:
        return ExternalLoad(name, "moment", link, value=_number(load.moment))
    return ExternalLoad(name, "moment", link, table=_table(load.angle, load.moment))


def _process(name: str, load: Load, names: _Names) -> ExternalLoad:
    """A process load: a table of force against the tools' relative penetration into a workpiece."""
    tools = _given(load.tools)
    axis = _number(load.axis)
    lo, hi = _given(load.workpiece)
    return ExternalLoad(
        name,
        "process",
        names.link(tools[0]),
        tuple(names.point(t) for t in tools),
        (math.cos(axis), math.sin(axis)),
        table=_table(_given(load.penetration), load.force),
        workpiece=(lo, hi),
    )


def compile_element(load: Load, mech: Mechanism, name: str, spec: Spec) -> dict[str, Any]:
    """The fields of the record of one force element ``name`` of a validated spec: ``points`` the two points
    (spring, damper), ``pair`` the revolute pair (torsion spring), ``value`` the stiffness or damping, ``free`` the
    free length or angle (a preload turned into the free length at the assembly pose ``mech.pose0``).

    Raises
    ------
    SpecError
        A preload that would need a negative free length (at the preload's line of the file).
    """
    if load.type == "torsion_spring":
        pair = _joint_pair(mech, str(load.joint), spec.joints[str(load.joint)].links)
        free = float(load.free_angle if load.free_angle is not None else 0.0)
        link = int(mech.pair_members[pair, 1])
        return {"kind": load.type, "link": link, "value": float(load.stiffness or 0.0), "pair": pair, "free": free}
    assert load.between is not None  # the checks of linkwork.spec require it
    points = tuple(_point(mech, ref) for ref in load.between)
    out = {"kind": load.type, "link": int(mech.point_link[points[0]]), "points": points}
    if load.type == "damper":
        return {**out, "value": float(load.damping or 0.0)}
    k = float(load.stiffness or 0.0)
    if load.free_length is not None:
        return {**out, "value": k, "free": float(load.free_length)}
    p = mech.points0()  # the preload is its tension in the assembly pose
    length = float(np.linalg.norm(p[points[1]] - p[points[0]]))
    free = length - (float(load.preload or 0.0) / k if k > 0 else 0.0)
    if free < 0:
        raise _problem(
            mech,
            ("loads", name, "preload"),
            f"a spring's preload of {float(load.preload or 0.0):g} N stretches it by {length - free:g} m at "
            f"{k:g} N/m, more than its length of {length:g} m in the assembly pose: its free length would be "
            f"negative; at most {k * length:g} N",
        )
    return {**out, "value": k, "free": free}


def _problem(mech: Mechanism, path: tuple[str, ...], message: str) -> SpecError:
    """A :class:`SpecError` of one problem at ``path`` of the mechanism's file (its line, where it was read)."""
    source = mech.description
    if source is not None:
        return SpecError([source.problem(path, message)])
    return SpecError([Problem(".".join(path), message)])


def _point(mech: Mechanism, ref: str) -> int:
    """Index of the point ``link.point``, or of the frame point named ``ref``."""
    return mech.point_names.index(ref if "." in ref else f"frame.{ref}")


def _joint_pair(mech: Mechanism, joint: str, links: list[str]) -> int:
    """The elementary pair of a revolute joint between its first two ``links`` (as the file names them)."""
    first = None
    for k, name in enumerate(mech.pair_joint):
        if name != joint:
            continue
        first = k if first is None else first
        members = [mech.link_names[int(i)] for i in mech.pair_members[k]]
        if members == list(links[:2]):
            return k
    assert first is not None
    return first


def compile_friction(spec: Spec, mech: Mechanism) -> tuple[PairFriction, ...]:
    """The :class:`PairFriction` of every elementary pair of the joints whose ``friction`` the validated
    ``spec`` gives, for its structural model ``mech``: a revolute pair's where the joint gives a ``radius``
    (a pin-in-slot's pin), every prismatic pair's."""
    out: list[PairFriction] = []
    for k, joint in enumerate(mech.pair_joint):
        law = spec.joints[joint].friction if joint in spec.joints else None
        if law is None:
            continue
        if mech.pair_type[k] == PairType.PRISMATIC:
            out.append(PairFriction(joint, k, float(law.f), float(law.f)))
        elif law.radius is not None:
            out.append(PairFriction(joint, k, float(law.f * law.radius), float(law.f)))
    return tuple(out)


def from_spec(machine: MachineSpec) -> MotorGear:
    """The :class:`~linkwork.structure.records.MotorGear` of a validated ``machine:`` section."""
    m = machine.motor
    gear = machine.gear
    fly = machine.flywheel
    return MotorGear(
        _motor(m),
        ratio=gear.ratio if gear else 1.0,
        efficiency=gear.efficiency if gear else 1.0,
        rotor=m.inertia or 0.0,
        flywheel=fly.inertia if fly else 0.0,
        flywheel_on=fly.on if fly else "motor",
    )


def _motor(m: MotorSpec) -> Characteristic:
    """The characteristic of a validated ``motor:`` (its type's values are there)."""
    if m.type == "constant":
        assert m.torque is not None
        return ConstantTorque(m.torque)
    if m.type == "linear":
        assert m.stall is not None and m.no_load is not None
        return LinearMotor(m.stall, m.no_load)
    assert m.power is not None and m.speed is not None and m.synchronous is not None and m.breakdown is not None
    return InductionMotor(m.power, m.speed, m.synchronous, m.breakdown)
