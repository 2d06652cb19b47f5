"""The solve program as the compiled kernels read it, and the batch that runs them.

:func:`encode` writes the closed-form steps of a program as an integer table (one row a step: its kind,
then columns by kind and the arms, :data:`KIND` ...); :func:`run_program` runs a compiled kernel of
:mod:`linkwork.motion.kernels_numba` over every sample of a batch, in parts on the threads of
:func:`linkwork.threads.in_parts`, and gives what it found (:class:`Solved`).  The scalar kernels themselves,
in machine code, are :mod:`linkwork.motion.kernels_numba`'s, which reads the flags from here.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, NamedTuple

import numpy as np

from linkwork import jit, threads
from linkwork.motion import groups
from linkwork.motion.program_table import ARM, ARMS, KIND
from linkwork.structure.model import Mechanism
from linkwork.structure.parameters import Geometry
from linkwork.structure.records import Step

#: Columns of a link's state in the scratch block of a sample (:data:`linkwork.motion.kernels_numba.S_X` ...)
STATE = 11


class Solved(NamedTuple):
    """What the compiled kernels give (:func:`run`).

    Attributes
    ----------
    q, v, a : ndarray, shape (N, 3, V, A)
        Pose, velocity and acceleration of every link.
    cos, sin : ndarray, shape (N, V, A)
        Of every link's angle (as the kernels placed its points).
    slack, det : ndarray, shape (S, V, A)
        Assembly margin and normalised Jacobian determinant of every step.
    valid : ndarray of bool, shape (V, A)
        Every step assembled.
    near : ndarray of bool, shape (S, V)
        A dyad's two assembly modes come within a step of each other: the NumPy path decides the mode.
    trouble : ndarray of bool, shape (S, V)
        A step fails to assemble, comes within :data:`SINGULAR` of a singular position or its
        determinant changes sign: only there are events looked for.
    singular : bool
        Some assembled sample has a normalised determinant below :data:`SINGULAR`.
    limit : ndarray of bool, shape (S, V)
        A dyad lies on a singular position to rounding (its outer joints together or its modes
        meeting): the NumPy kernels give the velocities there.
    some_near, some_limit, some_invalid, some_trouble : bool
        ``near.any()``, ``limit.any()``, ``not valid.all()`` and ``trouble.any()``, found by the kernels
        as they go.
    """

    q: np.ndarray
    v: np.ndarray
    a: np.ndarray
    cos: np.ndarray
    sin: np.ndarray
    slack: np.ndarray
    det: np.ndarray
    valid: np.ndarray
    near: np.ndarray
    trouble: np.ndarray
    singular: bool
    limit: np.ndarray
    some_near: bool = False
    some_limit: bool = False
    some_invalid: bool = False
    some_trouble: bool = True


#: Entries of the flags the kernel sets (:class:`Solved`): some sample singular, some step near a change
#: point, some step on a singular position to rounding, some sample not assembled, some step in trouble.
F_SINGULAR, F_NEAR, F_LIMIT, F_INVALID, F_TROUBLE = range(5)


def supports(program: tuple[Step, ...]) -> bool:
    """Whether every step has a compiled kernel (a code in :mod:`linkwork.motion.groups`)."""
    return all(groups.KINDS[step.kind].code is not None for step in program)


class Program(NamedTuple):
    """The solve program for the compiled kernels: one row of ``ops`` a step (the columns of
    :mod:`linkwork.motion.program_table`), and the assembly mode of each step."""

    ops: np.ndarray  # (S, 3 + 3 ARM) int
    branch: np.ndarray  # (S,)


def encode(program: tuple[Step, ...], point_link: np.ndarray) -> Program:
    """The program as an integer table (one row a step: the code of its kind, :data:`KIND`, then the
    columns its kind's ``encode`` writes, :mod:`linkwork.motion.groups`) and the branch of each step."""
    ops = np.full((len(program), ARMS + 3 * ARM), -1, dtype=np.int64)
    for s, step in enumerate(program):
        kind = groups.KINDS[step.kind]
        assert kind.code is not None and kind.encode is not None, step.kind
        ops[s, KIND] = kind.code
        kind.encode(step, point_link, ops[s])
    return Program(ops, np.array([step.branch for step in program], dtype=float))


def run_program(
    kernel: Callable[..., None],
    mech: Mechanism,
    geom: Geometry,
    values: np.ndarray,
    rates: np.ndarray,
    accels: np.ndarray,
) -> Solved:
    """Solve every sample with the compiled ``kernel`` (:func:`linkwork.motion.kernels_numba.run`).

    Parameters
    ----------
    mech : Mechanism
        With a compiled program (``mech.program_table``).
    geom : Geometry
        Dimensions of the design variants.
    values, rates, accels : (A, D)

    Returns
    -------
    Solved
    """
    assert mech.program_table is not None
    ops, branch = mech.program_table
    values, rates, accels = floats(values), floats(rates), floats(accels)
    n_var, n_ang, n_steps, n_links = geom.point_local.shape[0], values.shape[0], len(ops), mech.n_links_total
    out = np.empty((11 * n_links, n_var * n_ang))  # one block: q, v, a (3 rows a link each), cos, sin
    found = np.empty((2, n_steps, n_var, n_ang))  # slack, det
    marks = np.zeros((3, n_steps, n_var), dtype=np.bool_)  # near, trouble, limit
    valid = np.empty((n_var, n_ang), dtype=np.bool_)
    flags = np.zeros(5, dtype=np.bool_)
    args = (
        ops,
        branch,
        jit.read_only(geom.point_local),
        jit.read_only(geom.pair_origin),
        jit.read_only(geom.pair_axis),
        values,
        rates,
        accels,
        out,
        found,
        valid,
        marks,
        flags,
    )
    _in_parts(kernel, args, n_links, n_steps, n_var, n_ang)
    if n_ang < 3:  # too few samples to follow a change point: the mode of the assembly pose throughout
        marks[0] = False
        flags[F_NEAR] = False
    singular, near, limit, invalid, trouble = flags.tolist()
    q, v, a = out[: 9 * n_links].reshape(3, n_links, 3, n_var, n_ang)
    cos, sin = out[9 * n_links :].reshape(2, n_links, n_var, n_ang)
    slack, det = found
    return Solved(
        q, v, a, cos, sin, slack, det, valid, marks[0], marks[1], singular, marks[2], near, limit, invalid, trouble
    )


def floats(x: np.ndarray) -> np.ndarray:
    """``x`` as a C-ordered array of floats (itself where it is one already)."""
    return x if x.dtype == np.float64 and x.flags.c_contiguous else np.ascontiguousarray(x, dtype=float)


def _in_parts(
    kernel: Callable[..., None], args: tuple[Any, ...], n_links: int, n_steps: int, n_var: int, n_ang: int
) -> None:
    """Run the kernel on ``args`` over the samples, in parts on the threads of :func:`linkwork.threads.in_parts`,
    each with scratch blocks of its own."""

    def part(lo: int, hi: int) -> None:
        kernel(*args, lo, hi, np.zeros((n_links, STATE)), np.zeros((n_steps, 2, 3)), np.zeros((n_steps, 5)))

    threads.in_parts(part, n_ang, n_var * n_ang)
