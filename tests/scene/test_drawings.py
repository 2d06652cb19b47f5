"""The drawings of a mechanism from one scene: no text covers another in any figure, the joints are where
the kinematics puts them in every renderer (matplotlib, the viewer's payload, DXF), the plans are drawn
to their scale where the mechanism moves, and the drawings for CAD and the animation are written."""

from __future__ import annotations

import math

import numpy as np
import pytest

import linkwork as lw
from drawing_checks import overlaps
from linkwork.errors import SpecError
from linkwork.examples import names
from linkwork.examples import text as example_text
from linkwork.motion.analysis import transmission
from linkwork.motion.plans import plan_series
from linkwork.scene import scheme_scene
from linkwork.scene.plans import plan_scene
from linkwork.scene.positions import best_position, plan_positions, position_angles, working_point
from linkwork.structure.model import point_labels

pytest.importorskip("matplotlib")

from matplotlib.figure import Figure  # noqa: E402

from linkwork import figures  # noqa: E402
from linkwork.figures.animation import Film  # noqa: E402


def _solved(name: str, steps: int = 72):
    mech = lw.compile(lw.example(name))
    cycle = lw.kinematics(mech, steps=steps)
    twelve = lw.kinematics(mech, position_angles(mech))
    return mech, cycle, twelve


def test_the_overlap_check_finds_texts_and_axes_that_cover_each_other():
    fig = Figure(figsize=(4, 3))
    ax = fig.add_axes((0.1, 0.1, 0.5, 0.5))
    fig.add_axes((0.4, 0.4, 0.5, 0.5))
    ax.text(0.5, 0.5, "covered")
    ax.text(0.52, 0.5, "covering")
    ax.text(0.1, 0.9, "alone")
    fig.text(0.95, 0.5, "cut at the edge")
    found = overlaps(fig)
    assert "text 'covered' (axes '') covers text 'covering' (axes '')" in found
    assert "text 'cut at the edge' (figure) reaches beyond the figure" in found
    assert sum(" covers axes " in f for f in found) == 1
    assert not any("alone" in f for f in found)


@pytest.mark.parametrize("lang", ["en", "ru"])
@pytest.mark.parametrize("name", names())
def test_no_text_covers_another_in_any_drawing(name, lang):
    """The scheme, the plan of positions, both plans, the sheet of twelve plans and frames of the
    animation of every bundled example, in both languages, read back through the Agg renderer."""
    mech, cycle, twelve = _solved(name)
    k = plan_positions(mech, twelve)[0]
    drawn = {
        "scheme": figures.draw_scheme(twelve, k, trajectories=True, position=k, cycle=cycle, lang=lang),
        "positions": figures.draw_positions(cycle, lang=lang),
        "velocity plan": figures.velocity_plan(twelve, k, position=k, lang=lang),
        "acceleration plan": figures.acceleration_plan(twelve, k, position=k, lang=lang),
        "velocity plans": figures.plan_sheet(twelve, "velocity", lang=lang),
    }
    picks = [0, 18, 36, 54]
    film = Film(scheme_scene(cycle, at=picks), picks, lang)
    for artist in [*film.moving, *film.texts]:
        artist.set_animated(False)  # drawn with the figure, so that the check reads them back
    problems = {what: overlaps(fig) for what, fig in drawn.items()}
    for i in picks:
        film.show(i)
        problems[f"animation frame {i}"] = overlaps(film.fig)
    assert {what: found for what, found in problems.items() if found} == {}


