"""Drawings of the results (matplotlib, ``pip install "linkwork[plot]"``): the kinematic scheme,
the plan of positions, velocity and acceleration plans, and diagrams against the crank angle.

Every function takes public results and returns a matplotlib ``Figure`` (no pyplot state), to
show, save (``fig.savefig("scheme.svg")``) or embed.
"""

from __future__ import annotations

from linkwork.figures.animation import animate
from linkwork.figures.diagrams import (
    dynamics_diagrams,
    foundation_diagram,
    hodograph,
    kinematic_diagrams,
    link_angles,
    motion_diagram,
    run_diagram,
    torque_diagram,
)
from linkwork.figures.plans import acceleration_plan, draw_plan, plan_sheet, velocity_plan
from linkwork.figures.scheme import draw_limits, draw_positions, draw_scheme
from linkwork.optional import require

require("matplotlib", purpose="the drawings (linkwork.figures)")

__all__ = [
    "acceleration_plan",
    "animate",
    "draw_plan",
    "draw_limits",
    "draw_positions",
    "draw_scheme",
    "dynamics_diagrams",
    "run_diagram",
    "foundation_diagram",
    "hodograph",
    "kinematic_diagrams",
    "link_angles",
    "motion_diagram",
    "plan_sheet",
    "torque_diagram",
    "velocity_plan",
]
