"""The kinds of group of the solve program, one record each (:class:`GroupKind`), read by every dispatch.

A kind is how one sort of group is recognised in the structural model and solved: its step
(:mod:`linkwork.motion.program`), its NumPy kernel (:mod:`linkwork.motion.kernels`), its assembly mode read
off the assembly pose, its code and its row of the compiled program's table (:mod:`linkwork.motion.program_table`)
for its numba twin (:mod:`linkwork.motion.kernels_numba`), its construction of the velocity and acceleration
plans (:mod:`linkwork.motion.plan_steps`), and what the analyses need to know of it.  :data:`KINDS` holds them in
the order the groups are tried; the solve (:mod:`linkwork.motion.solve`), the compiled program, the plans, the
events, the change points and the transmission angles all read it, so a new kind is one record here plus its
kernels and its tests (how: the docstring of :mod:`linkwork.motion`).

The numba twins dispatch on the integer codes assigned here (:data:`CRANK` ...) inside machine code
(``kernels_numba._step``): the driving links take the lowest codes, so that ``code < DYAD`` there says "a
driving link".  The kernels are compiled with these values and cached; the cache is keyed to the kernel
modules' sources, so a code changed here must go with a change of ``kernels_numba.py``.
"""

from __future__ import annotations

import dataclasses
import functools
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from linkwork.motion import kernels, newton, plan_steps, program, program_table
from linkwork.motion.state import Inputs, State, single_state
from linkwork.structure.model import AssurGroup, Mechanism
from linkwork.structure.records import Step

#: The codes of the kinds solved by the compiled kernels (column ``KIND`` of the program's table): the driving
#: links first (:data:`CRANK`, :data:`SLIDE`), then the groups; RRR, RRP and PRP share one kernel.
CRANK, SLIDE, DYAD, RPR, RPP = range(5)

#: Makes the step of a group of this kind, or None where the group is not of it: ``(mech, group, driven)``,
#: ``driven`` the drive of each driven pair.
BuildStep = Callable[[Mechanism, AssurGroup, dict[int, int]], Step | None]
#: Places the step's links in the state over every sample (the NumPy kernel): ``(step, state, inputs, branch)``,
#: ``branch`` the assembly mode of every sample ``(V, A)`` where one is given (None: followed from the assembly
#: pose).
SolveStep = Callable[[Step, State, Inputs, np.ndarray | None], None]
#: The assembly mode (+1 or -1) of the step in the single-pose state of the assembly pose: ``(step, state,
#: point_link)``.
ReadMode = Callable[[Step, State, np.ndarray], float]
#: Writes the step's columns into its row ``(WIDTH,)`` of the program's table: ``(step, point_link, row)``.
EncodeStep = Callable[[Step, np.ndarray, np.ndarray], None]
#: Draws the step's vectors of the velocity and acceleration plans: ``(construction, step)``.
DrawPlan = Callable[[plan_steps.PlanConstruction, Step], None]


@dataclass(frozen=True)
class GroupKind:
    """One kind of group of the solve program.

    Attributes
    ----------
    name : str
        :attr:`Step.kind` of its steps (``crank``, ``RRR`` ...).
    build : callable
        Its step from a group of the structural model, or None (:data:`BuildStep`).
    solve : callable
        Its NumPy kernel (:data:`SolveStep`).
    mode : callable or None
        Reads its assembly mode off the assembly pose (:data:`ReadMode`); None: it has one (+1).
    code : int or None
        The code of its compiled twin (:data:`CRANK` ...; ``kernels_numba._step`` dispatches on it); None:
        solved by the NumPy kernels only (a program with such a step has no compiled table).
    encode : callable or None
        Its row of the compiled program's table (:data:`EncodeStep`), with a code.
    twin : str
        The name of its scalar kernel in :mod:`linkwork.motion.kernels_numba` (compiled inline), with a code.
    plan : callable or None
        Its construction of the velocity and acceleration plans (:data:`DrawPlan`); None: its points appear by their
        absolute vectors only.
    driving : bool
        A driving link: always assembled, never singular, its motion the drive's.
    changes_mode : bool
        Its two assembly modes meet at change points, where the motion goes on in the other: its mode is followed
        sample by sample (and can be given so, the ``branch`` of :data:`SolveStep`).
    transmission : bool
        A dyad in closed form whose normalised determinant gives a transmission angle
        (:func:`linkwork.motion.analysis.transmission`).
    iterative : bool
        Solved by iterations from a start pose (Newton's method): refining between samples needs the poses of
        the nearest ones.
    """

    name: str
    build: BuildStep
    solve: SolveStep
    mode: ReadMode | None = None
    code: int | None = None
    encode: EncodeStep | None = None
    twin: str = ""
    plan: DrawPlan | None = None
    driving: bool = False
    changes_mode: bool = False
    transmission: bool = False
    iterative: bool = False


