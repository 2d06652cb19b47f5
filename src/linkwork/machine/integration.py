"""The one integrator of the machine unit's equation of motion, and its named events.

The steady cycle (:mod:`linkwork.machine.simulation`, turn by turn in the turning angle), the runs in time
(:mod:`linkwork.machine.timerun`, piece by piece between the crank's stops) and the phases of a working cycle of
blows (:mod:`linkwork.impulse.phases`) integrate the equations their reduced terms
(:mod:`linkwork.machine.reduction`) give through :func:`integrate`: SciPy's ``solve_ivp`` with the explicit
Runge-Kutta method of order 8 (DOP853), its dense output, and terminal events that say what ended a piece.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

#: The method of every integration of the machine's motion: explicit Runge-Kutta of order 8(5,3).
METHOD = "DOP853"


@dataclass(frozen=True)
class IntegrationEvent:
    """A terminal event of scipy's ``solve_ivp`` with a name: where ``fn(t, y)`` crosses zero in
    ``direction`` (negative: falling, positive: rising, zero: either way)."""

    name: str
    fn: Callable[[float, np.ndarray], float]
    direction: float = 0.0
    terminal: bool = True

    def __call__(self, t: float, y: np.ndarray) -> float:
        return self.fn(t, y)


def fired(events: Sequence[IntegrationEvent], sol: Any) -> frozenset[str]:
    """The names of the events that ended (or occurred in) the solution ``sol`` of ``solve_ivp``."""
    return frozenset(event.name for event, times in zip(events, sol.t_events, strict=True) if len(times))


def integrate(
    rates: Callable[[float, np.ndarray], Any],
    span: tuple[float, float],
    y0: Sequence[float] | np.ndarray,
    *,
    rtol: float,
    atol: float | Sequence[float],
    events: IntegrationEvent | Sequence[IntegrationEvent] | None = None,
    dense: bool = True,
    **options: Any,
) -> Any:
    """``dy/dt = rates(t, y)`` from ``y0`` over ``span`` (or to the first terminal event) by :data:`METHOD`.

    Parameters
    ----------
    rates : callable
        ``rates(t, y) -> dy/dt``, ``y`` of shape ``(n,)`` (the independent variable is time or the turning angle,
        as the caller's equation has it).
    span : (float, float)
        Where the integration starts and where it ends at the latest.
    y0 : array_like (n,)
        The state at ``span[0]``.
    rtol, atol : float
        The relative and absolute tolerances (``atol`` may be one a component).
    events : IntegrationEvent or sequence of them, optional
        Where the integration stops (terminal events) or what it records.
    dense : bool
        Keep the dense output (``sol.sol``), to read the solution between its steps.
    options
        Further options of ``solve_ivp`` (``first_step``, ``max_step``).

    Returns
    -------
    scipy.integrate OdeResult
        ``sol.t``, ``sol.y`` ``(n, steps)``, ``sol.status`` (0: the end of ``span``, 1: a terminal event, < 0:
        failure), ``sol.t_events`` and ``sol.sol``.
    """
    from scipy.integrate import solve_ivp

    return solve_ivp(rates, span, y0, method=METHOD, rtol=rtol, atol=atol, events=events, dense_output=dense, **options)
