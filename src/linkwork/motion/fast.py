"""Compiled kernels for the common steps (a crank and the RRR, RRP and PRP dyads).

Used when numba is installed (``pip install 'linkwork[fast]'``); the NumPy
kernels of :mod:`linkwork.motion.kernels` are the reference and the
fallback, and the tests check that both give the same numbers.  Each kernel
makes one pass over the samples with no temporary arrays.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

try:  # numba is an optional extra
    from numba import njit, prange
except ImportError:  # pragma: no cover - exercised where numba is missing
    njit = None
    prange = range

AVAILABLE = njit is not None


def _compile(fn: Any, inline: bool = False) -> Any:
    if not AVAILABLE:
        return None
    return njit(cache=True, error_model="numpy", inline="always" if inline else "never")(fn)


def _crank(q, v, a, cos, sin, local, link, base, own, src, sign, phi, dphi, ddphi):  # pragma: no cover
    n_var, n_ang = q.shape[2], q.shape[3]
    for i in range(n_var):
        sx, sy = local[src, 0, i, 0], local[src, 1, i, 0]
        ox, oy = local[own, 0, i, 0], local[own, 1, i, 0]
        for j in range(n_ang):
            cb, sb = cos[base, i, j], sin[base, i, j]
            wb, eb = v[base, 2, i, j], a[base, 2, i, j]
            rx, ry = cb * sx - sb * sy, sb * sx + cb * sy
            px, py = q[base, 0, i, j] + rx, q[base, 1, i, j] + ry
            vx, vy = v[base, 0, i, j] - wb * ry, v[base, 1, i, j] + wb * rx
            ax = a[base, 0, i, j] - eb * ry - wb * wb * rx
            ay = a[base, 1, i, j] + eb * rx - wb * wb * ry
            th = q[base, 2, i, j] + sign * phi[j]
            w = wb + sign * dphi[j]
            e = eb + sign * ddphi[j]
            c, s = math.cos(th), math.sin(th)
            _place(q, v, a, cos, sin, link, i, j, th, w, e, c, s, px, py, vx, vy, ax, ay, ox, oy)


def _place(q, v, a, cos, sin, link, i, j, th, w, e, c, s, px, py, vx, vy, ax, ay, lx, ly):  # pragma: no cover
    rx, ry = c * lx - s * ly, s * lx + c * ly
    q[link, 0, i, j] = px - rx
    q[link, 1, i, j] = py - ry
    q[link, 2, i, j] = th
    v[link, 0, i, j] = vx + w * ry
    v[link, 1, i, j] = vy - w * rx
    v[link, 2, i, j] = w
    a[link, 0, i, j] = ax + e * ry + w * w * rx
    a[link, 1, i, j] = ay - e * rx + w * w * ry
    a[link, 2, i, j] = e
    cos[link, i, j] = c
    sin[link, i, j] = s


def _locus(q, v, a, cos, sin, local, origin, axis, arms, xpts, k, i, j):  # pragma: no cover
    """One arm's locus of X: (cx, cy, r, ux, uy, pvx, pvy, pax, pay, unused).

    For a turning arm (ux, uy) is the unit direction of X from the outer joint in the link's frame."""
    xp = xpts[k]
    xlx = local[xp, 0, i, 0] if xp >= 0 else 0.0
    xly = local[xp, 1, i, 0] if xp >= 0 else 0.0
    if arms[k, 0] == 0:
        sp, sl, own = arms[k, 2], arms[k, 3], arms[k, 4]
        cb, sb = cos[sl, i, j], sin[sl, i, j]
        lx, ly = local[sp, 0, i, 0], local[sp, 1, i, 0]
        rx, ry = cb * lx - sb * ly, sb * lx + cb * ly
        wb, eb = v[sl, 2, i, j], a[sl, 2, i, j]
        dx, dy = xlx - local[own, 0, i, 0], xly - local[own, 1, i, 0]
        r = math.sqrt(dx * dx + dy * dy)
        # the direction of X from the outer joint in the link's own frame, as (cos, sin) in (ux, uy)
        return (
            q[sl, 0, i, j] + rx,
            q[sl, 1, i, j] + ry,
            r,
            dx / r,
            dy / r,
            v[sl, 0, i, j] - wb * ry,
            v[sl, 1, i, j] + wb * rx,
            a[sl, 0, i, j] - eb * ry - wb * wb * rx,
            a[sl, 1, i, j] + eb * rx - wb * wb * ry,
            0.0,
        )
    pair, car, spt, own_is_slider = arms[k, 2], arms[k, 3], arms[k, 4], arms[k, 5]
    cc, sc = cos[car, i, j], sin[car, i, j]
    ux = cc * axis[pair, 0, i, 0] - sc * axis[pair, 1, i, 0]
    uy = sc * axis[pair, 0, i, 0] + cc * axis[pair, 1, i, 0]
    if own_is_slider:
        ox, oy = origin[pair, 0, i, 0], origin[pair, 1, i, 0]
        dx, dy = xlx - local[spt, 0, i, 0], xly - local[spt, 1, i, 0]
    else:
        ox, oy = local[spt, 0, i, 0], local[spt, 1, i, 0]
        dx, dy = xlx - origin[pair, 0, i, 0], xly - origin[pair, 1, i, 0]
    bx = q[car, 0, i, j] + cc * ox - sc * oy
    by = q[car, 1, i, j] + sc * ox + cc * oy
    return (bx + cc * dx - sc * dy, by + sc * dx + cc * dy, 0.0, ux, uy, 0.0, 0.0, 0.0, 0.0, 0.0)


