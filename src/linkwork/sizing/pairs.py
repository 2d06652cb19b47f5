"""The pairs of a mechanism as the sizing reads them: each revolute pair's force and relative turning over the
cycle, each prismatic pair's normal force and moment, at the samples of a forces result (first variant)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from linkwork.kinetostatics.reaction_forces import Forces
from linkwork.sizing.common import worst
from linkwork.structure.model import PairType


@dataclass(frozen=True)
class Pair:
    """One pair over the cycle.

    Attributes
    ----------
    label : str
        The joint's name (``joint:link`` for each pair of a compound hinge).
    kind : str
        ``revolute`` or ``prismatic``.
    links : tuple of str
        Its two links.
    force : ndarray (A,)
        The size of the force it carries, N.
    turning : ndarray (A,)
        The speed of its two links relative to each other, rad/s (revolute); 0 for a prismatic pair.
    relative : ndarray (A,)
        The angle of the first link relative to the second, unwrapped, rad (revolute).
    moment : ndarray (A,)
        The guide's moment on the slider, N m (prismatic); 0 for a revolute pair.
    sliding : ndarray (A,)
        The slider's speed along the guide, m/s (prismatic); 0 for a revolute pair.
    peak, peak_phi : float
        The largest force over the cycle refined between the samples (:func:`linkwork.kinetostatics.peaks.refine`,
        the one rule of every route), N, and the crank angle phi there, deg; ``inf`` where the force grows without
        bound towards a singular position (no part holds it); NaN where not known (the samples' peak is used).
    """

    label: str
    kind: str
    links: tuple[str, str]
    force: np.ndarray
    turning: np.ndarray
    relative: np.ndarray
    moment: np.ndarray
    sliding: np.ndarray
    peak: float = math.nan
    peak_phi: float = math.nan

    def force_max(self, phi: np.ndarray) -> tuple[float, float]:
        """The largest force (N) and the crank angle phi (deg) where it is: the refined peak (:attr:`peak`), else
        the largest sample's (``phi`` the samples' angles, deg)."""
        if math.isnan(self.peak):
            i = worst(self.force)
            return float(self.force[i]), float(phi[i])
        return self.peak, self.peak_phi


def pairs_of(f: Forces) -> list[Pair]:
    """Every revolute and prismatic pair of ``f``'s mechanism (a pin in a slot left out), first variant, with the
    peak of its force refined (:func:`~linkwork.kinetostatics.peaks.pair_force_peaks`)."""
    from linkwork.kinetostatics.peaks import pair_force_peaks
    from linkwork.motion.analysis import CrankAngles

    mech, kin = f.mechanism, f.kinematics
    refined = pair_force_peaks(f, list(range(mech.n_pairs)))
    angles = CrankAngles.of(mech)
    joints = [mech.pair_joint[k] for k in range(mech.n_pairs)]
    out = []
    for k in range(mech.n_pairs):
        a, b = (int(i) for i in mech.pair_links[k])
        if mech.link_virtual[a] or mech.link_virtual[b]:
            continue
        joint = str(mech.pair_joint[k])
        label = f"{joint}:{mech.link_names[b]}" if joints.count(joint) > 1 else joint
        force = np.hypot(*np.moveaxis(f.pair_force(k)[0], -1, 0))
        zero = np.zeros_like(force)
        names = (mech.link_names[a], mech.link_names[b])
        peak = float(refined.value[k])
        at = float(angles.phi(refined.at[k])) if angles is not None and math.isfinite(refined.at[k]) else math.nan
        if mech.pair_type[k] == PairType.REVOLUTE:
            q, v = kin.pose[0], kin.vel[0]
            turning = v[:, a, 2] - v[:, b, 2]
            relative = np.unwrap(q[:, a, 2] - q[:, b, 2])
            out.append(Pair(label, "revolute", names, force, turning, relative, zero, zero, peak, at))
        else:
            moment = np.asarray(f.multipliers[0, :, 2 * k], dtype=float)
            sliding = _sliding(f, k)
            out.append(Pair(label, "prismatic", names, force, zero, zero, moment, sliding, peak, at))
    return out


def _sliding(f: Forces, k: int) -> np.ndarray:
    """The speed of the slider along the guide of prismatic pair ``k``, m/s (first variant): the velocity of the
    slider's point of the pair less that of the guide's link at the same place, along the guide."""
    from linkwork.motion.analysis import guide_lines

    mech, kin = f.mechanism, f.kinematics
    u = guide_lines(kin, np.array([k]))[1][0, :, 0]  # (2, A)
    point = mech.point_names[int(mech.pair_points[k, 1])]
    pos, vel = kin.position(point), kin.velocity(point)
    pos, vel = (pos[0], vel[0]) if pos.ndim == 3 else (pos, vel)
    g = int(mech.pair_links[k, 0])
    q, v = kin.pose[0][:, g], kin.vel[0][:, g]  # (A, 3) the guide link's origin and its speeds
    carried = np.stack([v[:, 0] - v[:, 2] * (pos[:, 1] - q[:, 1]), v[:, 1] + v[:, 2] * (pos[:, 0] - q[:, 0])], -1)
    rel = vel - carried
    return np.abs(rel[:, 0] * u[0] + rel[:, 1] * u[1])
