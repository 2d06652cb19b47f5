"""One study of a mechanism: its analyses composed once, each computed when it is first read.

The report (:mod:`linkwork.report`), the viewer (:mod:`linkwork.web.cycle`) and the commands read a
:class:`Study` rather than composing kinematics, forces, dynamics, sizing and requirements themselves, so
that every output shows the same result from the same call.  Nothing is computed until it is read, and
nothing twice::

    study = Study(lw.compile(lw.load("shears-slider-crank")))
    study.forces.driving_torque      # solves the cycle, then its forces, once
    study.forces_twelve              # the twelve positions: solved once more, no more

An analysis that fails raises when read (a :class:`~linkwork.errors.LinkworkError` saying why) and is tried
again when read again; what succeeded is kept.
"""

from __future__ import annotations

from functools import cached_property
from typing import TYPE_CHECKING, Any

import numpy as np

from linkwork.errors import LinkworkError
from linkwork.limits import TURN_STEPS

if TYPE_CHECKING:
    from linkwork.impulse.cycle import WorkingCycle
    from linkwork.impulse.mechanism import Impact
    from linkwork.kinetostatics.reaction_forces import Forces
    from linkwork.machine.steady_cycle import Dynamics
    from linkwork.machine.timerun import Run
    from linkwork.motion.kinematic_analysis import Kinematics
    from linkwork.sizing import Sizing
    from linkwork.structure.model import Mechanism

__all__ = ["Study"]


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
    """

    def __init__(self, mech: Mechanism, steps: int = TURN_STEPS, overrides: dict[str, float] | None = None):
        self.mech = mech
        self.steps = steps
        self.overrides = dict(overrides or {})

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

    @cached_property
    def kin(self) -> Kinematics:
        """The cycle: :attr:`steps` equal steps of a turn from position 0."""
        from linkwork.motion.kinematic_analysis import kinematics

        return kinematics(self.mech, self.turn(self.steps), variants=self.variants)

    @cached_property
    def twelve(self) -> Kinematics:
        """The 12 positions, position 0 first."""
        from linkwork.motion.kinematic_analysis import kinematics

        return kinematics(self.mech, self.turn(12), variants=self.variants)

    def phi(self, angles: Any) -> np.ndarray:
        """Crank angles turned from position 0, degrees in [0, 360), of drive angles (rad), as the tables and
        JSON files write them (:func:`linkwork.motion.analysis.phi_deg`)."""
        from linkwork.motion.analysis import phi_deg

        return np.asarray(phi_deg(angles, self.zero, self.sign))

    # ------------------------------------------------------------------ forces

    @cached_property
    def forces(self) -> Forces:
        """Reactions, driving torque and foundation loads over the cycle (:func:`linkwork.forces`)."""
        from linkwork.kinetostatics.reaction_forces import forces_of

        return forces_of(self.kin)

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

        return requirement_rows(self.requirements_kin)

    # ------------------------------------------------------------------ machine

    @cached_property
    def dynamics(self) -> Dynamics:
        """The machine unit run to its steady cycle with the file's drive (:func:`linkwork.dynamics`)."""
        from linkwork.machine import dynamics

        return dynamics(self.mech)

    @cached_property
    def time_run(self) -> Run:
        """The run in time the file's ``simulate:`` asks for (:func:`linkwork.simulate`)."""
        from linkwork.machine.timerun import simulate

        asked = self.mech.spec.simulate if self.mech.spec is not None else None
        if asked is None:
            raise LinkworkError("the file asks for no run in time: give it a 'simulate:' section")
        return simulate(self.mech, asked.until, angle=asked.angle, speed=asked.speed or 0.0, motor=asked.motor)

    @cached_property
    def sizing(self) -> Sizing:
        """Motor, gear, flywheel, bearings, pins and bolts sized from the loads (:func:`linkwork.size`); the motor
        chosen where the file's ``sizing: motor`` asks for it; the links' masses as ``linkwork size`` sizes them by
        default, from the sized parts, to a fixed point."""
        from linkwork.api import compile as compile_spec
        from linkwork.sizing import size

        spec = self.mech.spec.sizing if self.mech.spec is not None else None
        return size(self.mech, motor=bool(spec is not None and spec.motor), compile_spec=compile_spec)

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
