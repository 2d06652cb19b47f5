"""How each kind of item and vector looks, for every renderer: colour, line width, fill, dashes and the
DXF layer it goes on (the viewer's stylesheet, ``web/static/viewer.css``, gives the same look to the
SVG classes of the same names)."""

from __future__ import annotations

from dataclasses import dataclass

BLUE = "#1f5fa8"


@dataclass(frozen=True)
class Style:
    """The look of one kind.

    Attributes
    ----------
    colour : str
        Of the line (``#rrggbb``).
    width : float
        Line width, points (1/72 in) on paper.
    fill : str or None
        Fill colour of an outline or circle; None for none.
    alpha : float
        Opacity of the fill.
    dash : tuple of float
        On and off lengths in points; empty for a solid line.
    layer : str
        The DXF layer.
    aci : int
        The DXF layer's colour (AutoCAD colour index), one a CAD program shows on a black screen and on white
        paper alike (7: black on white, white on black); each plan's kinds of vector apart.
    """

    colour: str
    width: float
    fill: str | None = None
    alpha: float = 1.0
    dash: tuple[float, ...] = ()
    layer: str = "0"
    aci: int = 7


#: The scheme's items (:data:`linkwork.scene.scheme.KINDS`).
SCHEME = {
    "path": Style("#999999", 0.7, dash=(3.0, 2.0), layer="TRAJECTORIES", aci=8),
    "workpiece": Style("#777777", 0.6, layer="WORKPIECE", aci=8),
    "hatch": Style("#000000", 0.6, layer="HATCHING"),
    "support": Style("#000000", 0.9, layer="SUPPORTS"),
    "guide": Style("#000000", 0.9, layer="GUIDES"),
    "bar": Style(BLUE, 2.2, layer="LINKS", aci=150),
    "plate": Style(BLUE, 2.2, fill=BLUE, alpha=0.18, layer="LINKS", aci=150),
    "tool": Style("#000000", 0.9, fill="#d9d9d9", layer="TOOLS"),
    "edge": Style("#000000", 2.0, layer="TOOLS"),
    "block": Style("#000000", 1.1, fill="#ffffff", layer="BLOCKS"),
    "pivot": Style("#000000", 1.1, fill="#ffffff", layer="PIVOTS"),
    "marker": Style(BLUE, 0.5, fill=BLUE, layer="MARKERS", aci=150),
    "spring": Style("#000000", 0.9, layer="SPRINGS"),  # the force elements (:class:`~linkwork.scene.Element`)
    "damper": Style("#000000", 0.9, layer="DAMPERS"),
}

#: The plans' vectors (:data:`linkwork.scene.plans.KINDS`).
VECTORS = {
    "absolute": Style("#000000", 1.4, layer="ABSOLUTE"),
    "rotation": Style("#1f77b4", 1.0, layer="ROTATION", aci=150),
    "normal": Style("#2ca02c", 1.0, layer="NORMAL", aci=3),
    "tangential": Style("#1f77b4", 1.0, dash=(4.0, 1.5), layer="TANGENTIAL", aci=140),
    "transport": Style("#9467bd", 1.0, dash=(3.0, 2.0), layer="TRANSPORT", aci=200),
    "coriolis": Style("#d62728", 1.0, layer="CORIOLIS", aci=1),
    "sliding": Style("#ff7f0e", 1.0, layer="SLIDING", aci=30),
}

#: Colours of the texts: a point's name, a link's number, a construction point of a plan.
TEXT = {"point": "#111111", "frame": "#111111", "link": BLUE, "position": "#111111", "minor": "#777777"}

#: The force plans' and the lever's arrows (:data:`linkwork.scene.force_plans.FORCE_KINDS`); a reaction read off
#: a plan is drawn in its kind's colour, dashed.
FORCES = {
    "weight": Style("#8c564b", 1.2, layer="WEIGHTS"),
    "inertia": Style("#d62728", 1.2, layer="INERTIA"),
    "load": Style("#000000", 1.6, layer="LOADS"),
    "known": Style("#9467bd", 1.2, layer="KNOWN_REACTIONS"),
    "tangential": Style("#1f77b4", 1.2, layer="TANGENTIAL_R"),
    "normal": Style("#2ca02c", 1.2, layer="NORMAL_R"),
    "reaction": Style("#ff7f0e", 1.4, layer="REACTIONS"),
    "internal": Style("#17becf", 1.2, dash=(4.0, 2.0), layer="INNER_REACTIONS"),
    "balancing": Style("#e377c2", 1.6, layer="BALANCING"),
    "lever": Style("#999999", 0.6, layer="LEVER"),
}
