"""Loads of the links, the reactions group by group, and the two independent checks."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from linkwork.kinetostatics.external import Applied, evaluate, generalised, resultant
from linkwork.kinetostatics.external import power as external_power
from linkwork.kinetostatics.geometry import variant_geometry
from linkwork.motion.kinematic_analysis import Kinematics
from linkwork.structure.assemble import group_rows
from linkwork.structure.constraints import build_rows, perp, residuals_and_jacobian
from linkwork.structure.model import Mechanism


@dataclass(frozen=True)
class Loads:
    """Loads on every link, frame included, over (V, A).

    Attributes
    ----------
    applied : ndarray (V, A, N, 3)
        Generalised applied loads (force x, y and moment about the link's local origin): gravity
        and the external loads of the file.
    inertia : ndarray (V, A, N, 3)
        d'Alembert loads: -m a_C and -(J_C epsilon + r_C x m a_C).
    com, com_velocity, com_acceleration : ndarray (V, A, N, 2)
        Centre of mass of every link.
    """

    applied: np.ndarray
    inertia: np.ndarray
    com: np.ndarray
    com_velocity: np.ndarray
    com_acceleration: np.ndarray
    external: Applied | None = None  # the external loads, where they were evaluated

    @property
    def total(self) -> np.ndarray:
        return self.applied + self.inertia


def _cross(r: np.ndarray, f: np.ndarray) -> np.ndarray:
    return r[..., 0] * f[..., 1] - r[..., 1] * f[..., 0]


def inertia_and_gravity(kin: Kinematics, external: Applied | None = None) -> Loads:
    """Gravity, the external loads (``external``, default those of the file:
    :func:`~linkwork.kinetostatics.external.evaluate`) and the d'Alembert inertia loads of every link."""
    m = kin.mechanism
    mass, lx, ly, j_c = _mass_arrays(kin)
    q, v, a = kin.pose, kin.vel, kin.acc  # (V, A, N, 3)
    c, s = np.cos(q[..., 2]), np.sin(q[..., 2])
    r = np.stack([c * lx - s * ly, s * lx + c * ly], -1)  # origin -> centre of mass, global
    w, e = v[..., 2:3], a[..., 2:3]
    turned = perp(r)
    com = q[..., :2] + r
    vc = v[..., :2] + w * turned
    ac = a[..., :2] + e * turned - w * w * r
    weight = np.broadcast_to(mass[..., None] * m.gravity_vector, com.shape)
    applied = np.concatenate([weight, _cross(r, weight)[..., None]], -1)
    if external is None:
        external = evaluate(kin)
    if external.forces or external.moments:
        applied = applied + generalised(kin, external)
    f_in = -mass[..., None] * ac
    inertia = np.concatenate([f_in, (_cross(r, f_in) - j_c * a[..., 2])[..., None]], -1)
    return Loads(applied, inertia, com, vc, ac, external)


def gravity_power(kin: Kinematics, com_velocity: np.ndarray) -> np.ndarray:
    """Power (W) of gravity on every link, ``(V, A)``, from the centres' velocities ``(V, A, N, 2)``."""
    mass = _mass_arrays(kin)[0]
    g = kin.mechanism.gravity_vector
    return np.sum(mass * (com_velocity[..., 0] * g[0] + com_velocity[..., 1] * g[1]), -1)


def _mass_arrays(kin: Kinematics) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Mass, centre of mass x and y (local) and moment of inertia of every link of every variant,
    each ``(V, 1, N)`` to broadcast over angles."""
    ms = kin.mass_properties
    return ms.mass[:, None], ms.com[:, None, :, 0], ms.com[:, None, :, 1], ms.inertia[:, None]


def group_order(mech: Mechanism) -> list[tuple[list[int], list[int]]]:
    """The links of each Assur group and the constraint rows it owns (the rows between its links
    and the links placed before it), in solving order."""
    rows = build_rows(mech.pair_type, mech.pair_links, mech.drive_pair)
    placed: set[int] = {0}
    owned: list[tuple[list[int], list[int]]] = []
    for group in mech.structure.groups:
        links = set(group.links)
        owned.append((list(group.links), group_rows(rows, placed, links)))
        placed |= links
    return owned


def solve_reactions(kin: Kinematics, loads: Loads, jac: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Multipliers of every constraint row ``(V, A, m)``, group by group from the last group back,
    and the generalised force the pairs put on the frame ``(V, A, 3)`` (force, moment about the origin);
    ``jac`` the constraints' Jacobian at ``kin`` where it is known already (:func:`jacobian`).

    Where a group's system is singular (a dead point) its reactions are NaN.
    """
    lam, frame = balance(kin, loads.total[None], jac)
    return lam[0], frame[0]


def jacobian(kin: Kinematics) -> np.ndarray:
    """The constraints' Jacobian at the poses of ``kin``, ``(V, A, m, 3N)``: the reactions' matrix."""
    return residuals_and_jacobian(kin.pose, kin.mechanism, geom=variant_geometry(kin))[1]


def balance(kin: Kinematics, totals: np.ndarray, jac: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """:func:`solve_reactions` of ``S`` sets of loads at once, ``totals`` ``(S, V, A, N, 3)`` (each link's force and
    moment about its origin): the multipliers ``(S, V, A, m)`` and the frame's generalised force ``(S, V, A, 3)``.
    The reactions are linear in the loads: one Jacobian and one factorisation of each group's matrix serve every
    set (the friction's responses to each pair's friction, :mod:`linkwork.kinetostatics.friction`)."""
    m = kin.mechanism
    jac = jacobian(kin) if jac is None else jac
    owned = group_order(m)
    rhs_all = -np.moveaxis(totals.reshape(totals.shape[:3] + (-1,)), 0, -1)  # (V, A, 3N, S)
    lam = np.full(jac.shape[:-1] + (len(totals),), np.nan)
    done: list[int] = []
    for links, sel in reversed(owned):
        cols = np.array([3 * i + k for i in links for k in range(3)])
        rhs = rhs_all[..., cols, :]
        if done:  # the reactions known, as loads: (V, A, 3n, r) @ (V, A, r, S)
            rows = np.array(done)
            rhs = rhs - np.matmul(np.swapaxes(jac[..., rows[:, None], cols], -1, -2), lam[..., rows, :])
        mat = np.swapaxes(jac[..., np.array(sel)[:, None], cols], -1, -2)  # (V, A, 3n, 3n): a column per row
        lam[..., sel, :] = _solve(mat, rhs)
        done += sel
    frame = np.matmul(np.swapaxes(jac[..., :3], -1, -2), lam)  # (V, A, 3, S)
    return np.moveaxis(lam, -1, 0), np.moveaxis(frame, -1, 0)


#: Smallest ratio of a group matrix's least singular value to its largest of a solvable group.
RATIO = 1e-9


def _solve(mat: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """Batched square solves of ``mat`` ``(..., n, n)`` for the columns of ``rhs`` ``(..., n, S)``; NaN where a matrix
    is singular (:func:`solvable`) or not finite."""
    good = np.isfinite(mat).all(axis=(-1, -2)) & np.isfinite(rhs).all(axis=(-1, -2))
    out = np.full(rhs.shape, np.nan)
    if not good.any():
        return out
    a, b = mat[good], rhs[good]
    n, s = a.shape[-1], b.shape[-1]
    try:  # the solution and the inverse from one factorisation
        both = np.linalg.solve(a, np.concatenate([b, np.broadcast_to(np.eye(n), a.shape)], axis=-1))
    except np.linalg.LinAlgError:  # an exactly singular matrix in the batch
        both = None
    ok = solvable(a, None if both is None else both[..., s:])
    x = np.full(b.shape, np.nan)
    if both is not None:
        x[ok] = both[ok, :, :s]
    elif ok.any():
        x[ok] = np.linalg.solve(a[ok], b[ok])
    out[good] = x
    return out


def solvable(a: np.ndarray, inverse: np.ndarray | None = None) -> np.ndarray:
    """Whether each matrix of ``a`` ``(..., n, n)`` is solvable: its least singular value over its largest above
    :data:`RATIO`.  With its ``inverse`` the singular values are needed only where the Frobenius norms leave it
    open: the condition number k lies between ``|A|_F |A^-1|_F / n`` and ``|A|_F |A^-1|_F``, so a product
    under ``1 / RATIO`` is solvable and one of ``n / RATIO`` or over is not (a factorisation costs a seventh of a
    decomposition into singular values)."""
    if inverse is None:
        sv = np.linalg.svd(a, compute_uv=False)
        return sv[..., -1] > RATIO * np.maximum(sv[..., 0], 1e-300)
    with np.errstate(over="ignore", invalid="ignore"):
        product = np.linalg.norm(a, axis=(-2, -1)) * np.linalg.norm(inverse, axis=(-2, -1))
    ok = product < 1.0 / RATIO
    open_ = ~ok & ~(product >= a.shape[-1] / RATIO)  # NaN (an overflowed inverse) is open too
    if open_.any():
        ok[open_] = solvable(a[open_])
    return ok


def power_check(kin: Kinematics, loads: Loads) -> np.ndarray:
    """Driving torque from the power balance: (dT/dt - power of the applied loads) / drive speed.

    Needs one drive (several drives share the power in a way the balance alone does not fix);
    NaN otherwise.  Shape (V, A, D).
    """
    m = kin.mechanism
    kinetic_rate = kinetic_energy_rate(kin, loads)
    power = gravity_power(kin, loads.com_velocity) + external_power(kin, loads.external)
    rate = kin.rates[None, :, 0]
    out = np.full(kinetic_rate.shape + (m.n_drives,), np.nan)
    if m.n_drives == 1:
        with np.errstate(invalid="ignore", divide="ignore"):  # at rest the balance says nothing: NaN
            out[..., 0] = (kinetic_rate - power) / rate
    return out


def kinetic_energy_rate(kin: Kinematics, loads: Loads) -> np.ndarray:
    """dT/dt of the links, W, (V, A): the sum of m v_C . a_C + J_C omega epsilon."""
    mass, _, _, j_c = _mass_arrays(kin)
    v, a = kin.vel, kin.acc
    translation = np.sum(mass * np.sum(loads.com_velocity * loads.com_acceleration, -1), -1)
    return translation + np.sum(j_c * v[..., 2] * a[..., 2], -1)


def foundation(kin: Kinematics, frame: np.ndarray, loads: Loads) -> np.ndarray:
    """Force (x, y) and moment about the origin the machine puts on its foundation, (V, A, 3):
    the pairs' force on the frame plus the frame's own weight and the loads applied to it."""
    return frame + loads.applied[..., 0, :]


def momentum_check(kin: Kinematics, loads: Loads) -> np.ndarray:
    """The same from the theorem on the change of momentum: the foundation carries the weights of
    all links and the external loads, less the rate of change of the momentum of the links (and
    of their moment of momentum)."""
    m = kin.mechanism
    mass, _, _, j_c = _mass_arrays(kin)
    f = mass[..., None] * m.gravity_vector - mass[..., None] * loads.com_acceleration
    moment = np.sum(_cross(loads.com, f), -1) - np.sum(j_c * kin.acc[..., 2], -1)
    total = np.concatenate([np.sum(f, axis=-2), moment[..., None]], -1)
    return total + resultant(loads.external, total.shape[:-1])
