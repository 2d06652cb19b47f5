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

from linkwork.io.dxf_sheet import FORMATS, GostSheet, TitleBlock, number, reduction  # noqa: E402
from linkwork.io.sheet_drawings import SheetAnalyses, write_sheets  # noqa: E402

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
    analyses = SheetAnalyses(twelve, 9, cycle, force_plans(one), lever(one), 0, "φ = 86,6°")
    paths = write_sheets(analyses, folder, "ru", fmt, BLOCK)
    assert paths[-1].name == "sheets.pdf" and paths[-1].read_bytes().count(b"/Type /Page") - 1 == len(paths) - 1
    return [ezdxf.readfile(p) for p in paths[:-1]], float(one.external.magnitude["cutting"][0, 0])


@pytest.mark.slow
@pytest.mark.parametrize(("fmt", "count"), [("A1", 2), ("A3", 3), ("A4", 6)])
def test_each_drawing_of_the_course_project_has_a_place_of_its_own_and_states_its_scales(fmt, count, tmp_path):
    """Sheet 1 (the plan of positions, the velocity and acceleration plans, the scheme there) and sheet 2 (the
    scheme under the cutting load, the four groups' force plans, the lever, the legend of the arrows): each drawing
    a block whose box (its texts included, each on one line) overlaps no other, nor the title block, and lies
    inside the frame; every text at least 2.5 mm high; each drawing states its scales as μl = 0,004 м/мм does; the
    Russian notes hold no English word; the knives' cutting force drawn on its layer F / μF long.  The 11 drawings
    on 2 sheets of A1, 3 of A3 (four drawings a sheet), 6 of A4 (two), each numbered in its title block, and the
    PDF of as many pages beside them."""
    from linkwork.io.dxf_sheet import drawn_box

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
        boxes = [drawn_box(entities) + np.r_[at, at] for entities, at in _blocks(doc) if at is not None]
        for b in boxes:
            assert b[0] >= 20 and b[1] >= 5 and b[2] <= width - 5 and b[3] <= height - 5, b
        for a, b in itertools.combinations([*boxes, block], 2):
            assert a[2] <= b[0] or b[2] <= a[0] or a[3] <= b[1] or b[3] <= a[1], (a, b)
        texts = list(_texts(msp))
        assert min(_height(e) for e in texts) >= 2.5
        notes.append([_content(e) for e in texts if e.dxf.layer == "NOTES"])
    every = [s for sheet in notes for s in sheet]
    assert sum(len(doc.modelspace().query("INSERT")) for doc in docs) == 11
    assert sum(bool(re.fullmatch(r"μl = 0,\d+ м/мм", s)) for s in every) == 3  # the positions, the two schemes
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
    from linkwork.cli.analyze import _sheets
    from linkwork.io.sheet_drawings import sheet_options
    from linkwork.scene.positions import plan_positions
    from linkwork.spec.edit import text_with_section

    mech = lw.compile(lw.example("double-cut-shears"))
    assert sheet_options(mech) == ("A1", TitleBlock())
    given = _sheets("a3", ["developer=Иванов И. И.", "litera = У"], True)
    assert sheet_options(mech, given) == ("A3", TitleBlock(developer="Иванов И. И.", litera="У"))
    spec = lw.example("double-cut-shears")
    edited = lw.compile(
        lw.loads(
            text_with_section(
                spec, "drawing", {"sheet": "A3", "title_block": {"developer": "Иванов И. И.", "litera": "У"}}
            )
        )
    )
    assert sheet_options(edited) == sheet_options(mech, given)
    assert plan_positions(edited) == plan_positions(mech) == [9]


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


# ------------------------------------------------------------------ the dynamics sheet, the PDF, ГОСТ 2.303 and 2.304

J0, SWING, M0, OMEGA, DELTA, ZERO, SHIFT = 2.0, 1.5, 3000.0, 3.0, 0.05, 0.3, 1.0


