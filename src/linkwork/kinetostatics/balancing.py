"""Balancing the shaking force with counterweights on links that turn about frame pivots.

The shaking force is the resultant of the inertia forces of the moving links,
``-sum m_i a_Ci``: what the foundation feels beyond the weights.  A
counterweight of mass ``mu`` on link ``j``, at the local vector ``c`` from the
link's pivot on the frame, adds ``-mu d2/dt2 (R(theta_j) c)`` to it, which is
linear in the mass-radius vector ``p = mu c``.  The ``p`` of all counterweights
together therefore follow from one linear least-squares problem over the cycle:
minimise the sum of the squared shaking forces (full balancing; it is exact,
a zero residual, where the links chosen can balance the mechanism fully, as
the crank and rocker of a four-bar can), or of their first harmonics in the
crank angle (first-harmonic balancing, the usual choice for a slider-crank,
whose slider a rotating counterweight can balance only in part).

The balanced mechanism (links with the counterweights' mass, centre of mass
and inertia added, as point masses) is then solved again in full, so the
figures after balancing (shaking force and moment, driving torque, joint
reactions) come from the same solver as those before, independently of the
least-squares step.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from linkwork.angles import wrap
from linkwork.did_you_mean import suggest
from linkwork.errors import LinkworkError
from linkwork.kinetostatics.peaks import pair_force_peaks, shaking_peaks, torque_peak
from linkwork.kinetostatics.reaction_forces import Forces, forces
from linkwork.limits import TURN_STEPS
from linkwork.structure.model import Mechanism, PairType, frozen, one_crank


@dataclass(frozen=True)
class Counterweight:
    """A counterweight on ``link``: mass-radius product ``mass_radius`` (kg m) at ``angle`` (rad)
    from the link's local x axis, measured from its pivot ``pivot`` (a frame joint); ``mass`` (kg)
    at ``radius`` (m)."""

    link: str
    pivot: str
    mass_radius: float
    angle: float
    radius: float
    mass: float

    def as_dict(self) -> dict[str, Any]:
        return {
            "link": self.link,
            "pivot": self.pivot,
            "mass_radius_kg_m": self.mass_radius,
            "angle_deg": math.degrees(self.angle),
            "radius_m": self.radius,
            "mass_kg": self.mass,
        }


@dataclass(frozen=True)
class Balance:
    """Counterweights and the forces before and after.

    Attributes
    ----------
    counterweights : list of Counterweight
    harmonic : int or None
        1 for first-harmonic balancing, None for full.
    mechanism : Mechanism
        The balanced mechanism.
    before, after : Forces
    """

    counterweights: list[Counterweight]
    harmonic: int | None
    mechanism: Mechanism
    before: Forces
    after: Forces

    def summary(self) -> dict[str, dict[str, float]]:
        """Peak and RMS shaking force (N), peak shaking moment (N m), peak driving torque (N m), and
        the largest force in any revolute pair (N), before and after; the peaks refined between the samples
        (:mod:`linkwork.kinetostatics.peaks`), the RMS over the samples."""

        def figures(f: Forces) -> dict[str, float]:
            force = np.hypot(*np.moveaxis(f.shaking_force, -1, 0))
            revolute = [k for k in range(f.mechanism.n_pairs) if f.mechanism.pair_type[k] == PairType.REVOLUTE]
            shaking = shaking_peaks(f).value
            return {
                "shaking_force_peak": float(shaking[0]),
                "shaking_force_rms": float(np.sqrt(np.nanmean(force**2))),
                "shaking_moment_peak": float(abs(shaking[1])),
                "driving_torque_peak": float(abs(torque_peak(f).value[0])),
                "pair_force_peak": float(np.nanmax(pair_force_peaks(f, revolute).value)) if revolute else 0.0,
            }

        return {"before": figures(self.before), "after": figures(self.after)}


def _pivot(mech: Mechanism, link: int) -> tuple[int, int]:
    """(pair, point) of the revolute pair joining ``link`` to the frame."""
    for k in range(mech.n_pairs):
        a, b = (int(x) for x in mech.pair_links[k])
        if mech.pair_type[k] == PairType.REVOLUTE and {a, b} == {0, link}:
            return k, int(mech.pair_points[k, 1 if b == link else 0])
    raise LinkworkError(
        f'link "{mech.link_names[link]}" does not turn about a frame pivot: counterweights go on links '
        "jointed to the frame by a revolute pair (crank, rocker)"
    )


def balance(
    mech: Mechanism,
    links: list[str] | tuple[str, ...],
    *,
    harmonic: int | None = None,
    radius: dict[str, float] | float | None = None,
    steps: int = TURN_STEPS,
    speed: npt.ArrayLike | None = None,
) -> Balance:
    """Counterweights on ``links`` that cancel the shaking force (``harmonic=None``) or its first
    harmonic in the crank angle (``harmonic=1``).

    Parameters
    ----------
    mech : Mechanism
        A compiled mechanism (``linkwork.balance`` also takes a path, an example name or a Spec).
    links : list of str
        The links that carry a counterweight, each turning about a frame pivot.
    harmonic : int, optional
        None: the whole shaking force, by least squares over the turn; 1: its first harmonic.
    radius : float or dict of str to float, optional
        The distance of each counterweight from its pivot, m (one value, or one per link); default the
        distance of the link's farthest point.
    steps : int
        Crank angles over one turn; default 360.
    speed : array_like, optional
        The drive's uniform angular speed, rad/s; default the file's.

    Returns
    -------
    Balance
        The counterweights (mass, kg; radius, m; angle, rad on the link) and the shaking force, moment,
        driving torque and pair forces before and after (``summary``).

    Examples
    --------
    >>> import linkwork as lw
    >>> b = lw.balance("four-bar", ["crank"], steps=36)
    >>> b.counterweights[0].link, round(b.counterweights[0].radius, 3)
    ('crank', 0.1)
    """
    counterweight_links(mech, links, harmonic, steps)
    return balance_of(forces(mech, steps=steps, speed=speed), links, harmonic=harmonic, radius=radius)


def balance_of(
    before: Forces,
    links: list[str] | tuple[str, ...],
    *,
    harmonic: int | None = None,
    radius: dict[str, float] | float | None = None,
) -> Balance:
    """The counterweights of :func:`balance` from the forces ``before`` of a mechanism over equal steps of a
    whole turn of its crank (:func:`linkwork.forces`, or a study's :attr:`~linkwork.study.Study.forces`),
    without solving them again; the forces after are solved at the same drive angles and speed.

    Raises
    ------
    LinkworkError
        As :func:`balance`; and for forces of several variants (a sweep's), or at other angles than equal steps
        of a whole turn.
    """
    kin = before.kinematics
    mech = kin.mechanism
    index = counterweight_links(mech, links, harmonic, len(kin.angles))
    if kin.valid_all.shape[0] != 1:
        raise LinkworkError("balancing takes the forces of one mechanism, not of several variants")
    step = np.abs(np.diff(kin.angles))
    if not np.allclose(step, 2 * np.pi / len(kin.angles), rtol=0, atol=1e-9):
        raise LinkworkError("balancing takes the forces over equal steps of a whole turn of the crank")
    if not np.all(kin.valid):
        raise LinkworkError("the mechanism does not assemble over the whole turn: it cannot be balanced over it")
    p = _mass_radius(before, index, harmonic)
    mass, com, inertia = (np.array(x, dtype=float) for x in (mech.link_mass, mech.link_com, mech.link_inertia))
    weights = []
    for n, j in enumerate(index):
        r = radius.get(mech.link_names[j]) if isinstance(radius, dict) else radius
        weight, at = _counterweight(mech, j, p[2 * n], p[2 * n + 1], r)
        weights.append(weight)
        if weight.mass > 0:
            total = mass[j] + weight.mass
            new_com = (mass[j] * com[j] + weight.mass * at) / total
            inertia[j] += mass[j] * np.sum((com[j] - new_com) ** 2) + weight.mass * np.sum((at - new_com) ** 2)
            mass[j], com[j] = total, new_com
    balanced = dataclasses.replace(mech, link_mass=frozen(mass), link_com=frozen(com), link_inertia=frozen(inertia))
    after = forces(balanced, np.array(kin.drive), speed=np.array(kin.rates[0]))
    return Balance(weights, harmonic, balanced, before, after)


def counterweight_links(
    mech: Mechanism, links: list[str] | tuple[str, ...], harmonic: int | None, steps: int
) -> list[int]:
    """The indices of the links named for counterweights, the arguments of :func:`balance` checked (before any
    solving: ``steps`` is the number of equal steps of the turn it will be balanced over).

    Raises
    ------
    LinkworkError
        For a harmonic other than 1 or None, a mechanism without one crank, fewer than 8 steps, no links or
        an unknown one.
    """
    if harmonic not in (None, 1):
        raise LinkworkError(f"harmonic: expected 1 (first-harmonic balancing) or None (full), got {harmonic}")
    if not one_crank(mech):
        raise LinkworkError("balancing needs one crank (a revolute drive) turning uniformly")
    if steps < 8:
        raise LinkworkError(f"steps: expected at least 8 angles over the turn, got {steps}")
    if not links:
        raise LinkworkError("give at least one link for a counterweight")
    for name in links:
        if name not in mech.link_names[1:]:
            raise LinkworkError(f'no link "{name}"{suggest(name, mech.link_names[1:])}')
    return [mech.link_names.index(name) for name in links]


def _mass_radius(before: Forces, index: list[int], harmonic: int | None) -> np.ndarray:
    """The mass-radius vectors ``p`` (kg m), ``(2 k,)`` (x, y of each link's in turn, local to it), whose
    counterweights cancel the shaking force of ``before`` (or its first harmonic), by least squares over
    its angles."""
    kin = before.kinematics
    theta, w, e = kin.pose[0, :, :, 2], kin.vel[0, :, :, 2], kin.acc[0, :, :, 2]
    columns = []
    for j in index:
        c, s = np.cos(theta[:, j]), np.sin(theta[:, j])
        ww, ee = w[:, j] ** 2, e[:, j]
        # d2/dt2 of R(theta) e_x and R(theta) e_y
        columns.append(np.stack([-ee * s - ww * c, ee * c - ww * s], -1))
        columns.append(np.stack([-ee * c + ww * s, -ee * s - ww * c], -1))
    a = np.stack(columns, -1)  # (A, 2, 2k): acceleration of the mass moment per unit p
    b = -before.shaking_force  # sum m a_C, (A, 2)
    if harmonic == 1:
        phi = kin.angles
        basis = np.stack([np.cos(phi), np.sin(phi)], -1) * math.sqrt(2.0 / len(phi))  # orthonormal on the grid
        a = _first_harmonic(a, basis)
        b = _first_harmonic(b, basis)
    p, *_ = np.linalg.lstsq(a.reshape(-1, a.shape[-1]), -b.reshape(-1), rcond=None)
    return p


def _counterweight(
    mech: Mechanism, j: int, px: float, py: float, radius: float | None
) -> tuple[Counterweight, np.ndarray]:
    """The counterweight of mass-radius vector ``(px, py)`` on link ``j`` at ``radius`` from its pivot (default:
    the distance of the link's farthest point), and where it is in the link's coordinates ``(2,)``."""
    k, point = _pivot(mech, j)
    pivot_local = mech.point_local[point]
    own = mech.point_local[mech.point_link == j]
    r = float(radius) if radius is not None else float(np.max(np.hypot(*(own - pivot_local).T)))
    if not r > 0:
        raise LinkworkError(f'radius of the counterweight on "{mech.link_names[j]}": expected a positive length')
    mr = math.hypot(px, py)
    mu = mr / r
    weight = Counterweight(mech.link_names[j], mech.pair_joint[k], mr, wrap(math.atan2(py, px)), r, mu)
    at = pivot_local + np.array([px, py]) / mr * r if mu > 0 else pivot_local
    return weight, at


def _first_harmonic(x: np.ndarray, basis: np.ndarray) -> np.ndarray:
    """Projection of series ``x`` (A, ...) onto cos and sin of the crank angle."""
    coef = np.einsum("ak,a...->k...", basis, x)
    return np.einsum("ak,k...->a...", basis, coef)
