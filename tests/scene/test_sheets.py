"""The drawing sheets of a course project (``analyze --dxf``): formats of ГОСТ 2.301 with their frame and title
block (ГОСТ 2.104 form 1), text of ГОСТ 2.304, each drawing in a place of its own with its scales, read back
from the DXF with ezdxf."""

from __future__ import annotations

import functools
import itertools
import re

import numpy as np
import pytest

import linkwork as lw

ezdxf = pytest.importorskip("ezdxf")
pytest.importorskip("matplotlib")

from ezdxf import bbox  # noqa: E402

from linkwork.io.dxf_sheet import FORMATS, GostSheet, TitleBlock, number, reduction, write_sheets  # noqa: E402

BLOCK = TitleBlock(
    title="Ножницы",
    designation="ТММ.КП.01.00.00",
    organisation="МГТУ, гр. М-31",
    developer="Иванов И. И.",
    checker="Петров П. П.",
    litera="У",
)


def _texts(layout):
    """Every TEXT and MTEXT of ``layout`` and of the blocks it inserts, as placed on the sheet."""
    for e in layout:
        if e.dxftype() == "INSERT":
            yield from _texts(list(e.virtual_entities()))
        elif e.dxftype() in ("TEXT", "MTEXT"):
            yield e


def _height(e) -> float:
    return float(e.dxf.height if e.dxftype() == "TEXT" else e.dxf.char_height)


def _content(e) -> str:
    return e.dxf.text if e.dxftype() == "TEXT" else e.plain_text()


@pytest.mark.parametrize("fmt", list(FORMATS))
def test_a_sheet_is_its_format_with_the_frame_and_the_title_block_of_form_1(fmt, tmp_path):
    """The format's trimming line from (0, 0) to its size (A1 841 x 594 mm), the frame 20 mm from the left edge
    and 5 mm from the others, the title block 185 x 55 mm in the frame's lower right corner with the words of
    form 1 and the fields given in it, no text lower than 2.5 mm."""
    width, height = {"A1": (841, 594), "A2": (594, 420), "A3": (420, 297), "A4": (210, 297)}[fmt]
    path = GostSheet(fmt, BLOCK, 1, 2, "ru").save(tmp_path / "s.dxf")
    doc = ezdxf.readfile(path)
    msp = doc.modelspace()
    box = bbox.extents(msp)
    assert tuple(box.extmin)[:2] == pytest.approx((0, 0)) and tuple(box.extmax)[:2] == pytest.approx((width, height))
    (frame,) = msp.query("LWPOLYLINE[layer=='FRAME']")
    assert sorted(map(tuple, np.round(np.array(frame.get_points("xy")), 6))) == sorted(
        [(20, 5), (width - 5, 5), (width - 5, height - 5), (20, height - 5)]
    )
    outline = [p for p in msp.query("LWPOLYLINE[layer=='TITLE_BLOCK']")]
    assert len(outline) == 1
    xy = np.array(outline[0].get_points("xy"))
    assert xy.min(0) == pytest.approx([width - 5 - 185, 5]) and xy.max(0) == pytest.approx([width - 5, 60])
    words = {_content(e) for e in _texts(msp)}
    form = {"Изм.", "Лист", "№ докум.", "Подп.", "Дата", "Разраб.", "Пров.", "Т.контр.", "Н.контр.", "Утв."}
    form |= {"Лит.", "Масса", "Масштаб", "Лист 1", "Листов 2"}
    assert form <= words
    assert {"ТММ.КП.01.00.00", "Ножницы", "МГТУ, гр. М-31", "Иванов И. И.", "Петров П. П.", "У"} <= words
    assert min(_height(e) for e in _texts(msp)) >= 2.5
    lines = msp.query("LINE[layer=='TITLE_BLOCK']")
    assert {e.dxf.lineweight for e in lines} == {70, 35}  # ГОСТ 2.303: s = 0.7 mm and s / 2
    for e in _texts(msp):  # each word of the block inside it
        b = bbox.extents([e])
        assert b.extmin.x >= width - 190 - 1e-6 and b.extmax.y <= 60 + 1e-6, _content(e)


def test_the_numbers_of_the_sheets_are_written_as_in_russia():
    assert [number(x, "ru") for x in (0.002, 0.0025, 5000.0, 10000.0, 2.5)] == [
        "0,002",
        "0,0025",
        "5000",
        "10000",
        "2,5",
    ]
    assert number(0.05, "en") == "0.05"
    # ГОСТ 2.302's reductions: the least that draws the length in 1 mm of paper
    assert [reduction(x) for x in (0.001, 0.0011, 0.0021, 0.0031, 0.0049, 0.006)] == [1, 2, 2.5, 4, 5, 10]


@functools.cache
def _shears_sheets(folder: str, fmt: str) -> tuple[list, float]:
    from linkwork.kinetostatics.force_polygons import force_plans
    from linkwork.kinetostatics.zhukovsky import lever
    from linkwork.motion.analysis import position_angles, zero_angle

    mech = lw.compile(lw.example("double-cut-shears"))
    zero = zero_angle(mech)
    twelve = lw.kinematics(mech, position_angles(mech, 12, zero))
    cycle = lw.kinematics(mech, position_angles(mech, 72, zero))
    at = zero + np.radians(86.6)  # under the cutting load
    one = lw.forces(lw.kinematics(mech, [at]))
    paths = write_sheets(twelve, 9, cycle, force_plans(one), lever(one), 0, "φ = 86,6°", folder, "ru", fmt, BLOCK)
    return [ezdxf.readfile(p) for p in paths], float(one.external.magnitude["cutting"][0, 0])


