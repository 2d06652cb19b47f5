"""Kernels of the solve program: positions, velocities and accelerations of one group.

Every kernel works on whole arrays ``(n_variants, n_angles)`` and writes the
state of its links into :class:`~linkwork.motion.state.State`.  The class II
dyads are solved in closed form: positions by intersecting the loci of the
point X where the dyad closes (a circle about an outer joint, or a line of a
guide), velocities and accelerations from the two vector equations of X,
one 2x2 linear system each (with the Coriolis terms of sliding pairs).
Samples where a group cannot be assembled come out as NaN.

:mod:`linkwork.motion.kernels_numba` is their twin in machine code (the package's docstring says how the
two are kept alike).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from typing import Any, NamedTuple

import numpy as np
from numpy.polynomial import polynomial as poly

from linkwork.angles import wrap
from linkwork.motion.state import (
    Flip,
    State,
    StepRecord,
    Vec,
    add,
    cross,
    dot,
    norm,
    perp,
    rot,
    scale,
    single_state,
    solve2,
    sub,
)
from linkwork.structure.model import Mechanism
from linkwork.structure.records import Arm, Step

#: The quantities of a point :func:`point_motion_into` gives (:func:`linkwork.motion.points.point_motion`).
POSITION, VELOCITY, ACCELERATION = range(3)


def point_motion_into(
    kind: int,
    q: np.ndarray,
    v: np.ndarray,
    a: np.ndarray,
    cos: np.ndarray,
    sin: np.ndarray,
    lx: np.ndarray,
    ly: np.ndarray,
    out: np.ndarray,
) -> None:
    """The position, velocity or acceleration (``kind``: :data:`POSITION` ...) of a point at ``(lx, ly)``
    ``(V,)`` in the frame of a link of pose, velocity and acceleration ``q``, ``v``, ``a`` ``(3, V, A)`` and
    angle's cosine and sine ``cos``, ``sin`` ``(V, A)``, written into ``out`` ``(V, A, 2)``."""
    rx, ry = cos * lx[:, None] - sin * ly[:, None], sin * lx[:, None] + cos * ly[:, None]
    if kind == POSITION:
        out[..., 0], out[..., 1] = q[0] + rx, q[1] + ry
    elif kind == VELOCITY:
        out[..., 0], out[..., 1] = v[0] - v[2] * ry, v[1] + v[2] * rx
    else:
        w, e = v[2], a[2]
        out[..., 0], out[..., 1] = a[0] - e * ry - w * w * rx, a[1] + e * rx - w * w * ry


def _x_local(state: State, idx: int) -> Vec:
    if idx < 0:
        zero = np.zeros(state.local.shape[2:])
        return zero, zero
    return state.loc(idx)


class _Locus:
    """The locus of X given by one arm, with what its velocity equations need."""

    def __init__(self, state: State, arm: Arm, x_loc: Vec, point_link: np.ndarray):
        self.arm = arm
        if arm.kind == "R":
            self.p, self.vp, self.ap = state.point(int(point_link[arm.src]), arm.src)
            d = sub(x_loc, state.loc(arm.own))
            self.r = norm(d)
            self.local_angle = np.arctan2(d[1], d[0])
        else:
            c = arm.carrier
            cs = state.cos[c], state.sin[c]
            if arm.own_is_slider:
                origin, self.u = state.line(arm.pair, c)
                self.l0 = add(origin, rot(*cs, sub(x_loc, state.loc(arm.slider_point))))
            else:
                s = state.point(c, arm.slider_point)[0]
                self.u = rot(*cs, (state.axis[arm.pair, 0], state.axis[arm.pair, 1]))
                self.l0 = add(s, rot(*cs, sub(x_loc, (state.origin[arm.pair, 0], state.origin[arm.pair, 1]))))
            self.carrier = c

    def column(self, x: Vec) -> Vec:
        return perp(sub(x, self.p)) if self.arm.kind == "R" else self.u

    def base(self, state: State, x: Vec) -> tuple[Vec, Vec]:
        """Velocity and acceleration of X with the arm's unknown rate (and its square terms) left out."""
        if self.arm.kind == "R":
            return self.vp, self.ap
        return state.material(self.carrier, x)

    def accel_extra(self, state: State, x: Vec, k: np.ndarray) -> Vec:
        """Acceleration terms quadratic in the rates: centripetal (R) or Coriolis (P)."""
        if self.arm.kind == "R":
            return scale(-(k * k), sub(x, self.p))
        return scale(2 * state.v[self.carrier, 2] * k, perp(self.u))


#: Normalised Jacobian determinant below which a sample is a singular position.
SINGULAR = 1e-9
#: Nearness to a singular position of a dyad, relative to its size.  Outer joints this near each other
#: (a rhombus with its crank on the frame) have lost their direction from each other to rounding: it is
#: taken from their relative velocity and acceleration.  Between two samples the two assembly modes
#: trade places only where the motion comes this near a singular position.
CLOSE = 1e-6
#: Relative rounding of what a dyad is solved from (positions of its outer joints, squared half gap
#: between its modes), in units of its size and of the coordinates' magnitude (64 ulps).
ROUNDING = 64 * np.finfo(float).eps


