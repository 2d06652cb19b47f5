"""The records that the stages above the structure compile into the model (:class:`Mechanism`).

:func:`linkwork.compile` (:mod:`linkwork.api`) is the one compile: the structural model
(:func:`linkwork.structure.compile.structural_model`), then the solve program (:class:`Step`, by
:func:`linkwork.motion.groups.build`), the external loads (:class:`ExternalLoad`, by
:func:`linkwork.stage_records.compile_loads`), the friction in the pairs (:class:`PairFriction`, by
:func:`linkwork.stage_records.compile_friction`) and the machine unit's motor and gear
(:class:`MotorGear`, by :func:`linkwork.stage_records.from_spec`).  They are small frozen records of numbers
and indices into the model's arrays, defined here so that the model names no package above its own; the
stages that compile them are those that read them.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from linkwork.errors import LinkworkError

if TYPE_CHECKING:
    from linkwork.structure.model import AssurGroup

# --- the solve program (linkwork.motion) ------------------------------------------------------------------


@dataclass(frozen=True)
class Arm:
    """How one link of a dyad carries the point X where the dyad closes.

    ``kind`` "R": the link turns about the point ``src`` of a placed link,
    which is its own point ``own``; "P": the link keeps the angle of the
    placed link ``carrier`` and X slides along a line of the pair ``pair``.
    """

    kind: str
    link: int
    pair: int
    own: int = -1  # R: own point at the outer joint
    src: int = -1  # R: the placed link's point there
    carrier: int = -1  # P: the placed link whose angle the link keeps
    own_is_slider: bool = True  # P: the link is the slider of the pair (else the guide)
    slider_point: int = -1  # P: the slider's point of the pair


@dataclass(frozen=True)
class Step:
    """One group of the solve program."""

    kind: str
    group: AssurGroup
    links: tuple[int, ...]
    arms: tuple[Arm, ...] = ()
    x_local: tuple[int, ...] = ()  # point index of X on each arm's link (-1: the link's origin)
    drive: int = -1
    pair: int = -1
    inner: int = -1
    branch: float = 1.0
    #: crank: +1 where the driven link is the second of its pair (its angle is the base's plus the
    #: drive's), -1 where it is the first (the base's minus the drive's)
    sign: float = 1.0

    @property
    def label(self) -> str:
        return self.group.label


# --- the external loads and the friction in the pairs (linkwork.kinetostatics) ----------------------------


@dataclass(frozen=True)
class ExternalLoad:
    """One external load, compiled.

    Attributes
    ----------
    name : str
    kind : str
        ``force``, ``moment``, ``process`` or ``friction`` (in the pair ``pair``: a moment for a
        revolute pair, a force for a prismatic one, of size ``value``); or a force element
        (:mod:`linkwork.kinetostatics.elements`): ``spring`` and ``damper`` between ``points``, of stiffness
        or damping ``value``, ``torsion_spring`` in the pair ``pair``; ``free`` the free length or angle.
    link : int
        The link a force or moment acts on (for a process load: the first tool's link).
    points : tuple of int
        Point indices: the point of a force, the tools of a process load.
    vector : tuple of float
        Force: its components (N) when ``value`` is 1, else the unit direction of the magnitude;
        process: the unit axis.
    value : float
        Constant magnitude (N, N m); NaN where a table gives it.
    table : tuple of ndarray or None
        ``(x, y)``: drive angles (rad) or relative penetrations, and magnitudes (N or N m).
    workpiece : tuple of float
        Process: extent along the axis (m).
    """

    name: str
    kind: str
    link: int
    points: tuple[int, ...] = ()
    vector: tuple[float, float] = (0.0, 0.0)
    value: float = math.nan
    table: tuple[np.ndarray, np.ndarray] | None = None
    workpiece: tuple[float, float] = (0.0, 0.0)
    pair: int = -1  # friction, torsion spring: the elementary pair it acts in
    free: float = math.nan  # spring: free length (m); torsion spring: free angle (rad)


@dataclass(frozen=True)
class PairFriction:
    """The friction law of one elementary pair.

    Attributes
    ----------
    joint : str
        The joint of the pair (a compound hinge's pairs each have their own).
    pair : int
        The elementary pair.
    coefficient : float
        ``f r`` (m, the radius of the friction circle) in a revolute pair, ``f`` in a prismatic one.
    f : float
        The friction coefficient.
    """

    joint: str
    pair: int
    coefficient: float
    f: float


# --- the machine unit (linkwork.machine) --------------------------------------------------------------------


def speeds(omega: Any) -> Any:
    """``omega`` as it is where it is a Python float (the simulation asks for one speed at every step: a
    float's arithmetic is ten times quicker than a NumPy scalar's, and gives the same numbers), else as a
    NumPy array of floats."""
    return omega if type(omega) is float else np.asarray(omega, dtype=float)


@dataclass(frozen=True)
class MotorGear:
    """The motor, gear and flywheel of a machine unit (``Mechanism.motor_gear``), compiled by
    :func:`linkwork.stage_records.from_spec`.

    Attributes
    ----------
    motor : callable
        Torque (N m) on the motor shaft against its speed (rad/s): a characteristic of
        :mod:`linkwork.machine.drive` (``ConstantTorque``, ``LinearMotor``, ``InductionMotor``).
    ratio : float
        ``u = omega_motor / omega_crank``.
    efficiency : float
        Of the gear, applied to the motor torque.
    rotor : float
        Inertia of the rotor and everything else on the motor shaft, kg m^2.
    flywheel : float
        Inertia of a flywheel, kg m^2, on the shaft named by ``flywheel_on``.
    flywheel_on : str
        ``"motor"`` or ``"crank"``.
    """

    motor: Callable[[Any], Any]
    ratio: float = 1.0
    efficiency: float = 1.0
    rotor: float = 0.0
    flywheel: float = 0.0
    flywheel_on: str = "crank"

    def __post_init__(self) -> None:
        if not self.ratio > 0:
            raise LinkworkError(f"gear ratio: expected a positive number, got {self.ratio}")
        if not 0 < self.efficiency <= 1:
            raise LinkworkError(f"gear efficiency: expected a number in (0, 1], got {self.efficiency}")
        if self.flywheel_on not in ("motor", "crank"):
            raise LinkworkError(f'flywheel: on "motor" or "crank", got "{self.flywheel_on}"')
        if self.rotor < 0 or self.flywheel < 0:
            raise LinkworkError("inertias of rotor and flywheel must not be negative")

    @property
    def inertia(self) -> float:
        """Constant inertia the rotor and the flywheel add on the crank shaft, kg m^2."""
        on_motor = self.rotor + (self.flywheel if self.flywheel_on == "motor" else 0.0)
        return on_motor * self.ratio**2 + (self.flywheel if self.flywheel_on == "crank" else 0.0)

    def moment(self, omega: Any) -> Any:
        """Moment (N m) of the motor, through the gear, on the crank at crank speed ``omega``."""
        return self.ratio * self.efficiency * self.motor(self.ratio * speeds(omega))

    def with_flywheel(self, inertia: float) -> MotorGear:
        """The same motor and gear with another flywheel (on the same shaft)."""
        return dataclasses.replace(self, flywheel=inertia)


@dataclass(frozen=True)
class ToolRecord:
    """The tool the striker hits, for the working cycle (the file's ``impact: tool:``, SI): its ``mass`` (kg),
    the ``feed`` pressing it onto its seat (N) and the work's ``resistance`` to its motion into it (N)."""

    mass: float
    feed: float
    resistance: float = 0.0


@dataclass(frozen=True)
class ImpactRecord:
    """A blow of the point ``at`` (``link.point``) on a surface at rest, in the assembly pose (the file's
    ``impact:`` section, SI; compiled by :func:`linkwork.structure.compile.structural_model`).

    Attributes
    ----------
    at : str
        The striking point.
    normal : float
        Direction of the surface's normal, out of it (towards the striker), rad.
    omega : float
        Angular speed of the striking link (or of ``link``) before the blow, rad/s, counter-clockwise positive.
    link : str or None
        The link whose angular speed ``omega`` is.
    restitution : float
        ``R = -omega_after / omega_before``.
    friction : float
        Tangential impulse over normal impulse.
    rod_joint : str or None
        For the reduced model of seed 004: the joint at which the rod's mass is taken.
    tool : ToolRecord or None
        The tool, for the working cycle.
    """

    at: str
    normal: float
    omega: float
    link: str | None = None
    restitution: float = 0.0
    friction: float = 0.0
    rod_joint: str | None = None
    tool: ToolRecord | None = None