@pytest.mark.slow
@pytest.mark.parametrize(("fmt", "count"), [("A1", 2), ("A3", 3), ("A4", 6)])
def test_each_drawing_of_the_course_project_has_a_place_of_its_own_and_states_its_scales(fmt, count, tmp_path):
    """Sheet 1 (the plan of positions, the velocity and acceleration plans) and sheet 2 (the scheme under the
    cutting load, the four groups' force plans, the lever, the legend of the arrows): each drawing a block whose
    box (ezdxf's, text included) overlaps no other, nor the title block, and lies inside the frame; every text at
    least 2.5 mm high; each drawing states its scales as μl = 0,004 м/мм does; the Russian notes hold no English
    word; the knives' cutting force drawn on its layer F / μF long.  The 10 drawings on 2 sheets of A1, 3 of A3
    (four drawings a sheet), 6 of A4 (two), each numbered in its title block."""
    docs, cutting = _shears_sheets(str(tmp_path), fmt)
    assert len(docs) == count
    for k, doc in enumerate(docs, start=1):
        words = {e.dxf.text for e in doc.modelspace().query("TEXT")}
        assert {f"Лист {k}", f"Листов {count}"} <= words
    width, height = FORMATS[fmt]
    block = np.array([width - 5 - 185, 5, width - 5, 60])
    notes = []
    for doc in docs:
        msp = doc.modelspace()
        box = bbox.extents(msp)
        assert tuple(box.extmax)[:2] == pytest.approx((width, height))
        boxes = []
        for insert in msp.query("INSERT"):
            b = bbox.extents(insert.virtual_entities())
            boxes.append(np.r_[tuple(b.extmin)[:2], tuple(b.extmax)[:2]])
        for b in boxes:
            assert b[0] >= 20 and b[1] >= 5 and b[2] <= width - 5 and b[3] <= height - 5, b
        for a, b in itertools.combinations([*boxes, block], 2):
            assert a[2] <= b[0] or b[2] <= a[0] or a[3] <= b[1] or b[3] <= a[1], (a, b)
        texts = list(_texts(msp))
        assert min(_height(e) for e in texts) >= 2.5
        notes.append([_content(e) for e in texts if e.dxf.layer == "NOTES"])
    every = [s for sheet in notes for s in sheet]
    assert sum(len(doc.modelspace().query("INSERT")) for doc in docs) == 10
    assert sum(bool(re.fullmatch(r"μl = 0,\d+ м/мм", s)) for s in every) == 2  # the positions, the scheme
    assert sum(bool(re.fullmatch(r"μv = [\d,]+ \(м/с\)/мм", s)) for s in every) == 1
    assert sum(bool(re.fullmatch(r"μa = [\d,]+ \(м/с²\)/мм", s)) for s in every) == 1
    assert sum(bool(re.fullmatch(r"μF = [\d,]+ Н/мм", s)) for s in every) == 4
    assert sum(bool(re.fullmatch(r"μv = [\d,]+ \(м/с\)/мм;  μF = [\d,]+ Н/мм", s)) for s in every) == 1
    assert not [s for s in every if re.search(r"[A-Za-z]{3,}", s)]
    loads = []
    for insert in (i for doc in docs for i in doc.modelspace().query("INSERT")):
        scale = [_content(e) for e in _texts(insert.virtual_entities()) if _content(e).startswith("μF = ")]
        for e in insert.virtual_entities():
            if e.dxftype() == "LINE" and e.dxf.layer == "LOADS" and scale:
                mu = float(scale[0].split()[2].replace(",", "."))
                loads.append((e.dxf.start - e.dxf.end).magnitude * mu)
    assert cutting == pytest.approx(250e3)
    assert loads and loads == pytest.approx([cutting] * len(loads), rel=1e-9)


def test_the_options_fill_the_title_block_as_the_file_would():
    """``--sheet a3 --title-block developer=...`` give the sheets what ``drawing: {sheet: A3, title_block:
    {developer: ...}}`` in the file gives; the file's positions stay."""
    from linkwork.cli.analyze import _with_sheets
    from linkwork.io.dxf_sheet import sheet_options

    mech = lw.compile(lw.example("double-cut-shears"))
    assert sheet_options(mech) == ("A1", TitleBlock())
    edited = _with_sheets(mech, "a3", ["developer=Иванов И. И.", "litera = У"], True)
    assert sheet_options(edited) == ("A3", TitleBlock(developer="Иванов И. И.", litera="У"))
    assert edited.spec.drawing.positions == [9]


@pytest.mark.parametrize(
    ("argv", "says"),
    [
        (["--dxf", "--sheet", "A0"], '--sheet: expected A1, A2, A3 or A4, got "A0"'),
        (["--dxf", "--title-block", "author=X"], "--title-block: expected KEY=VALUE, KEY one of title, designation"),
        (["--sheet", "A3"], "--sheet and --title-block: the sheets are written with --dxf; add it"),
    ],
)
def test_a_wrong_sheet_option_is_refused_in_one_line_before_any_work(argv, says, tmp_path):
    from typer.testing import CliRunner

    import linkwork.cli.analyze  # noqa: F401 - registers the command
    from linkwork.cli.main import app

    result = CliRunner().invoke(app, ["analyze", "double-cut-shears", "--out", str(tmp_path / "r"), *argv])
    assert result.exit_code == 2
    lines = result.stderr.strip().splitlines()
    assert lines[-1].startswith("error: " + says) or lines[-1].startswith(says), lines
    assert len(lines) <= 2 and "Traceback" not in result.output
    assert not (tmp_path / "r").exists()
