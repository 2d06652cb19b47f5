"""The report's section of the requirements of a synthesised file: asked, achieved, met."""

from __future__ import annotations

import math
from typing import Any

from linkwork import figures
from linkwork.report.html import Section, paragraph, table
from linkwork.report.run import ReportRun
from linkwork.scene.limits import limits_scene
from linkwork.structure.model import one_crank


def requirements_section(run: ReportRun) -> None:
    """The section a file that carries requirements (a synthesised one) opens with: each requirement, what the
    mechanism achieves as the analysis measures it, and the limit positions with theta drawn."""

    if not one_crank(run.mech):
        return

    kin = run.study.requirements_kin
    found = run.study.requirements
    if found is None:
        return
    kind, rows = found
    sec = Section("requirements", run.t("section.requirements"), [paragraph(run.t("requirements.intro", kind=kind))])
    head = [run.t(f"requirements.head.{k}") for k in ("name", "asked", "achieved", "met")]
    sec.body.append(table(head, [_requirement_row(run, row) for row in rows]))
    limits = limits_scene(kin)
    if limits is not None:
        theta = math.degrees(limits.theta)
        k = (180.0 + theta) / (180.0 - theta)
        sec.body.append(
            paragraph(run.t("requirements.theta", theta=f"{theta:.3f}", k=f"{k:.6g}", member=limits.who(run.lang)))
        )
        lang = run.lang
        sec.figures.append(
            run.figure(
                "limits", lambda: figures.draw_limits(kin, lang=lang), run.t("caption.limits", member=limits.who(lang))
            )
        )
    run.sections.append(sec)


def _requirement_row(run: ReportRun, row: Any) -> list[str]:
    """A requirement's name, the value asked (with its sense), what the mechanism achieves, whether it is met."""
    scale, unit = {"length": (1e3, "unit.mm"), "angle": (180 / math.pi, "unit.deg")}.get(row.kind, (1.0, ""))

    def shown(x: float) -> str:
        text = f"{x * scale:.10g}"
        return f"{text}{run.t(unit)}" if unit == "unit.deg" else f"{text} {run.t(unit)}" if unit else text

    sense = "" if row.sense in ("equal", "given") else run.t(f"requirements.sense.{row.sense.replace(' ', '_')}") + " "
    achieved = run.t("requirements.as_given") if row.achieved is None else shown(row.achieved)
    met = "" if row.met is None else run.t("requirements.yes" if row.met else "requirements.no")
    within = "" if row.tolerance is None else f" \u00b1 {shown(row.tolerance)}"  # the file's stated tolerance
    return [run.t(f"requirement.{row.name}"), sense + shown(row.asked) + within, achieved, met]
