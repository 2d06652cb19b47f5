"""The closed-form solve program compiled to machine code (with numba, when installed).

The same mathematics as :mod:`linkwork.motion.kernels`, one sample at a
time: for each design variant and drive value the steps of the program run
in order on a small scratch block of link states, and the results go
straight into the link-major output arrays.  No temporaries the size of the
batch are made, which is what makes NumPy slow on long batches.

Used for programs made of closed-form steps only (cranks, slides and the
class II dyads); the NumPy kernels remain the reference and handle the
rest: Newton groups, samples near change points (where the assembly mode is
chosen by continuation) and explicit branch overrides.  When they run
(``LINKWORK_NUMBA``, the cache, the compile in the background) is
:mod:`linkwork.jit`'s to say: :func:`wanted` for a batch, :func:`available`
for the pieces that follow a solve.
"""

from __future__ import annotations

import functools
import math
from typing import Any

import numpy as np

from linkwork import jit
from linkwork.motion import groups
from linkwork.motion.compiled_program import (  # noqa: F401 - read here by the callers of the compiled kernels
    F_INVALID,
    F_LIMIT,
    F_NEAR,
    F_SINGULAR,
    F_TROUBLE,
    STATE,
    Program,
    Solved,
    encode,
    floats,
    run_program,
    supports,
)
from linkwork.motion.groups import CRANK, DYAD, RPR, SLIDE
from linkwork.motion.kernels import CLOSE, POSITION, ROUNDING, SINGULAR, VELOCITY
from linkwork.motion.program_table import (
    ARM,
    ARM_CARRIER,
    ARM_IS_SLIDER,
    ARM_KIND,
    ARM_LINK,
    ARM_OWN,
    ARM_PAIR,
    ARM_SLIDER_POINT,
    ARM_SRC,
    ARM_SRC_LINK,
    ARMS,
    CRANK_BASE,
    CRANK_DRIVE,
    CRANK_LINK,
    CRANK_OWN,
    CRANK_SIGN,
    CRANK_SRC,
    DYAD_XA,
    DYAD_XB,
    KIND,
    RPR_INNER,
    SLIDE_DRIVE,
    SLIDE_GUIDE,
    SLIDE_LINK,
    SLIDE_PAIR,
    SLIDE_POINT,
)
from linkwork.structure.model import Mechanism
from linkwork.structure.parameters import Geometry

# Columns of a link's state in the scratch block of a sample: pose, velocity, acceleration, cos and
# sin of its angle
S_X, S_Y, S_ANGLE, S_VX, S_VY, S_OMEGA, S_AX, S_AY, S_EPS, S_COS, S_SIN = range(STATE)
# Columns of the constants of an R arm of a dyad: the radius of X about the outer joint, and the
# local vector from the joint to X over the radius squared
PRE_R, PRE_UX, PRE_UY = range(3)
# Columns of what a dyad left at the sample before: X, the vector to X of its other mode, the determinant
PREV_X, PREV_Y, PREV_GX, PREV_GY, PREV_DET = range(5)


def available() -> bool:
    """Whether the compiled kernels are in use in this process (:func:`linkwork.jit.active`; they are wrapped
    with numba's ``njit`` now, if they were not)."""
    return jit.active() and compiled()


def wanted(samples: int) -> bool:
    """Whether a batch of ``samples`` samples (variants times angles) is solved by the compiled kernels
    (:func:`linkwork.jit.use`: loaded where they pay)."""
    return jit.use(samples) and compiled()


