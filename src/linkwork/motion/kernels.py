"""Kernels of the solve program: positions, velocities and accelerations of one group.

Every kernel works on whole arrays ``(n_variants, n_angles)`` and writes the
state of its links into :class:`~linkwork.motion.state.State`.  The class II
dyads are solved in closed form: positions by intersecting the loci of the
point X where the dyad closes (a circle about an outer joint, or a line of a
guide), velocities and accelerations from the two vector equations of X,
one 2x2 linear system each (with the Coriolis terms of sliding pairs).
Samples where a group cannot be assembled come out as NaN.
"""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np

from linkwork.motion.program import Arm, Step
from linkwork.motion.state import State, Vec, add, cross, dot, norm, perp, rot, scale, single_state, solve2, sub


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


def _intersect(la: _Locus, lb: _Locus, branch: np.ndarray | float) -> tuple[Vec, np.ndarray]:
    """X where the two loci meet, and the assembly margin (negative where they do not)."""
    if la.arm.kind == "R" and lb.arm.kind == "R":
        d = sub(lb.p, la.p)
        dist2 = dot(d, d)
        inv = 1.0 / np.sqrt(dist2)
        a = (la.r * la.r - lb.r * lb.r + dist2) * (0.5 * inv)
        h2 = la.r * la.r - a * a
        rsum2 = (la.r + lb.r) ** 2
        slack = _touching(np.minimum(rsum2 - dist2, dist2 - (la.r - lb.r) ** 2) / rsum2)
        e = scale(inv, d)
        h = branch * np.sqrt(np.where(slack >= 0, np.maximum(h2, 0.0), h2))
        return (la.p[0] + a * e[0] - h * e[1], la.p[1] + a * e[1] + h * e[0]), slack
    if la.arm.kind == "P" and lb.arm.kind == "P":
        den = cross(la.u, lb.u)
        t = cross(sub(lb.l0, la.l0), lb.u) / den
        return add(la.l0, scale(t, la.u)), np.abs(den)
    circle, line = (la, lb) if la.arm.kind == "R" else (lb, la)
    w = sub(circle.p, line.l0)
    t0 = dot(w, line.u)
    h = cross(line.u, w)
    disc = circle.r * circle.r - h * h
    slack = _touching(disc / (circle.r * circle.r))
    return add(line.l0, scale(t0 + branch * np.sqrt(np.where(slack >= 0, np.maximum(disc, 0.0), disc)), line.u)), slack


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
    flips: list[tuple[int, int, int]] = []
    if branch is None:
        branch_used: Any = step.branch
        if "R" in (arm_a.kind, arm_b.kind):
            full = np.full(state.valid.shape, step.branch)
            flips = _change_points(state, la, lb, full)
            if flips:
                branch_used = full
    else:
        branch_used = branch
    x, slack = _intersect(la, lb, branch_used)
    # no single point X although the loci "meet" (coincident circle centres, parallel guides): not assembled
    slack = np.where((slack >= 0) & ~(np.isfinite(x[0]) & np.isfinite(x[1])), -1.0, slack)
    ca, cb = la.column(x), lb.column(x)
    va, aa = la.base(state, x)
    vb, ab = lb.base(state, x)
    ncb = scale(-1.0, cb)
    ka, kb, det = solve2(ca, ncb, sub(vb, va))
    ea, eb = la.accel_extra(state, x, ka), lb.accel_extra(state, x, kb)
    ka_d, kb_d, _ = solve2(ca, ncb, sub(add(ab, eb), add(aa, ea)))
    vx = add(va, scale(ka, ca))
    ax = add(add(aa, scale(ka_d, ca)), ea)
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
    _record(state, slack, det / (norm(ca) * norm(cb)), None if np.isscalar(branch_used) else branch_used, flips)


def _change_points(state: State, la: _Locus, lb: _Locus, branch: np.ndarray) -> list[tuple[int, int, int]]:
    """Follow the motion through change points, along the angles in the order given.

    From the sample nearest the assembly pose, forwards and then backwards,
    each sample where the two assembly modes of the dyad nearly meet (their
    points X closer together than X moves in a step) takes the mode whose X
    lies nearer the extrapolation of X from the two samples before it.  So
    the motion keeps going smoothly where the modes cross (the isosceles
    slider-crank at 0 and 180 deg, a parallelogram laid flat) and never
    jumps between modes that are apart.  ``branch`` is changed in place;
    returns (variant, first sample in the new mode, sample nearest the change point).
    """
    x_p, _ = _intersect(la, lb, branch)
    x_m, _ = _intersect(la, lb, -branch)
    n = branch.shape[1]
    if n < 3:
        return []
    gap = norm(sub(x_p, x_m))  # (V, A)
    step = np.fmax(
        norm((np.diff(x_p[0], axis=1), np.diff(x_p[1], axis=1))),
        norm((np.diff(x_m[0], axis=1), np.diff(x_m[1], axis=1))),
    )  # (V, A - 1), either mode
    move = np.empty_like(gap)
    move[:, 0], move[:, -1] = step[:, 0], step[:, -1]
    np.fmax(step[:, :-1], step[:, 1:], out=move[:, 1:-1])
    with np.errstate(invalid="ignore"):
        near = gap <= 2 * move + 1e-12 * (1 + float(np.abs(state.local).max()))
    if not near.any():
        return []
    xp, xm = np.stack(x_p, -1), np.stack(x_m, -1)
    drive = state.drive
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
                    flips.append((int(v), int(here), touch))
    return flips


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
    sign = 1.0 if step.extra["b"] == arm.link else -1.0
    theta = state.q[base, 2] + sign * phi
    omega = state.v[base, 2] + sign * dphi
    eps = state.a[base, 2] + sign * ddphi
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
    flips: list[tuple[int, int, int]] | None = None,
) -> None:
    slack = np.broadcast_to(slack, state.valid.shape)
    state.step_slack.append(slack)
    state.step_det.append(np.broadcast_to(det, state.valid.shape))
    state.step_valid.append(slack >= 0)
    state.step_branch.append(branch)
    state.step_flips.append(flips or [])
    state.step_jumps.append([])


def with_branches(mech: Any, steps: list[Step]) -> list[Step]:
    """Read the branch of every closed-form step off the assembly pose."""
    state = single_state(mech)
    out = []
    for step in steps:
        if step.kind == "crank":
            step = dataclasses.replace(step, extra={"b": int(mech.pair_links[step.pair, 1])})
        elif step.kind in ("RRR", "RRP", "PRP", "RPP"):
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
            rel = (rel + np.pi) % (2 * np.pi) - np.pi
            step = dataclasses.replace(step, branch=float(np.sign(np.ravel(rel)[0])) or 1.0)
        out.append(step)
    return out
