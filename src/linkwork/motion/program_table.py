"""The solve program as an integer table, the form the compiled kernels read: the columns of a step's row and the
writers of each kind's columns (the ``encode`` of each kind of :mod:`linkwork.motion.groups`).

A row holds the code of its step's kind (:data:`KIND`), then columns by kind (:data:`CRANK_LINK` ...,
:data:`SLIDE_LINK` ..., :data:`DYAD_XA`, :data:`RPR_INNER`), then up to three arms of :data:`ARM` columns each
from :data:`ARMS`; unused columns stay -1.  :mod:`linkwork.motion.kernels_numba` reads them by these names.
"""

from __future__ import annotations

import numpy as np

from linkwork.structure.records import Arm, Step

# Columns of a step's row of the compiled program: the code of its kind, then by kind
KIND = 0
#: crank: the driven link, the placed link it turns on (the base), the base's point at the pivot, the
#: driven link's point there, the sign of the drive angle (:attr:`Step.sign`), the drive
CRANK_LINK, CRANK_BASE, CRANK_SRC, CRANK_OWN, CRANK_SIGN, CRANK_DRIVE = range(1, 7)
#: slide: the slider, the link that carries the guide, the prismatic pair, the slider's point, the drive
SLIDE_LINK, SLIDE_GUIDE, SLIDE_PAIR, SLIDE_POINT, SLIDE_DRIVE = range(1, 6)
#: dyad: the point of X on each arm's link (-1: the link's origin); RPR: the inner prismatic pair
DYAD_XA, DYAD_XB = 1, 2
RPR_INNER = 1
#: the first column of the arms, :data:`ARM` columns each (:class:`~linkwork.structure.records.Arm`)
ARMS = 3
#: Columns of an arm, from its first: R (0) or P (1), its link, its outer pair, R: its own point at the
#: outer joint, the placed link's point there and that link; P: the link whose angle it keeps, whether
#: it is the pair's slider, the slider's point of the pair
ARM_KIND, ARM_LINK, ARM_PAIR, ARM_OWN, ARM_SRC, ARM_SRC_LINK, ARM_CARRIER, ARM_IS_SLIDER, ARM_SLIDER_POINT = range(9)
ARM = 9
#: Columns of a row: the kind's, then three arms.
WIDTH = ARMS + 3 * ARM


def crank_row(step: Step, point_link: np.ndarray, row: np.ndarray) -> None:
    """A crank's columns (:data:`CRANK_LINK` ...) into its ``row`` ``(WIDTH,)``."""
    arm = step.arms[0]
    row[CRANK_LINK], row[CRANK_BASE], row[CRANK_SRC] = arm.link, int(point_link[arm.src]), arm.src
    row[CRANK_OWN], row[CRANK_SIGN], row[CRANK_DRIVE] = arm.own, int(step.sign), step.drive


def slide_row(step: Step, point_link: np.ndarray, row: np.ndarray) -> None:
    """A slide's columns (:data:`SLIDE_LINK` ...) into its ``row`` ``(WIDTH,)``."""
    arm = step.arms[0]
    row[SLIDE_LINK], row[SLIDE_GUIDE], row[SLIDE_PAIR] = arm.link, arm.carrier, arm.pair
    row[SLIDE_POINT], row[SLIDE_DRIVE] = arm.slider_point, step.drive


def dyad_row(step: Step, point_link: np.ndarray, row: np.ndarray) -> None:
    """A dyad closed at X (RRR, RRP, PRP): the points of X (:data:`DYAD_XA`, :data:`DYAD_XB`) and its arms."""
    row[DYAD_XA], row[DYAD_XB] = step.x_local
    arms_row(step, point_link, row)


def rpr_row(step: Step, point_link: np.ndarray, row: np.ndarray) -> None:
    """An RPR dyad: its inner prismatic pair (:data:`RPR_INNER`) and its arms."""
    row[RPR_INNER] = step.inner
    arms_row(step, point_link, row)


def arms_row(step: Step, point_link: np.ndarray, row: np.ndarray) -> None:
    """The arms of a step (:data:`ARM_KIND` ... each, from :data:`ARMS`) into its ``row`` ``(WIDTH,)``."""
    for j, arm in enumerate(step.arms):
        row[ARMS + j * ARM : ARMS + (j + 1) * ARM] = _arm(arm, point_link)


def _arm(arm: Arm, point_link: np.ndarray) -> list[int]:
    """An arm's columns (:data:`ARM_KIND` ...)."""
    src_link = int(point_link[arm.src]) if arm.src >= 0 else -1
    return [
        0 if arm.kind == "R" else 1,
        arm.link,
        arm.pair,
        arm.own,
        arm.src,
        src_link,
        arm.carrier,
        int(arm.own_is_slider),
        arm.slider_point,
    ]
