"""The report's "Sizing" section: the tables of :func:`linkwork.sizing.size` in the report's language, for a file
with a ``sizing:`` section (or a report asked for it)."""

from __future__ import annotations

import html
import math
import re
from typing import TYPE_CHECKING, Any

from linkwork.errors import LinkworkError
from linkwork.lang import TEXTS

if TYPE_CHECKING:
    from linkwork.sizing import Sizing, Table
    from linkwork.structure.model import Mechanism


def asks_sizing(mech: Mechanism, asked: bool | None) -> bool:
    """Whether the report has the section: as ``asked``, else where the file has a ``sizing:`` section."""
    if asked is not None:
        return asked
    return mech.spec is not None and mech.spec.sizing is not None


def sizing_section(mech: Mechanism, t: Any) -> tuple[list[str], Sizing | None]:
    """The HTML of the section (``t(key, **values)``: the report's texts) and the sizing (None where it failed:
    the section says why).  The motor is chosen where the file's ``sizing: motor`` asks for it (it runs the
    machine once a motor tried) and the file has a drive speed."""
    from linkwork.sizing import size

    spec = mech.spec.sizing if mech.spec is not None else None
    body = [_p(t("sizing.intro"))]
    try:
        result = size(mech, motor=bool(spec is not None and spec.motor))
    except LinkworkError as exc:
        return [*body, _p(t("sizing.failed", why=str(exc)))], None
    rows = [
        [_text(t, "sizing.input.", key), "-" if value is None else _text(t, "sizing.word.", value)]
        for key, value in result.inputs.items()
    ]
    body += [_p(t("sizing.inputs")), _html_table([t("sizing.col.quantity"), t("sizing.col.value")], rows)]
    for table in result.tables():
        body += [_p(t(f"sizing.table.{table.key}")), _translated(table, t)]
    given = mech.spec is not None and mech.spec.machine is not None and mech.spec.machine.motor is not None
    for part, why in result.missing.items():
        if part == "motor" and why == "not asked" and given:  # the file's own motor: nothing to choose
            body.append(_p(t("sizing.motor_given")))
        else:
            body.append(_p(t("sizing.missing", part=_text(t, "sizing.word.", part), why=_text(t, "sizing.word.", why))))
    return body, result


def _translated(table: Table, t: Any) -> str:
    """The table with its headings, row names, units and words in the report's language (as they are where the
    text table has none for them)."""
    head = [_text(t, "sizing.col.", c) for c in table.columns]
    rows = []
    for row in table.rows:
        cells = []
        for c, value in enumerate(row):
            if isinstance(value, str):
                prefix = "sizing.row." if c == 0 and table.columns[0] == "quantity" else "sizing.word."
                prefix = "sizing.unit." if table.columns[c] == "unit" else prefix
                value = _text(t, prefix, value)
            cells.append(value)
        rows.append(cells)
    return _html_table(head, rows)


def _text(t: Any, prefix: str, text: Any) -> Any:
    """``text`` in the report's language where the texts have it under ``prefix`` (a link's least round section
    by its pattern); as it is otherwise (names from the file, numbers)."""
    if not isinstance(text, str):
        return text
    least = re.fullmatch(r"least round d (\S+) mm", text)
    if least:
        return t("sizing.least_round", d=least.group(1))
    rolling = re.fullmatch(r"no: swings (\S+) < (\S+) deg between its elements", text)
    if rolling:
        return t("sizing.rolling_no", swing=rolling.group(1), pitch=rolling.group(2))
    joints = re.fullmatch(r"joints (.+)", text)
    if joints:
        return t("sizing.joints", joints=joints.group(1))
    unbounded = re.fullmatch(r"the force grows without bound .* at phi (\S+) deg: .*", text)
    if unbounded:
        return t("sizing.unbounded", phi=unbounded.group(1))
    return t(prefix + text) if prefix + text in TEXTS else text


def _cell(x: Any) -> str:
    if isinstance(x, float):
        return "-" if not math.isfinite(x) else f"{x:.4g}"
    return html.escape(str(x))


def _html_table(head: list[str], rows: list[list[Any]]) -> str:
    out = ["<table><thead><tr>" + "".join(f"<th>{html.escape(h)}</th>" for h in head) + "</tr></thead><tbody>"]
    out += ["<tr>" + "".join(f"<td>{_cell(x)}</td>" for x in row) + "</tr>" for row in rows]
    return "".join(out) + "</tbody></table>"


def _p(text: str) -> str:
    return f"<p>{html.escape(text)}</p>"
