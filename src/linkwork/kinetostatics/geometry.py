"""The variants' dimensions of a kinematics result, as the force computations read them."""

from __future__ import annotations

import numpy as np

from linkwork.motion.analysis import guide
from linkwork.motion.kinematic_analysis import Kinematics
from linkwork.structure.parameters import Geometry


def _guides(kin: Kinematics) -> tuple[np.ndarray, np.ndarray]:
    """The guides' origins and directions of the variants, ``(M, 2, V, 1)`` each."""
    # linkwork.motion.kinematic_analysis.kinematics gives both for every result
    assert kin.origin is not None and kin.axis is not None
    return kin.origin, kin.axis


def variant_geometry(kin: Kinematics) -> Geometry:
    """The local dimensions of the variants of ``kin``: points ``(V, 1, P, 2)``, guide origins and
    directions ``(V, 1, M, 2)``, as :func:`linkwork.structure.constraints.residuals_and_jacobian` reads them."""
    origin, axis = _guides(kin)
    return Geometry(*(np.moveaxis(g, (0, 1), (2, 3)) for g in (kin.local, origin, axis)))


def guide_direction(kin: Kinematics, k: int) -> np.ndarray:
    """Unit direction ``(V, A, 2)`` of the guide line of prismatic pair ``k`` in the frame's axes: its local
    direction turned by the angle of the guide (the pair's first link;
    :func:`~linkwork.motion.analysis.guide`)."""
    return guide(kin, k)[1]
