"""The texts of the report and the drawings, in English and Russian: a catalogue a language and :func:`t`.

The texts live in data files, ``texts/en.toml`` and ``texts/ru.toml`` (a key and its text a line); a third
language is a third file and its name added to :data:`LANGUAGES`.

``t("caption.velocity_plan", "ru")`` is ``"План скоростей"``; a text with fields takes them as
keywords, ``t("title.hodograph", "en", name="four-bar", joint="O2")`` (braces of their own doubled, as
``str.format`` reads them).  The Russian texts follow
the notation of the Russian school of the theory of machines and mechanisms (план положений,
план скоростей, полюс p, масштаб μ_v, кинематическая схема, кинематические диаграммы); names from
the mechanism's file and the symbols of quantities stay as they are.  Units are written in each
language's designations (mm and мм).
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from pathlib import Path
from typing import Any

from linkwork.errors import LinkworkError
from linkwork.limits import excerpt

#: The languages of the texts, the first the default.
LANGUAGES = ("en", "ru")

#: The folder of the catalogues: one file a language, ``<lang>.toml``, each with every key.
CATALOGUES = Path(__file__).resolve().parent / "texts"


def catalogue(lang: str) -> dict[str, str]:
    """The texts of ``lang``, key -> text, read from its catalogue (``texts/<lang>.toml``)."""
    import tomllib  # here: ``linkwork --help`` imports this module, and reads no text

    with (CATALOGUES / f"{lang}.toml").open("rb") as f:
        return tomllib.load(f)


def _table() -> dict[str, tuple[str, ...]]:
    """key: its text in each language of :data:`LANGUAGES`, in that order; a key the first language's catalogue
    lacks in another is an error of the catalogues (tests/test_lang.py checks them), here a ``KeyError``."""
    texts = [catalogue(lang) for lang in LANGUAGES]
    return {key: tuple(each[key] for each in texts) for key in texts[0]}


@functools.cache
def texts() -> dict[str, tuple[str, ...]]:
    """key: (English, Russian), from the catalogues, read when first asked for (not when ``linkwork --help``
    imports this module)."""
    return _table()


def __getattr__(name: str) -> Any:
    if name == "TEXTS":  # the table, as ``from linkwork.lang import TEXTS`` names it
        return texts()
    raise AttributeError(f"module 'linkwork.lang' has no attribute {name!r}")


def check_lang(lang: str) -> None:
    """Raise :class:`~linkwork.errors.LinkworkError` unless ``lang`` is one of :data:`LANGUAGES`."""
    if lang not in LANGUAGES:
        raise LinkworkError(f"--lang: expected one of {', '.join(LANGUAGES)}, got {excerpt(lang)!r}")


def link_named(name: str, translate: Callable[[str], str]) -> str:
    """A link's name as a table writes it: the frame (the link the file calls ``frame``) in the report's language
    (``translate``: a key to its text, e.g. ``"стойка"``), every other link by its name in the file."""
    return translate("link.frame") if name == "frame" else name


def kind_named(kind: str, name: str) -> str:
    """``rocker output``: a member's kind and its name, the word once where the name is the kind's word
    (``rocker``, not ``rocker rocker``)."""
    return kind if name.strip().lower() == kind.lower() else f"{kind} {name}"


def group_kind(kind: str, lang: str) -> str:
    """An Assur group's kind (``RRP``) in the notation of the language (``ВВП`` in Russian: вращательная,
    поступательная)."""
    return kind.translate(str.maketrans("RP", "ВП")) if lang == "ru" else kind


def group_label(label: str, lang: str) -> str:
    """A group's label (``II(4,5) RRP``) with its kind in the notation of the language."""
    head, _, kind = label.partition(" ")
    return f"{head} {group_kind(kind, lang)}" if kind else head


#: The keys and words of a file's loads and machine as the report's input section shows them, in Russian (in
#: English they stay as the file writes them).
FILE_WORDS_RU = {
    "tools": "инструменты",
    "at": "точка",
    "on": "звено",
    "joint": "пара",
    "axis": "ось",
    "workpiece": "заготовка",
    "penetration": "относительное внедрение",
    "force": "сила",
    "moment": "момент",
    "value": "величина",
    "power": "мощность",
    "speed": "частота вращения",
    "synchronous": "синхронная частота вращения",
    "breakdown": "кратность максимального момента",
    "inertia": "момент инерции",
    "ratio": "передаточное отношение",
    "efficiency": "КПД",
    "process": "технологическая",
    "induction": "асинхронный",
    "motor": "двигатель",
    "gear": "передача",
    "flywheel": "маховик",
    "type": "тип",
    "delta": "δ",
}

