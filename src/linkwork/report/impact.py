"""The report's section of the blow: the impulses in the file's pose, and the working cycle of blows with the
file's drive and tool."""

from __future__ import annotations

from typing import Any

import numpy as np

from linkwork.errors import LinkworkError
from linkwork.report.html import Section, paragraph, table
from linkwork.report.run import ReportRun


def impact_section(run: ReportRun) -> None:
    mech = run.mech
    blow = mech.blow
    assert blow is not None  # _build calls this only for a mechanism with a blow
    run.progress("impact")
    r = run.study.impact
    sec = Section("impact", run.t("section.impact"))
    rows: list[list[Any]] = [[run.t("impact.impulse_on", at=blow.at), _vector(r.impulse, run.t("unit.Ns"))]]
    rows += [[run.t("impact.joint", joint=j), _vector(v, run.t("unit.Ns"))] for j, v in r.joints.items()]
    rows += [[run.t("impact.energy_lost"), r.energy_loss]]
    if r.ideal_com is not None:
        rows.append([run.t("impact.ideal_com"), _vector(np.asarray(r.ideal_com) * 1000, run.t("unit.mm"))])
    sec.body.append(table([run.t("impact.head.blow"), run.t("dynamics.head.value")], rows))
    if mech.motor_gear is not None and blow.tool is not None:
        _impact_cycle(run, sec)
    run.sections.append(sec)


def _vector(v: Any, unit: str) -> str:
    return f"({v[0]:.4g}, {v[1]:.4g}) {unit}"


def _impact_cycle(run: ReportRun, sec: Section) -> None:
    """The working cycle with the file's drive and tool: the steady cycle's blow and phases."""

    mech = run.mech
    assert mech.blow is not None  # _impact calls this only for a mechanism with a blow
    try:
        c = run.study.blows
    except LinkworkError as exc:
        sec.body.append(paragraph(run.t("impact.cycle_failed", reason=str(exc))))
        return
    b = c.last
    sec.body.append(paragraph(run.t("impact.cycle", blows=f"{c.blows_per_minute:.4g}")))
    ns = run.t("unit.Ns")
    rows: list[list[Any]] = [
        [run.t("impact.speed"), b.impact_speed],
        [run.t("impact.crank_speeds"), f"{b.crank_speed_before:.4g} / {b.crank_speed_after:.4g}"],
        [run.t("impact.energies"), f"{b.energy_lost:.4g} / {b.energy_to_tool:.4g}"],
        [run.t("impact.impulse_on", at=mech.blow.at), _vector(b.impulse, ns)],
    ]
    rows += [[run.t("impact.joint", joint=j), _vector(v, ns)] for j, v in b.joints.items()]
    rows += [[run.t("impact.work"), b.work_on_work], [run.t("impact.motor_power"), c.mean_power]]
    sec.body.append(table([run.t("impact.head.steady"), run.t("dynamics.head.value")], rows))
    phases = [
        [run.t(f"phase.{p.kind}"), p.freedom, 1000 * (p.start - b.time), 1000 * p.duration] for p in c.cycle_phases()
    ]
    head = [run.t(f"phases.head.{k}") for k in ("phase", "freedom", "from", "lasts")]
    sec.body.append(table(head, phases))
