"""One study of a mechanism: its analyses composed once, each computed when it is first read.

The report (:mod:`linkwork.report`), the viewer (:mod:`linkwork.web.cycle`) and the commands read a
:class:`Study` rather than composing kinematics, forces, dynamics, sizing and requirements themselves, so
that every output shows the same result from the same call.  Nothing is computed until it is read, and
nothing twice::

    study = Study(lw.compile(lw.load("shears-slider-crank")))
    study.forces.driving_torque      # solves the cycle, then its forces, once
    study.forces_twelve              # the twelve positions: solved once more, no more

The commands ask a study for what their options say (the cycle's drive angles, or its steps and the angle they turn
from, and its speed; :class:`DynamicsOptions`, :class:`SizingOptions`) and print what it reads, so that
``linkwork kinematics``, ``forces``, ``balance``, ``dynamics`` and ``size`` give the numbers of
:func:`linkwork.kinematics`, :func:`linkwork.forces`, :func:`linkwork.balance`, :func:`linkwork.dynamics` and
:func:`linkwork.size` called with the same options, and the report the same where it asks the same.

An analysis that fails raises when read (a :class:`~linkwork.errors.LinkworkError` saying why) and is tried
again when read again; what succeeded is kept.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from linkwork.errors import LinkworkError
from linkwork.limits import DYNAMICS_STEPS, TURN_STEPS

if TYPE_CHECKING:
    from linkwork.impulse.cycle import WorkingCycle
    from linkwork.impulse.mechanism import Impact
    from linkwork.kinetostatics.balancing import Balance
    from linkwork.kinetostatics.reaction_forces import Forces
    from linkwork.machine.steady_cycle import Dynamics
    from linkwork.machine.timerun import Run
    from linkwork.motion.kinematic_analysis import Kinematics
    from linkwork.sizing import Sizing
    from linkwork.sizing.common import Catalogue
    from linkwork.spec.schema import SizingSpec, Spec
    from linkwork.structure.model import Mechanism

__all__ = ["DynamicsOptions", "SizingOptions", "Study"]


@dataclass(frozen=True)
class DynamicsOptions:
    """How a study runs the machine unit to its steady cycle (:func:`linkwork.dynamics`).

    Attributes
    ----------
    delta : float, optional
        The coefficient of speed fluctuation a flywheel is sized for, (max - min) / mean; default the file's
        (none: no flywheel sized).
    steps : int
        Equal steps of one turn of the reduced model (:data:`~linkwork.limits.DYNAMICS_STEPS`, 3600).
    """

    delta: float | None = None
    steps: int = DYNAMICS_STEPS


@dataclass(frozen=True)
class SizingOptions:
    """How a study sizes the machine (:func:`linkwork.size`).

    Attributes
    ----------
    inputs : SizingSpec or mapping
        Fields of the file's ``sizing:`` section given over it (:class:`~linkwork.spec.schema.SizingSpec`, the one
        home of their defaults; bare numbers in SI); empty: the file's section as it is.
    motor : bool, optional
        Choose the motor from the catalogue (False: bearings, pins, links and bolts only); default as the file's
        ``sizing: motor`` says.
    catalogue : Catalogue, optional
        The motor catalogue, read already (:func:`linkwork.sizing.motor.motor_catalogue`); default the bundled one.
    progress : callable, optional
        ``progress(k, n)``: told of each motor ``k`` of the ``n`` of the catalogue the choice looks at.
    """

    inputs: SizingSpec | Mapping[str, Any] = field(default_factory=dict)
    motor: bool | None = None
    catalogue: Catalogue | None = None
    progress: Callable[[int, int], None] | None = None


class Study:
    """The analyses of ``mech`` (or of a variant of it), each computed once, when first read.

    Parameters
    ----------
    mech : Mechanism
        From :func:`linkwork.compile`.
    steps : int
        Equal steps of the crank's turn of the cycle (:attr:`kin`), from position 0 in the drive's direction.
    overrides : dict, optional
        A variant: named values (SI, checked by the caller) that differ from the file's; its kinematics are
        solved as one variant of ``mech`` (:func:`linkwork.kinematics` with ``variants``).
    start : float, optional
        The drive angle (rad, to the frame's x axis) from which the cycle's ``steps`` turn; default position 0
        (:attr:`zero`).  The commands' ``--steps`` turn from the assembly pose, as :func:`linkwork.kinematics`'s
        ``steps`` do (``start=mech.drive_start[0]``).
    angles : array_like, optional
        The drive coordinates of the cycle instead of ``steps``, as :func:`linkwork.kinematics` takes them (rad
        to the frame's x axis, or m of a linear drive), shape ``(A,)`` or ``(A, drives)``: a command's
        ``--angles``.
    speed : float, optional
        The drive's uniform speed (rad/s, or m/s) of the cycle and the twelve positions, in the file's
        direction; default the file's.
    dynamics : DynamicsOptions, optional
        How :attr:`dynamics` runs the machine unit; default the file's flywheel rule at 3600 steps.
    sizing : SizingOptions, optional
        How :attr:`sizing` sizes the machine; default the file's ``sizing:`` section.
    """

    def __init__(
        self,
        mech: Mechanism,
        steps: int = TURN_STEPS,
        overrides: dict[str, float] | None = None,
        *,
        start: float | None = None,
        angles: npt.ArrayLike | None = None,
        speed: float | None = None,
        dynamics: DynamicsOptions | None = None,
        sizing: SizingOptions | None = None,
    ):
        self.mech = mech
        self.steps = steps
        self.overrides = dict(overrides or {})
        self.start = start
        self.angles = None if angles is None else np.asarray(angles, dtype=float)
        self.speed = speed
        self.dynamics_options = dynamics or DynamicsOptions()
        self.sizing_options = sizing or SizingOptions()

    @property
    def variants(self) -> dict[str, list[float]] | None:
        """The overrides as :func:`linkwork.kinematics` takes them (one variant), or None."""
        return {name: [value] for name, value in self.overrides.items()} or None

    # ------------------------------------------------------------------ kinematics

    @cached_property
    def zero(self) -> float:
        """Drive angle of position 0, rad (:func:`linkwork.motion.analysis.zero_angle`)."""
        from linkwork.motion.analysis import zero_angle

        return zero_angle(self.mech)

    @cached_property
    def sign(self) -> float:
        """+1 where the crank turns counter-clockwise, -1 clockwise."""
        from linkwork.motion.kinematic_analysis import direction

        return direction(self.mech)

    def turn(self, count: int) -> np.ndarray:
        """Drive angles (rad) of ``count`` equal steps of a turn from position 0, in the drive's direction."""
        from linkwork.motion.analysis import position_angles

        return position_angles(self.mech, count, self.zero)

    def cycle_angles(self) -> np.ndarray:
        """The drive coordinates of the cycle: :attr:`angles` where given, else :attr:`steps` equal steps of a
        turn from :attr:`start` (default position 0) in the drive's direction."""
        from linkwork.motion.analysis import position_angles

        if self.angles is not None:
            return self.angles
        return position_angles(self.mech, self.steps, self.zero if self.start is None else self.start)

    @cached_property
    def kin(self) -> Kinematics:
        """The cycle (:meth:`cycle_angles`: :attr:`steps` equal steps of a turn from position 0 unless asked
        otherwise), at :attr:`speed`."""
        from linkwork.motion.kinematic_analysis import kinematics

        return kinematics(self.mech, self.cycle_angles(), variants=self.variants, speed=self.speed)

    @cached_property
    def twelve(self) -> Kinematics:
        """The 12 positions, position 0 first, at :attr:`speed`."""
        from linkwork.motion.kinematic_analysis import kinematics

        return kinematics(self.mech, self.turn(12), variants=self.variants, speed=self.speed)

    def phi(self, angles: Any) -> np.ndarray:
        """Crank angles turned from position 0, degrees in [0, 360), of drive angles (rad), as the tables and
        JSON files write them (:func:`linkwork.motion.analysis.phi_deg`)."""
        from linkwork.motion.analysis import phi_deg

        return np.asarray(phi_deg(angles, self.zero, self.sign))

    # ------------------------------------------------------------------ forces

    @cached_property
    def forces(self) -> Forces:
        """Reactions, driving torque and foundation loads over the cycle (:func:`linkwork.forces`: of the file's
        mechanism, a spring or damper whose points meet at an assembled sample is refused, as there)."""
        from linkwork.kinetostatics.reaction_forces import elements_defined, forces_of

        found = forces_of(self.kin)
        if not self.overrides:
            elements_defined(found)
        return found

    def bolt_speed(self, pull: float) -> float:
        """The uniform crank speed (rad/s) at which the largest pull on the bolts reaches ``pull`` (N); ``inf``
        where no speed does, 0 where the bolts carry it at rest (:func:`linkwork.bolt_speed`, over a turn of
        :data:`~linkwork.limits.TURN_STEPS` steps)."""
        from linkwork.kinetostatics.bolt_lift import bolt_speed

        return bolt_speed(self.mech, pull=pull)

    @cached_property
    def forces_twelve(self) -> Forces:
        """The forces at the 12 positions."""
        from linkwork.kinetostatics.reaction_forces import forces_of

        return forces_of(self.twelve)

    @cached_property
    def forces_or_reason(self) -> tuple[Forces | None, str]:
        """The forces of the cycle, or None and why there are none: the reactions are statically indeterminate
        (redundant constraints), the file gives no masses and no loads, or the analysis refused."""
        mech = self.mech
        if mech.structure.redundant:
            return None, "the mechanism has redundant constraints: its reactions are statically indeterminate"
        if not (np.asarray(self.kin.mass_properties.mass)[0, 1:] > 0).any() and not mech.loads:
            return None, "the file gives no masses and no loads"
        try:
            return self.forces, ""
        except LinkworkError as exc:
            return None, str(exc)

    def balance(
        self,
        links: list[str] | tuple[str, ...],
        *,
        harmonic: int | None = None,
        radius: dict[str, float] | float | None = None,
    ) -> Balance:
        """Counterweights on ``links`` against the shaking force of :attr:`forces` (``harmonic=None``) or its first
        harmonic (``harmonic=1``), with ``radius`` (m) from their pivots (default each link's farthest point), and
        the forces after, solved at the cycle's angles (:func:`linkwork.balance`; the cycle must be equal steps of
        a whole turn).  The arguments are checked before the forces are solved."""
        from linkwork.kinetostatics.balancing import balance_of, counterweight_links

        counterweight_links(self.mech, links, harmonic, self.steps if self.angles is None else len(self.angles))
        return balance_of(self.forces, links, harmonic=harmonic, radius=radius)

    # ------------------------------------------------------------------ requirements

    @cached_property
    def requirements_kin(self) -> Kinematics:
        """The cycle at 360 steps from the assembly pose, on which a synthesised file's requirements are
        measured (:func:`linkwork.synthesis.achieved.requirement_rows`)."""
        from linkwork.motion.kinematic_analysis import kinematics

        return kinematics(self.mech, steps=360)

    @cached_property
    def requirements(self) -> tuple[str, list[Any]] | None:
        """The kind and the rows (asked, achieved, met) of the file's requirements, or None where it has none."""
        from linkwork.synthesis.achieved import requirement_rows

        return requirement_rows(self.requirements_kin, self.file)

    @cached_property
    def file(self) -> Spec | None:
        """The description the mechanism was compiled from, read back from the document it keeps
        (:func:`linkwork.spec.reader.described`); None for a mechanism without one."""
        from linkwork.spec.reader import described

        return described(self.mech.description)

    # ------------------------------------------------------------------ machine

    @cached_property
    def dynamics(self) -> Dynamics:
        """The machine unit run to its steady cycle with the file's drive (:func:`linkwork.dynamics`), as
        :attr:`dynamics_options` ask."""
        from linkwork.machine import dynamics

        asked = self.dynamics_options
        return dynamics(self.mech, delta=asked.delta, steps=asked.steps)

    @cached_property
    def time_run(self) -> Run:
        """The run in time the file's ``simulate:`` asks for (:func:`linkwork.simulate`)."""
        from linkwork.machine.timerun import simulate

        asked = self.file.simulate if self.file is not None else None
        if asked is None:
            raise LinkworkError("the file asks for no run in time: give it a 'simulate:' section")
        return simulate(self.mech, asked.until, angle=asked.angle, speed=asked.speed or 0.0, motor=asked.motor)

    @cached_property
    def sizing(self) -> Sizing:
        """Motor, gear, flywheel, bearings, pins and bolts sized from the loads (:func:`linkwork.size`), as
        :attr:`sizing_options` ask: by default the motor chosen where the file's ``sizing: motor`` asks for it,
        and the links' masses as ``linkwork size`` sizes them by default, from the sized parts, to a fixed point."""
        from linkwork.api import compile as compile_spec
        from linkwork.sizing import size

        asked = self.sizing_options
        motor = asked.motor
        if motor is None:
            file = self.file
            motor = bool(file is not None and file.sizing is not None and file.sizing.motor)
        return size(
            self.mech,
            sizing=asked.inputs,
            motor=motor,
            catalogue=asked.catalogue,
            progress=asked.progress,
            compile_spec=compile_spec,
        )

    # ------------------------------------------------------------------ impact

    @cached_property
    def impact(self) -> Impact:
        """The impulses of the file's blow in its pose (:func:`linkwork.impact`)."""
        from linkwork.impulse import impact

        return impact(self.mech)

    @cached_property
    def blows(self) -> WorkingCycle:
        """The working cycle of blows with the file's drive and tool (:func:`linkwork.simulate_blows`)."""
        from linkwork.impulse import simulate_blows

        return simulate_blows(self.mech)