@pytest.mark.parametrize("name", ["double-cut-shears", "four-bar", "percussion-rocker"])
def test_every_renderer_puts_the_joints_where_the_kinematics_does(name, tmp_path):
    """The pivots' centres read back from the matplotlib figure, from the viewer's payload (the scene's items
    placed by its poses) and from the DXF (mm, where ezdxf is installed) are the points' positions the
    kinematics solves."""
    from linkwork.web.payload import cycle_payload

    mech, cycle, twelve = _solved(name)
    k = 7
    fig = figures.draw_scheme(twelve, k, cycle=cycle)
    drawn = {
        a.get_gid().split(":", 1)[1]: np.array(a.center)
        for a in fig.axes[0].patches
        if (a.get_gid() or "").startswith("pivot:")
    }
    revolute = {j for j, t in zip(mech.pair_joint, mech.pair_type, strict=True) if t == 0}
    assert set(drawn) == revolute
    for joint, centre in drawn.items():
        np.testing.assert_allclose(centre, twelve.position(joint)[k], rtol=0, atol=1e-12)

    payload = cycle_payload(mech, steps=36)
    scene, kin36 = payload["scene"], lw.kinematics(mech, np.radians(payload["angles_deg"]))
    for item in (it for it in scene["items"] if it["kind"] == "pivot"):
        pose = np.array(scene["poses"][20][item["link"]])
        c, s = math.cos(pose[2]), math.sin(pose[2])
        x, y = item["xy"][0]
        np.testing.assert_allclose(
            [pose[0] + c * x - s * y, pose[1] + s * x + c * y], kin36.position(item["name"])[20], rtol=0, atol=1e-8
        )

    try:
        import ezdxf
    except ImportError:
        return
    from linkwork.io.dxf import write_scheme

    path = write_scheme(scheme_scene(twelve, at=[k], cycle=cycle), k, tmp_path / "scheme.dxf")
    doc = ezdxf.readfile(path)
    assert doc.units == ezdxf.units.MM
    circles = [e for e in doc.modelspace().query("CIRCLE") if e.dxf.layer == "PIVOTS"]
    assert len(circles) == len(revolute)
    got = sorted((round(e.dxf.center.x, 6), round(e.dxf.center.y, 6)) for e in circles)
    want = sorted(
        (round(1000 * twelve.position(j)[k][0], 6), round(1000 * twelve.position(j)[k][1], 6)) for j in revolute
    )
    np.testing.assert_allclose(got, want, rtol=0, atol=1e-6)


@pytest.mark.parametrize("name", ["double-cut-shears", "watt-six-bar", "percussion-rocker"])
def test_dxf_plans_are_the_velocities_and_accelerations_drawn_to_their_scale(name, tmp_path):
    """Every absolute vector of the DXF plans, its length in mm times the stated scale, is the point's speed
    and acceleration the kinematics computes (to 1e-9); its direction too."""
    ezdxf = pytest.importorskip("ezdxf")
    from linkwork.io.dxf import write_drawings

    mech, cycle, twelve = _solved(name)
    k = plan_positions(mech, twelve)[0]
    write_drawings(twelve, k, tmp_path, cycle=cycle)
    by_label = {label.lower(): mech.point_names[p] for label, p in point_labels(mech)}
    checked = 0
    for kind, state in (("velocity", twelve.velocity), ("acceleration", twelve.acceleration)):
        doc = ezdxf.readfile(tmp_path / f"{kind}_plan.dxf")
        scale = float(doc.header.custom_vars.get("LINKWORK_SCALE"))
        note = " ".join(e.dxf.text for e in doc.modelspace().query("TEXT") if e.dxf.layer == "NOTES")
        assert f"= {scale:g} (m/s" in note
        for line in doc.modelspace().query("LINE"):
            what = line.get_xdata("LINKWORK")[0].value
            if not what.startswith("absolute:p->"):
                continue
            target = by_label.get(what.split("->", 1)[1])
            if target is None:
                continue
            drawn = np.array([line.dxf.end.x - line.dxf.start.x, line.dxf.end.y - line.dxf.start.y]) * scale
            want = state(target)[k]
            np.testing.assert_allclose(drawn, want, rtol=1e-9, atol=1e-9 * np.hypot(*want))
            assert line.dxf.layer == "ABSOLUTE"
            checked += 1
    assert checked >= 4
    layers = {e.dxf.layer for e in ezdxf.readfile(tmp_path / "scheme.dxf").modelspace()}
    assert {"LINKS", "PIVOTS", "SUPPORTS", "HATCHING", "LABELS"} <= layers
    assert {"LINKS", "TRAJECTORIES"} <= {e.dxf.layer for e in ezdxf.readfile(tmp_path / "positions.dxf").modelspace()}


