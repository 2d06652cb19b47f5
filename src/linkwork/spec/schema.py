"""The mechanism description: pydantic models of the file format.

Quantities are converted to SI while validating: a string carries its own
unit, a bare number is read by the rule of :func:`linkwork.units.bare_unit`
(see :class:`Units`).  Each quantity's field is marked by a
:class:`Quantity`, which :mod:`linkwork.spec.values` follows to list every
value read.  The JSON Schema of these models is what ``linkwork schema``
prints.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Annotated, Any, Literal

from pydantic import (
    BaseModel,
    BeforeValidator,
    ConfigDict,
    Discriminator,
    Field,
    PrivateAttr,
    Tag,
    ValidationInfo,
    WithJsonSchema,
)
from pydantic_core import PydanticCustomError

from linkwork.errors import UnitParseError
from linkwork.limits import MAX_GEAR_RATIO, MAX_MAGNITUDE, MAX_RUN_TIME, MIN_DELTA, WIDTH_RATIOS, echo
from linkwork.units import DEFAULT_UNITS, KINDS, MADE_OF, parse_quantity


@dataclass(frozen=True)
class Quantity:
    """Marks a field (or item) of the format as a quantity.

    ``kind``: one of :data:`linkwork.units.KINDS`, or ``drive_speed`` /
    ``drive_coordinate`` for a drive's, whose kind follows its joint's type.
    ``shape``: ``one`` value, a ``point`` (two lengths), a ``point_or_name``
    or a ``table`` (one value or a list of them).
    """

    kind: str
    shape: str = "one"


def _declared(info: ValidationInfo) -> dict[str, str]:
    ctx = info.context or {}
    return ctx.get("units", DEFAULT_UNITS)


def _error(message: str) -> PydanticCustomError:
    return PydanticCustomError("linkwork", "{message}", {"message": message})


def _scalar(kind: str, value: Any, info: ValidationInfo, sign: str = "") -> float:
    try:
        x = parse_quantity(value, kind, _declared(info))
    except UnitParseError as exc:
        raise _error(str(exc)) from None
    noun = KINDS[kind][0].split(" ", 1)[1]
    if abs(x) > MAX_MAGNITUDE:
        raise _error(f"expected {KINDS[kind][0]} of a machine's size, got {echo(value)} (out of range)")
    if sign == "positive" and not x > 0:
        raise _error(f"expected a positive {noun}, got {echo(value)}")
    if sign == "nonnegative" and not x >= 0:
        raise _error(f"expected a non-negative {noun}, got {echo(value)}")
    return x


def _number_or_text(value: Any) -> Any:
    if value is None or isinstance(value, str) or (isinstance(value, int | float) and not isinstance(value, bool)):
        return value
    raise _error(f"expected a number or a number with a unit, got {echo(value)}")


def _quantity(kind: str, sign: str = "") -> tuple[BeforeValidator, WithJsonSchema, Quantity]:
    """The metadata of a float field that holds one quantity of ``kind`` (``sign``: ``positive``,
    ``nonnegative`` or any): its validator, its JSON schema and its :class:`Quantity` mark."""
    phrase = KINDS[kind][0]

    def validate(value: Any, info: ValidationInfo) -> float:
        return _scalar(kind, value, info, sign)

    desc = f"{phrase}: {_BARE[kind in MADE_OF]}"
    if sign:
        desc = f"{sign} " + desc
    schema = {"anyOf": [{"type": "number"}, {"type": "string"}], "description": desc}
    return BeforeValidator(validate), WithJsonSchema(schema), Quantity(kind)


_BARE = {
    False: "a string with a unit, or a number in the file's unit of its kind (units:)",
    True: "a string with a unit; a number only in the unit units: declares for its kind, or in SI where "
    "the file's units of what it is made of are SI",
}


#: A pure number (a ratio, a coefficient): finite, and at most :data:`~linkwork.limits.MAX_MAGNITUDE` either way.
Number = Annotated[float, Field(allow_inf_nan=False, ge=-MAX_MAGNITUDE, le=MAX_MAGNITUDE)]
Length = Annotated[float, *_quantity("length")]
PositiveLength = Annotated[float, *_quantity("length", "positive")]
NonnegativeLength = Annotated[float, *_quantity("length", "nonnegative")]
Angle = Annotated[float, *_quantity("angle")]
PositiveMass = Annotated[float, *_quantity("mass", "positive")]
Inertia = Annotated[float, *_quantity("inertia", "nonnegative")]
NonnegativeAcceleration = Annotated[float, *_quantity("acceleration", "nonnegative")]
Force = Annotated[float, *_quantity("force")]
PositiveForce = Annotated[float, *_quantity("force", "positive")]
NonnegativeForce = Annotated[float, *_quantity("force", "nonnegative")]
PositiveMoment = Annotated[float, *_quantity("moment", "positive")]
Moment = Annotated[float, *_quantity("moment")]
PositivePower = Annotated[float, *_quantity("power", "positive")]
PositiveAngularSpeed = Annotated[float, *_quantity("angular_speed", "positive")]
AngularSpeed = Annotated[float, *_quantity("angular_speed")]
Damping = Annotated[float, *_quantity("damping", "nonnegative")]
PositiveTime = Annotated[float, *_quantity("time", "positive")]


def _stiffness() -> tuple[BeforeValidator, WithJsonSchema, Quantity]:
    """The metadata of a spring's ``stiffness``: N/m of a spring, N m/rad of a torsion spring (by the load's
    ``type``, read before it)."""

    def validate(value: Any, info: ValidationInfo) -> float:
        return _scalar(stiffness_kind(info.data.get("type")), value, info, "nonnegative")

    schema = {
        "anyOf": [{"type": "number"}, {"type": "string"}],
        "description": "non-negative stiffness: N/m of a spring, N*m/rad of a torsion spring; " + _BARE[True],
    }
    return BeforeValidator(validate), WithJsonSchema(schema), Quantity("load_stiffness")


def stiffness_kind(load_type: Any) -> str:
    """The kind of quantity of a load's ``stiffness`` by the load's type."""
    return "torsion_stiffness" if load_type == "torsion_spring" else "stiffness"


Stiffness = Annotated[float, *_stiffness()]


def _one_or_table(kind: str) -> tuple[BeforeValidator, WithJsonSchema, Quantity]:
    """The metadata of a field that holds a quantity of ``kind``, or a list of them (the values of a table)."""
    phrase = KINDS[kind][0]

    def validate(value: Any, info: ValidationInfo) -> float | list[float]:
        if not isinstance(value, list):
            return _scalar(kind, value, info)
        out = []
        for i, v in enumerate(value):
            try:
                out.append(_scalar(kind, v, info))
            except PydanticCustomError as exc:
                raise _error(f"item {i}: {exc.message()}") from None
        return out

    schema = {
        "anyOf": [{"type": "number"}, {"type": "string"}, {"type": "array"}],
        "description": f"{phrase}, or a list of them (a table): {_BARE[kind in MADE_OF]}",
    }
    return BeforeValidator(validate), WithJsonSchema(schema), Quantity(kind, "table")


#: The words a drive's ``direction`` may be written in (any case), and the one each means.
DIRECTIONS = {
    "ccw": "ccw",
    "counterclockwise": "ccw",
    "counter-clockwise": "ccw",
    "anticlockwise": "ccw",
    "anti-clockwise": "ccw",
    "cw": "cw",
    "clockwise": "cw",
    "forward": "forward",
    "backward": "backward",
}


def direction_word(value: Any) -> Any:
    """``ccw``, ``cw``, ``forward`` or ``backward`` for a word of :data:`DIRECTIONS`; anything else as it is."""
    return DIRECTIONS.get(value.strip().lower(), value) if isinstance(value, str) else value


ForceOrTable = Annotated[float | list[float], *_one_or_table("force")]
MomentOrTable = Annotated[float | list[float], *_one_or_table("moment")]


def _vector(value: Any, info: ValidationInfo) -> tuple[float, float]:
    if not isinstance(value, list | tuple) or len(value) != 2:
        got = f"{len(value)} values" if isinstance(value, list | tuple) else echo(value)
        raise _error(f"expected a point [x, y] of two lengths, got {got}")
    return (_scalar("length", value[0], info), _scalar("length", value[1], info))


_VEC_SCHEMA = {
    "type": "array",
    "items": {"anyOf": [{"type": "number"}, {"type": "string"}]},
    "minItems": 2,
    "maxItems": 2,
    "description": "a point [x, y]: two lengths",
}
Vec2 = Annotated[
    tuple[float, float], BeforeValidator(_vector), WithJsonSchema(_VEC_SCHEMA), Quantity("length", "point")
]


def _point_or_vector(value: Any, info: ValidationInfo) -> str | tuple[float, float]:
    if isinstance(value, str):
        return value
    return _vector(value, info)


PointOrVec = Annotated[
    str | tuple[float, float],
    BeforeValidator(_point_or_vector),
    WithJsonSchema({"anyOf": [{"type": "string", "description": "a point name"}, _VEC_SCHEMA]}),
    Quantity("length", "point_or_name"),
]


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)


class Units(_Strict):
    """Units in which bare numbers of the file are read.

    A bare length, mass, time or angle is read in the unit declared here for
    its kind (by default m, kg, s and deg).  A bare number of any other kind
    (force, moment, inertia, speed, angular_speed, acceleration, power,
    stiffness, torsion_stiffness, damping) is read in the unit declared here for
    that kind; where none is declared, in SI (N, N*m, kg*m^2, m/s, rad/s,
    m/s^2, W, N/m, N*m/rad, N*s/m) only where the units of what it
    is made of are SI (m, kg, s, rad, and N where forces are declared);
    otherwise it needs its unit, e.g. "30 rpm" or "2 kg*m^2".
    """

    length: str = Field(default=DEFAULT_UNITS["length"], description="e.g. m or mm")
    mass: str = Field(default=DEFAULT_UNITS["mass"], description="e.g. kg")
    time: str = Field(default=DEFAULT_UNITS["time"], description="e.g. s or min")
    angle: str = Field(default=DEFAULT_UNITS["angle"], description="deg or rad")
    force: str | None = Field(default=None, description="e.g. N or kN")
    moment: str | None = Field(default=None, description="of moments and torques, e.g. N*m or kN*m")
    inertia: str | None = Field(default=None, description="of moments of inertia, e.g. kg*m^2 or kg*mm^2")
    speed: str | None = Field(default=None, description="of linear speeds, e.g. m/s or mm/s")
    angular_speed: str | None = Field(default=None, description="e.g. rpm or rad/s")
    acceleration: str | None = Field(default=None, description="e.g. m/s^2")
    power: str | None = Field(default=None, description="e.g. W or kW")
    stiffness: str | None = Field(default=None, description="of springs, e.g. N/m or N/mm")
    torsion_stiffness: str | None = Field(default=None, description="of torsion springs, e.g. N*m/rad")
    damping: str | None = Field(default=None, description="of dampers, e.g. N*s/m")


class Frame(_Strict):
    """The fixed link (link 0): its points in global coordinates."""

    points: dict[str, Vec2] = Field(default_factory=dict, description="frame points, global [x, y]")
    mass: PositiveMass | None = Field(default=None, description="mass of the housing or bed")
    com: PointOrVec | None = Field(default=None, description="centre of mass of the frame, global")


class Link(_Strict):
    """A moving link, described by its own dimensions in its local frame.

    A binary link may be given by ``ends: [P, Q]`` and ``length``: P is at the
    local origin and Q at (length, 0).  Any further points (joint points of
    ternary and quaternary links, markers such as a blade edge) go in
    ``points`` with local coordinates.
    """

    ends: list[str] | None = Field(None, description="two point names: the link runs from the first to the second")
    length: PositiveLength | None = Field(None, description="distance between the two ends")
    points: dict[str, Vec2] = Field(default_factory=dict, description="points in the link's own coordinates")
    mass: PositiveMass | None = None
    com: PointOrVec | None = Field(
        None,
        description="centre of mass: a point name or local [x, y]; default for a link given by ends and length: "
        "the middle of its ends (markers are not material), otherwise the centroid of the points",
    )
    inertia: Inertia | None = Field(
        None,
        description="moment of inertia about the centre of mass (or about inertia_about); "
        "default for a link given by ends and length: uniform rod m L^2/12, otherwise 0",
    )
    inertia_about: str | None = Field(None, description="a point name: inertia is given about this point")
    description: str | None = None


class FrictionLaw(_Strict):
    """Friction in a joint's pairs in proportion to the force each carries (Coulomb's law).

    A revolute pair's friction moment is ``f radius |R|`` (``R`` the pair's force; ``f radius`` the radius
    of the friction circle), against the relative turning; a prismatic pair's friction force is ``f |N|``
    (``N`` the guide's normal force; ``atan f`` the friction angle), against the relative sliding.  A
    pin-in-slot joint: ``f |N|`` in the slot, and ``f radius |R|`` on the pin where ``radius`` is given.
    """

    f: Annotated[float, Field(allow_inf_nan=False, ge=0, le=MAX_MAGNITUDE)] = Field(
        description="friction coefficient: tangential force over normal force, from 0 up"
    )
    radius: NonnegativeLength | None = Field(
        None,
        description="revolute: the radius of the pin (or journal) the pair turns on; f radius is the "
        "radius of the friction circle",
    )


class Joint(_Strict):
    """A kinematic pair.

    ``revolute``: the links share the point ``point`` (default: the joint's
    name); three or more links make a compound hinge.  ``prismatic``: the
    second link (the slider) translates along a line of the first (the guide)
    through ``through`` with direction ``axis`` in the guide's coordinates;
    ``point`` is the slider's point on that line, and the slider's axes stay
    parallel to the guide's.  ``pin-in-slot``: a higher pair; the point of
    the second link moves in a straight slot of the first.
    """

    type: Literal["revolute", "prismatic", "pin-in-slot"]
    links: list[str] = Field(description="names of the joined links ('frame' for the fixed link)")
    point: str | None = Field(None, description="the point of the pair; default: the joint's name")
    through: PointOrVec | None = Field(None, description="prismatic/pin-in-slot: a point of the guide line")
    axis: Angle | None = Field(None, description="prismatic/pin-in-slot: direction of the guide line")
    friction: FrictionLaw | None = Field(
        None,
        description="friction in proportion to the pair's force: {f, radius} for a revolute joint, {f} for a "
        "prismatic one",
    )


class Law(_Strict):
    """A drive motion law given as a table of the drive coordinate against time."""

    time: list[Annotated[float, BeforeValidator(lambda v, i: _scalar("time", v, i)), Quantity("time")]]
    value: list[Annotated[Any, Quantity("drive_coordinate")]] = Field(
        description="drive coordinate: angles for a revolute drive, lengths for a prismatic one"
    )


class Drive(_Strict):
    """An input motion on a joint.

    For a revolute joint the drive coordinate is the angle of the second
    link's local x axis (for a link given by ends: the line from its first to
    its second end) measured from the first link's x axis; for a prismatic
    joint, the position of the slider's point along the guide axis from the
    ``through`` point.
    """

    joint: str
    speed: Annotated[
        Any,
        BeforeValidator(_number_or_text),
        WithJsonSchema({"anyOf": [{"type": "number"}, {"type": "string"}]}),
        Quantity("drive_speed"),
    ] = Field(
        None,
        description="uniform speed: an angular speed (revolute) or a speed (prismatic), with its unit, "
        'e.g. "30 rpm" (a bare number as for any speed: see units)',
    )
    direction: Annotated[
        Literal["ccw", "cw", "forward", "backward"] | None,
        BeforeValidator(direction_word),
        WithJsonSchema({"anyOf": [{"enum": list(DIRECTIONS)}, {"type": "null"}]}),
    ] = Field(
        None,
        description="revolute drives: ccw (counterclockwise, counter-clockwise, anticlockwise) or cw (clockwise); "
        "prismatic ones: forward or backward",
    )
    angle: Angle | None = Field(None, description="revolute: drive angle of the assembly pose (default 0)")
    position: Length | None = Field(None, description="prismatic: drive position of the assembly pose (default 0)")
    law: Law | None = None


class Load(_Strict):
    """An external load: a force at a point, a moment on a link, or a technological (process) load.

    ``force``: acts at the point ``at`` (``link.point``) with global components
    ``force: [Fx, Fy]``, or with ``magnitude`` along the global ``direction``.
    ``moment``: acts on the link ``on``, counter-clockwise positive.  Either may
    follow the crank angle: ``angle: [...]`` (drive angles of the first drive,
    increasing, spanning at most a turn) with ``magnitude`` or ``moment`` a list
    of the same length; linear in between, zero outside the table.

    ``process``: the resistance of a workpiece to the tools, such as a cutting
    force.  ``tools`` are one or two points (``link.point``): the first comes
    from the positive side of ``axis`` (a global direction), the second from
    the negative side; ``workpiece`` is its extent ``[low, high]`` along the
    axis.  The relative penetration ``eps`` is the sum of the tools'
    penetrations divided by the workpiece's height; ``force`` against
    ``penetration`` (linear in between, zero outside) is the force that pushes
    the first tool back along ``axis`` and the second the other way.  It acts
    only while the tools move into the workpiece and are in it: none while
    ``eps`` is zero or less, whatever the table gives at 0.  With one tool
    the workpiece rests on the frame, which takes the opposite force at the
    tool's point.

    ``friction``: a constant (Coulomb) friction in the pairs of a ``joint``: a
    ``moment`` against the relative turning of a revolute pair, or a force
    ``magnitude`` against the sliding of a prismatic one.

    Force elements: ``spring``, a linear spring ``between`` two points (``link.point``, a frame point
    by its name) of ``stiffness`` (N/m) and ``free_length``, or with ``preload`` (its tension in the
    assembly pose) instead; its force acts along the line of the points, tension positive.
    ``damper``: between two points, a force ``damping`` times the rate of change of their distance.
    ``torsion_spring``: in the revolute ``joint``, a moment ``stiffness`` (N m/rad) times the turn of the
    joint's second link relative to its first, from ``free_angle`` (the second link's angle less the
    first's, each link's angle that of its local x axis).
    """

    type: Literal["force", "moment", "process", "friction", "spring", "damper", "torsion_spring"]
    joint: str | None = Field(None, description="friction, torsion_spring: the joint whose pairs it acts in")
    at: str | None = Field(None, description="force: the point link.point where it acts")
    on: str | None = Field(None, description="moment: the link it acts on")
    force: list[Force] | None = Field(
        None, description="force: [Fx, Fy], global; process: forces of the table against penetration"
    )
    magnitude: ForceOrTable | None = Field(None, description="force: magnitude along direction, or a table")
    direction: Angle | None = Field(None, description="force: direction of the magnitude, global")
    moment: MomentOrTable | None = Field(None, description="moment: its value, or a table")
    angle: list[Angle] | None = Field(None, description="crank angles of a table (first drive)")
    tools: list[str] | None = Field(None, description="process: one or two points link.point")
    axis: Angle | None = Field(None, description="process: global direction along which the first tool is pushed")
    workpiece: list[Length] | None = Field(None, description="process: [low, high] extent along the axis")
    penetration: list[float] | None = Field(None, description="process: relative penetrations of the table")
    between: list[str] | None = Field(None, description="spring, damper: two points link.point (frame: its name)")
    stiffness: Stiffness | None = Field(None, description="spring: N/m; torsion_spring: N m/rad")
    free_length: Length | None = Field(None, description="spring: its length without force")
    preload: Force | None = Field(None, description="spring: its tension in the assembly pose, for free_length")
    damping: Damping | None = Field(None, description="damper: force per unit rate of change of the distance")
    free_angle: Angle | None = Field(None, description="torsion_spring: the joint's relative turn without moment")
    description: str | None = None


class Motor(_Strict):
    """The motor's mechanical characteristic.

    ``constant``: ``torque`` at any speed.  ``linear``: ``stall`` torque at rest falling to zero at
    the ``no_load`` speed.  ``induction``: rated ``power`` at the rated ``speed``, the
    ``synchronous`` speed and the ``breakdown`` torque ratio (Kloss formula).
    """

    type: Literal["constant", "linear", "induction"]
    torque: Moment | None = Field(None, description="constant: the torque")
    stall: PositiveMoment | None = Field(None, description="linear: torque at rest")
    no_load: PositiveAngularSpeed | None = Field(None, description="linear: speed at zero torque")
    power: PositivePower | None = Field(None, description="induction: rated power")
    speed: PositiveAngularSpeed | None = Field(None, description="induction: rated speed")
    synchronous: PositiveAngularSpeed | None = Field(None, description="induction: synchronous speed")
    breakdown: Number | None = Field(None, description="induction: breakdown torque / rated torque, e.g. 2.2")
    inertia: Inertia | None = Field(None, description="moment of inertia of the rotor")


class TimeRun(_Strict):
    """A run in time for the report (``linkwork simulate``): ``until`` its length, from the crank angle
    ``angle`` (to the x axis; default the assembly angle) at the speed ``speed`` (counter-clockwise positive;
    default at rest); ``motor: false`` leaves the file's motor out."""

    until: PositiveTime = Field(le=MAX_RUN_TIME, description=f"length of the run, at most {MAX_RUN_TIME:g} s")
    angle: Angle | None = Field(None, description="the crank's angle to the x axis at the start")
    speed: AngularSpeed | None = Field(None, description="the crank's speed at the start, counter-clockwise +")
    motor: bool = Field(True, description="with the machine's motor (false: free motion)")


