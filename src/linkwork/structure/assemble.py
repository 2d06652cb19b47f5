"""Assemble a mechanism in its assembly pose, group by group, from the hints.

Each group of the decomposition is solved by a least-squares Newton method
(scipy's Levenberg-Marquardt) on its own coordinates, started from the pose
that best fits the already placed joint points and the hints.  The hints
thus choose the assembly mode of every group.
"""

from __future__ import annotations

import math

import numpy as np

from linkwork.errors import UnassemblableError
from linkwork.structure.constraints import PRISMATIC, REVOLUTE, Rows, residuals_and_jacobian
from linkwork.structure.model import AssurGroup, Mechanism


def fit_pose(local: np.ndarray, glob: np.ndarray, theta: float | None = None) -> np.ndarray:
    """Rigid pose ``(x, y, theta)`` that maps local points onto global ones.

    With ``theta`` given only the translation is fitted; with one point and
    no ``theta`` the angle is taken as zero.
    """
    local = np.atleast_2d(local)
    glob = np.atleast_2d(glob)
    if theta is None:
        if len(local) >= 2:
            lc, gc = local - local.mean(0), glob - glob.mean(0)
            cross = np.sum(lc[:, 0] * gc[:, 1] - lc[:, 1] * gc[:, 0])
            dot = np.sum(lc[:, 0] * gc[:, 0] + lc[:, 1] * gc[:, 1])
            theta = math.atan2(cross, dot)
        else:
            theta = 0.0
    c, s = math.cos(theta), math.sin(theta)
    rot = local @ np.array([[c, s], [-s, c]])
    t = (glob - rot).mean(0)
    return np.array([t[0], t[1], theta])


def scaled(q: np.ndarray, mech: Mechanism, rows: Rows, scale: float, drive_values: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Residuals and Jacobian with angles made commensurate with lengths."""
    r, jac = residuals_and_jacobian(q, mech, drive_values, with_drives=True)
    r = np.where(rows.angular, r * scale, r)
    jac = np.where(rows.angular[:, None], jac * scale, jac)
    jac[:, 2::3] /= scale
    return r, jac


def group_rows(rows: Rows, placed: set[int], group: set[int]) -> list[int]:
    allowed = placed | group
    return [i for i, rl in enumerate(rows.links) if set(map(int, rl)) <= allowed and set(map(int, rl)) & group]


def solve_group(
    mech: Mechanism, rows: Rows, q: np.ndarray, subset: tuple[int, ...], sel: list[int], scale: float,
    drive_values: np.ndarray | None = None,
) -> tuple[np.ndarray, float]:
    """Solve one group in place of ``q``; returns the new q and the largest residual (m)."""
    from scipy.optimize import least_squares

    cols = [3 * i + c for i in subset for c in range(3)]
    q = q.copy()

    def put(x: np.ndarray) -> np.ndarray:
        qq = q.copy()
        qq[list(subset)] = x.reshape(-1, 3) * [1.0, 1.0, 1.0 / scale]
        return qq

    def fun(x: np.ndarray) -> np.ndarray:
        return scaled(put(x), mech, rows, scale, drive_values)[0][sel]

    def jac(x: np.ndarray) -> np.ndarray:
        return scaled(put(x), mech, rows, scale, drive_values)[1][np.ix_(sel, cols)]

    x0 = (q[list(subset)] * [1.0, 1.0, scale]).ravel()
    sol = least_squares(fun, x0, jac=jac, method="lm", xtol=1e-15, ftol=1e-15, gtol=1e-15, max_nfev=400)
    q = put(sol.x)
    return q, float(np.max(np.abs(fun(sol.x)))) if sel else 0.0


def initial_guess(
    mech: Mechanism, q: np.ndarray, group: AssurGroup, placed: set[int], hints: dict[int, np.ndarray]
) -> np.ndarray:
    """A starting pose of the group's links from placed joints and hints."""
    from linkwork.structure.constraints import global_points

    q = q.copy()
    glob_all = global_points(q, mech.point_link, mech.point_local)
    for i in group.links:
        local, glob = [], []
        theta = None
        for k in group.pairs:
            a, b = (int(v) for v in mech.pair_links[k])
            if i not in (a, b):
                continue
            other = b if i == a else a
            if other in placed and mech.pair_type[k] == REVOLUTE:
                mine = mech.pair_points[k, 0 if i == a else 1]
                theirs = mech.pair_points[k, 1 if i == a else 0]
                local.append(mech.point_local[mine])
                glob.append(glob_all[theirs])
            if other in placed and mech.pair_type[k] == PRISMATIC:
                theta = q[other, 2]
            for d, dk in enumerate(mech.drive_pair):
                if dk == k and other in placed and mech.pair_type[k] == REVOLUTE:
                    phi = mech.drive_start[d]
                    theta = q[a, 2] + phi if i == b else q[b, 2] - phi
        for p in np.flatnonzero(mech.point_link == i):
            if int(p) in hints:
                local.append(mech.point_local[p])
                glob.append(hints[int(p)])
        if local:
            q[i] = fit_pose(np.array(local), np.array(glob), theta)
        elif theta is not None:
            q[i, 2] = theta
    return q


def assemble(
    mech: Mechanism, rows: Rows, groups: list[AssurGroup], hints: dict[int, np.ndarray], scale: float
) -> np.ndarray:
    """Poses ``(N, 3)`` of the assembly; raises UnassemblableError."""
    q = np.zeros((mech.n_links_total, 3))
    placed = {0}
    for group in groups:
        q = initial_guess(mech, q, group, placed, hints)
        sel = group_rows(rows, placed, set(group.links))
        q, worst = solve_group(mech, rows, q, group.links, sel, scale)
        if not worst <= 1e-9 * scale:
            raise UnassemblableError(_why(mech, group, worst), group=group.label)
        placed |= set(group.links)
    return q


def _why(mech: Mechanism, group: AssurGroup, worst: float) -> str:
    drives = ", ".join(
        f"{mech.pair_joint[k]} = {_coord(mech, k, mech.drive_start[d])}" for d, k in enumerate(mech.drive_pair)
    )
    return (
        f"group {group.label} (links {', '.join(group.link_names)}) cannot be assembled at the drive "
        f"position {drives}: its joints {', '.join(group.joints)} cannot all be closed "
        f"(a gap of {worst:.4g} m remains); check the dimensions, or the drive angle of the assembly pose"
    )


def _coord(mech: Mechanism, pair: int, value: float) -> str:
    if mech.pair_type[pair] == REVOLUTE:
        return f"{math.degrees(value):.6g} deg"
    return f"{value:.6g} m"
