"""The reactions solved one sample at a time in machine code (with numba, when installed): the twin of
:mod:`linkwork.kinetostatics.reactions`.

The same mathematics as :func:`linkwork.kinetostatics.reactions.solve_reactions`:
the constraint Jacobian's rows of each Assur group, from the last group back,
a small square system per group (Gaussian elimination with partial pivoting),
the reactions of the groups solved before it as known loads.  The inertia and
gravity loads are formed in the kernel from the link states; external loads
come in as generalised forces.  A group whose pivots fall below
:data:`SINGULAR` relative to its matrix gets NaN reactions, and so do the
groups solved after it.  It runs where the compiled kinematics ran
(:func:`linkwork.jit.loaded`).
"""

from __future__ import annotations

import functools
import math
from typing import NamedTuple

import numpy as np

from linkwork import jit, threads
from linkwork.kinetostatics.external import Applied
from linkwork.kinetostatics.geometry import variant_geometry
from linkwork.kinetostatics.reactions import group_order
from linkwork.motion import kernels_numba
from linkwork.motion.kinematic_analysis import Kinematics
from linkwork.structure.model import Mechanism, PairType, per_mechanism

#: Row kinds.
REV_X, REV_Y, ANGLE, NORMAL, DRIVE_ANGLE, DRIVE_LINE = range(6)
#: Smallest pivot, relative to the largest entry of a group's matrix, of a solvable group.
SINGULAR = 1e-12


def available() -> bool:
    """Whether the compiled kernel runs (numba there, imported now if it was not, and not turned off)."""
    return kernels_numba.available() and compiled()


class Encoded(NamedTuple):
    """A mechanism's constraint rows and Assur groups as integer tables for the kernel.

    Attributes
    ----------
    rows : ndarray of int, shape (m, 6)
        Each row: its kind (:data:`REV_X`, ...), links a and b, point of a, point of b, pair.
    groups : ndarray of int, shape (G, 2 + 4 L + m + 1)
        The groups in the order they are solved (reverse of the structure), one a row: the number of
        its links, its links (``L`` places, the most links of a group), the number of its rows, its rows
        (``3 L`` places), then the rows of the groups solved before it that touch its links (ended by -1).
    on_frame : ndarray of int
        The rows that touch the frame, ended by -1.
    """

    rows: np.ndarray
    groups: np.ndarray
    on_frame: np.ndarray

    @property
    def width(self) -> int:
        """``L``, the most links of a group."""
        return (self.groups.shape[1] - 2 - len(self.rows) - 1) // 4


@per_mechanism
def encode(mech: Mechanism) -> Encoded:
    """The constraint rows and the Assur groups of ``mech`` as the kernel reads them (found once per
    mechanism: its structure alone decides them; shared, not to be changed)."""
    rows = []
    for k in range(mech.n_pairs):
        a, b = (int(x) for x in mech.pair_links[k])
        pa, pb = (int(x) for x in mech.pair_points[k])
        if mech.pair_type[k] == PairType.REVOLUTE:
            rows += [[REV_X, a, b, pa, pb, k], [REV_Y, a, b, pa, pb, k]]
        else:
            rows += [[ANGLE, a, b, pa, pb, k], [NORMAL, a, b, pa, pb, k]]
    for k in mech.drive_pair:
        a, b = (int(x) for x in mech.pair_links[k])
        kind = DRIVE_ANGLE if mech.pair_type[k] == PairType.REVOLUTE else DRIVE_LINE
        rows.append([kind, a, b, int(mech.pair_points[k, 0]), int(mech.pair_points[k, 1]), int(k)])
    owned = group_order(mech)
    width = max(len(links) for links, _ in owned)
    known_width = len(rows) + 1
    table = np.full((len(owned), 2 + 4 * width + known_width), -1, dtype=np.int64)
    done: list[int] = []
    for g, (links, sel) in enumerate(reversed(owned)):
        table[g, 0] = len(links)
        table[g, 1 : 1 + len(links)] = links
        table[g, 1 + width] = len(sel)
        table[g, 2 + width : 2 + width + len(sel)] = sel
        known = [r for r in done if rows[r][1] in links or rows[r][2] in links]
        table[g, 2 + 4 * width : 2 + 4 * width + len(known)] = known
        done += sel
    on_frame = [r for r in range(len(rows)) if rows[r][1] == 0 or rows[r][2] == 0] + [-1]
    tables = Encoded(np.array(rows, dtype=np.int64).reshape(-1, 6), table, np.array(on_frame, dtype=np.int64))
    for t in tables:
        t.setflags(write=False)  # shared by every later call
    return tables


