"""``linkwork.size``: the machine sized from its loads: motor, gear and flywheel, bearings, pins, bolts.

The loads are those of the kinetostatics at the file's uniform crank speed (the steady cycle's speed varies
within ``delta`` of it); the motor is chosen and run with the machine dynamics (:mod:`linkwork.sizing.motor`).
Every input with a default is stated in the record (``inputs``).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from linkwork.errors import LinkworkError
from linkwork.sizing.bearings import Bearings, Bush, bearings
from linkwork.sizing.bolts import BoltResult, size_bolts
from linkwork.sizing.common import Catalogue, Table, bundled
from linkwork.sizing.governing import governing_diameter, governing_table, made_diameters
from linkwork.sizing.links import Bars, bars
from linkwork.sizing.masses import SizedMasses, block_masses, blocks, sized_masses
from linkwork.sizing.motor import MotorChoice, choose_motor, motor_catalogue, synchronous_problem
from linkwork.sizing.pairs import Pair, pairs_of
from linkwork.sizing.pin_shear import Pins, Steel, pins
from linkwork.sizing.proportions import Proportions, proportions
from linkwork.sizing.shaft import Shaft, main_shaft, split
from linkwork.structure.model import Mechanism

#: The default life of rolling bearings, h.
LIFE_H = 20000.0
#: The default coefficient of speed fluctuation where the file gives none.
DELTA = 0.05
#: The default gear efficiency where the file gives no gear.
EFFICIENCY = 0.95


@dataclass(frozen=True)
class Sizing:
    """The sizing of a machine: each part's result (None where it was not asked or has no data: ``missing``
    says why), and the inputs it was sized with, defaults included."""

    name: str
    inputs: dict[str, Any]
    motor: MotorChoice | None
    bearings: Bearings
    pins: Pins
    bolts: BoltResult | None
    missing: dict[str, str]
    links: Bars | None = None
    shaft: Shaft | None = None
    masses: SizedMasses | None = None  # the links' masses sized to a fixed point (masses="sized"), else None
    proportions: Proportions | None = None  # the sized parts against each other and the geometry

    def warnings(self) -> list[str]:
        """The parts that do not fit (:mod:`~linkwork.sizing.proportions`), a sentence each."""
        return self.proportions.warnings() if self.proportions is not None else []

    def tables(self) -> list[Table]:
        out = [self.motor.table()] if self.motor is not None else []
        out += [governing_table(self.pins, self.bearings)]
        out += [self.shaft.table()] if self.shaft is not None else []
        out += self.bearings.tables() + [self.pins.table()]
        out += [self.links.table()] if self.links is not None else []
        out += [self.proportions.table()] if self.proportions is not None else []
        out += self.bolts.tables() if self.bolts is not None else []
        return out

    def record(self) -> dict[str, Any]:
        """The JSON record (write it with :func:`linkwork.io.jsonout.dumps`)."""
        return {
            "name": self.name,
            "inputs": self.inputs,
            "motor": self.motor.record() if self.motor is not None else None,
            "bearings": self.bearings.record(),
            "pins": self.pins.record(),
            "joints": governing_table(self.pins, self.bearings).record(),
            "shaft": self.shaft.record() if self.shaft is not None else None,
            "masses_kg": self.masses.masses if self.masses is not None else None,
            "links": self.links.record() if self.links is not None else None,
            "proportions": self.proportions.record() if self.proportions is not None else None,
            "bolts": self.bolts.record() if self.bolts is not None else None,
            "missing": self.missing,
        }


def _row(cat: Catalogue, name: str, what: str) -> dict[str, float]:
    if name not in cat.names:
        raise LinkworkError(f'{what} "{name}": one of {", ".join(cat.names)} ({cat.source})')
    return cat.row(cat.names.index(name))


def _file_parts(file: Any) -> tuple[dict[str, tuple[float, float]], dict[str, float], dict[str, Any]]:
    """The pins (diameter, width), the guides' lengths and the links' sections (shape, dimensions) of the file's
    ``sizing:`` section (None: none of them), SI."""
    if file is None:
        return {}, {}, {}
    pins_given = {k: (v.diameter, v.width) for k, v in file.pins.items()}
    sections = {
        name: (sec.shape, {k: v for k, v in sec.model_dump(exclude={"shape"}).items() if v is not None})
        for name, sec in file.sections.items()
    }
    return pins_given, dict(file.guides), sections


def size(
    mech: Mechanism,
    *,
    life_h: float | None = None,
    kind: str = "ball",
    delta: float | None = None,
    efficiency: float | None = None,
    reserve: float = 0.8,
    catalogue: str | Path | Catalogue | None = None,
    synchronous: float | None = None,
    motor: bool = True,
    steel: str = "C45 normalised",
    safety: float = 2.0,
    bush: str = "tin bronze CuSn12 greased",
    width_ratio: float = 1.0,
    bolts: Any = None,
    bolt_class: str = "5.6",
    bolt_safety: float = 1.5,
    joint_safety: float = 1.5,
    friction: float = 0.2,
    load_factor: float = 0.25,
    steps: int = 360,
    progress: Callable[[int, int], None] | None = None,
    masses: str | None = None,
    compile_spec: Callable[[Any], Mechanism] | None = None,
) -> Sizing:
    """Size the machine ``mech`` (``linkwork.size`` also takes a path, an example name or a Spec).

    Parameters
    ----------
    mech : Mechanism
        The compiled machine (one crank).
    life_h : float
        Basic rating life L10h of the rolling bearings, h (default: the file's ``sizing: life``, else 20000).
    kind : str
        ``ball`` or ``roller`` bearings (the life exponent 3 or 10/3).
    delta : float
        Coefficient of speed fluctuation the flywheel is sized for (default: the file's, else 0.05).
    efficiency : float
        Of the gear (default: the file's gear's, else 0.95).
    reserve : float
        The share of the motor's breakdown torque its peak torque may reach.
    catalogue : path or Catalogue
        A motor catalogue (CSV, the columns of the bundled ``motors.csv``, or one read already); default the bundled
        one.
    synchronous : float
        Keep to motors of this synchronous speed, rad/s.
    motor : bool
        Choose the motor (False: bearings, pins and bolts only).
    steel, safety : str, float
        The steel grade of the pins and links (``steels.csv``) and the safety factor on its yield strength.
    bush, width_ratio : str, float
        The plain bush (``bushes.csv``) and the width / diameter of the least pins.
    bolts : array (n, 2)
        Foundation bolts' positions, m (default: the file's ``sizing: bolts``); none: no bolt sizing.
    bolt_class, bolt_safety, joint_safety, friction, load_factor
        The bolts' property class (``bolt_classes.csv``) and safety on its yield; the joint's safety against
        opening and sliding, its friction coefficient and load factor.
    steps : int
        Crank angles over the turn for the loads.
    progress : callable, optional
        ``progress(k, n)``: told of each motor ``k`` of the ``n`` of the catalogue the choice looks at.
    masses : str
        ``"sized"`` (the default where the mechanism has its file and ``compile_spec`` is given, as
        ``linkwork.size`` gives it): the bars' masses from their sized steel sections and the blocks' from their
        pins and guides, iterated with the loads to a fixed point (:mod:`linkwork.sizing.masses`); ``"file"``: the
        links' masses as the file gives them (or its default rule), the default otherwise.
    compile_spec : callable
        How an edited file is compiled, for ``masses="sized"`` (``linkwork.size`` passes :func:`linkwork.compile`).

    Returns
    -------
    Sizing
        The links' sections, the pins, the bearings (rating, life), the bolts, the motor, gear and flywheel
        chosen, each with the load that governs it, and the inputs and defaults used (``inputs``).

    Examples
    --------
    >>> import linkwork as lw
    >>> sized = lw.size("double-cut-shears", steps=72)  # doctest: +SKIP
    >>> sized.motor  # doctest: +SKIP
    """
    file = mech.spec.sizing if mech.spec is not None and mech.spec.sizing is not None else None
    if life_h is None:
        life_h = file.life / 3600.0 if file is not None and file.life is not None else LIFE_H
    if delta is None:
        delta = mech.delta if mech.delta is not None else DELTA
    if efficiency is None:
        efficiency = mech.motor_gear.efficiency if mech.motor_gear is not None else EFFICIENCY
    if bolts is None and file is not None and file.bolts:
        bolts = np.array(file.bolts, dtype=float)
    cat = motor_catalogue(catalogue) if motor else None  # read, and its speeds checked, before any computing
    if cat is not None and synchronous is not None:
        why = synchronous_problem(cat, synchronous)
        if why is not None:
            raise LinkworkError(why)
    steel_row = _row(bundled("steels.csv"), steel, "steel")
    bush_row = _row(bundled("bushes.csv"), bush, "bush")
    _row(bundled("bolt_classes.csv"), bolt_class, "bolt class")  # a wrong class said even where no bolts are sized
    bush_limits = Bush(bush, bush_row["p"], bush_row["v"], bush_row["pv"])
    grade = Steel(steel, steel_row["yield"], steel_row["tensile"], steel_row["endurance"])
    pin_sizes, guides, given = _file_parts(file)
    from linkwork.kinetostatics.reaction_forces import forces
    from linkwork.motion.analysis import CrankAngles

    if masses is None:
        masses = "sized" if mech.spec is not None and compile_spec is not None else "file"
    if masses not in ("file", "sized"):
        raise LinkworkError(f'masses: "file" or "sized", got "{masses}"')
    angles = CrankAngles.of(mech)
    if angles is None:
        raise LinkworkError("sizing needs one crank driven by the frame: the cycle is its turn")

    def bars_of(m: Mechanism) -> Bars:
        fm = forces(m, steps=steps)
        return bars(fm, np.asarray(angles.phi(fm.angles), dtype=float), grade, safety=safety, sections=given)

    if masses == "sized" and compile_spec is None:
        raise LinkworkError('masses="sized" compiles the file with each round\'s masses: call linkwork.size')

    def pin_of(force: float) -> float:
        return governing_diameter(force, grade, safety, width_ratio, bush_limits.p)

    def blocks_of(m: Mechanism, bars_: Bars) -> dict[str, float]:
        return block_masses(pairs_of(forces(m, steps=steps)), bars_, pin_of, width_ratio, bush_limits.p)

    sized = (
        sized_masses(mech, bars_of, compile_spec, blocks_of=blocks_of)
        if masses == "sized" and compile_spec is not None
        else None
    )
    mech = sized.mechanism if sized is not None else mech
    f = forces(mech, steps=steps)
    phi = np.asarray(angles.phi(f.angles), dtype=float)
    crank = abs(float(mech.drive_speed[0]))
    pairs = pairs_of(f)
    missing: dict[str, str] = {}
    pinned = pins(pairs, phi, grade, safety=safety, sizes=pin_sizes, width_ratio=width_ratio)
    shaft = _shaft(mech, pairs, pinned, file)
    pairs_of_joints = pairs  # as the joints are, before the main shaft's two bearings
    if shaft is not None:
        pairs = split(pairs, shaft.joint, shaft.shares)
        pin_sizes = {
            **pin_sizes,
            **{f"{shaft.joint}/{n}": pin_sizes[shaft.joint] for n in (1, 2) if shaft.joint in pin_sizes},
        }
        pin_sizes.pop(shaft.joint, None)
    found = bearings(
        pairs,
        phi,
        crank,
        life_h=life_h,
        kind=kind,
        bush=bush_limits,
        pins=pin_sizes,
        width_ratio=width_ratio,
        guides=guides,
    )
    linked = bars(f, phi, grade, safety=safety, sections=given)
    slid = blocks(pairs_of_joints, linked, pin_of, width_ratio, bush_limits.p)
    depths = {b.link: _depth(b, given) for b in linked.bars}
    made = made_diameters(pinned, found)
    checked = proportions(mech, f.kinematics, made, linked, depths, {k: b.length for k, b in slid.items()})
    unbounded = [p for p in pairs_of_joints if math.isinf(p.peak)]
    if unbounded:
        missing[f"joints {', '.join(p.label for p in unbounded)}"] = (
            f"the force grows without bound as the crank nears the singular position at phi "
            f"{unbounded[0].peak_phi:.4g} deg: no pin, bush or bearing holds it"
        )
    held = None
    if bolts is not None and len(bolts):
        found_loads = np.asarray(f.foundation, dtype=float)
        held = size_bolts(
            found_loads,
            phi,
            np.asarray(bolts, dtype=float),
            threads=bundled("threads.csv"),
            classes=bundled("bolt_classes.csv"),
            bolt_class=bolt_class,
            safety=joint_safety,
            friction=friction,
            load_factor=load_factor,
            bolt_safety=bolt_safety,
        )
    else:
        missing["bolts"] = "no bolt pattern: give sizing: bolts: [[x, y], ...] in the file"
    choice = None  # last: the runs of the machine take the longest, and the other parts' problems come first
    if motor:
        from linkwork.machine.reduction import reduced

        choice = choose_motor(
            mech,
            reduced(mech),
            delta,
            efficiency=efficiency,
            reserve=reserve,
            catalogue=cat,
            synchronous=synchronous,
            progress=progress,
        )
    else:
        missing["motor"] = "not asked"
    chosen = {
        "delta": delta,
        "gear_efficiency": efficiency,
        "reserve": reserve,
        "catalogue": cat.source
        if cat is not None and catalogue is not None
        else "motors.csv (bundled, typical values)",
        "synchronous_rpm": synchronous * 30 / math.pi if synchronous is not None else None,
    }
    inputs = {
        "life_h": life_h,
        "bearing_kind": kind,
        **(chosen if motor else {}),
        "steel": steel,
        "pin_safety": safety,
        "bush": bush,
        "width_ratio": width_ratio,
        "bolt_class": bolt_class,
        "bolt_safety": bolt_safety,
        "joint_safety": joint_safety,
        "friction": friction,
        "load_factor": load_factor,
        "steps": steps,
        "crank_rpm": crank * 30 / math.pi,
        "loads": "kinetostatics at the file's uniform crank speed",
        "masses": sized.said() if sized is not None else "the file's (or its default rule)",
    }
    return Sizing(mech.name or "mechanism", inputs, choice, found, pinned, held, missing, linked, shaft, sized, checked)


def _depth(bar: Any, given: dict[str, Any]) -> float:
    """The depth (m) of a bar's section in the mechanism's plane: the file's section's (round and tube ``d``,
    rectangle and I ``h``), else the least round bar's."""
    if bar.link in given:
        shape, dims = given[bar.link]
        return float(dims["d"] if shape in ("round", "tube") else dims["h"])
    return math.sqrt(4 * bar.area / math.pi)


def _shaft(mech: Mechanism, pairs: list[Pair], pinned: Pins, file: Any) -> Shaft | None:
    """The main shaft of the crank's pivot (the first drive's joint with the frame), or None (no such pair)."""
    joint = mech.spec.drives[0].joint if mech.spec is not None and mech.spec.drives else None
    pair = next((p for p in pairs if p.label == joint and p.kind == "revolute" and "frame" in p.links), None)
    pin = next((p for p in pinned.pins if p.label == joint), None)
    if pair is None or pin is None:
        return None
    return main_shaft(pair, file.shaft if file is not None else None, pin.diameter, pinned, pin.force)