def _speeds(kin, index: int) -> np.ndarray:
    """Speeds of the joints of the moving links at sample ``index``, m/s."""
    mech = kin.mechanism
    joints = sorted({int(p) for pair in mech.pair_points for p in pair if p >= 0 and mech.point_link[p] != 0})
    v = np.array([kin.velocity(mech.point_names[p])[index] for p in joints])
    return np.hypot(v[:, 0], v[:, 1])


@pytest.mark.parametrize("name", names())
def test_the_plans_are_drawn_where_the_mechanism_moves(name):
    """Not at a dead point, where the chain beyond the crank stands still and the plan collapses onto the pole:
    at the position drawn at least half of the moving joints move at a tenth of the fastest one's speed or
    more, and every dyad transmits at an angle of at least 10 degrees."""
    mech, cycle, twelve = _solved(name)
    k = plan_positions(mech, twelve)[0]
    speeds = _speeds(twelve, k)
    assert np.mean(speeds >= 0.1 * speeds.max()) >= 0.5, speeds
    for mu in transmission(twelve).values():
        assert np.degrees(np.asarray(mu).reshape(-1, 12)[0, k]) >= 10.0


def test_the_slider_crank_plans_avoid_the_singular_positions():
    """The shears of seed 000 (OA = AB): the knife is fastest where B passes O, at crank angles 0 and 180
    degrees, where the mechanism is singular (the rod along the normal to the guide); the plans are drawn
    elsewhere, at the next fastest positions."""
    mech, cycle, twelve = _solved("shears-slider-crank")
    angles = np.degrees(position_angles(mech)) % 360
    k = best_position(twelve)
    assert min(abs(angles[k] - 0) % 180, 180 - abs(angles[k] - 0) % 180) >= 29.0
    phi = np.radians(angles[k])
    assert np.hypot(*twelve.velocity("B")[k]) == pytest.approx(2 * 0.15 * 10 * abs(math.cos(phi)), rel=1e-9)


def test_the_file_names_the_positions_of_the_plans():
    mech = lw.compile(lw.example("double-cut-shears"))
    assert plan_positions(mech) == [9]
    assert mech.point_names[working_point(mech)] == "knife_upper.edge"
    text = example_text("four-bar") + "drawing: {positions: [3, 5]}\n"
    assert plan_positions(lw.compile(lw.loads(text, file="four-bar.yaml"))) == [3, 5]
    bad = example_text("four-bar") + "drawing: {positions: [12]}\n"
    with pytest.raises(SpecError, match=r"four-bar.yaml:\d+: drawing.positions\[0\]: expected a number at most 11"):
        lw.loads(bad, file="four-bar.yaml")


def test_points_with_one_vector_share_one_label():
    """The knife's edge moves with its slide: one label, the textbook's letter "e" (the edge's file name,
    "knife_upper.edge", is no letter of a plan); at position 0 (the knives open, every point of the chain
    below the crank at rest) the pole's label names every point at rest."""
    mech, cycle, twelve = _solved("double-cut-shears")
    vel, _ = plan_series(twelve)
    scene = plan_scene(vel, list(range(12)))
    j = scene.names.index("e")
    edge = scene.names.index("knife_upper.edge")
    for k in range(1, 12):
        if scene.text[k][j]:
            assert scene.text[k][j].split(", ")[0] == "e" and "knife_upper.edge" not in scene.text[k][j]
            assert scene.text[k][edge] == ""
    pole = scene.text[0][scene.names.index("p")].split(", ")
    at_rest = [
        lab
        for lab in scene.names[: len(vel.points)]
        if lab != "p" and "." not in lab and np.hypot(*vel.values[0, 0, vel.labels.index(lab)]) < 1e-9
    ]
    assert at_rest and set(at_rest) <= set(pole)


