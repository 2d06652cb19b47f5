"""Kinematic state arrays and the small vector helpers the kernels share.

The state is kept link-major, one contiguous ``(n_variants, n_angles)``
block per quantity, so that every kernel operation streams through
contiguous memory: ``q[i] = (x, y, theta)`` is the pose of link ``i`` (the
origin of its local frame and the angle of its x axis), ``v[i] = (vx, vy,
omega)`` its velocity and ``a[i] = (ax, ay, epsilon)`` its acceleration.
Plane vectors are pairs ``(x, y)`` of arrays.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

from linkwork.structure.model import Mechanism
from linkwork.structure.parameters import Geometry, soa

Vec = tuple[np.ndarray, np.ndarray]


def rot(c: np.ndarray, s: np.ndarray, v: Vec) -> Vec:
    """Rotate ``v`` by the angle whose cosine and sine are ``c`` and ``s``."""
    return c * v[0] - s * v[1], s * v[0] + c * v[1]


def perp(v: Vec) -> Vec:
    """``v`` turned by +90 degrees: ``omega x r`` is ``omega * perp(r)``."""
    return -v[1], v[0]


def add(a: Vec, b: Vec) -> Vec:
    return a[0] + b[0], a[1] + b[1]


def sub(a: Vec, b: Vec) -> Vec:
    return a[0] - b[0], a[1] - b[1]


def scale(k: np.ndarray | float, v: Vec) -> Vec:
    return k * v[0], k * v[1]


def cross(a: Vec, b: Vec) -> np.ndarray:
    return a[0] * b[1] - a[1] * b[0]


def dot(a: Vec, b: Vec) -> np.ndarray:
    return a[0] * b[0] + a[1] * b[1]


def norm(v: Vec) -> np.ndarray:
    return np.sqrt(v[0] * v[0] + v[1] * v[1])  # np.hypot is many times slower on arrays


def solve2(c1: Vec, c2: Vec, rhs: Vec) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Solve ``k1 c1 + k2 c2 = rhs`` by Cramer's rule; also returns the determinant."""
    det = cross(c1, c2)
    inv = 1.0 / det
    return cross(rhs, c2) * inv, cross(c1, rhs) * inv, det


class Flip(NamedTuple):
    """A change point a dyad's mode was followed through: the motion goes on in the other mode from
    sample ``first`` on (in the order walked from the assembly pose); ``near`` is the sample nearest
    the change point."""

    variant: int
    first: int
    near: int


class Jump(NamedTuple):
    """Samples ``sample`` and ``sample + 1`` between which a Newton-solved group jumps."""

    variant: int
    sample: int


class Inputs(NamedTuple):
    """What the NumPy kernel of a step reads besides the step and the state (:class:`linkwork.motion.groups.GroupKind`).

    Attributes
    ----------
    mech : Mechanism
    geom : Geometry
        Dimensions of the design variants.
    values, rates, accels : ndarray, shape (A, D)
        Drive coordinates (rad or m) and their first and second time derivatives.
    own : tuple of ndarray, or None
        The drive coordinate of every variant at every sample ``(V, A)`` in place of the shared
        ``values[:, 0]``, and the poses ``(N, 3, V, A)`` Newton's method starts from there (or None);
        None: the shared ``values``.
    """

    mech: Mechanism
    geom: Geometry
    values: np.ndarray
    rates: np.ndarray
    accels: np.ndarray
    own: tuple[np.ndarray, np.ndarray | None] | None = None