class Singular(NamedTuple):
    """Where a dyad is singular: a quantity of the motion ``y`` (a tuple of components, ``(V, A)``
    each) with its first two time derivatives ``v`` and ``a``, reaching ``target`` (a component
    ``(V, 1)`` or scalar each; NaN: never) to within ``tol`` (``(V, 1)``).  A scalar reaches it at an
    extremum (the two modes meet there), and cannot assemble beyond it (``beyond``: +1 above, -1
    below); a vector (the relative position of outer joints) passes through it."""

    y: tuple[np.ndarray, ...]
    v: tuple[np.ndarray, ...]
    a: tuple[np.ndarray, ...]
    target: tuple[np.ndarray | float, ...]
    tol: np.ndarray
    beyond: float = 0.0


class Limit(NamedTuple):
    """The velocity of X where a dyad is on a singular position to rounding, which its velocity
    equations leave open: that of the motion through it, ``base + s * across`` in its mode s (+-1)."""

    on: np.ndarray  # (V, A) bool
    base: Vec
    across: Vec
    own: np.ndarray  # (V, A): s is the sample's branch times this where nonzero, else the mode just after it


class _OnLimit(NamedTuple):
    """Samples on one kind of singular position to rounding (``on``), and the velocity of X there: see
    :class:`Limit`."""

    on: np.ndarray
    base: Vec
    across: Vec
    own: np.ndarray | float


def _limit(*parts: _OnLimit) -> Limit | None:
    """One Limit from parts where samples are on them; None where none is."""
    parts = tuple(p for p in parts if np.any(p.on))
    if not parts:
        return None
    on = np.logical_or.reduce([p.on for p in parts])

    def pick(value: Callable[[_OnLimit], np.ndarray | float]) -> np.ndarray:
        out = np.zeros(on.shape)
        for p in parts:
            out = np.where(p.on, value(p), out)
        return out

    base = (pick(lambda p: p.base[0]), pick(lambda p: p.base[1]))
    return Limit(on, base, (pick(lambda p: p.across[0]), pick(lambda p: p.across[1])), pick(lambda p: p.own))


class Closure(NamedTuple):
    """Where the two loci of X meet: ``X = mid + branch * h * n`` in assembly mode ``branch`` (+-1)."""

    mid: Vec
    n: Vec
    h: np.ndarray  # NaN where the loci do not meet
    slack: np.ndarray  # the assembly margin, negative where the loci do not meet
    singular: tuple[Singular, ...] = ()  # where the two modes trade places
    limit: Limit | None = None  # the velocity of X on a singular position to rounding


def _closure(state: State, la: _Locus, lb: _Locus) -> Closure:
    """Where the loci of the two arms meet, in either assembly mode."""
    if la.arm.kind == "R" and lb.arm.kind == "R":
        return _circles(la, lb)
    if la.arm.kind == "P" and lb.arm.kind == "P":
        den = cross(la.u, lb.u)
        t = cross(sub(lb.l0, la.l0), lb.u) / den
        zero = np.zeros_like(den)
        return Closure(add(la.l0, scale(t, la.u)), (zero, zero), zero, np.abs(den))  # one mode
    circle, line = (la, lb) if la.arm.kind == "R" else (lb, la)
    w = sub(circle.p, line.l0)
    n = perp(line.u)
    q = dot(n, w)  # signed distance of the circle's centre from the line
    r2 = circle.r * circle.r
    slack = _touching((r2 - q * q) / r2)
    # q over time: the velocity and acceleration of the centre relative to the line's link
    v_line, a_line = state.material(line.carrier, circle.p)
    rel = sub(circle.vp, v_line)
    acc = sub(sub(circle.ap, a_line), scale(2 * state.v[line.carrier, 2], perp(rel)))
    size = circle.r * (circle.r + norm(circle.p) + norm(line.l0))
    q_v, q_a = dot(n, rel), dot(n, acc)
    h, snapped = _root(r2 - q * q, slack, -2 * q, q_v, q_a, ROUNDING * size, r2)
    tol = CLOSE * circle.r
    touch = tuple(Singular((q,), (q_v,), (q_a,), (sign * circle.r,), tol, sign) for sign in (1.0, -1.0))
    mid = add(line.l0, scale(dot(w, line.u), line.u))
    # on the change point to rounding: at the extremum of q to within the rounding of its rate
    on = (slack >= 0) & snapped & (np.abs(q_v) <= 8 * ROUNDING * (norm(circle.vp) + norm(v_line)))
    limit = None
    if np.any(on):  # on a change point: the middle moves with the line's link and the centre along it
        mid_v = add(state.material(line.carrier, mid)[0], scale(dot(rel, line.u), line.u))
        limit = _limit(_OnLimit(on, mid_v, scale(np.sqrt(np.maximum(-q * q_a, 0.0)), line.u), 0.0))
    return Closure(mid, line.u, h, slack, touch, limit)


