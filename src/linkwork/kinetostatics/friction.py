"""Friction in the pairs in proportion to the forces they carry, solved with the reactions.

A joint's ``friction: {f, radius}`` makes the friction of each of its elementary pairs proportional to
the force the pair carries (Coulomb's law): a revolute pair's friction moment is ``f r |R|`` (``f r`` the
radius of the friction circle), a prismatic pair's friction force ``f |N|`` (``N`` the guide's normal
force, ``atan f`` the friction angle); each opposes the pair's relative motion
(:func:`~linkwork.kinetostatics.external.relative_motion`), whose direction the kinematics fixes.

The friction loads are then linear in their sizes ``mu`` (one a pair), and so are the reactions:
``lambda(mu) = lambda_0 + sum_j mu_j G_j``, where ``lambda_0`` are the reactions without this friction
and ``G_j`` those of a unit friction in pair ``j`` alone (``K + 1`` solves of the linear kinetostatics, all
samples at once).  The sizes solve ``mu = c |A lambda(mu)|`` (``c`` the coefficients ``f r`` or ``f``,
``A`` picks each pair's force): a small non-linear system per sample, solved by Newton's method from
the friction of the reactions without it, vectorised over the samples, until no size changes by more than
:data:`TOLERANCE` of the sample's largest.  Where the map does not contract at the solution (the spectral
radius ``rho`` of its Jacobian is 1 or more), successive approximations would grow without bound: the friction
feeds itself, and the pair locks (self-locking).  Next to such positions the solution exists but friction
multiplies the forces by about ``1 / (1 - rho)``, without bound as ``rho`` nears 1: where it multiplies the
largest pair force by :data:`LOCKING` or more, the pairs lock too (a design rule; the position is told from
Newton's root, or from the map's linear model at the successive approximations where Newton's method finds
none, within a few steps however near ``rho`` is to 1).  Where neither settles nor grows it does not converge.
Both leave NaN reactions there and are reported as a
:class:`~linkwork.errors.FrictionWarning` with the crank angle.  Where the reactions without friction are
indeterminate (a dead point) the friction is unknown and taken as zero (also reported).  A last solve
with the friction found gives the reactions, so the power and momentum balances hold to the solver's
precision at every sample.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from linkwork.errors import FrictionWarning
from linkwork.kinetostatics.external import Applied, generalised, pair_friction, relative_motion
from linkwork.motion.kinematic_analysis import Kinematics
from linkwork.structure.model import Mechanism, PairType
from linkwork.structure.records import PairFriction

#: Convergence: the largest change of a friction size in the last step, relative to the sample's largest size.
TOLERANCE = 1e-12
#: Newton steps at most.
MAX_ITERATIONS = 50
#: Successive approximations at most, where Newton's method finds no root (to tell a locking pair).
SUCCESSIVE = 2000
#: The factor by which friction may multiply the largest force in a sample's pairs (over that without it) short of
#: self-locking: at or above it the pairs lock.  Next to a lock the factor grows as ``1 / (1 - rho)`` (``rho`` the
#: spectral radius of ``dT/dmu``, 1 at the lock), and so does the driving torque; at 1000 the drive would give some
#: 1000 times its power without friction for the same work (an efficiency of about 0.1 %): locked for a designer.
LOCKING = 1e3

#: A solve of the linear kinetostatics with given external loads: a tuple whose first item is the
#: multipliers ``(V, A, m)``.
Solver = Callable[[Applied], tuple[Any, ...]]
#: The multipliers that balance sets of loads alone, ``(S, V, A, N, 3)`` -> ``(S, V, A, m)``
#: (:func:`linkwork.kinetostatics.reactions.balance`): the friction's responses in one solve.
Responder = Callable[[np.ndarray], np.ndarray]


@dataclass(frozen=True)
class FrictionSolution:
    """The friction in proportion to the pairs' forces over (V, A).

    Attributes
    ----------
    pairs : tuple of PairFriction
    size : ndarray (V, A, K)
        Each pair's friction: moment (N m) in a revolute pair, force (N) in a prismatic one; zero where the
        reactions are indeterminate, NaN where the pair locks or the iteration does not converge.
    relative : ndarray (V, A, K)
        Each pair's relative motion, rad/s or m/s (:func:`~linkwork.kinetostatics.external.relative_motion`).
    locked, unconverged, indeterminate : ndarray (V, A) of bool
    iterations : int
        Steps taken.
    residual : float
        The largest ``|mu - c |A lambda||`` of the final reactions, relative to the largest friction size.
    problems : tuple of FrictionWarning
    """

    pairs: tuple[PairFriction, ...]
    size: np.ndarray
    relative: np.ndarray
    locked: np.ndarray
    unconverged: np.ndarray
    indeterminate: np.ndarray
    iterations: int
    residual: float
    problems: tuple[FrictionWarning, ...]

    @property
    def loss(self) -> np.ndarray:
        """Power lost in each pair, W, ``(V, A, K)``: ``size |relative motion|``."""
        return self.size * np.abs(self.relative)


def with_friction(kin: Kinematics, base: Applied, sizes: np.ndarray, pairs: tuple[PairFriction, ...]) -> Applied:
    """``base`` and the friction of ``sizes`` ``(V, A, K)`` in the ``pairs``."""
    out = Applied(list(base.forces), list(base.moments), dict(base.magnitude), dict(base.penetration))
    for j, p in enumerate(pairs):
        pair_friction(kin, p.pair, sizes[..., j], out)
    return out


def _gains(
    kin: Kinematics, base: Applied, lam0: np.ndarray, scale: np.ndarray, solvers: tuple[Solver, Responder | None]
) -> np.ndarray:
    """d (pair forces' components) / d mu_j of each pair j with friction, ``(V, A, 2K, K)``: the reactions to pair
    j's friction of size ``scale[j]`` alone, over that size (the reactions are linear in the loads), all in one solve
    where ``respond`` is given (the NumPy kernels), else each with ``base`` less the reactions ``lam0`` to ``base``
    (the compiled kernels: a solve each)."""
    solve, respond = solvers
    pairs: tuple[PairFriction, ...] = kin.mechanism.friction
    rows = _rows(pairs)
    units = [np.zeros(kin.valid_all.shape + (len(pairs),)) for _ in pairs]
    for j, unit in enumerate(units):
        unit[..., j] = scale[j]
    if respond is None:
        lams = [solve(with_friction(kin, base, unit, pairs))[0][..., rows] - lam0[..., rows] for unit in units]
        return np.stack(lams, -1) / scale
    empty = Applied([], [], {}, {})
    alone = np.stack([generalised(kin, with_friction(kin, empty, unit, pairs)) for unit in units])
    return np.moveaxis(respond(alone)[..., rows], 0, -1) / scale


def pair_forces(mech: Mechanism, lam: np.ndarray, pairs: tuple[PairFriction, ...]) -> np.ndarray:
    """The force each of ``pairs`` carries, ``(V, A, K)``: ``|R|`` of a revolute pair, ``|N|`` of a prismatic
    one, from the multipliers ``lam`` ``(V, A, m)``."""
    return _carried(_revolute(mech, pairs), lam[..., _rows(pairs)])


def _revolute(mech: Mechanism, pairs: tuple[PairFriction, ...]) -> np.ndarray:
    return np.array([mech.pair_type[p.pair] == PairType.REVOLUTE for p in pairs])


def _carried(revolute: np.ndarray, lam: np.ndarray) -> np.ndarray:
    """:func:`pair_forces` from the two multipliers of each pair, ``lam`` ``(..., 2K)`` (:func:`_rows`)."""
    first, second = lam[..., 0::2], lam[..., 1::2]
    return np.where(revolute, np.hypot(first, second), np.abs(second))


def _rows(pairs: tuple[PairFriction, ...]) -> np.ndarray:
    """The multipliers of each of ``pairs``: a revolute pair's force, a prismatic pair's moment and normal force."""
    return np.array([r for p in pairs for r in (2 * p.pair, 2 * p.pair + 1)], dtype=np.intp)


def solve_friction(
    kin: Kinematics, base: Applied, solve: Solver, respond: Responder | None = None
) -> tuple[FrictionSolution, Applied, tuple[Any, ...]]:
    """The friction of ``kin.mechanism.friction`` with the reactions.

    Parameters
    ----------
    kin : Kinematics
    base : Applied
        The other external loads (:func:`~linkwork.kinetostatics.external.evaluate`).
    solve : callable
        The linear kinetostatics (:data:`Solver`).

    Returns
    -------
    FrictionSolution, Applied, tuple
        The friction, every external load with it, and ``solve``'s answer with them.
    """
    mech = kin.mechanism
    pairs: tuple[PairFriction, ...] = mech.friction
    c = np.array([p.coefficient for p in pairs])
    lam0 = solve(base)[0]
    force0 = pair_forces(mech, lam0, pairs)
    scale = np.maximum(c * np.max(np.where(np.isfinite(force0), force0, 0.0), axis=(0, 1)), 1.0)
    rows = _rows(pairs)
    gain = _gains(kin, base, lam0, scale, (solve, respond))
    mu, steps, locked, unconverged = _iterate(_revolute(mech, pairs), lam0[..., rows], gain, c)
    indeterminate = kin.valid_all & ~np.isfinite(force0).all(-1)
    mu = np.where(indeterminate[..., None], 0.0, mu)
    mu = np.where((locked | unconverged)[..., None], np.nan, mu)
    applied = with_friction(kin, base, mu, pairs)
    answer = solve(applied)
    found = c * pair_forces(mech, answer[0], pairs)
    good = np.isfinite(found) & np.isfinite(mu) & ~indeterminate[..., None]
    top = float(np.max(np.abs(mu), where=good, initial=0.0))
    residual = float(np.max(np.abs(found - mu), where=good, initial=0.0)) / top if top > 0 else 0.0
    relative = np.stack([relative_motion(kin, p.pair) for p in pairs], -1)
    problems = _problems(kin, pairs, locked, unconverged, indeterminate)
    out = FrictionSolution(pairs, mu, relative, locked, unconverged, indeterminate, steps, residual, problems)
    return out, applied, answer


def _iterate(
    revolute: np.ndarray, lam0: np.ndarray, gain: np.ndarray, c: np.ndarray
) -> tuple[np.ndarray, int, np.ndarray, np.ndarray]:
    """Newton's method for ``mu = T(mu) = c |A (lam0 + gain mu)|`` from ``mu = T(0)`` over all samples at once.

    ``revolute`` ``(K,)`` which pairs turn, ``lam0`` ``(V, A, 2K)`` the multipliers of the pairs without this
    friction, ``gain`` ``(V, A, 2K, K)`` their change with each size.  A sample is solved once no size changes
    by more than :data:`TOLERANCE` of its largest.  The pairs lock where the solution is unstable (the spectral
    radius of ``dT/dmu`` 1 or more: successive approximations would not settle) and where the friction multiplies
    the largest pair force by :data:`LOCKING` or more (:func:`_amplification`), whether Newton's test of the step
    accepted that solution or, that close to locking, rounding kept the step above it while ``mu = T(mu)`` holds to
    :data:`TOLERANCE`.  Where no solution is found, successive approximations decide (:func:`_successive`).
    Returns the sizes ``(V, A, K)``, the steps taken, and where the pairs lock and where the iteration
    does not converge ``(V, A)``.
    """
    finite = np.isfinite(lam0).all(-1) & np.isfinite(gain).all((-1, -2))
    lam0 = np.where(finite[..., None], lam0, 0.0)
    gain = np.where(finite[..., None, None], gain, 0.0)
    eye = np.eye(len(c))
    mu = _map(revolute, lam0, gain, c, np.zeros(lam0.shape[:-1] + (len(c),)))[0]
    done = ~finite  # nothing to solve there
    steps = 0
    while steps < MAX_ITERATIONS and not done.all():
        steps += 1
        mapped, slope = _map(revolute, lam0, gain, c, mu)
        matrix = np.where(done[..., None, None], eye, eye - slope)
        good = np.abs(np.linalg.det(matrix)) > 1e-12
        matrix = np.where(good[..., None, None], matrix, eye)
        change = np.linalg.solve(matrix, (mapped - mu)[..., None])[..., 0]
        change = np.where((good & ~done)[..., None], change, 0.0)
        mu = mu + change
        done |= good & (np.max(np.abs(change), -1) <= TOLERANCE * np.max(np.abs(mu), -1))
    mapped, slope = _map(revolute, lam0, gain, c, mu)
    top = np.max(np.abs(mu), -1)
    root = finite & (done | ((mu >= 0).all(-1) & (np.max(np.abs(mapped - mu), -1) <= TOLERANCE * top)))
    amplified = ~(_amplification(revolute, lam0, gain, mu) < LOCKING)
    locked = finite & ((done & ~(_radius(slope) < 1.0)) | (root & amplified))
    done |= locked
    if not done.all():  # no root found: successive approximations tell growth without bound from settling
        start = _map(revolute, lam0, gain, c, np.zeros_like(mu))[0]
        grows, settled, found = _successive(revolute, lam0, gain, c, start, ~done)
        mu = np.where(settled[..., None], found, mu)
        locked |= grows
        done |= settled | grows
    return mu, steps, locked, finite & ~done


def _radius(slope: np.ndarray) -> np.ndarray:
    """The spectral radius of each Jacobian ``slope`` ``(..., K, K)``: ``(...)``, NaN where it is not finite."""
    finite = np.isfinite(slope).all((-1, -2))
    radius = np.max(np.abs(np.linalg.eigvals(np.where(finite[..., None, None], slope, 0.0))), -1)
    return np.where(finite, radius, np.nan)


def _amplification(revolute: np.ndarray, lam0: np.ndarray, gain: np.ndarray, mu: np.ndarray) -> np.ndarray:
    """The factor by which the friction ``mu`` ``(..., K)`` multiplies the largest force in the pairs: the largest
    of :func:`pair_forces` with it over the largest without it, ``(...)`` (1 where both are zero, infinite where
    the friction loads pairs that carry nothing without it)."""
    with np.errstate(invalid="ignore", over="ignore"):
        force = np.max(_carried(revolute, lam0 + np.einsum("...rk,...k->...r", gain, mu)), -1)
    force0 = np.max(_carried(revolute, lam0), -1)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(force0 > 0, force / np.where(force0 > 0, force0, 1.0), np.where(force > 0, np.inf, 1.0))


def _successive(
    revolute: np.ndarray, lam0: np.ndarray, gain: np.ndarray, c: np.ndarray, mu: np.ndarray, active: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Successive approximations ``mu <- T(mu)`` from ``mu`` where ``active``: where they grow without bound (the
    pairs lock), where they settle (to :data:`TOLERANCE`), and the sizes they settle at.

    They grow without bound where the friction multiplies the largest pair force by :data:`LOCKING` or more
    (:func:`_amplification`), and, told without waiting for that, where the largest size rises and the map's
    linear model at the iterate, ``T(mu) + J (x - mu)`` (``J = dT/dmu``), grows without bound (the spectral
    radius of ``J`` 1 or more) or settles at a friction that multiplies the largest pair force by
    :data:`LOCKING` or more.  Next to a lock the map is nearly that linear model (``T`` is homogeneous of degree 1
    in ``mu`` but for the reactions without friction), with ``J`` near its spectral radius 1: the iterates grow by
    about ``T(0)`` a step, ``1 / (1 - rho)`` steps to settle.  Only the active samples are iterated.
    """
    grows = np.zeros(active.shape, bool)
    settled = np.zeros(active.shape, bool)
    found = mu.copy()
    idx = np.nonzero(active)
    l0, g, x = lam0[idx], gain[idx], mu[idx]
    up, still = np.zeros(len(x), bool), np.zeros(len(x), bool)
    for _ in range(SUCCESSIVE):
        new, slope = _map(revolute, l0, g, c, x)
        top = np.max(new, -1)
        with np.errstate(invalid="ignore", over="ignore"):
            beyond = ~(_amplification(revolute, l0, g, new) < LOCKING)  # NaN or inf: without bound too
            up |= ~still & (beyond | ((top > np.max(x, -1)) & _ahead(revolute, l0, g, x, new, slope)))
            still |= ~up & (np.max(np.abs(new - x), -1) <= TOLERANCE * top)
        x = np.where((~up & ~still)[:, None], new, x)
        if (up | still).all():
            break
    grows[idx], settled[idx], found[idx] = up, still, x
    return grows, settled, found


def _ahead(
    revolute: np.ndarray, lam0: np.ndarray, gain: np.ndarray, mu: np.ndarray, mapped: np.ndarray, slope: np.ndarray
) -> np.ndarray:
    """Where the map's linear model at ``mu`` ``(N, K)``, ``x -> mapped + slope (x - mu)``, has no stable fixed point
    (the spectral radius of ``slope`` 1 or more) or one with sizes ``>= 0`` whose friction multiplies the largest pair
    force by :data:`LOCKING` or more: ``(N,)``."""
    eye = np.eye(mu.shape[-1])
    matrix = eye - slope
    stable = (_radius(slope) < 1.0) & (np.abs(np.linalg.det(matrix)) > 1e-12)
    limit = mu + np.linalg.solve(np.where(stable[:, None, None], matrix, eye), (mapped - mu)[..., None])[..., 0]
    return ~stable | ((limit >= 0).all(-1) & ~(_amplification(revolute, lam0, gain, limit) < LOCKING))


def _map(
    revolute: np.ndarray, lam0: np.ndarray, gain: np.ndarray, c: np.ndarray, mu: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """``T(mu) = c |A (lam0 + gain mu)|`` ``(V, A, K)`` and its Jacobian ``(V, A, K, K)`` (:func:`_iterate`)."""
    lam = lam0 + np.einsum("...rk,...k->...r", gain, mu)
    first, second = lam[..., 0::2], lam[..., 1::2]
    size = np.hypot(first, second)
    safe = np.where(size > 0, size, 1.0)
    d_first = np.where(revolute, first / safe, 0.0)  # d|A lam| / d lam of each pair's two multipliers
    d_second = np.where(revolute, second / safe, np.sign(second))
    slope = c[:, None] * (d_first[..., None] * gain[..., 0::2, :] + d_second[..., None] * gain[..., 1::2, :])
    return c * _carried(revolute, lam), slope


def _problems(
    kin: Kinematics,
    pairs: tuple[PairFriction, ...],
    locked: np.ndarray,
    unconverged: np.ndarray,
    indeterminate: np.ndarray,
) -> tuple[FrictionWarning, ...]:
    """One :class:`~linkwork.errors.FrictionWarning` for each kind of failure and variant, naming the joints
    with friction and the positions (the crank angle phi)."""
    from linkwork.motion.analysis import CrankAngles

    crank = CrankAngles.of(kin.mechanism)
    joints = ", ".join(dict.fromkeys(p.joint for p in pairs))
    angles = np.broadcast_to(kin.angles, kin.valid_all.shape)
    out = []
    for kind, mask in (("locks", locked), ("does not converge", unconverged), ("indeterminate", indeterminate)):
        for v in np.flatnonzero(mask.any(-1)):
            at = angles[v][mask[v]]
            shown = tuple(float(x) for x in (crank.phi(at, 1) if crank is not None else at))
            unit = " deg" if crank is not None else ""
            where = ", ".join(f"{x:g}" for x in shown[:6]) + (f" and {len(shown) - 6} more" if len(shown) > 6 else "")
            name = "phi = " if crank is not None else ""
            what = {
                "locks": f"friction in {joints} locks the mechanism (self-locking) at {name}{where}{unit}",
                "does not converge": f"friction in {joints} does not converge in {MAX_ITERATIONS} Newton steps at "
                f"{name}{where}{unit}",
                "indeterminate": f"friction in {joints} is taken as zero at {name}{where}{unit}, where the reactions "
                "are indeterminate (a dead point)",
            }[kind]
            variant = f" (variant {v})" if kin.variants else ""
            out.append(FrictionWarning(joints, kind, shown, int(v), what + variant))
    return tuple(out)


def has_friction(mech: Mechanism) -> bool:
    """Whether ``mech`` has friction in proportion to its pairs' forces."""
    return bool(getattr(mech, "friction", ()))
