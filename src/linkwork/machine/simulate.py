"""Forward simulation of the machine unit from rest (or any speed) to its steady cycle.

The equation of motion ``J(psi) psi'' + J'(psi) psi'^2 / 2 = M(psi) + M_drive(psi')`` is the
derivative of the energy equation, which is integrated instead, with the crank's turning angle
``psi`` as the independent variable:

    dE/dpsi = M(psi) + M_drive(omega),   dt/dpsi = 1 / omega,   omega = sqrt(2 E / (J(psi) + J_d))

(``E`` the kinetic energy, ``J`` the reduced inertia of the mechanism as a periodic cubic spline
through its exact values, ``J_d`` the drive's constant inertia, ``M`` the reduced load moment,
linear between the grid points: technological loads have corners).  Without loads and drive the
energy stays exactly constant, and the turns are the natural steps: each is integrated from
``2 pi k`` to ``2 pi (k + 1)`` with scipy's ``solve_ivp`` (DOP853).  The crank must keep turning
forward: a drive too weak to carry it through a turn is reported.  From rest the first
micro-radian is taken in closed form (constant moment), where ``dt/dpsi`` is infinite.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from linkwork.errors import LinkworkError


class PeriodicSplines:
    """Periodic cubic splines of several columns over a turn of the crank, on a uniform grid ``psi``,
    evaluated one turning angle at a time (fast scalars)."""

    def __init__(self, psi: np.ndarray, columns: list[np.ndarray]) -> None:
        from scipy.interpolate import CubicSpline

        k = len(psi)
        self.k, self.h = k, 2 * math.pi / k
        x = np.append(psi, 2 * math.pi)
        coef = []
        for col in columns:
            spline = CubicSpline(x, np.append(col, col[0]), bc_type="periodic")
            coef.append(spline.c.T)  # per interval: cubic, square, linear, constant
        self.c = [tuple(map(float, np.concatenate([c[i] for c in coef]))) for i in range(k)]

    def interval(self, psi: float) -> tuple[int, float]:
        """The grid interval of ``psi`` and the fraction of it that ``psi`` is into."""
        u = (psi % (2 * math.pi)) / self.h
        i = min(int(u), self.k - 1)
        return i, u - i

    def value(self, i: int, f: float) -> float:
        """The first column at the fraction ``f`` into grid interval ``i``."""
        x = f * self.h
        c3, c2, c1, c0 = self.c[i][:4]
        return ((c3 * x + c2) * x + c1) * x + c0

    def at(self, psi: float) -> tuple[float, ...]:
        """Value and first and second derivatives of every column at ``psi``."""
        i, f = self.interval(psi)
        x = f * self.h
        c = self.c[i]
        out = []
        for j in range(0, len(c), 4):
            c3, c2, c1, c0 = c[j : j + 4]
            out += [((c3 * x + c2) * x + c1) * x + c0, (3 * c3 * x + 2 * c2) * x + c1, 6 * c3 * x + 2 * c2]
        return tuple(out)


class Model:
    """``J`` and ``M`` of a :class:`~linkwork.machine.reduced.Reduced` as fast scalar functions: ``J``
    by a periodic cubic spline, ``M`` linear between the grid points (technological loads have corners)."""

    def __init__(self, red: Any, extra_inertia: float = 0.0) -> None:
        self.inertia = PeriodicSplines(red.psi, [red.inertia])
        self.m = list(map(float, np.append(red.load, red.load[0])))
        self.extra = float(extra_inertia)

    def at(self, psi: float) -> tuple[float, float]:
        """``J + J_d`` and ``M`` at ``psi``."""
        i, f = self.inertia.interval(psi)
        m = self.m[i] + (self.m[i + 1] - self.m[i]) * f
        return self.inertia.value(i, f) + self.extra, m


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
        :attr:`cycle_start`), speed."""
        last = self.last
        sel = (self.t >= last.start) & (self.t <= last.end)
        return self.t[sel] - last.start, self.psi[sel] - self.psi[sel][0], self.omega[sel]

    @property
    def cycle_start(self) -> float:
        """Turning angle (rad, from the assembly angle) at the start of the last turn, where the turning
        angle of :meth:`cycle` is 0: the crank's drive angle there is its assembly angle plus this, in the
        direction of rotation."""
        return float(self.psi[np.flatnonzero(self.t >= self.last.start)[0]])


