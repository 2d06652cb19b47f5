"""The phases of the working cycle, each integrated to its first event (:mod:`linkwork.impulse.cycle`).

* ``flight``: the striker free, the tool on its seat: one degree of freedom (``psi``); it ends where
  the striker reaches the tool (``reach``);
* ``apart``: striker and tool moving apart: two degrees of freedom (``psi``, ``u``), the tool in free
  flight (:class:`~linkwork.impulse.contact.FreeTool`); it ends where they meet again (``gap``) or
  the tool is back on its seat;
* ``contact``: the striker pushing the tool: one degree of freedom, the contact force the constraint's
  multiplier; it ends where the force falls to zero (``separate``), the tool is back on its seat
  (``seated``), the tool's motion turns (``turn``) or the striker's sliding does (``slide``), or
  friction would lock the contact (``locking``).

Every phase also ends where the crank stops (``stalled``).  Between events the motion is integrated
with scipy's ``solve_ivp`` (DOP853); each function returns a :class:`Segment` with its samples and
the names of the events that ended it.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any, NamedTuple

import numpy as np

from linkwork.errors import LinkworkError
from linkwork.impulse.contact import OMEGA, PSI, ContactFlags, ContactModel, FreeTool
from linkwork.machine.integration import IntegrationEvent, fired, integrate

FLIGHT, APART, CONTACT = "flight", "apart", "contact"
#: The phases, in the order of their codes in the samples (``mode``).
KINDS = (FLIGHT, APART, CONTACT)
#: Degrees of freedom of the machine (mechanism and tool) in each phase.
FREEDOM = {FLIGHT: 1, APART: 2, CONTACT: 1}
#: m: a gap event fires this far past touching, not lost to rounding at zero.
SLACK = 1e-12


class Samples(NamedTuple):
    """Samples of a run, (k,) each: time (s), turning angle (rad), crank speed (rad/s), the tool's
    travel into the work (m) and its speed (m/s), the contact force (N, NaN outside contact), the
    phase (its index in :data:`KINDS`), the crank's acceleration and friction over contact force
    (in contact; NaN elsewhere)."""

    t: np.ndarray
    psi: np.ndarray
    omega: np.ndarray
    u: np.ndarray
    v: np.ndarray
    force: np.ndarray
    mode: np.ndarray
    acceleration: np.ndarray
    phi: np.ndarray


@dataclass(frozen=True)
class Segment:
    """A stretch of one phase, from ``start`` to ``end`` (s), integrated until its first event.

    ``state`` is the state at its end (:data:`~linkwork.impulse.contact.PSI` ...), ``psi_start`` the
    turning angle where it began, ``events`` the names of the events that ended it (none: it reached
    the end of its span), ``flags`` how the striker pressed the tool (contact only)."""

    kind: str
    start: float
    end: float
    psi_start: float
    state: np.ndarray
    samples: Samples
    events: frozenset[str]
    flags: ContactFlags | None = None


def _stalled(t: float, y: np.ndarray) -> float:
    return y[OMEGA]


#: The crank stops (or turns back).
STALLED = IntegrationEvent("stalled", _stalled, -1)


def _integrate(
    kind: str,
    rates: Callable[[float, np.ndarray], Any],
    t: float,
    t_end: float,
    y: np.ndarray,
    rtol: float,
    events: Sequence[IntegrationEvent],
    **options: Any,
) -> Any:
    """The machine's integrator (:func:`linkwork.machine.integration.integrate`, DOP853) from ``(t, y)`` to
    ``t_end`` or the first terminal event; its failure is reported."""
    dense = bool(options.pop("dense_output", False))
    sol = integrate(rates, (t, t_end), y, rtol=rtol, atol=1e-12, events=list(events), dense=dense, **options)
    if sol.status == -1:
        raise LinkworkError(f"the integrator failed in the {kind} phase: {sol.message}")
    return sol


def _segment(
    kind: str,
    t: float,
    sol: Any,
    samples: Samples,
    events: Sequence[IntegrationEvent],
    flags: ContactFlags | None = None,
) -> Segment:
    """The segment of ``kind`` from ``t`` that ``solve_ivp`` solved (``sol``) with ``events``."""
    y_end = sol.y[:, -1].copy()
    return Segment(kind, t, float(sol.t[-1]), float(sol.y[0, 0]), y_end, samples, fired(events, sol), flags)


def _unpressed(sol: Any, kind: str, u: np.ndarray, v: np.ndarray) -> Samples:
    """The samples of a phase without contact, at the solver's steps."""
    nan = np.full(len(sol.t), np.nan)
    force = np.full_like(sol.t, np.nan)
    return Samples(sol.t, sol.y[0], sol.y[1], u, v, force, np.full(len(sol.t), KINDS.index(kind)), nan, nan)