def run(mech: Mechanism, geom: Geometry, values: np.ndarray, rates: np.ndarray, accels: np.ndarray) -> Solved:
    """Solve every sample with the compiled kernel (:func:`linkwork.motion.compiled_program.run_program`).

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
    kernel: Any = _kernel  # the compiled kernel, which compiled() put in the Python function's place
    return run_program(kernel, mech, geom, values, rates, accels)


def scan(values: np.ndarray) -> tuple[bool, float, float]:
    """Whether every entry of the drive coordinates ``values`` (A, D) is finite, and the least and the most
    step of the first drive from one sample to the next (inf and -inf for one sample), in one pass."""
    scanned: Any = _scan  # compiled (by compiled()) for C-ordered arrays of floats: others as such first
    finite, least, most = scanned(floats(values))
    return bool(finite), float(least), float(most)


def _scan(values):
    """:func:`scan` of C-ordered floats."""
    finite = True
    for i in range(values.shape[0]):
        for d in range(values.shape[1]):
            finite = finite and math.isfinite(values[i, d])
    least, most = math.inf, -math.inf
    for i in range(1, values.shape[0]):
        step = values[i, 0] - values[i - 1, 0]
        least, most = min(least, step), max(most, step)
    return finite, least, most


def point_motion_into(kind, q, v, a, cos, sin, lx, ly, out):
    """The twin of :func:`linkwork.motion.kernels.point_motion`: the position, velocity or acceleration
    (``kind``) of a point at ``(lx, ly)`` ``(V,)`` in the frame of a link of pose, velocity and acceleration
    ``q``, ``v``, ``a`` ``(3, V, A)`` and angle's cosine and sine ``cos``, ``sin`` ``(V, A)``, written into
    ``out`` ``(V, A, 2)``."""
    for var in range(out.shape[0]):
        for i in range(out.shape[1]):
            c, s = cos[var, i], sin[var, i]
            rx, ry = c * lx[var] - s * ly[var], s * lx[var] + c * ly[var]
            if kind == POSITION:
                out[var, i, 0] = q[0, var, i] + rx
                out[var, i, 1] = q[1, var, i] + ry
            elif kind == VELOCITY:
                w = v[2, var, i]
                out[var, i, 0] = v[0, var, i] - w * ry
                out[var, i, 1] = v[1, var, i] + w * rx
            else:
                w, e = v[2, var, i], a[2, var, i]
                out[var, i, 0] = a[0, var, i] - e * ry - w * w * rx
                out[var, i, 1] = a[1, var, i] + e * rx - w * w * ry


# ---------------------------------------------------------------------------------------------
# scalar kernels; a link's state in the scratch block L[i] is its columns S_X ... S_SIN


def _point(L, link, lx, ly):
    c, s = L[link, S_COS], L[link, S_SIN]
    rx, ry = c * lx - s * ly, s * lx + c * ly
    w, e = L[link, S_OMEGA], L[link, S_EPS]
    return (
        L[link, S_X] + rx,
        L[link, S_Y] + ry,
        L[link, S_VX] - w * ry,
        L[link, S_VY] + w * rx,
        L[link, S_AX] - e * ry - w * w * rx,
        L[link, S_AY] + e * rx - w * w * ry,
    )


def _material(L, link, x, y):
    rx, ry = x - L[link, S_X], y - L[link, S_Y]
    w, e = L[link, S_OMEGA], L[link, S_EPS]
    return (
        L[link, S_VX] - w * ry,
        L[link, S_VY] + w * rx,
        L[link, S_AX] - e * ry - w * w * rx,
        L[link, S_AY] + e * rx - w * w * ry,
    )


def _place(L, link, theta, omega, eps, x, y, vx, vy, ax, ay, lx, ly, c, s):
    rx, ry = c * lx - s * ly, s * lx + c * ly
    w2 = omega * omega
    L[link, S_X], L[link, S_Y], L[link, S_ANGLE] = x - rx, y - ry, theta
    L[link, S_VX], L[link, S_VY], L[link, S_OMEGA] = vx + omega * ry, vy - omega * rx, omega
    L[link, S_AX], L[link, S_AY], L[link, S_EPS] = ax + eps * ry + w2 * rx, ay - eps * rx + w2 * ry, eps
    L[link, S_COS], L[link, S_SIN] = c, s


def _place_like(L, link, guide, x, y, vx, vy, ax, ay, lx, ly):
    _place(
        L,
        link,
        L[guide, S_ANGLE],
        L[guide, S_OMEGA],
        L[guide, S_EPS],
        x,
        y,
        vx,
        vy,
        ax,
        ay,
        lx,
        ly,
        L[guide, S_COS],
        L[guide, S_SIN],
    )


def _loc(local, p):
    if p < 0:
        return 0.0, 0.0
    return local[p, 0], local[p, 1]


def _src_point(L, ops, st, o, local):
    """Position, velocity and acceleration of the outer joint of the R arm at ``ops[st, o:]``."""
    src = ops[st, o + ARM_SRC]
    return _point(L, ops[st, o + ARM_SRC_LINK], local[src, 0], local[src, 1])


def _locus(L, ops, st, o, pre, local, origin, axis, xlx, xly):
    """The locus of X of the arm at ``ops[st, o:]``: (px, py, vpx, vpy, apx, apy, r, c0, s0) for an
    R arm (circle about p, the local vector from the joint to X over r^2), (l0x, l0y, ux, uy, 0...) for P."""
    if ops[st, o + ARM_KIND] == 0:
        px, py, vpx, vpy, apx, apy = _src_point(L, ops, st, o, local)
        j = (o - ARMS) // ARM
        return px, py, vpx, vpy, apx, apy, pre[st, j, PRE_R], pre[st, j, PRE_UX], pre[st, j, PRE_UY]
    g, k = ops[st, o + ARM_CARRIER], ops[st, o + ARM_PAIR]
    c, s = L[g, S_COS], L[g, S_SIN]
    ux, uy = c * axis[k, 0] - s * axis[k, 1], s * axis[k, 0] + c * axis[k, 1]
    sp = ops[st, o + ARM_SLIDER_POINT]
    if ops[st, o + ARM_IS_SLIDER] == 1:  # the arm's link is the slider: the guide line of the carrier, shifted to X
        ox, oy = origin[k, 0], origin[k, 1]
        dx, dy = xlx - local[sp, 0], xly - local[sp, 1]
        bx, by = L[g, S_X] + c * ox - s * oy, L[g, S_Y] + s * ox + c * oy
    else:  # the arm's link is the guide: the line through the carrier's slider point
        bx, by = _point(L, g, local[sp, 0], local[sp, 1])[:2]
        dx, dy = xlx - origin[k, 0], xly - origin[k, 1]
    return bx + c * dx - s * dy, by + s * dx + c * dy, ux, uy, 0.0, 0.0, 0.0, 0.0, 0.0


def _touching(x):
    return 0.0 if -1e-12 < x < 0 else x


def _snap(h2, dh2, q_v, q_a, rounding):
    """The squared half gap between the two modes of a dyad near a change point, and whether it is
    the motion's (:func:`linkwork.motion.closure._root`)."""
    motion = dh2 * q_v * q_v / (2 * q_a)
    return (motion, True) if abs(h2 - motion) <= rounding else (h2, False)


