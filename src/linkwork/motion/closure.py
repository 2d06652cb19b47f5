"""Where a class II dyad closes: the loci of its point X and where they meet.

Each arm of a dyad gives a locus of the point X where the dyad closes (:class:`Locus`: a circle about an
outer joint, or a line of a guide); :func:`closure_of` intersects them (:class:`Closure`: X in either
assembly mode, the assembly margin, where the two modes trade places and the velocity of X on a singular
position to rounding).  Used by the dyad kernels of :mod:`linkwork.motion.kernels` and by
:mod:`linkwork.motion.change_points`.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import NamedTuple

import numpy as np

from linkwork.motion.state import State, Vec, add, cross, dot, norm, perp, rot, scale, sub
from linkwork.structure.records import Arm


class Locus:
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


def closure_of(state: State, la: Locus, lb: Locus) -> Closure:
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


def _circles(la: Locus, lb: Locus) -> Closure:
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
    limit = _limit(*_circles_limit(la, lb, (e, a, h), on, joined, (dv, da), (dist, dist_v, dist_a)))
    return Closure(add(la.p, scale(a, e)), perp(e), h, slack, singular, limit)


def _circles_limit(
    la: Locus,
    lb: Locus,
    chord: tuple[Vec, np.ndarray, np.ndarray],
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
    s is the mode just after the sample.  ``chord``: the unit vector e from P_a to P_b, the distance a of the
    chord's middle from P_a along it and the half chord h; ``on``: there; ``rel``: the velocity and acceleration
    of P_b - P_a; ``distance``: their distance and its first two time derivatives."""
    (e, a, h), (dv, da), (dist, dist_v, dist_a) = chord, rel, distance
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


def mode_point(closure: Closure, branch: np.ndarray | float) -> Vec:
    """X in the assembly mode ``branch``."""
    return add(closure.mid, scale(branch * closure.h, closure.n))


def _touching(slack: np.ndarray) -> np.ndarray:
    """Margins within rounding of zero are a touch (one point), not a miss."""
    return np.where((slack < 0) & (slack > -1e-12), 0.0, slack)
