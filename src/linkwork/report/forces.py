"""The report's section of the forces: the driving torque, the joints' largest forces, the forces at the twelve
positions, the foundation, the efficiency with friction, the checks, and the graphical method's part
(:mod:`linkwork.report.kinetostatic`)."""

from __future__ import annotations

import functools
import math
from typing import TYPE_CHECKING, Any

import numpy as np

from linkwork import figures
from linkwork.io.force_tables import has_losses, to_json, write_csv
from linkwork.io.jsonout import dumps
from linkwork.kinetostatics.peaks import pair_force_peaks, torque_peak
from linkwork.kinetostatics.tables import pair_labels
from linkwork.lang import friction_problem, group_label, link_named
from linkwork.report.html import Section, deg, fixed, paragraph, table
from linkwork.report.kinematics import ReportCycle
from linkwork.report.run import ReportRun
from linkwork.structure.model import PairType, one_crank

if TYPE_CHECKING:
    from linkwork.kinetostatics.reaction_forces import Forces


def forces_section(run: ReportRun, cycle: ReportCycle) -> None:

    mech = run.mech
    run.progress("forces")
    f = run.study.forces
    write_csv(f, run.folder / "forces.csv")
    (run.folder / "forces.json").write_text(dumps(to_json(f)), encoding="utf-8")
    at12 = run.study.forces_twelve
    sec = Section("forces", run.t("section.forces"))
    unit = _force_unit(f)
    sec.body += _torque_text(run, cycle, f)
    sec.body += _joint_table(run, cycle, f, unit)
    sec.body += _forces_at_positions(run, at12, unit)
    sec.body += _foundation_table(run, cycle, f, unit)
    sec.body += _efficiency_text(run, f)
    sec.body += _checks_table(run, f)
    zero, lang = cycle.zero, run.lang
    sec.figures.append(
        run.figure("driving_torque", lambda: figures.torque_diagram(f, zero, lang), run.t("caption.driving_torque"))
    )
    sec.figures.append(
        run.figure("foundation", lambda: figures.foundation_diagram(f, zero, lang), run.t("caption.foundation"))
    )
    for k in range(mech.n_pairs):
        if mech.pair_links[k, 0] == 0 and mech.pair_type[k] == PairType.REVOLUTE:
            joint = str(mech.pair_joint[k])
            make = functools.partial(figures.hodograph, f, joint, at=at12, zero=zero, lang=lang)
            sec.figures.append(run.figure(f"hodograph_{joint}", make, run.t("caption.hodograph", joint=joint)))
    if one_crank(mech):  # the graphical method: force plans and Zhukovsky's lever where the load acts
        from linkwork.report.kinetostatic import sections

        body, names = sections(run, at12, cycle, f)
        sec.body += body
        sec.figures += names
    run.sections.append(sec)


def _efficiency_text(run: ReportRun, f: Forces) -> list[str]:
    """With friction in the pairs: where it has no solution, the efficiency of the cycle and the instantaneous
    one, and a table of the work lost in each joint (:mod:`linkwork.kinetostatics.efficiency`)."""

    if not has_losses(f):
        return []
    out = []
    for problem in f.friction.problems if f.friction is not None else ():
        out.append(paragraph(friction_problem(problem, run.lang)))
    e = f.efficiency
    drive, cycle, eta = float(e.work(e.drive)), float(e.cycle), e.instantaneous
    if math.isfinite(cycle) and np.isfinite(eta).any():
        useful = float(e.work(e.useful))
        low, high = (round(float(x), 3) + 0.0 for x in (np.nanmin(eta), np.nanmax(eta)))  # no "-0.000"
        out.append(
            paragraph(
                run.t(
                    "efficiency.text",
                    cycle=f"{cycle:.4f}",
                    useful=f"{useful:.4g}",
                    drive=f"{drive:.4g}",
                    low=f"{low:.3f}",
                    high=f"{high:.3f}",
                )
            )
        )
    else:
        out.append(paragraph(run.t("efficiency.none")))
    works = e.work(e.losses)
    peaks = [
        float(np.nanmax(e.losses[:, j])) if np.isfinite(e.losses[:, j]).any() else math.nan
        for j in range(len(e.joints))
    ]
    share = works / drive * 100 if drive > 0 else np.full(len(works), np.nan)
    rows = [list(r) for r in zip(e.joints, fixed(works), fixed(share), fixed(peaks), strict=True)]
    head = [
        run.t("efficiency.head.joint"),
        run.t("efficiency.head.work"),
        run.t("efficiency.head.share"),
        run.t("efficiency.head.peak"),
    ]
    return out + [table(head, rows)]


def _force_unit(f: Forces) -> tuple[float, str]:
    """kN where the largest joint force is 10 kN or more, else N: (factor from N, unit key)."""
    big = np.nanmax(np.abs(f.multipliers)) if np.isfinite(f.multipliers).any() else 0.0
    return (1e-3, "unit.kN") if big >= 1e4 else (1.0, "unit.N")