def simulate(
    red: Any,
    drive: Any,
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
    from scipy.integrate import solve_ivp

    model = Model(red, drive.inertia)
    moment = drive.moment

    def rhs(psi: float, y: np.ndarray) -> list[float]:
        j, m = model.at(psi)
        e = max(y[1], 1e-300)
        w = math.sqrt(2 * e / j)
        return [1.0 / w, m + float(moment(w))]

    def stalled(psi: float, y: np.ndarray) -> float:
        return y[1]

    stalled.terminal = True
    stalled.direction = -1
    psi0 = float(start)
    j0 = model.at(psi0)[0]
    if omega0 < 0:
        raise LinkworkError(f"omega0: the crank turns forward, from rest or faster; got {omega0}")
    t0, e0 = 0.0, 0.5 * j0 * omega0**2
    first = psi0
    if omega0 == 0:
        m0 = model.at(psi0)[1] + float(moment(0.0))
        if not m0 > 0:
            raise LinkworkError(
                f"the drive cannot start the crank at {math.degrees(psi0 % (2 * np.pi)):.1f} deg of turning: "
                f"its moment at rest ({float(moment(0.0)):.6g} N m) does not overcome the loads "
                f"({-model.at(psi0)[1]:.6g} N m)"
            )
        step = 1e-6
        first, e0, t0 = psi0 + step, m0 * step, math.sqrt(2 * j0 * step / m0)
    ts, ps, ws, done = [], [], [], []
    for k in range(turns):
        lo, hi = (first if k == 0 else psi0 + 2 * np.pi * k), psi0 + 2 * np.pi * (k + 1)
        sol = solve_ivp(
            rhs, (lo, hi), [t0, e0], method="DOP853", rtol=rtol, atol=[1e-12, 1e-12 * max(e0, 1.0)],
            events=stalled, dense_output=True,
        )  # fmt: skip
        if sol.status != 0:
            where = float(sol.t[-1]) - psi0
            raise LinkworkError(
                f"the drive cannot carry the crank through turn {k + 1}: it stops "
                f"{math.degrees(where % (2 * np.pi)):.1f} deg of turning after the start "
                "(too weak a motor, or too little flywheel for the work of the cycle)"
            )
        grid = np.linspace(lo, hi, points + 1)
        y = sol.sol(grid)
        j = np.array([model.at(p)[0] for p in grid])
        w = np.sqrt(2 * np.maximum(y[1], 0.0) / j)
        if k == 0 and omega0 == 0:
            grid, y, w = np.concatenate([[psi0], grid]), np.concatenate([[[0.0], [0.0]], y], axis=1), np.append(0.0, w)
        t1, e1 = float(sol.y[0, -1]), float(sol.y[1, -1])
        w1 = math.sqrt(2 * e1 / model.at(hi)[0])
        ts.append(y[0])
        ps.append(grid)
        ws.append(w)
        done.append(Turn(float(y[0][0]) if k else 0.0, t1, float(w.min()), float(w.max()), w1))
        t0, e0 = t1, e1
        if len(done) > 2:
            a, b = done[-2], done[-1]
            scale = b.omega_mean
            if all(abs(x - z) <= tol * scale for x, z in ((a.omega_mean, b.omega_mean), (a.omega_min, b.omega_min))):
                break
    steady = len(done) > 2 and abs(done[-1].omega_mean - done[-2].omega_mean) <= tol * done[-1].omega_mean
    return Motion(np.concatenate(ts), np.concatenate(ps), np.concatenate(ws), done, steady)