@per_mechanism
def _shapes_of(mech: Mechanism) -> np.ndarray:
    """:func:`shapes` of the tables of ``mech``, found once per mechanism."""
    rows, groups, _ = encode(mech)
    out = shapes(rows, groups)
    out.setflags(write=False)  # shared by every later call
    return out


#: Shapes of a group's system: general (Gaussian elimination), one link with three rows, a dyad.
GENERAL, SINGLE, DYAD = range(3)


def shapes(rows: np.ndarray, groups: np.ndarray) -> np.ndarray:
    """How each group's system is solved, ``(G, 7)``: the shape, then its rows in the order the
    solver takes them (SINGLE: the three rows; DYAD: two rows on the first link only, two on the
    second only, two between them)."""
    width = (groups.shape[1] - 2 - rows.shape[0] - 1) // 4
    out = np.full((len(groups), 7), -1, dtype=np.int64)
    out[:, 0] = GENERAL
    for g, row in enumerate(groups):
        links = [int(x) for x in row[1 : 1 + row[0]]]
        sel = [int(x) for x in row[2 + width : 2 + width + row[1 + width]]]
        if len(links) == 1 and len(sel) == 3:
            out[g] = [SINGLE, *sel, -1, -1, -1]
            continue
        if len(links) != 2 or len(sel) != 6:
            continue
        touch = [tuple(link in (rows[r, 1], rows[r, 2]) for link in links) for r in sel]
        only_a = [r for r, t in zip(sel, touch, strict=True) if t == (True, False)]
        only_b = [r for r, t in zip(sel, touch, strict=True) if t == (False, True)]
        both = [r for r, t in zip(sel, touch, strict=True) if t == (True, True)]
        if len(only_a) == len(only_b) == len(both) == 2:
            out[g] = [DYAD, *only_a, *only_b, *both]
    return out


def run(kin: Kinematics, applied: Applied | None) -> tuple[np.ndarray, np.ndarray]:
    """Multipliers ``(V, A, m)`` and the foundation loads ``(V, A, 3)``: the pairs' force and moment
    on the frame plus the frame's own applied loads (its weight, external loads on it).

    ``applied``: the external loads, or None.
    """
    mech = kin.mechanism
    rows, groups, on_frame = encoded = encode(mech)
    shape_of = _shapes_of(mech)
    n_var, n_ang = kin.valid_all.shape
    geom = variant_geometry(kin)
    local, origin, axis = (
        jit.read_only(np.ascontiguousarray(g[:, 0])) for g in (geom.point_local, geom.pair_origin, geom.pair_axis)
    )
    f_link, f_val, f_pos, m_link, m_val = _external(applied, (n_var, n_ang))
    ms = kin.mass_properties  # (V or 1, N)
    mass = np.ascontiguousarray(np.broadcast_to(ms.mass, (n_var, mech.n_links_total)), dtype=float)
    com = np.ascontiguousarray(np.broadcast_to(ms.com, (n_var, mech.n_links_total, 2)), dtype=float)
    inertia = np.ascontiguousarray(np.broadcast_to(ms.inertia, (n_var, mech.n_links_total)), dtype=float)
    m = len(rows)
    lam = np.empty((n_var, n_ang, m))
    frame = np.empty((n_var, n_ang, 3))
    size = 3 * encoded.width

    gx, gy = (float(x) for x in mech.gravity_vector)

    def part(lo: int, hi: int) -> None:
        _kernel(
            rows,
            groups,
            shape_of,
            on_frame,
            kin.q,
            kin.v,
            kin.a,
            local,
            origin,
            axis,
            mass,
            com,
            inertia,
            gx,
            gy,
            f_link,
            f_val,
            f_pos,
            m_link,
            m_val,
            lam,
            frame,
            lo,
            hi,
            np.empty((mech.n_links_total, 6)),
            np.empty((m, 6)),
            np.empty((size, size)),
            np.empty(size),
            np.empty(m),
            np.zeros((m, 8)),
        )

    threads.in_parts(part, n_ang, n_var * n_ang)
    return lam, frame


