"""The tolerances a synthesised file's requirements carry: its lengths are written to 0.1 mm
(:func:`~linkwork.synthesis.common.step`), and each requirement the analysis measures moves with them by at most
what :func:`measure_written` finds, in the one solve that also measures the file as written."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

from linkwork.synthesis.common import TOLERANCE, VERIFY_STEPS, step
from linkwork.synthesis.measuring import Own, measure

if TYPE_CHECKING:
    from linkwork.spec.schema import Spec
    from linkwork.structure.model import Mechanism

#: Headroom over the first-order bound of :func:`measure_written` for its second-order remainder.
MARGIN = 1.1


class Written(NamedTuple):
    """What the analysis measures of a written file (:func:`~linkwork.synthesis.measuring.measure`), SI, and the
    tolerance of each of those quantities that the rounding of its lengths implies, SI."""

    measured: dict[str, float]
    tolerances: dict[str, float]


def rounding_variants(mech: Mechanism, paths: list[str] | None = None) -> dict[str, np.ndarray]:
    """The variants of the written ``mech`` (:func:`linkwork.kinematics`'s ``variants``) that move each length of
    ``paths`` (named parameters; by default every nonzero length) by +-step / 2 in turn: variant 0 is the file as
    written, variants ``2 i + 1`` and ``2 i + 2`` move the ``i``-th length up and down, ``2 len(paths) + 1`` in all."""
    from linkwork.structure.parameters import parameter_list

    delta = step() / 2
    lengths = {p.name: p.value for p in parameter_list(mech) if p.kind == "length" and p.value != 0}
    names = list(lengths) if paths is None else list(paths)
    variants = {name: np.full(2 * len(names) + 1, lengths[name]) for name in names}
    for i, name in enumerate(names):
        variants[name][2 * i + 1 : 2 * i + 3] += (delta, -delta)
    return variants


def measure_written(mech: Mechanism, spec: Spec, own: Own | None = None, paths: list[str] | None = None) -> Written:
    """What the analysis measures of the written file ``spec`` (compiled: ``mech``) and the tolerance (SI) of each
    quantity measured, from one solve of the turn of the file and of each rounding variant
    (:func:`rounding_variants`).

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
    spec : Spec
        The written file.
    own : callable, optional
        The kind's own measurement beside the common one (:data:`~linkwork.synthesis.measuring.Own`).
    paths : list of str, optional
        The lengths the file rounds.

    Returns
    -------
    Written
        ``measured``: requirement name -> value measured on the file as written (variant 0); ``tolerances``:
        requirement name -> tolerance (m, rad or a ratio), for each quantity measured.
    """
    from linkwork.api import kinematics

    runs = measure(kinematics(mech, steps=VERIFY_STEPS, variants=rounding_variants(mech, paths)), spec, own)
    return Written(runs[0], {key: spread([run[key] for run in runs]) for key in runs[0]})


def spread(values: Any) -> float:
    """The tolerance of a quantity computed on the :func:`rounding_variants` (``(2 n + 1,)``: the file as written,
    then each length up and down): the first-order bound times :data:`MARGIN`, plus :data:`TOLERANCE` of it."""
    values = np.asarray(values, dtype=float)
    first = float(np.sum(np.abs(values[1::2] - values[2::2]))) / 2
    return MARGIN * first + TOLERANCE * abs(float(values[0]))