def _drive(step: Step, state: State, at: Inputs) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The drive of a driving step at every sample, and its rates and accelerations, ``(V, A)`` each."""
    ones = np.ones(state.valid.shape)
    d = step.drive
    drive = at.values[:, d] * ones if at.own is None else at.own[0]
    return drive, at.rates[:, d] * ones, at.accels[:, d] * ones


def _crank(step: Step, state: State, at: Inputs, branch: np.ndarray | None = None) -> None:
    kernels.crank(step, state, at.mech.point_link, *_drive(step, state, at))


def _slide(step: Step, state: State, at: Inputs, branch: np.ndarray | None = None) -> None:
    kernels.slide(step, state, at.mech.point_link, *_drive(step, state, at))


def _dyad(step: Step, state: State, at: Inputs, branch: np.ndarray | None = None) -> None:
    kernels.dyad(step, state, at.mech.point_link, branch=branch)


def _rpr(step: Step, state: State, at: Inputs, branch: np.ndarray | None = None) -> None:
    kernels.rpr(step, state, at.mech.point_link)


def _rpp(step: Step, state: State, at: Inputs, branch: np.ndarray | None = None) -> None:
    kernels.rpp(step, state, at.mech.point_link)


def _joint_dyad(name: str) -> GroupKind:
    """RRR, RRP and PRP: closed at their inner joint, one kernel for the three."""
    return GroupKind(
        name,
        build=functools.partial(program.joint_dyad, name),
        solve=_dyad,
        mode=kernels.dyad_mode,
        code=DYAD,
        encode=program_table.dyad_row,
        twin="_dyad",
        plan=plan_steps.joint_dyad,
        changes_mode=True,
        transmission=True,
    )


#: Every kind of group, in the order a group is tried (the first whose ``build`` takes it); ``newton`` last, for
#: any group the others leave.
KINDS: dict[str, GroupKind] = {
    kind.name: kind
    for kind in (
        GroupKind(
            "crank",
            build=program.crank,
            solve=_crank,
            code=CRANK,
            encode=program_table.crank_row,
            twin="_crank",
            plan=plan_steps.crank,
            driving=True,
        ),
        GroupKind(
            "slide",
            build=program.slide,
            solve=_slide,
            code=SLIDE,
            encode=program_table.slide_row,
            twin="_slide",
            driving=True,
        ),
        _joint_dyad("RRR"),
        _joint_dyad("RRP"),
        _joint_dyad("PRP"),
        GroupKind(
            "RPR",
            build=program.rpr,
            solve=_rpr,
            mode=kernels.rpr_mode,
            code=RPR,
            encode=program_table.rpr_row,
            twin="_rpr",
            plan=plan_steps.rpr,
            transmission=True,
        ),
        GroupKind(
            "RPP",
            build=program.rpp,
            solve=_rpp,
            mode=kernels.dyad_mode,
            code=RPP,
            encode=program_table.arms_row,
            twin="_rpp",
        ),
        GroupKind("newton", build=program.newton, solve=newton.solve, iterative=True),
    )
}

#: The kinds solved in closed form by both twins (each with a code).
CLOSED_FORM = tuple(name for name, kind in KINDS.items() if kind.code is not None)
#: The kinds of driving link, those whose mode is followed through change points, and those with a transmission
#: angle.
DRIVING = tuple(name for name, kind in KINDS.items() if kind.driving)
CHANGES_MODE = tuple(name for name, kind in KINDS.items() if kind.changes_mode)
TRANSMISSION = tuple(name for name, kind in KINDS.items() if kind.transmission)


def build(mech: Mechanism) -> list[Step]:
    """The steps of the solve program of a mechanism's structural model, one per Assur group in the order of the
    decomposition, each of the first kind of :data:`KINDS` that takes it; their branches not yet read
    (:func:`with_branches`)."""
    driven = {int(k): d for d, k in enumerate(mech.drive_pair)}
    steps = []
    for g in mech.structure.groups:
        step = next(s for s in (kind.build(mech, g, driven) for kind in KINDS.values()) if s is not None)
        steps.append(step)
    return steps


def with_branches(mech: Mechanism, steps: list[Step]) -> list[Step]:
    """The steps with the branch of each that has two assembly modes read off the assembly pose."""
    state = single_state(mech)
    out = []
    for step in steps:
        mode = KINDS[step.kind].mode
        out.append(step if mode is None else dataclasses.replace(step, branch=mode(step, state, mech.point_link)))
    return out