class Gear(_Strict):
    """A gear between motor and crank: ``ratio`` = motor speed / crank speed."""

    ratio: float = Field(
        gt=0, le=MAX_GEAR_RATIO, allow_inf_nan=False, description=f"motor / crank speed, at most {MAX_GEAR_RATIO:g}"
    )
    efficiency: float = Field(1.0, gt=0, le=1, description="of the gear")


class FlywheelSpec(_Strict):
    """A flywheel on the motor shaft or on the crank shaft."""

    inertia: Inertia
    on: Literal["motor", "crank"] = "crank"


class Machine(_Strict):
    """The drive of the machine unit, for machine dynamics."""

    motor: Motor
    gear: Gear | None = None
    flywheel: FlywheelSpec | None = None
    delta: float | None = Field(
        None, ge=MIN_DELTA, lt=1, description="coefficient of speed fluctuation to size a flywheel for"
    )


class ToolSpec(_Strict):
    """The tool the striker hits, for the working cycle: it slides along the face's normal, the
    feed presses it back onto its seat (the face's position in the pose of the blow), the work
    resists its motion into it."""

    mass: PositiveMass = Field(description="the tool's mass")
    feed: PositiveForce = Field(description="constant force pressing the tool towards the striker, onto its seat")
    resistance: NonnegativeForce = Field(0.0, description="force of the work against the tool's motion into it")