def _torque_text(run: ReportRun, cycle: ReportCycle, f: Forces) -> list[str]:

    torque = np.asarray(f.driving_torque)
    if not np.isfinite(torque).any():
        return []
    peak = torque_peak(f)  # refined between the samples, as every route gives it
    top, at = float(peak.value[0]), float(peak.at[0])
    big = float(np.nanmax(np.abs(torque))) if math.isinf(top) else abs(top)
    factor, unit = (1e-3, "unit.kNm") if big >= 1e4 else (1.0, "unit.Nm")
    return [
        paragraph(
            run.t(
                "forces.torque.unbounded" if math.isinf(top) else "forces.torque",
                peak=f"{top * factor:.4g}",
                mean=f"{np.nanmean(torque) * factor:.4g}",
                unit=run.t(unit),
                at=deg(float(cycle.phi(at))),
            )
        )
    ]


def _joint_table(run: ReportRun, cycle: ReportCycle, f: Forces, unit: tuple[float, str]) -> list[str]:

    mech = run.mech
    rows: list[list[Any]] = []
    members = mech.pair_links if mech.pair_members is None else mech.pair_members  # in the file's order
    labels = pair_labels(mech)
    peaks = pair_force_peaks(f, [k for _, k in labels])  # refined between the samples, as every route gives them
    for (label, k), size, at in zip(labels, peaks.value, peaks.at, strict=True):
        if not np.isnan(size):  # infinite where it grows without bound towards a singular position
            a, b = (link_named(mech.link_names[int(x)], run.t) for x in members[k])
            rows.append([label, f"{a} \u2192 {b}", float(size) * unit[0], deg(float(cycle.phi(at)))])
    sizes = np.array([row[2] for row in rows], dtype=float)
    for row, text, endless in zip(rows, fixed(np.where(np.isinf(sizes), np.nan, sizes)), np.isinf(sizes), strict=True):
        row[2] = run.t("joints.unbounded") if endless else text
    head = [
        run.t("joints.head.joint"),
        run.t("joints.head.links"),
        run.t("joints.head.largest", unit=run.t(unit[1])),
        run.t("head.at_phi"),
    ]
    return [table(head, rows)] + ([paragraph(run.t("joints.unbounded.note"))] if np.isinf(sizes).any() else [])


def _forces_at_positions(run: ReportRun, f: Forces, unit: tuple[float, str]) -> list[str]:
    """The driving torque and the forces in the frame's joints at the 12 positions."""
    mech = run.mech
    supports = [str(mech.pair_joint[k]) for k in range(mech.n_pairs) if mech.pair_links[k, 0] == 0]
    supports = list(dict.fromkeys(supports))
    torque = np.asarray(f.driving_torque)
    tf, tunit = (1e-3, "unit.kNm") if np.nanmax(np.abs(torque), initial=0.0) >= 1e4 else (1.0, "unit.Nm")
    columns = [fixed(torque * tf)] + [fixed(np.hypot(*np.asarray(f.reaction(j)).T) * unit[0]) for j in supports]
    rows = [[k, f"{30 * k}", *(c[k] for c in columns)] for k in range(12)]
    head = [run.t("head.position"), run.t("head.phi"), run.t("positions.head.torque", unit=run.t(tunit))]
    head += [run.t("positions.head.support", joint=j, unit=run.t(unit[1])) for j in supports]
    return [paragraph(run.t("positions.forces")), table(head, rows)]


def _foundation_table(run: ReportRun, cycle: ReportCycle, f: Forces, unit: tuple[float, str]) -> list[str]:
    b = f.bolts()
    factor, funit = unit
    mfactor, munit = (1e-3, "unit.kNm") if abs(b.moment) >= 1e4 else (1.0, "unit.Nm")
    rows = [
        [run.t(f"foundation.{name}", unit=run.t(u)), value * k, deg(float(cycle.phi(angle)))]
        for name, value, angle, k, u in (
            ("shear", b.shear, b.shear_angle, factor, funit),
            ("pull", b.pull, b.pull_angle, factor, funit),
            ("push", b.push, b.push_angle, factor, funit),
            ("moment", b.moment, b.moment_angle, mfactor, munit),
        )
    ]
    head = [run.t("foundation.head"), run.t("foundation.head.largest"), run.t("head.at_phi")]
    return [table(head, rows)]


def _checks_table(run: ReportRun, f: Forces) -> list[str]:

    from linkwork.kinetostatics.crosschecks import cross_checks, free_body_residuals

    checks: list[list[Any]] = [[run.t(f"check.{k}"), f"{v:.2g}"] for k, v in cross_checks(f).items()]
    checks += [
        [run.t("check.free_body", group=group_label(label, run.lang)), f"{residual:.2g}"]
        for label, residual in free_body_residuals(f).items()
    ]
    return [paragraph(run.t("checks.title")), table([run.t("checks.head.check"), run.t("checks.head.value")], checks)]