def _external(applied: Applied | None, shape: tuple[int, int]) -> tuple[np.ndarray, ...]:
    """The external loads as the kernel reads them: the links of the forces ``(F,)``, the forces and their
    points ``(F, V, A, 2)``; the links of the moments ``(C,)`` and the moments ``(C, V, A)``."""
    forces = applied.forces if applied is not None else []
    moments = applied.moments if applied is not None else []
    f_link = np.array([f.link for f in forces], dtype=np.int64)
    f_val = np.stack([np.broadcast_to(f.force, shape + (2,)) for f in forces]) if forces else np.zeros((0, 1, 1, 2))
    f_pos = np.stack([np.broadcast_to(f.position, shape + (2,)) for f in forces]) if forces else np.zeros((0, 1, 1, 2))
    m_link = np.array([m.link for m in moments], dtype=np.int64)
    m_val = np.stack([np.broadcast_to(m.moment, shape) for m in moments]) if moments else np.zeros((0, 1, 1))
    return f_link, f_val, f_pos, m_link, m_val


def _row_geometry(rows, local, origin, axis, var, G):
    """Local coordinates each row needs, for one design variant: point of a, point of b, guide
    direction and origin (local to the guide)."""
    for r in range(rows.shape[0]):
        pa, pb, k = rows[r, 3], rows[r, 4], rows[r, 5]
        if pa >= 0:
            G[r, 0], G[r, 1] = local[var, pa, 0], local[var, pa, 1]
        if pb >= 0:
            G[r, 2], G[r, 3] = local[var, pb, 0], local[var, pb, 1]
        G[r, 4], G[r, 5] = axis[var, k, 0], axis[var, k, 1]
        G[r, 6], G[r, 7] = origin[var, k, 0], origin[var, k, 1]


def _rows_at(rows, q, G, var, i, J, Q):
    """Jacobian entries of every row at one sample: J[r] = d/d(x_a, y_a, th_a, x_b, y_b, th_b).
    ``Q[n, 3:6]`` holds cos and sin of every link's angle, and the angle."""
    for r in range(rows.shape[0]):
        kind, a, b = rows[r, 0], rows[r, 1], rows[r, 2]
        if kind == ANGLE or kind == DRIVE_ANGLE:
            J[r, 0], J[r, 1], J[r, 2], J[r, 3], J[r, 4], J[r, 5] = 0.0, 0.0, -1.0, 0.0, 0.0, 1.0
            continue
        ca, sa, cb, sb = Q[a, 3], Q[a, 4], Q[b, 3], Q[b, 4]
        rbx, rby = cb * G[r, 2] - sb * G[r, 3], sb * G[r, 2] + cb * G[r, 3]  # R_b p_b
        if kind == REV_X:
            ray = sa * G[r, 0] + ca * G[r, 1]
            J[r, 0], J[r, 1], J[r, 2], J[r, 3], J[r, 4], J[r, 5] = 1.0, 0.0, -ray, -1.0, 0.0, rby
            continue
        if kind == REV_Y:
            rax = ca * G[r, 0] - sa * G[r, 1]
            J[r, 0], J[r, 1], J[r, 2], J[r, 3], J[r, 4], J[r, 5] = 0.0, 1.0, rax, 0.0, -1.0, -rbx
            continue
        ux, uy = G[r, 4], G[r, 5]
        gx, gy = ca * ux - sa * uy, sa * ux + ca * uy  # the guide direction, global
        if kind == NORMAL:
            gx, gy = -gy, gx
        cx, cy = ca * G[r, 6] - sa * G[r, 7], sa * G[r, 6] + ca * G[r, 7]  # R_a c
        dx = q[b, 0, var, i] + rbx - q[a, 0, var, i] - cx
        dy = q[b, 1, var, i] + rby - q[a, 1, var, i] - cy
        # d(v)/d(theta_a) = perp(v); d(c)/d(theta_a) = perp(R_a c)
        J[r, 0], J[r, 1] = -gx, -gy
        J[r, 2] = (-gy * dx + gx * dy) - (gx * -cy + gy * cx)
        J[r, 3], J[r, 4] = gx, gy
        J[r, 5] = gx * -rby + gy * rbx


def _col(J, rows, r, link):
    """The three entries of row ``r`` in the equations of ``link``."""
    o = 0 if rows[r, 1] == link else 3
    return J[r, o], J[r, o + 1], J[r, o + 2]


def _cross(ax, ay, az, bx, by, bz):
    return ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx


