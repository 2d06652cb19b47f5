"""The tolerances a synthesised file's requirements carry: its lengths are written to 0.1 mm
(:func:`~linkwork.synthesis.common.step`), and each requirement the analysis measures moves with them by at most
what :func:`rounding_tolerances` finds; and what the analysis measures of a mechanism for the requirements of its
kind (:func:`measure`), which the file's verification and the report's requirements section read."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np

from linkwork.spec.reader import described
from linkwork.synthesis.common import TOLERANCE, VERIFY_STEPS, step

if TYPE_CHECKING:
    from linkwork.motion.kinematic_analysis import Kinematics
    from linkwork.spec.schema import Spec

#: Headroom over the first-order bound of :func:`rounding_tolerances` for its second-order remainder.
MARGIN = 1.1

#: A kind's own measurement of a solved turn (its ``variant``), beside what :func:`measure` measures of every kind:
#: :attr:`linkwork.synthesis.kinds.Kind.measure` (the shears' :func:`knives`).
Own = Callable[["Kinematics", int], dict[str, float]]


def tolerances_of(spec: Spec, own: Own | None = None, paths: list[str] | None = None) -> dict[str, float]:
    """The tolerances the rounding of ``spec``'s lengths (``paths``, else every nonzero one) implies for the
    requirements its kind's measurement gives (``own`` beside the common one, :func:`rounding_tolerances`)."""
    from linkwork.api import mechanism_of

    return rounding_tolerances(mechanism_of(spec), own, paths)


def rounding_tolerances(mech: Any, own: Own | None = None, paths: list[str] | None = None) -> dict[str, float]:
    """The tolerance (SI) of each requirement the analysis measures on a file whose lengths are written to the
    step :func:`~linkwork.synthesis.common.step` (0.1 mm, :data:`~linkwork.synthesis.common.STEP`).

    Each written length (``paths``, named parameters; by default every nonzero length of ``mech``) is within
    delta = step / 2 of the exact one, so to first order a requirement q measured on the file is within
    ``sum_i |dq/dx_i| delta`` of its exact value.  Each term is the central difference
    ``|q(x + delta e_i) - q(x - delta e_i)| / 2`` as the analysis measures it on the file (exact where q is
    quadratic in x_i); the second-order remainder, ``1/2 sum_ij |d2q/dx_i dx_j| delta^2``, is about delta / L of the
    first-order term for lengths L (under 1e-3 for lengths over 50 mm), so the tolerance is the first-order bound
    times :data:`MARGIN`, plus the analysis's own resolution (:data:`~linkwork.synthesis.common.TOLERANCE` of q).

    Parameters
    ----------
    mech : Mechanism
        The written file, compiled.
    own : callable, optional
        The kind's own measurement beside the common one (:func:`measure`).
    paths : list of str, optional
        The lengths the file rounds.

    Returns
    -------
    dict
        Requirement name -> tolerance (m, rad or a ratio), for each measured quantity.
    """
    from linkwork.api import kinematics
    from linkwork.structure.parameters import parameter_list

    delta = step() / 2
    lengths = {p.name: p.value for p in parameter_list(mech) if p.kind == "length" and p.value != 0}
    names = list(lengths) if paths is None else list(paths)
    variants = {name: np.full(2 * len(names) + 1, lengths[name]) for name in names}
    for i, name in enumerate(names):
        variants[name][2 * i + 1 : 2 * i + 3] += (delta, -delta)
    kin = kinematics(mech, steps=VERIFY_STEPS, variants=variants)
    runs = [measure(kin, own, v) for v in range(2 * len(names) + 1)]
    out = {}
    for key, value in runs[0].items():
        first = sum(abs(runs[2 * i + 1][key] - runs[2 * i + 2][key]) / 2 for i in range(len(names)))
        out[key] = MARGIN * first + TOLERANCE * abs(value)
    return out


def measure(kin: Kinematics, own: Own | None = None, variant: int = 0) -> dict[str, float]:
    """What the analysis measures of the working member over ``kin`` (its ``variant``): stroke or swing, time
    ratio, the largest pressure angle (of the dyads driving a slider, else of all) and the least transmission
    angle; then the kind's ``own`` measurement (the shears' knives, :func:`knives`)."""
    from linkwork.motion.analysis import extremes, transmission, working

    out: dict[str, float] = {}
    members = working(kin.mechanism)
    found = {e.name: e for e in extremes(kin, variant)}
    if members and members[0].name in found:
        e = found[members[0].name]
        out["stroke" if e.kind == "slider" else "swing"] = e.stroke
        out["time_ratio"] = e.time_ratio
    angles = transmission(kin)
    if angles:
        least = {k: float(np.nanmin(np.atleast_2d(v)[variant])) for k, v in angles.items()}
        sliding = [v for k, v in least.items() if k.endswith("RRP")] or list(least.values())
        out["max_pressure_angle"] = math.pi / 2 - min(sliding)
        out["min_transmission_angle"] = min(least.values())
    if own is not None:
        out.update(own(kin, variant))
    return out


def knives(kin: Kinematics, variant: int = 0) -> dict[str, float]:
    """The knives' strokes, K, overlap and opening of the shears solved in ``kin`` (its ``variant``) as the design
    metrics measure them, each knife's stroke along its guide as the file names it
    (:func:`~linkwork.spec.shears.shears_parts`)."""
    from linkwork.design.evaluate import Evaluation
    from linkwork.design.metrics import METRICS
    from linkwork.errors import SynthesisError
    from linkwork.spec.shears import shears_parts

    found = shears_parts(described(kin.mechanism.description))
    if isinstance(found, str):
        raise SynthesisError(f"double-cut shears: the mechanism's file has no {found}")
    upper, lower = found.guides
    ev = Evaluation(kin)

    def one(name: str, arg: str | None = None) -> float:
        return float(np.ravel(METRICS[name].compute(ev, arg))[variant])

    return {
        "upper_stroke": one("stroke", upper),
        "lower_stroke": one("stroke", lower),
        "time_ratio": one("working_time_ratio"),
        "overlap": one("knife_overlap"),
        "opening": one("knife_clearance"),
    }
