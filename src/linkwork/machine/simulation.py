"""Forward simulation of the machine unit from rest (or any speed) to its steady cycle.

The equation of motion ``J(psi) psi'' + J'(psi) psi'^2 / 2 = M(psi) + M_drive(psi')`` is the
derivative of the energy equation, which is integrated instead, with the crank's turning angle
``psi`` as the independent variable:

    dE/dpsi = M(psi) + M_drive(omega),   dt/dpsi = 1 / omega,   omega = sqrt(2 E / (J(psi) + J_d))

(``E`` the kinetic energy, ``J`` the reduced inertia of the mechanism as a periodic cubic spline
through its exact values, ``J_d`` the drive's constant inertia, ``M`` the reduced load moment,
linear between the grid points: technological loads have corners).  Without loads and drive the
energy stays exactly constant, and the turns are the natural steps: each is integrated from
``2 pi k`` to ``2 pi (k + 1)`` by the machine's integrator (:func:`linkwork.machine.integration.integrate`,
DOP853).  The crank must keep turning
forward: a drive too weak to carry it through a turn is reported.  From rest the first
micro-radian is taken in closed form (constant moment), where ``dt/dpsi`` is infinite.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

from linkwork.errors import LinkworkError
from linkwork.machine.integration import IntegrationEvent, integrate

if TYPE_CHECKING:
    from linkwork.machine.reduction import Reduced
    from linkwork.structure.records import MotorGear


class Curve(NamedTuple):
    """A smooth quantity at one turning angle ``psi`` of the crank: its value and its first and
    second derivatives in ``psi`` (per rad, per rad^2)."""

    value: float
    slope: float
    curvature: float


_tuple = tuple.__new__


def periodic_cubic(y: np.ndarray, h: float) -> np.ndarray:
    """The periodic cubic spline through ``y`` at equal steps ``h`` over a period (``y[0]`` again one step
    after ``y[-1]``): per interval ``i``, from ``i h``, the coefficients ``(k, 4)`` of its cubic in the distance
    ``x`` from the interval's start, cubic first, constant last.

    The second derivatives ``m`` at the knots solve ``m[i-1] + 4 m[i] + m[i+1] = 6 (y[i+1] - 2 y[i] + y[i-1])
    / h^2`` round the period; its matrix is circulant, with eigenvalues ``4 + 2 cos(2 pi j / k)`` (2 to 6:
    well conditioned), so the system is solved by the FFT.  The spline SciPy's ``CubicSpline`` gives with
    ``bc_type="periodic"``, to rounding, without importing ``scipy.interpolate`` (a third of a second)."""
    k = len(y)
    y1 = np.roll(y, -1)
    rhs = 6.0 / h**2 * (y1 - 2.0 * y + np.roll(y, 1))
    eig = 4.0 + 2.0 * np.cos(2.0 * math.pi * np.arange(k // 2 + 1) / k)
    m = np.fft.irfft(np.fft.rfft(rhs) / eig, n=k)
    m1 = np.roll(m, -1)
    return np.stack([(m1 - m) / (6.0 * h), m / 2.0, (y1 - y) / h - h * (2.0 * m + m1) / 6.0, y], axis=1)


class PeriodicSplines:
    """Periodic cubic splines of several columns over a turn of the crank, on a uniform grid ``psi``,
    evaluated one turning angle at a time (fast scalars)."""

    def __init__(self, psi: np.ndarray, columns: Sequence[np.ndarray]) -> None:
        k = len(psi)
        self.k, self.h = k, 2 * math.pi / k
        coef = [periodic_cubic(np.asarray(col, dtype=float), self.h) for col in columns]
        #: per interval, per column: the coefficients of its cubic, constant last
        self.c = [tuple(tuple(map(float, c[i])) for c in coef) for i in range(k)]
        self.first = coef[0]  # (k, 4): the first column's, for many angles at once

    def interval(self, psi: float) -> tuple[int, float]:
        """The grid interval of ``psi`` and the fraction of it that ``psi`` is into."""
        u = (psi % (2 * math.pi)) / self.h
        i = min(int(u), self.k - 1)
        return i, u - i

    def values(self, psi: np.ndarray) -> np.ndarray:
        """The first column at every turning angle of ``psi`` (rad), the same numbers :meth:`value` gives one
        at a time."""
        u = np.mod(psi, 2 * math.pi) / self.h
        i = np.minimum(u.astype(int), self.k - 1)
        x = (u - i) * self.h
        c3, c2, c1, c0 = self.first[i].T
        return ((c3 * x + c2) * x + c1) * x + c0

    def value(self, i: int, f: float) -> float:
        """The first column at the fraction ``f`` into grid interval ``i``."""
        x = f * self.h
        c3, c2, c1, c0 = self.c[i][0]
        return ((c3 * x + c2) * x + c1) * x + c0

    def at(self, psi: float) -> tuple[Curve, ...]:
        """Every column at ``psi``, in the order given, with its first and second derivatives."""
        i, f = self.interval(psi)
        x = f * self.h
        out = []
        for c3, c2, c1, c0 in self.c[i]:  # tuple.__new__: the Curve without its Python-level constructor
            out.append(
                _tuple(Curve, (((c3 * x + c2) * x + c1) * x + c0, (3 * c3 * x + 2 * c2) * x + c1, 6 * c3 * x + 2 * c2))
            )
        return tuple(out)


class InertiaAndLoad(NamedTuple):
    """The machine unit at one turning angle: ``inertia`` ``J + J_d`` (kg m^2) and the reduced load
    moment ``load`` ``M`` (N m)."""

    inertia: float
    load: float


class Model:
    """``J`` and ``M`` of a :class:`~linkwork.machine.reduction.Reduced` as fast scalar functions: ``J``
    by a periodic cubic spline, ``M`` linear between the grid points (technological loads have corners)."""

    def __init__(self, red: Reduced, extra_inertia: float = 0.0) -> None:
        self.inertia = PeriodicSplines(red.psi, [red.inertia])
        self.m = list(map(float, np.append(red.load, red.load[0])))
        self.extra = float(extra_inertia)
        damping = red.damping
        #: the dampers' reduced coefficient, linear between the grid points like ``M``; None without dampers
        self.b = None if damping is None else list(map(float, np.append(damping, damping[0])))

    def damping(self, psi: float) -> float:
        """The dampers' reduced coefficient ``B`` (N m s/rad) at ``psi``: their moment is ``-B omega``."""
        if self.b is None:
            return 0.0
        i, f = self.inertia.interval(psi)
        return self.b[i] + (self.b[i + 1] - self.b[i]) * f

    def at(self, psi: float) -> InertiaAndLoad:
        """``J + J_d`` and ``M`` at ``psi``."""
        i, f = self.inertia.interval(psi)
        m = self.m[i] + (self.m[i + 1] - self.m[i]) * f
        return _tuple(InertiaAndLoad, (self.inertia.value(i, f) + self.extra, m))

    def inertias(self, psi: np.ndarray) -> np.ndarray:
        """``J + J_d`` at every turning angle of ``psi`` (rad), as :meth:`at` gives them one at a time."""
        return self.inertia.values(psi) + self.extra