class ImpactSpec(_Strict):
    """A blow of a point of the mechanism on a surface at rest, in the assembly pose."""

    at: str = Field(description="the striking point, link.point")
    normal: Angle = Field(description="direction of the surface's normal, out of it (towards the striker)")
    omega: AngularSpeed = Field(
        description="angular speed of the striking link (or of `link`) before the blow, counter-clockwise positive"
    )
    link: str | None = Field(None, description="the link whose angular speed `omega` is")
    restitution: float = Field(ge=0, le=1, description="R = -omega_after / omega_before")
    friction: Number = Field(0.0, ge=0, description="f: tangential impulse / normal impulse")
    rod_joint: str | None = Field(
        None, description="for the reduced model of seed 004: the joint at which the rod's mass is taken"
    )
    tool: ToolSpec | None = Field(None, description="the tool, for the working cycle (linkwork impact --cycle)")


class TitleBlockSpec(_Strict):
    """The fields of the drawing sheets' title block (основная надпись, ГОСТ 2.104 form 1), each as written."""

    title: str = Field(default="", description="graph 1, the product's name (default: the mechanism's name)")
    designation: str = Field(default="", description="graph 2, the document's designation, e.g. ТММ.КП.01.00.00")
    organisation: str = Field(default="", description="graph 9, the organisation (the school and the group)")
    developer: str = Field(default="", description="who drew the sheets (Разраб.)")
    checker: str = Field(default="", description="who checked them (Пров.)")
    norm_control: str = Field(default="", description="who checked the norms (Н.контр.)")
    approved: str = Field(default="", description="who approved them (Утв.)")
    date: str = Field(default="", description="the date beside the developer's name")
    litera: str = Field(default="", description="the document's letter (У: a student's work)")


