"""The report's first section: what was computed.

The mechanism as it was solved (its compiled arrays, so that a speed given on the command line shows as
the speed used): the drive, the links' dimensions and mass properties, the guides; then the file's loads
and machine (motor, gear, flywheel, delta) as it gives them (:func:`linkwork.spec.values.values_read`), and
the file itself.  Lengths in mm and angles in degrees, whatever units the file declares.
"""

from __future__ import annotations

import html
import math
from collections import defaultdict
from typing import TYPE_CHECKING, Any

from linkwork.lang import file_value, file_word, link_named
from linkwork.spec.reader import described
from linkwork.structure.model import PairType

if TYPE_CHECKING:
    from linkwork.spec.values import ValueRead
    from linkwork.structure.model import Mechanism

#: The table's cells: an HTML table of a header and rows of text (escaped here).
Rows = list[list[str]]


def _table(head: list[str], rows: Rows, code: bool = False) -> str:
    """An HTML table; ``code``: its cells are the file's own words (keys and values as it writes them), set
    as code."""
    out = ["<table><thead><tr>" + "".join(f"<th>{html.escape(h)}</th>" for h in head) + "</tr></thead><tbody>"]
    cell = "<td><code>{}</code></td>" if code else "<td>{}</td>"
    out += ["<tr>" + "".join(cell.format(html.escape(x)) for x in row) + "</tr>" for row in rows]
    return "".join(out) + "</tbody></table>"


def _mm(xy: Any) -> str:
    """Local coordinates (m) in mm: ``(500, 0)``."""
    return "(" + ", ".join(f"{round(float(c) * 1000, 3) + 0.0:g}" for c in xy) + ")"


def _g(x: float) -> str:
    return f"{x:.6g}"


def input_section(mech: Mechanism, steps: int, t: Any) -> list[str]:
    """The HTML of the section: paragraphs and tables (``t(key, **values)``: the report's texts)."""
    body = [f"<p>{html.escape(t('input.intro', name=mech.name, steps=steps))}</p>"]
    body.append(f"<p>{html.escape(_drive(mech, t))}</p>")
    body.append(_links(mech, t))
    guides = _guides(mech, t)
    if guides:
        body.append(guides)
    read = _values(mech)
    lang = _lang(t)
    spec = described(mech.description)
    loads = _grouped(read, "loads.", spec.loads if spec is not None else {}, lang)
    if loads:
        head = [t("input.head.load"), t("input.head.type"), t("input.head.given")]
        body.append(f"<p>{html.escape(t('input.loads'))}</p>" + _table(head, loads, code=True))
    given = spec.machine if spec is not None else None
    machine = _grouped(read, "machine.", {k: getattr(given, k, None) for k in ("motor", "gear", "flywheel")}, lang)
    if machine:
        head = [t("input.head.part"), t("input.head.given")]
        rows = [[file_word(name, lang), "; ".join(x for x in (kind, text) if x)] for name, kind, text in machine]
        body.append(f"<p>{html.escape(t('input.machine'))}</p>" + _table(head, rows, code=True))
    text = _file_text(mech)
    if text:
        file = f"<code>{html.escape(mech.source or mech.name)}</code>"  # the file's name: its own word
        summary = html.escape(t("input.file", file="\0")).replace("\0", file)
        body.append(f"<details><summary>{summary}</summary><pre>{html.escape(text)}</pre></details>")
    return body


def _drive(mech: Mechanism, t: Any) -> str:
    """The drive as it was solved: its joint, speed and direction, its coordinate in the assembly pose."""
    k = int(mech.drive_pair[0])
    speed = float(mech.drive_speed[0])
    joint = mech.pair_joint[k]
    if mech.pair_type[k] != PairType.REVOLUTE:
        return t("input.drive.linear", joint=joint, speed=_g(abs(speed)), start=_g(mech.drive_start[0] * 1000))
    if not math.isfinite(speed):
        return t("input.drive.law", joint=joint, start=_g(math.degrees(mech.drive_start[0])))
    turn = t("input.ccw" if speed >= 0 else "input.cw")
    rpm = _g(abs(speed) * 30 / math.pi)
    return t(
        "input.drive", joint=joint, rpm=rpm, rad=_g(abs(speed)), turn=turn, start=_g(math.degrees(mech.drive_start[0]))
    )