@dataclass
class StepRecord:
    """What solving one step of the program found at every sample: ``(V, A)`` arrays.

    Attributes
    ----------
    valid : ndarray of bool
        The step assembled.
    det : ndarray
        Its normalised Jacobian determinant (zero at a singular position).
    slack : ndarray
        Its assembly margin (negative where it does not assemble).
    branch : ndarray or None
        The assembly mode used sample by sample; None: the step's own throughout.
    flips : list of Flip
        The change points its mode was followed through.
    jumps : list of Jump
        Where a Newton-solved group jumps between samples.
    limit : ndarray of bool or None
        Where a dyad is on a singular position to rounding: its velocities there are those of the
        motion through it (not its accelerations); None: nowhere.
    """

    valid: np.ndarray
    det: np.ndarray
    slack: np.ndarray
    branch: np.ndarray | None = None
    flips: list[Flip] = field(default_factory=list)
    jumps: list[Jump] = field(default_factory=list)
    limit: np.ndarray | None = None

    def window(self, lo: int, hi: int) -> StepRecord:
        """The samples ``lo`` to ``hi`` (inclusive), renumbered from ``lo``."""
        cut = slice(lo, hi + 1)
        return StepRecord(
            self.valid[:, cut],
            self.det[:, cut],
            self.slack[:, cut],
            None if self.branch is None else self.branch[:, cut],
            [Flip(v, j - lo, i - lo) for v, j, i in self.flips if lo <= i <= hi],
            [Jump(v, j - lo) for v, j in self.jumps if lo <= j < hi],
            None if self.limit is None else self.limit[:, cut],
        )

    def take(self, samples: np.ndarray | slice) -> StepRecord:
        """The samples ``samples`` (indices ``(a,)``, or a slice) of the arrays (the change points and jumps as they
        are)."""
        return dataclasses.replace(
            self,
            valid=self.valid[:, samples],
            det=self.det[:, samples],
            slack=self.slack[:, samples],
            branch=None if self.branch is None else self.branch[:, samples],
            limit=None if self.limit is None else self.limit[:, samples],
        )

    @staticmethod
    def concatenate(parts: list[StepRecord], offsets: list[int], mode: float) -> StepRecord:
        """The records of one step over consecutive blocks of variants, the first variant of each at
        ``offsets``; ``mode``: the step's own assembly mode, of the blocks that kept it throughout."""

        def joined(arrays: list[np.ndarray | None], fill: float | bool) -> np.ndarray | None:
            if all(x is None for x in arrays):
                return None
            blocks = [np.full(p.valid.shape, fill) if x is None else x for x, p in zip(arrays, parts, strict=True)]
            return np.concatenate(blocks)

        return StepRecord(
            np.concatenate([p.valid for p in parts]),
            np.concatenate([p.det for p in parts]),
            np.concatenate([p.slack for p in parts]),
            joined([p.branch for p in parts], mode),
            [Flip(v + o, i, j) for p, o in zip(parts, offsets, strict=False) for v, i, j in p.flips],
            [Jump(v + o, j) for p, o in zip(parts, offsets, strict=False) for v, j in p.jumps],
            joined([p.limit for p in parts], False),
        )


