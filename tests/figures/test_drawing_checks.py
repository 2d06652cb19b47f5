"""The drawing checks (tests/drawing_checks.py) see every text a reader sees: texts of several lines and the
figure's suptitle among them, so that their size and overlaps are checked."""

from __future__ import annotations

import pytest

pytest.importorskip("matplotlib")


def test_texts_of_several_lines_and_the_suptitle_are_drawn_texts():
    from matplotlib.figure import Figure

    from drawing_checks import drawn_texts

    fig = Figure(figsize=(4, 3))
    ax = fig.add_subplot()
    fig.suptitle("name\nposition 6")
    ax.text(0.5, 0.5, "Φ₂\nG₂")
    ax.text(0.2, 0.2, "")  # an empty text is not drawn
    texts = {t.get_text() for t in drawn_texts(fig)}
    assert {"name\nposition 6", "Φ₂\nG₂"} <= texts
    assert "" not in texts


def test_two_texts_of_several_lines_on_each_other_are_an_overlap():
    from matplotlib.figure import Figure

    from drawing_checks import overlaps

    fig = Figure(figsize=(4, 3))
    fig.text(0.5, 0.5, "first\nsecond", ha="center", va="center")
    fig.text(0.5, 0.5, "third\nfourth", ha="center", va="center")
    found = overlaps(fig)
    assert len(found) == 1 and "'first\\nsecond'" in found[0] and "'third\\nfourth'" in found[0], found
