"""Kinematic state arrays and the small vector helpers the kernels share.

The state of link ``i`` is its pose ``(x, y, theta)`` (origin of its local
frame and angle of its x axis), its velocity ``(vx, vy, omega)`` and its
acceleration ``(ax, ay, epsilon)``, each an array of shape
``(n_variants, n_angles, n_links, 3)``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np


def rot(theta: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Rotate vectors ``v (..., 2)`` by angles ``theta (...)``."""
    c, s = np.cos(theta), np.sin(theta)
    return np.stack([c * v[..., 0] - s * v[..., 1], s * v[..., 0] + c * v[..., 1]], axis=-1)


def perp(v: np.ndarray) -> np.ndarray:
    """``v`` turned by +90 degrees: ``omega x r`` is ``omega * perp(r)``."""
    return np.stack([-v[..., 1], v[..., 0]], axis=-1)


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1]


def solve2(c1: np.ndarray, c2: np.ndarray, rhs: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Solve ``k1 c1 + k2 c2 = rhs`` for 2-vectors by Cramer's rule; also returns the determinant."""
    det = cross(c1, c2)
    with np.errstate(divide="ignore", invalid="ignore"):
        k1 = cross(rhs, c2) / det
        k2 = cross(c1, rhs) / det
    return k1, k2, det


@dataclass
class State:
    """Arrays being filled by the solve program, group by group."""

    pose: np.ndarray
    vel: np.ndarray
    acc: np.ndarray
    local: np.ndarray  # (V, 1, P, 2) point coordinates of the variants
    origin: np.ndarray  # (V, 1, M, 2)
    axis: np.ndarray  # (V, 1, M, 2)
    valid: np.ndarray  # (V, A) bool
    step_valid: list[np.ndarray] = field(default_factory=list)  # per step (V, A)
    step_det: list[np.ndarray] = field(default_factory=list)  # per step, normalised Jacobian determinant
    step_slack: list[np.ndarray] = field(default_factory=list)  # per step, assembly margin (< 0: no assembly)
    placed: set[int] = field(default_factory=lambda: {0})
    start_index: int = 0  # the sample nearest to the assembly pose: continuation starts there
    step_branch: list[np.ndarray | None] = field(default_factory=list)  # per step, the mode used (V, A)
    step_flips: list[list[tuple[int, int]]] = field(default_factory=list)  # per step, change points

    def point(self, link: int, p: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Position, velocity and acceleration of point ``p`` of ``link``: each ``(V, A, 2)``."""
        return self.point_at(link, self.local[:, :, p])

    def point_at(self, link: int, loc: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        q, v, a = self.pose[:, :, link], self.vel[:, :, link], self.acc[:, :, link]
        r = rot(q[..., 2], loc)
        w, e = v[..., 2, None], a[..., 2, None]
        return q[..., :2] + r, v[..., :2] + w * perp(r), a[..., :2] + e * perp(r) - w * w * r

    def place(
        self,
        link: int,
        theta: np.ndarray,
        omega: np.ndarray,
        eps: np.ndarray,
        x: np.ndarray,
        vx: np.ndarray,
        ax: np.ndarray,
        loc: np.ndarray,
    ) -> None:
        """Set a link's state from its angle terms and the motion of its point at local ``loc``."""
        r = rot(theta, loc)
        w, e = omega[..., None], eps[..., None]
        self.pose[:, :, link, :2] = x - r
        self.pose[:, :, link, 2] = theta
        self.vel[:, :, link, :2] = vx - w * perp(r)
        self.vel[:, :, link, 2] = omega
        self.acc[:, :, link, :2] = ax - e * perp(r) + w * w * r
        self.acc[:, :, link, 2] = eps

    def line(self, k: int, guide: int) -> tuple[np.ndarray, np.ndarray]:
        """Global origin and unit direction of the guide line of prismatic pair ``k``."""
        q = self.pose[:, :, guide]
        return q[..., :2] + rot(q[..., 2], self.origin[:, :, k]), rot(q[..., 2], self.axis[:, :, k])

    def material(self, link: int, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Velocity and acceleration of the material point of ``link`` at global ``x``."""
        q, v, a = self.pose[:, :, link], self.vel[:, :, link], self.acc[:, :, link]
        r = x - q[..., :2]
        w, e = v[..., 2, None], a[..., 2, None]
        return v[..., :2] + w * perp(r), a[..., :2] + e * perp(r) - w * w * r
