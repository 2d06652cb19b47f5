"""The closed-form solve program compiled to machine code (with numba, when installed).

The same mathematics as :mod:`linkwork.motion.kernels`, one sample at a
time: for each design variant and drive value the steps of the program run
in order on a small scratch block of link states, and the results go
straight into the link-major output arrays.  No temporaries the size of the
batch are made, which is what makes NumPy slow on long batches.

Used for programs made of closed-form steps only (cranks, slides and the
class II dyads); the NumPy kernels remain the reference and handle the
rest: Newton groups, samples near change points (where the assembly mode is
chosen by continuation) and explicit branch overrides.  ``available()``
says whether numba is there; ``LINKWORK_NUMBA=0`` in the environment turns
the compiled path off.
"""

from __future__ import annotations

import functools
import importlib.util
import math
import os
from concurrent.futures import ThreadPoolExecutor
from typing import Any

import numpy as np

from linkwork.motion.kernels import CLOSE, ROUNDING, SINGULAR
from linkwork.motion.program import Arm, Step

#: Step kinds of the compiled program.
CRANK, SLIDE, DYAD, RPR, RPP = range(5)
#: Fields of an arm in the encoded program.
ARM = 9
_CODES = {"crank": CRANK, "slide": SLIDE, "RRR": DYAD, "RRP": DYAD, "PRP": DYAD, "RPR": RPR, "RPP": RPP}


#: Threads a long batch is split over (the kernels release the GIL), and the least samples per thread.
THREADS = min(os.cpu_count() or 1, 8)
PER_THREAD = 5_000
_POOL: list[ThreadPoolExecutor] = []


def _pool() -> ThreadPoolExecutor:
    if not _POOL:
        _POOL.append(ThreadPoolExecutor(THREADS, thread_name_prefix="linkwork"))
    return _POOL[0]


#: Whether kinematics uses the compiled path: numba installed and not turned off (numba itself is imported,
#: and the kernels compiled or loaded from its cache, when they are first used: :func:`available`).
ENABLED = os.environ.get("LINKWORK_NUMBA", "1") != "0" and importlib.util.find_spec("numba") is not None


def available() -> bool:
    """Whether the compiled kernels run: numba there (imported now, if it was not) and not turned off."""
    return ENABLED and compiled()


def supports(program: tuple[Step, ...]) -> bool:
    """Whether every step has a compiled kernel."""
    return all(step.kind in _CODES for step in program)


def _arm(arm: Arm, point_link: np.ndarray) -> list[int]:
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


