"""``linkwork.bolt_speed``: the crank speed at which the foundation bolts start to be pulled (or carry a
given pull)."""

from __future__ import annotations

import math

import numpy as np

from linkwork.kinetostatics.peaks import POINTS, peak_of, refine
from linkwork.kinetostatics.reaction_forces import Forces, forces
from linkwork.limits import TURN_STEPS
from linkwork.structure.model import Mechanism


def bolt_speed(mech: Mechanism, pull: float = 0.0, *, steps: int = TURN_STEPS) -> float:
    """Uniform crank speed (rad/s) at which the largest pull on the bolts reaches ``pull`` (N), over
    ``steps`` equal steps of the turn.

    Parameters
    ----------
    mech : Mechanism
        A compiled mechanism (``linkwork.bolt_speed`` also takes a path, an example name or a Spec).
    pull : float
        The pull on the bolts, N (upward foundation force); default 0, the speed at which the frame lifts.
    steps : int
        Equal steps of one turn; default 360.

    Returns
    -------
    float
        The crank speed, rad/s; ``inf`` if no speed reaches the pull, 0 if the bolts carry it at rest.

    Examples
    --------
    >>> import linkwork as lw
    >>> round(lw.bolt_speed("four-bar", steps=36), 1)  # rad/s
    13.9

    With the crank turning uniformly, every velocity is proportional to the
    speed and every acceleration to its square, so the vertical foundation
    force is ``F(phi) = G(phi) + omega^2 I(phi)``: ``G`` from the weights
    (computed at rest) and ``I`` from the inertia (the force at 1 rad/s less
    ``G``).  The pull reaches ``pull`` first at ``omega^2 = min (pull - G) / I``
    over the angles where ``I > 0``, refined between the samples (and the largest pull at rest) by the rule of
    every peak (:func:`~linkwork.kinetostatics.peaks.refine`).  Returns ``inf`` if no speed does it,
    0 if the bolts carry that pull at rest already.
    """
    at_rest, at_one = forces(mech, steps=steps, speed=0.0), forces(mech, steps=steps, speed=1.0)
    lifting = peak_of(at_rest, lambda g: g.foundation_filled_all[..., 1], "max").value[0]
    if lifting >= pull:
        return 0.0

    def need(rest: Forces, one: Forces) -> np.ndarray:
        """The square of the speed at which the pull reaches ``pull`` at each sample, ``(V, A)``."""
        g = rest.foundation_filled_all[..., 1]
        inertia = one.foundation_filled_all[..., 1] - g
        return np.where(inertia > 0, (pull - g) / inertia, np.inf)

    def quantity(at: np.ndarray) -> np.ndarray:
        rest, one = at_rest.at(at), at_one.at(at)
        return np.full(at.shape, np.nan) if rest is None or one is None else need(rest, one).reshape(at.shape)

    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        best = float(refine(need(at_rest, at_one), at_rest.angles, quantity, "min", POINTS[0]).value[0])
    return math.sqrt(best) if math.isfinite(best) else math.inf