def _circles(la: _Locus, lb: _Locus) -> Closure:
    """Two circles: X at ``a`` along the line of centres from la's and ``h`` across it."""
    d = sub(lb.p, la.p)
    dv, da = sub(lb.vp, la.vp), sub(lb.ap, la.ap)  # relative velocity and acceleration of the centres
    dist2 = dot(d, d)
    dist = np.sqrt(dist2)
    inv = 1.0 / dist
    k = la.r * la.r - lb.r * lb.r
    a = np.where(dist > 0, (k + dist2) * (0.5 * inv), 0.0)
    rsum2 = (la.r + lb.r) ** 2
    slack = _touching(np.minimum(rsum2 - dist2, dist2 - (la.r - lb.r) ** 2) / rsum2)
    e = scale(inv, d)
    close = dist <= CLOSE * (la.r + lb.r)
    rounding = 8 * ROUNDING * (la.r + lb.r + norm(la.p) + norm(lb.p))
    joined = np.zeros(dist.shape)
    if np.any(close):
        # d = tau (v - acc tau / 2) a time tau after the centres met: its direction from their motion,
        # where they do pass through each other (off their line of motion by no more than the rounding
        # and the curvature's share); centres that miss each other keep the direction they have
        speed2 = dot(dv, dv)
        tau = dot(d, dv) / speed2
        along = sub(dv, scale(0.5 * tau, da))
        side = np.where(tau < 0, -1.0, 1.0)
        sign = side / norm(along)
        through = np.abs(cross(d, dv)) <= (rounding + dist2 * norm(da) / speed2) * np.sqrt(speed2)
        turned = close & through & np.isfinite(sign)
        e = (np.where(turned, sign * along[0], e[0]), np.where(turned, sign * along[1], e[1]))
        joined = np.where((dist <= rounding) & np.isfinite(sign), side, 0.0)
    dist_v = dot(d, dv) / dist  # the distance of the centres over time
    dist_a = (dot(dv, dv) + dot(d, da) - dist_v * dist_v) / dist
    # rounding of h2 = ra^2 - a^2: that of the positions (of their magnitude) through a = (k + D^2) / 2 D
    size = la.r * la.r + 2 * np.abs(a) * (
        np.abs(dist2 - k) / (2 * dist2) * (norm(la.p) + norm(lb.p) + dist) + (np.abs(k) + dist2) / (2 * dist)
    )
    h, snapped = _root(la.r * la.r - a * a, slack, -a * (dist2 - k) / dist2, dist_v, dist_a, ROUNDING * size, la.r**2)
    # the modes trade places where the circles touch, or where their centres coincide (then the radii
    # are equal); followed are the relative position of the centres and its square, smooth functions
    tol = CLOSE * (la.r + lb.r)
    outer, inner = la.r + lb.r, np.abs(la.r - lb.r)
    square = ((dist2,), (2 * dot(d, dv),), (2 * (dot(dv, dv) + dot(d, da)),))
    singular = (
        Singular(d, dv, da, (0.0, 0.0), tol),
        Singular(*square, (outer * outer,), 2 * outer * tol, 1.0),
        Singular(*square, (np.where(inner > tol, inner * inner, np.nan),), 2 * inner * tol, -1.0),
    )
    # on the change point to rounding: at the extremum of the distance to within the rounding of its rate
    on = (slack >= 0) & snapped & (dist > rounding) & (np.abs(dist_v) <= rounding * norm(dv) / dist)
    limit = _limit(*_circles_limit(la, lb, e, a, h, on, joined, (dv, da), (dist, dist_v, dist_a)))
    return Closure(add(la.p, scale(a, e)), perp(e), h, slack, singular, limit)


def _circles_limit(
    la: _Locus,
    lb: _Locus,
    e: Vec,
    a: np.ndarray,
    h: np.ndarray,
    on: np.ndarray,
    joined: np.ndarray,
    rel: tuple[Vec, Vec],
    distance: tuple[np.ndarray, np.ndarray, np.ndarray],
) -> list[_OnLimit]:
    """Velocity of X where two circles are on a singular position to rounding (see :class:`Limit`).

    Centres together (equal radii): X = P_a + d / 2 + h n about it, n turning as the direction of d,
    whose limit is that of d' (turning at the part of d'' / 2 |d'| across it), and h' = 0 there; s is
    the sample's branch times the side of it.  Circles touching (the modes meet): the middle moves as
    P_a + a e, and h at the rate |h'| with h'^2 = (dh2/dq) q'' / 2 about the extremum of the distance q;
    s is the mode just after the sample.  ``on``: there; ``rel``: the velocity and acceleration of
    P_b - P_a; ``distance``: their distance and its first two time derivatives."""
    (dv, da), (dist, dist_v, dist_a) = rel, distance
    parts: list[_OnLimit] = []
    if np.any(joined):
        speed = norm(dv)
        turn = scale(cross(dv, da) / (2 * speed**3), perp(dv))  # d e / dt: da across e over 2 |dv|
        parts.append(_OnLimit(joined != 0, add(la.vp, scale(0.5, dv)), scale(h, perp(turn)), joined))
    k = la.r * la.r - lb.r * lb.r
    if np.any(on):
        e_v = scale(1.0 / dist, sub(dv, scale(dist_v, e)))
        mid_v = add(la.vp, add(scale((dist * dist - k) / (2 * dist * dist) * dist_v, e), scale(a, e_v)))
        h_v = np.sqrt(np.maximum(-a * (dist * dist - k) / (dist * dist) * dist_a / 2, 0.0))
        parts.append(_OnLimit(on, mid_v, scale(h_v, perp(e)), 0.0))
    return parts


