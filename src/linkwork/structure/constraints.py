"""Constraint equations of a planar mechanism and their Jacobian.

Every link ``i`` has a pose ``q[i] = (x, y, theta)``: the global position of
its local origin and the angle of its local x axis.  Link 0 is the frame
(pose zero).  A point with local coordinates ``p`` on link ``i`` is at
``(x, y) + R(theta) p``.

Rows, per pair:

* revolute ``a``-``b`` at points ``pa``, ``pb``: ``P_a - P_b = 0`` (2 rows);
* prismatic, guide ``a`` with line through ``c`` along ``u`` (local to a),
  slider ``b`` with point ``pb``: ``theta_b - theta_a = 0`` and
  ``n_a . (P_b - C_a) = 0`` with ``n = perp(u)`` (2 rows);

and per drive: ``theta_b - theta_a - phi = 0`` (revolute) or
``u_a . (P_b - C_a) - s = 0`` (prismatic).

All functions broadcast over leading dimensions of ``q``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from linkwork.angles import wrap
from linkwork.structure.model import Mechanism, PairType
from linkwork.structure.parameters import Geometry


@dataclass(frozen=True)
class Rows:
    """Bookkeeping of the constraint rows.

    Attributes
    ----------
    pair : ndarray of int, shape (m,)
        Pair index of each row (-1 for a drive row).
    drive : ndarray of int, shape (m,)
        Drive index of each row (-1 for a pair row).
    links : ndarray of int, shape (m, 2)
        The two links a row involves.
    angular : ndarray of bool, shape (m,)
        Rows whose residual is an angle (rad) rather than a length.
    """

    pair: np.ndarray
    drive: np.ndarray
    links: np.ndarray
    angular: np.ndarray

    @property
    def n(self) -> int:
        return len(self.pair)


def build_rows(pair_type: np.ndarray, pair_links: np.ndarray, drive_pair: np.ndarray) -> Rows:
    """Rows of the pair constraints followed by one row per drive."""
    pair, drive, links, angular = [], [], [], []
    for k, kind in enumerate(pair_type):
        pair += [k, k]
        drive += [-1, -1]
        links += [pair_links[k], pair_links[k]]
        angular += [False, False] if kind == PairType.REVOLUTE else [True, False]
    for d, k in enumerate(drive_pair):
        pair.append(-1)
        drive.append(d)
        links.append(pair_links[k])
        angular.append(pair_type[k] == PairType.REVOLUTE)
    return Rows(
        np.array(pair, dtype=int),
        np.array(drive, dtype=int),
        np.array(links, dtype=int).reshape(-1, 2),
        np.array(angular, dtype=bool),
    )


def _rot(theta: np.ndarray, v: np.ndarray) -> np.ndarray:
    c, s = np.cos(theta), np.sin(theta)
    return np.stack([c * v[..., 0] - s * v[..., 1], s * v[..., 0] + c * v[..., 1]], axis=-1)


#: The quarter turn of a reversed pair: ``(u_y, u_x) * (-1, 1) = (-u_y, u_x)``.
_QUARTER = np.array([-1.0, 1.0])


def perp(u: np.ndarray) -> np.ndarray:
    """``u`` turned a quarter counter-clockwise, ``(..., 2)``: ``(-u_y, u_x)`` (one NumPy operation, exact)."""
    return np.asarray(u)[..., ::-1] * _QUARTER


#: The local dimensions the constraints are read with: a mechanism's own, or its variants'.
Dimensions = Geometry | Mechanism


@dataclass(frozen=True)
class _Poses:
    """Link poses ``q`` ``(..., N, 3)`` broadcast over ``batch``, the leading dimensions of ``q`` and of the
    dimensions ``dims`` they are read with."""

    q: np.ndarray
    dims: Dimensions
    batch: tuple[int, ...]
    jac: np.ndarray  # (..., m, 3 N): the Jacobian, filled a row at a time
    filled: list[int] = field(default_factory=lambda: [0])

    def zeros(self) -> np.ndarray:
        """The Jacobian's next row, of zeros, ``(..., 3 N)`` (a view: the rows are asked for in their order)."""
        i = self.filled[0]
        self.filled[0] = i + 1
        return self.jac[..., i, :]

    def point(self, link: int, p_local: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Global position ``(..., 2)`` of the point ``p_local`` of ``link`` and its derivative by the link's angle."""
        theta = self.q[..., link, 2]
        rp = _rot(theta, np.broadcast_to(p_local, self.batch + (2,)))
        return self.q[..., link, :2] + rp, perp(rp)


def residuals_and_jacobian(
    q: np.ndarray,
    mech: Mechanism,
    drive_values: np.ndarray | None = None,
    with_drives: bool = True,
    geom: Geometry | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Residuals ``(..., m)`` and Jacobian ``(..., m, 3 * n_links_total)``.

    Parameters
    ----------
    q : ndarray, shape (..., N, 3)
        Link poses, frame included as link 0.
    mech : Mechanism
        Needs the ``pair_*``, ``point_*`` and ``drive_*`` arrays.
    geom : Geometry, optional
        Dimensions of design variants (``point_local``, ``pair_origin``,
        ``pair_axis`` with leading dimensions that broadcast against ``q``'s);
        default: the mechanism's own.
    drive_values : ndarray, shape (..., n_drives), optional
        Drive coordinates; default: the assembly values ``drive_start``.
    with_drives : bool
        Include the drive rows.
    """
    q = np.asarray(q, dtype=float)
    dims: Dimensions = mech if geom is None else geom
    batch = np.broadcast_shapes(q.shape[:-2], np.shape(dims.point_local)[:-2])
    m = 2 * len(mech.pair_type) + (len(mech.drive_pair) if with_drives else 0)
    at = _Poses(np.broadcast_to(q, batch + q.shape[-2:]), dims, batch, np.zeros(batch + (m, 3 * q.shape[-2])))
    rows: list[tuple[np.ndarray, np.ndarray]] = []
    for k, kind in enumerate(mech.pair_type):
        rows += _revolute_rows(at, mech, k) if kind == PairType.REVOLUTE else _prismatic_rows(at, mech, k)
    if with_drives:
        values = mech.drive_start if drive_values is None else np.asarray(drive_values, dtype=float)
        values = np.broadcast_to(values, batch + (len(mech.drive_pair),))
        rows += [_drive_row(at, mech, k, values[..., d]) for d, k in enumerate(mech.drive_pair)]
    if not rows:
        return np.zeros(batch + (0,)), np.zeros(batch + (0, 3 * q.shape[-2]))
    assert at.filled[0] == m == len(rows)
    return np.stack([r for r, _ in rows], axis=-1), at.jac


def _revolute_rows(at: _Poses, mech: Mechanism, k: int) -> list[tuple[np.ndarray, np.ndarray]]:
    """The residual and Jacobian row of revolute pair ``k`` along x and along y: ``P_a - P_b``."""
    a, b = mech.pair_links[k]
    pa, dpa = at.point(a, at.dims.point_local[..., mech.pair_points[k, 0], :])
    pb, dpb = at.point(b, at.dims.point_local[..., mech.pair_points[k, 1], :])
    out = []
    for axis in (0, 1):
        row = at.zeros()
        row[..., 3 * a + axis] += 1.0
        row[..., 3 * a + 2] += dpa[..., axis]
        row[..., 3 * b + axis] -= 1.0
        row[..., 3 * b + 2] -= dpb[..., axis]
        out.append((pa[..., axis] - pb[..., axis], row))
    return out


def _prismatic_rows(at: _Poses, mech: Mechanism, k: int) -> list[tuple[np.ndarray, np.ndarray]]:
    """The residuals and Jacobian rows of prismatic pair ``k``: the slider's angle less the guide's, and the
    distance of the slider's point from the guide line."""
    a, b = mech.pair_links[k]
    row = at.zeros()
    row[..., 3 * b + 2] += 1.0
    row[..., 3 * a + 2] -= 1.0
    return [(wrap(at.q[..., b, 2] - at.q[..., a, 2]), row), _line_row(at, mech, k, normal=True)]


def _drive_row(at: _Poses, mech: Mechanism, k: int, value: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The residual and Jacobian row of a drive of pair ``k`` at the drive coordinates ``value`` ``(...)``:
    the angle of b from a less the drive angle, or the slider's point along the guide less the drive position."""
    a, b = mech.pair_links[k]
    if mech.pair_type[k] != PairType.REVOLUTE:
        r, row = _line_row(at, mech, k, normal=False)
        return r - value, row
    row = at.zeros()
    row[..., 3 * b + 2] += 1.0
    row[..., 3 * a + 2] -= 1.0
    return wrap(at.q[..., b, 2] - at.q[..., a, 2] - value), row


def _line_row(at: _Poses, mech: Mechanism, k: int, normal: bool) -> tuple[np.ndarray, np.ndarray]:
    """The slider's point of prismatic pair ``k`` from the guide line's origin, along the line's normal (``normal``)
    or its direction, ``v . (P_b - C_a)``, and its Jacobian row."""
    a, b = mech.pair_links[k]
    p_b, dpb = at.point(b, at.dims.point_local[..., mech.pair_points[k, 1], :])
    c_a, dc = at.point(a, at.dims.pair_origin[..., k, :])
    u = _rot(at.q[..., a, 2], np.broadcast_to(at.dims.pair_axis[..., k, :], at.batch + (2,)))
    v = perp(u) if normal else u
    dv = perp(v)  # d(v)/d(theta_a)
    d = p_b - c_a
    r = np.sum(v * d, axis=-1)
    row = at.zeros()
    row[..., 3 * a : 3 * a + 2] -= v
    row[..., 3 * a + 2] += np.sum(dv * d, axis=-1) - np.sum(v * dc, axis=-1)
    row[..., 3 * b : 3 * b + 2] += v
    row[..., 3 * b + 2] += np.sum(v * dpb, axis=-1)
    return r, row


def velocity_products(q: np.ndarray, qd: np.ndarray, mech: Mechanism, geom: Geometry | None = None) -> np.ndarray:
    """The terms of the constraints' second time derivative that are quadratic in velocity.

    With these, ``J @ qdd + gamma = d2(drive)/dt2`` on drive rows and 0 on the others.
    Shapes as in :func:`residuals_and_jacobian`: ``(..., m)`` with the drive rows last.
    """
    dims: Dimensions = mech if geom is None else geom
    batch = np.broadcast_shapes(q.shape[:-2], qd.shape[:-2], np.shape(dims.point_local)[:-2])
    q = np.broadcast_to(q, batch + q.shape[-2:])
    qd = np.broadcast_to(qd, batch + qd.shape[-2:])
    out: list[np.ndarray] = []

    def rp(link: int, p_local: np.ndarray) -> np.ndarray:
        return _rot(q[..., link, 2], np.broadcast_to(p_local, batch + (2,)))

    def vel(link: int, r: np.ndarray) -> np.ndarray:
        return qd[..., link, :2] + qd[..., link, 2, None] * perp(r)

    def line_gamma(k: int, direction: str) -> np.ndarray:
        a, b = mech.pair_links[k]
        r_b = rp(b, dims.point_local[..., mech.pair_points[k, 1], :])
        r_c = rp(a, dims.pair_origin[..., k, :])
        u = rp(a, dims.pair_axis[..., k, :])
        v = perp(u) if direction == "n" else u
        d = q[..., b, :2] + r_b - q[..., a, :2] - r_c
        dd = vel(b, r_b) - vel(a, r_c)
        wa, wb = qd[..., a, 2], qd[..., b, 2]
        return (
            -(wa**2) * np.sum(v * d, -1)
            + 2 * wa * np.sum(perp(v) * dd, -1)
            + np.sum(v * (-(wb[..., None] ** 2) * r_b + wa[..., None] ** 2 * r_c), -1)
        )

    for k, kind in enumerate(mech.pair_type):
        a, b = mech.pair_links[k]
        if kind == PairType.REVOLUTE:
            ra = rp(a, dims.point_local[..., mech.pair_points[k, 0], :])
            rb = rp(b, dims.point_local[..., mech.pair_points[k, 1], :])
            g = -(qd[..., a, 2, None] ** 2) * ra + qd[..., b, 2, None] ** 2 * rb
            out += [g[..., 0], g[..., 1]]
        else:
            out.append(np.zeros(batch))
            out.append(line_gamma(k, "n"))
    for k in mech.drive_pair:
        out.append(np.zeros(batch) if mech.pair_type[k] == PairType.REVOLUTE else line_gamma(k, "u"))
    return np.stack(out, axis=-1)