@dataclass(frozen=True)
class Turn:
    """One turn of the crank: when it started and ended (s), the crank speeds in it (rad/s) and the
    speed at its end (from the solver's step onto the end, not from the interpolant)."""

    start: float
    end: float
    omega_min: float
    omega_max: float
    omega_end: float = math.nan

    @property
    def omega_mean(self) -> float:
        """Average speed over the turn, ``2 pi / duration``."""
        return 2 * math.pi / (self.end - self.start)

    @property
    def delta(self) -> float:
        """Coefficient of speed fluctuation ``(max - min) / mean``, the mean taken as ``(max + min) / 2``."""
        return 2 * (self.omega_max - self.omega_min) / (self.omega_max + self.omega_min)


@dataclass(frozen=True)
class Motion:
    """A simulated run.

    Attributes
    ----------
    t, psi, omega : ndarray
        Time (s), turning angle of the crank (rad, from the assembly angle) and its speed (rad/s),
        at the solver's dense-output points.
    turns : list of Turn
    steady : bool
        Whether the run reached its steady cycle (consecutive turns alike within ``tol``).
    """

    t: np.ndarray
    psi: np.ndarray
    omega: np.ndarray
    turns: list[Turn]
    steady: bool

    @property
    def last(self) -> Turn:
        return self.turns[-1]

    def startup_time(self, within: float = 0.02) -> float:
        """Time (s) until the turns' mean speed stays within ``within`` of the last turn's."""
        target = self.last.omega_mean
        start = self.last.start
        for turn in reversed(self.turns):  # back from the end while the turns stay within
            if abs(turn.omega_mean - target) > within * target:
                break
            start = turn.start
        return start

    def cycle(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The last turn: time from its start, turning angle within the turn (0 to 2 pi, from
        :attr:`cycle_start`), speed; each sample once (the turns of :attr:`t` share their ends, so a
        turn's first sample is also the last of the turn before)."""
        last = self.last
        sel = np.flatnonzero((self.t >= last.start) & (self.t <= last.end))
        sel = sel[np.r_[True, np.diff(self.t[sel]) > 0]]
        return self.t[sel] - last.start, self.psi[sel] - self.psi[sel][0], self.omega[sel]

    @property
    def cycle_start(self) -> float:
        """Turning angle (rad, from the assembly angle) at the start of the last turn, where the turning
        angle of :meth:`cycle` is 0: the crank's drive angle there is its assembly angle plus this, in the
        direction of rotation."""
        return float(self.psi[np.flatnonzero(self.t >= self.last.start)[0]])


def run_turns(
    red: Reduced,
    drive: MotorGear,
    *,
    omega0: float = 0.0,
    start: float = 0.0,
    turns: int = 500,
    tol: float = 1e-6,
    rtol: float = 1e-10,
    points: int = 720,
) -> Motion:
    """Run the machine unit from the turning angle ``start`` (rad from the assembly angle) at crank
    speed ``omega0`` until the steady cycle (``turns`` at the most).

    ``drive`` has ``moment(omega)`` (N m on the crank) and ``inertia`` (its constant inertia on the
    crank shaft).  ``points`` + 1 points, uniform in the turning angle, are kept per turn; the
    steady cycle is reached when two turns in a row have the same mean and least speed within
    ``tol`` (relative).
    """
    unit = _Unit(Model(red, drive.inertia), drive.moment, float(start), rtol, points)
    first, t0, e0 = unit.first_step(omega0)
    ts, ps, ws, done = [], [], [], []
    for k in range(turns):
        lo = first if k == 0 else unit.psi0 + 2 * np.pi * k
        t, psi, w, turn, e0 = unit.turn(k, lo, t0, e0, from_rest=k == 0 and omega0 == 0)
        ts.append(t)
        ps.append(psi)
        ws.append(w)
        done.append(turn)
        t0 = turn.end
        if len(done) > 2 and _alike(done[-2], done[-1], tol):
            break
    steady = len(done) > 2 and abs(done[-1].omega_mean - done[-2].omega_mean) <= tol * done[-1].omega_mean
    return Motion(np.concatenate(ts), np.concatenate(ps), np.concatenate(ws), done, steady)


def _alike(a: Turn, b: Turn, tol: float) -> bool:
    """Whether two turns have the same mean and least speed within ``tol`` of the later one's mean."""
    scale = b.omega_mean
    return all(abs(x - z) <= tol * scale for x, z in ((a.omega_mean, b.omega_mean), (a.omega_min, b.omega_min)))


def _stalled(psi: float, y: np.ndarray) -> float:
    return float(y[1])


@dataclass(frozen=True)
class _Unit:
    """The machine unit's energy equation with the crank's turning angle as the independent variable:
    the state is ``(t, E)``, time (s) and kinetic energy (J), from the turning angle ``psi0``."""

    model: Model
    moment: Callable[[Any], Any]
    psi0: float
    rtol: float
    points: int

    def __call__(self, psi: float, y: np.ndarray) -> list[float]:
        """``dt/dpsi`` and ``dE/dpsi``."""
        j, m = self.model.at(psi)
        e = max(y[1], 1e-300)
        w = math.sqrt(2 * e / j)
        if self.model.b is not None:
            m -= self.model.damping(psi) * w
        return [1.0 / w, m + float(self.moment(w))]

    def first_step(self, omega0: float) -> tuple[float, float, float]:
        """Where the integration starts: turning angle, time and kinetic energy; from rest the first
        micro-radian is taken in closed form (constant moment), where ``dt/dpsi`` is infinite."""
        psi0 = self.psi0
        j0 = self.model.at(psi0).inertia
        if omega0 < 0:
            raise LinkworkError(f"omega0: the crank turns forward, from rest or faster; got {omega0}")
        if omega0 != 0:
            return psi0, 0.0, 0.5 * j0 * omega0**2
        m0 = self.model.at(psi0).load + float(self.moment(0.0))
        if not m0 > 0:
            raise LinkworkError(
                f"the drive cannot start the crank at {math.degrees(psi0 % (2 * np.pi)):.1f} deg of turning: "
                f"its moment at rest ({float(self.moment(0.0)):.6g} N m) does not overcome the loads "
                f"({-self.model.at(psi0).load:.6g} N m)"
            )
        step = 1e-6
        return psi0 + step, math.sqrt(2 * j0 * step / m0), m0 * step

    def turn(
        self, k: int, lo: float, t0: float, e0: float, from_rest: bool
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, Turn, float]:
        """Turn ``k`` from the turning angle ``lo`` at time ``t0`` with kinetic energy ``e0``: its
        samples (time, turning angle, speed), the :class:`Turn` and the kinetic energy at its end."""
        hi = self.psi0 + 2 * np.pi * (k + 1)
        stalled = IntegrationEvent("stalled", _stalled, -1)
        sol = integrate(self, (lo, hi), [t0, e0], rtol=self.rtol, atol=[1e-12, 1e-12 * max(e0, 1.0)], events=stalled)
        if sol.status != 0:
            where = float(sol.t[-1]) - self.psi0
            raise LinkworkError(
                f"the drive cannot carry the crank through turn {k + 1}: it stops "
                f"{math.degrees(where % (2 * np.pi)):.1f} deg of turning after the start "
                "(too weak a motor, or too little flywheel for the work of the cycle)"
            )
        grid = np.linspace(lo, hi, self.points + 1)
        y = sol.sol(grid)
        j = self.model.inertias(grid)
        w = np.sqrt(2 * np.maximum(y[1], 0.0) / j)
        if from_rest:
            grid, y, w = (
                np.concatenate([[self.psi0], grid]),
                np.concatenate([[[0.0], [0.0]], y], axis=1),
                np.append(0.0, w),
            )
        t1, e1 = float(sol.y[0, -1]), float(sol.y[1, -1])
        w1 = math.sqrt(2 * e1 / self.model.at(hi)[0])
        low, high = self._extremes(sol, grid[-self.points - 1 :], w[-self.points - 1 :])
        low = min(low, float(w.min()))  # a run from rest starts at 0
        return y[0], grid, w, Turn(float(y[0][0]) if k else 0.0, t1, low, high, w1), e1

    def _extremes(self, sol: Any, grid: np.ndarray, w: np.ndarray) -> tuple[float, float]:
        """The least and largest speed of a turn, refined between the points kept (``grid``, ``w``) on the solver's
        dense output by the rule of every peak (:func:`linkwork.kinetostatics.peaks.refine`)."""
        from linkwork.kinetostatics.peaks import refine

        def speed(at: np.ndarray) -> np.ndarray:
            psi = np.clip(at[0], grid[0], grid[-1])
            return np.sqrt(2 * np.maximum(sol.sol(psi)[1], 0.0) / self.model.inertias(psi))[None]

        low, high = (refine(w[None], grid, speed, kind).value[0] for kind in ("min", "max"))
        return float(low), float(high)
