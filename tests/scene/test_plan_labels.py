"""The labels of the plans as the textbook writes them, in every renderer: subscripts, not raw underscores
(matplotlib's mathtext, the viewer's pattern, DXF's MTEXT stacks), the Russian acceleration pole π, the
points' letters rather than the file's names."""

from __future__ import annotations

import re

import numpy as np
import pytest

import linkwork as lw
from linkwork.motion.plans import plan_series
from linkwork.scene.geometry import SUBSCRIPTED, text_runs, text_size
from linkwork.scene.plans import plan_scene
from linkwork.scene.positions import position_angles


def _twelve(name: str):
    mech = lw.compile(lw.example(name))
    return lw.kinematics(mech, position_angles(mech))


@pytest.mark.parametrize(
    ("text", "runs"),
    [
        ("n_ba", [("n", False), ("ba", True)]),
        ("k'_e", [("k'", False), ("e", True)]),
        ("a, n_cb", [("a, n", False), ("cb", True)]),
        ("O1, O2", [("O", False), ("1", True), (", O", False), ("2", True)]),
        ("0, 1, 11", [("0, 1, 11", False)]),
        ("knife_upper.edge", [("knife_upper.edge", False)]),
        ("π", [("π", False)]),
        ("Φ2", [("Φ", False), ("2", True)]),  # the inertia force in Russian, Φ₂ as in the figures' mathtext
        ("G6, Φ6", [("G", False), ("6", True), (", Φ", False), ("6", True)]),
        ("MΦ2''", [("MΦ", False), ("2", True), ("''", False)]),
    ],
)
def test_a_label_splits_into_its_subscripts(text, runs):
    assert text_runs(text) == runs
    # the subscript is set smaller: the label is narrower than its raw text without the underscore
    plain = "".join(r for r, _ in runs)
    assert text_size(text, 1.0)[0] <= text_size(plain, 1.0)[0]
    # the viewer's page reads the same pattern (JavaScript's syntax is the same for it)
    found = [m.group(0) for m in re.finditer(SUBSCRIPTED, text)]
    assert len(found) == sum(sub for _, sub in runs)


def test_the_plans_show_letters_and_no_raw_underscore_in_any_language():
    pytest.importorskip("matplotlib")
    from linkwork import figures

    twelve = _twelve("double-cut-shears")
    for lang in ("en", "ru"):
        fig = figures.acceleration_plan(twelve, 9, lang=lang)
        fig.canvas.draw()  # mathtext parses
        texts = [t.get_text() for t in fig.findobj(lambda a: hasattr(a, "get_text")) if t.get_text()]
        outside = [re.sub(r"\$[^$]*\$", "", t) for t in texts]
        assert not [t for t in outside if "_" in t], texts
        assert not [t for t in texts if "knife" in t], texts
        # the normal components' ends: n with its subscript in mathtext
        assert any(re.fullmatch(r"n\$_\{\\mathregular\{[a-z0-9']+\}\}\$", t) for t in texts), texts


def test_the_russian_acceleration_plan_has_the_pole_pi():
    twelve = _twelve("double-cut-shears")
    vel, acc = plan_series(twelve)
    for series, lang, pole in ((acc, "ru", "π"), (acc, "en", "p"), (vel, "ru", "p")):
        scene = plan_scene(series, [9], lang=lang)
        j = scene.names.index("p")
        assert scene.text[0][j].split(", ")[0] == pole
        assert f" {pole}," in scene.scale_note(lang)


def test_dxf_labels_stack_their_subscripts(tmp_path):
    ezdxf = pytest.importorskip("ezdxf")
    from ezdxf.tools.text import MTextParser, TokenType

    from linkwork.io.dxf import write_drawings

    twelve = _twelve("double-cut-shears")
    write_drawings(twelve, 9, tmp_path, lang="ru")
    labels = [
        e
        for e in ezdxf.readfile(tmp_path / "acceleration_plan.dxf").modelspace().query("MTEXT")
        if e.dxf.layer == "LABELS"
    ]
    tokens = [[(tok.type, tok.data) for tok in MTextParser(e.text)] for e in labels]
    words = ["".join(d for k, d in toks if k == TokenType.WORD) for toks in tokens]
    stacks = [d for toks in tokens for k, d in toks if k == TokenType.STACK]
    assert "π" in words and not [w for w in words if "_" in w]
    # each normal component's end n_XY: n, then XY stacked under an empty upper part (a subscript)
    assert stacks and all(upper == "" and re.fullmatch(r"[a-z0-9']+", lower) for upper, lower, _ in stacks)
    assert len(stacks) == sum(1 for w in words if w.startswith("n"))
    np.testing.assert_equal(len(labels), len(words))