def _dynamics():
    """A machine whose steady cycle is known in closed form: its reduction from the drive angle ZERO (ψ = 0),
    position 0 SHIFT rad further (φ = ψ - SHIFT), the crank turning counter-clockwise; J = J0 + SWING sin²ψ, the
    loads' reduced moment M = -M0 (1 + cos ψ), so that the drive moment that balances them is M0 and the energy
    given from position 0 is ΔT = -M0 (sin ψ - sin SHIFT); the flywheel sized for DELTA by Wittenbauer's tangents;
    the speed over the cycle ω = OMEGA (1 + 0.01 sin ψ)."""
    from types import SimpleNamespace

    from linkwork.machine.flywheel import size_flywheel_wittenbauer
    from linkwork.machine.reduction import Reduced
    from linkwork.machine.steady_cycle import Dynamics
    from linkwork.motion.analysis import CrankAngles

    psi = 2 * np.pi * np.arange(720) / 720
    red = Reduced(psi, ZERO + psi, J0 + SWING * np.sin(psi) ** 2, SWING * np.sin(2 * psi), -M0 * (1 + np.cos(psi)))
    fly = size_flywheel_wittenbauer(red, DELTA, OMEGA)
    turn = np.linspace(0.0, 2 * np.pi, 721)
    omega = OMEGA * (1 + 0.01 * np.sin(turn))
    motion = SimpleNamespace(
        cycle=lambda: (turn / OMEGA, turn, omega), cycle_start=0.0, last=SimpleNamespace(omega_mean=OMEGA, delta=0.02)
    )
    drive = SimpleNamespace(flywheel_on="crank", flywheel=fly.on_crank)
    return Dynamics(red, drive, motion, fly, motion, CrankAngles(ZERO + SHIFT, 1.0), "closed form")


def _drawings(doc):
    """Each drawing of a sheet: its title, its scales' line and its entities as placed on the sheet."""
    out = {}
    for insert in doc.modelspace().query("INSERT"):
        items = list(insert.virtual_entities())
        notes = [_content(e) for e in items if e.dxftype() == "TEXT" and e.dxf.layer == "NOTES"]
        out[notes[-1]] = (next((n for n in notes if n.startswith("μ")), ""), items)  # the title is written last
    return out


def _scales(line: str) -> list[float]:
    return [float(x.replace(",", ".")) for x in re.findall(r"μ\S+ = ([\d,]+)", line)]


def _origin(items):
    """The crossing of a diagram's axes: the x of its longest vertical AXES line, the y of its longest horizontal."""
    lines = [e for e in items if e.dxftype() == "LINE" and e.dxf.layer == "AXES"]
    vertical = max(
        (e for e in lines if abs(e.dxf.start.x - e.dxf.end.x) < 1e-9), key=lambda e: e.dxf.start.distance(e.dxf.end)
    )
    across = max(
        (e for e in lines if abs(e.dxf.start.y - e.dxf.end.y) < 1e-9), key=lambda e: e.dxf.start.distance(e.dxf.end)
    )
    return np.array([vertical.dxf.start.x, across.dxf.start.y])


def _curves(items, dashed=False):
    """The points (mm) of each polyline of a diagram's curves (solid or ``dashed``; not the legend's strokes)."""
    return [
        np.array(e.get_points("xy"))
        for e in items
        if e.dxftype() == "LWPOLYLINE"
        and e.dxf.layer == "DIAGRAMS"
        and (e.dxf.linetype == "DASHED") == dashed
        and len(e) > 2
    ]


@functools.cache
def _dynamics_sheet(folder: str):
    from linkwork.io.dxf_dynamics import dynamics_drawings

    sheet = GostSheet("A1", BLOCK, 3, 3, "ru")
    sheet.place(dynamics_drawings(_dynamics(), "ru"))
    return ezdxf.readfile(sheet.save(f"{folder}/sheet_3.dxf"))


