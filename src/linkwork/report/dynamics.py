"""The report's sections of the machine unit: its steady cycle (dynamics, the flywheel) and the run in time the
file asks for."""

from __future__ import annotations

import math
from typing import Any

from linkwork import figures
from linkwork.errors import LinkworkError
from linkwork.io import dynamics_tables, run_tables
from linkwork.io.jsonout import dumps
from linkwork.report.html import Section, paragraph, table
from linkwork.report.kinematics import ReportCycle
from linkwork.report.run import ReportRun
from linkwork.units import turn_deg


def dynamics_section(run: ReportRun, cycle: ReportCycle) -> None:

    mech = run.mech
    run.progress("dynamics")
    result = run.study.dynamics  # as lw.dynamics and linkwork dynamics run it
    data = dynamics_tables.to_json(mech, result, zero=cycle.zero)
    (run.folder / "dynamics.json").write_text(dumps(data), encoding="utf-8")
    rpm = 30 / math.pi
    last = result.motion.last
    sec = Section("dynamics", run.t("section.dynamics"))
    rows: list[list[Any]] = [
        [run.t("dynamics.mean_speed"), last.omega_mean * rpm],
        [run.t("dynamics.speed_range"), f"{last.omega_min * rpm:.4g} \u2026 {last.omega_max * rpm:.4g}"],
        [run.t("dynamics.delta"), last.delta],
        [run.t("dynamics.drive_power"), result.drive_power],
        [run.t("dynamics.motor_power"), result.mean_power],
        [run.t("dynamics.startup"), result.startup_time],
        [run.t("dynamics.flywheel", shaft=run.t(f"shaft.{result.drive.flywheel_on}")), result.drive.flywheel],
    ]
    fly = result.flywheel
    if fly is not None:
        rows[2:3] = [
            [run.t("dynamics.delta_asked"), fly.delta],
            [run.t("dynamics.delta_true"), last.delta],
            [run.t("dynamics.energy_swing"), fly.energy_swing],
            [run.t("dynamics.inertia_needed"), f"{fly.inertia:.6g}"],
        ]
    sec.body.append(table([run.t("dynamics.head.quantity"), run.t("dynamics.head.value")], rows))
    if fly is not None:
        sec.body.append(
            paragraph(
                run.t(
                    "dynamics.why_delta",
                    true=f"{last.delta:.4g}",
                    asked=f"{fly.delta:.4g}",
                    rpm=f"{fly.omega_mean * rpm:.4g}",
                )
            )
        )
    zero, lang = cycle.zero, run.lang
    sec.figures.append(
        run.figure("dynamics", lambda: figures.dynamics_diagrams(result, zero, lang), run.t("caption.dynamics"))
    )
    run.sections.append(sec)


def simulate_section(run: ReportRun) -> None:
    """The run in time the file asks for (``simulate:``), as ``linkwork simulate`` runs it: a table of its
    start, end and stops, ``simulate.json`` and ``simulate.csv`` beside the report, and its diagram."""

    asked = run.study.file.simulate if run.study.file is not None else None
    assert asked is not None  # _build calls this only for a file with a run
    run.progress("simulate")
    sec = Section("simulate", run.t("section.simulate"))
    try:
        result = run.study.time_run
    except LinkworkError as exc:
        sec.body.append(paragraph(str(exc)))
        run.sections.append(sec)
        return
    (run.folder / "simulate.json").write_text(dumps(run_tables.to_json(result)), encoding="utf-8")
    (run.folder / "simulate.csv").write_text(run_tables.csv_text(result), encoding="utf-8")
    ends = [f"{turn_deg(float(result.angle[i])):.2f}; {result.speed[i]:.6g}" for i in (0, -1)]
    rows: list[list[Any]] = [
        [run.t("simulate.until"), asked.until],
        [run.t("simulate.start"), ends[0]],
        [run.t("simulate.end"), ends[1]],
        [run.t("simulate.turned"), math.degrees(result.angle[-1] - result.angle[0])],
    ]
    stops = [f"{e.time:.6g}" for e in result.events if e.kind == "stop"]
    if stops:
        rows.append([run.t("simulate.stops"), ", ".join(stops[:12]) + (" \u2026" if len(stops) > 12 else "")])
    sec.body.append(table([run.t("dynamics.head.quantity"), run.t("dynamics.head.value")], rows))
    lang = run.lang
    sec.figures.append(run.figure("simulate", lambda: figures.run_diagram(result, lang), run.t("caption.simulate")))
    run.sections.append(sec)
