"""``linkwork.forces``: reactions, driving torque and foundation loads of a kinematics result."""

from __future__ import annotations

import math
import time
import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property, partial
from typing import Any, NamedTuple

import numpy as np
import numpy.typing as npt

from linkwork import jit
from linkwork.did_you_mean import suggest
from linkwork.errors import LinkworkError
from linkwork.kinetostatics import reactions_numba
from linkwork.kinetostatics.bolts import Bolts, bolt_loads
from linkwork.kinetostatics.efficiency import Efficiency, efficiency
from linkwork.kinetostatics.external import Applied, evaluate
from linkwork.kinetostatics.free_body import FreeBody, free_bodies
from linkwork.kinetostatics.friction import FrictionSolution, has_friction, solve_friction
from linkwork.kinetostatics.geometry import guide_direction
from linkwork.kinetostatics.peaks import peaks
from linkwork.kinetostatics.reactions import (
    Loads,
    balance,
    foundation,
    inertia_and_gravity,
    jacobian,
    momentum_check,
    power_check,
    solve_reactions,
)
from linkwork.motion.analysis import guide_lines
from linkwork.motion.kinematic_analysis import Kinematics, kinematics
from linkwork.structure.model import Mechanism, PairType, per_mechanism


@dataclass(frozen=True)
class Forces:
    """Reactions, driving torque and foundation loads over the angles of a kinematics result.

    Shapes as in :class:`~linkwork.motion.Kinematics`: ``(n_variants, n_angles, ...)``
    with the variant axis dropped for a single mechanism.  SI units.
    :func:`linkwork.forces` makes it; read it through its accessors.

    Parameters
    ----------
    kinematics : Kinematics
        The motion the forces were solved for.
    multipliers : ndarray, shape (V, A, m)
        The reaction of every constraint row (see :meth:`reaction`), N or N m.
    foundation_all : ndarray, shape (V, A, 3)
        Force ``(x, y)``, N, and moment about the origin, N m, on the foundation at every sample (NaN at a
        singular position; :attr:`foundation` fills those).
    friction : FrictionSolution or None, default None
        The friction in proportion to the pairs' forces (:mod:`linkwork.kinetostatics.friction`), where the
        file gives one.

    Attributes
    ----------
    loads : Loads
        Applied and inertia loads of every link (computed when first asked for, as are the checks).
    external : Applied
        The file's external loads (:func:`~linkwork.kinetostatics.external.evaluate`), those the reactions
        were solved with (the friction in proportion to the pairs' forces included).
    """

    kinematics: Kinematics
    multipliers: np.ndarray
    foundation_all: np.ndarray  # (V, A, 3)
    friction: FrictionSolution | None = None

    @cached_property
    def loads(self) -> Loads:
        """Applied (gravity, external) and inertia loads of every link."""
        return inertia_and_gravity(self.kinematics, self.external)

    @cached_property
    def external(self) -> Applied:
        """The file's external loads, every elementary force and moment (kept where they were evaluated to
        solve the reactions)."""
        return evaluate(self.kinematics)

    @cached_property
    def foundation_momentum_all(self) -> np.ndarray:
        """The foundation loads from the theorem on the change of momentum, (V, A, 3)."""
        return momentum_check(self.kinematics, self.loads)

    @cached_property
    def torque_power_all(self) -> np.ndarray:
        """The driving torque from the power balance, (V, A, D)."""
        return power_check(self.kinematics, self.loads)

    def _repr_html_(self) -> str:
        """A notebook's view: the samples, the largest driving torque and foundation force of the samples (not
        refined: see ``linkwork.kinetostatics.peaks``), the singular samples."""
        from linkwork.display import number, table

        torque = np.abs(self.driving_torque_all[..., 0])
        found = self.foundation_filled_all
        return table(
            f"Forces of {self.mechanism.name}",
            [
                ("variants x angles", " x ".join(str(n) for n in torque.shape)),
                ("largest driving torque of the samples", number(float(np.nanmax(torque)), "N m")),
                (
                    "largest foundation force of the samples",
                    number(float(np.nanmax(np.hypot(found[..., 0], found[..., 1]))), "N"),
                ),
                ("singular samples (reactions NaN)", int(np.count_nonzero(self.singular_all))),
            ],
        )

    def to_xarray(self) -> Any:
        """The reactions and loads as an xarray Dataset (the ``data`` extra), the numbers of ``forces.csv``.

        ``force`` over ``variant`` x ``angle`` x ``joint`` x ``component`` (x, y): the force the joint's
        first-named link (coordinate ``first``) exerts on the second (``second``), as :meth:`reaction` gives it;
        ``moment`` of a prismatic pair on its slider (NaN for the others); ``driving_torque``,
        ``foundation_force`` (``component``), ``foundation_moment``, ``shaking_force``, ``shaking_moment`` and
        ``singular`` over ``variant`` x ``angle``.  The coordinate ``angle`` is φ from position 0 in degrees
        with one crank; each variable's unit in its ``units`` attribute.

        Raises
        ------
        MissingDependencyError
            Without xarray, naming the extra that brings it.
        """
        from linkwork.kinetostatics.tables import to_dataset

        return to_dataset(self)

    def to_pandas(self, by: str = "joint") -> Any:
        """:meth:`to_xarray` as a pandas DataFrame: ``by="joint"``, indexed by ``variant`` x ``angle`` x
        ``joint``, the force's ``x`` and ``y`` and the ``moment``; ``by="angle"``, indexed by ``variant`` x
        ``angle``, the driving torque and the foundation's and shaking loads.  Units in ``attrs["units"]``.

        Raises
        ------
        MissingDependencyError
            Without pandas, naming the extra that brings it.
        """
        from linkwork.kinetostatics.tables import to_frame

        return to_frame(self, by)

    def _out(self, a: np.ndarray) -> np.ndarray:
        return a if self.kinematics.variants else a[0]

    @property
    def mechanism(self) -> Mechanism:
        return self.kinematics.mechanism

    @property
    def angles(self) -> np.ndarray:
        return self.kinematics.angles

    @cached_property
    def singular_all(self) -> np.ndarray:
        """True where the mechanism assembles but its reactions are indeterminate (a dead or change
        point: some group's system is singular there), ``(V, A)``."""
        return self.kinematics.valid_all & ~np.all(np.isfinite(self.multipliers), axis=-1)

    @property
    def singular(self) -> np.ndarray:
        """:attr:`singular_all` without the variant axis for one mechanism: ``(..., n_angles)``."""
        return self._out(self.singular_all)

    @cached_property
    def driving_torque_all(self) -> np.ndarray:
        """Torque (N m; N for a linear drive) each drive puts on its driven link, of every variant,
        ``(V, A, D)``: the reactions' multipliers of the drives, and at a singular position of one drive the power
        balance's (:attr:`driving_torque` without the variant axis)."""
        m = self.mechanism
        lam = self.multipliers[..., 2 * m.n_pairs :]
        fill = self.singular_all[..., None] & ~np.isfinite(lam)
        if m.n_drives != 1 or not fill.any():
            return lam
        return np.where(fill, self.torque_power_all, lam)

    @property
    def driving_torque(self) -> np.ndarray:
        """Torque (N m) the drive puts on its driven link, counter-clockwise positive (N for a linear drive):
        ``(..., n_angles)`` for one drive, ``(..., n_angles, n_drives)`` for several.

        At a singular position (:attr:`singular`: a dead or change point, where the reactions are
        indeterminate) the torque of one drive is still defined: there it is the power balance's."""
        lam = self.driving_torque_all
        return self._out(lam[..., 0] if self.mechanism.n_drives == 1 else lam)

    def pairs(self, joint: str) -> list[int]:
        m = self.mechanism
        ks = [k for k, j in enumerate(m.pair_joint) if j == joint]
        if not ks:
            raise KeyError(f'no joint "{joint}"{suggest(joint, sorted(set(m.pair_joint)))}')
        return ks

    def pair_force(self, k: int) -> np.ndarray:
        """Force (N) that link ``pair_links[k, 0]`` exerts on link ``pair_links[k, 1]`` in pair ``k``:
        ``(V, A, 2)``, in the model's order (times ``mechanism.pair_sign[k]``: in the file's, as
        :meth:`reaction` gives it).  For a prismatic pair (guide first) it is normal to the guide and
        acts at the slider's point of the pair."""
        m = self.mechanism
        lam = self.multipliers[..., 2 * k : 2 * k + 2]
        if m.pair_type[k] == PairType.REVOLUTE:
            return -lam
        u = guide_direction(self.kinematics, k)
        normal = lam[..., 1]  # along n = u turned by +90 deg, on the slider
        return np.stack([-u[..., 1] * normal, u[..., 0] * normal], -1)

    def reaction(self, joint: str, on: str | None = None) -> np.ndarray:
        """Force (N) in a joint, ``(..., n_angles, 2)``, in the order the file's ``links`` name its links.

        Without ``on``: the force the first-named link exerts on the second, whichever link the drive
        of the joint turns.  A pin in a slot: the slot's force on the pin.  A compound hinge of
        k >= 3 links is k - 1 pairs, each between the member nearest the frame (which carries the pin)
        and one of the others; this is its first pair, that of the first-named link: the force the
        first-named link exerts on the pin's carrier, or on the second-named link where the first
        carries the pin.

        With ``on=link``: the force the joint puts on that link, the sum of the forces of all its
        other members on it (for two links, the other's force on it); it does not depend on which
        member carries the pin.  A prismatic pair's moment is :meth:`pair_moment`.

        Raises
        ------
        KeyError
            No such joint, or ``on`` is not one of its links.
        """
        ks = self.pairs(joint)
        m = self.mechanism
        if on is None:
            return self._out(m.pair_sign[ks[0]] * self.pair_force(ks[0]))
        members = {int(i) for k in ks for i in m.pair_links[k] if not m.link_virtual[int(i)]}
        names = [m.link_names[i] for i in sorted(members)]
        if on not in names:
            raise KeyError(f'joint "{joint}" joins {", ".join(names)}, not "{on}"{suggest(on, names)}')
        link = m.link_names.index(on)
        total = np.zeros(self.multipliers.shape[:-1] + (2,))
        for k in ks:
            a, b = (int(x) for x in m.pair_links[k])
            if link in (a, b):
                total = total + (self.pair_force(k) if link == b else -self.pair_force(k))
        return self._out(total)

    def reactions(self, joints: Sequence[str], on: Sequence[str]) -> np.ndarray:
        """The forces that the ``joints`` put on the links ``on`` (one each), ``(..., n_angles, R, 2)``: each
        ``reaction(joint, on=link)``, the same numbers, gathered from the forces of all the pairs at once.

        Raises
        ------
        KeyError
            As :meth:`reaction`.
        """
        try:
            plan = _gather(self.mechanism, tuple(joints), tuple(on))
        except KeyError:
            for joint, link in zip(joints, on, strict=True):
                self.reaction(joint, on=link)  # raises the KeyError that says what is wrong
            raise
        forces = self._pair_forces(plan.pairs, plan.guides)  # (U, 2, V, A): each component along the angles
        # each pair's force, its negative, and zero: the terms of the sums
        signed = np.concatenate([forces, -forces, np.zeros((1,) + forces.shape[1:])])
        total = np.zeros((len(joints),) + forces.shape[1:])
        for column in plan.columns:  # the first term of each, then the second, ..., as reaction adds them
            total = total + signed[column]  # + 0.0 after the last term: changes no sum
        return self._out(total.transpose(2, 3, 0, 1))  # a view (V, A, R, 2)

    def _pair_forces(self, pairs: np.ndarray, guides: np.ndarray) -> np.ndarray:
        """:meth:`pair_force` of each of ``pairs``, ``(len(pairs), 2, V, A)``, by the same arithmetic for all at
        once; ``guides``: the places of the prismatic ones in ``pairs``."""
        m, kin = self.mechanism, self.kinematics
        lam = self.multipliers[..., : 2 * m.n_pairs].reshape(self.multipliers.shape[:-1] + (m.n_pairs, 2))
        lam = np.take(lam.transpose(2, 3, 0, 1), pairs, axis=0)
        out = -lam
        if len(guides):
            u = guide_lines(kin, pairs[guides])[1]  # (P, 2, V, A)
            normal = lam[guides, 1]
            out[guides, 0] = -u[:, 1] * normal
            out[guides, 1] = u[:, 0] * normal
        return out

    def pair_moment(self, joint: str) -> np.ndarray:
        """Moment (N m) the guide exerts on the slider in a prismatic joint, about the slider's point."""
        k = self.pairs(joint)[0]
        if self.mechanism.pair_type[k] != PairType.PRISMATIC:
            raise LinkworkError(f'joint "{joint}" is revolute: it carries no moment')
        return self._out(self.multipliers[..., 2 * k])

    @cached_property
    def foundation_filled_all(self) -> np.ndarray:
        """:attr:`foundation_all` of every variant, ``(V, A, 3)`` (N, N, N m), with the theorem on the change of
        momentum's value at a singular position, where the reactions are NaN (:attr:`foundation`)."""
        fill = self.singular_all[..., None] & ~np.isfinite(self.foundation_all)
        if not fill.any():
            return self.foundation_all
        return np.where(fill, self.foundation_momentum_all, self.foundation_all)

    @property
    def foundation(self) -> np.ndarray:
        """Force (x, y) in N and moment about the origin in N m that the machine (frame included)
        puts on its foundation: ``(..., n_angles, 3)``.  y up: a positive y force pulls the bolts.

        At a singular position (:attr:`singular`) it is still defined: there it is the theorem on
        the change of momentum's."""
        return self._out(self.foundation_filled_all)

    @property
    def shaking_force(self) -> np.ndarray:
        """Resultant of the inertia forces of the links, N: ``(..., n_angles, 2)``; what the
        foundation feels beyond the weights and the external loads."""
        return self._out(self.shaking_force_all)

    @property
    def shaking_force_all(self) -> np.ndarray:
        """:attr:`shaking_force` of every variant, ``(V, A, 2)``."""
        return np.sum(self.loads.inertia[..., :2], axis=-2)

    @property
    def shaking_moment(self) -> np.ndarray:
        """Resultant moment of the inertia loads about the origin, N m: ``(..., n_angles)``."""
        return self._out(self.shaking_moment_all)

    @property
    def shaking_moment_all(self) -> np.ndarray:
        """:attr:`shaking_moment` of every variant, ``(V, A)``."""
        q, f = self.kinematics.pose, self.loads.inertia
        about = f[..., 2] + q[..., 0] * f[..., 1] - q[..., 1] * f[..., 0]
        return np.sum(about, axis=-1)

    @property
    def checks(self) -> dict[str, float]:
        """Largest discrepancy of the independent checks, relative to the largest value checked
        (NaN where a check has nothing to compare: the power balance at rest).  The foundation's moment is
        measured against the larger of its own largest value and its force's largest times the mechanism's reach
        (the farthest link origin from the frame's origin): a moment that is zero but for rounding (every force
        through the origin) is then not noise divided by noise."""

        def rel(a: np.ndarray, b: np.ndarray, floor: float = 0.0) -> float:
            if not np.isfinite(a - b).any():
                return math.nan  # nothing to compare: at rest, or every position singular
            scale = max(float(np.nanmax(np.abs(b))) if np.isfinite(b).any() else 0.0, floor)
            return float(np.nanmax(np.abs(a - b)) / scale) if scale > 0 else float(np.nanmax(np.abs(a - b)))

        m = self.mechanism
        lam = self.multipliers[..., 2 * m.n_pairs :]
        found, momentum = self.foundation_all, self.foundation_momentum_all
        with np.errstate(invalid="ignore"):
            reach = np.hypot(self.kinematics.pose[..., 0], self.kinematics.pose[..., 1])
            force = np.hypot(found[..., 0], found[..., 1])
        arm = float(np.nanmax(reach)) if np.isfinite(reach).any() else 0.0
        moment_scale = arm * (float(np.nanmax(force)) if np.isfinite(force).any() else 0.0)
        return {
            "driving_torque_vs_power_balance": rel(lam, self.torque_power_all),
            "foundation_force_vs_momentum": rel(found[..., :2], momentum[..., :2]),
            "foundation_moment_vs_momentum": rel(found[..., 2], momentum[..., 2], moment_scale),
        }

    @cached_property
    def efficiency(self) -> Efficiency:
        """The power balance split into the drive's, the useful loads', the friction's in each pair and the
        rates of kinetic and potential energy; the instantaneous and the cycle's efficiency
        (:mod:`linkwork.kinetostatics.efficiency`; the variant axis kept)."""
        return efficiency(self)

    def free_bodies(self) -> list[FreeBody]:
        """Every Assur group cut free: the forces of the other links on it, its loads, and the
        sum of them all (the residual, zero for a correct solution); see
        :mod:`linkwork.kinetostatics.free_body`."""
        return free_bodies(self)

    def bolts(self) -> Bolts:
        """Pull, push and shear of the foundation bolts, the moment, and where their maxima occur (from
        :attr:`foundation`, defined at singular positions too), of the first variant: refined between the
        samples by the rule of every peak (:func:`~linkwork.kinetostatics.peaks.refine`), so that they do not
        depend on the grid.  Found once per result."""
        found = self.__dict__.get("_bolts")
        if found is None:
            loads = peaks(self, _bolt_quantities, "max", which=np.arange(4), variants=np.zeros(4, dtype=np.intp))
            found = bolt_loads(loads, float(self.angles[0]))
            object.__setattr__(self, "_bolts", found)  # frozen: kept as the result's cached values are
        return found

    def at(self, angles: np.ndarray, variants: np.ndarray | None = None) -> Forces | None:
        """The forces of the same mechanism solved again at other drive coordinates, for refining a quantity between
        the samples: at the angles ``(R, K)`` of :meth:`Kinematics.at <linkwork.motion.Kinematics.at>` (row ``r`` for
        variant ``variants[r]``; for one mechanism, every row for it), as variants ``(R, K)``; None where that gives
        none."""
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            kin = self.kinematics.at(angles, variants)
            return None if kin is None else forces_of(kin)


