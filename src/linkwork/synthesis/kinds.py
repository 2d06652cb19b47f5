"""The kinds of synthesis, one :class:`Kind` each in one registry (:data:`KINDS`): its name, its requirements
record (:mod:`linkwork.requirements`), the function that synthesises it from that record, and the family the
viewer's slider offers of a file it wrote.  Adding a kind is its record, its module and one entry here."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from linkwork.requirements import RECORDS
from linkwork.synthesis import crank_rocker, families, shears, slider_crank, slotted_lever, toggle_press
from linkwork.synthesis.common import Synthesis
from linkwork.synthesis.measuring import Own, knives


@dataclass(frozen=True)
class Kind:
    """A kind of synthesis.

    Attributes
    ----------
    name : str
        ``"slider-crank"``, ...: the name ``lw.synthesize``, the command and a file's ``requirements: kind`` use.
    record : type
        Its requirements, a frozen dataclass (:data:`linkwork.requirements.RECORDS`).
    synthesize : callable
        ``synthesize(record) -> Synthesis``: the mechanism meeting a record of requirements (SI).
    family : callable or None
        ``family(spec, given) -> dict or None``: the family a file of this kind leaves, for the viewer's slider
        (``given``: the file's ``requirements:``), as :func:`~linkwork.synthesis.achieved.family_members` states it.
    measure : callable or None
        ``measure(kin, spec) -> dict``: what the kind measures of a solved turn (every variant) beside what every
        kind does, in the one measurement (:func:`~linkwork.synthesis.measuring.measure`) that its verification,
        its tolerances and the report's requirements read.
    """

    name: str
    record: type
    synthesize: Callable[[Any], Synthesis]
    family: Callable[[Any, dict[str, Any]], dict[str, Any] | None] | None = None
    measure: Own | None = None


def _kinds(*kinds: Kind) -> dict[str, Kind]:
    registry = {kind.name: kind for kind in kinds}
    assert list(registry) == list(RECORDS) and all(k.record is RECORDS[k.name] for k in kinds)
    return registry


#: The kinds, by name, in the order :data:`linkwork.requirements.RECORDS` lists them.
KINDS: dict[str, Kind] = _kinds(
    Kind(slider_crank.KIND, RECORDS[slider_crank.KIND], slider_crank.synthesize, families.slider_crank_family),
    Kind(crank_rocker.KIND, RECORDS[crank_rocker.KIND], crank_rocker.synthesize, families.crank_rocker_family),
    Kind(slotted_lever.KIND, RECORDS[slotted_lever.KIND], slotted_lever.synthesize, families.slotted_lever_family),
    Kind(toggle_press.KIND, RECORDS[toggle_press.KIND], toggle_press.synthesize),
    Kind(shears.KIND, RECORDS[shears.KIND], shears.synthesize, families.shears_family, knives),
)