@dataclass
class State:
    """Arrays being filled by the solve program, group by group.

    Attributes
    ----------
    q, v, a : ndarray, shape (N, 3, V, A)
        Pose, velocity and acceleration of every link.
    cos, sin : ndarray, shape (N, V, A)
        Of each link's angle, kept with the pose (the accessors of :class:`~linkwork.motion.kinematic_analysis.
        Kinematics` place points with them).
    local : ndarray, shape (P, 2, V, 1)
    origin, axis : ndarray, shape (M, 2, V, 1)
        Dimensions of the design variants (guide lines of prismatic pairs).
    valid : ndarray of bool, shape (V, A)
        Every step so far assembled.
    steps : list of StepRecord
        One for each step solved so far.
    """

    q: np.ndarray
    v: np.ndarray
    a: np.ndarray
    cos: np.ndarray
    sin: np.ndarray
    local: np.ndarray
    origin: np.ndarray
    axis: np.ndarray
    valid: np.ndarray  # (V, A) bool
    steps: list[StepRecord] = field(default_factory=list)
    placed: set[int] = field(default_factory=lambda: {0})
    start_index: int = 0  # the sample nearest to the assembly pose: continuation starts there
    drive: np.ndarray = field(default_factory=lambda: np.zeros(0))  # (A,) coordinate of the first drive
    rate: np.ndarray | None = None  # (A,) its time derivative; None where other drives move too
    # per step (V,), from the compiled path: where a step may have events (no assembly, a singular
    # position, a sign change of its determinant); None: look everywhere
    step_trouble: np.ndarray | None = None
    # from the compiled path: no step of any variant is in trouble (``step_trouble`` all False)
    quiet: bool = False

    @classmethod
    def empty(cls, n_links: int, local: np.ndarray, origin: np.ndarray, axis: np.ndarray, n_ang: int) -> State:
        n_var = local.shape[2]
        shape = (n_links, 3, n_var, n_ang)
        cos = np.ones((n_links, n_var, n_ang))
        return cls(
            np.zeros(shape),
            np.zeros(shape),
            np.zeros(shape),
            cos,
            np.zeros_like(cos),
            local,
            origin,
            axis,
            np.ones((n_var, n_ang), dtype=bool),
        )

    def loc(self, p: int) -> Vec:
        """Local coordinates of point ``p``: ``(V, 1)`` arrays."""
        return self.local[p, 0], self.local[p, 1]

    def point(self, link: int, p: int) -> tuple[Vec, Vec, Vec]:
        """Position, velocity and acceleration of point ``p`` of ``link``."""
        return self.point_at(link, self.loc(p))

    def point_at(self, link: int, loc: Vec) -> tuple[Vec, Vec, Vec]:
        q, v, a = self.q[link], self.v[link], self.a[link]
        r = rot(self.cos[link], self.sin[link], loc)
        w, e = v[2], a[2]
        return (
            (q[0] + r[0], q[1] + r[1]),
            (v[0] - w * r[1], v[1] + w * r[0]),
            (a[0] - e * r[1] - w * w * r[0], a[1] + e * r[0] - w * w * r[1]),
        )

    def place(
        self,
        link: int,
        turn: tuple[np.ndarray, np.ndarray, np.ndarray],
        point: tuple[Vec, Vec, Vec],
        loc: Vec,
        cs: tuple[np.ndarray, np.ndarray] | None = None,
    ) -> None:
        """Set a link's state from its angle, angular speed and acceleration ``turn`` and the position, velocity and
        acceleration ``point`` of its point at local ``loc``."""
        theta, omega, eps = turn
        x, vx, ax = point
        c, s = cs if cs is not None else (np.cos(theta), np.sin(theta))
        r = rot(c, s, loc)
        q, v, a = self.q[link], self.v[link], self.a[link]
        q[0], q[1], q[2] = x[0] - r[0], x[1] - r[1], theta
        v[0], v[1], v[2] = vx[0] + omega * r[1], vx[1] - omega * r[0], omega
        w2 = omega * omega
        a[0], a[1], a[2] = ax[0] + eps * r[1] + w2 * r[0], ax[1] - eps * r[0] + w2 * r[1], eps
        self.cos[link], self.sin[link] = c, s

    def place_like(self, link: int, guide: int, x: Vec, vx: Vec, ax: Vec, loc: Vec) -> None:
        """Place a link that keeps the angle of ``guide`` (a slider on it), through its point at local ``loc``."""
        turn = (self.q[guide, 2], self.v[guide, 2], self.a[guide, 2])
        self.place(link, turn, (x, vx, ax), loc, (self.cos[guide], self.sin[guide]))

    def line(self, k: int, guide: int) -> tuple[Vec, Vec]:
        """Global origin and unit direction of the guide line of prismatic pair ``k``."""
        c, s = self.cos[guide], self.sin[guide]
        o = rot(c, s, (self.origin[k, 0], self.origin[k, 1]))
        return (self.q[guide, 0] + o[0], self.q[guide, 1] + o[1]), rot(c, s, (self.axis[k, 0], self.axis[k, 1]))

    def material(self, link: int, x: Vec) -> tuple[Vec, Vec]:
        """Velocity and acceleration of the material point of ``link`` at global ``x``."""
        q, v, a = self.q[link], self.v[link], self.a[link]
        r = (x[0] - q[0], x[1] - q[1])
        w, e = v[2], a[2]
        return (
            (v[0] - w * r[1], v[1] + w * r[0]),
            (a[0] - e * r[1] - w * w * r[0], a[1] + e * r[0] - w * w * r[1]),
        )


def single_state(mech: Mechanism) -> State:
    """The assembly pose as a state of one variant at one angle (at rest)."""
    state = State.empty(
        mech.n_links_total,
        soa(np.asarray(mech.point_local)[None, None]),
        soa(np.asarray(mech.pair_origin)[None, None]),
        soa(np.asarray(mech.pair_axis)[None, None]),
        1,
    )
    pose = np.asarray(mech.pose0, dtype=float)
    state.q[:, :, 0, 0] = pose
    state.cos[:, 0, 0], state.sin[:, 0, 0] = np.cos(pose[:, 2]), np.sin(pose[:, 2])
    return state
