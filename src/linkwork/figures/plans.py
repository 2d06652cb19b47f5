"""Velocity and acceleration plans drawn as the graphical method draws them.

The drawing is in millimetres of the sheet: a vector ``u`` of the plan is drawn
``u / scale`` mm long (``scale`` in units per mm, written on the sheet as
``mu_v`` or ``mu_a``).  The pole ``p`` is at the origin; every point's
absolute vector ends at its lower-case letter; the relative vectors of the
construction (rotation, normal and tangential, transport, Coriolis, sliding)
are drawn between plan points in their own styles.  Each drawn vector is a
line whose ``gid`` is ``"kind:start->end"`` (tests read them back).
"""

from __future__ import annotations

from typing import Any

import numpy as np

STYLE = {
    "absolute": {"color": "black", "lw": 1.6},
    "rotation": {"color": "tab:blue", "lw": 1.1},
    "normal": {"color": "tab:green", "lw": 1.1},
    "tangential": {"color": "tab:blue", "lw": 1.1},
    "transport": {"color": "tab:purple", "lw": 1.1, "ls": "--"},
    "coriolis": {"color": "tab:red", "lw": 1.1},
    "sliding": {"color": "tab:orange", "lw": 1.1},
}


def _arrow(ax: Any, start: np.ndarray, end: np.ndarray, kind: str, gid: str) -> None:
    style = STYLE.get(kind, STYLE["rotation"])
    (line,) = ax.plot([start[0], end[0]], [start[1], end[1]], **style)
    line.set_gid(gid)
    d = end - start
    size = float(np.hypot(*d))
    if size > 0:
        head = min(3.0, 0.3 * size)
        u = d / size
        w = np.array([-u[1], u[0]])
        tip = np.array([end, end - head * u + 0.35 * head * w, end - head * u - 0.35 * head * w])
        ax.fill(tip[:, 0], tip[:, 1], color=style["color"], lw=0)


def draw_plan(plan: Any, ax: Any = None) -> Any:
    """Draw a :class:`~linkwork.motion.plans.Plan`; returns the matplotlib Figure."""
    from matplotlib.figure import Figure

    fig = ax.figure if ax is not None else Figure(figsize=(6, 6))
    ax = ax if ax is not None else fig.add_subplot()
    scale = plan.scale
    at = {label: np.asarray(vec, dtype=float) / scale for label, vec in plan.points.items()}
    at["p"] = np.zeros(2)
    for label, pos in at.items():
        if label != "p" and np.hypot(*pos) > 0:
            _arrow(ax, np.zeros(2), pos, "absolute", f"absolute:p->{label}")
    known = dict(at)
    for vec in plan.vectors:
        start = known.get(vec.start)
        if start is None:
            continue
        end = start + np.asarray(vec.vector, dtype=float) / scale
        known.setdefault(vec.end, end)
        _arrow(ax, start, end, vec.kind, f"{vec.kind}:{vec.start}->{vec.end}")
    for label, pos in known.items():
        ax.plot(*pos, "o", color="black", ms=2.5)
        ax.annotate(label, pos, xytext=(3, 3), textcoords="offset points", fontsize=9)
    unit = "(m/s)/mm" if plan.kind == "velocity" else "(m/s²)/mm"
    mu = "μ_v" if plan.kind == "velocity" else "μ_a"
    ax.set_title(f"{plan.kind} plan at {np.degrees(plan.angle) % 360:.1f}°;  {mu} = {scale:g} {unit}")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("mm")
    ax.set_ylabel("mm")
    ax.grid(True, lw=0.3, alpha=0.5)
    return fig


def velocity_plan(kin: Any, index: int, ax: Any = None) -> Any:
    """The velocity plan of sample ``index`` of a kinematics result."""
    from linkwork.motion.plans import plans

    return draw_plan(plans(kin, index)[0], ax)


def acceleration_plan(kin: Any, index: int, ax: Any = None) -> Any:
    """The acceleration plan of sample ``index`` of a kinematics result."""
    from linkwork.motion.plans import plans

    return draw_plan(plans(kin, index)[1], ax)
