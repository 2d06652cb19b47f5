"""``linkwork.size``: the machine sized from its loads: motor, gear and flywheel, bearings, pins, bolts.

The loads are those of the kinetostatics at the file's uniform crank speed (the steady cycle's speed varies
within ``delta`` of it); the motor is chosen and run with the machine dynamics (:mod:`linkwork.sizing.motor`).
Its inputs are one record, the schema of the file's ``sizing:`` section (:class:`~linkwork.spec.schema.SizingSpec`,
the one home of their defaults); every input is stated in the result (``inputs``).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

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
from linkwork.spec.reader import described
from linkwork.spec.schema import SizingSpec
from linkwork.structure.model import Mechanism

if TYPE_CHECKING:
    from linkwork.kinetostatics.reaction_forces import Forces

#: The default life of rolling bearings, h (:class:`~linkwork.spec.schema.SizingSpec`'s ``life``).
LIFE_H = SizingSpec.model_fields["life"].default / 3600.0
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


#: The keyword options of :func:`size` named otherwise in the record (:class:`~linkwork.spec.schema.SizingSpec`):
#: the field each gives and the factor to its SI value.
RENAMED = {"life_h": ("life", 3600.0), "kind": ("bearings", 1.0)}
#: Fields of the record that are no keyword option of :func:`size` (``motor`` is its own argument).
NOT_OPTIONS = ("motor",)


def sizing_inputs(
    mech: Mechanism, sizing: SizingSpec | Mapping[str, Any] | None = None, options: Mapping[str, Any] | None = None
) -> SizingSpec:
    """The record the machine ``mech`` is sized with: its file's ``sizing:`` section (or the defaults of
    :class:`~linkwork.spec.schema.SizingSpec`, their one home), with the fields of ``sizing`` (a record, or a
    mapping of its fields; bare numbers in SI) over it and the keyword ``options`` of :func:`size` over those
    (None: not given).

    Raises
    ------
    TypeError
        An option that is no field of the record (with the field it may have meant).
    SpecError
        A value out of its range, one problem per field (``sizing.reserve: ...``).
    """
    from pydantic import ValidationError

    from linkwork.did_you_mean import suggest
    from linkwork.errors import Problem, SpecError
    from linkwork.units import SI_UNITS

    spec = described(mech.description)
    base = spec.sizing if spec is not None and spec.sizing is not None else SizingSpec()
    if isinstance(sizing, SizingSpec):
        given = {k: getattr(sizing, k) for k in sizing.model_fields_set}
    else:
        given = dict(sizing or {})
    known = [k for k in (*SizingSpec.model_fields, *RENAMED) if k not in NOT_OPTIONS]
    for key, value in (options or {}).items():
        if key not in known:
            hint = suggest(key, known)
            raise TypeError(f"size() got an unexpected keyword argument {key!r}" + (f" ({hint})" if hint else ""))
        if value is not None:
            name, factor = RENAMED.get(key, (key, 1.0))
            given[name] = value * factor if factor != 1.0 else value
    given = {k: v.tolist() if isinstance(v, np.ndarray) else v for k, v in given.items()}
    try:
        checked = SizingSpec.model_validate(given, context={"units": SI_UNITS})
    except ValidationError as exc:
        problems = [
            Problem("sizing." + ".".join(str(x) for x in e["loc"]), e["msg"]) for e in exc.errors(include_url=False)
        ]
        raise SpecError(problems) from None
    return base.model_copy(update={k: getattr(checked, k) for k in checked.model_fields_set})


@dataclass(frozen=True)
class _Rules:
    """What every part is sized by: the inputs, the steel of the pins and links and the plain bush (read from the
    bundled catalogues), and the file's pins (diameter, width), guides' lengths and links' sections, SI."""

    inputs: SizingSpec
    grade: Steel
    bush: Bush
    pins: dict[str, tuple[float, float]]
    guides: dict[str, float]
    sections: dict[str, Any]

    @classmethod
    def of(cls, inp: SizingSpec) -> _Rules:
        steel_row = _row(bundled("steels.csv"), inp.steel, "steel")
        bush_row = _row(bundled("bushes.csv"), inp.bush, "bush")
        _row(bundled("bolt_classes.csv"), inp.bolt_class, "bolt class")  # said even where no bolts are sized
        sections = {
            name: (sec.shape, {k: v for k, v in sec.model_dump(exclude={"shape"}).items() if v is not None})
            for name, sec in inp.sections.items()
        }
        return cls(
            inp,
            Steel(inp.steel, steel_row["yield"], steel_row["tensile"], steel_row["endurance"]),
            Bush(inp.bush, bush_row["p"], bush_row["v"], bush_row["pv"]),
            {k: (v.diameter, v.width) for k, v in inp.pins.items()},
            dict(inp.guides),
            sections,
        )

    def pin_of(self, force: float) -> float:
        """The diameter of the pin and bush that carry ``force`` (N), m."""
        return governing_diameter(force, self.grade, self.inputs.safety, self.inputs.width_ratio, self.bush.p)

    def bars(self, f: Any, phi: np.ndarray) -> Bars:
        """The links as bars under the forces ``f`` at the crank angles ``phi`` (deg)."""
        return bars(f, phi, self.grade, safety=self.inputs.safety, sections=self.sections)