def test_the_dynamics_sheet_draws_the_machine_to_its_stated_scales(tmp_path):
    """Read back, each diagram's curve at its stated μ from its axes' crossing is the closed form over φ from
    position 0 (ψ = φ + SHIFT): J(φ) = J0 + SWING sin²ψ, M(φ) = -M0 (1 + cos ψ) with the drive moment M0 dashed,
    ΔT(φ) = -M0 (sin ψ - sin SHIFT) (0 at position 0, not at the reduction's first angle); Wittenbauer's tangents
    cut the energy axis where the largest and least of ΔT - k J over the turn (found here on a fine grid) put them,
    k = (ω (1 ± δ/2))² / 2, and the flywheel's figures give the inertia (b_max - b_min) / (k_max - k_min) they
    imply."""
    drawings = _drawings(_dynamics_sheet(str(tmp_path)))
    phi = np.radians(np.linspace(0, 360, 200001))
    psi = phi + SHIFT
    inertia, energy = J0 + SWING * np.sin(psi) ** 2, -M0 * (np.sin(psi) - np.sin(SHIFT))
    closed = {"J(φ)": inertia, "M(φ)": -M0 * (1 + np.cos(psi)), "ΔT(φ)": energy}
    for key, values in closed.items():
        (title,) = [t for t in drawings if t.endswith(" " + key)]
        scales, items = drawings[title]
        mx, my = _scales(scales)
        origin = _origin(items)
        (curve,) = _curves(items)
        x, y = ((curve - origin) * [mx, my]).T
        assert 0 <= x.min() < 0.5 and x.max() == pytest.approx(x.min() + 360, abs=1e-6)  # a turn from position 0
        expected = np.interp(np.radians(x), phi, values, period=2 * np.pi)
        assert y == pytest.approx(expected, abs=1e-4 * M0 if key != "J(φ)" else 1e-4)
    scales, items = drawings[[t for t in drawings if t.endswith("M(φ)")][0]]
    (drive,) = _curves(items, dashed=True)
    assert (drive[:, 1] - _origin(items)[1]) * _scales(scales)[1] == pytest.approx(M0, rel=1e-9)
    title = [t for t in drawings if "Виттенбауэра" in t][0]
    scales, items = drawings[title]
    mj, me = _scales(scales)
    origin = _origin(items)
    found = []
    for k, pick in (((OMEGA * (1 + DELTA / 2)) ** 2 / 2, np.max), ((OMEGA * (1 - DELTA / 2)) ** 2 / 2, np.min)):
        b = pick(energy - k * inertia)
        found.append((k, b))
    tangents = [e for e in items if e.dxftype() == "LWPOLYLINE" and e.dxf.layer == "TANGENTS"]
    drawn = sorted(((np.array(e.get_points("xy"))[0] - origin) * [mj, me]).tolist() for e in tangents)
    assert [x for x, _ in drawn] == pytest.approx([0, 0], abs=1e-9)
    assert [y for _, y in drawn] == pytest.approx(sorted(b for _, b in found), abs=1e-3 * M0)
    (k1, b1), (k2, b2) = found
    need = (b1 - b2) / (k1 - k2)
    figures = [t for t in drawings["Маховик"][1] if t.dxftype() == "TEXT" and "J = " in _content(t)]
    value = float(re.search(r"J = ([\d,]+)", _content(figures[0])).group(1).replace(",", "."))
    assert value == pytest.approx(need, rel=1e-3)
    for title, (scales, _) in drawings.items():  # every diagram states both its scales
        if title != "Маховик":
            assert re.fullmatch(r"μ(φ|J) = [\d,]+ (°|кг·м²)/мм;  μ(J|M|ΔT|ω) = [\d,]+ \S+/мм", scales), scales


@functools.cache
def _shears():
    """The shears' twelve positions, their cycle, and the force plans and the lever under the cutting load."""
    from linkwork.kinetostatics.force_polygons import force_plans
    from linkwork.kinetostatics.zhukovsky import lever
    from linkwork.motion.analysis import position_angles, zero_angle

    mech = lw.compile(lw.example("double-cut-shears"))
    zero = zero_angle(mech)
    twelve = lw.kinematics(mech, position_angles(mech, 12, zero))
    cycle = lw.kinematics(mech, position_angles(mech, 36, zero))
    one = lw.forces(lw.kinematics(mech, [zero + np.radians(86.6)]))
    return twelve, cycle, force_plans(one), lever(one)


@pytest.fixture(scope="module")
def shears():
    return _shears()


def _all_sheets(shears, folder, fmt, lang):
    twelve, cycle, plans, lv = shears
    analyses = SheetAnalyses(twelve, 3, cycle, plans, lv, 0, "φ = 86,6°", _dynamics())
    paths = write_sheets(analyses, folder, lang, fmt, BLOCK, pdf=False)
    return [ezdxf.readfile(p) for p in paths]


def _boxes_overlap(a, b, by=0.0) -> bool:
    return min(a[2], b[2]) - max(a[0], b[0]) > by and min(a[3], b[3]) - max(a[1], b[1]) > by