def _base(q, v, a, arms, k, xx, xy, cx, cy, ux, uy, pvx, pvy, pax, pay, i, j):  # pragma: no cover
    """Column, velocity base and acceleration base of X along one arm."""
    if arms[k, 0] == 0:
        return -(xy - cy), xx - cx, pvx, pvy, pax, pay
    car = arms[k, 3]
    rx, ry = xx - q[car, 0, i, j], xy - q[car, 1, i, j]
    wc, ec = v[car, 2, i, j], a[car, 2, i, j]
    return (
        ux,
        uy,
        v[car, 0, i, j] - wc * ry,
        v[car, 1, i, j] + wc * rx,
        a[car, 0, i, j] - ec * ry - wc * wc * rx,
        a[car, 1, i, j] + ec * rx - wc * wc * ry,
    )


def _dyad(q, v, a, cos, sin, local, origin, axis, arms, xpts, branch, slack, det_out):  # pragma: no cover
    """arms: int array (2, 7): kind (0 R, 1 P), link, src point / pair, src link / carrier,
    own point / slider point, own_is_slider, unused; xpts: X's point index on each link (-1: origin)."""
    n_var, n_ang = q.shape[2], q.shape[3]
    k0, k1 = arms[0, 0], arms[1, 0]
    for i in range(n_var):
        for j in range(n_ang):
            c0x, c0y, r0, u0x, u0y, v0x, v0y, a0x, a0y, g0 = _locus(
                q, v, a, cos, sin, local, origin, axis, arms, xpts, 0, i, j
            )
            c1x, c1y, r1, u1x, u1y, v1x, v1y, a1x, a1y, g1 = _locus(
                q, v, a, cos, sin, local, origin, axis, arms, xpts, 1, i, j
            )
            sg = branch[i, j]
            if k0 == 0 and k1 == 0:
                dx, dy = c1x - c0x, c1y - c0y
                dist2 = dx * dx + dy * dy
                inv = 1.0 / math.sqrt(dist2)
                t = (r0 * r0 - r1 * r1 + dist2) * 0.5 * inv
                h2 = r0 * r0 - t * t
                rs2 = (r0 + r1) * (r0 + r1)
                sl_ = min(rs2 - dist2, dist2 - (r0 - r1) * (r0 - r1)) / rs2
                ex, ey = dx * inv, dy * inv
                h = sg * math.sqrt(h2) if h2 >= 0 else math.nan
                xx, xy = c0x + t * ex - h * ey, c0y + t * ey + h * ex
            elif k0 == 1 and k1 == 1:
                den = u0x * u1y - u0y * u1x
                t = ((c1x - c0x) * u1y - (c1y - c0y) * u1x) / den
                xx, xy = c0x + t * u0x, c0y + t * u0y
                sl_ = abs(den)
            else:
                if k0 == 0:
                    px, py, rr, lx0, ly0, lux, luy = c0x, c0y, r0, c1x, c1y, u1x, u1y
                else:
                    px, py, rr, lx0, ly0, lux, luy = c1x, c1y, r1, c0x, c0y, u0x, u0y
                wx, wy = px - lx0, py - ly0
                t0 = wx * lux + wy * luy
                hh = lux * wy - luy * wx
                disc = rr * rr - hh * hh
                sl_ = disc / (rr * rr)
                s = t0 + sg * math.sqrt(disc) if disc >= 0 else math.nan
                xx, xy = lx0 + s * lux, ly0 + s * luy
            slack[i, j] = sl_
            cax, cay, bvax, bvay, baax, baay = _base(
                q, v, a, arms, 0, xx, xy, c0x, c0y, u0x, u0y, v0x, v0y, a0x, a0y, i, j
            )
            cbx, cby, bvbx, bvby, babx, baby = _base(
                q, v, a, arms, 1, xx, xy, c1x, c1y, u1x, u1y, v1x, v1y, a1x, a1y, i, j
            )
            # ka ca - kb cb = base_b - base_a
            det = -(cax * cby - cay * cbx)
            rxv, ryv = bvbx - bvax, bvby - bvay
            ka = (-rxv * cby + ryv * cbx) / det
            kb = (cax * ryv - cay * rxv) / det
            if k0 == 0:
                eax, eay = -ka * ka * (xx - c0x), -ka * ka * (xy - c0y)
            else:
                wc = v[arms[0, 3], 2, i, j]
                eax, eay = -2 * wc * ka * u0y, 2 * wc * ka * u0x
            if k1 == 0:
                ebx, eby = -kb * kb * (xx - c1x), -kb * kb * (xy - c1y)
            else:
                wc = v[arms[1, 3], 2, i, j]
                ebx, eby = -2 * wc * kb * u1y, 2 * wc * kb * u1x
            rxa, rya = babx + ebx - baax - eax, baby + eby - baay - eay
            kad = (-rxa * cby + rya * cbx) / det
            kbd = (cax * rya - cay * rxa) / det
            det_out[i, j] = det / (math.sqrt(cax * cax + cay * cay) * math.sqrt(cbx * cbx + cby * cby))
            vxx, vxy = bvax + ka * cax, bvay + ka * cay
            axx, axy = baax + kad * cax + eax, baay + kad * cay + eay
            _put(
                q,
                v,
                a,
                cos,
                sin,
                local,
                arms,
                xpts,
                0,
                i,
                j,
                xx,
                xy,
                c0x,
                c0y,
                v0x,
                v0y,
                a0x,
                a0y,
                u0x,
                u0y,
                ka,
                kad,
                vxx,
                vxy,
                axx,
                axy,
            )
            _put(
                q,
                v,
                a,
                cos,
                sin,
                local,
                arms,
                xpts,
                1,
                i,
                j,
                xx,
                xy,
                c1x,
                c1y,
                v1x,
                v1y,
                a1x,
                a1y,
                u1x,
                u1y,
                kb,
                kbd,
                vxx,
                vxy,
                axx,
                axy,
            )


