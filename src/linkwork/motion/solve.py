"""Running the solve program over crank angles and design variants: each step by its kind's kernel
(:data:`linkwork.motion.groups.KINDS`), the compiled twins where they cover the program."""

from __future__ import annotations

import time

import numpy as np

from linkwork import jit
from linkwork.angles import wrap
from linkwork.motion import kernels, kernels_numba
from linkwork.motion.groups import KINDS
from linkwork.motion.state import Inputs, State, StepRecord
from linkwork.structure.model import Mechanism, PairType
from linkwork.structure.parameters import Geometry
from linkwork.structure.records import Step


def run(
    mech: Mechanism,
    program: tuple[Step, ...],
    geom: Geometry,
    values: np.ndarray,
    rates: np.ndarray,
    accels: np.ndarray,
) -> State:
    """Solve every step for all variants and angles.

    Parameters
    ----------
    values, rates, accels : ndarray, shape (A, D)
        Drive coordinates and their first and second time derivatives.

    Many variants are solved in chunks of about :data:`CHUNK` samples, so
    that the arrays of a chunk stay in the processor's cache.
    """
    n_var, n_ang = geom.n_variants, values.shape[0]
    twin = mech.program_table is not None and program is mech.program  # the compiled kernels cover it
    if twin and kernels_numba.wanted(n_var * n_ang):
        state = _run_compiled(mech, program, geom, values, rates, accels)
        if state is not None:
            return state
    start = time.thread_time()
    size = max(1, CHUNK // max(n_ang, 1))
    if n_var <= size:
        state = run_numpy(mech, program, geom, values, rates, accels)
    else:
        parts = []
        for first in range(0, n_var, size):
            part = Geometry(*(g[first : first + size] for g in (geom.point_local, geom.pair_origin, geom.pair_axis)))
            parts.append(run_numpy(mech, program, part, values, rates, accels))
        state = _concatenate(parts, program)
    if twin:  # time the compiled twin would save: what pays for loading it
        jit.spent(time.thread_time() - start)
    return state


def _concatenate(parts: list[State], program: tuple[Step, ...]) -> State:
    """The states of consecutive blocks of variants as one."""
    out = parts[0]
    for name in ("q", "v", "a", "cos", "sin", "local", "origin", "axis"):
        axis = 2 if name != "cos" and name != "sin" else 1
        setattr(out, name, np.concatenate([getattr(p, name) for p in parts], axis=axis))
    out.valid = np.concatenate([p.valid for p in parts])
    offsets = [int(o) for o in np.cumsum([0] + [p.valid.shape[0] for p in parts])]
    out.steps = [
        StepRecord.concatenate(list(records), offsets, step.branch)
        for step, *records in zip(program, *(p.steps for p in parts), strict=True)
    ]
    return out


def _run_compiled(
    mech: Mechanism,
    program: tuple[Step, ...],
    geom: Geometry,
    values: np.ndarray,
    rates: np.ndarray,
    accels: np.ndarray,
) -> State | None:
    """The compiled closed-form path; None where a dyad passes near a change point, or lies on a singular
    position to rounding (the NumPy path follows the motion there)."""
    res = kernels_numba.run(mech, geom, values, rates, accels)
    if res.some_near or res.some_limit:
        return None
    state = State(res.q, res.v, res.a, res.cos, res.sin, *geom.link_major, res.valid)
    # the kernels give cranks and slides a margin of 1: always assembled; every step wherever every sample is
    assembled = res.slack >= 0 if res.some_invalid else [res.valid] * len(program)
    state.steps = [StepRecord(ok, d, s) for ok, d, s in zip(assembled, res.det, res.slack, strict=True)]
    state.step_trouble = res.trouble
    state.quiet = not res.some_trouble
    if res.singular:
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            _repair_singular(mech, program, geom, values, rates, accels, state)
    if res.some_invalid:
        _not_assembled(state)
    return state


def _not_assembled(state: State) -> None:
    """NaN in every quantity of the samples where the mechanism does not assemble."""
    bad = ~state.valid
    for arr in (state.q, state.v, state.a):
        arr[:, :, bad] = np.nan
    for arr in (state.cos, state.sin):
        arr[:, bad] = np.nan


#: Samples per chunk of design variants.
CHUNK = 1 << 15


def run_numpy(
    mech: Mechanism,
    program: tuple[Step, ...],
    geom: Geometry,
    values: np.ndarray,
    rates: np.ndarray,
    accels: np.ndarray,
    branches: list[np.ndarray | None] | None = None,
) -> State:
    """Solve every step by the NumPy kernels, all variants at once (:func:`run` without the compiled
    kernels and the chunks of variants); ``branches``: the assembly mode of each dyad at each sample ``(V, A)``,
    per step of the program (None: followed from the assembly pose)."""
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        state = _solve(mech, program, geom, values, rates, accels, branches)
        _repair_singular(mech, program, geom, values, rates, accels, state)
    _not_assembled(state)
    return state


def run_each(
    mech: Mechanism,
    geom: Geometry,
    drive: np.ndarray,
    rate: float,
    modes: list[np.ndarray | None] | None = None,
    start: np.ndarray | None = None,
) -> State | None:
    """Every variant at its own drive coordinates ``drive`` ``(V, A)`` (one drive turning at the uniform ``rate``), by
    the NumPy kernels, for refining a quantity between the samples of a solved cycle
    (:meth:`linkwork.motion.Kinematics.at`).

    ``modes``: per step of the program, the assembly mode of each dyad at each sample ``(V, A)`` (None: the step's
    own); no change point is followed.  ``start``: the poses ``(N, 3, V, A)`` from which a group solved by Newton's
    method starts (the nearest sample's; without them such a program gives None).  None with several drives.
    Samples at a singular position are left as the kernels give them (not repaired): NaN where a linear system has
    no solution."""
    iterative = any(KINDS[step.kind].iterative for step in mech.program)
    if mech.n_drives != 1 or (iterative and start is None):
        return None
    n_ang = drive.shape[1]
    values = np.ascontiguousarray(drive[0])[:, None]
    rates, accels = np.full((n_ang, 1), float(rate)), np.zeros((n_ang, 1))
    fixed = [
        (np.full(drive.shape, s.branch) if m is None else m) if KINDS[s.kind].changes_mode else None
        for s, m in zip(mech.program, modes or [None] * len(mech.program), strict=True)
    ]
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        state = _solve(mech, mech.program, geom, values, rates, accels, branches=fixed, own=(drive, start))
    _not_assembled(state)
    return state


#: Normalised Jacobian determinant below which a sample is a singular position.
SINGULAR = kernels.SINGULAR


def _solve(
    mech: Mechanism,
    program: tuple[Step, ...],
    geom: Geometry,
    values: np.ndarray,
    rates: np.ndarray,
    accels: np.ndarray,
    branches: list[np.ndarray | None] | None = None,
    own: tuple[np.ndarray, np.ndarray | None] | None = None,
) -> State:
    """Solve every step by the NumPy kernels; ``own``: the drive coordinate of every variant at every sample
    ``(V, A)`` in place of the shared ``values[:, 0]``, and the poses ``(N, 3, V, A)`` Newton's method starts from
    there (one drive: :func:`run_each`)."""
    n_ang = values.shape[0]
    state = State.empty(mech.n_links_total, *geom.link_major, n_ang)
    offset = wrap(values[:, 0] - mech.drive_start[0])
    if mech.pair_type[mech.drive_pair[0]] == PairType.PRISMATIC:
        offset = values[:, 0] - mech.drive_start[0]
    state.start_index = int(np.argmin(np.abs(offset)))
    state.drive = values[:, 0]
    state.rate = rates[:, 0] if values.shape[1] == 1 else None
    at = Inputs(mech, geom, values, rates, accels, own)
    for i, step in enumerate(program):
        KINDS[step.kind].solve(step, state, at, branches[i] if branches is not None else None)
        state.valid &= state.steps[-1].valid
        state.placed |= set(step.links)
    return state


def _repair_singular(
    mech: Mechanism,
    program: tuple[Step, ...],
    geom: Geometry,
    values: np.ndarray,
    rates: np.ndarray,
    accels: np.ndarray,
    state: State,
) -> None:
    """Velocities and accelerations at samples exactly on a singular position.

    There the linear systems have no unique solution; the motion's own
    values are the limits from both sides, taken as the mean of the
    solutions a small step (1e-3 rad, or 1e-3 of the mechanism's size for a
    linear drive) to either side, each in the assembly mode of its side,
    extrapolated to a zero step (Richardson).
    """
    det = np.stack([np.abs(r.det) for r in state.steps])  # (S, V, A)
    singular = state.valid & np.any(det < SINGULAR, axis=0)
    idx = np.flatnonzero(singular.any(axis=0))
    if len(idx) == 0:
        return
    sides = _side_modes(mech, program, values, state, det, idx)
    scale = max(float(np.abs(mech.point_local).max()), 1e-3)
    delta = np.where(mech.pair_type[mech.drive_pair] == PairType.REVOLUTE, 1e-3, 1e-3 * scale)
    means = []
    for h in (delta, 2 * delta):
        minus, plus = (
            _solve(mech, program, geom, values[idx] + sign * h, rates[idx], accels[idx], branches)
            for sign, branches in zip((-1.0, 1.0), sides, strict=True)
        )
        means.append([0.5 * (a + b) for a, b in zip((minus.v, minus.a), (plus.v, plus.a), strict=True)])
    limits = [(4 * means[0][k] - means[1][k]) / 3 for k in range(2)]  # removes the h^2 error of the central mean
    _write_limits(mech, program, state, det, singular, idx, limits)


def _side_modes(
    mech: Mechanism, program: tuple[Step, ...], values: np.ndarray, state: State, det: np.ndarray, idx: np.ndarray
) -> tuple[list[np.ndarray | None], list[np.ndarray | None]]:
    """The assembly mode of every dyad just below and just above each singular sample ``idx``
    ``(a,)``: ``(V, a)`` per step (None for other steps).

    The mode on each side is that of the neighbouring sample on that side (whatever the order of the
    angles).  For a dyad singular at the sample it is that of the nearest sample on that side where the
    dyad is regular: samples a rounding beside the same singular position say nothing of the side (their
    own modes are those of either side).  Where there is none on one side, a change point is crossed: the
    other mode than the far side's; where there is none on either, the side facing the assembly pose
    keeps the sample's own mode."""
    n_ang = values.shape[0]
    below, above = np.maximum(idx - 1, 0), np.minimum(idx + 1, n_ang - 1)
    rising = np.where(below == above, True, values[above, 0] >= values[below, 0])
    facing_up = values[idx, 0] < mech.drive_start[0]
    lower: list[np.ndarray | None] = []
    upper: list[np.ndarray | None] = []
    for step, record, d in zip(program, state.steps, det, strict=True):
        if not KINDS[step.kind].changes_mode:
            lower.append(None)
            upper.append(None)
            continue
        full = record.branch if record.branch is not None else np.full(state.valid.shape, step.branch)
        before, after = _nearest_regular(~(d < SINGULAR), idx, below, above)
        near_minus, near_plus = np.where(rising, before, after), np.where(rising, after, before)  # (V, a)
        own = full[:, idx]
        minus, plus = np.take_along_axis(full, near_minus, 1), np.take_along_axis(full, near_plus, 1)
        has_minus, has_plus = near_minus != idx, near_plus != idx
        lone = d[:, idx] < SINGULAR  # singular at the sample: a side without a regular neighbour is crossed to
        minus = np.where(has_minus | ~lone, minus, np.where(has_plus, -plus, np.where(facing_up, -own, own)))
        plus = np.where(has_plus | ~lone, plus, np.where(has_minus, -minus, np.where(facing_up, own, -own)))
        lower.append(minus)
        upper.append(plus)
    return lower, upper


def _nearest_regular(
    regular: np.ndarray, idx: np.ndarray, below: np.ndarray, above: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """For a dyad singular at samples ``idx`` (``regular``: ``(V, A)``, False there): the nearest sample
    before and after each in the order given where it is regular, ``(V, a)`` each, the sample itself
    where there is none; where it is regular at a sample, its neighbours ``below`` and ``above``."""
    n_var, n_ang = regular.shape
    at = np.arange(n_ang)
    prev = np.maximum.accumulate(np.where(regular, at, -1), axis=1)  # last regular at or before
    succ = np.minimum.accumulate(np.where(regular, at, n_ang)[:, ::-1], axis=1)[:, ::-1]  # first at or after
    prev = np.concatenate([np.full((n_var, 1), -1), prev[:, :-1]], axis=1)[:, idx]  # strictly before
    succ = np.concatenate([succ[:, 1:], np.full((n_var, 1), n_ang)], axis=1)[:, idx]  # strictly after
    lone = ~regular[:, idx]
    before = np.where(lone, np.where(prev >= 0, prev, idx), below)
    after = np.where(lone, np.where(succ < n_ang, succ, idx), above)
    return before, after


def _write_limits(
    mech: Mechanism,
    program: tuple[Step, ...],
    state: State,
    det: np.ndarray,
    singular: np.ndarray,
    idx: np.ndarray,
    limits: list[np.ndarray],
) -> None:
    """Put the two-sided limits ``limits`` (velocities and accelerations, ``(N, 3, V, a)``) of the
    singular samples ``idx`` into the state, for the links of the first singular step and after it
    (upstream links are regular there), except the velocities where every singular step is a dyad on
    its singular position to rounding (its velocities are those of the motion through it already)."""
    first = np.argmax(det[:, :, idx] < SINGULAR, axis=0)  # (V, a)
    order = np.full(mech.n_links_total, -1)
    for i, step in enumerate(program):
        order[list(step.links)] = i
    affected = order[None, None, :] >= first[..., None]  # (V, a, N)
    mask = singular[:, idx][..., None] & affected
    limit = np.stack([np.zeros(det.shape[1:], bool) if r.limit is None else r.limit for r in state.steps])
    kept = np.all((det >= SINGULAR) | limit, axis=0)[:, idx]  # (V, a)
    for k, full in enumerate((state.v, state.a)):
        view = np.moveaxis(full, (0, 1), (2, 3))  # (V, A, N, 3)
        block = view[:, idx]
        take = mask & ~kept[..., None] if k == 0 else mask
        block[take] = np.moveaxis(limits[k], (0, 1), (2, 3))[take]
        view[:, idx] = block
