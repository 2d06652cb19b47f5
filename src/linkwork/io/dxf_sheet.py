"""Drawing sheets of a course project for CAD: the drawings (:mod:`linkwork.io.dxf`, :mod:`linkwork.io.dxf_forces`)
laid out on a sheet of a format of ГОСТ 2.301 with its frame and title block (основная надпись, ГОСТ 2.104
form 1), written as DXF with ezdxf.

The sheet is drawn 1:1 in millimetres of paper: the format's trimming line from (0, 0) to its width and height
(A1 841 x 594, A2 594 x 420, A3 420 x 297 landscape; A4 210 x 297 upright), the frame 20 mm from the left edge and
5 mm from the others, the title block 185 x 55 mm in the frame's lower right corner.  Each drawing is a block
of its own (``DRAWING_1``...) inserted at scale 1 in a cell of the field above and beside the title block, no
two cells overlapping: a scheme at a length scale μl of the series of ГОСТ 2.302 (1:1, 1:2, 1:2.5, 1:4, 1:5,
1:10...), a plan at a scale μ of the 1-2-2.5-5 series, each the largest that fits its cell, its title and its
scales written above it (``μl = 0,004 м/мм``; decimal commas in Russian); the title block's «Масштаб» the first
scheme's 1:N.  Text heights are those of ГОСТ 2.304 (2.5, 3.5, 5, 7 mm; the labels :data:`LABEL` mm, none under
2.5 mm on paper; no two texts covering each other, each measured on one line: :func:`text_box`); the lines those
of ГОСТ 2.303 (:func:`gost_lines`): the main lines 0.7 mm thick, the thin ones 0.25 to 0.35 mm, the dashed and
the dash-dot line thin, their strokes in mm of paper.

:func:`write_sheets` writes the sheets of the course project: ``sheet_1.dxf``, the kinematic analysis (the plan
of positions, the velocity and acceleration plans, the scheme there), ``sheet_2.dxf``, the kinetostatic analysis
(the scheme at the position of the force analysis, the force plans of the groups, Zhukovsky's lever, the legend
of the arrows) and, for a machine, ``sheet_3.dxf``, its dynamics (:mod:`linkwork.io.dxf_dynamics`); on A3 and A4,
which hold fewer drawings (:data:`CAPACITY`), the rest on the next sheets; and ``sheets.pdf``, the same sheets
drawn from their DXF documents (:mod:`linkwork.io.sheet_pdf`).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from linkwork.io.dxf import CAP, PURPOSE, STYLE, _document, _save, draw_plan, draw_positions, draw_scheme
from linkwork.lang import t
from linkwork.optional import require
from linkwork.scene.geometry import text_size
from linkwork.scene.style import FORCES, SCHEME, VECTORS

if TYPE_CHECKING:
    from linkwork.kinetostatics.force_polygons import ForcePlans
    from linkwork.kinetostatics.zhukovsky import Lever
    from linkwork.machine.steady_cycle import Dynamics
    from linkwork.motion.kinematic_analysis import Kinematics

#: Formats of ГОСТ 2.301, width x height in mm as the sheet is drawn (A4 upright, the others landscape).
FORMATS = {"A1": (841.0, 594.0), "A2": (594.0, 420.0), "A3": (420.0, 297.0), "A4": (210.0, 297.0)}
#: The frame's distance from the format's left edge (the binding) and from the other three, mm.
BINDING, EDGE = 20.0, 5.0
#: The title block of ГОСТ 2.104 form 1, mm.
BLOCK = (185.0, 55.0)
#: Text heights of ГОСТ 2.304 used, mm: the least, labels, titles, the designation.
SMALLEST, LABEL, TITLE, LARGE = 2.5, 3.5, 5.0, 7.0
#: Line weights (0.01 mm) of ГОСТ 2.303: the main line s = 0.7 mm, the thin line about s / 2.
THICK, THIN = 70, 35
#: ГОСТ 2.303's broken lines as DXF line types, on and off lengths in mm of paper ($LTSCALE 1), each replacing
#: ezdxf's line type of that name (drawn for inches, 1.27 mm strokes): the dashed line, strokes 2-8 mm long 1-2 mm
#: apart; the thin dash-dot line of axes and centres, strokes 5-30 mm long 3-5 mm apart with a dot midway.
LINETYPES = {"DASHED": (5.0, -1.5), "DASHDOT": (15.0, -1.5, 0.0, -1.5)}
#: The layers of the dynamics sheet's diagrams (:mod:`linkwork.io.dxf_dynamics`): the curves in the main line, the
#: axes and the tangents thin (the tangents dashed).
CURVES, AXES, TANGENTS = "DIAGRAMS", "AXES", "TANGENTS"
#: The layers in the thin dash-dot line: the paths of the joints' centres (the crank pin's circle is a centre line).
CENTRE_LINES = ("TRAJECTORIES",)
#: Reductions 1:N of ГОСТ 2.302 a scheme is drawn at.
REDUCTIONS = (1.0, 2.0, 2.5, 4.0, 5.0, 10.0, 15.0, 20.0, 25.0, 40.0, 50.0, 75.0, 100.0, 200.0, 400.0, 500.0, 1000.0)
#: How many drawings a sheet of each format holds; more go on the next sheet (A4: two, one above the other).
CAPACITY = {"A1": 8, "A2": 8, "A3": 4, "A4": 2}
#: Gap between two cells and between a cell and the frame, mm.
GAP = 5.0
#: Height of a drawing's heading (its title and its scales), mm.
HEADING = TITLE + LABEL + 3 * 2.0


@dataclass(frozen=True)
class TitleBlock:
    """The fields of the title block (ГОСТ 2.104 form 1), as written; empty fields stay empty.

    Attributes
    ----------
    title : str
        Графа 1, the name of the product and of the document (default: the mechanism's name).
    designation : str
        Графа 2, the document's designation (e.g. ``ТММ.КП.01.00.00``).
    organisation : str
        Графа 9, the organisation (the school and the group).
    developer, checker, norm_control, approved : str
        Surnames of who drew (Разраб.), checked (Пров.), checked the norms (Н.контр.) and approved (Утв.).
    date : str
        The date beside the developer's name.
    litera : str
        The document's letter (``У``: a student's work).
    """

    title: str = ""
    designation: str = ""
    organisation: str = ""
    developer: str = ""
    checker: str = ""
    norm_control: str = ""
    approved: str = ""
    date: str = ""
    litera: str = ""


@dataclass
class Cell:
    """A rectangle of the sheet a drawing goes in: ``[x0, y0, x1, y1]``, mm."""

    box: np.ndarray

    @property
    def size(self) -> tuple[float, float]:
        return float(self.box[2] - self.box[0]), float(self.box[3] - self.box[1])


@dataclass
class SheetDrawing:
    """One drawing of a sheet: ``draw(layout, width, height)`` draws it into a block, fitting ``width`` x
    ``height`` mm, and returns its extent (mm) and its scales' line (``μl = 0,004 м/мм``); ``title`` above it."""

    title: str
    draw: Callable[[Any, float, float], tuple[np.ndarray, str]]
    big: bool = False
    scale: str = ""  # a scheme's 1:N, for the title block's «Масштаб», set when it is drawn


