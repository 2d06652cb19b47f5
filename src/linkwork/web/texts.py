"""The words of the viewer's page in a language: its own texts and those it shares with the report, from the
catalogues of :mod:`linkwork.lang`, and the units it shows editable values in."""

from __future__ import annotations

from typing import Any

from linkwork.lang import LANGUAGES, check_lang, texts
from linkwork.web.edits import DISPLAY, display_unit

#: The texts of the catalogues (:mod:`linkwork.lang`) the page shows besides its own (``view.*``): the plans'
#: names and units, and the units of forces.
SHARED_TEXTS = (
    "plan.velocity",
    "plan.acceleration",
    "plan.unit.velocity",
    "plan.unit.acceleration",
    "unit.N",
    "unit.kN",
    "unit.Nm",
)


def page_texts(lang: str) -> dict[str, str]:
    """Every text the page writes, key: its text in ``lang`` (fields in braces, filled by the page): the
    ``view.*`` texts of the catalogues and :data:`SHARED_TEXTS`."""
    check_lang(lang)
    row = LANGUAGES.index(lang)
    table = texts()
    return {key: table[key][row] for key in [key for key in table if key.startswith("view.")] + list(SHARED_TEXTS)}


def display_units(lang: str) -> dict[str, list[Any]]:
    """The unit the page shows each kind of editable value in, in ``lang``, and its factor from SI."""
    return {kind: [display_unit(kind, lang), factor] for kind, (_, factor) in DISPLAY.items()}