def size(
    mech: Mechanism,
    sizing: SizingSpec | Mapping[str, Any] | None = None,
    *,
    motor: bool = True,
    catalogue: str | Path | Catalogue | None = None,
    steps: int = 360,
    progress: Callable[[int, int], None] | None = None,
    compile_spec: Callable[[Any], Mechanism] | None = None,
    **options: Any,
) -> Sizing:
    """Size the machine ``mech`` (``linkwork.size`` also takes a path, an example name or a Spec).

    Parameters
    ----------
    mech : Mechanism
        The compiled machine (one crank).
    sizing : SizingSpec or mapping, optional
        The inputs of the sizing (:class:`~linkwork.spec.schema.SizingSpec`, the schema of the file's ``sizing:``
        section, whose defaults are the defaults here): the bearings' ``life`` (s, or ``"20000 h"``) and kind
        (``bearings``: ball or roller), ``delta`` (default: the file's, else 0.05), the gear's ``efficiency``
        (default: the file's gear's, else 0.95), the ``reserve`` of the motor's breakdown torque, a
        ``synchronous`` speed to keep to, the ``steel`` of the pins and links (``steels.csv``) and its
        ``safety``, the plain ``bush`` (``bushes.csv``) and the pins' ``width_ratio``, the foundation ``bolts``
        (positions, m), their ``bolt_class`` (``bolt_classes.csv``), ``bolt_safety``, ``joint_safety``,
        ``friction`` and ``load_factor``, and ``masses``.  Given over the file's section, field by field.
    motor : bool
        Choose the motor (False: bearings, pins and bolts only).
    catalogue : path or Catalogue
        A motor catalogue (CSV, the columns of the bundled ``motors.csv``, or one read already); default the bundled
        one.
    steps : int
        Crank angles over the turn for the loads.
    progress : callable, optional
        ``progress(k, n)``: told of each motor ``k`` of the ``n`` of the catalogue the choice looks at.
    compile_spec : callable
        How an edited file is compiled, for ``masses="sized"`` (``linkwork.size`` passes :func:`linkwork.compile`).
        ``masses`` is ``"sized"`` by default where the mechanism has its file and ``compile_spec`` is given: the
        bars' masses from their sized steel sections and the blocks' from their pins and guides, iterated with
        the loads to a fixed point (:mod:`linkwork.sizing.masses`); ``"file"`` otherwise.
    **options
        Any field of ``sizing`` as a keyword (over ``sizing``), and ``life_h`` (the life in hours) and ``kind``
        (``bearings``) as before.

    Returns
    -------
    Sizing
        The links' sections, the pins, the bearings (rating, life), the bolts, the motor, gear and flywheel
        chosen, each with the load that governs it, and the inputs and defaults used (``inputs``).

    Examples
    --------
    >>> import linkwork as lw
    >>> sized = lw.size("double-cut-shears", sizing={"life": "30000 h"}, steps=72)  # doctest: +SKIP
    >>> sized.motor  # doctest: +SKIP
    """
    inp = sizing_inputs(mech, sizing, options)
    delta = inp.delta if inp.delta is not None else (mech.delta if mech.delta is not None else DELTA)
    efficiency = inp.efficiency
    if efficiency is None:
        efficiency = mech.motor_gear.efficiency if mech.motor_gear is not None else EFFICIENCY
    cat = motor_catalogue(catalogue) if motor else None  # read, and its speeds checked, before any computing
    if cat is not None and inp.synchronous is not None:
        why = synchronous_problem(cat, inp.synchronous)
        if why is not None:
            raise LinkworkError(why)
    rules = _Rules.of(inp)
    sized = _sized_masses(mech, rules, steps, compile_spec)
    mech = sized.mechanism if sized is not None else mech
    parts = _parts(mech, rules, steps)
    choice = _motor(mech, inp, delta, efficiency, cat, progress) if motor else None  # last: the runs take longest
    if not motor:
        parts.missing["motor"] = "not asked"
    chosen = {
        "delta": delta,
        "gear_efficiency": efficiency,
        "reserve": inp.reserve,
        "catalogue": cat.source
        if cat is not None and catalogue is not None
        else "motors.csv (bundled, typical values)",
        "synchronous_rpm": inp.synchronous * 30 / math.pi if inp.synchronous is not None else None,
    }
    inputs = _inputs_record(inp, chosen if motor else {}, steps, parts.crank, sized)
    p = parts
    return Sizing(
        mech.name or "mechanism",
        inputs,
        choice,
        p.bearings,
        p.pins,
        p.bolts,
        p.missing,
        p.links,
        p.shaft,
        sized,
        p.proportions,
    )


