"""The cross-checks of a force analysis, in one place: each result found again by an independent method, and how far
the two differ, the largest relative difference over the samples.  The command line (``linkwork forces``, its JSON),
the report and the viewer show them from here.

=====================================  ==========================================================================
``driving_torque_vs_power_balance``    the reactions' driving torque against the power balance
                                       (:attr:`Forces.checks <linkwork.kinetostatics.Forces.checks>`)
``foundation_force_vs_momentum``       the frame's reactions against the change of the links' momentum
``foundation_moment_vs_momentum``      their moment against the change of angular momentum
``driving_torque_vs_lever``            Zhukovsky's lever's balancing moment (:func:`~linkwork.kinetostatics.lever`)
                                       against the driving torque, relative to its largest size (one crank)
``force_plans_close``                  each group's force polygon (:func:`~linkwork.kinetostatics.force_plans`):
                                       its sum against its largest force (one crank)
=====================================  ==========================================================================

and each Assur group's free body: the residual of its balance against the largest force on it
(:func:`free_body_residuals`).  The graphical checks compare the samples where the mechanism moves and its groups
are solvable (not at a dead or change point, not where friction locks it).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from linkwork.structure.model import one_crank

if TYPE_CHECKING:
    from linkwork.kinetostatics.free_body import FreeBody
    from linkwork.kinetostatics.reaction_forces import Forces

__all__ = ["GRAPHICAL", "cross_checks", "free_body_residual", "free_body_residuals", "graphical_checks", "lever_gaps"]

#: The checks by the graphical method, on a mechanism of one crank.
GRAPHICAL = ("driving_torque_vs_lever", "force_plans_close")


def cross_checks(f: Forces) -> dict[str, float]:
    """Every cross-check of ``f`` but the free bodies (see the module): name -> the largest relative difference
    (NaN where there is nothing to compare); the graphical ones with one crank only."""
    out = dict(f.checks)
    if one_crank(f.mechanism):
        out |= graphical_checks(f)
    return out


def graphical_checks(f: Forces) -> dict[str, float]:
    """:data:`GRAPHICAL` of the first variant of ``f``, over the samples where it moves and is solvable."""
    from linkwork.kinetostatics.force_polygons import force_plans

    moving = _moving(f)
    if not moving.any():
        return dict.fromkeys(GRAPHICAL, math.nan)
    closure = 0.0
    for group in force_plans(f).groups:
        vectors = np.stack([p.vector[0, moving] for p in group.polygon])  # (P, S, 2)
        largest = np.max(np.hypot(vectors[..., 0], vectors[..., 1]), axis=0)
        total = np.hypot(*np.sum(vectors, axis=0).T)
        with np.errstate(invalid="ignore", divide="ignore"):
            closure = max(closure, float(np.nanmax(np.where(largest > 0, total / largest, total))))
    gaps = lever_gaps(f)[moving]  # NaN where there is nothing to compare (at rest: no torque)
    lever = float(np.nanmax(gaps)) if np.isfinite(gaps).any() else math.nan
    return {"driving_torque_vs_lever": lever, "force_plans_close": closure}


def _moving(f: Forces) -> np.ndarray:
    """The samples of the first variant of ``f`` where it moves and its groups are solvable, ``(A,)``."""
    return np.isfinite(np.asarray(f.driving_torque_all[0, :, 0])) & ~np.asarray(f.singular_all[0])


def lever_gaps(f: Forces, scale: float | None = None, balancing: np.ndarray | None = None) -> np.ndarray:
    """The difference of Zhukovsky's lever's balancing moment (``balancing`` ``(A,)`` where the caller has the lever
    already, else :func:`~linkwork.kinetostatics.lever` of ``f``) and the driving torque at each sample of the first
    variant of ``f``, over ``scale`` (default: the largest size of the driving torque where it moves): ``(A,)``,
    NaN where it does not."""
    from linkwork.kinetostatics.zhukovsky import lever

    if balancing is None:
        balancing = np.asarray(lever(f).balancing[0])
    torque = np.asarray(f.driving_torque_all[0, :, 0])
    moving = _moving(f)
    if scale is None:
        scale = float(np.max(np.abs(torque[moving]), initial=0.0))
    gap = np.abs(balancing - torque)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(moving, gap / scale if scale > 0 else gap, np.nan)


def free_body_residual(body: FreeBody) -> float:
    """How far the free body of a group is from balance: the largest residual force over the largest force on
    it, or the residual moment over that force times one metre more than the farthest point of application."""
    scale = max([float(np.nanmax(np.abs(c.force), initial=0.0)) for c in body.external] + [1e-300])
    arm = 1.0 + max(float(np.nanmax(np.abs(c.point), initial=0.0)) for c in body.external)
    force = float(np.nanmax(np.abs(body.residual[..., :2]), initial=0.0)) / scale
    moment = float(np.nanmax(np.abs(body.residual[..., 2]), initial=0.0)) / (scale * arm)
    return max(force, moment)


def free_body_residuals(f: Forces) -> dict[str, float]:
    """:func:`free_body_residual` of each Assur group of ``f``, by the group's label."""
    return {body.label: free_body_residual(body) for body in f.free_bodies()}
