"""Drawings of a mechanism as data: one scene, built once from the results, drawn by every renderer.

The kinematic scheme (:func:`scheme_scene`), the plan of positions and the velocity and acceleration
plans are described here as outlines, circles, vectors of named kinds and placed labels, in metres (the
scheme) or millimetres of the sheet (the plans), with NumPy only; :mod:`linkwork.figures` draws them
with matplotlib, the viewer's page as SVG and :mod:`linkwork.io.dxf` as DXF for CAD.
"""

from __future__ import annotations

from linkwork.scene.scheme import Item, Label, SchemeScene, scheme_scene

__all__ = ["Item", "Label", "SchemeScene", "scheme_scene"]