def _single(J, rows, sh, link, x, mu):
    """Three rows on one link: ``[c1 c2 c3] mu = x`` by Cramer's rule; False where singular."""
    r1, r2, r3 = sh[1], sh[2], sh[3]
    c1 = _col(J, rows, r1, link)
    c2 = _col(J, rows, r2, link)
    c3 = _col(J, rows, r3, link)
    n23 = _cross(c2[0], c2[1], c2[2], c3[0], c3[1], c3[2])
    det = c1[0] * n23[0] + c1[1] * n23[1] + c1[2] * n23[2]
    norm = math.sqrt((c1[0] ** 2 + c1[1] ** 2 + c1[2] ** 2) * (n23[0] ** 2 + n23[1] ** 2 + n23[2] ** 2))
    if not abs(det) > SINGULAR * norm:
        return False
    xc3 = _cross(x[0], x[1], x[2], c3[0], c3[1], c3[2])
    c2x = _cross(c2[0], c2[1], c2[2], x[0], x[1], x[2])
    mu[r1] = (x[0] * n23[0] + x[1] * n23[1] + x[2] * n23[2]) / det
    mu[r2] = (c1[0] * xc3[0] + c1[1] * xc3[1] + c1[2] * xc3[2]) / det
    mu[r3] = (c1[0] * c2x[0] + c1[1] * c2x[1] + c1[2] * c2x[2]) / det
    return True


def _pair_on(c1, c2, rx, ry, rz):
    """``c1 l1 + c2 l2 = r`` for (l1, l2), with ``n = c1 x c2`` (r in the plane of c1 and c2)."""
    n = _cross(c1[0], c1[1], c1[2], c2[0], c2[1], c2[2])
    nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2]
    a = _cross(rx, ry, rz, c2[0], c2[1], c2[2])
    b = _cross(c1[0], c1[1], c1[2], rx, ry, rz)
    return (a[0] * n[0] + a[1] * n[1] + a[2] * n[2]) / nn, (b[0] * n[0] + b[1] * n[1] + b[2] * n[2]) / nn


def _dyad(J, rows, sh, la, lb, x, mu):
    """A dyad's six rows: the two between its links from the balance of each link along the normal
    ``n`` of its own outer pair's columns (which takes them out), a 2 x 2 system; then each outer
    pair from its link's balance.  False where singular."""
    ca1, ca2 = _col(J, rows, sh[1], la), _col(J, rows, sh[2], la)
    cb1, cb2 = _col(J, rows, sh[3], lb), _col(J, rows, sh[4], lb)
    da1, da2 = _col(J, rows, sh[5], la), _col(J, rows, sh[6], la)
    db1, db2 = _col(J, rows, sh[5], lb), _col(J, rows, sh[6], lb)
    na = _cross(ca1[0], ca1[1], ca1[2], ca2[0], ca2[1], ca2[2])
    nb = _cross(cb1[0], cb1[1], cb1[2], cb2[0], cb2[1], cb2[2])
    m11 = na[0] * da1[0] + na[1] * da1[1] + na[2] * da1[2]
    m12 = na[0] * da2[0] + na[1] * da2[1] + na[2] * da2[2]
    m21 = nb[0] * db1[0] + nb[1] * db1[1] + nb[2] * db1[2]
    m22 = nb[0] * db2[0] + nb[1] * db2[1] + nb[2] * db2[2]
    det = m11 * m22 - m12 * m21
    scale = math.sqrt((m11 * m11 + m12 * m12) * (m21 * m21 + m22 * m22))
    if not abs(det) > SINGULAR * scale:
        return False
    ra = na[0] * x[0] + na[1] * x[1] + na[2] * x[2]
    rb = nb[0] * x[3] + nb[1] * x[4] + nb[2] * x[5]
    i1 = (ra * m22 - rb * m12) / det
    i2 = (m11 * rb - m21 * ra) / det
    mu[sh[5]], mu[sh[6]] = i1, i2
    a1, a2 = _pair_on(
        ca1, ca2, x[0] - i1 * da1[0] - i2 * da2[0], x[1] - i1 * da1[1] - i2 * da2[1], x[2] - i1 * da1[2] - i2 * da2[2]
    )
    b1, b2 = _pair_on(
        cb1, cb2, x[3] - i1 * db1[0] - i2 * db2[0], x[4] - i1 * db1[1] - i2 * db2[1], x[5] - i1 * db1[2] - i2 * db2[2]
    )
    mu[sh[1]], mu[sh[2]], mu[sh[3]], mu[sh[4]] = a1, a2, b1, b2
    return True


