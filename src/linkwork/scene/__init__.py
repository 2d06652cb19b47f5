"""Drawings of a mechanism as data: one scene, built once from the results, drawn by every renderer.

The kinematic scheme (:func:`scheme_scene`), the plan of positions (:func:`positions_scene`) and the
velocity and acceleration plans (:func:`plan_scene`) are described here as outlines, circles, vectors of
named kinds and placed labels, in metres (the scheme) or millimetres of the sheet (the plans), with NumPy
only; :mod:`linkwork.figures` draws them with matplotlib, the viewer's page as SVG (from the payload of
:mod:`linkwork.web.payload`) and :mod:`linkwork.io.dxf` as DXF for CAD.  Which positions the plans are
drawn for: :func:`plan_positions`.
"""

from __future__ import annotations

from linkwork.scene.plans import Arrow, PlanScene, plan_scene
from linkwork.scene.positions import (
    PositionsScene,
    best_position,
    plan_positions,
    position_angles,
    positions_scene,
    working_point,
)
from linkwork.scene.scheme import Element, Item, Label, SchemeScene, scheme_scene

__all__ = [
    "Arrow",
    "Element",
    "Item",
    "Label",
    "PlanScene",
    "PositionsScene",
    "SchemeScene",
    "best_position",
    "plan_positions",
    "plan_scene",
    "position_angles",
    "positions_scene",
    "scheme_scene",
    "working_point",
]
