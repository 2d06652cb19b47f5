"""The report's section of the kinematics: position 0, the positions, strokes and swings, the working members,
transmission angles, events, and the figures of the scheme, the plans and the diagrams."""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from linkwork import figures
from linkwork.figures.diagrams import member_label
from linkwork.io.motion_tables import write_csv, write_netcdf
from linkwork.lang import group_label, kind_named, link_named
from linkwork.motion.analysis import coordinate, extremes, transmission_angles, working
from linkwork.report.html import Section, deg, fixed, paragraph, ratio, table
from linkwork.report.kinematic_plans import worked_plans
from linkwork.report.run import ReportRun
from linkwork.scene.positions import plan_positions
from linkwork.structure.model import point_labels
from linkwork.units import turn_deg

if TYPE_CHECKING:
    from linkwork.motion.kinematic_analysis import Kinematics
    from linkwork.structure.model import Mechanism
    from linkwork.study import Study


@dataclass(frozen=True)
class ReportCycle:
    """The kinematics the report's tables and figures share: the study's cycle, and where the plans are drawn.

    Attributes
    ----------
    study : Study
        The mechanism's analyses: :attr:`kin` (its ``steps`` equal steps of a turn from position 0 in the drive's
        direction), :attr:`twelve` (the 12 positions, position 0 first), :attr:`zero` (the drive angle of
        position 0, rad) and :attr:`sign` (+1 where the crank turns counter-clockwise, -1 clockwise) are its.
    index : int
        The sample of ``kin`` at the position of the plans.
    drawn : tuple of int
        The positions the plans are drawn at (of the twelve).
    sheets : bool
        Whether the plans of all twelve positions are drawn too (``--position all``).
    dxf : bool
        Whether the drawings are written for CAD too.
    asked : int or float or None
        Where ``--position`` asks for the force analysis: a position of the twelve (int), φ (rad, float), or None
        (the largest driving torque on the working stroke, :mod:`linkwork.report.kinetostatic`).
    """

    study: Study
    index: int
    drawn: tuple[int, ...] = (0,)
    sheets: bool = False
    dxf: bool = False
    asked: int | float | None = None

    @property
    def kin(self) -> Kinematics:
        return self.study.kin

    @property
    def twelve(self) -> Kinematics:
        return self.study.twelve

    @property
    def zero(self) -> float:
        return self.study.zero

    @property
    def sign(self) -> float:
        return self.study.sign

    def phi(self, angles: Any) -> np.ndarray:
        """Crank angles turned from position 0, degrees in [0, 360) (:meth:`linkwork.study.Study.phi`)."""
        return self.study.phi(angles)


def kinematics_section(run: ReportRun, position: int | float | str | None, dxf: bool) -> ReportCycle:
    """The section of the kinematics; returns the cycle the later sections share."""

    mech, study = run.mech, run.study
    run.progress("kinematics")
    kin, twelve, zero, steps = study.kin, study.twelve, study.zero, study.steps
    drawn = [int(position) % 12] if isinstance(position, int) else plan_positions(mech, twelve)
    phi = np.degrees(np.arange(steps) * 2 * np.pi / steps)
    index = int(np.argmin(np.abs((phi - 30.0 * drawn[0] + 180.0) % 360.0 - 180.0)))
    asked = position if isinstance(position, int | float) else None
    cycle = ReportCycle(study, index, tuple(drawn), position == "all", dxf, asked)
    run.jobs.append(lambda: write_csv(kin, run.folder / "kinematics.csv"))
    run.jobs.append(lambda: write_netcdf(kin, run.folder / "kinematics.nc"))
    sec = Section("kinematics", run.t("section.kinematics"))
    sec.body.append(paragraph(_position_0(run, cycle)))
    where = run.t("at_position", position=drawn[0])
    first, lang = drawn[0], run.lang
    sec.figures += [
        run.figure(
            "scheme",
            lambda: figures.draw_scheme(twelve, first, position=first, cycle=kin, lang=lang),
            run.t("caption.scheme") + where,
        ),
        run.figure("positions", lambda: figures.draw_positions(kin, lang=lang), run.t("caption.positions")),
    ]
    sec.body += _positions_table(run, cycle)
    sec.body += _extremes_tables(run, cycle)
    sec.body += _working_table(run, cycle)
    sec.body += _transmission_table(run, cycle)
    sec.body += [paragraph(_event(run, cycle, e)) for e in kin.events]
    sec.body += worked_plans(run, twelve, first, str(first))  # the plans worked out (report/kinematic_plans.py)
    sec.figures += [
        run.figure(
            "kinematic_diagrams",
            lambda: figures.kinematic_diagrams(kin, zero, lang),
            run.t("caption.kinematic_diagrams"),
        ),
        *_plans(run, twelve, drawn, position == "all"),
        run.figure("link_angles", lambda: figures.link_angles(kin, zero, lang), run.t("caption.link_angles")),
    ]
    if dxf:
        from linkwork.io.dxf import write_drawings

        run.jobs.append(lambda: write_drawings(twelve, first, run.folder / "figures", cycle=kin, lang=lang))
    run.sections.append(sec)
    return cycle


