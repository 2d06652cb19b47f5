"""Synthesis from requirements: a mechanism file for a stroke (or swing), a time ratio and a bound on the
pressure (transmission) angle.

One module per kind, closed forms first; each returns a :class:`~linkwork.synthesis.common.Synthesis` whose
file is written through the one YAML writer of mechanism files, once, with its ``requirements:``; the stroke,
time ratio and extreme angles of the mechanism it describes are measured by the analysis
(:func:`~linkwork.synthesis.measuring.measure`, with the tolerances its lengths' rounding implies) before it is
written.
"""

from __future__ import annotations

import math
from typing import Any

from linkwork.errors import LinkworkError, SynthesisError
from linkwork.requirements import QUANTITIES, RECORDS, needs, required
from linkwork.synthesis.common import Family, Synthesis

__all__ = ["KINDS", "QUANTITIES", "Family", "Synthesis", "synthesize"]


def __getattr__(name: str) -> Any:
    """:data:`KINDS`, the registry of the kinds (:mod:`linkwork.synthesis.kinds`), loaded when first asked for."""
    if name == "KINDS":
        from linkwork.synthesis.kinds import KINDS

        return KINDS
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def synthesize(kind: str, **requirements: Any) -> Synthesis:
    """A mechanism of ``kind`` meeting ``requirements`` (SI: m, rad, ratios), verified by the analysis.

    Lengths and angles may also be strings with their unit (``stroke="400 mm"``, ``swing="45 deg"``).
    ``slider-crank``: ``stroke``, ``time_ratio``, and one of ``rod_ratio``, ``offset``; ``max_pressure_angle`` a bound;
    ``force`` (N) a working load over the last ``working`` (m) of the downward stroke; else ``criterion`` picks from the
    family: ``"pressure"`` (the least largest pressure angle) or ``"torque"`` (the least peak driving torque under the
    load, within the bound).  ``crank-rocker``: ``swing``, ``time_ratio``, and one of ``rocker``, ``frame`` (lengths);
    ``min_transmission_angle`` a bound.  ``slotted-lever``: ``stroke``, ``time_ratio`` (> 1), one of ``frame``,
    ``crank`` (else the greatest frame), ``rod`` (else the shortest meeting ``max_pressure_angle``, 10 deg by
    default).  ``toggle-press``: ``stroke``, ``force`` (N) at ``before`` (m) before the bottom dead centre,
    ``torque`` (N m, the crank's limit); ``swing`` and ``time_ratio`` of its four-bar.  These take ``speed``
    (default ``"60 rpm"``), ``section`` (the steel bars' width and height, m) and ``density``.
    ``double-cut-shears`` (the bundled file's structure, its masses and loads kept): ``upper_stroke``, ``lower_stroke``,
    ``time_ratio`` (the knives closing over opening), one of ``overlap`` (when closed), ``opening``; ``crank`` fixes the
    family's free crank length, else ``criterion`` picks it (``"pressure"``, the default: the greatest least
    transmission angle, or ``"torque"``, the least peak driving torque under the file's loads); ``speed`` replaces the
    file's.  Every kind keeps the design rule ``min_transmission_angle`` (rad): the least transmission angle of every
    dyad over the turn, 40 deg unless given (:data:`~linkwork.synthesis.common.LEAST_TRANSMISSION`), measured on
    the written file; the file's ``requirements:`` carries it.

    Parameters
    ----------
    kind : str
        ``"slider-crank"``, ``"crank-rocker"``, ``"slotted-lever"``, ``"toggle-press"`` or
        ``"double-cut-shears"``.
    **requirements
        The kind's requirements named above (the fields of its record,
        :data:`linkwork.requirements.RECORDS`): lengths in m, angles in rad, forces in N, torques in N m, or
        strings with their unit; ``speed`` a string (``"60 rpm"``).

    Returns
    -------
    Synthesis
        The dimensions found, the values the closed forms predict beside those measured on the written
        mechanism file (``predicted``, ``measured``), the file's ``text`` and its ``spec``.

    Raises
    ------
    SynthesisError
        An unknown kind or requirement, or requirements that cannot be met together (the message names
        them and the nearest value that can be met).

    Examples
    --------
    >>> import linkwork as lw
    >>> s = lw.synthesize("crank-rocker", swing="45 deg", time_ratio=1.2, rocker=0.3)
    >>> round(s.measured["time_ratio"], 3)
    1.2
    """
    if kind not in RECORDS:
        raise SynthesisError(f"unknown kind {kind!r}: expected one of {', '.join(RECORDS)}")
    known = list(needs(kind))
    unknown = [name for name in requirements if name not in known]
    if unknown:
        raise SynthesisError(f"{kind}: unknown requirement {', '.join(unknown)}; expected {', '.join(known)}")
    missing = [name for name in required(kind) if name not in requirements]
    if missing:
        raise SynthesisError(f"{kind}: missing requirement {', '.join(missing)}")
    si = {name: _si(name, value) for name, value in requirements.items()}
    in_range(si)
    import numpy as np

    from linkwork.synthesis.common import dimensioned
    from linkwork.synthesis.kinds import KINDS

    # the requirements that set the mechanism's scale, and so the step its file is dimensioned to (0.1 mm from 10 mm)
    scale = [float(si[n]) for n, need in needs(kind).items() if need.scale and isinstance(si.get(n), float | int)]
    try:
        # the closed forms' NaN and inf are refused by the checks that follow them; the file dimensioned to 0.1 mm
        with np.errstate(all="ignore"), dimensioned(*scale):
            result = KINDS[kind].synthesize(KINDS[kind].record(**si))
        return _carrying(result, {"criterion": requirements["criterion"]} if "criterion" in requirements else {})
    except SynthesisError:
        raise
    except LinkworkError as exc:  # the written mechanism, which the user never sees, cannot be read or analysed
        raise SynthesisError(f"{kind}: {_request(si)} give a mechanism the analysis cannot take: {_own(exc)}") from None