def _arm_motion(L, ops, st, o, P, x, y):
    """Column of the arm's unknown rate in the velocity equation of X, and X's velocity and
    acceleration with that rate left out: about the joint (R), or of the carrier's point at X (P)."""
    if ops[st, o + ARM_KIND] == 0:
        return -(y - P[1]), x - P[0], P[2], P[3], P[4], P[5]
    vx, vy, ax, ay = _material(L, ops[st, o + ARM_CARRIER], x, y)
    return P[2], P[3], vx, vy, ax, ay


def _arm_extra(L, ops, st, o, P, x, y, k):
    """Acceleration terms of X quadratic in the rates: centripetal (R) or Coriolis (P)."""
    if ops[st, o + ARM_KIND] == 0:
        return -k * k * (x - P[0]), -k * k * (y - P[1])
    f = 2 * L[ops[st, o + ARM_CARRIER], S_OMEGA] * k
    return -f * P[3], f * P[2]


def _circles(A, B, branch):
    """X where the circles of two R arms (their loci ``A``, ``B``) meet in the mode ``branch``: (x, y,
    the vector to X of the other mode, slack, on a singular position to rounding)."""
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
    limit = False
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
        size = ra * ra + 2 * abs(t) * (abs(dist2 - k) / (2 * dist2) * (norms + dist) + (abs(k) + dist2) / (2 * dist))
        h2, snapped = _snap(h2, -t * (dist2 - k) / dist2, dist_v, dist_a, ROUNDING * size)
        rounding = 8 * ROUNDING * (ra + rb + norms)
        speed = math.sqrt(dvx * dvx + dvy * dvy)
        on = slack >= 0 and snapped and dist > rounding and abs(dist_v) <= rounding * speed / dist
        limit = limit or on  # on the change point to rounding
    h = branch * math.sqrt(max(h2, 0.0) if slack >= 0 else h2)
    return A[0] + t * ex - h * ey, A[1] + t * ey + h * ex, 2 * h * ey, -2 * h * ex, slack, limit