def _bolt_quantities(f: Forces) -> np.ndarray:
    """What the bolts carry at each sample, ``(4, V, A)``: the shear ``|Fx|``, the upward force ``Fy`` (a pull where
    positive), the downward ``-Fy`` (a push where positive) and the size of the moment about the origin."""
    found = f.foundation_filled_all
    return np.stack([np.abs(found[..., 0]), found[..., 1], -found[..., 1], np.abs(found[..., 2])])


@jit.deciding
def forces(
    mech: Mechanism | Kinematics,
    angles: npt.ArrayLike | None = None,
    *,
    steps: int | None = None,
    speed: npt.ArrayLike | None = None,
    variants: dict[str, npt.ArrayLike] | None = None,
) -> Forces:
    """Reactions in every pair, the driving torque and the foundation loads (kinetostatics: the
    inertia forces of the links by d'Alembert's principle, the file's loads, friction where declared).

    Parameters
    ----------
    mech : Mechanism or Kinematics
        A compiled mechanism (``linkwork.forces`` also takes a path, an example name or a Spec), or a
        :class:`~linkwork.motion.Kinematics` result: then without the other arguments, its angles, speeds
        and variants are the result's (the same as :func:`forces_of`).
    angles : array_like, optional
        Crank angles, rad from the assembly pose, shape ``(n,)`` (``(n, drives)`` for several drives).
        Default: ``steps`` equal steps of one turn.
    steps : int, optional
        Equal steps of one turn when ``angles`` is not given; default 360 (:data:`linkwork.limits.TURN_STEPS`).
    speed : array_like, optional
        The drive's uniform angular speed, rad/s (one value, or one per variant); default the file's.
    variants : dict of str to array_like, optional
        Named parameters (:func:`linkwork.parameters`) each with one value per variant, SI units, shape
        ``(v,)``: the forces of ``v`` design variants at once.

    Returns
    -------
    Forces
        Reactions per joint, driving torque (N m) and foundation loads (N, N m) at each angle (and variant).

    Raises
    ------
    LinkworkError
        For a mechanism with redundant constraints: its reactions are statically indeterminate.
    UnassemblableError
        An angle at which the mechanism does not assemble.

    Examples
    --------
    >>> import linkwork as lw
    >>> f = lw.forces("four-bar", steps=12)
    >>> f.driving_torque.shape  # N m, one per crank angle
    (12,)
    """
    if isinstance(mech, Kinematics):
        if angles is not None or steps is not None or speed is not None or variants is not None:
            raise TypeError("forces(kinematics): the angles, speeds and variants are the kinematics result's")
        return forces_of(mech)
    _statically_determinate(mech)
    out = forces_of(kinematics(mech, angles, steps=steps, speed=speed, variants=variants))
    if not variants:
        elements_defined(out)
    return out