@pytest.mark.parametrize("lang", ["ru", "en"])
@pytest.mark.parametrize("fmt", list(FORMATS))
def test_no_text_is_under_2_5_mm_nor_covers_another_on_any_sheet(fmt, lang, shears, tmp_path):
    """Every sheet of the course project (kinematics, kinetostatics, dynamics) on every format in both languages,
    read back: every TEXT and MTEXT at least 2.5 mm high (ГОСТ 2.304), no two texts' boxes crossing by more than
    0.1 mm, each drawing's box inside the frame, clear of the others and of the title block; the title block's
    «Масштаб» is the reduction 1:N of the first scheme on the sheet (μl = N / 1000 м/мм), and every drawing but
    the legend and the flywheel's figures states its scales (μl, μv, μa, μF, μφ...)."""
    from linkwork.io.dxf_sheet import drawn_box, text_box

    docs = _all_sheets(shears, str(tmp_path), fmt, lang)
    assert len(docs) == {"A1": 3, "A2": 3, "A3": 5, "A4": 9}[fmt]
    width, height = FORMATS[fmt]
    block = np.array([width - 5 - 185, 5, width - 5, 60])
    for doc in docs:
        placed, texts, boxes = [], [], []
        for entities, at in _blocks(doc):
            if at is not None:
                placed.append(drawn_box(entities) + np.r_[at, at])
            for e in entities:
                if e.dxftype() in ("TEXT", "MTEXT"):
                    texts.append(e)
                    boxes.append(text_box(e) + (0.0 if at is None else np.r_[at, at]))
        assert min(_height(e) for e in texts) >= 2.5
        for (a, ea), (b, eb) in itertools.combinations(zip(boxes, texts, strict=True), 2):
            assert not _boxes_overlap(a, b, by=0.1), (_content(ea), _content(eb))
        for b in placed:
            assert b[0] >= 20 and b[1] >= 5 and b[2] <= width - 5 and b[3] <= height - 5, b
        for a, b in itertools.combinations([*placed, block], 2):
            assert not _boxes_overlap(a, b), (a, b)
        drawings = _drawings(doc)
        bare = {t for t, (scales, _) in drawings.items() if not scales}
        assert bare <= {"Обозначения на планах сил", "Маховик", "The arrows of the force plans", "The flywheel"}, bare
        written = [_content(e) for e in doc.modelspace().query("TEXT[layer=='TITLE_BLOCK']")]
        first = next((s for s, _ in drawings.values() if s.startswith("μl")), None)
        ratio = [w for w in written if w.startswith("1:")]
        if first is None:
            assert not ratio
        else:
            n = float(first.split()[2].replace(",", ".")) * 1000
            assert ratio == [f"1:{n:g}".replace(".", "," if lang == "ru" else ".")]


def _blocks(doc):
    """The sheet's own entities (``at`` None), then each drawing's block and where it is inserted (at scale 1,
    unturned: checked), its entities read in the block's coordinates."""
    msp = doc.modelspace()
    yield [e for e in msp if e.dxftype() != "INSERT"], None
    for insert in msp.query("INSERT"):
        assert (insert.dxf.xscale, insert.dxf.yscale, insert.dxf.rotation) == (1, 1, 0)
        yield list(doc.blocks.get(insert.dxf.name)), np.array(insert.dxf.insert)[:2]


def test_the_lines_of_the_sheets_are_those_of_gost_2_303(shears, tmp_path):
    """Read back from the sheets: the main lines (links, a plan's absolute vectors, the forces, the diagrams'
    curves, the frame) solid and s = 0.7 mm thick; the thin ones s/3 to s/2 (0.25 or 0.35 mm); the paths of the
    joints' centres in the thin dash-dot line, strokes 5-30 mm long 3-5 mm apart; the dashed lines (the plans'
    tangential and transport components, the reactions read off a plan, the tangents) strokes 2-8 mm long 1-2 mm
    apart; the eleven other positions of the plan of positions thin; every entity's line type and weight one of
    these."""
    docs = _all_sheets(shears, str(tmp_path), "A1", "ru")
    doc = docs[0]
    layer = {e.dxf.name: e for e in doc.layers}
    for name in ("LINKS", "ABSOLUTE", "LOADS", "REACTIONS", "DIAGRAMS", "FRAME"):
        assert (layer[name].dxf.linetype, layer[name].dxf.lineweight) == ("Continuous", 70), name
    for name in ("PIVOTS", "GUIDES", "SUPPORTS", "HATCHING", "AXES", "FORMAT", "ROTATION", "NORMAL"):
        assert layer[name].dxf.linetype == "Continuous" and layer[name].dxf.lineweight in (25, 35), name
    assert layer["TRAJECTORIES"].dxf.linetype == "DASHDOT" and layer["TRAJECTORIES"].dxf.lineweight <= 35
    for name in ("TANGENTIAL", "TRANSPORT", "INNER_REACTIONS", "TANGENTS"):
        assert layer[name].dxf.linetype == "DASHED" and layer[name].dxf.lineweight in (25, 35), name
    dash, gap = doc.linetypes.get("DASHED").simplified_line_pattern()
    assert 2 <= dash <= 8 and 1 <= gap <= 2
    stroke, *between = doc.linetypes.get("DASHDOT").simplified_line_pattern()
    assert 5 <= stroke <= 30 and 3 <= sum(between) <= 5 and len(between) == 3 and between[1] == 0  # a dot midway
    for d in docs:
        for insert in d.modelspace().query("INSERT"):
            for e in d.blocks.get(insert.dxf.name):
                linetype, weight = e.dxf.get("linetype", "BYLAYER"), e.dxf.get("lineweight", -1)
                assert linetype in ("BYLAYER", "DASHED", "Continuous") and weight in (-1, 35, 70), e
                if linetype == "BYLAYER":
                    linetype = layer[e.dxf.layer].dxf.linetype
                if linetype == "DASHED" and e.dxftype() != "SOLID":  # a dashed line is a thin one
                    assert (layer[e.dxf.layer].dxf.lineweight if weight == -1 else weight) <= 35, e
    positions = doc.blocks.get(doc.modelspace().query("INSERT")[0].dxf.name)
    thin = [e for e in positions if e.dxf.layer == "LINKS" and e.dxf.get("lineweight", -1) == 35]
    assert len(thin) >= 11 * 7  # the shears' seven moving links at the eleven other positions


