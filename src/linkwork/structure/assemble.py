"""Assemble a mechanism in its assembly pose, group by group, from the hints.

Each group of the decomposition is solved by a least-squares Newton method
(scipy's Levenberg-Marquardt) on its own coordinates, started from the pose
that best fits the already placed joint points and the hints.  The hints
thus choose the assembly mode of every group.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import NamedTuple

import numpy as np

from linkwork.errors import UnassemblableError
from linkwork.structure.constraints import Rows, residuals_and_jacobian
from linkwork.structure.model import AssurGroup, Mechanism, PairType, global_points


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


def scaled(
    q: np.ndarray, mech: Mechanism, rows: Rows, scale: float, drive_values: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """Residuals and Jacobian with angles made commensurate with lengths."""
    r, jac = residuals_and_jacobian(q, mech, drive_values, with_drives=True)
    r = np.where(rows.angular, r * scale, r)
    jac = np.where(rows.angular[:, None], jac * scale, jac)
    jac[:, 2::3] /= scale
    return r, jac


def group_rows(rows: Rows, placed: set[int], group: set[int]) -> list[int]:
    """The constraint rows a group owns: those between its links and the links ``placed`` before it."""
    allowed = placed | group
    return [i for i, rl in enumerate(rows.links) if set(map(int, rl)) <= allowed and set(map(int, rl)) & group]


def solve_group(
    mech: Mechanism,
    rows: Rows,
    q: np.ndarray,
    subset: tuple[int, ...],
    sel: list[int],
    scale: float,
    drive_values: np.ndarray | None = None,
) -> tuple[np.ndarray, float]:
    """Solve one group in place of ``q``; returns the new q and the largest residual (m)."""
    cols = [3 * i + c for i in subset for c in range(3)]
    q = q.copy()

    def put(x: np.ndarray) -> np.ndarray:
        qq = q.copy()
        qq[list(subset)] = x.reshape(-1, 3) * [1.0, 1.0, 1.0 / scale]
        return qq

    last: list[tuple[bytes, tuple[np.ndarray, np.ndarray]]] = []

    def both(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:  # residuals and Jacobian of the last x, once
        if not last or last[0][0] != x.tobytes():
            last[:] = [(x.tobytes(), scaled(put(x), mech, rows, scale, drive_values))]
        return last[0][1]

    def fun(x: np.ndarray) -> np.ndarray:
        return both(x)[0][sel]

    def jac(x: np.ndarray) -> np.ndarray:
        return both(x)[1][np.ix_(sel, cols)]

    x0 = (q[list(subset)] * [1.0, 1.0, scale]).ravel()
    x = least_squares(fun, jac, x0)
    q = put(x)
    return q, float(np.max(np.abs(fun(x)))) if sel else 0.0


def least_squares(
    fun: Callable[[np.ndarray], np.ndarray], jac: Callable[[np.ndarray], np.ndarray], x0: np.ndarray, steps: int = 400
) -> np.ndarray:
    """The ``x`` nearest ``x0`` that minimises ``|fun(x)|``, by the Levenberg-Marquardt method (Marquardt's
    scaling by the diagonal of ``J^T J``), to the last bit that lowers the residual: ``steps`` evaluations
    of ``fun`` at the most (as scipy's MINPACK ``lm`` with every tolerance 1e-15; for the few unknowns of an
    Assur group without the half second of importing ``scipy.optimize``)."""
    x = np.asarray(x0, dtype=float).copy()
    r = fun(x)
    cost, damping = float(r @ r), 1e-3
    for _ in range(steps):
        if math.sqrt(cost) <= 1e-16 * (1.0 + float(np.linalg.norm(x))):
            break  # the residual is down to the rounding of the unknowns
        j = jac(x)
        grad, normal = j.T @ r, j.T @ j
        scale = np.diag(np.maximum(np.diag(normal), 1e-12 * max(float(normal.diagonal().max()), 1e-300)))
        step = np.linalg.solve(normal + damping * scale, -grad)
        if -(2 * grad @ step + step @ normal @ step) <= 1e-15 * cost:
            break  # the linear model promises nothing more: a minimum, to the last bits
        trial = fun(x + step)
        new = float(trial @ trial)
        if new < cost:
            x, r, cost, damping = x + step, trial, new, max(damping / 10, 1e-15)
            if np.linalg.norm(step) <= 1e-15 * (1e-15 + np.linalg.norm(x)):
                break  # the unknowns no longer change
        elif damping >= 1e16:
            break  # no step lowers the residual
        else:
            damping *= 10
    return x


class Located(NamedTuple):
    """A point of a link whose place is known before its group is solved: the link's point ``own`` is at the
    point ``point`` of a placed link (``source`` "joint") or at the hint for it (``source`` "hint")."""

    own: int
    source: str
    point: int


class TiedAngle(NamedTuple):
    """A link's angle known through the prismatic or driven revolute ``pair`` that ties it to ``other``."""

    pair: int
    other: int


