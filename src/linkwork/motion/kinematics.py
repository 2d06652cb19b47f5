"""``linkwork.kinematics``: positions, velocities and accelerations over crank angles and design variants."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any

import numpy as np

from linkwork.errors import LinkworkError, UnassemblableError
from linkwork.motion.events import Event
from linkwork.structure.model import PairType
from linkwork.structure.parameters import Masses, apply


@dataclass(frozen=True)
class Kinematics:
    """Positions, velocities and accelerations over crank angles and design variants.

    The accessors return ``(n_variants, n_angles, ...)`` arrays, without the
    variant axis when no variants were asked for: ``position("E")`` is
    ``(n_angles, 2)`` for one mechanism and ``(n_variants, n_angles, 2)``
    for a sweep.  The state of a link is the pose ``(x, y, theta)`` of its
    local frame, its velocity ``(vx, vy, omega)`` and acceleration
    ``(ax, ay, epsilon)``; SI units, radians.  Samples where the mechanism
    does not assemble are NaN and ``valid`` is False there.
    """

    mechanism: Any
    drive: np.ndarray  # (A, D) drive coordinates
    rates: np.ndarray  # (A, D) drive speeds
    q: np.ndarray  # (N, 3, V, A) link poses, link-major
    v: np.ndarray  # (N, 3, V, A)
    a: np.ndarray  # (N, 3, V, A)
    local: np.ndarray  # (P, 2, V, 1) point coordinates of the variants
    valid_all: np.ndarray  # (V, A)
    events: tuple[Event, ...]
    variants: bool
    step_det: tuple[np.ndarray, ...] = ()
    axis: np.ndarray | None = None  # (M, 2, V, 1) guide directions of the variants
    origin: np.ndarray | None = None  # (M, 2, V, 1) guide origins of the variants
    masses: Masses | None = None  # mass properties of the variants' links; None: the mechanism's

    def _out(self, a: np.ndarray) -> np.ndarray:
        return a if self.variants else a[0]

    @property
    def pose(self) -> np.ndarray:
        """Link poses ``(V, A, N, 3)`` (a view)."""
        return np.moveaxis(self.q, (0, 1), (2, 3))

    @property
    def vel(self) -> np.ndarray:
        """Link velocities ``(V, A, N, 3)`` (a view)."""
        return np.moveaxis(self.v, (0, 1), (2, 3))

    @property
    def acc(self) -> np.ndarray:
        """Link accelerations ``(V, A, N, 3)`` (a view)."""
        return np.moveaxis(self.a, (0, 1), (2, 3))

    @property
    def mass_properties(self) -> Masses:
        """Mass, centre of mass and moment of inertia of every link of every variant, ``(V, N)``,
        ``(V, N, 2)``, ``(V, N)``: the mechanism's, or those the mass rule gives the variants
        (:mod:`linkwork.structure.parameters`)."""
        if self.masses is not None:
            return self.masses
        m = self.mechanism
        return Masses(m.link_mass[None], m.link_com[None], m.link_inertia[None])

    @property
    def angles(self) -> np.ndarray:
        """Drive coordinate of the (first) drive at each sample, rad (m for a linear drive)."""
        return self.drive[:, 0]

    @property
    def valid(self) -> np.ndarray:
        """True where every group assembled."""
        return self._out(self.valid_all)

    def point_index(self, point: str) -> int:
        """Index of a point given as ``link.point`` or a joint name."""
        try:
            return self.mechanism.point_index(point)
        except KeyError:
            from linkwork.spec.checks import suggest

            names = list(self.mechanism.point_names) + list(self.mechanism.joint_names)
            raise KeyError(f'no point "{point}"{suggest(point, names)}') from None

    def link_index(self, link: str | int) -> int:
        if isinstance(link, int | np.integer):
            return int(link)
        if link not in self.mechanism.link_names:
            from linkwork.spec.checks import suggest

            raise KeyError(f'no link "{link}"{suggest(link, self.mechanism.link_names)}')
        return self.mechanism.link_names.index(link)

    def _point(self, point: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        p = self.point_index(point)
        link = int(self.mechanism.point_link[p])
        q, v, a = self.q[link], self.v[link], self.a[link]
        lx, ly = self.local[p, 0], self.local[p, 1]
        c, s = np.cos(q[2]), np.sin(q[2])
        rx, ry = c * lx - s * ly, s * lx + c * ly
        w, e = v[2], a[2]
        pos = np.stack([q[0] + rx, q[1] + ry], -1)
        vel = np.stack([v[0] - w * ry, v[1] + w * rx], -1)
        acc = np.stack([a[0] - e * ry - w * w * rx, a[1] + e * rx - w * w * ry], -1)
        return pos, vel, acc

    def position(self, point: str) -> np.ndarray:
        """Global position of a point, m: ``(..., n_angles, 2)``."""
        return self._out(self._point(point)[0])

    def velocity(self, point: str) -> np.ndarray:
        """Velocity of a point, m/s: ``(..., n_angles, 2)``."""
        return self._out(self._point(point)[1])

    def acceleration(self, point: str) -> np.ndarray:
        """Acceleration of a point, m/s^2: ``(..., n_angles, 2)``."""
        return self._out(self._point(point)[2])

    def angle(self, link: str | int) -> np.ndarray:
        """Angle of a link's local x axis, rad: ``(..., n_angles)``."""
        return self._out(self.q[self.link_index(link), 2])

    def omega(self, link: str | int) -> np.ndarray:
        """Angular velocity, rad/s (counter-clockwise positive)."""
        return self._out(self.v[self.link_index(link), 2])

    def epsilon(self, link: str | int) -> np.ndarray:
        """Angular acceleration, rad/s^2."""
        return self._out(self.a[self.link_index(link), 2])

    def points(self) -> np.ndarray:
        """Positions of all points, ``(..., n_angles, n_points, 2)`` (order of ``mechanism.point_names``)."""
        m = self.mechanism
        q = self.q[m.point_link]  # (P, 3, V, A)
        c, s = np.cos(q[:, 2]), np.sin(q[:, 2])
        lx, ly = self.local[:, 0], self.local[:, 1]
        out = np.stack([q[:, 0] + c * lx - s * ly, q[:, 1] + s * lx + c * ly], -1)  # (P, V, A, 2)
        return self._out(np.moveaxis(out, 0, 2))

    def samples(self, index: Any) -> Kinematics:
        """The result at the samples ``index`` only (an int array or a slice of the angles), solved as they were;
        the events are the whole result's."""
        return dataclasses.replace(
            self,
            drive=self.drive[index],
            rates=self.rates[index],
            q=self.q[..., index],
            v=self.v[..., index],
            a=self.a[..., index],
            valid_all=self.valid_all[:, index],
            step_det=tuple(d[..., index] for d in self.step_det),
        )


