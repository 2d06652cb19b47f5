"""The drawing sheets of a course project as a PDF: each sheet's DXF document
(:class:`~linkwork.io.dxf_sheet.GostSheet`) drawn by ezdxf's drawing add-on with matplotlib on a page of the sheet's
format, 1:1 in millimetres of paper.

The PDF does not lay the sheet out again: it draws the very entities of the DXF (the frame, the title block, each
drawing's block where it was placed), so that the two cannot differ.  The lines keep their DXF line weights in
millimetres of paper (ГОСТ 2.303: 0.7 mm, 0.35 mm) and their line types (dashed, dash-dot), the texts their heights
(ГОСТ 2.304), the layers their colours on white paper.  The file is written atomically: a failure leaves no
half-written PDF.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from linkwork.atomic import write_atomic
from linkwork.optional import require

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from linkwork.io.dxf_sheet import GostSheet

PURPOSE = "the PDF of the drawing sheets (linkwork analyze --dxf)"

#: Points (1/72 in) in a millimetre: ezdxf's matplotlib backend takes a line weight in mm as a width in points.
POINTS_PER_MM = 72.0 / 25.4


def write_pdf(sheets: Sequence[GostSheet], path: str | Path) -> Path:
    """The ``sheets`` as the pages of one PDF at ``path``, each page the size of its format (A1 841 x 594 mm);
    returns the path."""
    require("matplotlib", "ezdxf", purpose=PURPOSE)
    from matplotlib.backends.backend_pdf import PdfPages

    def write(tmp: Path) -> None:
        with PdfPages(tmp, metadata={"Creator": "linkwork"}) as pdf:
            for sheet in sheets:
                pdf.savefig(page(sheet))

    return write_atomic(path, write)


def page(sheet: GostSheet) -> Figure:
    """The figure of ``sheet``: its format's size in inches, one axes over it whose unit is a millimetre of paper,
    the sheet's modelspace drawn in it by ezdxf (line weights in mm, line types as the DXF's, white paper)."""
    from ezdxf.addons.drawing import Frontend, RenderContext
    from ezdxf.addons.drawing.config import BackgroundPolicy, Configuration, LineweightPolicy
    from ezdxf.addons.drawing.matplotlib import MatplotlibBackend
    from matplotlib.figure import Figure

    width, height = sheet.width, sheet.height
    fig = Figure(figsize=(width / 25.4, height / 25.4))
    ax = fig.add_axes((0.0, 0.0, 1.0, 1.0))
    config = Configuration(
        lineweight_policy=LineweightPolicy.ABSOLUTE,
        lineweight_scaling=POINTS_PER_MM,
        background_policy=BackgroundPolicy.WHITE,
    )
    backend: Any = MatplotlibBackend(ax, adjust_figure=False)
    Frontend(RenderContext(sheet.doc), backend, config=config).draw_layout(sheet.doc.modelspace(), finalize=True)
    ax.set_xlim(0.0, width)
    ax.set_ylim(0.0, height)
    ax.set_aspect("equal")
    ax.set_axis_off()
    return fig
