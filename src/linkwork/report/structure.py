"""The report's section of the structure: counts, the Assur groups and the structural formula."""

from __future__ import annotations

from linkwork.lang import group_kind
from linkwork.report.html import Section, paragraph, table
from linkwork.report.run import ReportRun


def structure_section(run: ReportRun) -> None:
    run.progress("structure")
    s = run.mech.structure
    sec = Section("structure", run.t("section.structure"))
    sec.body.append(
        paragraph(run.t("structure.counts", n=s.n_links, p5=s.p5, p4=s.p4, w=s.dof, q=s.redundant, mobility=s.mobility))
    )
    head = [run.t(f"structure.head.{k}") for k in ("number", "group", "class", "order", "kind", "links", "joints")]
    rows = [
        [
            i,
            g.label.split(" ")[0],
            g.klass,
            "-" if g.order is None else g.order,
            group_kind(g.kind, run.lang),
            ", ".join(g.link_names),
            ", ".join(g.joints),
        ]
        for i, g in enumerate(s.groups, 1)
    ]
    sec.body.append(table(head, rows))
    sec.body.append(paragraph(run.t("structure.formula", formula=s.formula)))
    run.sections.append(sec)
