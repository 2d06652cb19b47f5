"""Evaluating the metrics of a batch of design variants on one compiled mechanism.

The geometry of the variants goes through :func:`linkwork.kinematics` (one
compile, many dimension sets).  Mass properties are the file's, except where
a variant sets a link's mass (``links.NAME.mass``): then the link's moment of
inertia about its centre of mass scales with it (its radius of gyration and
its centre of mass are kept).  The loads on the links are linear in each
link's mass and moment of inertia, and so are the reactions: the driving
torque and the foundation loads of a variant are those of the file's masses
plus, for every varied link, ``(s - 1)`` times the change that doubling that
link's mass and inertia makes, ``s`` being the variant's mass over the file's.
That is exact, and costs one more solution of the reactions per varied mass.

At a singular position of a sample (a dead point where the reactions are
indeterminate, NaN) the driving torque and the foundation loads are still
defined: there they are taken from the power balance and from the theorem on
the change of momentum, as :meth:`linkwork.kinetostatics.Forces.bolts` does.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np


def balances_of(kin: Any) -> tuple[np.ndarray, np.ndarray]:
    """Driving torque from the power balance ``(V, A)`` and foundation loads from the momentum theorem
    ``(V, A, 3)``: defined also where the reactions are singular."""
    from linkwork.kinetostatics.reactions import inertia_and_gravity, momentum_check, power_check

    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        loads = inertia_and_gravity(kin)
        return power_check(kin, loads)[..., 0], momentum_check(kin, loads)


def forces_of(kin: Any) -> tuple[np.ndarray, np.ndarray]:
    """Multipliers ``(V, A, m)`` and foundation loads ``(V, A, 3)`` over a kinematics result
    (the same solution as :func:`linkwork.forces`, without solving the kinematics again)."""
    from linkwork.kinetostatics import fast
    from linkwork.kinetostatics.external import evaluate as applied
    from linkwork.kinetostatics.reactions import foundation, inertia_and_gravity, solve_reactions

    mech = kin.mechanism
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        if fast.available():
            return fast.run(kin, applied(kin) if mech.loads else None)
        loads = inertia_and_gravity(kin)
        lam, frame = solve_reactions(kin, loads)
        return lam, foundation(kin, frame, loads)


@dataclass
class Evaluation:
    """The kinematics of a batch of variants, and their forces when first asked for.

    Attributes
    ----------
    kin : Kinematics
        With a variant axis: ``(V, A, ...)``.
    mass_scale : dict
        Link index -> ``(V,)`` ratio of the variants' mass to the file's.
    """

    kin: Any
    mass_scale: dict[int, np.ndarray] = field(default_factory=dict)

    @cached_property
    def _forces(self) -> tuple[np.ndarray, np.ndarray]:
        lam, found = self._superposed(forces_of)
        torque = lam[..., 2 * self.kin.mechanism.n_pairs]
        singular = ~(np.isfinite(torque) & np.all(np.isfinite(found), axis=-1))
        if np.any(singular & self.kin.valid_all):
            power, momentum = self._superposed(balances_of)
            torque = np.where(np.isfinite(torque), torque, power)
            found = np.where(np.isfinite(found), found, momentum)
        return torque, found

    def _superposed(self, solve: Any) -> tuple[np.ndarray, np.ndarray]:
        """``solve(kin)`` at the variants' masses: the file's plus ``(s - 1)`` times the change that
        doubling each varied link's mass and inertia makes (both results are linear in them)."""
        a0, b0 = a, b = solve(self.kin)
        mech = self.kin.mechanism
        for link, scale in self.mass_scale.items():
            mass, inertia = mech.link_mass.copy(), mech.link_inertia.copy()
            mass[link] *= 2.0
            inertia[link] *= 2.0
            heavy = dataclasses.replace(mech, link_mass=mass, link_inertia=inertia)
            a2, b2 = solve(dataclasses.replace(self.kin, mechanism=heavy))
            s = scale - 1.0
            a = a + s.reshape(-1, *[1] * (a0.ndim - 1)) * (a2 - a0)
            b = b + s.reshape(-1, *[1] * (b0.ndim - 1)) * (b2 - b0)
        return a, b

    @property
    def driving_torque(self) -> np.ndarray:
        """Driving torque on the crank, N m: ``(V, A)``; from the power balance at singular samples."""
        return self._forces[0]

    @property
    def foundation(self) -> np.ndarray:
        """Force x, y (N) and moment (N m) on the foundation: ``(V, A, 3)``; from the momentum theorem at
        singular samples."""
        return self._forces[1]


def evaluate(
    mech: Any, paths: list[str], values: np.ndarray, requests: list[Any], steps: int = 360
) -> dict[str, np.ndarray]:
    """Metrics of a batch of variants.

    Parameters
    ----------
    mech : Mechanism
    paths : list of str
        The varied dimensions (:func:`linkwork.design.plan.design_parameters`).
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
    from linkwork.motion import kinematics

    values = np.asarray(values, dtype=float).reshape(len(values), len(paths))
    geometry, scale = {}, {}
    for j, path in enumerate(paths):
        if path.endswith(".mass"):
            link = mech.link_names.index(path.split(".")[1])
            scale[link] = values[:, j] / mech.link_mass[link]
        else:
            geometry[path] = values[:, j]
    if not geometry:  # a variant axis all the same
        first = next(p for p in _any_parameter(mech))
        geometry[first] = np.full(len(values), _any_parameter(mech)[first])
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        kin = kinematics(mech, steps=steps, variants=geometry)
        ev = Evaluation(kin, scale)
        ok = kin.valid_all.all(axis=1)
        out = {}
        for r in requests:
            column = np.asarray(r.metric.compute(ev, r.arg), dtype=float)
            out[r.column] = column if r.metric.name == "assembles" else np.where(ok, column, np.nan)
    return out


def _any_parameter(mech: Any) -> dict[str, float]:
    from linkwork.motion.geometry import parameters

    return parameters(mech)