def _root(
    h2: np.ndarray,
    slack: np.ndarray,
    dh2: np.ndarray,
    q_v: np.ndarray,
    q_a: np.ndarray,
    rounding: np.ndarray | float,
    r2: np.ndarray | float,
) -> tuple[np.ndarray, np.ndarray]:
    """The half gap h between the two modes from its square ``h2``, a function of a distance q, and
    where it is taken from the motion about a change point.

    Where the two modes meet the motion passes an extremum of q (a change point): there h2 = dh2 (q - q0)
    and q - q0 = q_v^2 / (2 q_a) about it (``dh2`` = dh2/dq, ``q_v``, ``q_a`` its first two time
    derivatives).  Where h2 is within CLOSE of r2 of zero and that to within its ``rounding``, the
    motion's value is taken: the square root of a rounded h2 would be off by the square root of the
    rounding, and differ between a mechanism and the same mechanism moved.
    """
    motion = dh2 * q_v * q_v / (2 * q_a)
    snapped = (np.abs(h2) <= CLOSE * r2) & (np.abs(h2 - motion) <= rounding)
    h2 = np.where(snapped, motion, h2)
    return np.sqrt(np.where(slack >= 0, np.maximum(h2, 0.0), h2)), snapped


def _at(closure: Closure, branch: np.ndarray | float) -> Vec:
    """X in the assembly mode ``branch``."""
    return add(closure.mid, scale(branch * closure.h, closure.n))


def _touching(slack: np.ndarray) -> np.ndarray:
    """Margins within rounding of zero are a touch (one point), not a miss."""
    return np.where((slack < 0) & (slack > -1e-12), 0.0, slack)


def dyad(
    step: Step,
    state: State,
    point_link: np.ndarray,
    arms: tuple[Arm, Arm] | None = None,
    branch: np.ndarray | None = None,
) -> None:
    """RRR, RRP and PRP dyads (X = the inner joint), and the second stage of RPP.

    ``branch`` (V, A) overrides the step's assembly mode sample by sample;
    without it the mode of the assembly pose is followed, switching at
    change points (where the two modes meet and the motion goes on
    smoothly in the other one).
    """
    arm_a, arm_b = arms or step.arms
    xa = _x_local(state, step.x_local[0])
    xb = _x_local(state, step.x_local[1])
    la, lb = _Locus(state, arm_a, xa, point_link), _Locus(state, arm_b, xb, point_link)
    closure = _closure(state, la, lb)
    flips: list[Flip] = []
    if branch is None:
        branch_used: np.ndarray | float = step.branch
        if "R" in (arm_a.kind, arm_b.kind):
            full = np.full(state.valid.shape, step.branch)
            flips = _change_points(state, closure, full)
            if flips:
                branch_used = full
    else:
        branch_used = branch
    x, slack = _at(closure, branch_used), closure.slack
    # no single point X although the loci "meet" (coincident circle centres, parallel guides): not assembled
    slack = np.where((slack >= 0) & ~(np.isfinite(x[0]) & np.isfinite(x[1])), -1.0, slack)
    (ka, kb), (ka_d, kb_d), vx, ax, det = _motion(state, la, lb, x)
    lim = closure.limit
    if lim is not None:  # on a singular position to rounding: the velocity of the motion through it
        s = np.where(lim.own != 0, branch_used * lim.own, _later_mode(state, branch_used))
        vx = tuple(np.where(lim.on, g, v) for g, v in zip(add(lim.base, scale(s, lim.across)), vx, strict=True))
        ka, kb = (
            np.where(lim.on, cross(sub(x, loc.p), sub(vx, loc.vp)) / dot(sub(x, loc.p), sub(x, loc.p)), k)
            if loc.arm.kind == "R"
            else k
            for loc, k in ((la, ka), (lb, kb))
        )
    for arm, loc, k, kd, xl in ((arm_a, la, ka, ka_d, xa), (arm_b, lb, kb, kb_d, xb)):
        if arm.kind == "R":
            d = sub(x, loc.p)
            dist = norm(d)
            # angle of the link: direction of X from the outer joint, less its local direction
            c0, s0 = np.cos(loc.local_angle), np.sin(loc.local_angle)
            cg, sg = d[0] / dist, d[1] / dist
            c, s = cg * c0 + sg * s0, sg * c0 - cg * s0
            theta = np.arctan2(s, c)
            state.place(arm.link, theta, k, kd, loc.p, loc.vp, loc.ap, state.loc(arm.own), (c, s))
        else:
            state.place_like(arm.link, arm.carrier, x, vx, ax, xl)
    used = branch_used if isinstance(branch_used, np.ndarray) else None
    _record(state, slack, det, used, flips, None if lim is None else lim.on)


