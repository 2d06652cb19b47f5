"""Flywheel sizing by the energy method, and the exact cycle under a constant drive moment.

Energy method (after Merkalov): at a nearly uniform speed the drive gives
the constant moment that balances the loads over a turn, ``M_d = -mean(M)``.
The work ``A(psi) = integral (M + M_d) dpsi`` goes into kinetic energy; of it,
the mechanism's own reduced inertia takes ``J(psi) omega_m^2 / 2`` (its
variable part, counted at the mean speed), and the rest changes the energy of
the constant inertia ``J_c`` (flywheel, rotor): ``E(psi) = A(psi) - J(psi)
omega_m^2 / 2``.  Its swing over the turn, ``dE = max E - min E``, is
``J_c omega_m^2 delta``, whence ``J_c = dE / (delta omega_m^2)``.

Wittenbauer's diagram plots the same energy ``A(psi)`` against the reduced
inertia ``J(psi)``.  Seen from the pole ``(-J_c, -T_0)`` a point of the curve
lies at the slope ``omega^2 / 2``; the tangents to the curve at the slopes
``omega_max^2 / 2`` and ``omega_min^2 / 2`` (``omega_max, min = omega_m (1 +- delta / 2)``)
meet at the pole, whence ``J_c = (b_max - b_min) / (delta omega_m^2)`` with ``b`` their intercepts:
exact under a constant drive moment, with no approximation for the variable part.

Under a constant drive moment the energy integral gives the exact periodic
cycle: ``(J(psi) + J_c) omega^2 / 2 = (J(0) + J_c) omega_0^2 / 2 + A(psi)``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from linkwork.errors import LinkworkError
from linkwork.kinetostatics.peaks import POINTS, refine
from linkwork.limits import delta_problem

if TYPE_CHECKING:
    from linkwork.machine.reduction import Reduced


@dataclass(frozen=True)
class Flywheel:
    """A flywheel sized by the energy method.

    Attributes
    ----------
    delta : float
        The coefficient of speed fluctuation asked for.
    omega_mean : float
        Mean crank speed, rad/s.
    energy_swing : float
        ``dE``, J.
    inertia : float
        Constant inertia needed on the crank shaft, kg m^2 (flywheel, rotor and gear together).
    on_crank : float
        The flywheel's inertia reduced to the crank shaft: ``inertia`` less the drive's own constant
        inertia (0 where that is enough already), kg m^2.
    drive_moment : float
        The constant drive moment that balances the loads over a turn, N m on the crank.
    drive_power : float
        ``drive_moment * omega_mean``, W: the mean power the drive gives the crank.
    shaft : str
        The shaft the flywheel is on, ``"crank"`` or ``"motor"``.
    ratio : float
        The gear ratio ``omega_motor / omega_crank`` (for a flywheel on the motor shaft).
    """

    delta: float
    omega_mean: float
    energy_swing: float
    inertia: float
    on_crank: float
    drive_moment: float
    drive_power: float
    shaft: str = "crank"
    ratio: float = 1.0

    @property
    def flywheel(self) -> float:
        """The flywheel's inertia on its own shaft, kg m^2: ``on_crank`` on the crank shaft,
        ``on_crank / ratio**2`` on the motor shaft."""
        return self.on_crank if self.shaft == "crank" else self.on_crank / self.ratio**2


def _work(red: Reduced, moment: float) -> np.ndarray:
    """Work of the loads and a constant drive ``moment`` from psi = 0 at the grid points, (K,)."""
    return red.work()[:-1] + moment * red.psi


def _extreme(red: Reduced, values: np.ndarray, at: Callable[[np.ndarray], np.ndarray], kind: str) -> float:
    """The largest (``kind`` ``"max"``) or least (``"min"``) over the turn of a quantity whose values at the grid's
    points are ``values`` ``(K,)`` and ``at(psi) -> (N,)`` at any turning angles: refined between the points by
    the rule of every peak (:func:`~linkwork.kinetostatics.peaks.refine`) where the reduced quantities are known
    between them (:attr:`Reduced.between`), so that it does not depend on the grid; else the grid's."""
    if red.between is None:
        return float(values.max() if kind == "max" else values.min())
    found = refine(values[None], red.psi, lambda x: at(x[0])[None], kind, POINTS[0])
    return float(found.value[0])


def _energy_extreme(red: Reduced, slope: float, kind: str) -> float:
    """The largest or least (``kind``) over the turn of ``A(psi) - slope * J(psi)``, ``A`` the work of the loads and
    of the constant drive moment that balances them (:func:`_extreme`)."""
    moment = -red.mean_load

    def at(psi: np.ndarray) -> np.ndarray:
        work, inertia = red.work_at(psi)
        out: np.ndarray = work + moment * psi - slope * inertia
        return out

    return _extreme(red, _work(red, moment) - slope * red.inertia, at, kind)