#: Largest step (rad) of a path along which change points are followed.
PATH_STEP = np.radians(5.0)


def _path(mech: Any, angles: np.ndarray) -> tuple[np.ndarray | None, np.ndarray | None]:
    """A path of crank angles that reaches every asked angle from the assembly pose.

    Change points are followed along the order of the samples, so angles
    that are not such a path already (one angle, unsorted angles, big steps,
    angles away from the assembly pose) are solved on the sorted union of
    the asked angles and a grid of 5 degrees from the assembly angle; the
    result keeps the asked ones.  Returns (path, indices of the asked
    angles in it), or (None, None) when the angles are a path already.
    """
    if not any(step.kind in ("RRR", "RRP", "PRP") for step in mech.program):
        return None, None
    start = float(mech.drive_start[0])
    d = np.diff(angles)
    monotonic = len(angles) > 1 and (np.all(d > 0) or np.all(d < 0))
    step = PATH_STEP * (1 + 1e-9)
    if monotonic and np.abs(d).max() <= step and angles.min() - step <= start <= angles.max() + step:
        return None, None
    lo, hi = min(angles.min(), start), max(angles.max(), start)
    grid = start + PATH_STEP * np.arange(np.floor((lo - start) / PATH_STEP), np.ceil((hi - start) / PATH_STEP) + 1)
    asked = np.sort(angles)
    pos = np.clip(np.searchsorted(asked, grid), 1, len(asked)) - 1
    gap = np.minimum(np.abs(grid - asked[pos]), np.abs(grid - asked[np.minimum(pos + 1, len(asked) - 1)]))
    grid = grid[gap > 1e-9]  # no grid point beside an asked angle
    path, inverse = np.unique(np.concatenate([angles, grid]), return_inverse=True)
    return path, inverse[: len(angles)]


def direction(mech: Any) -> float:
    """+1 where the first drive turns counter-clockwise (or forward; also where it has no speed), -1 where
    it turns clockwise (backward): the sign of the drive coordinate's steps over a cycle."""
    return -1.0 if mech.drive_speed[0] < 0 else 1.0


def cycle(mech: Any, steps: int, start: float | None = None) -> np.ndarray:
    """Drive coordinates of a uniform cycle of the first drive, in its direction, from ``start`` (rad;
    default its assembly value)."""
    from linkwork.structure.model import one_crank

    if not one_crank(mech):
        raise LinkworkError("steps= needs a mechanism with one revolute drive; give the angles instead")
    first = mech.drive_start[0] if start is None else start
    return first + direction(mech) * 2 * np.pi * np.arange(steps) / steps


