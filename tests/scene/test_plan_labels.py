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


@pytest.mark.parametrize(("text", "runs"), [
    ("n_ba", [("n", False), ("ba", True)]),
    ("k'_e", [("k'", False), ("e", True)]),
    ("a, n_cb", [("a, n", False), ("cb", True)]),
    ("O1, O2", [("O", False), ("1", True), (", O", False), ("2", True)]),
    ("0, 1, 11", [("0, 1, 11", False)]),
    ("knife_upper.edge", [("knife_upper.edge", False)]),
    ("π", [("π", False)]),
])  # fmt: skip
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
        assert any(re.fullmatch(r"n\$_\{\\mathregular\{[a-z]+\}\}\$", t) for t in texts), texts


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
    labels = [e for e in ezdxf.readfile(tmp_path / "acceleration_plan.dxf").modelspace().query("MTEXT")
              if e.dxf.layer == "LABELS"]  # fmt: skip
    tokens = [[(tok.type, tok.data) for tok in MTextParser(e.text)] for e in labels]
    words = ["".join(d for k, d in toks if k == TokenType.WORD) for toks in tokens]
    stacks = [d for toks in tokens for k, d in toks if k == TokenType.STACK]
    assert "π" in words and not [w for w in words if "_" in w]
    # each normal component's end n_XY: n, then XY stacked under an empty upper part (a subscript)
    assert stacks and all(upper == "" and re.fullmatch(r"[a-z]+", lower) for upper, lower, _ in stacks)
    assert len(stacks) == sum(1 for w in words if w.startswith("n"))
    np.testing.assert_equal(len(labels), len(words))
