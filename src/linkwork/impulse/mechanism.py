"""Impact of a point of a one-degree-of-freedom mechanism against a surface at rest.

In the pose of impact every velocity is the crank speed ``psi'`` times its
transfer function (the kinematics at unit crank speed), so the mechanism's
mass matrix reduces to the reduced inertia ``J`` and an impulse ``S`` at the
point K (transfer function ``G_K``) is the generalised impulse ``G_K . S``:

    J (psi'_+ - psi'_-) = G_K . S,   S = s_n (n + phi t),   psi'_+ = -R psi'_-

(``R`` as in seed 004, on the speed of every link alike; the drive gives no
impulse: its torque is finite).  The jump of every link's velocity is then
``(psi'_+ - psi'_-)`` times its transfer function, and the impulsive
reactions of all pairs follow from the same group-by-group solution as the
forces (:mod:`linkwork.kinetostatics.reactions`), with the impulse at K as the
applied load and the change of momentum of every link in place of the
inertia loads; the drive row's multiplier, the drive's impulse, comes out
zero, a check.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, NamedTuple

import numpy as np
import numpy.typing as npt

from linkwork.errors import LinkworkError
from linkwork.impulse.rocker import RockerImpact, rocker_impact, sliding_direction
from linkwork.kinetostatics.free_body import contacts
from linkwork.kinetostatics.reaction_forces import Forces
from linkwork.kinetostatics.reactions import Loads, inertia_and_gravity, solve_reactions
from linkwork.motion import Kinematics, kinematics
from linkwork.structure.model import Mechanism, PairType


@dataclass(frozen=True)
class Impact:
    """The impact of a mechanism in one pose.

    Attributes
    ----------
    impulse : ndarray (2,)
        Impulse of the surface on the striking link at K, N s.
    speed_before, speed_after : float
        Crank speed, rad/s.
    velocities_before, velocities_after : ndarray (N, 3)
        Every link's (vx, vy, omega) of its local origin.
    joints : dict
        For each joint, the impulse (x, y) that its first-named link exerts on the second, N s
        (as :meth:`~linkwork.kinetostatics.Forces.reaction` gives forces: compound hinges, their first pair).
    drive_impulse : float
        The impulse the drive would have to give (zero up to rounding: a check).
    energy_loss : float
        J.
    inertia : float
        Reduced inertia on the crank in the pose, kg m^2.
    forces : Forces
        The impulses as a :class:`~linkwork.kinetostatics.Forces` (``pair_force`` in N s).
    ideal_com : ndarray (2,) or None
        Where the striking link's centre of mass would have to be (its mass and its inertia about
        its pivot kept) for its frame pivot to feel no impulse; None unless it turns about one.
    sliding_reverses : bool
        True where friction acts and the striker's sliding on the surface changes direction within
        the blow (in one degree of freedom every velocity scales by -R, so any R > 0 reverses it):
        the friction impulse is then taken one way throughout, as in seed 004's model, which a
        Coulomb law that followed the sliding would not give.
    """

    impulse: np.ndarray
    speed_before: float
    speed_after: float
    velocities_before: np.ndarray
    velocities_after: np.ndarray
    joints: dict[str, np.ndarray]
    drive_impulse: float
    energy_loss: float
    inertia: float
    phi: float
    forces: Forces
    ideal_com: np.ndarray | None = None
    sliding_reverses: bool = False

    def on(self, joint: str, link: str) -> np.ndarray:
        """Impulse (x, y) of a joint on ``link`` (of all its other links together), N s; see
        :meth:`~linkwork.kinetostatics.Forces.reaction`."""
        return self.forces.reaction(joint, on=link)[0]


@dataclass(frozen=True)
class BlowSetup:
    """What a blow needs, from the file's ``impact:`` section and the caller's arguments.

    Attributes
    ----------
    at : str
        The striking point, ``link.point``.
    normal : ndarray (2,)
        Unit normal of the surface, out of it (towards the striker).
    omega_before : float or None
        Angular speed of ``link`` before the blow, rad/s (None where not given: the working cycle
        finds it).
    restitution, friction : float
        R and f.
    link : str or None
        The link whose angular speed ``omega_before`` is (None: the link of ``at``).
    """

    at: str
    normal: np.ndarray
    omega_before: float | None
    restitution: float
    friction: float
    link: str | None


def blow_setup(
    mech: Mechanism,
    *,
    at: str | None = None,
    normal: npt.ArrayLike | float | None = None,
    omega_before: float | None = None,
    restitution: float | None = None,
    friction: float | None = None,
    link: str | None = None,
    need_speed: bool = True,
) -> BlowSetup:
    """The blow's inputs: each argument given here, else the file's ``impact:`` section's value
    (``normal`` as a vector or an angle in rad; the file gives an angle).

    Raises
    ------
    LinkworkError
        Naming every input neither given nor in the file, or R outside [0, 1] or f < 0.
    """
    blow = mech.blow
    at = at if at is not None else (blow.at if blow is not None else None)
    if normal is None and blow is not None:
        normal = blow.normal
    if omega_before is None and blow is not None:
        omega_before = blow.omega
    restitution = restitution if restitution is not None else (blow.restitution if blow is not None else None)
    friction = friction if friction is not None else (blow.friction if blow is not None else 0.0)
    link = link if link is not None else (blow.link if blow is not None else None)
    missing = [name for name, value in (("at", at), ("normal", normal), ("restitution", restitution)) if value is None]
    if need_speed and omega_before is None:
        missing.append("omega_before")
    if missing:
        raise LinkworkError(
            f"the blow needs {', '.join(missing)}: give them as arguments or in the file's impact: section"
        )
    assert at is not None and normal is not None and restitution is not None and friction is not None
    if not (0 <= restitution <= 1 and friction >= 0):
        raise LinkworkError(f"expected 0 <= R <= 1 and friction >= 0, got R = {restitution}, f = {friction}")
    if np.ndim(normal) == 0:
        angle = float(np.asarray(normal))
        n = np.array([math.cos(angle), math.sin(angle)])
    else:
        n = np.asarray(normal, dtype=float)
    length = float(np.linalg.norm(n)) if n.shape == (2,) else 0.0
    if not (length > 0 and math.isfinite(length)):
        raise LinkworkError(f"normal: expected a non-zero vector (x, y) or an angle, got {normal!r}")
    return BlowSetup(at, n / length, omega_before, float(restitution), float(friction), link)


def impact(
    mech: Mechanism,
    *,
    at: str | None = None,
    normal: npt.ArrayLike | float | None = None,
    omega_before: float | None = None,
    restitution: float | None = None,
    friction: float | None = None,
    link: str | None = None,
    angle: float | None = None,
    slip: float | None = None,
) -> Impact:
    """The impact of point ``at`` (``link.point``) on a surface at rest with outward ``normal``.

    Parameters
    ----------
    mech : Mechanism
        A compiled mechanism (``linkwork.impact`` also takes a path, an example name or a Spec).
    at : str, optional
        The point that strikes, ``link.point``; default the file's.
    normal : array_like or float, optional
        The surface's outward normal, a vector or an angle, rad.
    omega_before : float, optional
        The angular speed of ``link`` before the impact, rad/s.
    restitution : float, optional
        Newton's coefficient of restitution R, 0 to 1.
    friction : float, optional
        The coefficient of friction f at the point of impact.
    link : str, optional
        The link whose speed ``omega_before`` gives; default the link of ``at``.
    angle : float, optional
        The crank angle of the pose, rad; default the assembly pose.
    slip : float, optional
        As in :func:`~linkwork.impulse.rocker_impact`.

    Returns
    -------
    Impact
        The impulses (N s) at the point and in every pair, the speeds before and after, the energy lost (J).

    Examples
    --------
    >>> import linkwork as lw
    >>> hit = lw.impact("percussion-rocker")
    >>> round(float(hit.speed_after), 2)
    40.97

    ``mech``: a compiled Mechanism (``linkwork.impact`` also takes a path, an example name or a
    Spec: :mod:`linkwork.api`).  Every
    argument of the blow not given is the file's (its ``impact:`` section; see :func:`blow_setup`):
    ``normal`` a vector or an angle (rad); ``omega_before`` the angular speed of ``link``
    (default: the link of ``at``) before the impact, rad/s; ``restitution`` R and ``friction`` f.
    ``angle``: the crank angle of the pose (default: the assembly pose); ``slip`` as in
    :func:`~linkwork.impulse.rocker_impact`.
    """
    if mech.n_drives != 1:
        raise LinkworkError("impact needs a mechanism of one degree of freedom (one drive)")
    setup = blow_setup(
        mech, at=at, normal=normal, omega_before=omega_before, restitution=restitution, friction=friction, link=link
    )
    n, restitution, friction = setup.normal, setup.restitution, setup.friction
    phi0 = float(mech.drive_start[0]) if angle is None else float(angle)
    kin = kinematics(mech, np.array([phi0]), speed=1.0)
    if not bool(np.all(kin.valid)):
        raise LinkworkError(f"the mechanism does not assemble at {math.degrees(phi0):.3f} deg")
    point = striking_point(kin, setup.at)
    w_before = _crank_speed(kin, setup, point.link)
    pos, g_k = point.position[0], point.velocity[0]
    t = np.array([n[1], -n[0]])
    if not float(g_k @ n) * w_before < 0:
        raise LinkworkError(
            f'"{setup.at}" does not move towards the surface: its normal velocity is {g_k @ n * w_before:.6g} m/s'
        )
    sliding = float(g_k @ t) * w_before
    tiny = float(1e-12 * abs(w_before) * np.linalg.norm(g_k))
    phi = -friction * sliding_direction(sliding, tiny, slip)
    v = kin.vel[0, 0]
    inertia = pose_inertia(kin)
    jump = -(1.0 + restitution) * w_before
    s_n = inertia * jump / float(g_k @ (n + phi * t))
    impulse = s_n * (n + phi * t)
    forces, lam, joints = impulsive_reactions(kin, point.link, pos, impulse, jump)
    before = v * w_before
    ideal = _ideal_com(mech, forces, point.link, impulse, v[point.link, 2] * jump)
    return Impact(
        impulse,
        w_before,
        -restitution * w_before,
        before,
        -restitution * before,
        joints,
        float(lam[0, 0, 2 * mech.n_pairs]),
        0.5 * inertia * w_before**2 * (1 - restitution**2),
        inertia,
        phi,
        forces,
        ideal,
        bool(friction > 0 and restitution > 0 and abs(sliding) > tiny),
    )


class StrikingPoint(NamedTuple):
    """The striking point of the (first) variant of a kinematics result: the index of its ``link``, its
    ``position`` (A, 2) and its ``velocity`` (A, 2) at the samples (m, m/s in the result's speed)."""

    link: int
    position: np.ndarray
    velocity: np.ndarray


def striking_point(kin: Kinematics, at: str) -> StrikingPoint:
    """The point ``at`` (``link.point`` or a joint's name) in ``kin``."""
    mech = kin.mechanism
    p = kin.point_index(at)
    pos, vel, _ = kin.motion_of(mech.point_names[p])
    return StrikingPoint(int(mech.point_link[p]), pos[0], vel[0])


def _crank_speed(kin: Kinematics, setup: BlowSetup, striker: int) -> float:
    """The crank speed before the blow (``kin`` at unit crank speed, in its single pose) at which the
    link of the blow turns at ``omega_before``."""
    assert setup.omega_before is not None
    name = setup.link if setup.link is not None else kin.mechanism.link_names[striker]
    gain = float(kin.omega(name)[0])  # the link's angular speed per unit crank speed
    if abs(gain) < 1e-12:
        raise LinkworkError(f'link "{name}" does not turn in this pose: give the speed of another link')
    return setup.omega_before / gain


def joint_links(mech: Mechanism) -> dict[str, tuple[str, str]]:
    """For each joint, its (first, second) link names in the order the joint names them."""
    members = mech.pair_links if mech.pair_members is None else mech.pair_members
    return {
        name: (mech.link_names[int(members[k, 0])], mech.link_names[int(members[k, 1])])
        for name, k in mech.first_pairs().items()
    }


def pose_inertia(kin: Kinematics) -> float:
    """Reduced inertia (kg m^2) on the crank in the single pose of ``kin`` (kinematics at unit
    crank speed), from the velocities of the centres of mass."""
    mech = kin.mechanism
    v = kin.vel[0, 0]
    vc = inertia_and_gravity(kin).com_velocity[0, 0]
    return float(np.sum(mech.link_mass * np.sum(vc * vc, -1) + mech.link_inertia * v[:, 2] ** 2))


def impulsive_reactions(
    kin: Kinematics, striker: int, at: np.ndarray, impulse: np.ndarray, jump: float
) -> tuple[Forces, np.ndarray, dict[str, np.ndarray]]:
    """Impulsive reactions of every pair in the single pose of ``kin`` (kinematics at unit crank
    speed) when the impulse ``impulse`` (N s, global axes) acts on link ``striker`` at the point
    ``at`` and the crank speed jumps by ``jump`` (in ``kin``'s unit of speed).

    The change of momentum of every link enters as an inertia load.  Returns the impulses as a
    :class:`~linkwork.kinetostatics.Forces` (``pair_force`` in N s), the raw multipliers (the drive
    row ``[..., 2 n_pairs]`` is the drive's impulse on the crank, N m s) and, for each joint, the
    impulse its first-named link exerts on the second (compound hinges: their first pair).
    """
    mech = kin.mechanism
    q, v = kin.pose[0, 0], kin.vel[0, 0]
    state = inertia_and_gravity(kin)
    r = state.com[0, 0] - q[:, :2]  # origin -> centre of mass of every link
    vc = state.com_velocity[0, 0]
    # impulsive loads: the impulse at K, and the change of momentum of every link (as an inertia load)
    applied = np.zeros((1, 1, mech.n_links_total, 3))
    arm = np.asarray(at) - q[striker, :2]
    applied[0, 0, striker] = [impulse[0], impulse[1], arm[0] * impulse[1] - arm[1] * impulse[0]]
    dm = mech.link_mass[:, None] * vc * jump  # m dv_C
    momentum = np.concatenate(
        [-dm, (-(r[:, 0] * dm[:, 1] - r[:, 1] * dm[:, 0]) - mech.link_inertia * v[:, 2] * jump)[:, None]], -1
    )
    loads = Loads(applied, momentum[None, None], r[None, None], vc[None, None], np.zeros_like(vc)[None, None])
    lam, frame = solve_reactions(kin, loads)
    forces = Forces(kin, lam, frame)
    joints = {joint: forces.reaction(joint)[0] for joint in mech.first_pairs()}
    return forces, lam, joints


def _ideal_com(mech: Mechanism, forces: Forces, link: int, impulse: np.ndarray, d_omega: float) -> np.ndarray | None:
    """m (C - O) d_omega z x = the impulses on the link other than its pivot's: solved for C."""
    pivot = None
    for k in range(mech.n_pairs):
        a, b = (int(x) for x in mech.pair_links[k])
        if mech.pair_type[k] == PairType.REVOLUTE and {a, b} == {0, link}:
            pivot = k
    if pivot is None or d_omega == 0:
        return None
    total = impulse.copy()
    support = None
    for c in contacts(forces):
        if c.on != link or c.drive:
            continue
        if c.other == 0 and c.joint == mech.pair_joint[pivot]:
            support = c.point[0, 0]
            continue
        total = total + c.force[0, 0]
    w = total / (mech.link_mass[link] * d_omega)
    return support + np.array([w[1], -w[0]])


def reduced_model(mech: Mechanism, *, at: str, rod_joint: str, **kw: Any) -> RockerImpact:
    """The model of seed 004 for the same blow: the striking link turning about its frame pivot,
    the link jointed to it at ``rod_joint`` replaced by its whole mass at that joint (the others
    left out); keyword arguments as for :func:`~linkwork.impulse.rocker_impact`."""
    p = mech.point_index(at)
    rocker = int(mech.point_link[p])
    pivot = None
    rod = None
    for k in range(mech.n_pairs):
        a, b = (int(x) for x in mech.pair_links[k])
        if mech.pair_type[k] == PairType.REVOLUTE and {a, b} == {0, rocker}:
            pivot = int(mech.pair_points[k, 1 if b == rocker else 0])
        if mech.pair_joint[k] == rod_joint and rocker in (a, b):
            rod = (b if a == rocker else a, int(mech.pair_points[k, 0 if a == rocker else 1]))
    if pivot is None or rod is None:
        raise LinkworkError(f'"{at}" is not on a link turning about a frame pivot with a joint "{rod_joint}"')
    q = mech.pose0[rocker]
    c, s = math.cos(q[2]), math.sin(q[2])

    def world(local: np.ndarray) -> np.ndarray:
        return q[:2] + np.array([c * local[0] - s * local[1], s * local[0] + c * local[1]])

    o, com, k_pt, n_pt = (
        world(x)
        for x in (mech.point_local[pivot], mech.link_com[rocker], mech.point_local[p], mech.point_local[rod[1]])
    )
    j_o = float(mech.link_inertia[rocker] + mech.link_mass[rocker] * np.sum((com - o) ** 2))
    return rocker_impact(
        inertia=j_o,
        mass=float(mech.link_mass[rocker]),
        com=com,
        impact_point=k_pt,
        support=o,
        rod_mass=float(mech.link_mass[rod[0]]),
        rod_joint=n_pt,
        **kw,
    )