def _later_mode(state: State, branch: np.ndarray | float) -> np.ndarray:
    """The assembly mode (+-1) of the motion just after each sample in time, read off a neighbour:
    its mode where it comes later, the other where it comes earlier (a singular position between)."""
    b = np.broadcast_to(branch, state.valid.shape)
    if b.shape[1] < 2 or state.rate is None:
        return b
    later = np.sign(np.diff(state.drive) * state.rate[:-1])  # +1 where the next sample comes later
    out = np.empty(b.shape)
    out[:, :-1] = b[:, 1:] * later
    out[:, -1] = -b[:, -2] * later[-1]
    return out


def _motion(state: State, la: _Locus, lb: _Locus, x: Vec) -> tuple[Any, ...]:
    """Velocity and acceleration of the dyad closed at ``x``, from the two vector equations of X: the
    rates of its arms (ka, kb) and their derivatives, X's velocity and acceleration, and the
    normalised determinant of the equations (zero at a singular position)."""
    ca, cb = la.column(x), lb.column(x)
    va, aa = la.base(state, x)
    vb, ab = lb.base(state, x)
    ncb = scale(-1.0, cb)
    ka, kb, det = solve2(ca, ncb, sub(vb, va))
    ea, eb = la.accel_extra(state, x, ka), lb.accel_extra(state, x, kb)
    ka_d, kb_d, _ = solve2(ca, ncb, sub(add(ab, eb), add(aa, ea)))
    vx = add(va, scale(ka, ca))
    ax = add(add(aa, scale(ka_d, ca)), ea)
    return (ka, kb), (ka_d, kb_d), vx, ax, det / (norm(ca) * norm(cb))


def _change_points(state: State, closure: Closure, branch: np.ndarray) -> list[Flip]:
    """Follow the motion through change points, along the angles in the order given.

    Where the two modes of a dyad cross (the isosceles slider-crank at 0 and
    180 deg, a parallelogram laid flat, a rhombus with its crank on the
    frame) the mode that keeps the velocities continuous has the other sign
    on the far side: from the sample nearest the assembly pose, forwards and
    then backwards, the mode changes between two samples that lie on either
    side of a crossing, and nowhere else (:func:`_crossings`), however fast X
    swings and whatever the samples (one on the crossing itself counts on
    the side its motion gives it).  Without the rate of a single drive, each
    sample where the modes nearly meet takes the mode whose X lies nearer
    the extrapolation from the two samples before it instead
    (:func:`_extrapolated`).  ``branch`` is changed in place.
    """
    x_p, x_m = _at(closure, branch), _at(closure, -branch)
    if branch.shape[1] < 3:
        return []
    gap = norm(sub(x_p, x_m))  # (V, A)
    near = _modes_near(state, x_p, x_m, gap)
    if not near.any():
        return []
    rate = state.rate
    if rate is not None and bool(np.all(np.isfinite(rate) & (rate != 0))):
        return _crossings(state, closure, branch, rate)
    return _extrapolated(state, np.stack(x_p, -1), np.stack(x_m, -1), near, gap, branch)


def _modes_near(state: State, x_p: Vec, x_m: Vec, gap: np.ndarray) -> np.ndarray:
    """Where the gap between the two modes' X is within twice the step X takes (in either mode) to or
    from a neighbouring sample: ``(V, A)``."""
    step = np.fmax(
        norm((np.diff(x_p[0], axis=1), np.diff(x_p[1], axis=1))),
        norm((np.diff(x_m[0], axis=1), np.diff(x_m[1], axis=1))),
    )  # (V, A - 1), either mode
    move = np.empty_like(gap)
    move[:, 0], move[:, -1] = step[:, 0], step[:, -1]
    np.fmax(step[:, :-1], step[:, 1:], out=move[:, 1:-1])
    with np.errstate(invalid="ignore"):
        near: np.ndarray = gap <= 2 * move + 1e-12 * (1 + float(np.abs(state.local).max()))
    return near


def _extrapolated(
    state: State, xp: np.ndarray, xm: np.ndarray, near: np.ndarray, gap: np.ndarray, branch: np.ndarray
) -> list[Flip]:
    """The mode of each sample where the modes nearly meet (``near``) whose X (``xp`` in the mode
    ``branch``, ``xm`` in the other, ``(V, A, 2)``) lies nearer the extrapolation from the two samples
    before it, walking from the sample nearest the assembly pose forwards and then backwards."""
    drive = state.drive
    n = branch.shape[1]
    flips = []
    start = state.start_index
    for v in np.unique(np.nonzero(near)[0]):
        flipped = np.zeros(n, dtype=bool)  # samples now in the mode opposite to the first solution

        def at(i: int, other: bool = False, v: int = v, flipped: np.ndarray = flipped) -> np.ndarray:
            return xm[v, i] if flipped[i] != other else xp[v, i]

        for direction in (1, -1):
            order = np.arange(start, n) if direction > 0 else np.arange(start, -1, -1)
            for k in range(2, len(order)):
                here = order[k]
                if not near[v, here]:
                    continue
                p1, p2 = order[k - 1], order[k - 2]
                span = drive[p1] - drive[p2]
                t = (drive[here] - drive[p1]) / span if span != 0 else 1.0
                guess = at(p1) + (at(p1) - at(p2)) * t
                tol = 1e-12 * (1 + np.abs(guess).max())
                if np.hypot(*(at(here, True) - guess)) < np.hypot(*(at(here) - guess)) - tol:
                    branch[v, order[k:]] *= -1
                    flipped[order[k:]] = ~flipped[order[k:]]
                    touch = int(order[k - 1] if gap[v, order[k - 1]] < gap[v, here] else here)
                    flips.append(Flip(int(v), int(here), touch))
    return flips