def size_flywheel(
    red: Reduced,
    delta: float,
    omega_mean: float,
    drive_inertia: float = 0.0,
    *,
    shaft: str = "crank",
    ratio: float = 1.0,
) -> Flywheel:
    """The constant inertia that keeps the speed fluctuation at ``delta``, by the energy method (Merkalov);
    ``drive_inertia`` is the drive's own on the crank shaft, ``shaft`` and ``ratio`` say where the flywheel goes."""
    _check_delta(delta)
    if not omega_mean > 0:
        raise LinkworkError(f"mean crank speed: expected a positive speed, got {omega_mean}")
    moment = -red.mean_load
    slope = 0.5 * omega_mean**2
    swing = _energy_extreme(red, slope, "max") - _energy_extreme(red, slope, "min")
    need = swing / (delta * omega_mean**2)
    return _flywheel(delta, omega_mean, swing, need, drive_inertia, moment, shaft, ratio)


def _check_delta(delta: float) -> None:
    """Raise LinkworkError unless ``delta`` is a coefficient of speed fluctuation from
    :data:`~linkwork.limits.MIN_DELTA` up to 1 (the inertia grows as 1/delta; below it a flywheel would
    be as good as infinite, and a tiny ``delta`` makes the tangents of Wittenbauer's diagram one line)."""
    why = delta_problem(delta, "delta")
    if why is not None:
        raise LinkworkError(why)


def _flywheel(
    delta: float,
    omega_mean: float,
    swing: float,
    need: float,
    drive_inertia: float,
    moment: float,
    shaft: str,
    ratio: float,
) -> Flywheel:
    if shaft not in ("crank", "motor"):
        raise LinkworkError(f'flywheel: on "motor" or "crank", got "{shaft}"')
    on_crank = max(need - drive_inertia, 0.0)
    return Flywheel(delta, omega_mean, swing, need, on_crank, moment, moment * omega_mean, shaft, ratio)


def wittenbauer(red: Reduced) -> tuple[np.ndarray, np.ndarray]:
    """Wittenbauer's diagram: the reduced inertia ``J(psi)`` and the energy ``A(psi)`` given to the
    machine from ``psi = 0`` by the loads and the constant drive moment that balances them, (K,) each."""
    return red.inertia, _work(red, -red.mean_load)


def size_flywheel_wittenbauer(
    red: Reduced,
    delta: float,
    omega_mean: float,
    drive_inertia: float = 0.0,
    *,
    shaft: str = "crank",
    ratio: float = 1.0,
) -> Flywheel:
    """The constant inertia for ``delta`` from the tangents to Wittenbauer's diagram; the arguments as
    for :func:`size_flywheel`."""
    _check_delta(delta)
    (k_max, b_max), (k_min, b_min) = wittenbauer_tangents(red, delta, omega_mean)
    need = (b_max - b_min) / (k_max - k_min)
    return _flywheel(delta, omega_mean, b_max - b_min, need, drive_inertia, -red.mean_load, shaft, ratio)


def wittenbauer_tangents(red: Reduced, delta: float, omega_mean: float) -> tuple[tuple[float, float], ...]:
    """The two tangents to Wittenbauer's diagram (:func:`wittenbauer`) for ``delta`` at ``omega_mean``,
    each ``(slope, intercept)`` of ``energy = slope * inertia + intercept`` (J, kg m^2): the upper at the
    slope ``omega_max^2 / 2``, the lower at ``omega_min^2 / 2``.  They meet at the inertia ``-need``, the
    constant inertia the crank shaft needs: ``need = (b_max - b_min) / (k_max - k_min)``, the segment
    they cut on the energy axis over the difference of their slopes."""
    k_max = 0.5 * (omega_mean * (1 + delta / 2)) ** 2
    k_min = 0.5 * (omega_mean * (1 - delta / 2)) ** 2
    return (k_max, _energy_extreme(red, k_max, "max")), (k_min, _energy_extreme(red, k_min, "min"))


def constant_moment_cycle(red: Reduced, inertia: float, omega_mean: float) -> tuple[np.ndarray, float]:
    """Exact periodic crank speed over a turn, (K,), under the constant drive moment that balances
    the loads, with a constant ``inertia`` added, the speed at ``psi = 0`` chosen so that
    ``(max + min) / 2 = omega_mean``; and its coefficient of speed fluctuation.  The largest and least
    speed are refined between the grid's points (:func:`_extreme`)."""
    moment = -red.mean_load
    work = _work(red, moment)
    total = red.inertia + inertia
    w0 = omega_mean
    for _ in range(50):
        start = 0.5 * total[0] * w0**2
        energy = start + work
        if energy.min() <= 0:
            raise LinkworkError("the crank stops within the turn at this speed: more inertia or more speed needed")
        omega = np.sqrt(2 * energy / total)

        def at(psi: np.ndarray, start: float = start) -> np.ndarray:
            done, own = red.work_at(psi)
            with np.errstate(invalid="ignore"):
                out: np.ndarray = np.sqrt(2 * (start + done + moment * psi) / (own + inertia))
            return out

        top, low = _extreme(red, omega, at, "max"), _extreme(red, omega, at, "min")
        mid = 0.5 * (top + low)
        if abs(mid - omega_mean) <= 1e-13 * omega_mean:
            break
        w0 += omega_mean - mid
    return omega, float((top - low) / mid)