def locate(
    mech: Mechanism, group: AssurGroup, placed: set[int], hints: dict[int, np.ndarray]
) -> tuple[dict[int, list[Located]], dict[int, TiedAngle | None]]:
    """What fixes each link of a group before it is solved.

    Returns
    -------
    points : dict
        For each link, its located points: joint points of placed links, and hints.
    angle : dict
        For each link, how its angle is known: tied by a prismatic or driven
        revolute pair to a link whose angle is known (placed, fitted, or
        itself tied), else None.
    """
    points: dict[int, list[Located]] = {i: [] for i in group.links}
    angle: dict[int, TiedAngle | None] = dict.fromkeys(group.links)
    driven = set(int(k) for k in mech.drive_pair)
    for i in group.links:
        for k in group.pairs:
            a, b = (int(v) for v in mech.pair_links[k])
            if i in (a, b) and (b if i == a else a) in placed and mech.pair_type[k] == PairType.REVOLUTE:
                mine, theirs = mech.pair_points[k, 0 if i == a else 1], mech.pair_points[k, 1 if i == a else 0]
                points[i].append(Located(int(mine), "joint", int(theirs)))
        for p in np.flatnonzero(mech.point_link == i):
            if int(p) in hints and all(int(p) != located.own for located in points[i]):
                points[i].append(Located(int(p), "hint", int(p)))
    known = set(placed) | {i for i in group.links if len(points[i]) >= 2}
    changed = True
    while changed:
        changed = False
        for k in group.pairs:
            a, b = (int(v) for v in mech.pair_links[k])
            if mech.pair_type[k] == PairType.PRISMATIC or k in driven:
                for i, other in ((a, b), (b, a)):
                    if i in angle and i not in known and other in known:
                        angle[i] = TiedAngle(k, other)
                        known.add(i)
                        changed = True
    return points, angle


def unfixed_links(mech: Mechanism, group: AssurGroup, placed: set[int], hints: dict[int, np.ndarray]) -> list[int]:
    """Links of a group whose starting pose the placed joints and hints leave open."""
    points, angle = locate(mech, group, placed, hints)
    n_points = np.bincount(mech.point_link, minlength=mech.n_links_total)
    return [i for i in group.links if len(points[i]) < 2 and angle[i] is None and n_points[i] >= 2]


def initial_guess(
    mech: Mechanism, q: np.ndarray, group: AssurGroup, placed: set[int], hints: dict[int, np.ndarray]
) -> np.ndarray:
    """A starting pose of the group's links from placed joints and hints."""
    q = q.copy()
    glob_all = global_points(q, mech.point_link, mech.point_local)
    points, angle = locate(mech, group, placed, hints)

    def target(src: str, p: int) -> np.ndarray:
        return glob_all[p] if src == "joint" else hints[p]

    fitted: set[int] = set(placed)
    pending = list(group.links)
    for _ in range(len(pending) + 1):
        for i in list(pending):
            how = angle[i]
            theta = None
            if how is not None:
                k, other = how
                if other not in fitted:
                    continue
                theta = q[other, 2]
                a, b = (int(v) for v in mech.pair_links[k])
                for d, dk in enumerate(mech.drive_pair):
                    if dk == k and mech.pair_type[k] == PairType.REVOLUTE:
                        phi = mech.drive_start[d]
                        theta = q[a, 2] + phi if i == b else q[b, 2] - phi
            local = [mech.point_local[located.own] for located in points[i]]
            glob = [target(located.source, located.point) for located in points[i]]
            if local:
                q[i] = fit_pose(np.array(local), np.array(glob), theta)
            elif theta is not None:
                q[i, 2] = theta
            fitted.add(i)
            pending.remove(i)
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
            raise UnassemblableError(_why(mech, group, worst, q, placed), group=group.label)
        placed |= set(group.links)
    return q


