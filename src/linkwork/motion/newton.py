"""Any group by a vectorised Newton method on its constraint rows (the kind ``newton`` of
:mod:`linkwork.motion.groups`: the groups no closed form covers).

Samples are solved in rings of growing distance from the drive values of the assembly pose, each started
from the nearest solved sample; velocities and accelerations come from the linear systems of the
differentiated constraints.
"""

from __future__ import annotations

import numpy as np

from linkwork.angles import wrap
from linkwork.motion.state import Inputs, Jump, State, StepRecord
from linkwork.structure.assemble import group_rows
from linkwork.structure.constraints import build_rows, residuals_and_jacobian, velocity_products
from linkwork.structure.model import Mechanism
from linkwork.structure.parameters import Geometry
from linkwork.structure.records import Step


def _rows(mech: Mechanism, links: tuple[int, ...], placed: set[int]) -> list[int]:
    """Constraint rows of a group: those that involve its links and placed links only."""
    return group_rows(build_rows(mech.pair_type, mech.pair_links, mech.drive_pair), placed, set(links))


def solve(step: Step, state: State, at: Inputs, branch: np.ndarray | None = None) -> None:
    """The NumPy kernel of a ``newton`` step (:mod:`linkwork.motion.groups`): from the assembly pose along the
    shared drive values (:func:`newton`), or from the given poses at each variant's own drive coordinates
    (:func:`newton_from`); ``branch`` is not read (the mode is the one continued from the start)."""
    group = _Group(at.mech, step, state, at.geom, (at.rates, at.accels))
    if at.own is not None and at.own[1] is not None:
        newton_from(group, state, at.own[0], at.own[1])
    else:
        newton(group, state, at.values)


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