def _rhs(groups, gi, width, known0, rows, J, Q, mu, x):
    """Right-hand side of group ``gi``: -Q of its links less the reactions already known."""
    nl = groups[gi, 0]
    for li in range(nl):
        link = groups[gi, 1 + li]
        for d in range(3):
            x[3 * li + d] = -Q[link, d]
    for kk in range(known0, groups.shape[1]):
        r = groups[gi, kk]
        if r < 0:
            break
        lr = mu[r]
        ra, rb = rows[r, 1], rows[r, 2]
        for li in range(nl):
            link = groups[gi, 1 + li]
            if ra == link:
                for d in range(3):
                    x[3 * li + d] -= J[r, d] * lr
            elif rb == link:
                for d in range(3):
                    x[3 * li + d] -= J[r, 3 + d] * lr


def _link_loads(q, v, a, mass, com, inertia, gx, gy, var, i, Q):
    """Gravity and d'Alembert inertia loads of every link at sample ``(var, i)``, about the link's origin, into
    ``Q[n, 0:3]``; ``Q[n, 3:6]``: cos and sin of the link's angle, and the angle."""
    Q[0, 3], Q[0, 4] = 1.0, 0.0  # the frame does not move
    for n in range(q.shape[0]):
        th, w, e = q[n, 2, var, i], v[n, 2, var, i], a[n, 2, var, i]
        if n > 0 and th != Q[n, 5]:  # a slider's angle stays put: no new cos and sin
            Q[n, 3], Q[n, 4], Q[n, 5] = math.cos(th), math.sin(th), th
        c, s = Q[n, 3], Q[n, 4]
        rx = c * com[var, n, 0] - s * com[var, n, 1]
        ry = s * com[var, n, 0] + c * com[var, n, 1]
        acx = a[n, 0, var, i] - e * ry - w * w * rx
        acy = a[n, 1, var, i] + e * rx - w * w * ry
        fx = -mass[var, n] * acx + mass[var, n] * gx
        fy = -mass[var, n] * acy + mass[var, n] * gy
        Q[n, 0] = fx
        Q[n, 1] = fy
        Q[n, 2] = rx * fy - ry * fx - inertia[var, n] * e


def _external_loads(q, f_link, f_val, f_pos, m_link, m_val, var, i, Q):
    """Add the external forces and moments at sample ``(var, i)`` to ``Q``."""
    for kk in range(f_link.shape[0]):
        n = f_link[kk]
        fx, fy = f_val[kk, var, i, 0], f_val[kk, var, i, 1]
        Q[n, 0] += fx
        Q[n, 1] += fy
        Q[n, 2] += (f_pos[kk, var, i, 0] - q[n, 0, var, i]) * fy - (f_pos[kk, var, i, 1] - q[n, 1, var, i]) * fx
    for kk in range(m_link.shape[0]):
        Q[m_link[kk], 2] += m_val[kk, var, i]


def _group_matrix(groups, gi, width, rows, J, M):
    """``M[c, j]``: the entry of the group's row ``j`` in coordinate ``c`` of its links; returns the largest
    magnitude of an entry."""
    big = 0.0
    for j in range(groups[gi, 1 + width]):
        r = groups[gi, 2 + width + j]
        ra, rb = rows[r, 1], rows[r, 2]
        for li in range(groups[gi, 0]):
            link = groups[gi, 1 + li]
            for d in range(3):
                val = 0.0
                if ra == link:
                    val = J[r, d]
                elif rb == link:
                    val = J[r, 3 + d]
                M[3 * li + d, j] = val
                big = max(big, abs(val))
    return big


def _eliminate(M, x, size, big):
    """Gaussian elimination with partial pivoting of ``M[:size, :size] y = x[:size]``, in place, to an upper
    triangle; False where ``big`` (the largest entry) is zero or a pivot falls below :data:`SINGULAR` relative
    to it."""
    ok = big > 0.0
    for col in range(size):
        if not ok:
            break
        piv = col
        for rr in range(col + 1, size):
            if abs(M[rr, col]) > abs(M[piv, col]):
                piv = rr
        if not abs(M[piv, col]) > SINGULAR * big:
            ok = False
            break
        if piv != col:
            for cc in range(col, size):
                M[col, cc], M[piv, cc] = M[piv, cc], M[col, cc]
            x[col], x[piv] = x[piv], x[col]
        inv = 1.0 / M[col, col]
        for rr in range(col + 1, size):
            f = M[rr, col] * inv
            if f != 0.0:
                for cc in range(col + 1, size):
                    M[rr, cc] -= f * M[col, cc]
                x[rr] -= f * x[col]
    return ok


