"""``--pdf`` carries the report's tables, set within the width of an A4 page, in the report's language."""

from __future__ import annotations

import re

import pytest

pytest.importorskip("matplotlib")


@pytest.fixture
def pages(monkeypatch):
    """The figures the PDF's pages are saved from, in order (PdfPages.savefig kept as it is)."""
    from matplotlib.backends.backend_pdf import PdfPages

    kept = []
    save = PdfPages.savefig

    def keep(self, figure=None, **kwargs):
        kept.append(figure)
        return save(self, figure, **kwargs)

    monkeypatch.setattr(PdfPages, "savefig", keep)
    return kept


@pytest.mark.slow  # over the default lane's budget on the NumPy kernels (tests/conftest.py)
def test_the_pdf_has_the_tables_within_the_page(tmp_path, pages, sketched_figures):
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from typer.testing import CliRunner

    import linkwork.cli.analyze  # noqa: F401  (registers the command)
    from linkwork.cli.main import app

    out = tmp_path / "r"
    args = [
        "analyze",
        "double-cut-shears",
        "--out",
        str(out),
        "--steps",
        "36",
        "--no-animation",
        "--pdf",
        "--lang",
        "ru",
    ]
    result = CliRunner().invoke(app, args)
    assert result.exit_code == 0, result.output
    assert (out / "report.pdf").stat().st_size > 10000
    texts = []
    for fig in pages:
        renderer = FigureCanvasAgg(fig).get_renderer()
        width = fig.get_figwidth() * fig.dpi
        for t in fig.texts:
            if t.get_text():
                box = t.get_window_extent(renderer)
                assert box.x0 >= 0 and box.x1 <= width + 0.5, t.get_text()  # nothing off the page
                texts.append(t.get_text())
    words = "\n".join(texts)
    # the 12 positions' table (its heading and the crank's angle of position 11), the joints' table in Russian
    assert "положение" in words and "кривошип" in words
    assert "стойка → crank" in words and "frame" not in words.replace("knife", "")


@pytest.mark.parametrize("lang", ["en", "ru"])
def test_the_pdf_writes_the_numbers_of_its_tables_and_paragraphs_as_the_page_does(tmp_path, pages, lang):
    """In Russian the PDF's tables and paragraphs have the HTML page's decimal commas and powers of ten (``320,5``,
    ``1,06·10⁴``), a name glued to a number (``O1.x``) as it is; in English the numbers as written."""
    from types import SimpleNamespace

    from linkwork.lang import t
    from linkwork.report.html import Section
    from linkwork.report.page import write_pdf

    body = [
        "<p>нужно 320.5 мм, O1.x</p>",
        "<table><tr><th>φ, °</th><th>M, Н·м</th></tr><tr><td>86.6</td><td>1.06e+04</td></tr></table>",
    ]
    run = SimpleNamespace(
        lang=lang,
        mech=SimpleNamespace(name="m", structure=SimpleNamespace(formula="W = 1")),
        sections=[Section("forces", "Силы", body)],
        figures={},
        t=lambda key, **values: t(key, lang, **values),
    )
    write_pdf(run, tmp_path / "report.pdf")
    words = [x.get_text() for page in pages for x in page.texts]
    if lang == "ru":
        assert {"86,6", "1,06·10⁴"} <= set(words), words
        assert any("320,5" in w and "O1.x" in w for w in words), words
        assert not any(re.search(r"\d\.\d", w.replace("O1.x", "")) for w in words), words
    else:
        assert {"86.6", "1.06e+04"} <= set(words), words
