"""The motion of a point carried by a link: what every reading of a point's position, velocity or
acceleration calls, with or without the compiled kernels."""

from __future__ import annotations

import time

import numpy as np

from linkwork import jit
from linkwork.motion import kernels, kernels_numba


def point_motion(
    kind: int, q: np.ndarray, v: np.ndarray, a: np.ndarray, cs: tuple[np.ndarray, np.ndarray], local: np.ndarray
) -> np.ndarray:
    """Position, velocity or acceleration (``kind``: :data:`~linkwork.motion.kernels.POSITION` ...) ``(V, A, 2)``
    of a point at ``local`` ``(2, V)`` in the frame of a link of pose, velocity and acceleration ``q``, ``v``,
    ``a`` ``(3, V, A)``, the cosine and sine of its angle ``cs`` ``(V, A)`` each: in one compiled pass where
    the compiled kernels run (:func:`linkwork.motion.kernels_numba.available`), by NumPy otherwise (the same
    arithmetic, in the same order: :func:`linkwork.motion.kernels.point_motion_into` and its twin)."""
    out = np.empty(q.shape[1:] + (2,))
    if kernels_numba.available():
        # every input a read-only view: a frozen result's arrays and a re-solve's new ones reach one compile
        q, v, a, c, s, lx, ly = (jit.read_only(x) for x in (q, v, a, cs[0], cs[1], local[0], local[1]))
        kernels_numba.point_motion_into(kind, q, v, a, c, s, lx, ly, out)
        return out
    start = time.thread_time()
    kernels.point_motion_into(kind, q, v, a, cs[0], cs[1], local[0], local[1], out)
    jit.spent(time.thread_time() - start)  # what the compiled twin would save (:mod:`linkwork.jit`)
    return out