def _plans(run: ReportRun, twelve: Kinematics, drawn: list[int], sheets: bool) -> list[str]:
    """The velocity and acceleration plans at the positions ``drawn`` (the first one's named
    ``velocity_plan``, the others' ``velocity_plan_9``...) and, with ``sheets``, those of all twelve."""

    names, lang = [], run.lang
    for k in drawn:
        tail = "" if k == drawn[0] else f"_{k}"
        where = run.t("at_position", position=k)
        names += [
            run.figure(
                f"velocity_plan{tail}",
                functools.partial(figures.velocity_plan, twelve, k, position=k, lang=lang),
                run.t("caption.velocity_plan") + where,
            ),
            run.figure(
                f"acceleration_plan{tail}",
                functools.partial(figures.acceleration_plan, twelve, k, position=k, lang=lang),
                run.t("caption.acceleration_plan") + where,
            ),
        ]
    if sheets:
        for kind in ("velocity", "acceleration"):
            sheet = run.figure(
                f"{kind}_plans",
                functools.partial(figures.plan_sheet, twelve, kind, lang=lang),
                run.t(f"caption.{kind}_plans"),
            )
            names.append(sheet)
    return names


def _position_0(run: ReportRun, cycle: ReportCycle) -> str:
    """What φ and position 0 are, in words."""

    members = working(run.mech)
    crank = deg(turn_deg(cycle.zero))
    if not members:
        return run.t("kin.phi.assembly", crank=crank)
    kind = "slider" if members[0].kind == "slider" else "rocker"
    member = member_label(run.mech, members[0], run.lang)
    if kind == "rocker":  # "the output rocker", not "the output rocker rocker"
        member = kind_named(run.t("kin.rocker_word"), member)
    return run.t(f"kin.phi.{kind}", member=member, crank=crank)


def _positions_table(run: ReportRun, cycle: ReportCycle) -> list[str]:

    mech, kin12 = run.mech, cycle.twelve
    labels = point_labels(mech)
    rows = []
    for k in range(12):
        row: list[Any] = [k, f"{30 * k}", deg(turn_deg(kin12.angles[k]))]
        for _, p in labels:
            x = kin12.position(mech.point_names[p])[k] * 1000
            row.append("-" if not np.isfinite(x).all() else tuple(f"{round(c, 1) + 0.0:.1f}" for c in x))
        rows.append(row)
    head = [run.t("head.position"), run.t("head.phi"), run.t("head.crank_to_x"), *[label for label, _ in labels]]
    return [paragraph(run.t("kin.positions")), table(head, rows)]


def _extremes_tables(run: ReportRun, cycle: ReportCycle) -> list[str]:
    """Strokes of the sliders (mm) and swings of the rockers (°), with the φ of their extreme positions."""

    mech = run.mech
    out: list[str] = []
    found = extremes(cycle.kin)
    for kind, scale in (("slider", 1000.0), ("rocker", 180.0 / math.pi)):
        ext = [e for e in found if e.kind == kind]
        values = [fixed([getattr(e, k) * scale for e in ext], 5) for k in ("stroke", "low", "high")]
        rows = []
        for i, e in enumerate(ext):
            slider = link_named(mech.link_names[_slider_link(mech, e.name)], run.t) if kind == "slider" else ""
            name = e.name if kind == "rocker" else f"{slider} ({e.name})"
            at_low, at_high = cycle.phi([e.at_low, e.at_high])
            rows.append(
                [
                    name,
                    *(v[i] for v in values),
                    deg(at_low),
                    deg(at_high),
                    ratio(e.time_ratio),
                    ratio(e.forward_time_ratio),
                ]
            )
        if rows:
            head = [run.t(f"extremes.head.{kind}.{k}") for k in ("name", "stroke", "low", "high")]
            head += [run.t(f"extremes.head.{k}") for k in ("phi_low", "phi_high", "k", "forward")]
            out += [paragraph(run.t(f"extremes.{kind}")), table(head, rows)]
    if out:
        out.append(paragraph(run.t("extremes.note")))
    return out


def _slider_link(mech: Mechanism, joint: str) -> int:
    k = list(mech.pair_joint).index(joint)
    return int(mech.pair_links[k, 1])


def _working_table(run: ReportRun, cycle: ReportCycle) -> list[str]:
    """Displacement, velocity and acceleration of the working members at the 12 positions."""

    mech = run.mech
    members = working(mech)
    if not members:
        return []
    head = [run.t("head.position"), run.t("head.phi")]
    columns = []
    for out in members:
        s, v, a = (x[0] for x in coordinate(cycle.twelve, out))
        d = s - s[0]
        if out.kind == "rocker":
            d = np.degrees(d - 2 * np.pi * np.round(d / (2 * np.pi)))
        columns += [d * 1000 if out.kind == "slider" else d, v, a]
        keys = ("s", "v", "a") if out.kind == "slider" else ("psi", "omega", "epsilon")
        label = member_label(mech, out, run.lang)
        head += [run.t(f"working.head.{k}", member=label) for k in keys]
    shown = [fixed(c) for c in columns]
    rows = [[k, f"{30 * k}", *(c[k] for c in shown)] for k in range(12)]
    return [paragraph(run.t("working.title")), table(head, rows)]


def _transmission_table(run: ReportRun, cycle: ReportCycle) -> list[str]:

    rows = []
    for label, mu in transmission_angles(cycle.kin).items():
        if np.isfinite(mu).any():
            i = int(np.nanargmin(mu))
            phi = deg(float(cycle.phi(cycle.kin.angles[i])))
            rows.append([group_label(label, run.lang), f"{math.degrees(float(mu[i])):.1f}", phi])
    if not rows:
        return []
    return [table([run.t("transmission.head.group"), run.t("transmission.head.least"), run.t("head.at_phi")], rows)]


def _event(run: ReportRun, cycle: ReportCycle, event: Any) -> str:
    start, end = cycle.phi([event.start, event.end])
    return run.t(f"event.{event.kind}", group=group_label(event.group, run.lang), start=deg(start), end=deg(end))
