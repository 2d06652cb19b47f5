"""Checks of a file's parts that can be made: force elements and the ``sizing:`` section's pins and sections, in SI.

A value may be valid as a number and still describe nothing that can be built: a spring of negative free length, a
tube whose wall is thicker than its radius, an I-section whose flanges are deeper than the section, a pin of
1e-300 m.  Each is one problem at its file:line, before any analysis (``check`` refuses what ``size`` would fail
on).  The number of loads is bounded too: each load is evaluated at every crank angle of an analysis, so the time
of an analysis grows with it (:data:`~linkwork.limits.MAX_LOADS`).
"""

from __future__ import annotations

from linkwork.errors import Problem
from linkwork.limits import MAX_LOADS, MIN_PART
from linkwork.spec.schema import SectionSpec, Spec
from linkwork.spec.yamlsource import Source

#: The dimensions each shape of section needs.
SECTION_DIMENSIONS = {"round": ("d",), "rectangle": ("b", "h"), "tube": ("d", "t"), "I": ("h", "b", "tw", "tf")}


def part_checks(spec: Spec, src: Source) -> list[Problem]:
    """The problems of ``spec``'s loads (their number, the springs' free lengths) and of its ``sizing:`` section
    (pins and sections of at least :data:`~linkwork.limits.MIN_PART`, sections whose parts fit)."""
    out = []
    if len(spec.loads) > MAX_LOADS:
        out.append(
            src.problem(
                ("loads",),
                f"{len(spec.loads):,} loads; at most {MAX_LOADS:,} (each is evaluated at every crank angle of an "
                "analysis: machine dynamics takes about 0.4 s more for each)",
            )
        )
    for name, load in spec.loads.items():
        if load.type == "spring" and load.free_length is not None and load.free_length < 0:
            out.append(
                src.problem(
                    ("loads", name, "free_length"),
                    f"a spring's free length is its length without force: from 0 up, got {load.free_length:g} m",
                )
            )
    if spec.sizing is None:
        return out
    for joint, pin in spec.sizing.pins.items():
        for key in ("diameter", "width"):
            value = getattr(pin, key)
            if value < MIN_PART:
                out.append(src.problem(("sizing", "pins", joint, key), _small(f"a pin's {key}", value)))
    for name, length in spec.sizing.guides.items():
        if length < MIN_PART:
            out.append(src.problem(("sizing", "guides", name), _small("a guide's length", length)))
    shaft = spec.sizing.shaft
    if shaft is not None and shaft.spacing < MIN_PART:
        out.append(src.problem(("sizing", "shaft", "spacing"), _small("the bearings' spacing", shaft.spacing)))
    for link, section in spec.sizing.sections.items():
        out += [src.problem(("sizing", "sections", link, key), why) for key, why in section_problems(section)]
    return out


def _small(what: str, value: float) -> str:
    return f"{what} of {value:g} m is below {MIN_PART * 1e3:g} mm: no part that small is made"


def section_problems(section: SectionSpec) -> list[tuple[str, str]]:
    """Why ``section`` cannot be made, as ``(dimension, why)``: a dimension its shape needs missing or below
    :data:`~linkwork.limits.MIN_PART`, one it does not use, a tube's wall of half its diameter or more, an
    I-section whose flanges fill its depth or whose web is wider than its flanges."""
    dims = {k: v for k, v in section.model_dump(exclude={"shape"}).items() if v is not None}
    need = SECTION_DIMENSIONS[section.shape]
    out = [(k, f"a {section.shape} section needs {', '.join(need)}: give {k}") for k in need if k not in dims]
    out += [(k, f"a {section.shape} section has no {k} (it takes {', '.join(need)})") for k in dims if k not in need]
    out += [(k, _small(f"a section's {k}", v)) for k, v in dims.items() if k in need and v < MIN_PART]
    if out:
        return out
    mm = {k: f"{v * 1e3:.6g} mm" for k, v in dims.items()}
    if section.shape == "tube" and not dims["t"] < dims["d"] / 2:
        out.append(("t", f"the wall t = {mm['t']} must be thinner than the radius d/2 = {dims['d'] * 500:.6g} mm"))
    if section.shape == "I":
        if not 2 * dims["tf"] < dims["h"]:
            out.append(("tf", f"two flanges of tf = {mm['tf']} fill the depth h = {mm['h']}: tf < h/2"))
        if not dims["tw"] <= dims["b"]:
            out.append(("tw", f"the web tw = {mm['tw']} is wider than the flanges b = {mm['b']}"))
    return out
