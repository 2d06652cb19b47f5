"""The percussion machine reduced to the crank's turning angle and the tool's travel: the contact model
of the working cycle (:mod:`linkwork.impulse.cycle`).

The crank turns through ``psi`` with the speed ``omega = psi'``; the mechanism's reduced inertia
``J(psi)`` and load moment ``M(psi)``, the height ``s(psi)`` of the striking point K above the seated
face along its normal ``n`` and K's sliding along the face per unit turning ``dK/dpsi . t`` are
periodic cubic splines over the turn (:class:`Curves`).  The drive adds its moment ``M_d(omega)``
and its constant inertia ``J_d``.  The tool, of mass ``m_t``, travels ``u`` into the work from its
seat; the feed ``F`` presses it back, the work resists its motion into it with ``F_w``.

Free of the tool the crank moves by ``(J + J_d) psi'' + J' psi'^2 / 2 = M + M_d``; pressing it
(``s + u = 0``) by the same equation with the contact force ``lambda`` acting through
``G_phi = s' + phi (dK/dpsi . t)`` (``phi = -f sgn(sliding)``), ``lambda`` being what keeps the tool
on the striker (:meth:`ContactModel.pressing`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from linkwork.errors import LinkworkError
from linkwork.machine.drive import Characteristic
from linkwork.machine.simulation import Curve, PeriodicSplines

_tuple = tuple.__new__

#: The integrated state, in order: turning angle ``psi`` (rad), crank speed ``omega`` (rad/s), and from
#: the start of the run the work of the drive on the crank, the work of the loads, the loss to friction
#: and the work done on the work (J).
PSI, OMEGA, DRIVE_WORK, LOAD_WORK, FRICTION_LOSS, WORK_DONE = range(6)


@dataclass(frozen=True)
class Tool:
    """The tool: ``mass`` (kg), the ``feed`` force pressing it towards the striker onto its seat
    (N, positive: it brings the tool back) and the work's ``resistance`` to its motion into it (N)."""

    mass: float
    feed: float
    resistance: float = 0.0

    def __post_init__(self) -> None:
        if not self.mass > 0:
            raise LinkworkError(f"tool: the mass must be positive, got {self.mass}")
        if not self.feed > 0:
            raise LinkworkError(f"tool: the feed force must be positive (it returns the tool), got {self.feed}")
        if not self.resistance >= 0:
            raise LinkworkError(f"tool: the work's resistance must not be negative, got {self.resistance}")


class Curves(NamedTuple):
    """The machine's curves at one turning angle ``psi``, each with its first and second derivatives
    in ``psi``."""

    #: ``J``: reduced inertia of the mechanism on the crank, kg m^2.
    inertia: Curve
    #: ``M``: reduced moment of gravity and the file's loads, N m.
    load: Curve
    #: ``s``: height of K above the seated face along its normal, m (its slope ``s' = dK/dpsi . n``).
    height: Curve
    #: ``dK/dpsi . t``: K's sliding along the face per unit turning of the crank, m/rad.
    sliding: Curve


class ContactFlags(NamedTuple):
    """How the striker presses the tool in a contact phase: whether the tool goes ``into`` the work
    (its resistance acts) and ``phi``, the friction over the contact force, ``-f sgn(sliding)``."""

    into: bool
    phi: float


class Pressing(NamedTuple):
    """The striker pressing the tool (:meth:`ContactModel.pressing`) at one state."""

    #: ``lambda``: the contact force, N (positive: pressing).
    force: float
    #: ``psi''``: the crank's angular acceleration, rad/s^2.
    acceleration: float
    #: ``dK/dpsi . t``, m/rad.
    sliding: float
    #: Friction over contact force.
    phi: float
    #: ``M``: the reduced load moment, N m.
    load: float
    #: ``s'``: the rate of the height of K over the turning of the crank, m/rad.
    height_slope: float
    #: ``M_d``: the drive's moment on the crank, N m.
    drive_moment: float


class ToolState(NamedTuple):
    """The tool's ``travel`` into the work from its seat (m) and its ``speed`` into it (m/s)."""

    travel: float
    speed: float


def heading(value: float, rate: float, scale: float) -> float:
    """The sign a quantity is taking: its own, or its rate's where it is zero (to rounding)."""
    if abs(value) > 1e-12 * max(abs(scale), 1.0):
        return math.copysign(1.0, value)
    return math.copysign(1.0, rate)


