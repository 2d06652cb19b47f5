"""The texts in English and Russian (:mod:`linkwork.lang`, a catalogue a language in ``texts/``)."""

from __future__ import annotations

import re
import string

import pytest

from linkwork.errors import LinkworkError
from linkwork.lang import LANGUAGES, TEXTS, t


def _fields(text: str) -> set[str]:
    return {name for _, name, _, _ in string.Formatter().parse(text) if name}


def test_every_text_has_both_languages_with_the_same_fields():
    """Each text fills the same fields in both languages, and the Russian one is written in Russian: it has
    Cyrillic letters unless it is only symbols, units and fields (``φ, °``, ``Fx, {unit}``)."""
    for key, texts in TEXTS.items():
        assert len(texts) == len(LANGUAGES) and all(texts), key
        en, ru = texts
        assert _fields(en) == _fields(ru), key
        words = re.sub(r"\{[^{}]*\}|\\[A-Za-z]+|\bF[xy]\b", "", ru)  # fields, mathtext, force components
        assert re.search("[а-яА-ЯёЁ]", words) or not re.search("[A-Za-z]{2,}", words), key
        t(key, "ru", **dict.fromkeys(_fields(ru), "x"))  # formats


def test_a_text_is_filled_and_an_unknown_language_or_key_refused():
    assert t("title.hodograph", "ru", name="four-bar", joint="O2") == "four-bar: реакция в паре O2, положения 0–11"
    assert t("axis.inertia", "ru") == r"$J_\mathrm{пр}$, кг·м²"
    with pytest.raises(LinkworkError, match="expected one of en, ru, got 'de'"):
        t("caption.scheme", "de")
    with pytest.raises(KeyError):
        t("no.such.text", "en")


def test_each_language_is_one_catalogue_with_every_key_and_nothing_else():
    """A catalogue a language (``texts/<lang>.toml``), each with the keys of every other and the same fields in
    each text; the folder holds no catalogue of a language the package does not list."""
    from linkwork.lang import CATALOGUES, catalogue

    assert sorted(p.stem for p in CATALOGUES.glob("*.toml")) == sorted(LANGUAGES)
    texts = {lang: catalogue(lang) for lang in LANGUAGES}
    keys = set(texts[LANGUAGES[0]])
    for lang, each in texts.items():
        assert set(each) == keys, (lang, sorted(keys ^ set(each)))
        assert all(isinstance(v, str) and v for v in each.values()), lang
    for key in keys:
        assert len({frozenset(_fields(texts[lang][key])) for lang in LANGUAGES}) == 1, key


def test_a_catalogue_missing_a_key_is_found(tmp_path, monkeypatch):
    """The check above fails on a catalogue that lacks a key the others have."""
    import linkwork.lang as lang

    for name in LANGUAGES:
        text = (lang.CATALOGUES / f"{name}.toml").read_text(encoding="utf-8")
        if name == "ru":
            text = "\n".join(line for line in text.splitlines() if not line.startswith('"caption.scheme"'))
        (tmp_path / f"{name}.toml").write_text(text, encoding="utf-8")
    monkeypatch.setattr(lang, "CATALOGUES", tmp_path)
    assert "caption.scheme" in lang.catalogue("en") and "caption.scheme" not in lang.catalogue("ru")
    with pytest.raises(KeyError, match="caption.scheme"):
        lang._table()


def test_russian_numbers_take_a_decimal_comma_and_a_power_of_ten_but_names_stay():
    from linkwork.lang import russian_html, russian_numbers

    assert russian_numbers("G6 294.3 Н; R36 = 4.912e+05 Н; h = 8.266e-15 мм; φ = 86.6°") == (
        "G6 294,3 Н; R36 = 4,912·10⁵ Н; h = 8,266·10⁻¹⁵ мм; φ = 86,6°"
    )
    assert russian_numbers("II(2,3), O1.x, v1.2.3, ISO 281, -150") == "II(2,3), O1.x, v1.2.3, ISO 281, -150"
    assert russian_numbers("ω2²·l = 3.142²·0.4 м") == "ω2²·l = 3,142²·0,4 м"
    assert (
        russian_numbers("(7.465, 49.77) Н·с; 0, 0.15, 0.3; звенья 6, 7")
        == "(7,465; 49,77) Н·с; 0; 0,15; 0,3; звенья 6, 7"
    )
    page = "<style>td{padding:0.5em}</style><p>0.05 м</p><pre>length: 0.10</pre><img src='data:x/y;base64,A1.2'>"
    assert russian_html(page) == page.replace("<p>0.05 м</p>", "<p>0,05 м</p>")
