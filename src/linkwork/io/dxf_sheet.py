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

from linkwork.io.dxf import CAP, STYLE, _document, _save
from linkwork.scene.geometry import text_size
from linkwork.scene.style import FORCES, SCHEME, VECTORS

if TYPE_CHECKING:
    pass

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
