"""Kernels of the solve program: positions, velocities and accelerations of one group.

Every kernel works on whole arrays ``(n_variants, n_angles)`` and writes the
state of its links into :class:`~linkwork.motion.state.State`.  The class II
dyads are solved in closed form: positions by intersecting the loci of the
point X where the dyad closes (a circle about an outer joint, or a line of a
guide), velocities and accelerations from the two vector equations of X,
one 2x2 linear system each (with the Coriolis terms of sliding pairs).
Samples where a group cannot be assembled come out as NaN.  Where the loci of a dyad meet is
:mod:`linkwork.motion.closure`'s; where its assembly mode changes along the samples,
:mod:`linkwork.motion.change_points`'.

:mod:`linkwork.motion.kernels_numba` is their twin in machine code (the package's docstring says how the
two are kept alike).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from linkwork.angles import wrap
from linkwork.motion.change_points import change_points
from linkwork.motion.closure import CLOSE, ROUNDING, SINGULAR, Locus, closure_of, mode_point  # noqa: F401 - the tolerances are read here
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
    solve2,
    sub,
)
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
    la, lb = Locus(state, arm_a, xa, point_link), Locus(state, arm_b, xb, point_link)
    closure = closure_of(state, la, lb)
    flips: list[Flip] = []
    if branch is None:
        branch_used: np.ndarray | float = step.branch
        if "R" in (arm_a.kind, arm_b.kind):
            full = np.full(state.valid.shape, step.branch)
            flips = change_points(state, closure, full)
            if flips:
                branch_used = full
    else:
        branch_used = branch
    x, slack = mode_point(closure, branch_used), closure.slack
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
            state.place(arm.link, (theta, k, kd), (loc.p, loc.vp, loc.ap), state.loc(arm.own), (c, s))
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


def _motion(state: State, la: Locus, lb: Locus, x: Vec) -> tuple[Any, ...]:
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
    state.place(arm_g.link, (theta, omega, eps), (pg, vg, ag), state.loc(arm_g.own), (c, s))
    state.place(arm_s.link, (theta, omega, eps), (ps, vs, as_), state.loc(arm_s.own), (c, s))
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
    state.place(arm.link, (theta, omega, eps), (p, vp, ap), state.loc(arm.own))
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


def dyad_mode(step: Step, state: State, point_link: np.ndarray) -> float:
    """The assembly mode (+1 or -1) of a dyad closed at X (RRR, RRP, PRP; RPP through its second stage) in the
    single-pose ``state`` of the assembly pose: on which side of the line between two circles' centres X lies,
    or along which direction of the line from the circle's centre."""
    arms = step.arms if step.kind != "RPP" else step.arms[1:]
    xa = _x_local(state, step.x_local[0])
    xb = _x_local(state, step.x_local[1])
    la = Locus(state, arms[0], xa, point_link)
    lb = Locus(state, arms[1], xb, point_link)
    x = state.point_at(arms[0].link, xa)[0]
    if la.arm.kind == "R" and lb.arm.kind == "R":
        branch = cross(sub(lb.p, la.p), sub(x, la.p))
    elif la.arm.kind == "R" or lb.arm.kind == "R":
        circle = la if la.arm.kind == "R" else lb
        other = lb if circle is la else la
        branch = dot(sub(x, circle.p), other.u)
    else:
        branch = np.ones(1)
    return float(np.sign(np.ravel(branch)[0])) or 1.0


def rpr_mode(step: Step, state: State, point_link: np.ndarray) -> float:
    """The assembly mode (+1 or -1) of an RPR dyad in the single-pose ``state`` of the assembly pose: the side of
    the line between its pivots its common angle lies on."""
    arm_g, arm_s = step.arms
    pg = state.point(int(point_link[arm_g.src]), arm_g.src)[0]
    ps = state.point(int(point_link[arm_s.src]), arm_s.src)[0]
    d = sub(ps, pg)
    n_loc = perp((state.axis[step.inner, 0], state.axis[step.inner, 1]))
    theta = state.q[arm_g.link, 2]
    rel = theta - np.arctan2(d[1], d[0]) + np.arctan2(n_loc[1], n_loc[0])
    rel = wrap(rel)
    return float(np.sign(np.ravel(rel)[0])) or 1.0