#: Units as a file writes them, in Russian.
FILE_UNITS_RU = {
    "kg*m^2": "кг·м²",
    "N*m": "Н·м",
    "kN*m": "кН·м",
    "rad/s": "рад/с",
    "rpm": "об/мин",
    "kN": "кН",
    "kW": "кВт",
    "deg": "°",
    "mm": "мм",
    "kg": "кг",
    "m": "м",
    "N": "Н",
    "W": "Вт",
    "s": "с",
    "h": "ч",
}


def file_word(word: str, lang: str) -> str:
    """A key or word of a file (``power``, ``process``) in ``lang``: itself in English, in Russian its Russian
    (:data:`FILE_WORDS_RU`), a name of the file's own as it is."""
    return FILE_WORDS_RU.get(word, word) if lang == "ru" else word


def file_value(text: str, lang: str) -> str:
    """A value as a file writes it (``250 kN``, ``0.03 kg*m^2``, ``90 deg``) in ``lang``: in Russian its units in
    Russian and a decimal comma (``250 кН``, ``0,03 кг·м²``, ``90°``); in English as written."""
    import re

    if lang != "ru":
        return text
    units = "|".join(re.escape(u) for u in FILE_UNITS_RU)

    def one(m: re.Match[str]) -> str:
        number, unit = m.group(1).replace(".", ","), FILE_UNITS_RU[m.group(2)]
        return f"{number}{unit}" if unit == "°" else f"{number} {unit}"

    out = re.sub(rf"(-?\d+(?:\.\d+)?(?:e[-+]?\d+)?)\s*({units})(?![\w*^/])", one, text)
    return re.sub(r"(?<![\w.])(-?\d+)\.(\d+)(?![\w.])", r"\1,\2", out)


_SUPERSCRIPT = str.maketrans("-+0123456789", "⁻⁺⁰¹²³⁴⁵⁶⁷⁸⁹")


def russian_numbers(text: str) -> str:
    """The numbers of a text as Russian writes them: a decimal comma (``294.3`` -> ``294,3``), a power of ten
    for an exponent (``2.5e+05`` -> ``2,5·10⁵``), numbers with decimals listed apart by semicolons
    (``(7.465, 49.77)`` -> ``(7,465; 49,77)``); a number glued to a name (``O1.x``, ``v1.2``) as it is."""
    import re

    def power(m: re.Match[str]) -> str:
        exponent = str(int(m.group(2)))
        return f"{m.group(1)}·10{exponent.translate(_SUPERSCRIPT)}"

    def apart(m: re.Match[str]) -> str:  # numbers with decimals listed apart by semicolons: (7,465; 49,77)
        return m.group(1) + ("; " if "." in m.group(1) + m.group(2) else ", ")

    text = re.sub(r"(?<![\w.])(-?\d+(?:\.\d+)?), (?=(-?\d+(?:\.\d+)?)(?![\w.]))", apart, text)
    after = r"(?![A-Za-zА-Яа-яЁё_0-9.])"  # not glued to a name ("²" may follow: 3.142² -> 3,142²)
    out = re.sub(rf"(?<![\w.])(-?\d+(?:\.\d+)?)e([-+]?\d+){after}", power, text)
    return re.sub(rf"(?<![\w.,])(-?\d+)\.(\d+){after}", r"\1,\2", out)


def numbers(text: str, lang: str) -> str:
    """``text`` with its numbers as ``lang`` writes them (:func:`russian_numbers` in Russian)."""
    return russian_numbers(text) if lang == "ru" else text


def russian_html(page: str) -> str:
    """:func:`russian_numbers` on the text of an HTML page, not on its tags, styles, scripts and ``<pre>`` blocks
    (a file's own text)."""
    import re

    parts = re.split(r"(<pre.*?</pre>|<style.*?</style>|<script.*?</script>|<[^>]*>)", page, flags=re.S)
    return "".join(p if k % 2 else russian_numbers(p) for k, p in enumerate(parts))


def t(key: str, lang: str = "en", /, **values: Any) -> str:
    """The text ``key`` in ``lang`` (``"en"`` or ``"ru"``), its fields filled from ``values``.

    Raises
    ------
    KeyError
        For a key the table does not have.
    LinkworkError
        For a language it does not have.
    """
    check_lang(lang)
    return texts()[key][LANGUAGES.index(lang)].format(**values)


def friction_problem(problem: Any, lang: str = "en") -> str:
    """A :class:`~linkwork.errors.FrictionWarning` (its ``kind`` and the crank angles φ of its ``angles``, deg) as
    the report and the viewer say it in ``lang``: the first eight angles, then an ellipsis."""
    at = ", ".join(f"{x:.0f}" for x in problem.angles[:8]) + (" …" if len(problem.angles) > 8 else "")
    return t(f"friction.{problem.kind}", lang, at=at)
