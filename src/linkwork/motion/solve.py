"""Running the solve program over crank angles and design variants."""

from __future__ import annotations

from typing import Any

import numpy as np

from linkwork.motion import fast, kernels
from linkwork.motion.program import Step
from linkwork.motion.state import State, soa
from linkwork.structure.constraints import residuals_and_jacobian, velocity_products
from linkwork.structure.model import PairType
from linkwork.structure.parameters import Geometry


def run(
    mech: Any,
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
    if fast.available() and mech.fast_program is not None and program is mech.program:
        state = _run_fast(mech, program, geom, values, rates, accels)
        if state is not None:
            return state
    size = max(1, CHUNK // max(n_ang, 1))
    if n_var <= size:
        return _run_chunk(mech, program, geom, values, rates, accels)
    parts = []
    for start in range(0, n_var, size):
        part = Geometry(*(g[start : start + size] for g in (geom.point_local, geom.pair_origin, geom.pair_axis)))
        parts.append(_run_chunk(mech, program, part, values, rates, accels))
    out = parts[0]
    for name in ("q", "v", "a", "cos", "sin", "local", "origin", "axis"):
        setattr(
            out,
            name,
            np.concatenate([getattr(p, name) for p in parts], axis=2 if name != "cos" and name != "sin" else 1),
        )
    out.valid = np.concatenate([p.valid for p in parts])
    for name in ("step_valid", "step_det", "step_slack"):
        setattr(out, name, [np.concatenate(x) for x in zip(*(getattr(p, name) for p in parts), strict=True)])
    out.step_branch = [
        None if x[0] is None else np.concatenate(x) for x in zip(*(p.step_branch for p in parts), strict=True)
    ]
    out.step_limit = [
        None
        if all(j is None for j in x)
        else np.concatenate([np.zeros(p.valid.shape, bool) if j is None else j for j, p in zip(x, parts, strict=True)])
        for x in zip(*(p.step_limit for p in parts), strict=True)
    ]
    offsets = np.cumsum([0] + [p.valid.shape[0] for p in parts])
    out.step_jumps = [
        [(v + int(o), j) for p, o in zip(parts, offsets, strict=False) for v, j in p.step_jumps[k]]
        for k in range(len(program))
    ]
    out.step_flips = [
        [(v + int(o), i, j) for p, o in zip(parts, offsets, strict=False) for v, i, j in p.step_flips[k]]
        for k in range(len(program))
    ]
    return out


def _run_fast(
    mech: Any, program: tuple[Step, ...], geom: Geometry, values: np.ndarray, rates: np.ndarray, accels: np.ndarray
) -> State | None:
    """The compiled closed-form path; None where a dyad passes near a change point, or lies on a singular
    position to rounding (the NumPy path follows the motion there)."""
    res = fast.run(mech, geom, values, rates, accels)
    if res["near"].any() or res["limit"].any():
        return None
    n_steps = len(program)
    state = State(
        res["q"],
        res["v"],
        res["a"],
        None,
        None,
        soa(geom.point_local),
        soa(geom.pair_origin),
        soa(geom.pair_axis),
        res["valid"],
        [
            s >= 0 if step.kind not in ("crank", "slide") else np.ones(s.shape, bool)
            for s, step in zip(res["slack"], program, strict=True)
        ],
        list(res["det"]),
        list(res["slack"]),
    )
    state.step_branch = [None] * n_steps
    state.step_limit = [None] * n_steps
    state.step_flips = [[] for _ in range(n_steps)]
    state.step_jumps = [[] for _ in range(n_steps)]
    state.step_trouble = res["trouble"]
    if res["singular"]:
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            _repair_singular(mech, program, geom, values, rates, accels, state)
    if not state.valid.all():
        bad = ~state.valid
        for arr in (state.q, state.v, state.a):
            arr[:, :, bad] = np.nan
    return state


#: Samples per chunk of design variants.
CHUNK = 1 << 15


def _run_chunk(
    mech: Any, program: tuple[Step, ...], geom: Geometry, values: np.ndarray, rates: np.ndarray, accels: np.ndarray
) -> State:
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        state = _solve(mech, program, geom, values, rates, accels)
        _repair_singular(mech, program, geom, values, rates, accels, state)
    bad = ~state.valid
    for arr in (state.q, state.v, state.a):
        arr[:, :, bad] = np.nan
    return state


#: Normalised Jacobian determinant below which a sample is a singular position.
SINGULAR = fast.SINGULAR


def _solve(
    mech: Any,
    program: tuple[Step, ...],
    geom: Geometry,
    values: np.ndarray,
    rates: np.ndarray,
    accels: np.ndarray,
    branches: list[np.ndarray | None] | None = None,
) -> State:
    n_var, n_ang = geom.n_variants, values.shape[0]
    state = State.empty(mech.n_links_total, soa(geom.point_local), soa(geom.pair_origin), soa(geom.pair_axis), n_ang)
    offset = (values[:, 0] - mech.drive_start[0] + np.pi) % (2 * np.pi) - np.pi
    if mech.pair_type[mech.drive_pair[0]] == PairType.PRISMATIC:
        offset = values[:, 0] - mech.drive_start[0]
    state.start_index = int(np.argmin(np.abs(offset)))
    state.drive = values[:, 0]
    state.rate = rates[:, 0] if values.shape[1] == 1 else None
    ones = np.ones((n_var, n_ang))
    for i, step in enumerate(program):
        branch = branches[i] if branches is not None else None
        if step.kind in ("crank", "slide"):
            d = step.drive
            args = (values[:, d] * ones, rates[:, d] * ones, accels[:, d] * ones)
            (kernels.crank if step.kind == "crank" else kernels.slide)(step, state, mech.point_link, *args)
        elif step.kind in ("RRR", "RRP", "PRP"):
            kernels.dyad(step, state, mech.point_link, branch=branch)
        elif step.kind == "RPR":
            kernels.rpr(step, state, mech.point_link)
        elif step.kind == "RPP":
            kernels.rpp(step, state, mech.point_link)
        else:
            newton(mech, step, state, geom, values, rates, accels)
        state.valid &= state.step_valid[-1]
        state.placed |= set(step.links)
    return state


def _repair_singular(
    mech: Any,
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
    det = np.stack([np.abs(d) for d in state.step_det])  # (S, V, A)
    singular = state.valid & np.any(det < SINGULAR, axis=0)
    idx = np.flatnonzero(singular.any(axis=0))
    if len(idx) == 0:
        return
    scale = max(float(np.abs(mech.point_local).max()), 1e-3)
    delta = np.where(mech.pair_type[mech.drive_pair] == PairType.REVOLUTE, 1e-3, 1e-3 * scale)
    n_ang = values.shape[0]
    # the assembly mode on each side: that of the neighbouring sample on that side (whatever the order
    # of the angles); where there is none, a change point is crossed: the other mode than the far side's
    below, above = np.maximum(idx - 1, 0), np.minimum(idx + 1, n_ang - 1)
    rising = np.where(below == above, True, values[above, 0] >= values[below, 0])
    near_minus, near_plus = np.where(rising, below, above), np.where(rising, above, below)
    side_branches = ([], [])
    for i, step in enumerate(program):
        b = state.step_branch[i]
        if step.kind not in ("RRR", "RRP", "PRP"):
            side_branches[0].append(None)
            side_branches[1].append(None)
            continue
        full = b if b is not None else np.full(state.valid.shape, step.branch)
        lone = det[i][:, idx] < SINGULAR
        minus, plus = full[:, near_minus].copy(), full[:, near_plus].copy()
        alone = near_minus == near_plus  # a single sample: the side facing the assembly pose keeps its mode
        facing_up = values[idx, 0] < mech.drive_start[0]
        minus = np.where(lone & (near_minus == idx) & ~(alone & ~facing_up), -plus, minus)
        plus = np.where(lone & (near_plus == idx) & ((near_minus != idx) | (alone & ~facing_up)), -minus, plus)
        side_branches[0].append(minus)
        side_branches[1].append(plus)
    means = []
    for h in (delta, 2 * delta):
        sides = []
        for sign, branches in ((-1.0, side_branches[0]), (1.0, side_branches[1])):
            sides.append(_solve(mech, program, geom, values[idx] + sign * h, rates[idx], accels[idx], branches))
        means.append([0.5 * (a + b) for a, b in zip((sides[0].v, sides[0].a), (sides[1].v, sides[1].a), strict=True)])
    # links of the first singular step and after it: upstream links are regular there
    first = np.argmax(det[:, :, idx] < SINGULAR, axis=0)  # (V, a)
    order = np.full(mech.n_links_total, -1)
    for i, step in enumerate(program):
        order[list(step.links)] = i
    affected = order[None, None, :] >= first[..., None]  # (V, a, N)
    mask = singular[:, idx][..., None] & affected
    # where every singular step is a dyad on its singular position to rounding, the velocities are
    # already those of the motion through it
    limit = np.stack([np.zeros(det.shape[1:], bool) if j is None else j for j in state.step_limit])
    kept = np.all((det >= SINGULAR) | limit, axis=0)[:, idx]  # (V, a)
    for k, full in enumerate((state.v, state.a)):
        richardson = (4 * means[0][k] - means[1][k]) / 3  # removes the h^2 error of the central mean
        view = np.moveaxis(full, (0, 1), (2, 3))  # (V, A, N, 3)
        block = view[:, idx]
        take = mask & ~kept[..., None] if k == 0 else mask
        block[take] = np.moveaxis(richardson, (0, 1), (2, 3))[take]
        view[:, idx] = block


def _rows(mech: Any, links: tuple[int, ...], placed: set[int]) -> list[int]:
    """Constraint rows of a group: those that involve its links and placed links only."""
    from linkwork.structure.assemble import group_rows
    from linkwork.structure.constraints import build_rows

    return group_rows(build_rows(mech.pair_type, mech.pair_links, mech.drive_pair), placed, set(links))


def newton(
    mech: Any,
    step: Step,
    state: State,
    geom: Geometry,
    values: np.ndarray,
    rates: np.ndarray,
    accels: np.ndarray,
    tol: float = 1e-12,
    iterations: int = 40,
) -> None:
    """Any group by a vectorised Newton method on its constraint rows.

    Samples are solved in rings of growing distance from the drive values
    of the assembly pose, each ring started from the nearest solved
    sample, so that the assembly mode of the assembly pose is followed
    along the cycle.  Velocities and accelerations come from the linear
    systems of the differentiated constraints.
    """
    links = list(step.links)
    sel = _rows(mech, step.links, state.placed)
    cols = np.array([3 * i + c for i in links for c in range(3)])
    n_var, n_ang = state.valid.shape
    drive = np.broadcast_to(values[None], (n_var, n_ang, values.shape[1]))
    scale = max(float(np.abs(mech.point_local).max()), 1e-3)
    q = np.ascontiguousarray(np.moveaxis(state.q, (0, 1), (2, 3)))  # (V, A, N, 3)
    q[:, :, links] = np.asarray(mech.pose0)[links]

    offset = (values - mech.drive_start + np.pi) % (2 * np.pi) - np.pi  # (A, D)
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
        converged[:, idx] = _newton_solve(mech, sub, drive[:, idx], links, sel, cols, geom, scale, tol, iterations)
        q[:, idx] = sub
        solved[idx] = True

    _, jac = residuals_and_jacobian(q, mech, drive, geom=geom)
    jac = jac[..., sel, :]
    js = jac[..., cols]
    rest = np.setdiff1d(np.arange(jac.shape[-1]), cols)
    vel = np.ascontiguousarray(np.moveaxis(state.v, (0, 1), (2, 3))).reshape(n_var, n_ang, -1)
    rhs = -np.einsum("vamk,vak->vam", jac[..., rest], vel[..., rest]) + _drive_rows(mech, sel, rates)
    vel[..., cols] = _lstsq(js, rhs)
    vel = vel.reshape(q.shape)
    gamma = velocity_products(q, vel, mech, geom=geom)[..., sel]
    acc = np.ascontiguousarray(np.moveaxis(state.a, (0, 1), (2, 3))).reshape(n_var, n_ang, -1)
    rhs = -np.einsum("vamk,vak->vam", jac[..., rest], acc[..., rest]) - gamma + _drive_rows(mech, sel, accels)
    acc[..., cols] = _lstsq(js, rhs)
    acc = acc.reshape(q.shape)
    for full, view in ((state.q, q), (state.v, vel), (state.a, acc)):
        full[links] = np.moveaxis(view[:, :, links], (0, 1), (2, 3))
    state.cos[links], state.sin[links] = np.cos(state.q[links, 2]), np.sin(state.q[links, 2])
    sv = np.linalg.svd(np.nan_to_num(js), compute_uv=False)
    state.step_slack.append(np.where(converged, 1.0, -1.0))
    state.step_det.append(sv[..., -1] / np.maximum(sv[..., 0], 1e-300))
    state.step_valid.append(converged)
    state.step_branch.append(None)
    state.step_limit.append(None)
    state.step_flips.append([])
    state.step_jumps.append(_jumps(state, links, values[:, 0], scale, converged))


def _jumps(
    state: State, links: list[int], drive: np.ndarray, scale: float = 1.0, ok: np.ndarray | None = None
) -> list[tuple[int, int]]:
    """Samples where a Newton-solved group moves far more than its neighbours would have it:
    the continuation may have changed the assembly mode there.  Returns (variant, sample) pairs."""
    if len(drive) < 4:
        return []
    step = np.maximum(np.abs(np.diff(drive)), 1e-300)
    moves = np.zeros(state.q.shape[2:3] + (len(drive) - 1,))
    for i in links:
        d = np.diff(state.q[i], axis=-1)
        turn = np.abs((d[2] + np.pi) % (2 * np.pi) - np.pi) * scale
        moves = np.maximum(moves, (np.hypot(d[0], d[1]) + turn) / step)
    if ok is not None:
        moves = np.where(ok[:, 1:] & ok[:, :-1], moves, np.nan)
    with np.errstate(invalid="ignore"):
        typical = np.nanmedian(moves, axis=1, keepdims=True)
        bad = moves > 20 * typical + 1e-6 * scale / step
    return [(int(v), int(j)) for v, j in np.argwhere(bad)]


def _drive_rows(mech: Any, sel: list[int], rates: np.ndarray) -> np.ndarray:
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


def _newton_solve(
    mech: Any,
    sub: np.ndarray,
    drive: np.ndarray,
    links: list[int],
    sel: list[int],
    cols: np.ndarray,
    geom: Any,
    scale: float,
    tol: float,
    iterations: int,
) -> np.ndarray:
    """Newton iterations in place on ``sub`` (V, a, N, 3); returns the convergence mask."""
    ok = np.zeros(sub.shape[:2], dtype=bool)
    flat = sub.reshape(sub.shape[0], sub.shape[1], -1)
    for _ in range(iterations):
        r, jac = residuals_and_jacobian(sub, mech, drive, geom=geom)
        r, js = r[..., sel], jac[..., sel, :][..., cols]
        ok = np.max(np.abs(r), axis=-1) < tol * scale
        if ok.all():
            break
        flat[..., cols] -= np.where(ok[..., None], 0.0, _lstsq(js, r))
        sub[:] = flat.reshape(sub.shape)
    return ok