class Drawing(_Strict):
    """What the drawings show: the positions whose velocity and acceleration plans are drawn, and the sheets.

    Positions are those of the graphical method, 0 to 11: position 0 where the working slider is at the
    high end of its stroke (the knives open), then every 30 degrees in the direction of rotation.
    Without ``positions``, the plans are drawn where the working point moves fastest and every dyad
    transmits well (never at a dead point).  ``sheet`` and ``title_block``: the format (ГОСТ 2.301) and the
    title block of the drawing sheets ``analyze --dxf`` writes.
    """

    positions: list[Annotated[int, Field(ge=0, le=11)]] = Field(
        default_factory=list, description="positions (0 to 11) whose velocity and acceleration plans are drawn"
    )
    sheet: Literal["A1", "A2", "A3", "A4"] = Field(default="A1", description="the format of the drawing sheets")
    title_block: TitleBlockSpec = Field(
        default=TitleBlockSpec(), description="the fields of the sheets' title block (ГОСТ 2.104)"
    )


class PinSize(_Strict):
    """The pin of a revolute joint: its diameter and the width of the eye (the bush's length)."""

    diameter: PositiveLength
    width: PositiveLength


class SectionSpec(_Strict):
    """A link's cross-section, for sizing it as a bar: ``round`` (d), ``rectangle`` (b across, h in the plane of
    the mechanism), ``tube`` (d outside, t wall), ``I`` (h depth in the plane, b flange width, tw web, tf flange)."""

    shape: Literal["round", "rectangle", "tube", "I"]
    d: PositiveLength | None = None
    b: PositiveLength | None = None
    h: PositiveLength | None = None
    t: PositiveLength | None = None
    tw: PositiveLength | None = None
    tf: PositiveLength | None = None


