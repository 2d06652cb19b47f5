"""Efficiency: where the drive's power goes, sample by sample and over the cycle.

The power balance of the mechanism (the theorem on the change of kinetic energy) splits the drive's power
``P_drive`` into

    P_drive = P_useful + P_friction + dT/dt + dPi/dt

``P_useful``: the power the file's loads (forces, moments, process loads) take from the machine (minus their
power); ``P_friction``: the power lost in the pairs, each pair's friction (constant, or in proportion to its
force: :mod:`linkwork.kinetostatics.friction`) times the speed of its relative motion; ``dT/dt`` the rate of
the links' kinetic energy and ``dPi/dt`` of their potential energy (minus the weights' power).

The instantaneous efficiency is ``1 - P_friction / P_drive`` where the drive gives power (``P_drive > 0``;
NaN elsewhere); the cycle's is the work of the useful loads over the drive's work,
``W_useful / W_drive``, over the samples (a whole turn of the crank: its kinetic and potential energy come
back, and it is ``1 - W_friction / W_drive``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from linkwork.kinetostatics.external import power as external_power
from linkwork.kinetostatics.external import relative_motion
from linkwork.kinetostatics.reactions import gravity_power, kinetic_energy_rate

if TYPE_CHECKING:
    from linkwork.kinetostatics.reaction_forces import Forces


@dataclass(frozen=True)
class Efficiency:
    """The powers of the balance over the samples, in W; shapes as in :class:`~linkwork.kinetostatics.Forces`:
    ``(V, A, ...)``, the variant axis dropped for a single mechanism (written ``(..., A)`` below).

    Attributes
    ----------
    drive : ndarray (..., A)
        The drives' power: torque times angular speed (force times speed for a linear drive).
    useful : ndarray (..., A)
        The power the file's loads take (minus their power; friction apart).
    joints : tuple of str
        The joints with friction, in the order of the file.
    losses : ndarray (..., A, J)
        The power lost to friction in each of ``joints`` (all its pairs), >= 0.
    kinetic : ndarray (..., A)
        dT/dt of the links.
    potential : ndarray (..., A)
        dPi/dt of the links' weights.
    step : ndarray (A,)
        The time each sample stands for, s, in the cycle's works (:meth:`work`).
    """

    drive: np.ndarray
    useful: np.ndarray
    joints: tuple[str, ...]
    losses: np.ndarray
    kinetic: np.ndarray
    potential: np.ndarray
    step: np.ndarray

    @property
    def friction(self) -> np.ndarray:
        """The power lost to friction in all the pairs, W, (..., A)."""
        return np.sum(self.losses, -1)

    @property
    def imbalance(self) -> np.ndarray:
        """``P_drive - P_useful - P_friction - dT/dt - dPi/dt``, W, (..., A): zero but for rounding."""
        return self.drive - self.useful - self.friction - self.kinetic - self.potential

    @property
    def instantaneous(self) -> np.ndarray:
        """``1 - P_friction / P_drive`` where the drive gives power, NaN elsewhere, (..., A)."""
        giving = self.drive > 0
        with np.errstate(invalid="ignore", divide="ignore"):
            return np.where(giving, 1.0 - self.friction / np.where(giving, self.drive, 1.0), np.nan)

    def work(self, power: np.ndarray) -> np.ndarray:
        """The work (J) of ``power`` over the samples, ``(...)`` of ``(..., A)`` (``(..., J)`` of the
        :attr:`losses`): each sample's power times the time it stands for (:attr:`step`), NaN where a sample
        has none."""
        axis = -1 if power.ndim == self.drive.ndim else -2
        step = self.step.reshape((-1,) + (1,) * (-1 - axis))
        return np.sum(power * step, axis=axis)

    @property
    def cycle(self) -> np.ndarray:
        """The cycle's efficiency ``W_useful / W_drive``, ``(...)`` (a 0-d array for one mechanism); NaN where
        the drive does no work."""
        drive = self.work(self.drive)
        with np.errstate(invalid="ignore", divide="ignore"):
            return np.where(drive > 0, self.work(self.useful) / np.where(drive > 0, drive, 1.0), np.nan)


def efficiency(f: Forces) -> Efficiency:
    """The :class:`Efficiency` of a :class:`~linkwork.kinetostatics.reaction_forces.Forces` result."""
    kin = f.kinematics
    drive = np.sum(f.driving_torque_all * kin.rates[None], -1)
    joints, losses = pair_losses(f)
    friction = np.sum(losses, -1)
    useful = -(external_power(kin, f.external) + friction)
    kinetic = kinetic_energy_rate(kin, f.loads)
    potential = -gravity_power(kin, f.loads.com_velocity)
    out = f._out
    return Efficiency(
        out(drive), out(useful), joints, out(losses), out(kinetic), out(potential), _steps(kin.angles, kin.rates[:, 0])
    )


def pair_losses(f: Forces) -> tuple[tuple[str, ...], np.ndarray]:
    """The joints with friction (constant, or in proportion to the force) and the power lost in each, W,
    ``(V, A, J)``: the friction's size times the speed of its pair's relative motion."""
    kin, mech = f.kinematics, f.mechanism
    parts: list[tuple[str, np.ndarray]] = []
    for load in mech.loads:
        if load.kind == "friction":
            parts.append((mech.pair_joint[load.pair], load.value * np.abs(relative_motion(kin, load.pair))))
    if f.friction is not None:
        loss = f.friction.loss
        parts += [(p.joint, loss[..., j]) for j, p in enumerate(f.friction.pairs)]
    joints = tuple(j for j in mech.joint_names if any(name == j for name, _ in parts)) or tuple(
        dict.fromkeys(name for name, _ in parts)
    )
    out = np.zeros(kin.valid_all.shape + (len(joints),))
    for name, loss in parts:
        out[..., joints.index(name)] += loss
    return joints, out


def _steps(angles: np.ndarray, rates: np.ndarray) -> np.ndarray:
    """The time each sample of the drive coordinates ``angles`` ``(A,)`` at ``rates`` stands for: a whole turn
    of equal steps (a periodic grid) gives each ``step / |rate|``; other samples the trapezoid rule's weights
    in time."""
    n = len(angles)
    with np.errstate(invalid="ignore", divide="ignore"):
        dt = np.diff(angles) / rates[:-1] if n > 1 else np.zeros(0)
    if n > 2 and np.allclose(np.abs(np.diff(angles)), 2 * math.pi / n, rtol=1e-9, atol=0):
        return np.abs(np.full(n, 2 * math.pi / n) / rates)
    out = np.zeros(n)
    out[:-1] += np.abs(dt) / 2
    out[1:] += np.abs(dt) / 2
    return out