def _motor(
    mech: Mechanism,
    inp: SizingSpec,
    delta: float,
    efficiency: float,
    cat: Catalogue | None,
    progress: Callable[[int, int], None] | None,
) -> MotorChoice:
    """The motor, gear and flywheel chosen from the catalogue ``cat`` for ``mech`` (:func:`choose_motor`)."""
    from linkwork.machine.reduction import reduced

    return choose_motor(
        mech,
        reduced(mech),
        delta,
        efficiency=efficiency,
        reserve=inp.reserve,
        catalogue=cat,
        synchronous=inp.synchronous,
        progress=progress,
    )


def _sized_masses(
    mech: Mechanism, rules: _Rules, steps: int, compile_spec: Callable[[Any], Mechanism] | None
) -> SizedMasses | None:
    """The links' masses sized to a fixed point with the loads (``masses="sized"``), or None (``"file"``)."""
    from linkwork.kinetostatics.reaction_forces import forces
    from linkwork.motion.analysis import CrankAngles

    masses = rules.inputs.masses
    if masses is None:
        masses = "sized" if mech.description is not None and compile_spec is not None else "file"
    angles = CrankAngles.of(mech)
    if angles is None:
        raise LinkworkError("sizing needs one crank driven by the frame: the cycle is its turn")
    if masses == "sized" and compile_spec is None:
        raise LinkworkError('masses="sized" compiles the file with each round\'s masses: call linkwork.size')
    if masses != "sized" or compile_spec is None:
        return None

    def bars_of(m: Mechanism) -> Bars:
        fm = drivable(forces(m, steps=steps))
        return rules.bars(fm, np.asarray(angles.phi(fm.angles), dtype=float))

    def blocks_of(m: Mechanism, bars_: Bars) -> dict[str, float]:
        width = rules.inputs.width_ratio
        return block_masses(pairs_of(forces(m, steps=steps)), bars_, rules.pin_of, width, rules.bush.p)

    return sized_masses(mech, bars_of, compile_spec, blocks_of=blocks_of)


def drivable(f: Forces) -> Forces:
    """``f``, where the machine can be driven through its whole turn; else raise :class:`LinkworkError` naming the
    crank angles where friction locks it (:data:`linkwork.kinetostatics.friction.LOCKING`).

    The design rule: a machine is sized only where its drive moves it at every position of the cycle.  Where friction
    locks it, no motor turns it through the cycle, and next to the lock the pairs' forces grow without bound (to
    :data:`~linkwork.kinetostatics.friction.LOCKING` times those without friction, where the rule calls it locked):
    every bearing, pin, bar and bolt sized for them would be sized for nothing."""
    from linkwork.kinetostatics.friction import LOCKING
    from linkwork.motion.events import runs

    fr = f.friction
    if fr is None or not fr.locked.any():
        return f
    variant = int(np.flatnonzero(fr.locked.any(-1))[0])
    shown = next(p.angles for p in fr.problems if p.kind == "locks" and p.variant == variant)
    spans, k = [], 0
    for i, j in runs(fr.locked[variant]):
        first, last = shown[k], shown[k + j - i]
        spans.append(f"{first:g}" if i == j else f"{first:g} to {last:g}")
        k += j - i + 1
    raise LinkworkError(  # sizing has one crank: the angles are phi, deg
        f"friction locks the machine at phi = {', '.join(spans)} deg (self-locking: the pairs' forces would be "
        f"{LOCKING:g} times those without friction or more, and no drive moves it there): no motor drives it "
        "through the turn, so nothing is sized; lower the friction coefficients, or change the proportions so "
        "that the pressure angles stay below the friction angles"
    )


@dataclass
class _Parts:
    """The parts sized from the loads of one mechanism, and what was not sized and why."""

    crank: float
    pins: Pins
    shaft: Shaft | None
    bearings: Bearings
    links: Bars
    proportions: Proportions
    bolts: BoltResult | None
    missing: dict[str, str]