def test_every_plan_states_its_scale_and_names_its_vectors():
    mech, cycle, twelve = _solved("double-cut-shears")
    for kind, fig in (
        ("velocity", figures.velocity_plan(twelve, 9)),
        ("acceleration", figures.acceleration_plan(twelve, 9)),
    ):
        texts = " | ".join(t.get_text() for t in fig.findobj(lambda a: hasattr(a, "get_text")))
        symbol = "μv" if kind == "velocity" else "μa"
        assert f"{symbol} = " in texts
        assert "absolute (from the pole)" in texts and "sliding along the guide" in texts


def test_the_scene_and_the_viewer_need_no_matplotlib():
    """The viewer's payload carries the scene; building it imports neither matplotlib nor ezdxf."""
    import subprocess
    import sys

    code = (
        "import sys, linkwork as lw\n"
        "from linkwork.web.payload import cycle_payload\n"
        "d = cycle_payload(lw.compile(lw.example('four-bar')), steps=12)\n"
        "assert d['scene']['items'] and d['scene']['plans']['velocity']['text']\n"
        "print(sorted(m for m in ('matplotlib', 'ezdxf') if m in sys.modules))\n"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert done.stdout.strip() == "[]"


def _cli():
    from typer.testing import CliRunner

    import linkwork.cli.analyze  # noqa: F401  (registers the command)
    from linkwork.cli.main import app

    return CliRunner(), app


@pytest.mark.slow  # over the default lane's budget on the NumPy kernels (tests/conftest.py)
def test_analyze_writes_the_drawings_for_cad_and_the_sheets_of_all_twelve_plans(report):
    ezdxf = pytest.importorskip("ezdxf")
    out = report("four-bar", dxf=True, position="all")  # 36 steps, no animation
    for name in ("scheme", "positions", "velocity_plan", "acceleration_plan"):
        doc = ezdxf.readfile(out / "figures" / f"{name}.dxf")
        assert doc.units == ezdxf.units.MM and len(doc.modelspace()) > 10
    for name in ("velocity_plans", "acceleration_plans"):
        assert (out / "figures" / f"{name}.png").stat().st_size > 10000
    assert "velocity_plans" in (out / "report.html").read_text()


def test_analyze_without_ezdxf_says_what_to_install_before_any_work(tmp_path, monkeypatch):
    import importlib

    real = importlib.import_module

    def without_ezdxf(name, *args, **kwargs):
        if name.split(".")[0] == "ezdxf":
            raise ImportError(name)
        return real(name, *args, **kwargs)

    monkeypatch.setattr(importlib, "import_module", without_ezdxf)
    runner, app = _cli()
    result = runner.invoke(app, ["analyze", "four-bar", "--out", str(tmp_path / "r"), "--dxf"])
    assert result.exit_code == 2
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and "ezdxf" in lines[0] and 'pip install "linkwork[cad]"' in lines[0]
    assert not (tmp_path / "r").exists()


@pytest.mark.parametrize("name", ["double-cut-shears", "watt-six-bar"])
def test_the_frames_of_the_animation_are_the_scene_drawn_at_their_sample(name):
    """Each frame (the labels laid over it as pictures drawn once) is, to a unit of rounding in a colour, the
    figure drawn afresh with every artist at that sample through the Agg renderer."""
    mech, cycle, twelve = _solved(name, steps=36)
    picks = [0, 5, 11, 17, 23, 29, 35]
    film = Film(scheme_scene(cycle, at=picks), picks, "ru")
    for i in picks:
        got = film.frame(i).astype(int)
        film.show(i)
        for artist in [*film.moving, *film.texts]:
            artist.set_animated(False)
        film.canvas.draw()
        for artist in [*film.moving, *film.texts]:
            artist.set_animated(True)
        want = np.asarray(film.canvas.buffer_rgba())[: got.shape[0], : got.shape[1], :3].astype(int)
        assert np.abs(got - want).max() <= 1, i


def test_the_animation_is_720_pixels_wide_and_an_mp4_where_imageio_ffmpeg_is(tmp_path):
    from PIL import Image

    from linkwork.figures.animation import animate

    mech = lw.compile(lw.example("double-cut-shears"))
    written = animate(lw.kinematics(mech, steps=72), tmp_path / "a.gif", frames=12)
    with Image.open(written[0]) as gif:
        assert gif.size[0] == 720 and gif.n_frames == 12
    try:
        import imageio_ffmpeg  # noqa: F401
    except ImportError:
        assert written == [tmp_path / "a.gif"]
    else:
        assert written[1] == tmp_path / "a.mp4" and written[1].read_bytes()[4:8] == b"ftyp"


def test_no_name_lies_on_a_slider_block_a_knife_or_the_hatching():
    """The double-cut shears at each of the twelve positions, read back through the Agg renderer: no label's
    box meets the box of a slider block, a knife, a support or a hatching stroke (E and F beside their blocks,
    the links' numbers off the hatching)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    mech, cycle, twelve = _solved("double-cut-shears")
    found = []
    for k in range(12):
        fig = figures.draw_scheme(twelve, k, cycle=cycle)
        canvas = FigureCanvasAgg(fig)
        canvas.draw()
        renderer = canvas.get_renderer()
        ax = fig.axes[0]
        symbols = [
            a
            for a in [*ax.patches, *ax.lines]
            if (a.get_gid() or "").split(":")[0] in ("block", "tool", "support", "hatch")
        ]
        assert len(symbols) > 40
        boxes = [(a.get_gid(), a.get_window_extent(renderer)) for a in symbols]
        for text in ax.texts:
            if not (text.get_gid() or "").startswith("label:"):
                continue
            box = text.get_window_extent(renderer)
            found += [f"position {k}: {text.get_text()!r} on {gid}" for gid, b in boxes if box.overlaps(b)]
    assert found == []


def test_the_drawings_for_cad_speak_the_language_of_the_report(tmp_path):
    """With ``lang="ru"`` the notes of the DXF files are Russian (the layers keep their names), and every text is
    in a TrueType style whose font has the Cyrillic and Greek letters (the default style's SHX font has not)."""
    ezdxf = pytest.importorskip("ezdxf")
    from linkwork.io.dxf import STYLE, write_drawings

    mech, cycle, twelve = _solved("double-cut-shears")
    write_drawings(twelve, 9, tmp_path, cycle=cycle, lang="ru")
    want = {
        "scheme": "кинематическая схема, угол кривошипа",
        "positions": "план 12 положений; 1:1, мм",
        "velocity_plan": "план скоростей, угол кривошипа",
        "acceleration_plan": "полюс π,  масштаб μa = ",  # the Russian school's pole of accelerations
    }
    for name, words in want.items():
        doc = ezdxf.readfile(tmp_path / f"{name}.dxf")
        texts = list(doc.modelspace().query("TEXT MTEXT"))
        note = " ".join(e.dxf.text for e in texts if e.dxf.layer == "NOTES")
        assert words in note
        assert {e.dxf.style for e in texts} == {STYLE}
        assert doc.styles.get(STYLE).dxf.font.lower().endswith(".ttf")
    layers = {e.dxf.layer for e in ezdxf.readfile(tmp_path / "velocity_plan.dxf").modelspace()}
    assert {"ABSOLUTE", "ROTATION", "NOTES"} <= layers


@pytest.mark.parametrize("name", names())
def test_the_working_point_rests_at_position_0(name):
    """Position 0 is an extreme of the first working member (a slider's stroke, a rocker's swing), so the
    point the plans follow, which that member carries where the file names no tool or blow, is at rest
    there: its speed at position 0 is zero to round-off, against its largest speed over the turn."""
    mech = lw.compile(lw.example(name))
    if mech.blow is not None or any(load.kind == "process" for load in mech.loads):
        pytest.skip("the working point is the file's tool or striking point")
    point = mech.point_names[working_point(mech)]
    zero = lw.kinematics(mech, position_angles(mech)[:1])
    cycle = lw.kinematics(mech, steps=360)
    assert np.hypot(*zero.velocity(point)[0]) <= 1e-9 * np.max(np.hypot(*cycle.velocity(point).T))


def test_the_crossings_of_segments_and_boxes_are_counted_pair_by_pair():
    """``segments_hit`` counts, for each box, the segments that cross or touch it: those whose extents overlap
    the box's on both axes and whose line does not leave all four corners on one side, as a test of each pair
    apart finds them (segments inside a box, through it, along its edge, beside it, and NaN ones)."""
    from linkwork.scene.labels import segments_hit

    rng = np.random.default_rng(7)
    segments = rng.uniform(-1, 1, (5, 40, 2, 2))
    segments[:, :3] = [[[-0.1, -0.1], [0.1, 0.1]], [[-2, 0.5], [2, 0.5]], [[0.5, -2], [0.5, 2]]]  # inside, along
    segments[:, 3] = np.nan
    lo = rng.uniform(-1, 0.5, (5, 6, 2))
    boxes = np.concatenate([lo, lo + rng.uniform(0.05, 0.8, (5, 6, 2))], -1)
    boxes[:, 0] = [-0.5, -0.5, 0.5, 0.5]

    def crosses(seg, box):
        (px, py), (qx, qy) = seg
        x0, y0, x1, y1 = box
        if not (max(px, qx) >= x0 and min(px, qx) <= x1 and max(py, qy) >= y0 and min(py, qy) <= y1):
            return False
        sides = [(qx - px) * (cy - py) - (qy - py) * (cx - px) for cx, cy in ((x0, y0), (x1, y0), (x1, y1), (x0, y1))]
        return not (all(s > 0 for s in sides) or all(s < 0 for s in sides))

    want = [[sum(crosses(s, b) for s in segments[a]) for b in boxes[a]] for a in range(len(boxes))]
    got = segments_hit(boxes, segments)
    assert got.dtype == float and got.tolist() == want
    assert got[:, 0].min() >= 3  # the three drawn through the first box
    assert segments_hit(boxes, segments[:, :0]).tolist() == np.zeros((5, 6)).tolist()


def test_the_scheme_draws_each_variant_of_a_sweep_where_the_kinematics_puts_its_points():
    """The scheme of each design variant of a sweep draws the trajectories of the kinematics' points of that
    variant, exactly, and its links' outlines from that variant's dimensions."""
    mech = lw.compile(lw.example("double-cut-shears"))
    key = "links.crank.length"
    crank = lw.parameters(mech)[key]
    sweep = lw.kinematics(mech, steps=72, variants={key: [0.97 * crank, crank, 1.03 * crank]})
    lengths = []
    for v in range(3):
        scene = scheme_scene(sweep, variant=v, at=[])
        want = np.stack([sweep.position(name)[v] for name in scene.path_names], 1)
        np.testing.assert_array_equal(scene.paths, want)
        bar = next(it for it in scene.items if it.name == "crank")
        lengths.append(float(np.hypot(*np.diff(bar.xy, axis=0)[0])))
    np.testing.assert_allclose(lengths, [0.97 * crank, crank, 1.03 * crank], rtol=1e-12)


def _sprung() -> lw.Mechanism:
    """Andrews' squeezer (its spring from b3's D to the frame's C) with a damper from b7's H to the frame's B."""
    from pathlib import Path

    text = (Path(__file__).resolve().parents[1] / "machine" / "andrews-squeezer.yaml").read_text()
    text = text.replace(
        "free_length: 0.07785}", "free_length: 0.07785}\n  push: {type: damper, between: [b7.H, B], damping: 0.5 N*s/m}"
    )
    return lw.compile(lw.loads(text, file="andrews-squeezer.yaml"))


def _check_spring(xy: np.ndarray, a: np.ndarray, b: np.ndarray, tol: float) -> None:
    """A zigzag from ``a`` to ``b``: it ends on the two points, stays within their span, and crosses their
    line 7 times (8 teeth alternating sides)."""
    np.testing.assert_allclose(xy[[0, -1]], [a, b], rtol=0, atol=tol)
    d = b - a
    along = (xy - a) @ d / (d @ d)
    assert along.min() > -1e-9 and along.max() < 1 + 1e-9
    across = (d[0] * (xy[:, 1] - a[1]) - d[1] * (xy[:, 0] - a[0])) / np.linalg.norm(d)
    side = np.sign(across[np.abs(across) > 1e-6 * np.linalg.norm(d)])
    assert len(side) == 8 and np.all(side[1:] == -side[:-1])


def test_springs_and_dampers_are_drawn_between_their_points_in_every_renderer(tmp_path):
    """Andrews' squeezer's spring and an added damper, read back from the matplotlib figure (the lines of gid
    ``spring:spring``, ``damper:push``), the DXF (layers SPRINGS, DAMPERS, mm) and the viewer's payload (the
    elements' points placed by the poses): the zigzag's and the dashpot's ends are the points' positions the
    kinematics solves, at another sample the drawing moves with them."""
    from linkwork.web.payload import cycle_payload

    mech = _sprung()
    kin = lw.kinematics(mech, steps=36)
    c, b = np.array([0.014, 0.072]), np.array([-0.03635, 0.03273])  # the frame's C and B in the file
    for k in (5, 20):
        d, h = (kin.position(p)[k] for p in ("b3.D", "b7.H"))
        fig = figures.draw_scheme(kin, k, cycle=kin)
        lines = {}
        for line in fig.axes[0].lines:
            lines.setdefault(line.get_gid(), []).append(np.asarray(line.get_xydata()))
        assert len(lines["spring:spring"]) == 1 and len(lines["damper:push"]) == 4
        _check_spring(lines["spring:spring"][0], d, c, 1e-12)
        np.testing.assert_allclose([lines["damper:push"][0][0], lines["damper:push"][-1][-1]], [h, b], atol=1e-12)

    payload = cycle_payload(mech, steps=36)
    kin36 = lw.kinematics(mech, np.radians(payload["angles_deg"]))
    scene = payload["scene"]
    assert [(e["kind"], e["name"]) for e in scene["elements"]] == [("spring", "spring"), ("damper", "push")]
    for element, points in zip(scene["elements"], (("b3.D", "C"), ("b7.H", "B")), strict=True):
        for j, (link, at) in enumerate(zip(element["links"], element["at"], strict=True)):
            pose = np.array(scene["poses"][20][link])
            co, si = math.cos(pose[2]), math.sin(pose[2])
            want = kin36.position(points[j])[20] if j == 0 else (c if points[1] == "C" else b)
            np.testing.assert_allclose(
                [pose[0] + co * at[0] - si * at[1], pose[1] + si * at[0] + co * at[1]], want, rtol=0, atol=1e-8
            )
    assert len(scene["elements"][0]["strokes"]) == 1 and len(scene["elements"][1]["strokes"]) == 4

    ezdxf = pytest.importorskip("ezdxf")
    from linkwork.io.dxf import write_scheme

    k = 20
    doc = ezdxf.readfile(write_scheme(scheme_scene(kin, at=[k], cycle=kin), k, tmp_path / "scheme.dxf"))
    polylines = {
        layer: [
            np.array([(v[0], v[1]) for v in e.get_points()])
            for e in doc.modelspace().query("LWPOLYLINE")
            if e.dxf.layer == layer
        ]
        for layer in ("SPRINGS", "DAMPERS")
    }
    assert len(polylines["SPRINGS"]) == 1 and len(polylines["DAMPERS"]) == 4
    d, h = (1000 * kin.position(p)[k] for p in ("b3.D", "b7.H"))
    _check_spring(polylines["SPRINGS"][0], d, 1000 * c, 1e-6)
    np.testing.assert_allclose([polylines["DAMPERS"][0][0], polylines["DAMPERS"][-1][-1]], [h, 1000 * b], atol=1e-6)
