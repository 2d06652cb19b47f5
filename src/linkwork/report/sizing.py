"""The report's "Sizing" section: the tables of :func:`linkwork.sizing.size` in the report's language, for a file
with a ``sizing:`` section (or a report asked for it)."""

from __future__ import annotations

import re
from typing import TYPE_CHECKING, Any

from linkwork.errors import LinkworkError
from linkwork.lang import TEXTS
from linkwork.report.html import Section, paragraph
from linkwork.report.html import table as html_table
from linkwork.spec.reader import described

if TYPE_CHECKING:
    from linkwork.report.run import ReportRun
    from linkwork.sizing import Sizing, Table
    from linkwork.structure.model import Mechanism
    from linkwork.study import Study


def asks_sizing(mech: Mechanism, asked: bool | None) -> bool:
    """Whether the report has the section: as ``asked``, else where the file has a ``sizing:`` section."""
    if asked is not None:
        return asked
    spec = described(mech.description)
    return spec is not None and spec.sizing is not None


def sizing_section(run: ReportRun) -> None:
    """The section, and ``sizing.json`` beside the report where the sizing succeeded."""
    from linkwork.io.jsonout import dumps

    run.progress("sizing")
    body, result = sizing_body(run.study, run.t)
    if result is not None:
        (run.folder / "sizing.json").write_text(dumps(result.record()), encoding="utf-8")
    run.sections.append(Section("sizing", run.t("section.sizing"), body))


def sizing_body(study: Study, t: Any) -> tuple[list[str], Sizing | None]:
    """The HTML of the section (``t(key, **values)``: the report's texts) and the sizing (None where it failed:
    the section says why): :attr:`linkwork.study.Study.sizing`, the motor chosen where the file's ``sizing:
    motor`` asks for it (it runs the machine once a motor tried) and the file has a drive speed."""
    body = [paragraph(t("sizing.intro"))]
    try:
        result = study.sizing
    except LinkworkError as exc:
        return [*body, paragraph(t("sizing.failed", why=str(exc)))], None
    rows = [
        [_text(t, "sizing.input.", key), "-" if value is None else _text(t, "sizing.word.", value)]
        for key, value in result.inputs.items()
    ]
    body += [paragraph(t("sizing.inputs")), html_table([t("sizing.col.quantity"), t("sizing.col.value")], rows)]
    for table in result.tables():
        body += [paragraph(t(f"sizing.table.{table.key}")), _translated(table, t)]
    spec = study.file
    given = spec is not None and spec.machine is not None and spec.machine.motor is not None
    for part, why in result.missing.items():
        if part == "motor" and why == "not asked" and given:  # the file's own motor: nothing to choose
            body.append(paragraph(t("sizing.motor_given")))
        else:
            body.append(
                paragraph(t("sizing.missing", part=_text(t, "sizing.word.", part), why=_text(t, "sizing.word.", why)))
            )
    checks = result.proportions.checks if result.proportions is not None else ()
    body += [
        paragraph(
            t(
                "sizing.warning",
                part=_text(t, "sizing.word.", c.part),
                rule=_text(t, "sizing.word.", c.rule),
                has=f"{c.has * 1e3:.4g}",
                needs=f"{c.needs * 1e3:.4g}",
                governs=_text(t, "sizing.word.", c.governs),
            )
        )
        for c in checks
        if not c.fits
    ]
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
    return html_table(head, rows)


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
    sized = re.fullmatch(
        r"links' masses from their sized steel sections \(at least a round bar of L/d = (\S+)\)"
        r"(?:; (.+) steel blocks carrying .+ asks)?, (?:to a fixed point in (\d+) rounds|not settled in (\d+) rounds)"
        r"(?:; the file's for (.+) \(no bars, no blocks\))?",
        text,
    )
    if sized:
        slender, blocks, done, not_done, kept = sized.groups()
        out = t("sizing.masses_sized", slender=slender, rounds=done or not_done)
        out += t("sizing.masses_blocks", blocks=blocks) if blocks else ""
        out += t("sizing.masses_unsettled") if not_done else ""
        return out + (t("sizing.masses_kept", kept=kept) if kept else "")
    eyes = re.fullmatch(r"eyes (\S+)-(\S+) apart", text)
    if eyes:
        return t("sizing.eyes", a=eyes.group(1), b=eyes.group(2))
    slot = re.fullmatch(r"(\S+) in (\S+)", text)
    if slot:
        return t("sizing.in_slot", block=slot.group(1), slot=slot.group(2))
    joints = re.fullmatch(r"joints (.+)", text)
    if joints:
        return t("sizing.joints", joints=joints.group(1))
    unbounded = re.fullmatch(r"the force grows without bound .* at phi (\S+) deg: .*", text)
    if unbounded:
        return t("sizing.unbounded", phi=unbounded.group(1))
    return t(prefix + text) if prefix + text in TEXTS else text
