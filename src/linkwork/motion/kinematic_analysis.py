"""``linkwork.kinematics``: positions, velocities and accelerations over crank angles and design variants."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, NamedTuple

import numpy as np
import numpy.typing as npt

from linkwork import jit
from linkwork.did_you_mean import suggest
from linkwork.errors import LinkworkError, UnassemblableError
from linkwork.limits import TURN_STEPS
from linkwork.motion import between, kernels, kernels_numba
from linkwork.motion.events import Event, find
from linkwork.motion.groups import KINDS
from linkwork.motion.points import point_motion
from linkwork.motion.solve import run, run_numpy
from linkwork.motion.state import State
from linkwork.structure.model import Mechanism, PairType, one_crank, per_mechanism
from linkwork.structure.parameters import Geometry, Masses, apply


@dataclass(frozen=True)
class Kinematics:
    """Positions, velocities and accelerations over crank angles and design variants.

    The accessors return ``(n_variants, n_angles, ...)`` arrays, without the
    variant axis when no variants were asked for: ``position("E")`` is
    ``(n_angles, 2)`` for one mechanism and ``(n_variants, n_angles, 2)``
    for a sweep.  The state of a link is the pose ``(x, y, theta)`` of its
    local frame, its velocity ``(vx, vy, omega)`` and acceleration
    ``(ax, ay, epsilon)``; SI units, radians.  Samples where the mechanism
    does not assemble are NaN and ``valid`` is False there.  ``cos`` and
    ``sin`` are those of each link's angle ``q[:, 2]``, as the solve placed
    the link's points with them; the accessors read points with them.

    :func:`linkwork.kinematics` makes it; read it through its accessors.
    Shapes below: ``A`` crank angles, ``V`` variants (1 for one mechanism),
    ``N`` links, ``P`` points, ``M`` pairs, ``D`` drives of the mechanism.

    Parameters
    ----------
    mechanism : Mechanism
        The compiled mechanism it was solved for.
    drive : ndarray, shape (A, D)
        The drives' coordinates at each sample, rad or m.
    rates : ndarray, shape (A, D)
        The drives' speeds at each sample, rad/s or m/s.
    q : ndarray, shape (N, 3, V, A)
        The pose ``(x, y, theta)`` of every link, m and rad.
    v : ndarray, shape (N, 3, V, A)
        Its velocity ``(vx, vy, omega)``, m/s and rad/s.
    a : ndarray, shape (N, 3, V, A)
        Its acceleration ``(ax, ay, epsilon)``, m/s^2 and rad/s^2.
    cos, sin : ndarray, shape (N, V, A)
        Cosine and sine of each link's angle.
    local : ndarray, shape (P, 2, V, 1)
        The points' local coordinates in each variant, m.
    axis : ndarray, shape (M, 2, V, 1)
        The guides' directions in each variant (unit vectors).
    origin : ndarray, shape (M, 2, V, 1)
        The guides' origins in each variant, m.
    valid_all : ndarray of bool, shape (V, A)
        Where the mechanism assembles.
    events : tuple of Event
        Dead points, singular positions and ranges that do not assemble.
    variants : bool
        Whether variants were asked for (the accessors keep the variant axis).
    step_det : tuple of ndarray, default ()
        ``(V, A)`` for each step of the program: its normalised Jacobian determinant.
    step_branch : tuple of (ndarray or None), default ()
        ``(V, A)`` for each step: the assembly mode used; None where it is the step's own.
    masses : Masses or None, default None
        Mass properties of the variants' links; None: the mechanism's.
    each : ndarray or None, default None
        ``(V, A)``: the drive coordinate of every variant where each has its own (:meth:`at`), rad or m.
    """

    mechanism: Mechanism
    drive: np.ndarray  # (A, D) drive coordinates
    rates: np.ndarray  # (A, D) drive speeds
    q: np.ndarray  # (N, 3, V, A) link poses, link-major
    v: np.ndarray  # (N, 3, V, A)
    a: np.ndarray  # (N, 3, V, A)
    cos: np.ndarray  # (N, V, A) of each link's angle
    sin: np.ndarray  # (N, V, A)
    local: np.ndarray  # (P, 2, V, 1) point coordinates of the variants
    axis: np.ndarray  # (M, 2, V, 1) guide directions of the variants
    origin: np.ndarray  # (M, 2, V, 1) guide origins of the variants
    valid_all: np.ndarray  # (V, A)
    events: tuple[Event, ...]
    variants: bool
    step_det: tuple[np.ndarray, ...] = ()  # (V, A) per step of the program, its normalised Jacobian determinant
    step_branch: tuple[np.ndarray | None, ...] = ()  # (V, A) per step, the assembly mode used; None: the step's own
    masses: Masses | None = None  # mass properties of the variants' links; None: the mechanism's
    each: np.ndarray | None = None  # (V, A) the drive coordinate of every variant where each has its own (:meth:`at`)

    @classmethod
    def _made(cls, **fields: Any) -> Kinematics:
        """A result of every field (given by name), made without the dataclass's ``__init__``, which sets
        the fields of a frozen dataclass one at a time (a few microseconds, a tenth of the fixed cost of a
        short solve)."""
        out = object.__new__(cls)
        out.__dict__.update(fields)
        return out

    @classmethod
    def _of_state(
        cls,
        mech: Mechanism,
        state: State,
        drive: np.ndarray,
        rates: np.ndarray,
        *,
        events: tuple[Event, ...] = (),
        variants: bool = False,
        masses: Masses | None = None,
        each: np.ndarray | None = None,
    ) -> Kinematics:
        """The result of a solved state (the kernels' ``run``): its poses, rates, frames and each step's
        determinant and assembly mode, with the drive ``(A, D)`` and its speeds."""
        return cls._made(
            mechanism=mech,
            drive=drive,
            rates=rates,
            q=state.q,
            v=state.v,
            a=state.a,
            cos=state.cos,
            sin=state.sin,
            local=state.local,
            axis=state.axis,
            origin=state.origin,
            valid_all=state.valid,
            events=events,
            variants=variants,
            step_det=tuple(r.det for r in state.steps),
            step_branch=tuple(r.branch for r in state.steps),
            masses=masses,
            each=each,
        )

    def _repr_html_(self) -> str:
        """A notebook's view: the mechanism, the variants, angles, points and links, where it assembles."""
        from linkwork.display import table

        mech, valid = self.mechanism, np.asarray(self.valid_all)
        return table(
            f"Kinematics of {mech.name}",
            [
                ("variants x angles", f"{valid.shape[0]} x {valid.shape[1]}"),
                ("joints", ", ".join(dict.fromkeys(mech.pair_joint))),
                ("moving links", ", ".join(mech.link_names[1:])),
                ("assembles at", f"{int(valid.sum())} of {valid.size} samples"),
                ("events", "; ".join(f"{e.kind} of {e.group}" for e in self.events) or "none"),
            ],
        )

    def to_xarray(self) -> Any:
        """The table ``linkwork kinematics --out F.nc`` writes, as an xarray Dataset (the ``data`` extra).

        Dimensions ``variant`` x ``angle`` x ``point`` (x, y, vx, vy, ax, ay of each labelled point) and
        ``variant`` x ``angle`` x ``link`` (theta, omega, epsilon of each moving link), ``valid``; the
        coordinate ``angle`` is φ from position 0 in degrees with one crank (the angle to x beside it,
        ``crank_angle_to_x``); each variable's unit in its ``units`` attribute.

        Raises
        ------
        MissingDependencyError
            Without xarray, naming the extra that brings it.
        """
        from linkwork.motion.tables import to_dataset

        return to_dataset(self)

    def to_pandas(self, by: str = "point") -> Any:
        """The variables of :meth:`to_xarray` over the points (``by="point"``) or the links (``by="link"``) as a
        pandas DataFrame indexed by ``variant`` x ``angle`` x ``by``; the units in ``attrs["units"]``.

        Raises
        ------
        MissingDependencyError
            Without pandas, naming the extra that brings it.
        """
        from linkwork.motion.tables import to_frame

        return to_frame(self, by)

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
    def angles_all(self) -> np.ndarray:
        """Drive coordinate of the (first) drive of every variant at each sample, ``(V, A)`` (a view): :attr:`angles`
        for every variant, or each variant's own (:meth:`at`)."""
        return self.each if self.each is not None else np.broadcast_to(self.angles, self.valid_all.shape)

    def at(self, angles: np.ndarray, variants: np.ndarray | None = None) -> Kinematics | None:
        """The same mechanism solved again at other drive coordinates, for refining a quantity between the samples
        (:mod:`linkwork.kinetostatics.peaks`): row ``r`` of ``angles`` ``(R, K)`` for variant ``variants[r]``
        (default: row ``r`` for variant ``r``; for one mechanism, every row for it), at the uniform speed of the first
        sample, as variants ``(R, K)``; one drive only (else None).

        Each angle is solved in the assembly modes of the two samples around it (a sample on a dyad's singular
        position has the modes of both sides: the other one's), and a group solved by Newton's method is started
        from the pose of the nearer one (:func:`~linkwork.motion.solve.run_each`).  Between two samples in different
        modes a change point lies: it is located (:mod:`~linkwork.motion.between`) and an angle is solved in the mode of
        the sample on its side of it (NaN, not valid, where it cannot be located).
        """
        found = between.modes_at(self, angles, variants)
        return None if found is None else between.solved(self, *found)

    def modes_at(
        self, angles: np.ndarray, variants: np.ndarray | None = None
    ) -> tuple[np.ndarray, np.ndarray, list[np.ndarray | None], np.ndarray] | None:
        """The assembly modes this result has at other drive coordinates (:func:`linkwork.motion.between.modes_at`)."""
        return between.modes_at(self, angles, variants)

    @property
    def valid(self) -> np.ndarray:
        """True where every group assembled."""
        return self._out(self.valid_all)

    def point_index(self, point: str) -> int:
        """Index of a point given as ``link.point`` or a joint name."""
        try:
            return self.mechanism.point_index(point)
        except KeyError:
            names = list(self.mechanism.point_names) + list(self.mechanism.joint_names)
            raise KeyError(f'no point "{point}"{suggest(point, names)}') from None

    def link_index(self, link: str | int) -> int:
        """Index of a link given by its name (or its index)."""
        if isinstance(link, int | np.integer):
            return int(link)
        if link not in self.mechanism.link_names:
            raise KeyError(f'no link "{link}"{suggest(link, self.mechanism.link_names)}')
        return self.mechanism.link_names.index(link)

    def motion_of(self, point: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Position, velocity and acceleration of a point, with the variant axis always.

        Parameters
        ----------
        point : str
            ``link.point`` or a joint name.

        Returns
        -------
        position, velocity, acceleration : ndarray
            ``(V, A, 2)`` each, m, m/s, m/s^2 (one variant: ``V`` = 1, unlike :meth:`position`, which drops the
            axis); NaN where the mechanism does not assemble.
        """
        return (
            self._motion(point, kernels.POSITION),
            self._motion(point, kernels.VELOCITY),
            self._motion(point, kernels.ACCELERATION),
        )

    def _motion(self, point: str, kind: int) -> np.ndarray:
        """The position, velocity or acceleration (``kind``) of a point, ``(V, A, 2)``: its link's motion
        carried to the point (:func:`~linkwork.motion.points.point_motion`)."""
        p = self.point_index(point)
        link = int(self.mechanism.point_link[p])
        cs = self.cos[link], self.sin[link]
        return point_motion(kind, self.q[link], self.v[link], self.a[link], cs, self.local[p, :, :, 0])

    def position(self, point: str) -> np.ndarray:
        """Global position of a point, m: ``(..., n_angles, 2)``."""
        return self._out(self._motion(point, kernels.POSITION))

    def velocity(self, point: str) -> np.ndarray:
        """Velocity of a point, m/s: ``(..., n_angles, 2)``."""
        return self._out(self._motion(point, kernels.VELOCITY))

    def acceleration(self, point: str) -> np.ndarray:
        """Acceleration of a point, m/s^2: ``(..., n_angles, 2)``."""
        return self._out(self._motion(point, kernels.ACCELERATION))

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
        every = self.point_positions(np.arange(len(self.mechanism.point_names)))  # (P, V, A, 2)
        return self._out(np.ascontiguousarray(every.transpose(1, 2, 0, 3)))

    def point_positions(self, points: npt.ArrayLike, variant: int | None = None) -> np.ndarray:
        """Positions ``(K, V, A, 2)`` of the points ``points`` (indices ``(K,)``), the points first, of every
        variant (of ``variant`` alone: ``V`` = 1): one pass of :func:`~linkwork.motion.points.point_motion` over
        them all, each point of each variant taken as a variant of its link (the arithmetic of :meth:`position`)."""
        points = np.asarray(points, dtype=np.intp)
        link = np.asarray(self.mechanism.point_link)[points]
        pick = slice(None) if variant is None else slice(variant, variant + 1)
        q, cos, sin = self.q[link, :, pick], self.cos[link, pick], self.sin[link, pick]  # (K, 3, V, A), (K, V, A)
        k, n_var, n_ang = cos.shape
        flat = np.ascontiguousarray(q.swapaxes(0, 1)).reshape(3, k * n_var, n_ang)
        local = np.ascontiguousarray(self.local[points, :, pick, 0].swapaxes(0, 1)).reshape(2, k * n_var)
        cs = cos.reshape(k * n_var, n_ang), sin.reshape(k * n_var, n_ang)
        return point_motion(kernels.POSITION, flat, flat, flat, cs, local).reshape(k, n_var, n_ang, 2)

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
            cos=self.cos[..., index],
            sin=self.sin[..., index],
            valid_all=self.valid_all[:, index],
            step_det=tuple(d[..., index] for d in self.step_det),
            step_branch=tuple(None if b is None else b[..., index] for b in self.step_branch),
            each=None if self.each is None else self.each[:, index],
        )


#: Largest step (rad) of a path along which change points are followed.
PATH_STEP = np.radians(5.0)


def _path(
    mech: Mechanism, angles: np.ndarray, steps: tuple[float, float] | None = None
) -> tuple[np.ndarray, np.ndarray | slice] | None:
    """A path of crank angles that reaches every asked angle from the assembly pose.

    Change points are followed along the order of the samples, so angles
    that are not such a path already (one angle, unsorted angles, big steps)
    are solved on the sorted union of the asked angles and a grid of 5
    degrees from the assembly angle, and angles that are a path but do not
    reach the assembly angle (a turn from elsewhere) after a lead from it on
    that grid (:func:`_led`); the result keeps the asked ones.  Returns
    (path, the asked angles' places in it: indices, or a slice), or None
    when the angles are a path already.  ``steps``: the least and most step
    between consecutive angles, where known.
    """
    facts = _drive_facts(mech)
    if not facts.follows:
        return None
    start = facts.start
    step = PATH_STEP * (1 + 1e-9)
    if len(angles) > 1:  # a path already: monotonic, in steps of at most PATH_STEP, through the start
        if steps is None:
            d = angles[1:] - angles[:-1]
            steps = float(d.min()), float(d.max())
        least, most = steps
        first, last = sorted((float(angles[0]), float(angles[-1])))
        if (least > 0 or most < 0) and max(most, -least) <= step:
            return None if first - step <= start <= last + step else _led(angles, start)
    lo, hi = min(angles.min(), start), max(angles.max(), start)
    grid = start + PATH_STEP * np.arange(np.floor((lo - start) / PATH_STEP), np.ceil((hi - start) / PATH_STEP) + 1)
    asked = np.sort(angles)
    pos = np.clip(np.searchsorted(asked, grid), 1, len(asked)) - 1
    gap = np.minimum(np.abs(grid - asked[pos]), np.abs(grid - asked[np.minimum(pos + 1, len(asked) - 1)]))
    grid = grid[gap > 1e-9]  # no grid point beside an asked angle
    path, inverse = np.unique(np.concatenate([angles, grid]), return_inverse=True)
    return path, inverse[: len(angles)]


def _led(angles: np.ndarray, start: float) -> tuple[np.ndarray, slice]:
    """Angles that are a path already (monotonic, in steps of at most :data:`PATH_STEP`) but do not reach
    the assembly angle ``start`` (a turn from elsewhere): the grid of :data:`PATH_STEP` from ``start`` up
    to them, then them, in their order of travel (or them, then the grid on to ``start``), and where they
    are in it.  The motion is followed as along the sorted union of :func:`_path`, without the grid's
    points among the asked angles, which are near enough to each other."""
    ahead = 1.0 if angles[-1] > angles[0] else -1.0
    if (angles[0] - start) * ahead > 0:  # the start lies behind the first angle: a lead-in
        grid = start + ahead * PATH_STEP * np.arange(math.ceil((angles[0] - start) * ahead / PATH_STEP))
        grid = grid[(angles[0] - grid) * ahead > 1e-9]
        return np.concatenate([grid, angles]), slice(len(grid), len(grid) + len(angles))
    grid = start - ahead * PATH_STEP * np.arange(math.ceil((start - angles[-1]) * ahead / PATH_STEP))[::-1]
    grid = grid[(grid - angles[-1]) * ahead > 1e-9]
    return np.concatenate([angles, grid]), slice(0, len(angles))


def direction(mech: Mechanism) -> float:
    """+1 where the first drive turns counter-clockwise (or forward; also where it has no speed), -1 where
    it turns clockwise (backward): the sign of the drive coordinate's steps over a cycle."""
    return -1.0 if mech.drive_speed[0] < 0 else 1.0


def cycle(mech: Mechanism, steps: int, start: float | None = None) -> np.ndarray:
    """Drive coordinates of a uniform cycle of the first drive, in its direction, from ``start`` (rad;
    default its assembly value)."""
    if not one_crank(mech):
        raise LinkworkError("steps= needs a mechanism with one revolute drive; give the angles instead")
    first = mech.drive_start[0] if start is None else start
    return first + direction(mech) * 2 * np.pi * np.arange(steps) / steps


@jit.deciding
def kinematics(
    mech: Mechanism,
    angles: npt.ArrayLike | None = None,
    *,
    steps: int | None = None,
    variants: Mapping[str, npt.ArrayLike] | None = None,
    speed: npt.ArrayLike | None = None,
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
        crank from its assembly angle, in its direction of rotation; without
        either, :data:`~linkwork.limits.TURN_STEPS` (360).
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
        Positions (m), velocities (m/s) and accelerations (m/s^2) of every labelled point, angles (rad),
        angular speeds and accelerations of every link, at each angle and variant; the events on the way.

    Examples
    --------
    >>> import linkwork as lw
    >>> kin = lw.kinematics("four-bar", steps=12)
    >>> kin.position("B").shape  # m, (angles, x and y)
    (12, 2)
    """
    values, span = _drive_values(mech, angles, steps)
    rates = np.empty_like(values)
    rates[:] = _speeds(mech, speed)
    for path, value in (variants or {}).items():
        if np.ndim(value) > 1:
            raise LinkworkError(f'variants["{path}"]: expected a one-dimensional array, got shape {np.shape(value)}')
    geom, masses = apply(mech, variants) if variants else (file_geometry(mech), None)
    state, events = _solve(mech, geom, values, rates, span)
    if strict and not state.valid.all():
        first = next(e for e in events if e.kind == "no-assembly")
        raise UnassemblableError(first.message, group=first.group, angle=first.start)
    return Kinematics._of_state(
        mech, state, values, rates, events=events, variants=variants is not None and len(variants) > 0, masses=masses
    )


@jit.deciding
def kinematics_at(
    mech: Mechanism, angles: np.ndarray, speeds: np.ndarray, accels: np.ndarray, *, along: Kinematics | None = None
) -> Kinematics:
    """The state at the drive coordinates ``angles`` ``(A, D)`` with the drive speeds ``speeds`` and
    accelerations ``accels`` (each ``(A, D)``), without events; the file's dimensions.  The accelerations are the
    true ones of a drive that speeds up: ``a = a_uniform + accel * d r / d phi``.

    ``along``: a cycle of the mechanism (one drive); each sample is solved in the assembly modes that cycle has at
    its angle (:meth:`Kinematics.modes_at`: past a change point, the other mode), as the cycle, the viewer and a
    run in time show it.  Without it the samples are taken as a motion in their order from the one nearest the
    assembly pose (the modes change at the change points between them; fewer than three samples keep the file's
    modes)."""
    geom = file_geometry(mech)
    found = None if along is None else along.modes_at(angles[:, 0][None, :])
    if found is None:
        state = run(mech, mech.program, geom, angles, speeds, accels)
    else:
        _, each, found_modes, _ = found
        modes = [
            np.full(each.shape, step.branch) if m is None and KINDS[step.kind].changes_mode else m
            for step, m in zip(mech.program, found_modes, strict=True)
        ]
        angles = np.where(np.isnan(each[0])[:, None], np.nan, angles)
        state = run_numpy(mech, mech.program, geom, angles, speeds, accels, branches=modes)
    return Kinematics._of_state(mech, state, angles, speeds)


#: The geometry of the file's dimensions of the mechanisms solved so far (:func:`file_geometry`), by
#: the mechanism's id, with a weak reference to it (the entry goes with the mechanism).
@per_mechanism
def file_geometry(mech: Mechanism) -> Geometry:
    """The geometry of the file's dimensions (one variant: :func:`~linkwork.structure.parameters.apply`
    without overrides), made once per mechanism; its arrays are read-only."""
    geom = apply(mech)[0]
    for array in (geom.point_local, geom.pair_origin, geom.pair_axis):
        array.flags.writeable = False
    return geom


def _drive_values(
    mech: Mechanism, angles: npt.ArrayLike | None, steps: int | None
) -> tuple[np.ndarray, tuple[float, float] | None]:
    """The drive coordinates asked for, ``(A, D)``, and the least and most step of the first drive
    between consecutive samples where the check of the values found them (:func:`kernels_numba.scan`, for
    :func:`_path`); :class:`LinkworkError` for anything else."""
    if angles is not None and steps is not None:
        raise LinkworkError("give either angles or steps, not both")
    if angles is None and steps is None:
        steps = TURN_STEPS
    if steps is not None and (isinstance(steps, bool) or not isinstance(steps, int | np.integer) or steps < 1):
        raise LinkworkError(f"steps: expected a positive whole number, got {steps!r}")
    values = cycle(mech, int(steps)) if steps is not None else np.asarray(angles, dtype=float)
    if values.size == 0:
        raise LinkworkError("no angles given")
    values = values.reshape(len(values), -1) if values.ndim else values.reshape(1, 1)
    if values.shape[1] != mech.n_drives:
        raise LinkworkError(f"the mechanism has {mech.n_drives} drives; angles must have shape (n, {mech.n_drives})")
    span = None
    if values.flags.c_contiguous and kernels_numba.available():  # one compiled pass: finite, and the steps
        finite, least, most = kernels_numba.scan(values)
        span = least, most
    else:
        finite = bool(np.isfinite(values).all())
    if not finite:
        raise LinkworkError("angles must be finite numbers")
    return values, span


class _DriveFacts(NamedTuple):
    """What a call needs to know of a mechanism's drives (:func:`_drive_facts`)."""

    revolute: bool  # the first drive is a revolute pair
    follows: bool  # one revolute drive and dyads that have change points: solved along a path (:func:`_path`)
    speeds: np.ndarray  # (D,) the file's speed of every drive, 1 where it gives none; read-only
    start: float  # the first drive's coordinate in the assembly pose


@per_mechanism
def _drive_facts(mech: Mechanism) -> _DriveFacts:
    """The facts of the mechanism's drives every call uses, found once per mechanism."""
    revolute = bool(mech.pair_type[mech.drive_pair[0]] == PairType.REVOLUTE)
    dyads = any(KINDS[step.kind].changes_mode for step in mech.program)
    speeds = np.array([x if math.isfinite(x) and x != 0 else 1.0 for x in mech.drive_speed.tolist()])
    speeds.flags.writeable = False
    return _DriveFacts(revolute, revolute and mech.n_drives == 1 and dyads, speeds, float(mech.drive_start[0]))


def _speeds(mech: Mechanism, speed: npt.ArrayLike | None) -> np.ndarray:
    """The speed of every drive, ``(D,)``: ``speed``, or the file's (1 where it gives none)."""
    if speed is None:
        return _drive_facts(mech).speeds
    speed = np.asarray(speed, dtype=float)
    if speed.size not in (1, mech.n_drives) or not np.isfinite(speed).all():
        raise LinkworkError(f"speed: expected {mech.n_drives} finite value(s), got {speed.tolist()!r}")
    return np.broadcast_to(speed.ravel(), (mech.n_drives,))


def _solve(
    mech: Mechanism, geom: Geometry, values: np.ndarray, rates: np.ndarray, span: tuple[float, float] | None = None
) -> tuple[State, tuple[Event, ...]]:
    """The state at the drive coordinates ``values`` ``(A, D)`` at the speeds ``rates`` ``(A, D)``, and the
    events along them.  A single crank is solved along a path from the assembly pose through every angle
    asked (:func:`_path`; ``span``: the least and most step of the first drive, where known), and the
    asked ones kept."""
    revolute = _drive_facts(mech).revolute
    path = _path(mech, values[:, 0], span)
    if path is None:
        state = run(mech, mech.program, geom, values, rates, np.zeros(values.shape))
        return state, tuple(find(mech.program, state, values[:, 0], revolute))
    angles, take = path
    rate = np.broadcast_to(rates[0], (len(angles), 1))
    state = run(mech, mech.program, geom, angles[:, None], rate, np.zeros((len(angles), 1)))
    within = (take.start, take.stop - 1) if isinstance(take, slice) else (int(take.min()), int(take.max()))
    events = tuple(find(mech.program, state, angles, revolute, within=within))

    def kept(x: np.ndarray) -> np.ndarray:
        return np.ascontiguousarray(x[..., take])

    state.q, state.v, state.a = kept(state.q), kept(state.v), kept(state.a)
    state.cos, state.sin, state.valid = kept(state.cos), kept(state.sin), kept(state.valid)
    state.steps = [r.take(take) for r in state.steps]
    return state, events