def _circle_line(L, ops, st, C, Ln, ol, branch):
    """X where the circle ``C`` of an R arm meets the line ``Ln`` of the P arm at ``ops[st, ol:]`` in the
    mode ``branch``: as :func:`_circles`."""
    wx, wy = C[0] - Ln[0], C[1] - Ln[1]
    nx, ny = -Ln[3], Ln[2]
    q = nx * wx + ny * wy  # signed distance of the circle's centre from the line
    r2 = C[6] * C[6]
    slack = _touching((r2 - q * q) / r2)
    disc = r2 - q * q
    limit = False
    if abs(disc) <= CLOSE * r2:  # near a change point: q over time, relative to the line's link
        g = ops[st, ol + ARM_CARRIER]
        vmx, vmy, amx, amy = _material(L, g, C[0], C[1])
        rx, ry = C[2] - vmx, C[3] - vmy
        f = 2 * L[g, S_OMEGA]
        cx, cy = (C[4] - amx) - f * -ry, (C[5] - amy) - f * rx
        size = C[6] + math.sqrt(C[0] * C[0] + C[1] * C[1]) + math.sqrt(Ln[0] * Ln[0] + Ln[1] * Ln[1])
        q_v = nx * rx + ny * ry
        disc, snapped = _snap(disc, -2 * q, q_v, nx * cx + ny * cy, ROUNDING * (C[6] * size))
        speeds = math.sqrt(C[2] * C[2] + C[3] * C[3]) + math.sqrt(vmx * vmx + vmy * vmy)
        limit = slack >= 0 and snapped and abs(q_v) <= 8 * ROUNDING * speeds  # on the change point
    root = branch * math.sqrt(max(disc, 0.0) if slack >= 0 else disc)
    t0 = wx * Ln[2] + wy * Ln[3]
    x, y = (Ln[0] + t0 * Ln[2]) + root * Ln[2], (Ln[1] + t0 * Ln[3]) + root * Ln[3]
    return x, y, -2 * root * Ln[2], -2 * root * Ln[3], slack, limit