def fly(model: ContactModel, t: float, y: np.ndarray, rtol: float, point: str) -> Segment:
    """The striker free, the tool on its seat, from ``(t, y)`` until the striker (the point ``point``)
    reaches the tool or the crank stops; at most 20 turns."""

    def reach(t_: float, y_: np.ndarray) -> float:
        return model.curves(y_[PSI]).height.value + SLACK

    events = [IntegrationEvent("reach", reach, -1), STALLED]
    horizon = t + 40 * math.pi / max(y[OMEGA], 1e-6)
    sol = _integrate(FLIGHT, model.free_rates, t, horizon, y, rtol, events)
    if sol.status == 0:
        raise LinkworkError(f'"{point}" does not come back to the tool within 20 turns of the crank')
    return _segment(FLIGHT, t, sol, _unpressed(sol, FLIGHT, np.zeros_like(sol.t), np.zeros_like(sol.t)), events)


def part(model: ContactModel, t: float, y: np.ndarray, rtol: float, free: FreeTool, fine_until: float) -> Segment:
    """Striker and tool apart, the tool flying ``free``, from ``(t, y)`` until they meet again, the
    tool is back on its seat or the crank stops; in short steps until ``fine_until`` (s), where the
    two may meet again at once (the segment then ends there)."""

    def gap(t_: float, y_: np.ndarray) -> float:
        return model.curves(y_[PSI]).height.value + free.state(t_).travel + SLACK

    events = [IntegrationEvent("gap", gap, -1), STALLED]
    span = max(free.t_seat - t, 1e-12)
    if t < fine_until:  # short steps while the two may meet again at once
        t_end, step = min(fine_until, t + span), (fine_until - t) / 32
    else:
        t_end, step = t + span, span / 64
    sol = _integrate(APART, model.free_rates, t, t_end, y, rtol, events, max_step=max(step, 1e-12))
    tool = [free.state(x) for x in sol.t]
    u = np.array([a for a, _ in tool])
    v = np.array([b for _, b in tool])
    return _segment(APART, t, sol, _unpressed(sol, APART, u, v), events)


def press(model: ContactModel, t: float, y: np.ndarray, rtol: float) -> Segment:
    """The striker pushing the tool from ``(t, y)``, with the flags of the start, until the contact
    force falls to zero, the tool is on its seat, the tool's motion or the striker's sliding turns,
    friction would lock the contact or the crank stops; at most two turns.  Sampled densely (the
    phase carries the forces): at least 33 samples, from the solver's interpolant."""
    flags = model.flags(y[PSI], y[OMEGA])
    events = _contact_events(model, flags)
    horizon = t + 4 * math.pi / max(y[OMEGA], 1e-6)
    sol = _integrate(CONTACT, model.contact_rates(flags), t, horizon, y, rtol, events, dense_output=True)
    if sol.status == 0:
        raise LinkworkError("the striker stays on the tool for two turns of the crank")
    tt = np.linspace(sol.t[0], sol.t[-1], max(len(sol.t), 33))
    yy = sol.sol(tt)
    yy[:, 0], yy[:, -1] = sol.y[:, 0], sol.y[:, -1]
    heights = [model.curves(a).height for a in yy[0]]
    u = -np.array([h.value for h in heights])
    v = -np.array([h.slope for h in heights]) * yy[1]
    both = np.array([model.pressing(a, b, flags)[:2] for a, b in zip(yy[0], yy[1], strict=True)])
    code = np.full(len(tt), KINDS.index(CONTACT))
    samples = Samples(tt, yy[0], yy[1], u, v, both[:, 0], code, both[:, 1], np.full(len(tt), flags.phi))
    return _segment(CONTACT, t, sol, samples, events, flags=flags)


def _contact_events(model: ContactModel, flags: ContactFlags) -> list[IntegrationEvent]:
    """The events that end a contact phase pressing so (``flags``)."""
    j_d, m_t = model.drive_inertia, model.tool.mass

    def separate(t_: float, y_: np.ndarray) -> float:
        return model.pressing(y_[PSI], y_[OMEGA], flags).force

    def seated(t_: float, y_: np.ndarray) -> float:
        return -model.curves(y_[PSI]).height.value

    def turn(t_: float, y_: np.ndarray) -> float:
        return -model.curves(y_[PSI]).height.slope * y_[OMEGA]

    def slide(t_: float, y_: np.ndarray) -> float:
        return model.curves(y_[PSI]).sliding.value * y_[OMEGA]

    def locking(t_: float, y_: np.ndarray) -> float:  # the effective inertia, over J + J_d
        c = model.curves(y_[PSI])
        j, ds, gt = c.inertia.value, c.height.slope, c.sliding.value
        return 1.0 + m_t * ds * (ds + flags.phi * gt) / (j + j_d) - 1e-9

    events = [
        IntegrationEvent("separate", separate, -1),
        IntegrationEvent("seated", seated, -1),
        IntegrationEvent("turn", turn, -1 if flags.into else 1),
        STALLED,
        IntegrationEvent("locking", locking, -1),
    ]
    if model.friction > 0:
        events.append(IntegrationEvent("slide", slide, 1 if flags.phi > 0 else -1))
    return events
