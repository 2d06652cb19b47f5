"""A mechanism in a Jupyter notebook shows itself as its kinematic scheme (SVG), once this extension is loaded::

    %load_ext linkwork.figures.notebook

IPython then draws a :class:`~linkwork.structure.model.Mechanism` left as the last line of a cell with
:func:`scheme_svg`.  The display is registered here, at the edge, by the class's name: the core, where
``Mechanism`` lives, imports no drawing package.
"""

from __future__ import annotations

import io
from typing import Any

from linkwork.figures.scheme import draw_scheme
from linkwork.motion.analysis import position_angles, zero_angle
from linkwork.motion.kinematic_analysis import kinematics
from linkwork.motion.tables import moving_links
from linkwork.structure.model import Mechanism

#: How many samples of the turn place the scheme's labels clear of the links' paths (as the report's scheme).
CYCLE_STEPS = 72


def scheme_svg(mech: Mechanism) -> str:
    """The kinematic scheme of ``mech`` at position 0, as the report draws it, with a key under it that names
    each link by its number; SVG text (the texts as SVG text, selectable)."""
    import matplotlib

    zero = zero_angle(mech)
    twelve = kinematics(mech, position_angles(mech, 12, zero))
    cycle = kinematics(mech, position_angles(mech, CYCLE_STEPS, zero))
    fig = draw_scheme(twelve, 0, position=0, cycle=cycle)
    key = "   ".join(f"{i} {name}" for name, i in moving_links(mech))
    fig.text(0.5, 0.01, key, ha="center", va="bottom", fontsize=9)
    out = io.StringIO()
    with matplotlib.rc_context({"svg.fonttype": "none", "svg.hashsalt": "linkwork"}):
        fig.savefig(out, format="svg", metadata={"Date": None})
    return out.getvalue()


def load_ipython_extension(ipython: Any) -> None:
    """Show every :class:`~linkwork.structure.model.Mechanism` as :func:`scheme_svg` (``%load_ext``)."""
    svg = ipython.display_formatter.formatters["image/svg+xml"]
    svg.for_type_by_name("linkwork.structure.model", "Mechanism", scheme_svg)


def unload_ipython_extension(ipython: Any) -> None:
    """Take the display of :func:`load_ipython_extension` off again (``%unload_ext``)."""
    svg = ipython.display_formatter.formatters["image/svg+xml"]
    svg.deferred_printers.pop(("linkwork.structure.model", "Mechanism"), None)
    svg.type_printers.pop(Mechanism, None)