def _dyad(L, ops, st, o1, o2, xa_i, xb_i, branch, pre, local, origin, axis):
    """A dyad through the loci of its arms at ``ops[st, o1:]`` and ``ops[st, o2:]``: places both links and
    returns (slack, normalised determinant, X, X of the other mode - X of this one, on a singular position
    to rounding)."""
    xax, xay = _loc(local, xa_i)
    xbx, xby = _loc(local, xb_i)
    A = _locus(L, ops, st, o1, pre, local, origin, axis, xax, xay)
    B = _locus(L, ops, st, o2, pre, local, origin, axis, xbx, xby)
    ka_r, kb_r = ops[st, o1 + ARM_KIND] == 0, ops[st, o2 + ARM_KIND] == 0
    if ka_r and kb_r:
        x, y, gx, gy, slack, limit = _circles(A, B, branch)
    elif not ka_r and not kb_r:
        den = A[2] * B[3] - A[3] * B[2]
        t = ((B[0] - A[0]) * B[3] - (B[1] - A[1]) * B[2]) / den
        x, y, gx, gy, slack, limit = A[0] + t * A[2], A[1] + t * A[3], 0.0, 0.0, abs(den), False
    else:
        C, Ln, ol = (A, B, o2) if ka_r else (B, A, o1)
        x, y, gx, gy, slack, limit = _circle_line(L, ops, st, C, Ln, ol, branch)
    if slack >= 0 and not (math.isfinite(x) and math.isfinite(y)):
        slack = -1.0
    det = _dyad_motion(L, ops, st, o1, o2, xa_i, xb_i, A, B, x, y, local)
    return slack, det, x, y, gx, gy, limit


def _dyad_motion(L, ops, st, o1, o2, xa_i, xb_i, A, B, x, y, local):
    """The rates of the arms of a dyad closed at X from the two vector equations of X, and both links
    placed; returns the normalised determinant of the equations."""
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
        link = ops[st, o + ARM_LINK]
        if ops[st, o + ARM_KIND] == 0:
            # X is on the circle of radius P[6] about P: its direction from P less the local one
            # (P[7], P[8]: the local one over the radius)
            gx_, gy_ = x - P[0], y - P[1]
            c, s = gx_ * P[7] + gy_ * P[8], gy_ * P[7] - gx_ * P[8]
            own = ops[st, o + ARM_OWN]
            _place(
                L, link, math.atan2(s, c), k, kd, P[0], P[1], P[2], P[3], P[4], P[5], local[own, 0], local[own, 1], c, s
            )
        else:
            lx, ly = _loc(local, xl)
            _place_like(L, link, ops[st, o + ARM_CARRIER], x, y, vx, vy, ax, ay, lx, ly)
    return d / math.sqrt((cax * cax + cay * cay) * (cbx * cbx + cby * cby))


def _rpr(L, ops, st, branch, local, origin, axis):
    k = ops[st, RPR_INNER]
    og, os_ = ARMS, ARMS + ARM
    pgx, pgy, vgx, vgy, agx, agy = _src_point(L, ops, st, og, local)
    psx, psy, vsx, vsy, asx, asy = _src_point(L, ops, st, os_, local)
    ulx, uly = axis[k, 0], axis[k, 1]
    nlx, nly = -uly, ulx
    sp, own_s, own_g = ops[st, os_ + ARM_SLIDER_POINT], ops[st, os_ + ARM_OWN], ops[st, og + ARM_OWN]
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
    lg, ls = ops[st, og + ARM_LINK], ops[st, os_ + ARM_LINK]
    _place(L, lg, theta, omega, eps, pgx, pgy, vgx, vgy, agx, agy, local[own_g, 0], local[own_g, 1], c, s)
    _place(L, ls, theta, omega, eps, psx, psy, vsx, vsy, asx, asy, local[own_s, 0], local[own_s, 1], c, s)
    return slack, d / math.sqrt(colx * colx + coly * coly)


def _crank(L, ops, st, local, values, rates, accels, i):
    """A crank at sample ``i``: it turns on its base by the drive angle."""
    link, base, src, own = ops[st, CRANK_LINK], ops[st, CRANK_BASE], ops[st, CRANK_SRC], ops[st, CRANK_OWN]
    sign, drv = ops[st, CRANK_SIGN], ops[st, CRANK_DRIVE]
    theta = L[base, S_ANGLE] + sign * values[i, drv]
    omega = L[base, S_OMEGA] + sign * rates[i, drv]
    eps = L[base, S_EPS] + sign * accels[i, drv]
    px, py, vx, vy, ax, ay = _point(L, base, local[src, 0], local[src, 1])
    c, s = math.cos(theta), math.sin(theta)
    _place(L, link, theta, omega, eps, px, py, vx, vy, ax, ay, local[own, 0], local[own, 1], c, s)


