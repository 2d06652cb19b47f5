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
from linkwork.motion.state import State, cross, dot, perp, rot, solve2


def _x_local(state: State, idx: int) -> np.ndarray:
    if idx < 0:
        return np.zeros(state.local.shape[:2] + (2,))
    return state.local[:, :, idx]


def _src_link(state: State, arm: Arm, point_link: np.ndarray) -> int:
    return int(point_link[arm.src])


class _Locus:
    """The locus of X given by one arm, with what its velocity equations need."""

    def __init__(self, state: State, arm: Arm, x_loc: np.ndarray, point_link: np.ndarray):
        self.arm = arm
        if arm.kind == "R":
            self.p, self.vp, self.ap = state.point(_src_link(state, arm, point_link), arm.src)
            d = x_loc - state.local[:, :, arm.own]
            self.r = np.hypot(d[..., 0], d[..., 1])
            self.local_angle = np.arctan2(d[..., 1], d[..., 0])
        else:
            c = arm.carrier
            theta = state.pose[:, :, c, 2]
            if arm.own_is_slider:
                origin, self.u = state.line(arm.pair, c)
                self.l0 = origin + rot(theta, x_loc - state.local[:, :, arm.slider_point])
            else:
                s = state.point(c, arm.slider_point)[0]
                self.u = rot(theta, state.axis[:, :, arm.pair])
                self.l0 = s + rot(theta, x_loc - state.origin[:, :, arm.pair])
            self.carrier = c

    def column(self, x: np.ndarray) -> np.ndarray:
        return perp(x - self.p) if self.arm.kind == "R" else self.u

    def base(self, state: State, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Velocity and acceleration of X with the arm's unknown rate (and its square terms) left out."""
        if self.arm.kind == "R":
            return self.vp, self.ap
        return state.material(self.carrier, x)

    def accel_extra(self, state: State, x: np.ndarray, k: np.ndarray) -> np.ndarray:
        """Acceleration terms quadratic in the rates: centripetal (R) or Coriolis (P)."""
        if self.arm.kind == "R":
            return -(k[..., None] ** 2) * (x - self.p)
        w = state.vel[:, :, self.carrier, 2]
        return 2 * (w * k)[..., None] * perp(self.u)


def _intersect(la: _Locus, lb: _Locus, branch: float) -> tuple[np.ndarray, np.ndarray]:
    """X where the two loci meet, and the assembly margin (negative where they do not)."""
    with np.errstate(invalid="ignore", divide="ignore"):
        if la.arm.kind == "R" and lb.arm.kind == "R":
            d = lb.p - la.p
            dist2 = dot(d, d)
            dist = np.sqrt(dist2)
            a = (la.r**2 - lb.r**2 + dist2) / (2 * dist)
            h2 = la.r**2 - a * a
            scale = (la.r + lb.r) ** 2
            slack = np.minimum((la.r + lb.r) ** 2 - dist2, dist2 - (la.r - lb.r) ** 2) / scale
            e = d / dist[..., None]
            x = la.p + a[..., None] * e + (branch * np.sqrt(h2))[..., None] * perp(e)
            return x, slack
        if la.arm.kind == "P" and lb.arm.kind == "P":
            den = cross(la.u, lb.u)
            t = cross(lb.l0 - la.l0, lb.u) / den
            return la.l0 + t[..., None] * la.u, np.abs(den)
        circle, line = (la, lb) if la.arm.kind == "R" else (lb, la)
        w = circle.p - line.l0
        t0 = dot(w, line.u)
        h = cross(line.u, w)
        disc = circle.r**2 - h * h
        x = line.l0 + (t0 + branch * np.sqrt(disc))[..., None] * line.u
        return x, disc / circle.r**2


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
    flips: list[tuple[int, int]] = []
    if branch is None:
        branch = np.full(state.valid.shape, step.branch)
        if "R" in (arm_a.kind, arm_b.kind):
            flips = _change_points(state, la, lb, branch)
    x, slack = _intersect(la, lb, branch)
    ca, cb = la.column(x), lb.column(x)
    ka, kb, det, vx = _rates(state, la, lb, x)
    va, aa = la.base(state, x)
    vb, ab = lb.base(state, x)
    rhs = ab + lb.accel_extra(state, x, kb) - aa - la.accel_extra(state, x, ka)
    ka_d, kb_d, _ = solve2(ca, -cb, rhs)
    ax = aa + ka_d[..., None] * ca + la.accel_extra(state, x, ka)
    for arm, loc, k, kd, xl in ((arm_a, la, ka, ka_d, xa), (arm_b, lb, kb, kb_d, xb)):
        if arm.kind == "R":
            v = x - loc.p
            theta = np.arctan2(v[..., 1], v[..., 0]) - loc.local_angle
            state.place(arm.link, theta, k, kd, loc.p, loc.vp, loc.ap, state.local[:, :, arm.own])
        else:
            c = arm.carrier
            state.place(arm.link, state.pose[:, :, c, 2], state.vel[:, :, c, 2], state.acc[:, :, c, 2], x, vx, ax, xl)
    norm = np.hypot(*np.moveaxis(ca, -1, 0)) * np.hypot(*np.moveaxis(cb, -1, 0))
    _record(state, slack, det / norm, branch, flips)


def _rates(state: State, la: _Locus, lb: _Locus, x: np.ndarray) -> tuple[np.ndarray, ...]:
    """The arms' rates, the determinant, and the velocity of X: X moves as base_a + ka col_a = base_b + kb col_b."""
    ca, cb = la.column(x), lb.column(x)
    va, _ = la.base(state, x)
    vb, _ = lb.base(state, x)
    ka, kb, det = solve2(ca, -cb, vb - va)
    return ka, kb, det, va + ka[..., None] * ca


def _change_points(state: State, la: _Locus, lb: _Locus, branch: np.ndarray) -> list[tuple[int, int]]:
    """Switch the mode after each change point along the angles (in the order given).

    A change point is a sample where the two assembly modes nearly meet
    (a local minimum of the intersection margin) and the velocity of X
    goes on continuously only in the other mode.  ``branch`` is changed in
    place; returns the (variant, first sample in the new mode) pairs.
    """
    x_p, slack = _intersect(la, lb, branch)
    root = np.sqrt(np.where(slack >= 0, slack, np.nan))
    inner = (root[:, 1:-1] <= root[:, :-2]) & (root[:, 1:-1] <= root[:, 2:]) & (root[:, 1:-1] < 0.2)
    cand = np.argwhere(inner)
    if len(cand) == 0:
        return []
    x_m, _ = _intersect(la, lb, -branch)
    v_p = _rates(state, la, lb, x_p)[3]
    v_m = _rates(state, la, lb, x_m)[3]
    flips = []
    start = state.start_index
    for v in np.unique(cand[:, 0]):
        mids = cand[cand[:, 0] == v, 1] + 1
        # from the sample nearest to the assembly pose, forwards and then backwards
        for direction in (1, -1):
            order = np.arange(start, branch.shape[1]) if direction > 0 else np.arange(start, -1, -1)
            pos = {int(i): n for n, i in enumerate(order)}
            parity = 1.0
            for i in sorted(
                (int(i) for i in mids if int(i) in pos and pos[int(i)] not in (0, len(order) - 1)), key=lambda i: pos[i]
            ):
                n = pos[i]
                prev, here, nxt = order[n - 1], order[n], order[n + 1]
                cur_v, alt_v = (v_p[v], v_m[v]) if parity > 0 else (v_m[v], v_p[v])
                cur_x, alt_x = (x_p[v], x_m[v]) if parity > 0 else (x_m[v], x_p[v])
                if not np.hypot(*(alt_x[here] - cur_x[here])) <= np.hypot(*(cur_x[nxt] - cur_x[prev])):
                    continue
                before = cur_v[prev]
                if np.all(np.isfinite(cur_v[here])) and np.hypot(*(alt_v[here] - before)) < np.hypot(
                    *(cur_v[here] - before)
                ):
                    first = n
                elif np.hypot(*(alt_v[nxt] - before)) < np.hypot(*(cur_v[nxt] - before)):
                    first = n + 1
                else:
                    continue
                branch[v, order[first:]] *= -1
                parity *= -1
                flips.append((int(v), int(order[first])))
    return flips


def rpr(step: Step, state: State, point_link: np.ndarray) -> None:
    """RPR dyad: the guide and the slider of the inner pair turn together about their outer joints."""
    arm_g, arm_s = step.arms
    k = step.inner
    pg, vg, ag = state.point(int(point_link[arm_g.src]), arm_g.src)
    ps, vs, as_ = state.point(int(point_link[arm_s.src]), arm_s.src)
    loc = state.local
    u_loc = state.axis[:, :, k]
    n_loc = perp(u_loc)
    w = (loc[:, :, arm_s.slider_point] - loc[:, :, arm_s.own]) - (state.origin[:, :, k] - loc[:, :, arm_g.own])
    e = dot(n_loc, w)
    d = ps - pg
    dist = np.hypot(d[..., 0], d[..., 1])
    with np.errstate(invalid="ignore", divide="ignore"):
        theta = (
            np.arctan2(d[..., 1], d[..., 0])
            - np.arctan2(n_loc[..., 1], n_loc[..., 0])
            + step.branch * np.arccos(-e / dist)
        )
        slack = 1 - (e / dist) ** 2
    u = rot(theta, u_loc)
    col = perp(pg - ps)
    omega, sdot, det = solve2(col, -u, vg - vs)
    rhs = ag - as_ + (omega**2)[..., None] * (pg - ps) + 2 * (omega * sdot)[..., None] * perp(u)
    eps, _, _ = solve2(col, -u, rhs)
    state.place(arm_g.link, theta, omega, eps, pg, vg, ag, loc[:, :, arm_g.own])
    state.place(arm_s.link, theta, omega, eps, ps, vs, as_, loc[:, :, arm_s.own])
    _record(state, slack, det / np.maximum(np.hypot(col[..., 0], col[..., 1]), 1e-300))


def rpp(step: Step, state: State, point_link: np.ndarray) -> None:
    """RPP dyad: every angle is the guide's; the pinned link first, then the other as two lines."""
    pinned, inner_arm, outer_arm = step.arms
    g = outer_arm.carrier
    p, vp, ap = state.point(int(point_link[pinned.src]), pinned.src)
    state.place(
        pinned.link,
        state.pose[:, :, g, 2],
        state.vel[:, :, g, 2],
        state.acc[:, :, g, 2],
        p,
        vp,
        ap,
        state.local[:, :, pinned.own],
    )
    dyad(step, state, point_link, arms=(inner_arm, outer_arm))


def crank(
    step: Step, state: State, point_link: np.ndarray, phi: np.ndarray, dphi: np.ndarray, ddphi: np.ndarray
) -> None:
    """A link driven by a revolute pair about a placed link."""
    arm = step.arms[0]
    base = int(point_link[arm.src])
    sign = 1.0 if int(state_pair_b(step)) == arm.link else -1.0
    theta = state.pose[:, :, base, 2] + sign * phi
    omega = state.vel[:, :, base, 2] + sign * dphi
    eps = state.acc[:, :, base, 2] + sign * ddphi
    p, vp, ap = state.point(base, arm.src)
    state.place(arm.link, theta, omega, eps, p, vp, ap, state.local[:, :, arm.own])
    _record(state, np.ones_like(theta), np.ones_like(theta))


def state_pair_b(step: Step) -> int:
    return step.extra["b"]


def slide(step: Step, state: State, point_link: np.ndarray, s: np.ndarray, ds: np.ndarray, dds: np.ndarray) -> None:
    """A slider driven along a guide of a placed link."""
    arm = step.arms[0]
    g = arm.carrier
    origin, u = state.line(arm.pair, g)
    x = origin + s[..., None] * u
    vm, am = state.material(g, x)
    vx = vm + ds[..., None] * u
    ax = am + dds[..., None] * u + 2 * (state.vel[:, :, g, 2] * ds)[..., None] * perp(u)
    state.place(
        arm.link,
        state.pose[:, :, g, 2],
        state.vel[:, :, g, 2],
        state.acc[:, :, g, 2],
        x,
        vx,
        ax,
        state.local[:, :, arm.slider_point],
    )
    _record(state, np.ones_like(s), np.ones_like(s))


def _record(
    state: State,
    slack: np.ndarray,
    det: np.ndarray,
    branch: np.ndarray | None = None,
    flips: list[tuple[int, int]] | None = None,
) -> None:
    ok = np.isfinite(slack) & (slack >= 0)
    state.step_slack.append(slack)
    state.step_det.append(det)
    state.step_valid.append(ok)
    state.step_branch.append(branch)
    state.step_flips.append(flips or [])


def with_branches(mech: Any, steps: list[Step]) -> list[Step]:
    """Read the branch of every closed-form step off the assembly pose."""
    from linkwork.motion.solve import single_state

    state = single_state(mech)
    out = []
    for step in steps:
        if step.kind == "crank":
            step = dataclasses.replace(step, extra={"b": int(mech.pair_links[step.pair, 1])})
        elif step.kind in ("RRR", "RRP", "PRP", "RPP"):
            arms = step.arms if step.kind != "RPP" else step.arms[1:]
            if step.kind == "RPP":
                _place_pinned(step, state, mech.point_link)
            xa = _x_local(state, step.x_local[0])
            xb = _x_local(state, step.x_local[1])
            la = _Locus(state, arms[0], xa, mech.point_link)
            lb = _Locus(state, arms[1], xb, mech.point_link)
            x = state.point_at(arms[0].link, xa)[0]
            if la.arm.kind == "R" and lb.arm.kind == "R":
                branch = np.sign(cross(lb.p - la.p, x - la.p))
            elif la.arm.kind == "R" or lb.arm.kind == "R":
                circle = la if la.arm.kind == "R" else lb
                other = lb if circle is la else la
                branch = np.sign(dot(x - circle.p, other.u))
            else:
                branch = np.ones(1)
            step = dataclasses.replace(step, branch=float(np.ravel(branch)[0]) or 1.0)
        elif step.kind == "RPR":
            arm_g, arm_s = step.arms
            pg = state.point(int(mech.point_link[arm_g.src]), arm_g.src)[0]
            ps = state.point(int(mech.point_link[arm_s.src]), arm_s.src)[0]
            d = ps - pg
            n_loc = perp(state.axis[:, :, step.inner])
            theta = state.pose[:, :, arm_g.link, 2]
            rel = theta - np.arctan2(d[..., 1], d[..., 0]) + np.arctan2(n_loc[..., 1], n_loc[..., 0])
            rel = (rel + np.pi) % (2 * np.pi) - np.pi
            step = dataclasses.replace(step, branch=float(np.sign(np.ravel(rel)[0])) or 1.0)
        out.append(step)
    return out


def _place_pinned(step: Step, state: State, point_link: np.ndarray) -> None:
    """No-op at the assembly pose: the pinned link of an RPP is already in place there."""
    del step, state, point_link