def _contrast(aci: int, background: tuple[int, int, int]) -> float:
    """WCAG contrast ratio of an AutoCAD colour against a background (relative luminance of sRGB)."""
    from ezdxf.colors import aci2rgb

    def luminance(rgb):
        c = np.array(rgb, dtype=float) / 255
        c = np.where(c <= 0.03928, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
        return float(c @ [0.2126, 0.7152, 0.0722])

    a, b = luminance(aci2rgb(aci)), luminance(background)
    return (max(a, b) + 0.05) / (min(a, b) + 0.05)


def test_dxf_layers_tell_the_kinds_apart_on_black_and_white(tmp_path):
    ezdxf = pytest.importorskip("ezdxf")
    from linkwork.io.dxf import write_drawings

    twelve = _twelve("double-cut-shears")
    write_drawings(twelve, 9, tmp_path, lang="en")
    for kind in ("velocity", "acceleration"):
        doc = ezdxf.readfile(tmp_path / f"{kind}_plan.dxf")
        looks = {lay.dxf.name: (lay.dxf.color, lay.dxf.linetype) for lay in doc.layers}
        vectors = ["ABSOLUTE", "ROTATION", "NORMAL", "TANGENTIAL", "TRANSPORT", "CORIOLIS", "SLIDING"]
        assert len({looks[name] for name in vectors}) == len(vectors), looks
        assert looks["TANGENTIAL"][1] != "Continuous" and looks["TANGENTIAL"][0] != looks["ROTATION"][0]
        # the legend: a stroke on the layer of each kind of vector drawn, and its name
        msp = doc.modelspace()
        tags = [(line.get_xdata("LINKWORK")[0].value, line.dxf.layer) for line in msp.query("LINE")]
        legend = {tag.split(":")[1]: layer for tag, layer in tags if tag.startswith("legend:")}
        drawn = {layer for tag, layer in tags if not tag.startswith("legend:")}
        assert set(legend.values()) == drawn and len(legend) >= 3
        notes = " ".join(e.plain_text() for e in msp.query("MTEXT") if e.dxf.layer == "NOTES")
        assert "tangential" in notes or kind == "velocity"
    doc = ezdxf.readfile(tmp_path / "scheme.dxf")
    links = doc.layers.get("LINKS").dxf.color
    assert _contrast(links, (0, 0, 0)) >= 3 and _contrast(links, (255, 255, 255)) >= 3
    # the title above everything drawn, the crank pin's circle (a trajectory) included
    msp = doc.modelspace()
    top = max(max(y for _, y, *_ in e.get_points()) for e in msp.query("LWPOLYLINE"))
    top = max(top, max(c.dxf.center.y + c.dxf.radius for c in msp.query("CIRCLE")))
    (note,) = [e for e in msp.query("TEXT") if e.dxf.layer == "NOTES"]
    assert note.dxf.align_point.y > top


def test_the_sheets_of_twelve_plans_letter_their_points_readably():
    """A sheet of the twelve plans (``--position all``) letters its points at 8.5 points or more (as large as
    the legend: about 24 pixels at the 200 dpi of the report's PNG)."""
    pytest.importorskip("matplotlib")
    from linkwork.figures.plans import plan_sheet

    kin = lw.kinematics(lw.compile(lw.example("double-cut-shears")), steps=36)
    fig = plan_sheet(kin, "velocity", lang="ru")
    letters = [t for ax in fig.axes for t in ax.texts if t.get_text() and t.get_color() != "#777777"]
    assert len(letters) >= 12
    assert min(t.get_fontsize() for t in letters) >= 8.5


def test_the_russian_inertia_forces_are_subscripted_in_the_dxf_as_the_weights_are():
    from linkwork.io.dxf import mtext

    assert mtext("G6, Φ6") == "G\\S^ 6;, Φ\\S^ 6;"
    assert mtext("MΦ2'") == "MΦ\\S^ 2;'"