def _slide(L, ops, st, local, origin, axis, values, rates, accels, i):
    """A slide at sample ``i``: its slider moves along the guide by the drive coordinate."""
    link, g, k = ops[st, SLIDE_LINK], ops[st, SLIDE_GUIDE], ops[st, SLIDE_PAIR]
    sp, drv = ops[st, SLIDE_POINT], ops[st, SLIDE_DRIVE]
    c, s = L[g, S_COS], L[g, S_SIN]
    ox, oy = origin[k, 0], origin[k, 1]
    ux, uy = c * axis[k, 0] - s * axis[k, 1], s * axis[k, 0] + c * axis[k, 1]
    sv, ds, dds = values[i, drv], rates[i, drv], accels[i, drv]
    x, y = L[g, S_X] + c * ox - s * oy + sv * ux, L[g, S_Y] + s * ox + c * oy + sv * uy
    vmx, vmy, amx, amy = _material(L, g, x, y)
    f = 2 * L[g, S_OMEGA] * ds
    ax, ay = amx + dds * ux - f * uy, amy + dds * uy + f * ux
    _place_like(L, link, g, x, y, vmx + ds * ux, vmy + ds * uy, ax, ay, local[sp, 0], local[sp, 1])


def _step(L, ops, st, branch, pre, local, origin, axis, values, rates, accels, i):
    """One step at one sample: (slack, normalised determinant, X, gap vector, on a singular position to
    rounding) (the last three for dyads)."""
    kind = ops[st, KIND]
    if kind == CRANK:
        _crank(L, ops, st, local, values, rates, accels, i)
        return 1.0, 1.0, 0.0, 0.0, 0.0, 0.0, False
    if kind == SLIDE:
        _slide(L, ops, st, local, origin, axis, values, rates, accels, i)
        return 1.0, 1.0, 0.0, 0.0, 0.0, 0.0, False
    if kind == DYAD:
        xa, xb = ops[st, DYAD_XA], ops[st, DYAD_XB]
        return _dyad(L, ops, st, ARMS, ARMS + ARM, xa, xb, branch, pre, local, origin, axis)
    if kind == RPR:
        slack, det = _rpr(L, ops, st, branch, local, origin, axis)
        return slack, det, 0.0, 0.0, 0.0, 0.0, False
    return _rpp(L, ops, st, branch, pre, local, origin, axis)  # RPP, the last code


def _rpp(L, ops, st, branch, pre, local, origin, axis):
    """RPP: the pinned link keeps the guide's angle; then the other link as a dyad of two lines."""
    o = ARMS
    g = ops[st, ARMS + 2 * ARM + ARM_CARRIER]
    px, py, vx, vy, ax, ay = _src_point(L, ops, st, o, local)
    own = ops[st, o + ARM_OWN]
    _place_like(L, ops[st, o + ARM_LINK], g, px, py, vx, vy, ax, ay, local[own, 0], local[own, 1])
    return _dyad(L, ops, st, ARMS + ARM, ARMS + 2 * ARM, -1, -1, branch, pre, local, origin, axis)


def _arm_constants(ops, local, pre):
    """Radius of X about the outer joint of every R arm of a dyad (of one variant), and the local
    vector from the joint to X over the radius squared."""
    for st in range(ops.shape[0]):
        if ops[st, KIND] != DYAD:
            continue
        for j in range(2):
            o = ARMS + j * ARM
            if ops[st, o + ARM_KIND] != 0:
                continue
            xlx, xly = _loc(local, ops[st, DYAD_XA + j])
            own = ops[st, o + ARM_OWN]
            dx, dy = xlx - local[own, 0], xly - local[own, 1]
            r = math.sqrt(dx * dx + dy * dy)
            pre[st, j, PRE_R] = r
            pre[st, j, PRE_UX], pre[st, j, PRE_UY] = (dx / (r * r), dy / (r * r)) if r > 0 else (1.0, 0.0)