def _lead(test: Singular) -> np.ndarray:
    """Time from the extremum (scalar) or the meeting (vector) of a quantity, to first order: positive
    after it.  (V, A)"""
    if len(test.y) == 1:
        return test.v[0] / test.a[0]
    return sum(y * v for y, v in zip(test.y, test.v, strict=True)) / sum(v * v for v in test.v)


def _crossings(state: State, closure: Closure, branch: np.ndarray, rate: np.ndarray) -> list[Flip]:
    """The mode flips between consecutive samples on either side of a crossing of the two modes.

    Which side of a crossing a sample lies on is the sign of its time from the extremum of the
    quantity whose target is the singular position (the distance of the outer joints, of a circle's
    centre from a line), from its first two derivatives there (so also a sample on the crossing, to
    rounding, is on one side); whether the extremum reaches the target between the samples, or goes
    beyond it (where the dyad cannot assemble: then nothing is crossed), is :func:`_reach`.
    """
    drive = state.drive
    start = state.start_index
    later = np.sign(np.diff(drive) * rate[:-1])  # +1 where the next sample comes later
    with np.errstate(invalid="ignore", divide="ignore"):
        times = [_lead(t) for t in closure.singular]
    # the side of each sample (a time of zero counts as after, as the limit direction of joined joints)
    leads = [np.where(np.isfinite(t), np.where(t < 0, -1.0, 1.0), 0.0) for t in times]
    if not leads:
        return []
    # where a lead changes sign from one sample to the next (an extremum between, or on one of them)
    # within reach of its target from either end
    dt = np.abs(np.diff(drive) / rate[:-1])
    changes = np.logical_or.reduce(
        [(s[:, 1:] != s[:, :-1]) & _within_reach(t, dt) for s, t in zip(leads, closure.singular, strict=True)]
    )
    flips = []
    for v, i in np.argwhere(changes):
        prev, here = (i, i + 1) if i >= start else (i + 1, i)  # walked away from the assembly pose
        ahead = later[i] if here > prev else -later[i]  # +1: the walk goes forward in time
        crossed = [
            (_reach(test, drive, rate, v, prev, here), time)
            for test, lead, time in zip(closure.singular, leads, times, strict=True)
            if lead[v, prev] * ahead < 0 < lead[v, here] * ahead  # before at prev, after at here
            and not _flat_touch(test, v, prev, here)
        ]
        if not crossed or any(verdict < 0 for verdict, _ in crossed) or all(verdict == 0 for verdict, _ in crossed):
            continue  # nothing crossed, or a gap where the dyad cannot assemble
        branch[v, slice(here, None) if here > prev else slice(None, here + 1)] *= -1
        time = next(t for verdict, t in crossed if verdict > 0)
        flips.append(Flip(int(v), int(here), int(prev if abs(time[v, prev]) < abs(time[v, here]) else here)))
    return flips


#: :func:`_flat_touch`: the order ratio ``u u'' / u'^2`` above which a touch is flat (1/2 at a change point, 3/4 at a
#: flat touch).
FLAT = 5 / 8


def _flat_touch(test: Singular, v: int, i: int, j: int) -> bool:
    """Whether a scalar quantity touches its target between samples ``i`` and ``j`` at an extremum of higher order
    (its distance from the target ``u ~ tau^4`` about it, ``tau`` the time from it), where no mode is crossed.

    At a change point ``u ~ tau^2``: the half gap between the two modes, ``h ~ sqrt(u) ~ |tau|``, goes on as
    ``h ~ tau`` through it, the other mode.  Where the dyad's outer joints themselves come to rest there (a toggle
    press whose upper link ends its swing on the line of the guide: the rocker's dead point on the dyad's change
    point) ``u ~ tau^4``, ``h ~ tau^2`` keeps its sign, and the motion keeps its mode (and, where the extremum
    falls short of the target or passes it by a rounding, the modes do not meet or meet twice: the same mode after
    either way).  The order is read off the sample farther from the target, from ``u u'' / u'^2 = (m - 1) / m``
    for ``u ~ tau^m``: 1/2 or 3/4, told apart at :data:`FLAT`."""
    if len(test.y) != 1:
        return False
    target = test.target[0]
    goal = float(target[v, 0]) if isinstance(target, np.ndarray) and target.ndim else float(target)
    u = [goal - test.y[0][v, k] for k in (i, j)]
    k = (i, j)[int(abs(u[1]) > abs(u[0]))]
    rate, turn = test.v[0][v, k], test.a[0][v, k]
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        ratio = np.float64(-(goal - test.y[0][v, k]) * turn) / np.float64(rate * rate)
    return bool(np.isfinite(ratio) and ratio > FLAT)