class ShaftSpec(_Strict):
    """The crank's main shaft on two bearings: their ``spacing`` (between their middles) and the crank's
    ``overhang`` outside the nearer one (its plane's distance from it); without ``overhang``, the crank midway
    between the two."""

    spacing: PositiveLength = Field(description="between the middles of the shaft's two bearings")
    overhang: NonnegativeLength | None = Field(
        None, description="the crank's plane outside the nearer bearing, from it (none: the crank midway)"
    )


#: A positive factor (a safety, a coefficient of friction) and a share of a whole, in (0, 1].
Factor = Annotated[float, Field(gt=0, allow_inf_nan=False)]
Share = Annotated[float, Field(gt=0, le=1)]


class SizingSpec(_Strict):
    """What ``linkwork size`` needs beyond the loads: the pins the joints have, the guides' lengths, the bolts,
    and the inputs of the sizing (the bearings' life, the materials, the safety factors) with their defaults:
    their one home (``linkwork.size(mech, sizing=...)`` and ``linkwork size`` give theirs over the file's)."""

    life: Annotated[float, *_quantity("time", "positive")] = Field(
        default=72_000_000.0, description="basic rating life L10h the rolling bearings are sized for (default 20000 h)"
    )
    pins: dict[str, PinSize] = Field(default_factory=dict, description="pins of revolute joints, by joint name")
    guides: dict[str, PositiveLength] = Field(default_factory=dict, description="guides' lengths, by prismatic joint")
    bolts: list[Vec2] = Field(default_factory=list, description="foundation bolts: their positions [x, y] on the bed")
    sections: dict[str, SectionSpec] = Field(default_factory=dict, description="cross-sections of links, by link name")
    shaft: ShaftSpec | None = Field(default=None, description="the crank's main shaft (default: the crank midway)")
    motor: bool = Field(default=False, description="the report chooses the motor too (runs the machine)")
    bearings: Literal["ball", "roller"] = Field(default="ball", description="rolling bearings: ball or roller")
    delta: float | None = Field(default=None, ge=MIN_DELTA, lt=1, description="speed fluctuation (default: machine's)")
    efficiency: Share | None = Field(default=None, description="of the gear (default: the gear's, else 0.95)")
    reserve: Share = Field(default=0.8, description="share of the breakdown torque the peak motor torque may reach")
    synchronous: Annotated[float, *_quantity("angular_speed", "positive")] | None = Field(
        default=None, description='keep to motors of this synchronous speed, e.g. "1500 rpm"'
    )
    steel: str = Field(default="C45 normalised", description="steel grade of the pins and links (steels.csv)")
    safety: Factor = Field(default=2.0, description="safety factor of the pins and links on the yield strength")
    bush: str = Field(default="tin bronze CuSn12 greased", description="plain bush (bushes.csv)")
    width_ratio: float = Field(default=1.0, ge=WIDTH_RATIOS[0], le=WIDTH_RATIOS[1], description="pins' width / d")
    bolt_class: str = Field(default="5.6", description="property class of the foundation bolts (bolt_classes.csv)")
    bolt_safety: Factor = Field(default=1.5, description="safety of the bolts on their yield strength")
    joint_safety: Factor = Field(default=1.5, description="safety of the bolted joint against opening and sliding")
    friction: Factor = Field(default=0.2, description="friction coefficient of the bolted joint")
    load_factor: float = Field(default=0.25, ge=0, lt=1, description="share of the working load the bolts take")
    masses: Literal["sized", "file"] | None = Field(
        default=None, description='the links\' masses: "sized" from their sections (the default), or the "file"\'s'
    )