@dataclass
class Placed:
    """Where a drawing went: its block's name and its box on the sheet ``[x0, y0, x1, y1]``, mm."""

    name: str
    box: np.ndarray = field(default_factory=lambda: np.zeros(4))


def number(x: float, lang: str) -> str:
    """``x`` to 4 significant digits, never with an exponent between 1e-4 and 1e7 (``10000``, ``0.0025``), with a
    decimal comma in Russian."""
    if x != 0 and not 1e-4 <= abs(x) < 1e7:
        text = f"{x:.3e}"
    else:
        decimals = 0 if x == 0 else max(0, 3 - math.floor(math.log10(abs(x))))
        text = f"{x:.{decimals}f}"
        text = text.rstrip("0").rstrip(".") if "." in text else text
    return text.replace(".", ",") if lang == "ru" else text


def nice_up(x: float, series: Sequence[float] = (1.0, 2.0, 2.5, 5.0)) -> float:
    """The least value of ``series`` times a power of ten at least ``x`` (> 0)."""
    power = 10.0 ** math.floor(math.log10(x))
    for step in (*series, 10.0):
        if step * power >= x * (1 - 1e-12):
            return step * power
    return 10.0 * power


def reduction(metres: float) -> float:
    """The least reduction 1:N of :data:`REDUCTIONS` that draws ``metres`` of the mechanism within 1 mm of paper
    (the length scale μl = N / 1000 m/mm)."""
    for n in REDUCTIONS:
        if n / 1000 >= metres:
            return n
    return nice_up(metres * 1000)