def kinematics(
    mech: Any,
    angles: Any = None,
    *,
    steps: int | None = None,
    variants: dict[str, Any] | None = None,
    speed: Any = None,
    strict: bool = False,
) -> Kinematics:
    """Positions, velocities and accelerations at the given drive coordinates.

    Parameters
    ----------
    mech : Mechanism
        The compiled mechanism (``linkwork.kinematics`` also takes a path, an example name or a
        Spec: :mod:`linkwork.api`).
    angles : array_like, shape (A,) or (A, D)
        Drive coordinates (rad for revolute drives, m for prismatic ones):
        the crank angle in the frame's axes, counter-clockwise from +x.
    steps : int, optional
        Instead of ``angles``: ``steps`` equal steps of a whole turn of the
        crank from its assembly angle, in its direction of rotation.
    variants : dict, optional
        Design variants: arrays of values (SI) of named parameters, all of
        one length V, e.g. ``{"links.crank.length": np.linspace(0.09, 0.11, 100)}``;
        :func:`parameters` lists the names.  An override means what the same
        edit of the file means, mass properties included (the mass rule of
        :mod:`linkwork.structure.parameters`); they come with the result for
        :func:`linkwork.forces`.
    speed : float or array_like (D,), optional
        Drive speeds (rad/s or m/s); default the file's.  A drive without a
        speed is taken at 1 rad/s (1 m/s): velocities are then the first
        kinematic transfer functions (velocity analogues).
    strict : bool
        Raise :class:`UnassemblableError` if any sample fails to assemble.

    Returns
    -------
    Kinematics
    """
    from linkwork.motion.events import find
    from linkwork.motion.solve import run
    if (angles is None) == (steps is None):
        raise LinkworkError("give either angles or steps")
    if steps is not None and (isinstance(steps, bool) or not isinstance(steps, int | np.integer) or steps < 1):
        raise LinkworkError(f"steps: expected a positive whole number, got {steps!r}")
    values = cycle(mech, int(steps)) if steps is not None else np.asarray(angles, dtype=float)
    if values.size == 0:
        raise LinkworkError("no angles given")
    values = values.reshape(len(values), -1) if values.ndim else values.reshape(1, 1)
    if values.shape[1] != mech.n_drives:
        raise LinkworkError(f"the mechanism has {mech.n_drives} drives; angles must have shape (n, {mech.n_drives})")
    if not np.isfinite(values).all():
        raise LinkworkError("angles must be finite numbers")
    if speed is None:
        rate = np.where(np.isfinite(mech.drive_speed) & (mech.drive_speed != 0), mech.drive_speed, 1.0)
    else:
        speed = np.asarray(speed, dtype=float)
        if speed.size not in (1, mech.n_drives) or not np.isfinite(speed).all():
            raise LinkworkError(f"speed: expected {mech.n_drives} finite value(s), got {speed.tolist()!r}")
        rate = np.broadcast_to(speed.ravel(), (mech.n_drives,))
    for path, value in (variants or {}).items():
        if np.ndim(value) > 1:
            raise LinkworkError(f'variants["{path}"]: expected a one-dimensional array, got shape {np.shape(value)}')
    rates = np.broadcast_to(rate, values.shape)
    geom, masses = apply(mech, variants)
    revolute = bool(mech.pair_type[mech.drive_pair[0]] == PairType.REVOLUTE)
    path, take = _path(mech, values[:, 0]) if revolute and mech.n_drives == 1 else (None, None)
    if path is None:
        state = run(mech, mech.program, geom, values, rates, np.zeros_like(values))
        events = tuple(find(mech.program, state, values[:, 0], revolute))
    else:
        # solve along a path from the assembly pose through every asked angle, then keep those
        state = run(
            mech, mech.program, geom, path[:, None], np.broadcast_to(rate, (len(path), 1)), np.zeros((len(path), 1))
        )
        events = tuple(find(mech.program, state, path, revolute, within=(int(take.min()), int(take.max()))))
        state.q, state.v, state.a = state.q[..., take], state.v[..., take], state.a[..., take]
        state.valid = state.valid[:, take]
        state.step_det = [d[:, take] for d in state.step_det]
    if strict and not state.valid.all():
        first = next(e for e in events if e.kind == "no-assembly")
        raise UnassemblableError(first.message, group=first.group, angle=first.start)
    return Kinematics(
        mech,
        values,
        np.array(rates),
        state.q,
        state.v,
        state.a,
        state.local,
        state.valid,
        events,
        variants is not None and len(variants) > 0,
        tuple(state.step_det),
        state.axis,
        state.origin,
        masses if variants else None,
    )