def _parts(mech: Mechanism, rules: _Rules, steps: int) -> _Parts:
    """Pins, the main shaft, bearings, links, their proportions and the bolts of ``mech`` under its loads."""
    from linkwork.kinetostatics.reaction_forces import forces
    from linkwork.motion.analysis import CrankAngles

    inp = rules.inputs
    angles = CrankAngles.of(mech)
    assert angles is not None  # checked before the masses were sized
    f = drivable(forces(mech, steps=steps))
    phi = np.asarray(angles.phi(f.angles), dtype=float)
    pairs = pairs_of(f)
    pin_sizes = rules.pins
    pinned = pins(pairs, phi, rules.grade, safety=inp.safety, sizes=pin_sizes, width_ratio=inp.width_ratio)
    shaft = _shaft(mech, pairs, pinned, inp)
    split_pairs = pairs  # the joints as they are, and (below) the main shaft's two bearings in its joint's place
    if shaft is not None:
        split_pairs = split(pairs, shaft.joint, shaft.shares)
        journal = {f"{shaft.joint}/{n}": pin_sizes[shaft.joint] for n in (1, 2) if shaft.joint in pin_sizes}
        pin_sizes = {**{k: v for k, v in pin_sizes.items() if k != shaft.joint}, **journal}
    crank = abs(float(mech.drive_speed[0]))
    found = bearings(
        split_pairs,
        phi,
        crank,
        life_h=inp.life / 3600.0,
        kind=inp.bearings,
        bush=rules.bush,
        pins=pin_sizes,
        width_ratio=inp.width_ratio,
        guides=rules.guides,
    )
    linked = rules.bars(f, phi)
    slid = blocks(pairs, linked, rules.pin_of, inp.width_ratio, rules.bush.p)
    depths = {b.link: _depth(b, rules.sections) for b in linked.bars}
    made = made_diameters(pinned, found)
    checked = proportions(mech, f.kinematics, made, linked, depths, {k: b.length for k, b in slid.items()})
    missing: dict[str, str] = {}
    unbounded = [p for p in pairs if math.isinf(p.peak)]
    if unbounded:
        missing[f"joints {', '.join(p.label for p in unbounded)}"] = (
            f"the force grows without bound as the crank nears the singular position at phi "
            f"{unbounded[0].peak_phi:.4g} deg: no pin, bush or bearing holds it"
        )
    held = _bolts(np.asarray(f.foundation, dtype=float), phi, inp)
    if held is None:
        missing["bolts"] = "no bolt pattern: give sizing: bolts: [[x, y], ...] in the file"
    return _Parts(crank, pinned, shaft, found, linked, checked, held, missing)


def _bolts(foundation: np.ndarray, phi: np.ndarray, inp: SizingSpec) -> BoltResult | None:
    """The foundation bolts of ``inp.bolts`` under the foundation's loads ``(A, 3)``; None without bolts."""
    if not inp.bolts:
        return None
    return size_bolts(
        foundation,
        phi,
        np.asarray(inp.bolts, dtype=float),
        bolt_class=inp.bolt_class,
        safety=inp.joint_safety,
        friction=inp.friction,
        load_factor=inp.load_factor,
        bolt_safety=inp.bolt_safety,
    )


def _inputs_record(
    inp: SizingSpec, chosen: dict[str, Any], steps: int, crank: float, sized: SizedMasses | None
) -> dict[str, Any]:
    """The inputs the machine was sized with, defaults included (:attr:`Sizing.inputs`); ``chosen``: the motor's
    (none where it was not chosen)."""
    return {
        "life_h": inp.life / 3600.0,
        "bearing_kind": inp.bearings,
        **chosen,
        "steel": inp.steel,
        "pin_safety": inp.safety,
        "bush": inp.bush,
        "width_ratio": inp.width_ratio,
        "bolt_class": inp.bolt_class,
        "bolt_safety": inp.bolt_safety,
        "joint_safety": inp.joint_safety,
        "friction": inp.friction,
        "load_factor": inp.load_factor,
        "steps": steps,
        "crank_rpm": crank * 30 / math.pi,
        "loads": "kinetostatics at the file's uniform crank speed",
        "masses": sized.said() if sized is not None else "the file's (or its default rule)",
    }


def _depth(bar: Any, given: dict[str, Any]) -> float:
    """The depth (m) of a bar's section in the mechanism's plane: the file's section's (round and tube ``d``,
    rectangle and I ``h``), else the least round bar's."""
    if bar.link in given:
        shape, dims = given[bar.link]
        return float(dims["d"] if shape in ("round", "tube") else dims["h"])
    return math.sqrt(4 * bar.area / math.pi)


def _shaft(mech: Mechanism, pairs: list[Pair], pinned: Pins, inp: SizingSpec) -> Shaft | None:
    """The main shaft of the crank's pivot (the first drive's joint with the frame), or None (no such pair)."""
    joint = mech.pair_joint[int(mech.drive_pair[0])] if len(mech.drive_pair) else None
    pair = next((p for p in pairs if p.label == joint and p.kind == "revolute" and "frame" in p.links), None)
    pin = next((p for p in pinned.pins if p.label == joint), None)
    if pair is None or pin is None:
        return None
    return main_shaft(pair, inp.shaft, pin.diameter, pinned, pin.force)