class GostSheet:
    """A DXF sheet of ``fmt`` with its frame and title block; :meth:`place` puts drawings in its field."""

    def __init__(self, fmt: str, block: TitleBlock, sheet: int, sheets: int, lang: str) -> None:
        self.width, self.height = FORMATS[fmt]
        self.fmt, self.lang = fmt, lang
        # keyed apart: the plans' and the force plans' kinds share names ("normal", "tangential"), not layers
        styles = {
            f"{what}.{kind}": s for what, d in (("s", SCHEME), ("v", VECTORS), ("f", FORCES)) for kind, s in d.items()
        }
        layers = ("FORMAT", "FRAME", "TITLE_BLOCK", "POINTS", CURVES, AXES, TANGENTS)
        self.doc, self.msp = _document(styles, extra=dict.fromkeys(layers, 7))
        self.doc.header["$LWDISPLAY"] = 1
        self.doc.header["$LTSCALE"] = 1.0
        for name, weight in (("FORMAT", THIN), ("FRAME", THICK), ("TITLE_BLOCK", THICK), (CURVES, THICK)):
            self.doc.layers.get(name).dxf.lineweight = weight
        gost_lines(self.doc)
        self.doc.layers.get(TANGENTS).dxf.linetype = "DASHED"
        self.placed: list[Placed] = []
        self._frame()
        self._title_block(block, sheet, sheets)

    @property
    def block_box(self) -> np.ndarray:
        """The title block ``[x0, y0, x1, y1]``, mm."""
        x1, y0 = self.width - EDGE, EDGE
        return np.array([x1 - BLOCK[0], y0, x1, y0 + BLOCK[1]])

    @property
    def field(self) -> np.ndarray:
        """The inside of the frame ``[x0, y0, x1, y1]``, mm."""
        return np.array([BINDING, EDGE, self.width - EDGE, self.height - EDGE])

    def _rect(self, box: Sequence[float] | np.ndarray, layer: str, weight: int | None = None) -> None:
        x0, y0, x1, y1 = (float(v) for v in box)
        attrs: dict[str, Any] = {"layer": layer}
        if weight is not None:
            attrs["lineweight"] = weight
        self.msp.add_lwpolyline([(x0, y0), (x1, y0), (x1, y1), (x0, y1)], close=True, dxfattribs=attrs)

    def _frame(self) -> None:
        self._rect([0.0, 0.0, self.width, self.height], "FORMAT")
        self._rect(self.field, "FRAME")

    def _line(self, a: tuple[float, float], b: tuple[float, float], thick: bool = True) -> None:
        x0, y0 = self.block_box[:2]
        self.msp.add_line(
            (x0 + a[0], y0 + a[1]),
            (x0 + b[0], y0 + b[1]),
            dxfattribs={"layer": "TITLE_BLOCK", "lineweight": THICK if thick else THIN},
        )

    def _word(self, text: str, at: tuple[float, float], height: float, width: float, left: bool = False) -> None:
        """A text of the title block centred at ``at`` (mm from its lower left corner; ``left``: starting
        there), ``height`` mm high, narrowed to fit ``width`` mm (never lower than :data:`SMALLEST`)."""
        if not text:
            return
        x0, y0 = self.block_box[:2]
        wide = text_size(text, height / CAP)[0]
        squeeze = min(1.0, (width - 1.0) / wide) if wide > 0 else 1.0
        add_text(self.msp, text, (x0 + at[0], y0 + at[1]), height, "TITLE_BLOCK", left=left, squeeze=squeeze)

    def _title_block(self, b: TitleBlock, sheet: int, sheets: int) -> None:
        """ГОСТ 2.104 form 1: 185 x 55 mm; the changes (4 rows and their heading), the signatures (6 rows), the
        designation (graph 2), the name (1), the material (3), the letter, mass and scale, the sheets, the
        organisation (9)."""
        self._rect(self.block_box, "TITLE_BLOCK", THICK)
        for u in (17.0, 40.0, 55.0, 65.0):
            self._line((u, 0.0), (u, 55.0))
        self._line((7.0, 30.0), (7.0, 55.0))
        for v in (5.0, 10.0, 15.0, 20.0, 25.0, 40.0, 45.0, 50.0):
            self._line((0.0, v), (65.0, v), thick=False)
        for v in (30.0, 35.0):
            self._line((0.0, v), (65.0, v))
        self._line((65.0, 40.0), (185.0, 40.0))
        self._line((135.0, 0.0), (135.0, 40.0))
        self._line((65.0, 15.0), (135.0, 15.0))
        for v in (15.0, 20.0, 35.0):
            self._line((135.0, v), (185.0, v))
        for u in (150.0, 167.0):
            self._line((u, 20.0), (u, 40.0))
        for u in (140.0, 145.0):
            self._line((u, 20.0), (u, 35.0), thick=False)
        self._line((155.0, 15.0), (155.0, 20.0))
        heads = (("Изм.", 3.5, 7.0), ("Лист", 12.0, 10.0), ("№ докум.", 28.5, 23.0), ("Подп.", 47.5, 15.0))
        for text, u, w in (*heads, ("Дата", 60.0, 10.0)):
            self._word(text, (u, 32.5), SMALLEST, w)
        roles = ("Разраб.", "Пров.", "Т.контр.", "", "Н.контр.", "Утв.")
        names = (b.developer, b.checker, "", "", b.norm_control, b.approved)
        for row, (role, name) in enumerate(zip(roles, names, strict=True)):
            v = 27.5 - 5.0 * row
            self._word(role, (1.0, v), SMALLEST, 16.0, left=True)
            self._word(name, (18.0, v), SMALLEST, 22.0, left=True)
        self._word(b.date, (60.0, 27.5), SMALLEST, 10.0)
        self._word(b.designation, (125.0, 47.5), LARGE, 120.0)
        self._name(b.title)
        for text, u, w in (("Лит.", 142.5, 15.0), ("Масса", 158.5, 17.0), ("Масштаб", 176.0, 18.0)):
            self._word(text, (u, 37.5), SMALLEST, w)
        self._word(b.litera, (137.5, 27.5), LABEL, 5.0)
        self._word(f"Лист {sheet}", (145.0, 17.5), SMALLEST, 20.0)
        self._word(f"Листов {sheets}", (170.0, 17.5), SMALLEST, 30.0)
        self._word(b.organisation, (160.0, 7.5), LABEL, 50.0)

    def _name(self, title: str) -> None:
        """Graph 1 (70 x 25 mm): the name in one line 5 mm high where it fits, else in two lines, 5 or 3.5 mm."""
        if text_size(title, TITLE / CAP)[0] <= 69.0:
            self._word(title, (100.0, 27.5), TITLE, 70.0)
            return
        words = title.split()
        cut = min(
            range(1, len(words)), key=lambda k: abs(len(" ".join(words[:k])) - len(" ".join(words[k:]))), default=1
        )
        lines = [" ".join(words[:cut]), " ".join(words[cut:])]
        size = TITLE if max(text_size(x, TITLE / CAP)[0] for x in lines) <= 69.0 else LABEL
        for line, v in zip(lines, (27.5 + 0.8 * size, 27.5 - 0.8 * size), strict=True):
            self._word(line, (100.0, v), size, 70.0)

    def _grid(self, region: np.ndarray, count: int, cols: int) -> list[Cell]:
        """``count`` cells in ``cols`` columns over ``region`` ``[x0, y0, x1, y1]`` (mm), row by row from the top,
        ``GAP`` apart; a cell that would reach into the title block stops above it."""
        if count == 0:
            return []
        x0, y0, x1, y1 = region
        rows = -(-count // cols)
        w, h = (x1 - x0 + GAP) / cols, (y1 - y0 + GAP) / rows
        top_of_block = float(self.block_box[3]) + GAP
        out = []
        for k in range(count):
            r, c = divmod(k, cols)
            box = np.array([x0 + c * w, y1 - (r + 1) * h + GAP, x0 + (c + 1) * w - GAP, y1 - r * h])
            if box[1] < top_of_block and box[2] > self.block_box[0] - GAP:
                box[1] = top_of_block
            out.append(Cell(box))
        return out

    def place(self, drawings: Sequence[SheetDrawing]) -> None:
        """Each drawing in a cell of its own, none overlapping another or the title block.  On a landscape sheet a
        ``big`` first drawing (a scheme) at the top of the field's left half, the last third of the others below
        it where it leaves a third of the height, the rest in a grid over the right half down to the title
        block; on an upright sheet every drawing in a column above the title block.  The title block's «Масштаб»
        is the first scheme's reduction (1:5)."""
        rest = list(drawings)
        x0, y0, x1, y1 = self.field + np.array([GAP, GAP, -GAP, -GAP])
        top_of_block = float(self.block_box[3]) + GAP
        if not rest:
            return
        if self.width > self.height and rest[0].big and len(rest) > 1:
            split = x0 + 0.5 * (x1 - x0)
            box = self._put(rest[0], Cell(np.array([x0, y0, split - GAP / 2, y1])))
            rest = rest[1:]
            below = np.array([x0, y0, split - GAP / 2, box[1] - GAP])
            n = max(1, len(rest) // 3) if len(rest) >= 2 and below[3] - below[1] >= (y1 - y0) / 3 else 0
            for d, cell in zip(rest[len(rest) - n :], self._grid(below, n, 1), strict=True):
                self._put(d, cell)
            rest = rest[: len(rest) - n]
            region = np.array([split + GAP / 2, top_of_block, x1, y1])
            cols = 1 if len(rest) <= 2 else 2
        else:
            region = np.array([x0, top_of_block, x1, y1])
            cols = 1 if len(rest) <= 2 or self.width < self.height else 2
        for d, cell in zip(rest, self._grid(region, len(rest), cols), strict=True):
            self._put(d, cell)
        self._word(next((d.scale for d in drawings if d.scale), ""), (176.0, 27.5), LABEL, 18.0)

    def _put(self, d: SheetDrawing, cell: Cell) -> np.ndarray:
        """Draw ``d`` into a block of its own, the largest that fits ``cell`` (its box measured by ezdxf, its texts
        included), and insert it centred across the cell, at its top; returns its box on the sheet, mm."""
        name = f"DRAWING_{len(self.placed) + 1}"
        w, h = cell.size
        across, down = 1.0, 1.0  # each shrunk where the drawing overflows: its texts do not shrink with it
        for _ in range(8):
            if name in self.doc.blocks:
                self.doc.blocks.delete_block(name, safe=False)
            block = self.doc.blocks.new(name=name)
            box = self._drawn(block, d, across * w, down * h)
            wide, tall = (box[2] - box[0]) / w, (box[3] - box[1]) / h
            if max(wide, tall) <= 1:
                break
            across *= 0.97 / wide if wide > 1 else 1.0
            down *= 0.97 / tall if tall > 1 else 1.0
        shift = np.array([(cell.box[0] + cell.box[2]) / 2 - (box[0] + box[2]) / 2, cell.box[3] - box[3]])
        self.msp.add_blockref(name, tuple(shift), dxfattribs={"layer": "0"})
        self.placed.append(Placed(name, box + np.r_[shift, shift]))
        return self.placed[-1].box

    def _drawn(self, block: Any, d: SheetDrawing, w: float, h: float) -> np.ndarray:
        """Draw ``d`` into ``block`` within ``w`` x ``h`` mm with its heading; returns its box (:func:`drawn_box`)."""
        box, scales = d.draw(block, w, h - HEADING)
        left, top = float(box[0]), float(box[3]) + 2.0
        if scales:
            add_text(
                block, scales, (left, top + LABEL / 2), LABEL, "NOTES", left=True, squeeze=_squeeze(scales, LABEL, w)
            )
        size = TITLE if text_size(d.title, TITLE / CAP)[0] <= w else LABEL  # a narrow cell's title smaller
        at = (left, top + LABEL + 2.0 + size / 2)
        add_text(block, d.title, at, size, "NOTES", left=True, squeeze=_squeeze(d.title, size, w))
        return drawn_box(block)

    def save(self, path: str | Path) -> Path:
        return _save(self.doc, path)


#: MTEXT's attachment points (1 top left ... 9 bottom right) as the alignments of a TEXT.
ATTACHMENT = dict(
    enumerate(("TOP_LEFT", "TOP_CENTER", "TOP_RIGHT", "MIDDLE_LEFT", "MIDDLE_CENTER", "MIDDLE_RIGHT"), start=1)
) | {7: "BOTTOM_LEFT", 8: "BOTTOM_CENTER", 9: "BOTTOM_RIGHT"}


def text_box(entity: Any) -> np.ndarray:
    """The box ``[x0, y0, x1, y1]`` (mm) of a TEXT or a one-line MTEXT as drawn: an MTEXT measured as the TEXT of
    its plain text (its subscripts inline) in its style, height and place (ezdxf measures an MTEXT without a column
    width as though it broke the line at every space, which a CAD program does not)."""
    from ezdxf import bbox
    from ezdxf.entities import Text
    from ezdxf.enums import TextEntityAlignment

    if entity.dxftype() == "MTEXT":
        dxf = entity.dxf
        text = Text.new(dxfattribs={"style": dxf.style, "height": dxf.char_height, "layer": dxf.layer})
        text.doc = entity.doc
        text.dxf.text = entity.plain_text(split=False).replace("^", "")
        align = TextEntityAlignment[ATTACHMENT.get(dxf.attachment_point, "TOP_LEFT")]
        text.set_placement(dxf.insert, align=align)
        entity = text
    found = bbox.extents([entity], fast=False)
    return np.array([found.extmin.x, found.extmin.y, found.extmax.x, found.extmax.y])


def drawn_box(entities: Any) -> np.ndarray:
    """The box ``[x0, y0, x1, y1]`` (mm) of ``entities`` (a block, a layout), each text as :func:`text_box`."""
    from ezdxf import bbox

    items = list(entities)
    lines = [e for e in items if e.dxftype() not in ("TEXT", "MTEXT")]
    boxes = [text_box(e) for e in items if e.dxftype() in ("TEXT", "MTEXT")]
    if lines:
        found = bbox.extents(lines)
        if found.has_data:
            boxes.append(np.array([found.extmin.x, found.extmin.y, found.extmax.x, found.extmax.y]))
    every = np.array(boxes)
    return np.r_[every[:, :2].min(0), every[:, 2:].max(0)]


def gost_lines(doc: Any) -> None:
    """The lines of ГОСТ 2.303 in ``doc``: the line types :data:`LINETYPES`, every dashed layer in the dashed line,
    :data:`CENTRE_LINES` in the dash-dot line, these and a layer that gives no weight the thin line's."""
    for name, pattern in LINETYPES.items():
        if name in doc.linetypes:
            doc.linetypes.remove(name)
        total = float(sum(abs(x) for x in pattern))
        doc.linetypes.add(name, pattern=[total, *pattern], description=f"ГОСТ 2.303 {name.lower()}")
    for layer in doc.layers:
        if layer.dxf.name in CENTRE_LINES:
            layer.dxf.linetype = "DASHDOT"
        elif layer.dxf.linetype.startswith("LW_"):
            layer.dxf.linetype = "DASHED"
        if layer.dxf.lineweight < 0 or layer.dxf.linetype != "Continuous":  # a broken line is a thin one
            layer.dxf.lineweight = min(THIN, layer.dxf.lineweight) if layer.dxf.lineweight > 0 else THIN
    for name in [lt.dxf.name for lt in doc.linetypes if lt.dxf.name.startswith("LW_")]:
        doc.linetypes.remove(name)


def add_text(
    layout: Any,
    text: str,
    at: tuple[float, float] | np.ndarray,
    height: float,
    layer: str,
    left: bool = False,
    squeeze: float = 1.0,
) -> None:
    """A TEXT ``height`` mm high (of its capitals) centred at ``at`` (``left``: starting there), ``squeeze`` its
    width factor."""
    from ezdxf.enums import TextEntityAlignment

    entity = layout.add_text(
        text, height=height, dxfattribs={"layer": layer, "style": STYLE, "width": max(0.7, float(squeeze))}
    )
    align = TextEntityAlignment.MIDDLE_LEFT if left else TextEntityAlignment.MIDDLE_CENTER
    entity.set_placement((float(at[0]), float(at[1])), align=align)


def _squeeze(text: str, height: float, width: float) -> float:
    """The width factor (down to 0.7, ГОСТ 2.304's narrow type) that fits ``text`` ``height`` mm high in
    ``width`` mm."""
    wide = text_size(text, height / CAP)[0]
    return 1.0 if wide <= width else max(0.7, width / wide)


def _metres(lang: str) -> str:
    return t("sheet.m_per_mm", lang)


def scheme_drawing(
    title: str, draw: Callable[..., np.ndarray], extent: np.ndarray, lang: str, em: float
) -> SheetDrawing:
    """A drawing of a scheme of ``extent`` (m, ``[x0, y0, x1, y1]``) drawn by ``draw(layout, mm=, em=)`` at the
    largest reduction of ГОСТ 2.302 that fits; its labels :data:`LABEL` mm high, or lower, down to
    :data:`SMALLEST`, where the reduction draws the font size ``em`` (m) their places were found for smaller."""
    span = np.asarray(extent[2:] - extent[:2], dtype=float)
    drawing = SheetDrawing(title, lambda layout, w, h: (np.zeros(4), ""), big=True)

    def fit(layout: Any, w: float, h: float) -> tuple[np.ndarray, str]:
        n = reduction(max(span[0] / w, span[1] / h) * 1.08)
        size = min(LABEL, max(SMALLEST, CAP * em * 1000.0 / n))  # the labels as large as their places allow
        box = draw(layout, mm=1000.0 / n, em=size / CAP)
        drawing.scale = f"1:{number(n, lang)}"
        return box, f"μl = {number(n / 1000, lang)} {_metres(lang)}"

    drawing.draw = fit
    return drawing


def _fitted(
    build: Callable[[float], Any], extent: Callable[[Any], np.ndarray], start: float, w: float, h: float
) -> Any:
    """The scene ``build(scale)`` at the least scale of the 1-2-2.5-5 series (the largest drawing) whose
    ``extent`` fits ``w`` x ``h`` mm, searched from ``start``."""
    scale = nice_up(start)
    scene = build(scale)
    best = None
    for _ in range(12):
        ratio = _ratio(extent(scene), w, h)
        if ratio <= 1:
            best = scene
            smaller = nice_up(scale * ratio * 1.01)
            if smaller >= scale:
                return scene
            scale = smaller
        else:
            if best is not None:
                return best
            scale = nice_up(scale * ratio * 1.01)
        scene = build(scale)
    return best if best is not None else scene


def _ratio(box: np.ndarray, w: float, h: float) -> float:
    return float(max((box[2] - box[0]) / w, (box[3] - box[1]) / h))


def plan_drawing(kin: Kinematics, index: int, kind: str, title: str, lang: str) -> SheetDrawing:
    """The velocity (``kind`` ``"velocity"``) or acceleration plan of sample ``index`` of ``kin``."""
    from linkwork.motion.plans import plan_series
    from linkwork.scene.plans import plan_scale, plan_scene

    series = plan_series(kin)[0 if kind == "velocity" else 1]
    valid = np.asarray(kin.valid_all[0])

    def fit(layout: Any, w: float, h: float) -> tuple[np.ndarray, str]:
        def build(scale: float) -> Any:
            return plan_scene(series, [index], scale=scale, em=LABEL / CAP, valid=valid, lang=lang)

        scene = _fitted(build, lambda s: s.extent(0), plan_scale(series, [index]), w, h)
        box = draw_plan(layout, scene, 0)
        unit = t(f"plan.unit.{kind}", lang)
        return box, f"{scene.symbol} = {number(scene.scale, lang)} {unit}"

    return SheetDrawing(title, fit)


def force_plan_drawing(plans: ForcePlans, group: int, index: int, title: str, lang: str) -> SheetDrawing:
    """The force plan of the ``group``-th group of ``plans`` at sample ``index``."""
    from linkwork.io.dxf_forces import _draw, _short
    from linkwork.scene.force_plans import force_plan_scene

    g = plans.groups[group]
    angle = float(plans.forces.angles[index])

    def fit(layout: Any, w: float, h: float) -> tuple[np.ndarray, str]:
        def build(scale: float) -> Any:
            return force_plan_scene(g, index, lang=lang, scale=scale, em=LABEL / CAP, angle=angle)

        scene = _fitted(build, lambda s: s.extent(), g.scale(index), w, h - 2 * LABEL)
        _draw(layout, scene, np.zeros(2))
        _short(layout, scene, np.zeros(2), lang, width=0.85 * (w - 2.0), em=SMALLEST / CAP)  # room for the font
        return scene.extent(), f"μF = {number(scene.scale, lang)} {t('sheet.n_per_mm', lang)}"

    return SheetDrawing(title, fit)


def lever_drawing(lv: Lever, kin: Kinematics, index: int, title: str, lang: str) -> SheetDrawing:
    """Zhukovsky's lever at sample ``index`` of ``kin``: the turned velocity plan at a scale μv that fits."""
    from linkwork.io.dxf_forces import _draw, _short
    from linkwork.motion.plans import plan_series
    from linkwork.scene.force_plans import lever_scene
    from linkwork.scene.plans import plan_scale

    series = plan_series(kin)[0]

    def fit(layout: Any, w: float, h: float) -> tuple[np.ndarray, str]:
        first = lever_scene(lv, series, index, lang=lang, em=LABEL / CAP)
        ratio = first.scale / first.plan_scale  # the forces shrink with the plan: (N/mm) / ((m/s)/mm)

        def build(scale: float) -> Any:
            return lever_scene(
                lv, series, index, lang=lang, em=LABEL / CAP, plan_scale=scale, scale=nice_up(ratio * scale)
            )

        scene = _fitted(build, lambda s: s.extent(), plan_scale(series, [index]), w, h - 2 * LABEL)
        _draw(layout, scene, np.zeros(2))
        _short(layout, scene, np.zeros(2), lang, width=0.85 * (w - 2.0), em=SMALLEST / CAP)  # room for the font
        unit = t("plan.unit.velocity", lang)
        scales = f"μv = {number(scene.plan_scale, lang)} {unit};  μF = {number(scene.scale, lang)} "
        return scene.extent(), scales + t("sheet.n_per_mm", lang)

    return SheetDrawing(title, fit)


def legend_drawing(plans: ForcePlans, index: int, lang: str) -> SheetDrawing:
    """The legend of the force plans at sample ``index``: for each kind of arrow drawn, a stroke on its layer (the
    reactions read off a plan dashed, as drawn), its name and the names of the arrows of that kind (a process
    load also by the file's name of it), so that no meaning rests on colour alone."""
    from linkwork.io.dxf import _head
    from linkwork.lang import t as text
    from linkwork.scene.force_plans import FORCE_KINDS, force_plan_scene

    names: dict[tuple[str, bool], list[str]] = {}  # (kind, dashed): the arrows' names
    for g in plans.groups:
        for a in force_plan_scene(g, index, lang=lang).arrows:
            key = (a.kind, a.resultant or a.kind == "internal")
            if a.text and a.text not in names.setdefault(key, []):
                names[key].append(a.text)
    loads = [ld.name for ld in plans.forces.mechanism.loads if ld.kind == "process"]

    def fit(layout: Any, w: float, h: float) -> tuple[np.ndarray, str]:
        rows = [k for kind in FORCE_KINDS for k in ((kind, False), (kind, True)) if k in names]
        lines = []
        for row, (kind, dashed) in enumerate(rows):
            y = -row * 2.2 * LABEL
            layer = FORCES[kind].layer
            layout.add_line(
                (0.0, y),
                (15.0, y),
                dxfattribs={"layer": layer, **({"linetype": "DASHED", "lineweight": THIN} if dashed else {})},
            )
            _head(layout, np.array([0.0, y]), np.array([15.0, y]), 3.0, layer)
            what = text(f"force.{kind}", lang) + (f" ({', '.join(loads)})" if kind == "load" and loads else "")
            if dashed and kind != "internal":
                what += text("sheet.read_off", lang)
            lines.append(f"{what}: {', '.join(names[(kind, dashed)])}")
            add_text(layout, lines[-1], (20.0, y), LABEL, "LABELS", left=True)
        wide = max((text_size(line, LABEL / CAP)[0] for line in lines), default=0.0)
        return np.array([0.0, -(len(rows) - 1) * 2.2 * LABEL - LABEL, 20.0 + wide, LABEL]), ""

    return SheetDrawing(t("sheet.legend", lang), fit)


def kinematics_drawings(twelve: Kinematics, position: int, cycle: Kinematics, lang: str) -> list[SheetDrawing]:
    """The drawings of the kinematic analysis: the plan of the twelve positions, the velocity and acceleration
    plans of ``position`` and the kinematic scheme there (on a landscape sheet under the plan of positions)."""
    from linkwork.scene.positions import positions_scene
    from linkwork.scene.scheme import scheme_scene

    scene = positions_scene(twelve, cycle=cycle, lang=lang)
    at = scheme_scene(twelve, at=[position], cycle=cycle)
    where = t("at_position", lang, position=position)
    drawings = [
        scheme_drawing(
            t("sheet.positions", lang, count=len(twelve.angles)),
            lambda layout, mm, em: draw_positions(layout, scene, mm=mm, em=em),
            scene.extent(),
            lang,
            scene.scheme.em,
        ),
        plan_drawing(twelve, position, "velocity", t("sheet.velocity", lang) + where, lang),
        plan_drawing(twelve, position, "acceleration", t("sheet.acceleration", lang) + where, lang),
        scheme_drawing(
            t("sheet.scheme", lang) + where,
            lambda layout, mm, em: draw_scheme(layout, at, position, trajectories=False, mm=mm, em=em),
            at.extent(position),
            lang,
            at.em,
        ),
    ]
    return drawings


def kinetostatics_drawings(
    plans: ForcePlans, lv: Lever, index: int, named: str, cycle: Kinematics, lang: str
) -> list[SheetDrawing]:
    """The drawings of the kinetostatic analysis at sample ``index`` of ``plans`` (``named``: its position, for
    the titles): the scheme there, each group's force plan, Zhukovsky's lever, the legend of the arrows."""
    from linkwork.lang import group_label
    from linkwork.scene.scheme import scheme_scene

    kin = plans.forces.kinematics
    scene = scheme_scene(kin, at=[index], cycle=cycle)
    where = t("at_position", lang, position=named)
    drawings = [
        scheme_drawing(
            t("sheet.scheme", lang) + where,
            lambda layout, mm, em: draw_scheme(layout, scene, index, trajectories=False, mm=mm, em=em),
            scene.extent(index),
            lang,
            scene.em,
        )
    ]
    for j, g in enumerate(plans.groups):
        label = group_label(g.label, lang)
        title = t("forceplans.driving", lang, group=label) if g.balancing is not None else label
        drawings.append(force_plan_drawing(plans, j, index, t("sheet.force_plan", lang, group=title), lang))
    drawings.append(lever_drawing(lv, kin, index, t("sheet.lever", lang), lang))
    drawings.append(legend_drawing(plans, index, lang))
    return drawings


def _titled(block: TitleBlock, name: str, what: str) -> TitleBlock:
    """``block`` with graph 1 filled: the file's title, else the mechanism's name, and the sheet's content."""
    import dataclasses

    return dataclasses.replace(block, title=f"{block.title or name}. {what}")


def sheet_options(mech: Any) -> tuple[str, TitleBlock]:
    """The format and the title block of the sheets of ``mech``: its file's ``drawing.sheet`` and
    ``drawing.title_block`` (A1 and empty fields where it gives none)."""
    drawing = getattr(mech.spec, "drawing", None) if mech.spec is not None else None
    if drawing is None:
        return "A1", TitleBlock()
    return drawing.sheet, TitleBlock(**drawing.title_block.model_dump())


def write_sheets(
    twelve: Kinematics,
    position: int,
    cycle: Kinematics,
    plans: ForcePlans,
    lever: Lever,
    index: int,
    named: str,
    folder: str | Path,
    lang: str = "en",
    fmt: str = "A1",
    block: TitleBlock | None = None,
    dynamics: Dynamics | None = None,
    pdf: bool = True,
) -> list[Path]:
    """The sheets of the kinematic analysis at ``position`` of ``twelve``, of the kinetostatic analysis at sample
    ``index`` of ``plans`` and ``lever`` (``named`` in the titles) and of the ``dynamics`` (where given: the
    steady cycle of :func:`linkwork.dynamics`) on format ``fmt`` with the title block ``block``, ``sheet_1.dxf``,
    ``sheet_2.dxf``... into ``folder`` (on A1 and A2 one sheet each, on A3 four drawings a sheet, on A4 two:
    :data:`CAPACITY`), numbered in their title blocks, and (``pdf``) the same sheets drawn as the pages of
    ``sheets.pdf`` (:func:`linkwork.io.sheet_pdf.write_pdf`); returns their paths."""
    require("ezdxf", purpose=PURPOSE)
    block = block or TitleBlock()
    name = twelve.mechanism.name
    parts = [
        (t("sheet.kinematics", lang), kinematics_drawings(twelve, position, cycle, lang)),
        (t("sheet.kinetostatics", lang), kinetostatics_drawings(plans, lever, index, named, cycle, lang)),
    ]
    if dynamics is not None:
        from linkwork.io.dxf_dynamics import dynamics_drawings

        parts.append((t("sheet.dynamics", lang), dynamics_drawings(dynamics, lang)))
    pages = [(what, d[k : k + CAPACITY[fmt]]) for what, d in parts for k in range(0, len(d), CAPACITY[fmt])]
    sheets, out = [], []
    for number_, (what, drawings) in enumerate(pages, start=1):
        sheet = GostSheet(fmt, _titled(block, name, what), number_, len(pages), lang)
        sheet.place(drawings)
        sheets.append(sheet)
        out.append(sheet.save(Path(folder) / f"sheet_{number_}.dxf"))
    if pdf:
        from linkwork.io.sheet_pdf import write_pdf

        out.append(write_pdf(sheets, Path(folder) / "sheets.pdf"))
    return out