def test_the_pdf_is_the_sheets_page_by_page_and_no_half_file(tmp_path, monkeypatch):
    """``sheets.pdf``: a page for each sheet, of its format's size in points (A3: 420 x 297 mm = 1190.55 x 841.89
    pt), its lines as thick as the DXF's on paper (0.7 mm = 1.984 pt, 0.35 mm = 0.992 pt); a failure drawing a page
    leaves the PDF that was there and no part of the new one."""
    import matplotlib

    from linkwork.io import sheet_pdf

    sheets = [GostSheet("A3", BLOCK, k, 2, "ru") for k in (1, 2)]
    with matplotlib.rc_context({"pdf.compression": 0}):
        path = sheet_pdf.write_pdf(sheets, tmp_path / "sheets.pdf")
    data = path.read_bytes()
    assert data.startswith(b"%PDF") and data.count(b"/Type /Page\n") + data.count(b"/Type /Page ") == 2
    boxes = {tuple(map(float, m)) for m in re.findall(rb"/MediaBox \[\s*0 0 ([\d.]+) ([\d.]+)\s*\]", data)}
    assert list(boxes) == [pytest.approx((420 / 25.4 * 72, 297 / 25.4 * 72), abs=0.01)]
    widths = {round(float(w), 3) for w in re.findall(rb"([\d.]+) w\b", data)}
    assert {round(0.7 / 25.4 * 72, 3), round(0.35 / 25.4 * 72, 3)} <= widths
    old = path.read_bytes()

    def fail(sheet):
        raise RuntimeError("no page")

    monkeypatch.setattr(sheet_pdf, "page", fail)
    with pytest.raises(RuntimeError):
        sheet_pdf.write_pdf(sheets, path)
    assert path.read_bytes() == old and sorted(p.name for p in tmp_path.iterdir()) == ["sheets.pdf"]


def test_a_label_is_measured_on_one_line_as_a_cad_program_draws_it():
    """An MTEXT label of several words (no column width: a CAD program does not break it) is measured as wide as
    the same words in a TEXT of that height, which ezdxf's text-to-path outlines confirm; ezdxf's own box of the
    MTEXT is a column a word wide, several lines tall."""
    from ezdxf.addons import text2path
    from ezdxf.enums import MTextEntityAlignment

    from linkwork.io.dxf import STYLE
    from linkwork.io.dxf_sheet import text_box

    doc = ezdxf.new(setup=True)
    msp = doc.modelspace()
    words = "short, named here: G1 = 392,4 Н"
    m = msp.add_mtext(words, dxfattribs={"char_height": 3.5, "style": STYLE})
    m.set_location((10.0, 20.0), attachment_point=MTextEntityAlignment.MIDDLE_LEFT)
    box = text_box(m)
    text = msp.add_text(words, height=3.5, dxfattribs={"style": STYLE})
    text.set_placement((10.0, 20.0))
    outline = ezdxf.path.bbox(text2path.make_paths_from_entity(text))
    assert box[0] == pytest.approx(10.0) and box[2] - box[0] == pytest.approx(outline.size.x, rel=0.05)
    assert box[3] - box[1] < 2 * 3.5 and box[1] < 20.0 < box[3]
    assert bbox.extents([m]).size.y > 3 * 3.5  # why the sheets measure it themselves
