"""Evaluating the metrics of a batch of design variants on one compiled mechanism.

The variants go through :func:`linkwork.kinematics` (one compile, many
parameter sets) and, for the metrics that need them, :func:`linkwork.forces`
of that kinematics result.  An override means what the same edit of the file
means, mass properties included: values the file gives stay, defaults (the
middle of a rod's ends or the centroid, a uniform rod's ``m L^2 / 12``) follow the variant's geometry and
mass (the mass rule of :mod:`linkwork.structure.parameters`).  At a singular
position (a dead point, where the reactions are indeterminate) the driving
torque and the foundation loads are still defined, by the power balance and
the theorem on the change of momentum (:class:`linkwork.kinetostatics.Forces`).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np

from linkwork.kinetostatics.reaction_forces import Forces, forces_of
from linkwork.motion.kinematic_analysis import Kinematics, kinematics
from linkwork.structure.model import Mechanism

if TYPE_CHECKING:
    from linkwork.design.metrics import MetricRequest


@dataclass
class Evaluation:
    """The kinematics of a batch of variants, and their forces when first asked for.

    Attributes
    ----------
    kin : Kinematics
        With a variant axis: ``(V, A, ...)``.
    """

    kin: Kinematics

    @cached_property
    def forces(self) -> Forces:
        """The :class:`~linkwork.kinetostatics.Forces` of the variants."""
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            return forces_of(self.kin)

    @property
    def driving_torque(self) -> np.ndarray:
        """Driving torque on the crank, N m: ``(V, A)``; from the power balance at singular samples."""
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            return self.forces.driving_torque

    @property
    def foundation(self) -> np.ndarray:
        """Force x, y (N) and moment (N m) on the foundation: ``(V, A, 3)``; from the momentum theorem at
        singular samples."""
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            return self.forces.foundation


def evaluate(
    mech: Mechanism, paths: list[str], values: np.ndarray, requests: list[MetricRequest], steps: int = 360
) -> dict[str, np.ndarray]:
    """Metrics of a batch of variants.

    Parameters
    ----------
    mech : Mechanism
    paths : list of str
        The varied parameters (:func:`linkwork.parameters`).
    values : ndarray, shape (V, len(paths))
        Their values, SI.
    requests : list of MetricRequest
    steps : int
        Crank angles of the turn.

    Returns
    -------
    dict
        Column name -> ``(V,)`` float array; NaN in every metric but ``assembles`` for a variant
        that does not assemble at every angle.
    """
    values = np.asarray(values, dtype=float).reshape(len(values), len(paths))
    overrides = {path: values[:, j] for j, path in enumerate(paths)}
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        kin = kinematics(mech, steps=steps, variants=overrides)
        ev = Evaluation(kin)
        ok = kin.valid_all.all(axis=1)
        out = {}
        for r in requests:
            column = np.asarray(r.metric.compute(ev, r.arg), dtype=float)
            out[r.column] = column if r.metric.name == "assembles" else np.where(ok, column, np.nan)
    return out