def elements_defined(f: Forces) -> None:
    """Raise where a spring's or damper's two points meet at an assembled sample (its line has no direction):
    the load, its points and the first crank angle.  (A sweep's variants get NaN there instead.)"""
    from linkwork.units import turn_deg

    kin, mech = f.kinematics, f.kinematics.mechanism
    for load in mech.loads:
        if load.kind not in ("spring", "damper"):
            continue
        bad = np.flatnonzero((kin.valid_all & np.isnan(f.external.magnitude[load.name])).any(axis=0))
        if len(bad):
            a, b = (mech.point_names[p] for p in load.points)
            raise LinkworkError(
                f'load "{load.name}": the {load.kind}\'s points {a} and {b} meet with the crank at '
                f"{turn_deg(float(kin.angles[bad[0]])):.6g} deg to x, where its line has no direction"
            )


def _statically_determinate(mech: Mechanism) -> None:
    if mech.structure.redundant:
        raise LinkworkError(
            f"the mechanism has {mech.structure.redundant} redundant constraint(s): its reactions are "
            "statically indeterminate (they depend on the links' elasticity); remove the redundant link"
        )


@jit.deciding
def forces_of(kin: Kinematics) -> Forces:
    """The :class:`Forces` of a kinematics result: reactions, driving torque and foundation loads at
    its angles, speeds and variants (with the variants' mass properties), without solving the
    motion again.

    Where friction in proportion to the pairs' forces has no solution (the pairs lock, it does not converge, or
    the reactions are indeterminate), a :class:`~linkwork.errors.FrictionWarning` for each kind, with the crank
    angles (also in :attr:`Forces.friction`).

    Parameters
    ----------
    kin : Kinematics
        A result of :func:`linkwork.kinematics`: its mechanism, angles, speed and variants are used.

    Returns
    -------
    Forces
        Reactions per joint, driving torque (N m) and foundation loads at the result's angles.

    Raises
    ------
    LinkworkError
        For a mechanism with redundant constraints.

    Examples
    --------
    >>> import linkwork as lw
    >>> kin = lw.kinematics("four-bar", steps=12)
    >>> lw.forces_of(kin).driving_torque.shape
    (12,)
    """
    mech = kin.mechanism
    _statically_determinate(mech)
    compiled = reactions_numba.available()
    if not has_friction(mech):
        external = evaluate(kin) if mech.loads or not compiled else None
        lam, found, loads = _solve(kin, external, compiled)
        return _made(Forces(kin, lam, found), external, loads)
    base = evaluate(kin)
    jac = None if compiled else jacobian(kin)  # the NumPy kernels' solves share it
    respond = None if compiled else partial(_respond, kin, jac)
    friction, external, (lam, found, loads) = solve_friction(
        kin, base, partial(_solve, kin, compiled=compiled, jac=jac), respond
    )
    for problem in friction.problems:
        warnings.warn(problem, stacklevel=2)
    return _made(Forces(kin, lam, found, friction), external, loads)