def encode(program: tuple[Step, ...], point_link: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The program as an integer table (one row a step) and the branch of each step."""
    ops = np.full((len(program), 3 + 3 * ARM), -1, dtype=np.int64)
    for s, step in enumerate(program):
        kind = _CODES[step.kind]
        ops[s, 0] = kind
        if kind == CRANK:
            arm = step.arms[0]
            sign = 1 if step.extra["b"] == arm.link else -1
            ops[s, 1:7] = [arm.link, int(point_link[arm.src]), arm.src, arm.own, sign, step.drive]
        elif kind == SLIDE:
            arm = step.arms[0]
            ops[s, 1:6] = [arm.link, arm.carrier, arm.pair, arm.slider_point, step.drive]
        else:
            if kind == DYAD:
                ops[s, 1:3] = step.x_local
            elif kind == RPR:
                ops[s, 1] = step.inner
            for j, arm in enumerate(step.arms):
                ops[s, 3 + j * ARM : 3 + (j + 1) * ARM] = _arm(arm, point_link)
    return ops, np.array([step.branch for step in program], dtype=float)


def run(mech: Any, geom: Any, values: np.ndarray, rates: np.ndarray, accels: np.ndarray) -> dict[str, Any]:
    """Solve every sample.

    Parameters
    ----------
    mech : Mechanism
        With a compiled program (``mech.fast_program``).
    geom : Geometry
        Dimensions of the design variants.
    values, rates, accels : (A, D)

    Returns arrays ``q, v, a`` (N, 3, V, A), ``slack, det`` (S, V, A),
    ``valid`` (V, A) (every step assembled), ``near`` (S, V) (True where a
    dyad's two assembly modes come within a step of each other: the NumPy
    path decides the mode there), ``trouble`` (S, V) (True where a step
    fails to assemble, comes within :data:`SINGULAR` of a singular position
    or its determinant changes sign: only there are events looked for),
    ``singular`` (whether any assembled sample has a normalised determinant
    below :data:`SINGULAR`) and ``limit`` (S, V) (True where a dyad lies
    on a singular position to rounding, its outer joints together or its
    modes meeting: the NumPy kernels give the velocities there).
    """
    ops, branch = mech.fast_program
    n_links = mech.n_links_total
    local, origin, axis = geom.point_local[:, 0], geom.pair_origin[:, 0], geom.pair_axis[:, 0]
    values, rates, accels = (np.ascontiguousarray(x, dtype=float) for x in (values, rates, accels))
    n_var, n_ang, n_steps = local.shape[0], values.shape[0], len(ops)
    out = np.empty((3, n_links, 3, n_var, n_ang))  # one block: q, v, a
    limit = np.zeros((n_steps, n_var), dtype=np.bool_)
    slack = np.empty((n_steps, n_var, n_ang))
    det = np.empty_like(slack)
    valid = np.empty((n_var, n_ang), dtype=np.bool_)
    near = np.zeros((n_steps, n_var), dtype=np.bool_)
    trouble = np.zeros((n_steps, n_var), dtype=np.bool_)
    singular = np.zeros(1, dtype=np.bool_)
    tol = 1e-12 * (1 + float(np.abs(local).max()))
    args: tuple[Any, ...] = (ops, branch, local, origin, axis, values, rates, accels, out, slack, det, valid)
    args += (near, trouble, singular, limit, tol)
    n_threads = min(THREADS, max(1, n_var * n_ang // PER_THREAD))
    bounds = np.linspace(0, n_ang, n_threads + 1).astype(int) if n_ang >= n_threads else np.array([0, n_ang])

    kernel: Any = _kernel  # the compiled kernel, which compiled() put in the Python function's place

    def part(lo: int, hi: int) -> None:
        kernel(*args, lo, hi, np.zeros((n_links, 11)), np.zeros((n_steps, 2, 3)), np.zeros((n_steps, 5)))

    if len(bounds) == 2:
        part(0, n_ang)
    else:  # the calling thread takes the first part
        rest = [_pool().submit(part, lo, hi) for lo, hi in zip(bounds[1:-1], bounds[2:], strict=True)]
        part(bounds[0], bounds[1])
        for job in rest:
            job.result()
    if n_ang < 3:  # too few samples to follow a change point: the mode of the assembly pose throughout
        near[:] = False
    return {
        "q": out[0],
        "v": out[1],
        "a": out[2],
        "slack": slack,
        "det": det,
        "valid": valid,
        "near": near,
        "trouble": trouble,
        "singular": bool(singular[0]),
        "limit": limit,
    }


# ---------------------------------------------------------------------------------------------
# scalar kernels; a link's state in the scratch block L[i] is
# x, y, theta, vx, vy, omega, ax, ay, epsilon, cos(theta), sin(theta)


def _point(L, link, lx, ly):
    c, s = L[link, 9], L[link, 10]
    rx, ry = c * lx - s * ly, s * lx + c * ly
    w, e = L[link, 5], L[link, 8]
    return (
        L[link, 0] + rx,
        L[link, 1] + ry,
        L[link, 3] - w * ry,
        L[link, 4] + w * rx,
        L[link, 6] - e * ry - w * w * rx,
        L[link, 7] + e * rx - w * w * ry,
    )


def _material(L, link, x, y):
    rx, ry = x - L[link, 0], y - L[link, 1]
    w, e = L[link, 5], L[link, 8]
    return L[link, 3] - w * ry, L[link, 4] + w * rx, L[link, 6] - e * ry - w * w * rx, L[link, 7] + e * rx - w * w * ry


def _place(L, link, theta, omega, eps, x, y, vx, vy, ax, ay, lx, ly, c, s):
    rx, ry = c * lx - s * ly, s * lx + c * ly
    w2 = omega * omega
    L[link, 0], L[link, 1], L[link, 2] = x - rx, y - ry, theta
    L[link, 3], L[link, 4], L[link, 5] = vx + omega * ry, vy - omega * rx, omega
    L[link, 6], L[link, 7], L[link, 8] = ax + eps * ry + w2 * rx, ay - eps * rx + w2 * ry, eps
    L[link, 9], L[link, 10] = c, s


def _place_like(L, link, guide, x, y, vx, vy, ax, ay, lx, ly):
    _place(L, link, L[guide, 2], L[guide, 5], L[guide, 8], x, y, vx, vy, ax, ay, lx, ly, L[guide, 9], L[guide, 10])


def _loc(local, p):
    if p < 0:
        return 0.0, 0.0
    return local[p, 0], local[p, 1]


def _locus(L, ops, st, o, pre, local, origin, axis, xlx, xly):
    """The locus of X of the arm at ``ops[st, o:]``: (px, py, vpx, vpy, apx, apy, r, c0, s0) for an
    R arm (circle about p, the local vector from the joint to X over r^2), (l0x, l0y, ux, uy, 0...) for P."""
    if ops[st, o] == 0:
        px, py, vpx, vpy, apx, apy = _point(L, ops[st, o + 5], local[ops[st, o + 4], 0], local[ops[st, o + 4], 1])
        j = (o - 3) // ARM
        return px, py, vpx, vpy, apx, apy, pre[st, j, 0], pre[st, j, 1], pre[st, j, 2]
    g, k = ops[st, o + 6], ops[st, o + 2]
    c, s = L[g, 9], L[g, 10]
    ux, uy = c * axis[k, 0] - s * axis[k, 1], s * axis[k, 0] + c * axis[k, 1]
    if ops[st, o + 7] == 1:  # the arm's link is the slider: the guide line of the carrier, shifted to X
        ox, oy = origin[k, 0], origin[k, 1]
        sp = ops[st, o + 8]
        dx, dy = xlx - local[sp, 0], xly - local[sp, 1]
        bx, by = L[g, 0] + c * ox - s * oy, L[g, 1] + s * ox + c * oy
    else:  # the arm's link is the guide: the line through the carrier's slider point
        sp = ops[st, o + 8]
        bx, by = _point(L, g, local[sp, 0], local[sp, 1])[:2]
        dx, dy = xlx - origin[k, 0], xly - origin[k, 1]
    return bx + c * dx - s * dy, by + s * dx + c * dy, ux, uy, 0.0, 0.0, 0.0, 0.0, 0.0


def _touching(x):
    return 0.0 if -1e-12 < x < 0 else x


def _snap(h2, dh2, q_v, q_a, rounding):
    """The squared half gap between the two modes of a dyad near a change point, and whether it is
    the motion's (:func:`linkwork.motion.kernels._root`)."""
    motion = dh2 * q_v * q_v / (2 * q_a)
    return (motion, True) if abs(h2 - motion) <= rounding else (h2, False)


def _arm_motion(L, ops, st, o, P, x, y):
    """Column of the arm's unknown rate in the velocity equation of X, and X's velocity and
    acceleration with that rate left out: about the joint (R), or of the carrier's point at X (P)."""
    if ops[st, o] == 0:
        return -(y - P[1]), x - P[0], P[2], P[3], P[4], P[5]
    vx, vy, ax, ay = _material(L, ops[st, o + 6], x, y)
    return P[2], P[3], vx, vy, ax, ay


def _arm_extra(L, ops, st, o, P, x, y, k):
    """Acceleration terms of X quadratic in the rates: centripetal (R) or Coriolis (P)."""
    if ops[st, o] == 0:
        return -k * k * (x - P[0]), -k * k * (y - P[1])
    f = 2 * L[ops[st, o + 6], 5] * k
    return -f * P[3], f * P[2]


def _dyad(L, ops, st, o1, o2, xa_i, xb_i, branch, pre, local, origin, axis):
    """A dyad through the loci of its arms at ``ops[st, o1:]`` and ``ops[st, o2:]``: places both links and
    returns (slack, normalised determinant, X, X of the other mode - X of this one)."""
    xax, xay = _loc(local, xa_i)
    xbx, xby = _loc(local, xb_i)
    A = _locus(L, ops, st, o1, pre, local, origin, axis, xax, xay)
    B = _locus(L, ops, st, o2, pre, local, origin, axis, xbx, xby)
    ka_r, kb_r = ops[st, o1] == 0, ops[st, o2] == 0
    gx = gy = 0.0
    limit = False
    if ka_r and kb_r:
        dx, dy = B[0] - A[0], B[1] - A[1]
        dvx, dvy, dax, day = B[2] - A[2], B[3] - A[3], B[4] - A[4], B[5] - A[5]
        dist2 = dx * dx + dy * dy
        dist = math.sqrt(dist2)
        inv = 1.0 / dist
        ra, rb = A[6], B[6]
        k = ra * ra - rb * rb
        t = (k + dist2) * (0.5 * inv) if dist > 0 else 0.0
        rsum2 = (ra + rb) * (ra + rb)
        slack = _touching(min(rsum2 - dist2, dist2 - (ra - rb) * (ra - rb)) / rsum2)
        ex, ey = dx * inv, dy * inv
        if dist <= CLOSE * (ra + rb):  # the outer joints (nearly) together: their direction from their motion
            speed2 = dvx * dvx + dvy * dvy
            tau = (dx * dvx + dy * dvy) / speed2
            wx, wy = dvx - 0.5 * tau * dax, dvy - 0.5 * tau * day
            sign = (-1.0 if tau < 0 else 1.0) / math.sqrt(wx * wx + wy * wy)
            rounding = (
                8 * ROUNDING * (ra + rb + math.sqrt(A[0] * A[0] + A[1] * A[1]) + math.sqrt(B[0] * B[0] + B[1] * B[1]))
            )
            miss = abs(dx * dvy - dy * dvx)
            through = miss <= (rounding + dist2 * math.sqrt(dax * dax + day * day) / speed2) * math.sqrt(speed2)
            if math.isfinite(sign):
                if through:
                    ex, ey = sign * wx, sign * wy
                limit = dist <= rounding  # together to rounding
        h2 = ra * ra - t * t
        if abs(h2) <= CLOSE * (ra * ra):  # near a change point: the motion about it
            dist_v = (dx * dvx + dy * dvy) / dist
            dist_a = ((dvx * dvx + dvy * dvy) + (dx * dax + dy * day) - dist_v * dist_v) / dist
            norms = math.sqrt(A[0] * A[0] + A[1] * A[1]) + math.sqrt(B[0] * B[0] + B[1] * B[1])
            size = ra * ra + 2 * abs(t) * (
                abs(dist2 - k) / (2 * dist2) * (norms + dist) + (abs(k) + dist2) / (2 * dist)
            )
            h2, snapped = _snap(h2, -t * (dist2 - k) / dist2, dist_v, dist_a, ROUNDING * size)
            rounding = 8 * ROUNDING * (ra + rb + norms)
            speed = math.sqrt(dvx * dvx + dvy * dvy)
            on = slack >= 0 and snapped and dist > rounding and abs(dist_v) <= rounding * speed / dist
            limit = limit or on  # on the change point to rounding
        h = branch * math.sqrt(max(h2, 0.0) if slack >= 0 else h2)
        x, y = A[0] + t * ex - h * ey, A[1] + t * ey + h * ex
        gx, gy = 2 * h * ey, -2 * h * ex
    elif not ka_r and not kb_r:
        den = A[2] * B[3] - A[3] * B[2]
        t = ((B[0] - A[0]) * B[3] - (B[1] - A[1]) * B[2]) / den
        x, y = A[0] + t * A[2], A[1] + t * A[3]
        slack = abs(den)
    else:
        C, Ln, ol = (A, B, o2) if ka_r else (B, A, o1)
        wx, wy = C[0] - Ln[0], C[1] - Ln[1]
        nx, ny = -Ln[3], Ln[2]
        q = nx * wx + ny * wy  # signed distance of the circle's centre from the line
        r2 = C[6] * C[6]
        slack = _touching((r2 - q * q) / r2)
        disc = r2 - q * q
        if abs(disc) <= CLOSE * r2:  # near a change point: q over time, relative to the line's link
            g = ops[st, ol + 6]
            vmx, vmy, amx, amy = _material(L, g, C[0], C[1])
            rx, ry = C[2] - vmx, C[3] - vmy
            f = 2 * L[g, 5]
            cx, cy = (C[4] - amx) - f * -ry, (C[5] - amy) - f * rx
            size = C[6] + math.sqrt(C[0] * C[0] + C[1] * C[1]) + math.sqrt(Ln[0] * Ln[0] + Ln[1] * Ln[1])
            q_v = nx * rx + ny * ry
            disc, snapped = _snap(disc, -2 * q, q_v, nx * cx + ny * cy, ROUNDING * (C[6] * size))
            speeds = math.sqrt(C[2] * C[2] + C[3] * C[3]) + math.sqrt(vmx * vmx + vmy * vmy)
            limit = slack >= 0 and snapped and abs(q_v) <= 8 * ROUNDING * speeds  # on the change point
        root = branch * math.sqrt(max(disc, 0.0) if slack >= 0 else disc)
        t0 = wx * Ln[2] + wy * Ln[3]
        x, y = (Ln[0] + t0 * Ln[2]) + root * Ln[2], (Ln[1] + t0 * Ln[3]) + root * Ln[3]
        gx, gy = -2 * root * Ln[2], -2 * root * Ln[3]
    if slack >= 0 and not (math.isfinite(x) and math.isfinite(y)):
        slack = -1.0
    # columns, base velocities and accelerations of X on each arm
    cax, cay, vax, vay, aax, aay = _arm_motion(L, ops, st, o1, A, x, y)
    cbx, cby, vbx, vby, abx, aby = _arm_motion(L, ops, st, o2, B, x, y)
    nbx, nby = -cbx, -cby
    d = cax * nby - cay * nbx
    inv = 1.0 / d
    rx, ry = vbx - vax, vby - vay
    ka, kb = (rx * nby - ry * nbx) * inv, (cax * ry - cay * rx) * inv
    eax, eay = _arm_extra(L, ops, st, o1, A, x, y, ka)
    ebx, eby = _arm_extra(L, ops, st, o2, B, x, y, kb)
    rx, ry = abx + ebx - aax - eax, aby + eby - aay - eay
    ka_d, kb_d = (rx * nby - ry * nbx) * inv, (cax * ry - cay * rx) * inv
    vx, vy = vax + ka * cax, vay + ka * cay
    ax, ay = aax + ka_d * cax + eax, aay + ka_d * cay + eay
    for j in range(2):
        o, P, k, kd, xl = (o1, A, ka, ka_d, xa_i) if j == 0 else (o2, B, kb, kb_d, xb_i)
        link = ops[st, o + 1]
        if ops[st, o] == 0:
            # X is on the circle of radius P[6] about P: its direction from P less the local one
            # (P[7], P[8]: the local one over the radius)
            gx_, gy_ = x - P[0], y - P[1]
            c, s = gx_ * P[7] + gy_ * P[8], gy_ * P[7] - gx_ * P[8]
            lx, ly = local[ops[st, o + 3], 0], local[ops[st, o + 3], 1]
            _place(L, link, math.atan2(s, c), k, kd, P[0], P[1], P[2], P[3], P[4], P[5], lx, ly, c, s)
        else:
            lx, ly = _loc(local, xl)
            _place_like(L, link, ops[st, o + 6], x, y, vx, vy, ax, ay, lx, ly)
    return slack, d / math.sqrt((cax * cax + cay * cay) * (cbx * cbx + cby * cby)), x, y, gx, gy, limit


def _rpr(L, ops, st, branch, local, origin, axis):
    k = ops[st, 1]
    og, os_ = 3, 3 + ARM
    pgx, pgy, vgx, vgy, agx, agy = _point(L, ops[st, og + 5], local[ops[st, og + 4], 0], local[ops[st, og + 4], 1])
    psx, psy, vsx, vsy, asx, asy = _point(L, ops[st, os_ + 5], local[ops[st, os_ + 4], 0], local[ops[st, os_ + 4], 1])
    ulx, uly = axis[k, 0], axis[k, 1]
    nlx, nly = -uly, ulx
    sp, own_s, own_g = ops[st, os_ + 8], ops[st, os_ + 3], ops[st, og + 3]
    wx = local[sp, 0] - local[own_s, 0] - (origin[k, 0] - local[own_g, 0])
    wy = local[sp, 1] - local[own_s, 1] - (origin[k, 1] - local[own_g, 1])
    e = nlx * wx + nly * wy
    dx, dy = psx - pgx, psy - pgy
    dist = math.sqrt(dx * dx + dy * dy)
    theta = math.atan2(dy, dx) - math.atan2(nly, nlx) + branch * math.acos(-e / dist)
    slack = 1 - (e / dist) ** 2
    c, s = math.cos(theta), math.sin(theta)
    ux, uy = c * ulx - s * uly, s * ulx + c * uly
    colx, coly = -(pgy - psy), pgx - psx
    nux, nuy = -ux, -uy
    d = colx * nuy - coly * nux
    rx, ry = vgx - vsx, vgy - vsy
    omega, sdot = (rx * nuy - ry * nux) / d, (colx * ry - coly * rx) / d
    rx = agx - asx + omega * omega * (pgx - psx) - 2 * omega * sdot * uy
    ry = agy - asy + omega * omega * (pgy - psy) + 2 * omega * sdot * ux
    eps = (rx * nuy - ry * nux) / d
    _place(L, ops[st, og + 1], theta, omega, eps, pgx, pgy, vgx, vgy, agx, agy, local[own_g, 0], local[own_g, 1], c, s)
    _place(L, ops[st, os_ + 1], theta, omega, eps, psx, psy, vsx, vsy, asx, asy, local[own_s, 0], local[own_s, 1], c, s)
    return slack, d / math.sqrt(colx * colx + coly * coly)


def _step(L, ops, st, branch, pre, local, origin, axis, values, rates, accels, i):
    """One step at one sample: (slack, normalised determinant, X, gap vector, on a singular position to
    rounding) (the last three for dyads)."""
    kind = ops[st, 0]
    if kind == CRANK:
        link, base, src, own, sign, drv = ops[st, 1], ops[st, 2], ops[st, 3], ops[st, 4], ops[st, 5], ops[st, 6]
        theta = L[base, 2] + sign * values[i, drv]
        omega = L[base, 5] + sign * rates[i, drv]
        eps = L[base, 8] + sign * accels[i, drv]
        px, py, vx, vy, ax, ay = _point(L, base, local[src, 0], local[src, 1])
        c, s = math.cos(theta), math.sin(theta)
        _place(L, link, theta, omega, eps, px, py, vx, vy, ax, ay, local[own, 0], local[own, 1], c, s)
        return 1.0, 1.0, 0.0, 0.0, 0.0, 0.0, False
    if kind == SLIDE:
        link, g, k, sp, drv = ops[st, 1], ops[st, 2], ops[st, 3], ops[st, 4], ops[st, 5]
        c, s = L[g, 9], L[g, 10]
        ox, oy = origin[k, 0], origin[k, 1]
        ux, uy = c * axis[k, 0] - s * axis[k, 1], s * axis[k, 0] + c * axis[k, 1]
        sv, ds, dds = values[i, drv], rates[i, drv], accels[i, drv]
        x, y = L[g, 0] + c * ox - s * oy + sv * ux, L[g, 1] + s * ox + c * oy + sv * uy
        vmx, vmy, amx, amy = _material(L, g, x, y)
        f = 2 * L[g, 5] * ds
        ax, ay = amx + dds * ux - f * uy, amy + dds * uy + f * ux
        _place_like(L, link, g, x, y, vmx + ds * ux, vmy + ds * uy, ax, ay, local[sp, 0], local[sp, 1])
        return 1.0, 1.0, 0.0, 0.0, 0.0, 0.0, False
    if kind == DYAD:
        return _dyad(L, ops, st, 3, 3 + ARM, ops[st, 1], ops[st, 2], branch, pre, local, origin, axis)
    if kind == RPR:
        slack, det = _rpr(L, ops, st, branch, local, origin, axis)
        return slack, det, 0.0, 0.0, 0.0, 0.0, False
    # RPP: the pinned link keeps the guide's angle; then the other link as a dyad of two lines
    o = 3
    g = ops[st, 3 + 2 * ARM + 6]
    px, py, vx, vy, ax, ay = _point(L, ops[st, o + 5], local[ops[st, o + 4], 0], local[ops[st, o + 4], 1])
    _place_like(L, ops[st, o + 1], g, px, py, vx, vy, ax, ay, local[ops[st, o + 3], 0], local[ops[st, o + 3], 1])
    return _dyad(L, ops, st, 3 + ARM, 3 + 2 * ARM, -1, -1, branch, pre, local, origin, axis)


def _arm_constants(ops, local, pre):
    """Radius of X about the outer joint of every R arm of a dyad (of one variant), and the local
    vector from the joint to X over the radius squared."""
    for st in range(ops.shape[0]):
        if ops[st, 0] != DYAD:
            continue
        for j in range(2):
            o = 3 + j * ARM
            if ops[st, o] != 0:
                continue
            xlx, xly = _loc(local, ops[st, 1 + j])
            dx, dy = xlx - local[ops[st, o + 3], 0], xly - local[ops[st, o + 3], 1]
            r = math.sqrt(dx * dx + dy * dy)
            pre[st, j, 0] = r
            pre[st, j, 1], pre[st, j, 2] = (dx / (r * r), dy / (r * r)) if r > 0 else (1.0, 0.0)


def _kernel(
    ops,
    branch,
    local,
    origin,
    axis,
    values,
    rates,
    accels,
    out,
    slack,
    det,
    valid,
    near,
    trouble,
    singular,
    limit,
    tol,
    lo,
    hi,
    L,
    pre,
    prev,
):
    """Samples ``lo:hi`` of every variant (``near`` also from the step between ``lo - 1`` and ``lo``).

    Scratch: ``L`` (N, 11) the link states of a sample, ``pre`` (S, 2, 3) constants of the R arms
    of a variant, ``prev`` (S, 5) X of each dyad, the vector to X of its other mode and the determinant
    at the sample before.
    """
    n_links, n_var = out.shape[1], out.shape[3]
    n_steps = ops.shape[0]
    for var in range(n_var):
        loc, org, axs = local[var], origin[var], axis[var]
        _arm_constants(ops, loc, pre)
        first = max(lo - 1, 0)
        for i in range(first, hi):
            L[0, 9] = 1.0
            ok = True
            small = False
            for st in range(n_steps):
                s, d, x, y, gx, gy, jn = _step(L, ops, st, branch[st], pre, loc, org, axs, values, rates, accels, i)
                if jn and i >= lo:
                    limit[st, var] = True
                ok = ok and s >= 0
                small = small or abs(d) < SINGULAR
                if ops[st, 0] >= DYAD:  # cranks and slides always assemble: filled below
                    if i >= lo:
                        slack[st, var, i] = s
                        det[st, var, i] = d
                    if not (s >= 0 and abs(d) >= SINGULAR) or (i > first and (d < 0) != (prev[st, 4] < 0)):
                        trouble[st, var] = True
                    prev[st, 4] = d
                if ops[st, 0] == DYAD and (ops[st, 3] == 0 or ops[st, 3 + ARM] == 0):
                    if i > first:
                        # does either sample come within twice the step (in either mode) of the other mode?
                        dp2 = (x - prev[st, 0]) ** 2 + (y - prev[st, 1]) ** 2
                        dm2 = (x + gx - prev[st, 0] - prev[st, 2]) ** 2 + (y + gy - prev[st, 1] - prev[st, 3]) ** 2
                        m2 = max(dp2, dm2)
                        if not (m2 == m2):
                            m2 = dp2 if dp2 == dp2 else dm2
                        lim = (2 * math.sqrt(m2) + tol) ** 2
                        if prev[st, 2] ** 2 + prev[st, 3] ** 2 <= lim or gx * gx + gy * gy <= lim:
                            near[st, var] = True
                    prev[st, 0], prev[st, 1], prev[st, 2], prev[st, 3] = x, y, gx, gy
            if i < lo:
                continue
            valid[var, i] = ok
            if ok and small:
                singular[0] = True
            for link in range(1, n_links):  # the frame's rows (at rest) are filled below
                for k in range(3):
                    out[0, link, k, var, i] = L[link, k]
                    out[1, link, k, var, i] = L[link, 3 + k]
                    out[2, link, k, var, i] = L[link, 6 + k]
        for t in range(3):  # the frame, at rest, its frame the global one
            for k in range(3):
                for i in range(lo, hi):
                    out[t, 0, k, var, i] = 0.0
        for st in range(n_steps):
            if ops[st, 0] < DYAD:  # a driving link always assembles
                for i in range(lo, hi):
                    slack[st, var, i] = 1.0
                for i in range(lo, hi):
                    det[st, var, i] = 1.0


#: Options of every compiled kernel: no reference counting, the kernels allocate nothing.
OPTS: dict[str, Any] = {"cache": True, "error_model": "numpy", "nogil": True, "_nrt": False}

#: The kernels inlined into the others, and those called from Python.
_INLINE = ("_point", "_material", "_place", "_place_like", "_loc", "_locus", "_touching", "_snap",
           "_arm_motion", "_arm_extra", "_dyad", "_rpr", "_step")  # fmt: skip
_CALLED = ("_arm_constants", "_kernel")


@functools.cache
def compiled() -> bool:
    """Wrap the kernels of this module with numba's ``njit`` (once; they are compiled on their first call, or
    loaded from numba's cache); False where numba cannot be imported."""
    try:
        from numba import njit
    except ImportError:  # pragma: no cover
        return False
    space = globals()
    for name in _INLINE:
        space[name] = njit(inline="always", **OPTS)(space[name])
    for name in _CALLED:
        space[name] = njit(**OPTS)(space[name])
    return True