def _why(mech: Mechanism, group: AssurGroup, worst: float, q: np.ndarray, placed: set[int]) -> str:
    drives = ", ".join(
        f"{mech.pair_joint[k]} = {_coord(mech, k, mech.drive_start[d])}" for d, k in enumerate(mech.drive_pair)
    )
    reason = _dyad_reason(mech, group, q, placed) or (
        f"its joints {', '.join(group.joints)} cannot all be closed (a gap of {worst:.4g} m remains)"
    )
    return (
        f"group {group.label} (links {', '.join(group.link_names)}) cannot be assembled at the drive "
        f"position {drives}: {reason}; check the dimensions, or the drive angle of the assembly pose"
    )


def _dyad_reason(mech: Mechanism, group: AssurGroup, q: np.ndarray, placed: set[int]) -> str | None:
    """Why an RRR or RRP dyad does not close, in the words of the circle construction."""
    if group.klass != 2 or group.kind not in ("RRR", "RRP"):
        return None
    dyad = _Dyad(mech, group, q, placed)
    (la, ka), (lb, kb) = dyad.outer.items()
    if group.kind == "RRR":
        ra, pa, na = dyad.arm(la, ka)
        rb, pb, nb = dyad.arm(lb, kb)
        d = float(np.hypot(*(pa - pb)))
        if d > ra + rb:
            return (
                f"the joints {na} and {nb} are {d:.4g} m apart, more than the {ra:.4g} + {rb:.4g} = "
                f"{ra + rb:.4g} m that the links {mech.link_names[la]} and {mech.link_names[lb]} can span"
            )
        return (
            f"the joints {na} and {nb} are {d:.4g} m apart, less than the difference {abs(ra - rb):.4g} m "
            f"of the links {mech.link_names[la]} and {mech.link_names[lb]}"
        )
    rod, slider = (la, lb) if mech.pair_type[dyad.outer[la]] == PairType.REVOLUTE else (lb, la)
    r, p, name = dyad.arm(rod, dyad.outer[rod])
    h = dyad.off_line(slider, p)
    return (
        f"the joint {name} is {h:.4g} m from the line on which the slider {mech.link_names[slider]} "
        f"carries the joint {mech.pair_joint[dyad.inner]}, more than the {r:.4g} m of the link {mech.link_names[rod]}"
    )


class _Dyad:
    """A dyad that does not close, in the pose ``q`` of the links ``placed`` before it: its inner pair, and
    the outer pair of each of its links (``outer``: link -> pair)."""

    def __init__(self, mech: Mechanism, group: AssurGroup, q: np.ndarray, placed: set[int]) -> None:
        self.mech, self.q, self.placed = mech, q, placed
        self.glob = global_points(q, mech.point_link, mech.point_local)
        self.inner = next(k for k in group.pairs if set(map(int, mech.pair_links[k])) <= set(group.links))
        self.outer: dict[int, int] = {}
        for k in group.pairs:
            if k == self.inner:
                continue
            a, b = (int(v) for v in mech.pair_links[k])
            self.outer[b if a in placed else a] = k

    def _inner_point(self, link: int) -> int:
        """The inner joint's point on ``link``."""
        return int(self.mech.pair_points[self.inner, 0 if int(self.mech.pair_links[self.inner, 0]) == link else 1])

    def arm(self, link: int, k: int) -> tuple[float, np.ndarray, str]:
        """Distance on ``link`` from its outer joint ``k`` to the inner one, the outer joint's position, name."""
        mech = self.mech
        a = int(mech.pair_links[k, 0])
        own = int(mech.pair_points[k, 1 if a in self.placed else 0])
        other = int(mech.pair_points[k, 0 if a in self.placed else 1])
        span = mech.point_local[self._inner_point(link)] - mech.point_local[own]
        return float(np.hypot(*span)), self.glob[other], mech.pair_joint[k]

    def off_line(self, slider: int, p: np.ndarray) -> float:
        """Distance of the point ``p`` from the line on which ``slider`` carries the inner joint."""
        mech, kp = self.mech, self.outer[slider]
        guide = int(mech.pair_links[kp, 0])
        c, s = math.cos(self.q[guide, 2]), math.sin(self.q[guide, 2])
        rot = np.array([[c, -s], [s, c]])
        u = rot @ mech.pair_axis[kp]
        origin = self.q[guide, :2] + rot @ mech.pair_origin[kp]
        offset = rot @ (mech.point_local[self._inner_point(slider)] - mech.point_local[int(mech.pair_points[kp, 1])])
        n = np.array([-u[1], u[0]])
        return abs(float(n @ (p - origin - offset)))


def _coord(mech: Mechanism, pair: int, value: float) -> str:
    if mech.pair_type[pair] == PairType.REVOLUTE:
        return f"{math.degrees(value):.6g} deg"
    return f"{value:.6g} m"