def _within_reach(test: Singular, dt: np.ndarray) -> np.ndarray:
    """Whether a quantity can come within its tolerance of its target between consecutive samples
    ``dt`` apart (A - 1,), by twice the first two terms of its Taylor expansion from either end:
    (V, A - 1)."""
    with np.errstate(invalid="ignore"):
        off = np.sqrt(sum((y - t) ** 2 for y, t in zip(test.y, test.target, strict=True)))
        speed = np.sqrt(sum(v * v for v in test.v))
        turn = np.sqrt(sum(a * a for a in test.a))
        ends = [
            off[:, k] - 2 * (speed[:, k] * dt + turn[:, k] * dt * dt) - test.tol
            for k in (slice(None, -1), slice(1, None))
        ]
        return (ends[0] <= 0) | (ends[1] <= 0)


def _reach(test: Singular, drive: np.ndarray, rate: np.ndarray, v: int, i: int, j: int) -> int:
    """Whether a quantity reaches its singular position between samples ``i`` and ``j``: 1 if it
    does, -1 if it goes beyond (a scalar whose dyad cannot assemble there), 0 if not.

    The quantity is followed by the quintic through its values and first two time derivatives at
    both samples, within its tolerance widened by how far the quintic is from the cubic through the
    values and first derivatives (a bound on its own error).
    """
    dt = (drive[j] - drive[i]) / rate[i]
    target = np.array([c[v, 0] if isinstance(c, np.ndarray) and c.ndim else c for c in test.target], dtype=float)
    if np.isnan(target).any():
        return 0  # a position this dyad never takes
    y, vel, acc = (np.array([[c[v, i], c[v, j]] for c in x]) for x in (test.y, test.v, test.a))
    y0, y1 = y[:, 0] - target, y[:, 1] - target
    v0, v1 = vel[:, 0] * dt, vel[:, 1] * dt
    a0, a1 = acc[:, 0] * dt * dt, acc[:, 1] * dt * dt
    if not np.isfinite(np.concatenate([y0, y1, v0, v1, a0, a1])).all():
        return 0
    # on [0, 1]: y0 + v0 t + a0 t^2 / 2 + c3 t^3 + c4 t^4 + c5 t^5 with the values at 1
    big_a, big_b, big_c = y1 - y0 - v0 - a0 / 2, v1 - v0 - a0, a1 - a0
    quintic = np.stack(
        [y0, v0, a0 / 2, 10 * big_a - 4 * big_b + big_c / 2, -15 * big_a + 7 * big_b - big_c]
        + [6 * big_a - 3 * big_b + big_c / 2],
        -1,
    )
    cubic = np.stack([y0, v0, 3 * (y1 - y0) - 2 * v0 - v1, 2 * (y0 - y1) + v0 + v1, 0 * y0, 0 * y0], -1)
    grid = np.linspace(0.0, 1.0, 17)
    tol = (
        test.tol[v, 0] + np.sqrt(sum(poly.polyval(grid, q - c) ** 2 for q, c in zip(quintic, cubic, strict=True))).max()
    )
    if len(quintic) == 1:  # the extreme excursion towards (and beyond) the target
        path = quintic[0] * test.beyond
        slope = poly.polyder(path)
        t = poly.polyroots(slope).real if np.any(slope) else np.zeros(0)
        top = poly.polyval(np.concatenate([[0.0, 1.0], np.clip(t, 0.0, 1.0)]), path).max()
        return -1 if top > tol else (1 if top >= -tol else 0)
    square = np.zeros(1)
    for c in quintic:  # |y(t) - target|^2
        square = poly.polyadd(square, poly.polymul(c, c))
    slope = poly.polyder(square)
    t = poly.polyroots(slope).real if np.any(slope) else np.zeros(0)
    low = poly.polyval(np.concatenate([[0.0, 1.0], np.clip(t, 0.0, 1.0)]), square).min()
    return 1 if np.sqrt(max(low, 0.0)) <= tol else 0


def rpr(step: Step, state: State, point_link: np.ndarray) -> None:
    """RPR dyad: the guide and the slider of the inner pair turn together about their outer joints."""
    arm_g, arm_s = step.arms
    k = step.inner
    pg, vg, ag = state.point(int(point_link[arm_g.src]), arm_g.src)
    ps, vs, as_ = state.point(int(point_link[arm_s.src]), arm_s.src)
    u_loc = (state.axis[k, 0], state.axis[k, 1])
    n_loc = perp(u_loc)
    w = sub(
        sub(state.loc(arm_s.slider_point), state.loc(arm_s.own)),
        sub((state.origin[k, 0], state.origin[k, 1]), state.loc(arm_g.own)),
    )
    e = dot(n_loc, w)
    d = sub(ps, pg)
    dist = norm(d)
    theta = np.arctan2(d[1], d[0]) - np.arctan2(n_loc[1], n_loc[0]) + step.branch * np.arccos(-e / dist)
    slack = 1 - (e / dist) ** 2
    c, s = np.cos(theta), np.sin(theta)
    u = rot(c, s, u_loc)
    col = perp(sub(pg, ps))
    nu = scale(-1.0, u)
    omega, sdot, det = solve2(col, nu, sub(vg, vs))
    rhs = add(add(sub(ag, as_), scale(omega * omega, sub(pg, ps))), scale(2 * omega * sdot, perp(u)))
    eps, _, _ = solve2(col, nu, rhs)
    state.place(arm_g.link, theta, omega, eps, pg, vg, ag, state.loc(arm_g.own), (c, s))
    state.place(arm_s.link, theta, omega, eps, ps, vs, as_, state.loc(arm_s.own), (c, s))
    _record(state, slack, det / norm(col))


