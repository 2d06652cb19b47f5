"""Reduced (generalised) inertia and load moment of a one-degree-of-freedom mechanism.

With the turning angle ``psi`` of the crank as the generalised coordinate
(``psi = 0`` at the assembly angle, increasing in the file's direction of
rotation), the kinetic energy is ``T = J(psi) psi'^2 / 2`` and the power of
the loads is ``M(psi) psi'``.  Both follow exactly from a kinematic solution
at unit crank speed, where every velocity is a first transfer function
(``d r / d psi``) and, the crank turning uniformly, every acceleration is
the second (``d2 r / d psi2``):

    J(psi)      = sum m_i |v_Ci|^2 + J_Ci omega_i^2
    dJ/dpsi     = 2 sum m_i v_Ci . a_Ci + J_Ci omega_i epsilon_i
    M(psi)      = sum m_i g . v_Ci + F . v_P + M omega_i     (gravity and the file's loads: :func:`load_moment`)
                  - sum S_k |omega_rel,k|                     (friction in proportion to the pairs' forces:
                                                               :func:`friction_moment`)

with the loads and the pairs' frictions ``S_k`` of the machine's state and the velocities at unit speed: one
formula for the steady cycle and the runs in time, which differ in the state alone.  The friction in proportion to
the pairs' forces depends on the speed (the inertia forces load the pairs): the steady cycle, whose ``M`` is a
table over the angle, takes it turning uniformly at the file's nominal crank speed
(:mod:`linkwork.kinetostatics.friction`, :func:`nominal_friction`), a moment always against the turning, and keeps
the dampers' moment, proportional to the speed, apart (``-B psi'``); a run in time takes every load at each state's
true speed (:func:`terms_of_both`, :func:`pair_friction_moment`).  The equation of motion of the machine unit is then
``J(psi) psi'' + J'(psi) psi'^2 / 2 = M(psi) + M_drive``.
"""

from __future__ import annotations

import dataclasses
import functools
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from linkwork.errors import LinkworkError
from linkwork.kinetostatics.external import Applied, evaluate, power_of_loads, relative_motion
from linkwork.kinetostatics.friction import FrictionSolution
from linkwork.kinetostatics.reaction_forces import forces_of
from linkwork.kinetostatics.reactions import gravity_power, inertia_and_gravity
from linkwork.limits import DYNAMICS_STEPS, TURN_STEPS
from linkwork.motion import cycle, kinematics
from linkwork.motion.kinematic_analysis import Kinematics, direction, kinematics_at
from linkwork.structure.model import Mechanism, one_crank
from linkwork.units import turn_deg