def _solve(
    kin: Kinematics, external: Applied | None, compiled: bool, jac: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray, Loads | None]:
    """The multipliers, the foundation loads and (solved in NumPy) the loads of every link, with the
    external loads ``external``: by the compiled kernel where it runs, else by NumPy (with the constraints'
    Jacobian ``jac`` where it is known already)."""
    if compiled:
        lam, found = reactions_numba.run(kin, external)
        return lam, found, None
    start = time.thread_time()
    loads = inertia_and_gravity(kin, external)
    lam, frame = solve_reactions(kin, loads, jac)
    found = foundation(kin, frame, loads)
    jit.spent(time.thread_time() - start)  # what the compiled kernel would save (:mod:`linkwork.jit`)
    return lam, found, loads


def _respond(kin: Kinematics, jac: np.ndarray | None, totals: np.ndarray) -> np.ndarray:
    """The multipliers that balance each of the sets of loads ``totals`` ``(S, V, A, N, 3)`` alone, on the NumPy
    kernels (:func:`~linkwork.kinetostatics.reactions.balance`): ``(S, V, A, m)``."""
    start = time.thread_time()
    lam = balance(kin, totals, jac)[0]
    jit.spent(time.thread_time() - start)
    return lam


def _made(out: Forces, external: Applied | None, loads: Loads | None) -> Forces:
    """``out`` with the values it was solved with cached."""
    if external is not None:
        object.__setattr__(out, "external", external)
    if loads is not None:
        object.__setattr__(out, "loads", loads)
    return out