def _links(mech: Mechanism, t: Any) -> str:
    """A row per link, the frame first: its points in its own coordinates, its mass, centre of mass and
    moment of inertia about it."""
    rows: Rows = []
    for i, name in enumerate(mech.link_names):
        if mech.link_virtual[i]:
            continue
        points = [p for p in range(len(mech.point_names)) if mech.point_link[p] == i]
        where = ", ".join(f"{mech.point_names[p].split('.', 1)[1]} {_mm(mech.point_local[p])}" for p in points)
        mass = float(mech.link_mass[i])
        rows.append(
            [
                link_named(name, t),
                where,
                _g(mass),
                _mm(mech.link_com[i]) if mass else "-",
                _g(float(mech.link_inertia[i])) if mass else "-",
            ]
        )
    head = [
        t("input.head.link"),
        t("input.head.points"),
        t("input.head.mass"),
        t("input.head.com"),
        t("input.head.inertia"),
    ]
    return f"<p>{html.escape(t('input.links'))}</p>" + _table(head, rows)


def _guides(mech: Mechanism, t: Any) -> str:
    """A row per guide (prismatic pair): its links, the guide line's point and direction, in the guide's
    coordinates."""
    rows: Rows = []
    for k in range(len(mech.pair_type)):
        guide, slider = (int(i) for i in mech.pair_links[k])
        if mech.pair_type[k] != PairType.PRISMATIC or mech.link_virtual[[guide, slider]].any():
            continue
        axis = math.degrees(math.atan2(float(mech.pair_axis[k, 1]), float(mech.pair_axis[k, 0])))
        links = " / ".join(link_named(mech.link_names[i], t) for i in (guide, slider))
        rows.append([mech.pair_joint[k], links, _mm(mech.pair_origin[k]), f"{round(axis, 6) + 0.0:g}"])
    if not rows:
        return ""
    head = [t("input.head.joint"), t("input.head.guide"), t("input.head.through"), t("input.head.axis")]
    return f"<p>{html.escape(t('input.guides'))}</p>" + _table(head, rows)


def _values(mech: Mechanism) -> list[ValueRead]:
    from linkwork.spec.values import values_read

    spec = described(mech.description)
    return values_read(spec) if spec is not None else []


def _lang(t: Any) -> str:
    """The language of the report's texts ``t`` (a report run's ``t``, whose run has a ``lang``; else English)."""
    return str(getattr(getattr(t, "__self__", None), "lang", "en"))


def _grouped(read: list[ValueRead], prefix: str, kinds: Any, lang: str = "en") -> Rows:
    """The values under ``prefix`` (``loads.``, ``machine.``) by their first name: ``[name, type, "axis 90
    deg; workpiece -0.05 m, 0.05 m"]``; the file's text where it has a unit, else the SI value with its."""
    fields: dict[str, dict[str, list[str]]] = defaultdict(lambda: defaultdict(list))
    for v in read:
        if not v.path.startswith(prefix):
            continue
        name, _, rest = v.path[len(prefix) :].partition(".")
        key = rest.split("[", 1)[0] or name
        shown = v.text if isinstance(v.text, str) else f"{v.value:g} {v.unit}".strip()
        fields[name][key].append(str(shown))
    rows = []
    each, field = ("; ", " | ") if lang == "ru" else (", ", "; ")  # a decimal comma: values apart by semicolons
    for name, given in fields.items():
        kind = file_word(str(getattr(kinds.get(name), "type", None) or ""), lang)
        where = _placed(kinds.get(name), lang, field)
        text = field.join(
            file_value(each.join(vals), lang)
            if k == name
            else f"{file_word(k, lang)} {file_value(each.join(vals), lang)}"
            for k, vals in given.items()
        )
        rows.append([name, kind, field.join(x for x in (where, text) if x)])
    return rows


def _placed(load: Any, lang: str = "en", field: str = "; ") -> str:
    """Where a load acts: ``tools knife_upper.edge, knife_lower.edge``, ``at coupler.M``, ``on rocker``."""
    if load is None:
        return ""
    out = []
    for key in ("tools", "at", "on", "joint"):
        value = getattr(load, key, None)
        if value:
            out.append(f"{file_word(key, lang)} {', '.join(value) if isinstance(value, list) else value}")
    return field.join(out)


def _file_text(mech: Mechanism) -> str | None:
    """The text of the file the mechanism was read from (a file or a bundled example), where it still reads
    as what was solved (the same data); None for one made in code, or a file changed since."""
    from pathlib import Path

    from linkwork import examples
    from linkwork.errors import LinkworkError
    from linkwork.spec.yamlsource import read_file, read_yaml

    source = mech.description
    if source is None or not mech.source:
        return None
    name = mech.source.removesuffix(".yaml")
    candidates = [lambda: read_file(mech.source or ""), lambda: examples.text(name)]
    for read in candidates if Path(mech.source).is_file() else candidates[1:]:
        try:
            text = read()
            if read_yaml(text).data == source.data:
                return text
        except (LinkworkError, OSError, ValueError):
            continue
    return None