def _back_substitute(M, x, size):
    """Solve the upper triangle ``M[:size, :size]`` for ``x[:size]`` in place."""
    for col in range(size - 1, -1, -1):
        acc = x[col]
        for cc in range(col + 1, size):
            acc -= M[col, cc] * x[cc]
        x[col] = acc / M[col, col]


def _general(groups, gi, width, rows, J, M, x, mu):
    """A group of any shape by Gaussian elimination (its right-hand side in ``x``); False where singular."""
    big = _group_matrix(groups, gi, width, rows, J, M)
    size = 3 * groups[gi, 0]
    ok = _eliminate(M, x, size, big)
    if ok:
        _back_substitute(M, x, size)
        for j in range(groups[gi, 1 + width]):
            mu[groups[gi, 2 + width + j]] = x[j]
    return ok


def _group(groups, gi, width, known0, rows, sh, J, Q, M, x, mu):
    """The reactions ``mu`` of group ``gi``'s rows from its links' loads and the reactions already known;
    False where its system is singular."""
    _rhs(groups, gi, width, known0, rows, J, Q, mu, x)
    if sh[0] == SINGLE:
        return _single(J, rows, sh, groups[gi, 1], x, mu)
    if sh[0] == DYAD:
        return _dyad(J, rows, sh, groups[gi, 1], groups[gi, 2], x, mu)
    return _general(groups, gi, width, rows, J, M, x, mu)


def _frame_loads(rows, on_frame, J, Q, mu, frame, var, i):
    """The foundation loads at sample ``(var, i)``: the frame's own loads and the pairs' force on it."""
    for d in range(3):
        total = Q[0, d]  # the frame's weight and the external loads on it
        for kk in range(on_frame.shape[0]):
            r = on_frame[kk]
            if r < 0:
                break
            if rows[r, 1] == 0:
                total += J[r, d] * mu[r]
            if rows[r, 2] == 0:
                total += J[r, 3 + d] * mu[r]
        frame[var, i, d] = total


def _kernel(
    rows,
    groups,
    shape_of,
    on_frame,
    q,
    v,
    a,
    local,
    origin,
    axis,
    mass,
    com,
    inertia,
    gx,
    gy,
    f_link,
    f_val,
    f_pos,
    m_link,
    m_val,
    lam,
    frame,
    lo,
    hi,
    Q,
    J,
    M,
    x,
    mu,
    G,
):
    """The reactions ``lam`` and foundation loads ``frame`` of the samples ``lo:hi`` of every variant: at each,
    the links' loads, the rows' Jacobian, then the groups in turn (NaN from a singular group on)."""
    n_rows = rows.shape[0]
    width = (groups.shape[1] - 2 - n_rows - 1) // 4
    known0 = 2 + 4 * width
    for var in range(lam.shape[0]):
        _row_geometry(rows, local, origin, axis, var, G)
        for n in range(q.shape[0]):
            Q[n, 5] = math.nan
        for i in range(lo, hi):
            _link_loads(q, v, a, mass, com, inertia, gx, gy, var, i, Q)
            _external_loads(q, f_link, f_val, f_pos, m_link, m_val, var, i, Q)
            _rows_at(rows, q, G, var, i, J, Q)
            bad = False
            for gi in range(groups.shape[0]):
                if bad or not _group(groups, gi, width, known0, rows, shape_of[gi], J, Q, M, x, mu):
                    for j in range(groups[gi, 1 + width]):
                        mu[groups[gi, 2 + width + j]] = math.nan
                    bad = True
            for r in range(n_rows):
                lam[var, i, r] = mu[r]
            _frame_loads(rows, on_frame, J, Q, mu, frame, var, i)


#: The kernels inlined into the others, and the one called from Python.
_INLINE = (
    "_row_geometry",
    "_rows_at",
    "_col",
    "_cross",
    "_single",
    "_pair_on",
    "_dyad",
    "_rhs",
    "_link_loads",
    "_external_loads",
    "_group_matrix",
    "_eliminate",
    "_back_substitute",
    "_general",
    "_group",
    "_frame_loads",
)
_CALLED = ("_kernel",)


@functools.cache
def compiled() -> bool:
    """Wrap the kernels of this module with numba's ``njit`` (once, as
    :func:`linkwork.motion.kernels_numba.compiled`)."""
    return jit.jit_in_place(globals(), _INLINE, _CALLED)