@dataclass(frozen=True)
class ContactModel:
    """The machine (mechanism and drive) on its crank's turning angle, and the tool.

    Attributes
    ----------
    splines : PeriodicSplines
        The columns of :class:`Curves`, in its order, over the turn.
    drive_inertia : float
        ``J_d``, kg m^2.
    efficiency : float
        Of the gear: the motor's shaft does the drive's work on the crank over it.
    moment : callable
        ``M_d(omega)``, N m on the crank.
    tool : Tool
    friction : float
        ``f`` between striker and tool.
    start_angle, sign : float
        The crank's drive angle at ``psi = 0`` and its direction of turning (+1 counter-clockwise).
    """

    splines: PeriodicSplines
    drive_inertia: float
    efficiency: float
    moment: Characteristic
    tool: Tool
    friction: float
    start_angle: float
    sign: float

    def curves(self, psi: float) -> Curves:
        """The machine's curves at the turning angle ``psi``."""
        return _tuple(Curves, self.splines.at(psi))  # tuple.__new__: without the Python-level constructor

    def degrees(self, psi: float) -> float:
        """The crank's drive angle at ``psi``, degrees in [0, 360)."""
        return math.degrees(self.start_angle + self.sign * psi) % 360

    def kinetic(self, psi: float, w: float, v: float) -> float:
        """Kinetic energy of machine and tool, J, at crank speed ``w`` and tool speed ``v``."""
        return 0.5 * (self.curves(psi).inertia.value + self.drive_inertia) * w * w + 0.5 * self.tool.mass * v * v

    def flags(self, psi: float, w: float) -> ContactFlags:
        """In contact: whether the tool is going into the work, and phi (against the sliding), from
        the signs the two velocities are taking (where they are zero, from their rates)."""
        c = self.curves(psi)
        ds, dds, gt, dgt = c.height.slope, c.height.curvature, c.sliding.value, c.sliding.slope
        into = heading(-ds * w, -dds * w * w, w * abs(ds) + 1e-300) > 0
        sliding = heading(gt * w, dgt * w * w, w * abs(gt) + 1e-300)
        return ContactFlags(into, -self.friction * sliding)

    def effective_inertia(self, psi: float, phi: float) -> float:
        """``J + J_d + m_t s' G_phi``, kg m^2: the inertia the crank meets pressing the tool."""
        c = self.curves(psi)
        j, ds, gt = c.inertia.value, c.height.slope, c.sliding.value
        return j + self.drive_inertia + self.tool.mass * ds * (ds + phi * gt)

    def locked(self, psi: float, inertia: float) -> LinkworkError:
        """The error of a contact that friction locks at ``psi``."""
        return LinkworkError(
            f"friction f = {self.friction:g} locks the contact at {self.degrees(psi):.1f} deg: the striker pressing "
            f"the tool would have no positive effective inertia (J + J_d + m_t s' G_phi = {inertia:.4g} kg m^2)"
        )

    def pressing(self, psi: float, w: float, flags: ContactFlags) -> Pressing:
        """The contact force and the crank's acceleration with the striker pressing the tool."""
        c = self.curves(psi)
        j, dj, m = c.inertia.value, c.inertia.slope, c.load.value
        ds, dds, gt = c.height.slope, c.height.curvature, c.sliding.value
        tool = self.tool
        jt = j + self.drive_inertia
        md = float(self.moment(w))
        q = m + md - 0.5 * dj * w * w
        phi = flags.phi
        gphi = ds + phi * gt
        rr = tool.resistance if flags.into else 0.0
        den = 1.0 + tool.mass * ds * gphi / jt  # the effective inertia of the contact over J + J_d
        if not den > 0:
            raise self.locked(psi, jt * den)
        lam = (tool.feed + rr - tool.mass * (dds * w * w + ds * q / jt)) / den
        return Pressing(lam, (q + gphi * lam) / jt, gt, phi, m, ds, md)

    def free_rates(self, t: float, y: np.ndarray) -> list[float]:
        """The rates of the state with the striker free of the tool."""
        c = self.curves(y[PSI])
        j, dj, m = c.inertia.value, c.inertia.slope, c.load.value
        w = y[OMEGA]
        md = float(self.moment(w))
        return [w, (m + md - 0.5 * dj * w * w) / (j + self.drive_inertia), md * w, m * w, 0.0, 0.0]

    def contact_rates(self, flags: ContactFlags) -> Callable[[float, np.ndarray], list[float]]:
        """The rates of the state with the striker pressing the tool so (``flags``)."""
        resistance = self.tool.resistance

        def rates(t: float, y: np.ndarray) -> list[float]:
            w = y[OMEGA]
            p = self.pressing(y[PSI], w, flags)
            v = -p.height_slope * w
            friction = -p.phi * p.force * p.sliding * w
            return [w, p.acceleration, p.drive_moment * w, p.load * w, friction, resistance * v if flags.into else 0.0]

        return rates


class FreeTool:
    """The tool flying free from ``(t0, u0, v0)``: a parabola into the work, another back to its seat."""

    def __init__(self, t0: float, u0: float, v0: float, tool: Tool) -> None:
        self.t0, self.u0, self.v0 = t0, u0, v0
        self.a_in = -(tool.feed + tool.resistance) / tool.mass
        self.a_out = -tool.feed / tool.mass
        if v0 > 0:
            self.t_top = t0 + v0 / -self.a_in
            self.u_top = u0 + v0 * v0 / (2 * -self.a_in)
        else:
            self.t_top, self.u_top = t0, u0
        self.resistance = tool.resistance
        # on the seat (u = 0) coming back
        if v0 > 0 or u0 > 0:
            if v0 > 0:
                self.t_seat = self.t_top + math.sqrt(2 * self.u_top / -self.a_out)
            else:
                a = 0.5 * self.a_out
                self.t_seat = t0 + (-v0 - math.sqrt(v0 * v0 - 4 * a * u0)) / (2 * a)
        else:
            self.t_seat = t0

    def state(self, t: float) -> ToolState:
        """Where the tool is at ``t`` and how fast it goes."""
        if t <= self.t_top and self.v0 > 0:
            d = t - self.t0
            return ToolState(self.u0 + self.v0 * d + 0.5 * self.a_in * d * d, self.v0 + self.a_in * d)
        if self.v0 > 0:
            d = t - self.t_top
            return ToolState(self.u_top + 0.5 * self.a_out * d * d, self.a_out * d)
        d = t - self.t0
        return ToolState(self.u0 + self.v0 * d + 0.5 * self.a_out * d * d, self.v0 + self.a_out * d)

    def work(self, t: float) -> float:
        """Work done on the work from ``t0`` to ``t``."""
        if self.v0 <= 0:
            return 0.0
        return self.resistance * (self.state(min(t, self.t_top))[0] - self.u0)