def rpp(step: Step, state: State, point_link: np.ndarray) -> None:
    """RPP dyad: every angle is the guide's; the pinned link first, then the other as two lines."""
    pinned, inner_arm, outer_arm = step.arms
    g = outer_arm.carrier
    p, vp, ap = state.point(int(point_link[pinned.src]), pinned.src)
    state.place_like(pinned.link, g, p, vp, ap, state.loc(pinned.own))
    dyad(step, state, point_link, arms=(inner_arm, outer_arm))


def crank(
    step: Step, state: State, point_link: np.ndarray, phi: np.ndarray, dphi: np.ndarray, ddphi: np.ndarray
) -> None:
    """A link driven by a revolute pair about a placed link."""
    arm = step.arms[0]
    base = int(point_link[arm.src])
    theta = state.q[base, 2] + step.sign * phi
    omega = state.v[base, 2] + step.sign * dphi
    eps = state.a[base, 2] + step.sign * ddphi
    p, vp, ap = state.point(base, arm.src)
    state.place(arm.link, theta, omega, eps, p, vp, ap, state.loc(arm.own))
    one = np.ones(state.valid.shape)
    _record(state, one, one)


def slide(step: Step, state: State, point_link: np.ndarray, s: np.ndarray, ds: np.ndarray, dds: np.ndarray) -> None:
    """A slider driven along a guide of a placed link."""
    arm = step.arms[0]
    g = arm.carrier
    origin, u = state.line(arm.pair, g)
    x = add(origin, scale(s, u))
    vm, am = state.material(g, x)
    vx = add(vm, scale(ds, u))
    ax = add(add(am, scale(dds, u)), scale(2 * state.v[g, 2] * ds, perp(u)))
    state.place_like(arm.link, g, x, vx, ax, state.loc(arm.slider_point))
    one = np.ones(state.valid.shape)
    _record(state, one, one)


def _record(
    state: State,
    slack: np.ndarray,
    det: np.ndarray,
    branch: np.ndarray | None = None,
    flips: list[Flip] | None = None,
    limit: np.ndarray | None = None,
) -> None:
    shape = state.valid.shape
    slack = np.broadcast_to(slack, shape)
    state.steps.append(
        StepRecord(
            slack >= 0,
            np.broadcast_to(det, shape),
            slack,
            branch,
            flips or [],
            [],
            None if limit is None else np.broadcast_to(limit, shape),
        )
    )


def with_branches(mech: Mechanism, steps: list[Step]) -> list[Step]:
    """Read the branch of every closed-form step off the assembly pose."""
    state = single_state(mech)
    out = []
    for step in steps:
        if step.kind in ("RRR", "RRP", "PRP", "RPP"):
            arms = step.arms if step.kind != "RPP" else step.arms[1:]
            xa = _x_local(state, step.x_local[0])
            xb = _x_local(state, step.x_local[1])
            la = _Locus(state, arms[0], xa, mech.point_link)
            lb = _Locus(state, arms[1], xb, mech.point_link)
            x = state.point_at(arms[0].link, xa)[0]
            if la.arm.kind == "R" and lb.arm.kind == "R":
                branch = cross(sub(lb.p, la.p), sub(x, la.p))
            elif la.arm.kind == "R" or lb.arm.kind == "R":
                circle = la if la.arm.kind == "R" else lb
                other = lb if circle is la else la
                branch = dot(sub(x, circle.p), other.u)
            else:
                branch = np.ones(1)
            step = dataclasses.replace(step, branch=float(np.sign(np.ravel(branch)[0])) or 1.0)
        elif step.kind == "RPR":
            arm_g, arm_s = step.arms
            pg = state.point(int(mech.point_link[arm_g.src]), arm_g.src)[0]
            ps = state.point(int(mech.point_link[arm_s.src]), arm_s.src)[0]
            d = sub(ps, pg)
            n_loc = perp((state.axis[step.inner, 0], state.axis[step.inner, 1]))
            theta = state.q[arm_g.link, 2]
            rel = theta - np.arctan2(d[1], d[0]) + np.arctan2(n_loc[1], n_loc[0])
            rel = wrap(rel)
            step = dataclasses.replace(step, branch=float(np.sign(np.ravel(rel)[0])) or 1.0)
        out.append(step)
    return out