def in_range(si: dict[str, Any]) -> None:
    """Raise :class:`SynthesisError` for a requirement (SI) no mechanism can be made to: a length, force or moment
    that is not finite or beyond :data:`~linkwork.synthesis.common.LENGTHS` (
    :data:`~linkwork.limits.MAX_MAGNITUDE` for forces and moments), a time ratio not in (0, :data:`TIME_RATIOS`],
    an angle not finite, a speed that is not a positive angular speed within the file's bound, a section out of the
    lengths' range.  Signs and each kind's own bounds are the kinds' to check, with their words."""
    from linkwork.limits import MAX_MAGNITUDE
    from linkwork.synthesis.common import LENGTHS, TIME_RATIOS

    for name, value in si.items():
        kind = QUANTITIES.get(name, "ratio" if name.endswith("ratio") else None)
        if kind is None or not isinstance(value, float | int):
            continue
        words = name.replace("_", " ")
        if not math.isfinite(value):
            raise SynthesisError(f"{words} {value!r}: expected a finite value")
        top = LENGTHS[1] if kind == "length" else MAX_MAGNITUDE
        if kind in ("length", "force", "moment") and abs(value) > top:
            raise SynthesisError(f"{words} {_si_text(value, kind)}: expected at most {_si_text(top, kind)}")
        if kind == "length" and 0 < value < LENGTHS[0]:
            raise SynthesisError(f"{words} {value:g} m: expected at least {LENGTHS[0] * 1e6:g} um")
        if name == "time_ratio" and not 0 < value <= TIME_RATIOS:
            raise SynthesisError(
                f"time ratio K = {value:g}: expected a K over 0 and at most {TIME_RATIOS:g} (the return stroke "
                f"then takes {360 / (1 + TIME_RATIOS):.3g} deg of the turn)"
            )
    if "speed" in si:
        _speed(si["speed"])
    for size in si.get("section", ()):
        if not LENGTHS[0] <= size <= LENGTHS[1]:
            raise SynthesisError(
                f"section {size!r} m: expected the bars' width and height from {LENGTHS[0] * 1e6:g} um to "
                f"{LENGTHS[1]:g} m"
            )


def _speed(text: Any) -> None:
    """Raise where the speed written in the file is not a positive angular speed the file can hold."""
    from linkwork.limits import MAX_MAGNITUDE
    from linkwork.units import parse_quantity

    try:
        w = parse_quantity(text, "angular_speed")
    except LinkworkError as exc:
        raise SynthesisError(f"speed: {exc}") from None
    if not 0 < w <= MAX_MAGNITUDE:
        raise SynthesisError(
            f"speed {text!s:.40}: expected a positive speed of at most {MAX_MAGNITUDE:g} rad/s (the file gives the "
            "direction of turning)"
        )


def _si_text(value: float, kind: str) -> str:
    return f"{value:g} {dict(length='m', force='N', moment='N*m').get(kind, '')}".rstrip()


def _request(si: dict[str, Any]) -> str:
    """The requirements as the user gave them (SI), in words: the options, not the file they give."""
    from linkwork.synthesis.achieved import written

    given = written("", {name: v for name, v in si.items() if isinstance(v, float | int) and not isinstance(v, bool)})
    return ", ".join(f"{name.replace('_', ' ')} {value}" for name, value in given.items() if name != "kind")


def _own(exc: Exception) -> str:
    """``exc``'s first line without the written file's name and line (a file the user never sees)."""
    import re

    first = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
    return re.sub(r"<synthesised>(:\d+)*:?\s*", "", first)


def _carrying(result: Synthesis, extra: dict[str, str]) -> Synthesis:
    """``result`` with its file written: the tree the kind wrote and measured (:attr:`Synthesis.tree`) with its
    requirements (``requirements:``, each measured one with its tolerance), for the report to state them beside
    what the mechanism achieves; the text written once, through the one writer, and read back once
    (:attr:`Synthesis.spec`)."""
    import dataclasses

    from ruamel.yaml.comments import CommentedMap

    from linkwork.spec.edit import yaml_text
    from linkwork.spec.reader import loads
    from linkwork.synthesis.achieved import SUFFIX, written
    from linkwork.synthesis.common import LEAST_TRANSMISSION

    data = result.tree
    data["requirements"] = CommentedMap(written(result.kind, result.requirements, extra, result.tolerances))
    for name in data["requirements"]:
        if name.endswith(SUFFIX):
            data["requirements"].yaml_add_eol_comment(
                "what the lengths written to 0.1 mm allow: the first-order bound of each within 0.05 mm", name
            )
    if "min_transmission_angle" in data["requirements"]:
        data["requirements"].yaml_add_eol_comment(
            f"the design rule: every dyad's transmission angle over the turn at least this ("
            f"{math.degrees(LEAST_TRANSMISSION):g} deg unless --min-transmission-angle lowers it)",
            "min_transmission_angle",
        )
    data.yaml_set_comment_before_after_key(
        "requirements", before="what the mechanism was synthesised for; the report states it beside what it achieves"
    )
    text = yaml_text(data)
    return dataclasses.replace(result, text=text, spec=loads(text, "<synthesised>"), tree=None)


def _si(name: str, value: Any) -> Any:
    """A requirement given as a string with its unit, in SI; anything else as given."""
    if isinstance(value, str) and name in QUANTITIES:
        from linkwork.units import parse_quantity

        return parse_quantity(value, QUANTITIES[name])
    return value