def _put(
    q,
    v,
    a,
    cos,
    sin,
    local,
    arms,
    xpts,
    k,
    i,
    j,
    xx,
    xy,
    cx,
    cy,
    pvx,
    pvy,
    pax,
    pay,
    lux,
    luy,
    kk,
    kd,
    vxx,
    vxy,
    axx,
    axy,
):  # pragma: no cover
    link = arms[k, 1]
    if arms[k, 0] == 0:
        own = arms[k, 4]
        dx, dy = xx - cx, xy - cy
        inv = 1.0 / math.sqrt(dx * dx + dy * dy)
        cg, sg = dx * inv, dy * inv
        c, s = cg * lux + sg * luy, sg * lux - cg * luy  # the link's angle: global direction less local
        _place(
            q,
            v,
            a,
            cos,
            sin,
            link,
            i,
            j,
            math.atan2(s, c),
            kk,
            kd,
            c,
            s,
            cx,
            cy,
            pvx,
            pvy,
            pax,
            pay,
            local[own, 0, i, 0],
            local[own, 1, i, 0],
        )
    else:
        car = arms[k, 3]
        xp = xpts[k]
        xlx = local[xp, 0, i, 0] if xp >= 0 else 0.0
        xly = local[xp, 1, i, 0] if xp >= 0 else 0.0
        _place(
            q,
            v,
            a,
            cos,
            sin,
            link,
            i,
            j,
            q[car, 2, i, j],
            v[car, 2, i, j],
            a[car, 2, i, j],
            cos[car, i, j],
            sin[car, i, j],
            xx,
            xy,
            vxx,
            vxy,
            axx,
            axy,
            xlx,
            xly,
        )


if AVAILABLE:
    _place = _compile(_place, inline=True)
    _locus = _compile(_locus, inline=True)
    _base = _compile(_base, inline=True)
    _put = _compile(_put, inline=True)
    crank_kernel = _compile(_crank)
    dyad_kernel = _compile(_dyad)
else:  # pragma: no cover
    crank_kernel = dyad_kernel = None


def arm_table(step: Any, point_link: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The integer description of a dyad's arms for :func:`dyad_kernel`."""
    rows = []
    for arm in step.arms:
        if arm.kind == "R":
            rows.append([0, arm.link, arm.src, int(point_link[arm.src]), arm.own, 0, 0])
        else:
            rows.append([1, arm.link, arm.pair, arm.carrier, arm.slider_point, int(arm.own_is_slider), 0])
    return np.array(rows, dtype=np.int64), np.array(step.x_local, dtype=np.int64)
