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