def _near(ops, st, prev, x, y, gx, gy, tol):
    """Whether a dyad's X at this sample or the one before comes within twice the step (in either mode)
    of its other mode."""
    dp2 = (x - prev[st, PREV_X]) ** 2 + (y - prev[st, PREV_Y]) ** 2
    dm2 = (x + gx - prev[st, PREV_X] - prev[st, PREV_GX]) ** 2 + (y + gy - prev[st, PREV_Y] - prev[st, PREV_GY]) ** 2
    m2 = max(dp2, dm2)
    if not (m2 == m2):
        m2 = dp2 if dp2 == dp2 else dm2
    g2_prev, g2 = prev[st, PREV_GX] ** 2 + prev[st, PREV_GY] ** 2, gx * gx + gy * gy
    # (2 sqrt(m2) + tol)^2 <= 8 m2 + 2 tol^2: both gaps beyond that (with room for rounding) are far
    bound = (8 * m2 + 2 * tol * tol) * (1 + 1e-9)
    if g2_prev > bound and g2 > bound:
        return False
    lim = (2 * math.sqrt(m2) + tol) ** 2
    return g2_prev <= lim or g2 <= lim


def _sample(
    ops,
    branch,
    pre,
    loc,
    org,
    axs,
    values,
    rates,
    accels,
    slack,
    det,
    near,
    trouble,
    limit,
    tol,
    L,
    prev,
    var,
    i,
    lo,
    first,
):
    """Every step at sample ``i`` of variant ``var`` into ``L``, with what the steps found (samples before
    ``lo`` only to carry on from); returns (every step assembled, some step within SINGULAR of a singular
    position)."""
    ok = True
    small = False
    for st in range(ops.shape[0]):
        s, d, x, y, gx, gy, jn = _step(L, ops, st, branch[st], pre, loc, org, axs, values, rates, accels, i)
        if jn and i >= lo:
            limit[st, var] = True
        ok = ok and s >= 0
        small = small or abs(d) < SINGULAR
        if ops[st, KIND] >= DYAD:  # cranks and slides always assemble: filled by _driving_rows
            if i >= lo:
                slack[st, var, i] = s
                det[st, var, i] = d
            if not (s >= 0 and abs(d) >= SINGULAR) or (i > first and (d < 0) != (prev[st, PREV_DET] < 0)):
                trouble[st, var] = True
            prev[st, PREV_DET] = d
        if ops[st, KIND] == DYAD and (ops[st, ARMS + ARM_KIND] == 0 or ops[st, ARMS + ARM + ARM_KIND] == 0):
            if i > first and _near(ops, st, prev, x, y, gx, gy, tol):
                near[st, var] = True
            prev[st, PREV_X], prev[st, PREV_Y], prev[st, PREV_GX], prev[st, PREV_GY] = x, y, gx, gy
    return ok, small


def _store(L, out, col):
    """The moving links' states at column ``col`` (a variant's sample) of ``out`` (the output block as
    rows (quantity, link, coordinate), then the cosines and the sines of the links' angles, :func:`run`);
    the frame's are filled by :func:`_driving_rows`."""
    n = L.shape[0]
    for link in range(1, n):
        for k in range(3):
            out[3 * link + k, col] = L[link, k]
            out[3 * (n + link) + k, col] = L[link, S_VX + k]
            out[3 * (2 * n + link) + k, col] = L[link, S_AX + k]
        out[9 * n + link, col] = L[link, S_COS]
        out[10 * n + link, col] = L[link, S_SIN]