@per_mechanism
def _reaction_terms(mech: Mechanism) -> dict[tuple[str, str], tuple[tuple[int, bool], ...]]:
    """For every joint and each of its links: the pairs whose forces add up to the joint's force on that link,
    in the order :meth:`Forces.reaction` adds them, and whether each is negated (the link is the pair's first)."""
    out: dict[tuple[str, str], tuple[tuple[int, bool], ...]] = {}
    for joint in dict.fromkeys(mech.pair_joint):
        ks = [k for k, j in enumerate(mech.pair_joint) if j == joint]
        members = {int(i) for k in ks for i in mech.pair_links[k] if not mech.link_virtual[int(i)]}
        for link in sorted(members):
            terms = []
            for k in ks:
                a, b = (int(x) for x in mech.pair_links[k])
                if link in (a, b):
                    terms.append((k, link != b))
            out[str(joint), mech.link_names[link]] = tuple(terms)
    return out


class _Gather(NamedTuple):
    """How :meth:`Forces.reactions` adds up several reactions (:func:`_gather`).

    Attributes
    ----------
    pairs : ndarray of int
        The pairs of their terms, ``U`` of them.
    guides : ndarray of int
        The places of the prismatic ones in ``pairs``.
    columns : tuple of ndarray of int
        The first term of each reaction, then the second, ...: the place of its pair's force (``i``, its place in
        ``pairs``), of its negative (``U + i``) or of zero (``2 U``, where it has fewer terms).
    """

    pairs: np.ndarray
    guides: np.ndarray
    columns: tuple[np.ndarray, ...]


@per_mechanism
def _gathers(mech: Mechanism) -> dict[tuple[tuple[str, ...], tuple[str, ...]], _Gather]:
    """The :func:`_gather` of the reactions asked for so far, by their joints and links."""
    return {}


def _gather(mech: Mechanism, joints: tuple[str, ...], on: tuple[str, ...]) -> _Gather:
    """How to add up the reactions of ``joints`` on the links ``on`` (:func:`_reaction_terms`), found once."""
    found = _gathers(mech)
    if (joints, on) not in found:
        terms = [_reaction_terms(mech)[key] for key in zip(joints, on, strict=True)]
        pairs = sorted({k for t in terms for k, _ in t})
        place = {k: i for i, k in enumerate(pairs)}
        n, width = len(pairs), max((len(t) for t in terms), default=0)
        places = [[place[k] + n * negated for k, negated in t] + [2 * n] * (width - len(t)) for t in terms]
        columns = tuple(np.array([p[c] for p in places], dtype=np.intp) for c in range(width))
        guides = [i for i, k in enumerate(pairs) if mech.pair_type[k] != PairType.REVOLUTE]
        found[joints, on] = _Gather(np.array(pairs, dtype=np.intp), np.array(guides, dtype=np.intp), columns)
    return found[joints, on]
