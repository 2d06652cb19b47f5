"""The kinematic scheme of a mechanism in a pose, with the conventional symbols.

Links are drawn through their joint points (a bar, or a hatched-free plate
for three and more), revolute pairs as small circles, supports on the frame
as hatched triangles, sliders as blocks on their guides, and guides on the
frame as hatched lines; links are numbered as in the file (1, 2, ...) and
points lettered with their names.  Optionally the plan of positions: the
mechanism in several positions, thin, with the trajectories of its points.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from linkwork.structure.model import PairType


def _points(kin: Any, index: int) -> np.ndarray:
    pts = kin.points()
    return pts[0, index] if kin.variants else pts[index]


def _size(pts: np.ndarray) -> float:
    finite = pts[np.isfinite(pts).all(-1)]
    return float(np.ptp(finite, axis=0).max()) if len(finite) > 1 else 1.0


def draw_scheme(kin: Any, index: int = 0, ax: Any = None, trajectories: bool = False) -> Any:
    """The scheme at sample ``index`` of a kinematics result; returns the matplotlib Figure.

    With ``trajectories``, the paths of the joint points over all the samples are drawn too.
    """
    from matplotlib.figure import Figure
    from matplotlib.patches import Circle, Polygon, Rectangle

    from linkwork.motion.analysis import guide
    from linkwork.structure.model import point_labels

    mech = kin.mechanism
    fig = ax.figure if ax is not None else Figure(figsize=(7, 6))
    ax = ax if ax is not None else fig.add_subplot()
    pts = _points(kin, index)
    size = _size(kin.points().reshape(-1, 2))
    r = 0.012 * size
    joint_pts = {int(p) for pair in mech.pair_points for p in pair if p >= 0}
    if trajectories:
        allpts = kin.points()
        allpts = allpts[0] if kin.variants else allpts
        for p in sorted(joint_pts):
            if mech.point_link[p] != 0:
                ax.plot(allpts[:, p, 0], allpts[:, p, 1], lw=0.6, color="0.6", zorder=1)
    for i in range(1, mech.n_links_total):
        if mech.link_virtual[i]:
            continue
        own = [p for p in range(len(mech.point_names)) if mech.point_link[p] == i and p in joint_pts]
        xy = pts[own] if own else pts[[p for p in range(len(mech.point_names)) if mech.point_link[p] == i]]
        if len(xy) == 2:
            ax.plot(xy[:, 0], xy[:, 1], lw=2.2, color="tab:blue", zorder=2, solid_capstyle="round")
        elif len(xy) > 2:
            centre = xy.mean(0)
            order = np.argsort(np.arctan2(xy[:, 1] - centre[1], xy[:, 0] - centre[0]))
            ax.add_patch(Polygon(xy[order], closed=True, fc="tab:blue", alpha=0.25, ec="tab:blue", lw=2, zorder=2))
        if len(xy):
            c = xy.mean(0)
            ax.annotate(str(i), c, xytext=(6, -10), textcoords="offset points", fontsize=9, color="tab:blue")
    for k in range(mech.n_pairs):
        a, b = (int(x) for x in mech.pair_links[k])
        pb = pts[int(mech.pair_points[k, 1])]
        if mech.pair_type[k] == PairType.REVOLUTE:
            ax.add_patch(Circle(pb, r, fc="white", ec="black", lw=1.2, zorder=4))
            if a == 0:
                tri = np.array([pb, pb + [-1.6 * r, -2.8 * r], pb + [1.6 * r, -2.8 * r]])
                ax.add_patch(Polygon(tri, closed=True, fc="none", ec="black", lw=1, zorder=3))
                ax.add_patch(Rectangle(pb + [-2.4 * r, -3.6 * r], 4.8 * r, 0.8 * r, fc="none", ec="black",
                                       hatch="////", lw=0.6, zorder=3))  # fmt: skip
        else:
            u = guide(kin, k)[1][0, index]
            w = np.array([-u[1], u[0]])
            block = np.array(
                [pb - 2 * r * u - r * w, pb + 2 * r * u - r * w, pb + 2 * r * u + r * w, pb - 2 * r * u + r * w]
            )
            ax.add_patch(Polygon(block, closed=True, fc="white", ec="black", lw=1.2, zorder=4))
            if a == 0:
                line = np.array([pb - 6 * r * u, pb + 6 * r * u]) - 1.4 * r * w
                ax.plot(line[:, 0], line[:, 1], color="black", lw=1, zorder=3)
                for s in np.linspace(-6, 6, 13):
                    base = pb + s * r * u - 1.4 * r * w
                    tick = np.array([base, base - 0.8 * r * w - 0.6 * r * u])
                    ax.plot(tick[:, 0], tick[:, 1], color="black", lw=0.5, zorder=3)
    for label, p in point_labels(mech, with_all=False):
        ax.annotate(label, pts[p], xytext=(5, 5), textcoords="offset points", fontsize=10)
    for p in range(len(mech.point_names)):
        if mech.point_link[p] == 0:
            ax.annotate(mech.point_names[p].split(".", 1)[1], pts[p], xytext=(5, 5), textcoords="offset points",
                        fontsize=10)  # fmt: skip
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_title(f"{mech.name}: crank at {np.degrees(kin.angles[index]) % 360:.1f}°")
    ax.set_xlabel("x, m")
    ax.set_ylabel("y, m")
    ax.autoscale_view()
    return fig


def draw_positions(kin: Any, count: int = 12, ax: Any = None) -> Any:
    """The plan of positions: ``count`` positions evenly over the samples, overlaid, with the
    trajectories of the joint points."""
    from matplotlib.figure import Figure

    fig = ax.figure if ax is not None else Figure(figsize=(7, 6))
    ax = ax if ax is not None else fig.add_subplot()
    mech = kin.mechanism
    n = len(kin.angles)
    allpts = kin.points()
    allpts = allpts[0] if kin.variants else allpts
    joint_pts = sorted({int(p) for pair in mech.pair_points for p in pair if p >= 0})
    for p in joint_pts:
        if mech.point_link[p] != 0:
            ax.plot(allpts[:, p, 0], allpts[:, p, 1], lw=0.6, color="0.5")
    for j, i in enumerate(np.linspace(0, n, count, endpoint=False).astype(int)):
        pts = allpts[i]
        for link in range(1, mech.n_links_total):
            own = [p for p in joint_pts if mech.point_link[p] == link]
            if len(own) >= 2:
                xy = pts[own]
                ax.plot(xy[:, 0], xy[:, 1], lw=0.9, color="tab:blue", alpha=0.6)
        moving = [p for p in joint_pts if mech.point_link[p] != 0]
        if moving:
            ax.annotate(str(j), pts[moving[-1]], xytext=(3, 3), textcoords="offset points", fontsize=7)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_title(f"{mech.name}: {count} positions")
    ax.set_xlabel("x, m")
    ax.set_ylabel("y, m")
    return fig
