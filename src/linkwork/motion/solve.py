"""Running the solve program over crank angles and design variants."""

from __future__ import annotations

import time

import numpy as np

from linkwork import jit
from linkwork.angles import wrap
from linkwork.motion import kernels, kernels_numba
from linkwork.motion.state import Jump, State, StepRecord
from linkwork.structure.assemble import group_rows
from linkwork.structure.constraints import build_rows, residuals_and_jacobian, velocity_products
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
    newton_steps = any(step.kind == "newton" for step in mech.program)
    if mech.n_drives != 1 or (newton_steps and start is None):
        return None
    n_ang = drive.shape[1]
    values = np.ascontiguousarray(drive[0])[:, None]
    rates, accels = np.full((n_ang, 1), float(rate)), np.zeros((n_ang, 1))
    fixed = [
        (np.full(drive.shape, s.branch) if m is None else m) if s.kind in ("RRR", "RRP", "PRP") else None
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
    n_var, n_ang = geom.n_variants, values.shape[0]
    state = State.empty(mech.n_links_total, *geom.link_major, n_ang)
    offset = wrap(values[:, 0] - mech.drive_start[0])
    if mech.pair_type[mech.drive_pair[0]] == PairType.PRISMATIC:
        offset = values[:, 0] - mech.drive_start[0]
    state.start_index = int(np.argmin(np.abs(offset)))
    state.drive = values[:, 0]
    state.rate = rates[:, 0] if values.shape[1] == 1 else None
    ones = np.ones((n_var, n_ang))
    each = None if own is None else own[0]
    for i, step in enumerate(program):
        branch = branches[i] if branches is not None else None
        if step.kind in ("crank", "slide"):
            d = step.drive
            drive = values[:, d] * ones if each is None else each
            args = (drive, rates[:, d] * ones, accels[:, d] * ones)
            (kernels.crank if step.kind == "crank" else kernels.slide)(step, state, mech.point_link, *args)
        elif step.kind in ("RRR", "RRP", "PRP"):
            kernels.dyad(step, state, mech.point_link, branch=branch)
        elif step.kind == "RPR":
            kernels.rpr(step, state, mech.point_link)
        elif step.kind == "RPP":
            kernels.rpp(step, state, mech.point_link)
        elif own is not None and own[1] is not None:
            newton_from(_Group(mech, step, state, geom, (rates, accels)), state, own[0], own[1])
        else:
            newton(_Group(mech, step, state, geom, (rates, accels)), state, values)
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
        if step.kind not in ("RRR", "RRP", "PRP"):
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


def _rows(mech: Mechanism, links: tuple[int, ...], placed: set[int]) -> list[int]:
    """Constraint rows of a group: those that involve its links and placed links only."""
    return group_rows(build_rows(mech.pair_type, mech.pair_links, mech.drive_pair), placed, set(links))


def newton(group: _Group, state: State, values: np.ndarray) -> None:
    """Any group by a vectorised Newton method on its constraint rows, the drive at ``values`` ``(A, D)``.

    Samples are solved in rings of growing distance from the drive values
    of the assembly pose, each ring started from the nearest solved
    sample, so that the assembly mode of the assembly pose is followed
    along the cycle.  Velocities and accelerations come from the linear
    systems of the differentiated constraints.
    """
    n_var, n_ang = state.valid.shape
    drive = np.broadcast_to(values[None], (n_var, n_ang, values.shape[1]))
    q = np.ascontiguousarray(np.moveaxis(state.q, (0, 1), (2, 3)))  # (V, A, N, 3)
    q[:, :, group.links] = np.asarray(group.mech.pose0)[group.links]
    converged = _rings(group, q, drive, values)
    _place(group, state, q, drive, converged, jumps=True)


def newton_from(group: _Group, state: State, each: np.ndarray, start: np.ndarray) -> None:
    """A group by Newton's method at every variant's own drive coordinates ``each`` ``(V, A)``, each sample started
    from its pose in ``start`` ``(N, 3, V, A)`` (a neighbouring solved sample's: :func:`run_each`)."""
    drive = np.ascontiguousarray(each[..., None])  # (V, A, 1)
    q = np.ascontiguousarray(np.moveaxis(state.q, (0, 1), (2, 3)))  # (V, A, N, 3)
    q[:, :, group.links] = np.moveaxis(start, (0, 1), (2, 3))[:, :, group.links]
    converged = _newton_solve(group, q, drive)
    _place(group, state, q, drive, converged, jumps=False)


def _place(group: _Group, state: State, q: np.ndarray, drive: np.ndarray, converged: np.ndarray, jumps: bool) -> None:
    """Put a Newton-solved group's poses ``q`` ``(V, A, N, 3)``, with its velocities and accelerations, into the
    state, and record the step (with its :func:`_jumps` where ``jumps``: along shared drive values)."""
    vel, acc, js = _group_rates(group, state, q, drive)
    links = group.links
    for full, view in ((state.q, q), (state.v, vel), (state.a, acc)):
        full[links] = np.moveaxis(view[:, :, links], (0, 1), (2, 3))
    state.cos[links], state.sin[links] = np.cos(state.q[links, 2]), np.sin(state.q[links, 2])
    sv = np.linalg.svd(np.nan_to_num(js), compute_uv=False)
    det = sv[..., -1] / np.maximum(sv[..., 0], 1e-300)
    found = _jumps(state, links, drive[0, :, 0], group.scale, converged) if jumps else []
    state.steps.append(StepRecord(converged, det, np.where(converged, 1.0, -1.0), jumps=found))


#: Newton's method: the residuals' bound, relative to the mechanism's size, and the most iterations.
TOL, ITERATIONS = 1e-12, 40


class _Group:
    """A group solved by Newton's method: its links, its constraint rows among the mechanism's
    (``sel``), the columns of its coordinates in the Jacobian, and the mechanism's size (m); the mechanism, the
    variants' dimensions and the drive's speeds and accelerations ``(A, D)`` it is solved with."""

    def __init__(
        self, mech: Mechanism, step: Step, state: State, geom: Geometry, rates: tuple[np.ndarray, np.ndarray]
    ) -> None:
        self.mech, self.geom = mech, geom
        self.rates, self.accels = rates
        self.links = list(step.links)
        self.sel = _rows(mech, step.links, state.placed)
        self.cols = np.array([3 * i + c for i in self.links for c in range(3)])
        self.scale = max(float(np.abs(mech.point_local).max()), 1e-3)


def _rings(group: _Group, q: np.ndarray, drive: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Solve the group's poses in ``q`` ``(V, A, N, 3)`` in place, ring by ring of growing distance from
    the drive values of the assembly pose, each sample started from the nearest one solved; returns
    where it converged, ``(V, A)``."""
    links, mech = group.links, group.mech
    n_var, n_ang = q.shape[:2]
    offset = wrap(values - mech.drive_start)  # (A, D)
    key = offset[:, 0] if values.shape[1] == 1 else np.max(np.abs(offset), axis=1)
    ring = np.floor(np.abs(key) / 0.2).astype(int)
    converged = np.zeros((n_var, n_ang), dtype=bool)
    solved = np.zeros(n_ang, dtype=bool)
    for r in np.unique(ring):
        idx = np.flatnonzero(ring == r)
        if solved.any():
            ref = np.flatnonzero(solved)
            ref = ref[np.argsort(key[ref])]
            pos = np.clip(np.searchsorted(key[ref], key[idx]), 1, len(ref)) - 1
            alt = np.minimum(pos + 1, len(ref) - 1)
            near = np.where(np.abs(key[ref[alt]] - key[idx]) < np.abs(key[ref[pos]] - key[idx]), ref[alt], ref[pos])
            sub = q[:, idx]
            sub[:, :, links] = q[:, near][:, :, links]
            q[:, idx] = sub
        sub = q[:, idx]
        converged[:, idx] = _newton_solve(group, sub, drive[:, idx])
        q[:, idx] = sub
        solved[idx] = True
    return converged


def _group_rates(
    group: _Group, state: State, q: np.ndarray, drive: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Velocities and accelerations ``(V, A, N, 3)`` with the group's from the linear systems of the
    differentiated constraints at the poses ``q``, and the group's block of the Jacobian."""
    sel, cols, mech, geom = group.sel, group.cols, group.mech, group.geom
    n_var, n_ang = q.shape[:2]
    _, jac = residuals_and_jacobian(q, mech, drive, geom=geom)
    jac = jac[..., sel, :]
    js = jac[..., cols]
    rest = np.setdiff1d(np.arange(jac.shape[-1]), cols)
    flat = np.ascontiguousarray(np.moveaxis(state.v, (0, 1), (2, 3))).reshape(n_var, n_ang, -1)
    rhs = -np.einsum("vamk,vak->vam", jac[..., rest], flat[..., rest]) + _drive_rows(mech, sel, group.rates)
    flat[..., cols] = _lstsq(js, rhs)
    vel = flat.reshape(q.shape)
    gamma = velocity_products(q, vel, mech, geom=geom)[..., sel]
    flat = np.ascontiguousarray(np.moveaxis(state.a, (0, 1), (2, 3))).reshape(n_var, n_ang, -1)
    rhs = -np.einsum("vamk,vak->vam", jac[..., rest], flat[..., rest]) - gamma + _drive_rows(mech, sel, group.accels)
    flat[..., cols] = _lstsq(js, rhs)
    return vel, flat.reshape(q.shape), js


def _jumps(
    state: State, links: list[int], drive: np.ndarray, scale: float = 1.0, ok: np.ndarray | None = None
) -> list[Jump]:
    """Samples where a Newton-solved group moves far more than its neighbours would have it:
    the continuation may have changed the assembly mode there.  Returns (variant, sample) pairs."""
    if len(drive) < 4:
        return []
    step = np.maximum(np.abs(np.diff(drive)), 1e-300)
    moves = np.zeros(state.q.shape[2:3] + (len(drive) - 1,))
    for i in links:
        d = np.diff(state.q[i], axis=-1)
        turn = np.abs(wrap(d[2])) * scale
        moves = np.maximum(moves, (np.hypot(d[0], d[1]) + turn) / step)
    if ok is not None:
        moves = np.where(ok[:, 1:] & ok[:, :-1], moves, np.nan)
    with np.errstate(invalid="ignore"):
        typical = np.nanmedian(moves, axis=1, keepdims=True)
        bad = moves > 20 * typical + 1e-6 * scale / step
    return [Jump(int(v), int(j)) for v, j in np.argwhere(bad)]


def _drive_rows(mech: Mechanism, sel: list[int], rates: np.ndarray) -> np.ndarray:
    """Right-hand side entries of the drive rows among ``sel``: shape (A, len(sel))."""
    n_pair_rows = 2 * len(mech.pair_type)
    out = np.zeros((rates.shape[0], len(sel)))
    for j, row in enumerate(sel):
        if row >= n_pair_rows:
            out[:, j] = rates[:, row - n_pair_rows]
    return out


def _lstsq(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Batched least squares (exact for square systems) through the pseudo-inverse."""
    return np.einsum("...ij,...j->...i", np.linalg.pinv(np.nan_to_num(a)), b)


def _newton_solve(group: _Group, sub: np.ndarray, drive: np.ndarray) -> np.ndarray:
    """Newton iterations in place on ``sub`` (V, a, N, 3) over the rows and columns of ``group`` (its residuals
    within :data:`TOL` of its scale, :data:`ITERATIONS` at most); returns the convergence mask."""
    sel, cols, scale, mech, geom = group.sel, group.cols, group.scale, group.mech, group.geom
    ok = np.zeros(sub.shape[:2], dtype=bool)
    flat = sub.reshape(sub.shape[0], sub.shape[1], -1)
    for _ in range(ITERATIONS):
        r, jac = residuals_and_jacobian(sub, mech, drive, geom=geom)
        r, js = r[..., sel], jac[..., sel, :][..., cols]
        ok = np.max(np.abs(r), axis=-1) < TOL * scale
        if ok.all():
            break
        flat[..., cols] -= np.where(ok[..., None], 0.0, _lstsq(js, r))
        sub[:] = flat.reshape(sub.shape)
    return ok