#: The forms of ``gravity:``, as pydantic tags them (the place of a problem leaves them out).
UNION_TAGS = ("<gravity with its direction>", "<gravity along -y>")


def _gravity_form(value: Any) -> str:
    """Which form of ``gravity:`` a value is: with its direction (a mapping) or a size along -y."""
    return UNION_TAGS[0] if isinstance(value, dict | Gravity) else UNION_TAGS[1]


class Gravity(_Strict):
    """Gravity of any size and direction: ``value`` (zero: none) along the global ``direction``
    (counter-clockwise from +x; 270 deg is -y)."""

    value: NonnegativeAcceleration = Field(description="acceleration of gravity; 0 for none")
    direction: Angle = Field(-1.5707963267948966, description="direction it acts in, global; default 270 deg (-y)")


class Spec(_Strict):
    """A planar mechanism: the root of a linkwork mechanism file."""

    name: str | None = None
    description: str | None = None
    units: Units = Field(default_factory=Units)
    gravity: Annotated[
        Annotated[Gravity, Tag(UNION_TAGS[0])] | Annotated[NonnegativeAcceleration, Tag(UNION_TAGS[1])],
        Discriminator(_gravity_form),
    ] = Field(
        9.81,
        description="acceleration of gravity along -y (0: none), or {value, direction} for any direction",
    )
    frame: Frame = Field(default_factory=Frame)
    links: dict[str, Link]
    joints: dict[str, Joint]
    drives: list[Drive]
    loads: dict[str, Load] = Field(default_factory=dict, description="external loads by name")
    machine: Machine | None = Field(None, description="motor, gear and flywheel, for machine dynamics")
    impact: ImpactSpec | None = Field(None, description="a blow, for linkwork impact")
    simulate: TimeRun | None = Field(None, description="a run in time, drawn in the report")
    drawing: Drawing | None = Field(None, description="what the drawings show (the positions of the plans)")
    sizing: SizingSpec | None = Field(None, description="pins, guides and foundation bolts, for linkwork size")
    requirements: dict[str, str | float] | None = Field(
        None,
        description="what the mechanism was synthesised for (linkwork synthesize): its kind and requirements, "
        "quantities with their units, each measured one with its <name>_tolerance (what its lengths written to "
        "0.1 mm allow); the report states them beside what the analysis measures",
    )
    hints: dict[str, Vec2] = Field(
        default_factory=dict,
        description="approximate global positions of moving points in the assembly pose "
        "(joint names or link.point); they choose the assembly mode",
    )
    _source: Any = PrivateAttr(default=None)

    def __eq__(self, other: object) -> bool:
        """Equal descriptions: the same values, wherever they were read from (a file's lines, or a builder)."""
        if not isinstance(other, Spec):
            return NotImplemented
        return type(self) is type(other) and self.__dict__ == other.__dict__

    def model_copy(self, *, update: Mapping[str, Any] | None = None, deep: bool = False) -> Spec:
        """A copy; with ``update``, one no longer read from a file: it keeps no :attr:`source` (whose data and lines
        are of the description as read)."""
        copied = super().model_copy(update=update, deep=deep)
        if update:
            copied._source = None
        return copied

    @property
    def source(self) -> Any:
        """The :class:`~linkwork.spec.yamlsource.Source` it was read from (lines for messages), or None."""
        return self._source