@dataclass(frozen=True)
class Reduced:
    """Reduced quantities on a uniform grid of the turning angle over one turn.

    Attributes
    ----------
    psi : ndarray (K,)
        Turning angle of the crank from its assembly angle, rad, ``2 pi k / K``.
    angle : ndarray (K,)
        The crank's drive angle at each ``psi``.
    inertia : ndarray (K,)
        Reduced moment of inertia ``J``, kg m^2, on the crank shaft.
    inertia_slope : ndarray (K,)
        ``dJ/dpsi``, kg m^2/rad.
    load : ndarray (K,)
        Reduced moment of gravity, the external loads and the friction in the pairs, N m; positive where
        they drive the crank forward (a cutting load gives a negative moment); the dampers' apart.
    friction : ndarray (K,)
        The part of ``load`` that the friction in proportion to the pairs' forces takes, N m (>= 0: it is
        subtracted); zero without it.
    damping : ndarray (K,) or None
        The dampers' reduced damping coefficient ``B``, N m s/rad: their moment is ``-B psi'``; None
        without dampers.
    between : callable or None
        ``between(psi) -> Reduced``: the same quantities at any turning angles ``psi`` ``(N,)`` (the mechanism
        solved there), for the work of the loads between the points of the grid and the extremes of what
        depends on it (:meth:`work_at`); None: only the grid's values are known.
    """

    psi: np.ndarray
    angle: np.ndarray
    inertia: np.ndarray
    inertia_slope: np.ndarray
    load: np.ndarray
    friction: np.ndarray | None = None
    damping: np.ndarray | None = None
    between: Callable[[np.ndarray], Reduced] | None = field(default=None, compare=False, repr=False)

    def at_speed(self, omega: float) -> Reduced:
        """The same with the dampers' moment at the crank speed ``omega`` (rad/s) in ``load``: the loads of a
        machine turning at that speed, for what reads the load moment alone (a flywheel's sizing)."""
        if self.damping is None:
            return self
        inner = self.between
        return dataclasses.replace(
            self,
            load=self.load - self.damping * omega,
            damping=None,
            between=None if inner is None else lambda psi: inner(psi).at_speed(omega),
        )

    def work(self) -> np.ndarray:
        """Work of the loads from ``psi = 0`` (J) at the points of the grid, ``(K + 1,)`` (the last value after the
        whole turn): over each step by Gauss-Lobatto's rule, halving a step where a load is not smooth in it (the
        loads evaluated between the points, :attr:`between`: to rounding, whatever the grid; :meth:`_integral`),
        else by the trapezoid rule.  Found once."""
        found: np.ndarray | None = self.__dict__.get("_work")
        if found is None:
            found = np.concatenate([[0.0], np.cumsum(self._step_work())])
            self.__dict__["_work"] = found  # frozen: kept as a cached value
        return found

    def _step_work(self) -> np.ndarray:
        """The work of the loads over each step of the grid, ``(K,)`` (:meth:`work`)."""
        step = 2 * np.pi / len(self.psi)
        if self.between is None:
            m = np.append(self.load, self.load[0])
            out: np.ndarray = (m[1:] + m[:-1]) * step / 2
            return out
        return self._integral(self.psi, self.psi + step)

    def _integral(self, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
        """The work of the loads from ``lo`` to ``hi`` ``(N,)``, to rounding: Gauss-Lobatto's rule of :data:`NODES`
        on each span, and on its halves where the two differ by more than :data:`AGREE` of the largest load times
        the span (a kink or a jump of a load inside it: a knife that meets the workpiece), and so on.  The rule
        takes the ends of the span, so that a kink between its inner nodes and an end is seen.

        Bounded in time and memory whatever the loads: at most ``N /`` :data:`SPANS` spans (at least
        :data:`SPANS_LEAST`) are halved a round, those whose halves disagree most for their length (a jump of a load
        is halved to the rounding of the angle, a kink nearly so), so that the loads are evaluated at most
        ``12 N + 16`` :data:`HALVINGS` ``max(N / SPANS, SPANS_LEAST)`` times.  A load known only to a few units of
        rounding (near a singular position, where its halves never agree to :data:`AGREE`) is then not halved for
        ever: a span left open takes its halves' sum, within their disagreement of the true work."""
        assert self.between is not None
        nodes, weights = NODES

        def rule(a: np.ndarray, b: np.ndarray) -> np.ndarray:
            x = a[:, None] + (b - a)[:, None] * (1 + nodes) / 2
            assert self.between is not None
            out: np.ndarray = self.between(x.ravel()).load.reshape(x.shape) @ weights * (b - a) / 2
            return out

        scale = AGREE * float(np.max(np.abs(self.load), initial=0.0))
        cap = max(len(lo) // SPANS, SPANS_LEAST)
        total, owner, whole = np.zeros(len(lo)), np.arange(len(lo)), rule(lo, hi)
        for _ in range(HALVINGS):
            mid = 0.5 * (lo + hi)
            halves = rule(np.concatenate([lo, mid]), np.concatenate([mid, hi]))
            left, right = halves[: len(lo)], halves[len(lo) :]
            gap = np.abs(left + right - whole) / np.maximum(np.abs(hi - lo), np.finfo(float).tiny)
            done = ~(gap > scale)  # NaN (no assembly) is done too
            if np.count_nonzero(~done) > cap:  # the worst for their length go on; the rest take their halves' sum
                done[np.argsort(np.where(done, np.inf, -gap), kind="stable")[cap:]] = True
            np.add.at(total, owner[done], (left + right)[done])
            more = ~done
            if not more.any():
                return total
            lo, hi = np.concatenate([lo[more], mid[more]]), np.concatenate([mid[more], hi[more]])
            owner, whole = np.tile(owner[more], 2), np.concatenate([left[more], right[more]])
        np.add.at(total, owner, whole)
        return total

    def work_at(self, psi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The work of the loads from ``psi = 0`` to any turning angles ``psi`` ``(N,)`` (past a turn, the turn's
        work more: the loads repeat), from the grid's :meth:`work` and the rule of :meth:`work` from the point below,
        and the reduced inertia there, ``(N,)`` each; needs :attr:`between`."""
        assert self.between is not None, "the work between the points needs the mechanism (between)"
        n, work = len(self.psi), self.work()
        step = 2 * np.pi / n
        turns = np.floor(psi / (2 * np.pi))
        rest = psi - 2 * np.pi * turns
        k = np.clip(np.floor(rest / step).astype(np.intp), 0, n - 1)
        start = self.psi[k]
        return work[k] + self._integral(start, rest) + turns * work[-1], self.between(rest).inertia

    @property
    def mean_load(self) -> float:
        """Mean reduced load moment over the turn, N m: the drive must supply its opposite (the work of a turn,
        :meth:`work`, over the turn)."""
        return float(self.work()[-1] / (2 * np.pi))


#: Gauss-Lobatto's nodes on [-1, 1] and weights with which the work of the loads is integrated over a span
#: (:meth:`Reduced.work`): exact for a load that is a polynomial of degree 5 over it.
NODES = (np.array([-1.0, -1 / math.sqrt(5), 1 / math.sqrt(5), 1.0]), np.array([1.0, 5.0, 5.0, 1.0]) / 6)
#: A span's work is taken where the rule on its halves agrees with it to this fraction of the largest load times
#: the span (the turn's work is then known to this fraction of the largest load times a turn), else its halves'.
AGREE = 1e-14
#: Halvings of a span at most.
HALVINGS = 60
#: Spans halved in a round at most (:meth:`Reduced._integral`): one in this many of the spans asked, and at least
#: :data:`SPANS_LEAST` (a jump of a load keeps two spans open a round).
SPANS, SPANS_LEAST = 16, 64


def reduced(mech: Mechanism, *, steps: int = DYNAMICS_STEPS) -> Reduced:
    """Reduced inertia, its slope and the reduced load moment over ``steps`` equal steps of one turn of
    the crank (the dynamic model of the machine: kinetic energy and power brought to the crank).

    Parameters
    ----------
    mech : Mechanism
        A compiled mechanism (``linkwork.reduced`` also takes a path, an example name or a Spec).
    steps : int
        Equal steps of one turn; default 3600 (:data:`linkwork.limits.DYNAMICS_STEPS`).

    Returns
    -------
    Reduced
        ``inertia`` (kg m^2) and ``inertia_slope`` (kg m^2/rad) at each angle, the reduced ``load`` moment
        (N m) and its ``mean_load``.

    Raises
    ------
    LinkworkError
        Unless the mechanism has one crank (a revolute drive) and assembles over the whole turn.

    Examples
    --------
    >>> import linkwork as lw
    >>> r = lw.reduced("double-cut-shears", steps=360)
    >>> r.inertia.shape
    (360,)
    """
    if not one_crank(mech):
        raise LinkworkError("machine dynamics needs one crank (a revolute drive)")
    if steps < 16:
        raise LinkworkError(f"steps: expected at least 16 angles over the turn, got {steps}")
    sign = -1.0 if mech.drive_speed[0] < 0 else 1.0
    angle = cycle(mech, steps)
    kin = kinematics(mech, angle, speed=sign)
    if not np.all(kin.valid):
        bad = turn_deg(angle[~np.asarray(kin.valid)][0])
        raise LinkworkError(f"the mechanism does not assemble over the whole turn (first at {bad:.1f} deg)")
    psi = 2 * np.pi * np.arange(steps) / steps
    return dataclasses.replace(_reduced_of(kin, psi, sign), between=functools.partial(_between, mech, sign))


def _between(mech: Mechanism, sign: float, psi: np.ndarray) -> Reduced:
    """The reduced quantities at any turning angles ``psi`` ``(N,)`` (:attr:`Reduced.between`): NaN where the
    mechanism does not assemble."""
    with np.errstate(invalid="ignore", divide="ignore"):
        return _reduced_of(kinematics(mech, mech.drive_start[0] + direction(mech) * psi, speed=sign), psi, sign)


def inertia_terms(kin: Kinematics, loads: Any, rows: slice = slice(None)) -> tuple[np.ndarray, np.ndarray]:
    """The reduced inertia ``J = sum(m vc.vc + J_s w^2)`` (kg m^2) and its slope ``dJ/dphi = 2 sum(m vc.ac +
    J_s w e)`` (kg m^2/rad) of the samples ``rows`` of ``kin`` solved at unit crank speed and rest's acceleration
    (the transfer functions), ``loads`` its :func:`~linkwork.kinetostatics.reactions.inertia_and_gravity`: each
    ``(K,)``.  The one place the machine's reduced inertia is computed."""
    ms = kin.mass_properties
    m, j = ms.mass[0], ms.inertia[0]
    vc, ac = loads.com_velocity[0, rows], loads.com_acceleration[0, rows]
    w, e = kin.vel[0, rows, :, 2], kin.acc[0, rows, :, 2]
    inertia = np.sum(m * np.sum(vc * vc, -1) + j * w * w, -1)
    slope = 2 * np.sum(m * np.sum(vc * ac, -1) + j * w * e, -1)
    return inertia, slope


def _reduced_of(kin: Kinematics, psi: np.ndarray, sign: float) -> Reduced:
    """The reduced quantities of the solution ``kin`` at unit crank speed (``sign``: its direction) at the turning
    angles ``psi``: the loads' moment of that motion (:func:`load_moment`) but the dampers', whose moment at unit speed
    is ``-B`` (:func:`_damping`), less the friction at the file's speed (:func:`nominal_friction`)."""
    mech, angle = kin.mechanism, kin.angles
    loads = inertia_and_gravity(kin, Applied([], [], {}, {}))  # the external loads: one at a time, in load_moment
    inertia, slope = inertia_terms(kin, loads)
    friction = nominal_friction(kin, sign)
    kinds = tuple(sorted({load.kind for load in mech.loads} - {"damper"}))
    load = load_moment(kin, loads.com_velocity, kinds=kinds) - friction
    return Reduced(psi, angle, inertia, slope, load, friction, _damping(kin))


def load_moment(
    kin: Kinematics,
    com_velocity: np.ndarray | None,
    *,
    kinds: tuple[str, ...] | None = None,
    at: slice = slice(None),
    moving: slice = slice(None),
) -> np.ndarray:
    """The loads' reduced moment (N m, ``(K,)``): the power of gravity and the file's loads (those of the ``kinds``
    given, default all) at unit crank speed, ``Q = sum m g . v_C + sum F . v_P + M omega``, the loads those of the
    state, the velocities the first transfer functions.  The one formula of the machine's load moment: the steady
    cycle's (:func:`reduced`, the state the motion at unit speed itself) and the run in time's
    (:func:`terms_of_both`, the loads of the samples ``at`` of ``kin`` at the true speed, the velocities of the same
    poses at unit speed, the samples ``moving``).

    Parameters
    ----------
    kin : Kinematics
        The poses, one variant.
    com_velocity : ndarray (1, A, N, 2) or None
        The links' centres' velocities over ``kin`` (:func:`~linkwork.kinetostatics.reactions.inertia_and_gravity`),
        m/s; None: gravity left out.
    kinds : tuple of str, optional
        The kinds of the file's loads taken; default all.
    at, moving : slice
        The samples of ``kin`` whose loads are taken, and those whose velocities (at unit crank speed), as many.

    Returns
    -------
    ndarray (K,)
        N m; each load evaluated and its power added before the next (:func:`power_of_loads`: the memory does not
        grow with the number of loads).
    """
    total = power_of_loads(kin, kinds, at=at, moving=moving)
    if com_velocity is not None:
        total = gravity_power(kin, com_velocity[:, moving]) + total
    out: np.ndarray = total[0]
    return out


def friction_moment(friction: FrictionSolution, at: slice, relative: np.ndarray) -> np.ndarray:
    """The friction in proportion to the pairs' forces reduced to the crank, N m ``(K,)``, >= 0 (against the
    motion): each pair's friction of the samples ``at`` of its solution (``f r |R|`` in a revolute pair, ``f |N|``
    along a guide) times its relative motion at unit crank speed, ``relative`` ``(K, pairs)`` (rad or m a rad of
    the crank): ``sum size |relative|``, the power it takes at unit speed.  The one formula of the friction's
    moment: the steady cycle's at the file's speed (:func:`nominal_friction`), the run's at the true speed
    (:func:`pair_friction_moment`)."""
    out: np.ndarray = np.sum(friction.size[0, at] * np.abs(relative), axis=-1)
    return out


def nominal_friction(kin: Kinematics, sign: float) -> np.ndarray:
    """The steady cycle's friction in proportion to the pairs' forces (:func:`friction_moment`) at the poses of
    ``kin`` at unit crank speed (``sign`` its direction), the pairs loaded as when turning uniformly at the file's
    speed: N m, ``(K,)``, zero without such friction.

    Raises
    ------
    LinkworkError
        Where the friction has no solution (the pairs lock, or it does not converge).
    """
    mech = kin.mechanism
    if not mech.friction:
        return np.zeros(len(kin.angles))
    rate = abs(float(mech.drive_speed[0]))
    rate = rate if math.isfinite(rate) and rate > 0 else 1.0
    fr = forces_of(kinematics(mech, kin.angles, speed=sign * rate)).friction
    assert fr is not None
    for problem in fr.problems:
        if problem.kind != "indeterminate":
            raise LinkworkError(f"machine dynamics needs the friction at every angle: {problem}")
    relative = np.stack([relative_motion(kin, p.pair)[0] for p in fr.pairs], -1)
    return friction_moment(fr, slice(None), relative)


def _damping(kin: Kinematics) -> np.ndarray | None:
    """The dampers' reduced damping coefficient ``(K,)`` over ``kin`` at unit crank speed (minus their moment
    there, :func:`load_moment`), or None without dampers."""
    if not any(load.kind == "damper" for load in kin.mechanism.loads):
        return None
    return -load_moment(kin, None, kinds=("damper",))


# --- the terms at any states (phi, omega) of a run in time (linkwork.machine.timerun) ---------------------


@dataclass(frozen=True)
class ReducedTerms:
    """``J`` (kg m^2, the drive's included), ``J'`` (kg m^2/rad) and ``Q`` (N m), each ``(K,)``."""

    inertia: np.ndarray
    slope: np.ndarray
    load: np.ndarray


def reduced_terms(
    mech: Mechanism,
    phi: np.ndarray,
    omega: np.ndarray,
    extra_inertia: float = 0.0,
    along: Kinematics | None = None,
) -> ReducedTerms:
    """The reduced inertia, its slope and the loads' reduced moment at the states ``(phi, omega)`` ``(K,)``,
    from one kinematic solution of the 2K samples: each pose at unit speed (the transfer functions) and at
    its true speed (the loads: a damper's force, a friction's sense), in the assembly modes the mechanism's
    cycle ``along`` (default :func:`cycle_of`) has at those angles (:func:`poses`).

    Raises
    ------
    LinkworkError
        Where a pose does not assemble, or a load has no value there (a spring whose points meet).
    """
    k = len(phi)
    kin = unit_and_true_speeds(mech, phi, omega, along)
    if not kin.valid_all.all():
        bad = float(phi[np.flatnonzero(~kin.valid_all[0, :k] | ~kin.valid_all[0, k:])[0]])
        raise LinkworkError(
            f"the run reaches a pose where the mechanism does not assemble: crank at "
            f"{turn_deg(bad):.6g} deg to x (a dead point, or past the end of its travel)"
        )
    terms = terms_of_both(kin, k, extra_inertia)
    if not np.isfinite(terms.load).all():
        _no_value(kin, phi, k)
    return terms


def unit_and_true_speeds(
    mech: Mechanism, phi: np.ndarray, omega: np.ndarray, along: Kinematics | None = None
) -> Kinematics:
    """The poses ``phi`` ``(K,)`` at unit speed, then at the speeds ``omega``: ``2K`` samples at rest's acceleration,
    in the assembly modes of the cycle ``along`` (default :func:`cycle_of`)."""
    k = len(phi)
    angles = np.concatenate([phi, phi])[:, None]
    speeds = np.concatenate([np.ones(k), omega])[:, None]
    return poses(along if along is not None else cycle_of(mech), angles, speeds, np.zeros((2 * k, 1)))


def poses(along: Kinematics, angles: np.ndarray, speeds: np.ndarray, accels: np.ndarray) -> Kinematics:
    """:func:`~linkwork.motion.kinematic_analysis.kinematics_at` of the mechanism of the cycle ``along``
    (:func:`cycle_of`) in the assembly modes that cycle has at each angle: where the crank passes a change point,
    the motion goes on in the other mode, as in ``linkwork kinematics`` and the viewer, whatever the order or
    number of the poses asked."""
    return kinematics_at(along.mechanism, angles, speeds, accels, along=along)


def cycle_of(mech: Mechanism) -> Kinematics:
    """The mechanism's cycle over a turn from its assembly pose (:func:`~linkwork.motion.kinematics` of
    :data:`~linkwork.limits.TURN_STEPS` angles), whose assembly modes a run in time keeps to (:func:`poses`)."""
    return kinematics(mech, steps=TURN_STEPS)


def terms_of_both(kin: Kinematics, k: int, extra_inertia: float) -> ReducedTerms:
    """:func:`reduced_terms` of the ``2K`` samples of :func:`unit_and_true_speeds` (NaN where a pose does not
    assemble)."""
    loads = inertia_and_gravity(kin, Applied([], [], {}, {}))  # the external loads: one at a time, in load_moment
    inertia, slope = inertia_terms(kin, loads, slice(0, k))
    inertia = inertia + extra_inertia
    load = load_moment(kin, loads.com_velocity, at=slice(k, None), moving=slice(0, k))
    if kin.mechanism.friction:
        load = load - pair_friction_moment(kin, k)
    return ReducedTerms(inertia, slope, load)


def pair_friction_moment(kin: Kinematics, k: int) -> np.ndarray:
    """The friction in proportion to the pairs' forces reduced to the crank at the ``K`` states of the ``2K`` samples
    of :func:`unit_and_true_speeds`, N m ``(K,)``, against the crank's sense of motion (zero at a speed of exactly
    zero: at rest it is a reaction, taken by the run's stops at :data:`~linkwork.machine.timerun.CREEP`).

    Each pair's friction (a moment ``f r |R|`` of a revolute pair, a force ``f |N|`` along a guide) is solved with the
    reactions at the true speed (the inertia forces of that speed loading the pairs, the crank's own acceleration
    left out of them, as the steady cycle leaves it out at the nominal speed: :func:`nominal_friction`), and its
    power at unit crank speed is the moment (:func:`friction_moment`).

    Raises
    ------
    LinkworkError
        Where friction locks the mechanism at a state: no drive moves it there.
    """
    import warnings

    from linkwork.errors import FrictionWarning

    with warnings.catch_warnings():  # the problems are for a cycle's reader; here a lock is an error
        warnings.simplefilter("ignore", FrictionWarning)
        fr = forces_of(kin).friction
    assert fr is not None
    locked = fr.locked[0, k:] | fr.unconverged[0, k:]
    if locked.any():
        where = turn_deg(float(kin.angles[k + int(np.argmax(locked))]))
        raise LinkworkError(
            f"friction locks the mechanism with the crank at {where:.6g} deg to x (self-locking: no drive moves it "
            "there): the run in time cannot go on"
        )
    return np.sign(kin.rates[k:, 0]) * friction_moment(fr, slice(k, None), fr.relative[0, :k])


def _no_value(kin: Kinematics, phi: np.ndarray, k: int) -> None:
    """Raise for the first load without a value at the run's poses (a spring whose two points meet)."""
    assert kin.mechanism.loads
    for name, size in evaluate(kin).magnitude.items():
        bad = np.flatnonzero(~np.isfinite(size[0, k:]))
        if len(bad):
            where = turn_deg(float(phi[bad[0]]))
            raise LinkworkError(
                f'load "{name}" has no value with the crank at {where:.6g} deg to x: '
                "a spring's or damper's two points meet there, and its line has no direction"
            )
    raise LinkworkError("the loads have no value at a pose of the run")