def _driving_rows(ops, out, n_links, slack, det, var, lo, hi):
    """The frame at rest, its frame the global one, and the driving links assembled and regular,
    at the samples ``lo:hi`` of variant ``var``."""
    n_ang = slack.shape[2]
    for t in range(3):
        for k in range(3):
            for i in range(lo, hi):
                out[3 * n_links * t + k, var * n_ang + i] = 0.0
    for i in range(lo, hi):
        out[9 * n_links, var * n_ang + i] = 1.0
        out[10 * n_links, var * n_ang + i] = 0.0
    for st in range(ops.shape[0]):
        if ops[st, KIND] < DYAD:
            for i in range(lo, hi):
                slack[st, var, i] = 1.0
            for i in range(lo, hi):
                det[st, var, i] = 1.0


def _tolerance(local):
    """How close (m) a dyad's two modes may come at the same place: 1e-12 of 1 m plus the largest
    coordinate of a point of any variant (``local``: (V, 1, P, 2))."""
    most = 0.0
    for var in range(local.shape[0]):
        for p in range(local.shape[2]):
            most = max(most, abs(local[var, 0, p, 0]), abs(local[var, 0, p, 1]))
    return 1e-12 * (1 + most)


def _kernel(
    ops, branch, local, origin, axis, values, rates, accels, out, found, valid, marks, flags, lo, hi, L, pre, prev
):
    """Samples ``lo:hi`` of every variant (``near`` also from the step between ``lo - 1`` and ``lo``);
    sets ``flags`` (:data:`F_SINGULAR` ...) where something is found.

    ``out``: the output block (:func:`run`) as rows (quantity, link, coordinate), then the cosine and the
    sine of each link's angle, and columns (variant, sample); ``found``: slack and det; ``marks``: near,
    trouble and limit.  Scratch: ``L`` (N, STATE) the link states of a sample, ``pre`` (S, 2, 3) constants
    of the R arms of a variant, ``prev`` (S, 5) X of each dyad, the vector to X of its other mode and the
    determinant at the sample before.
    """
    slack, det, near, trouble, limit = found[0], found[1], marks[0], marks[1], marks[2]
    tol = _tolerance(local)
    n_ang = values.shape[0]
    for var in range(local.shape[0]):
        loc, org, axs = local[var, 0], origin[var, 0], axis[var, 0]
        _arm_constants(ops, loc, pre)
        first = max(lo - 1, 0)
        for i in range(first, hi):
            L[0, S_COS] = 1.0
            ok, small = _sample(
                ops,
                branch,
                pre,
                loc,
                org,
                axs,
                values,
                rates,
                accels,
                slack,
                det,
                near,
                trouble,
                limit,
                tol,
                L,
                prev,
                var,
                i,
                lo,
                first,
            )
            if i < lo:
                continue
            valid[var, i] = ok
            if not ok:
                flags[F_INVALID] = True
            elif small:
                flags[F_SINGULAR] = True
            _store(L, out, var * n_ang + i)
        _driving_rows(ops, out, L.shape[0], slack, det, var, lo, hi)
        for st in range(ops.shape[0]):
            if near[st, var]:
                flags[F_NEAR] = True
            if limit[st, var]:
                flags[F_LIMIT] = True
            if trouble[st, var]:
                flags[F_TROUBLE] = True


#: The kernels inlined into the others (the scalar kernel of each kind of group, :mod:`linkwork.motion.groups`,
#: among them), and those called from Python.
_INLINE = tuple(
    dict.fromkeys(
        """_point _material _place _place_like _loc _src_point _locus _touching _snap _arm_motion _arm_extra _circles
        _circle_line _dyad_motion _step _near _sample _store _driving_rows _tolerance""".split()
        + [kind.twin for kind in groups.KINDS.values() if kind.twin]
    )
)
_CALLED = ("_arm_constants", "_kernel", "_scan", "point_motion_into")


@functools.cache
def compiled() -> bool:
    """Wrap the kernels of this module with numba's ``njit`` (once; they are compiled on their first call, or
    loaded from numba's cache); False where numba cannot be imported."""
    return jit.jit_in_place(globals(), _INLINE, _CALLED)
