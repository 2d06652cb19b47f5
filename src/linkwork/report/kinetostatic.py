"""The kinetostatic analysis by the graphical method, as a course project presents it, for the report.

At the position of the plans: for each Assur group in the order the method takes them (the last group
first, the driving link last) the forces on it, the moment equations solved first (each term a force
and its arm, the unknown tangential component or a guide's couple), then the vector equation of the
force plan with its scale μF and each vector's length on the plan, and the reactions read off it; for the
driving link the balancing moment.  Then the force plans and Zhukovsky's lever drawn, and a table that
sets the lever's balancing moment beside the kinetostatic driving torque at the twelve positions.
"""

from __future__ import annotations

import functools
import html
import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from linkwork.lang import group_label

if TYPE_CHECKING:
    from linkwork.kinetostatics.force_polygons import GroupPlan, MomentEquation
    from linkwork.kinetostatics.peaks import Peak
    from linkwork.kinetostatics.reaction_forces import Forces


def _n(x: float, digits: int = 4) -> str:
    """``x`` to ``digits`` significant digits; ``0`` below 1e-9 (a rounding's residue: an arm of 8e-15 mm)."""
    if math.isfinite(x) and abs(x) < 1e-9:
        return "0"
    return "-" if not math.isfinite(x) else f"{float(f'{x:.{digits}g}') + 0.0:.{digits}g}"  # no "-0"


def _esc(text: str) -> str:
    return html.escape(text)


def _table(head: list[str], rows: list[list[Any]]) -> str:
    out = ["<table><thead><tr>" + "".join(f"<th>{_esc(h)}</th>" for h in head) + "</tr></thead><tbody>"]
    out += ["<tr>" + "".join(f"<td>{_esc(str(x))}</td>" for x in row) + "</tr>" for row in rows]
    return "".join(out) + "</tbody></table>"


def _angle(v: np.ndarray) -> str:
    return f"{math.degrees(math.atan2(float(v[1]), float(v[0]))) % 360:.1f}"


@dataclass(frozen=True)
class Where:
    """The position of the graphical kinetostatics: ``index`` of the samples of ``forces``, its number of the
    twelve (``position``; None for an angle between them), φ from position 0 (``phi``, degrees), and why it was
    taken (``why``, a paragraph in the report's language)."""

    forces: Forces
    index: int
    position: int | None
    phi: float
    why: str

    def name(self, run: Any) -> str:
        """``9`` for a position of the twelve, ``φ = 86.6°`` (decimal comma in Russian) for an angle."""
        if self.position is not None:
            return str(self.position)
        return "φ = " + decimal(f"{self.phi:.1f}", run.lang) + "°"


def decimal(text: str, lang: str) -> str:
    """A number as ``lang`` writes it: a decimal comma in Russian."""
    return text.replace(".", ",") if lang == "ru" else text


def where_forces(run: Any, at12: Forces, cycle: Any, f: Forces) -> Where:
    """Where the force plans and the lever are drawn: the position ``--position`` asked (a number of the
    twelve, or φ in rad), else the largest driving torque on the working stroke
    (:func:`working_torque_peak`), solved there (a position between the twelve
    as one sample of its own)."""
    from linkwork.kinetostatics import forces
    from linkwork.motion import kinematics

    asked = cycle.asked
    if isinstance(asked, int):
        return Where(at12, asked % 12, asked % 12, 30.0 * (asked % 12), run.t("kgraph.where.asked"))
    if asked is None:
        peak = working_torque_peak(f)
        if not np.isfinite(peak.at[0]):
            k = cycle.drawn[0]
            return Where(at12, k, k, 30.0 * k, "")
        drive = float(peak.at[0])
    else:
        drive = cycle.zero + cycle.sign * float(asked)
    phi = float(cycle.phi(drive))
    one = forces(kinematics(run.mech, np.array([drive])))
    torque = float(np.asarray(one.driving_torque)[0])
    loads = _loads_text(run, one)
    text = "" if asked is None else run.t("kgraph.where.angle")
    if asked is None:
        text = run.t("kgraph.where.peak", torque=decimal(f"{torque:.0f}", run.lang), loads=loads)
    return Where(one, 0, None, phi, text)


def working_torque_peak(f: Forces) -> Peak:
    """Where the force analysis of a course project is done: the largest driving torque (by size, with its sign)
    on the working stroke (:func:`linkwork.scene.positions.working_stroke`: the knives closing, the ram going
    down; every sample of a mechanism without a working member), of the first variant of ``f``, ``(1,)``.

    The refined peak of the whole turn (:func:`torque_peak`) where its nearest sample is on the working stroke;
    else the largest sample on it (a torque that peaks on the idle stroke, where a heavy link swings back,
    is not where the machine works).  NaN where no sample on the stroke is finite.
    """
    from linkwork.kinetostatics.peaks import Peak, driving_torque, torque_peak
    from linkwork.scene.positions import working_stroke

    kin = f.kinematics
    angles = np.asarray(kin.angles, dtype=float)
    torque = np.asarray(driving_torque(f))[0]
    stroke = working_stroke(kin) & np.isfinite(torque)
    if not stroke.any():
        return Peak(np.array([np.nan]), np.array([np.nan]))
    peak = torque_peak(f)
    at = float(peak.at[0])
    gap = np.abs(np.angle(np.exp(1j * (angles - at))))
    nearest = int(np.argmin(gap))
    if np.isfinite(peak.value[0]) and stroke[nearest]:
        return Peak(peak.value[:1].copy(), peak.at[:1].copy())
    best = int(np.argmax(np.where(stroke, np.abs(torque), -np.inf)))
    return Peak(np.array([torque[best]]), np.array([angles[best]]))


def _loads_text(run: Any, f: Forces) -> str:
    """The process loads acting at the first sample of ``f``, ``cutting 250 kN`` each, in the report's language
    (``no process load`` where none acts)."""
    found = []
    for name, size in f.external.magnitude.items():
        kind = next((ld.kind for ld in run.mech.loads if ld.name == name), "")
        value = float(np.asarray(size).reshape(-1)[0])
        if kind == "process" and math.isfinite(value):
            found.append(f"{name} {decimal(_n(value / 1000), run.lang)} {run.t('unit.kN')}")
    return ", ".join(found) if found else run.t("kgraph.where.no_load")


def sections(run: Any, at12: Forces, cycle: Any, f: Forces) -> tuple[list[str], list[str]]:
    """The body (HTML) and the figures' names of the graphical kinetostatics for the report ``run``
    (:class:`linkwork.report.run.ReportRun`) at :func:`where_forces` (``at12``: the forces at the twelve positions,
    ``f`` over the report's cycle ``cycle``, :class:`~linkwork.report.kinematics.ReportCycle`); with ``cycle.sheets``,
    each group's force plans and the levers of all twelve positions on sheets too; with ``cycle.dxf``,
    ``figures/force_plans.dxf`` and ``figures/lever.dxf``."""
    from linkwork.figures import force_plans as figures
    from linkwork.kinetostatics.force_polygons import force_plans
    from linkwork.kinetostatics.zhukovsky import lever

    at = where_forces(run, at12, cycle, f)
    plans, lv = force_plans(at.forces), lever(at.forces)
    lang, i, named = run.lang, at.index, at.name(run)
    body = [f"<h3>{_esc(run.t('kgraph.title', position=named))}</h3>"]
    body += [f"<p>{_esc(at.why)}</p>"] if at.why else []
    if at.position is None:  # the plans the inertia forces come from, worked out at this angle
        from linkwork.report.kinematic_plans import worked_plans

        body += worked_plans(run, at.forces.kinematics, at.index, named)
    body.append(f"<p>{_esc(run.t('kgraph.intro'))}</p>")
    for g in plans.groups:
        body += _group(run, g, i)
    extra = (at, np.asarray(lv.balancing[0])) if at.position is None else None
    levers = lever(at12)  # the twelve positions': their table and their sheet
    body += _lever_table(run, at12, levers.balancing[0], extra)
    make_plans = functools.partial(figures.force_plans_figure, plans, i, named, lang)
    make_lever = functools.partial(figures.lever_figure, lv, at.forces.kinematics, i, named, lang)
    where = run.t("at_position", position=named)
    names = []
    if at.position is None:  # the plans the inertia forces come from, at this position
        names += _kinematic_plans(run, at, where)
    names += [
        run.figure("force_plans", make_plans, run.t("caption.force_plans") + where),
        run.figure("lever", make_lever, run.t("caption.lever") + where),
    ]
    if cycle.sheets:
        all12 = force_plans(at12)
        for j, g in enumerate(all12.groups):
            caption = run.t("caption.force_plan_sheet", group=group_label(g.label, lang))
            name = f"force_plans_{'_'.join(str(k) for k in g.links)}"
            names.append(run.figure(name, functools.partial(figures.force_plan_sheet, all12, j, lang), caption))
        names.append(
            run.figure(
                "levers",
                functools.partial(figures.lever_sheet, levers, at12.kinematics, lang),
                run.t("caption.levers"),
            )
        )
    if cycle.dxf:
        from linkwork.io.dxf_forces import write_force_plans, write_lever

        folder = run.folder / "figures"
        kin = at.forces.kinematics
        run.jobs.append(lambda: write_force_plans(plans, i, folder / "force_plans.dxf", lang))
        run.jobs.append(lambda: write_lever(lv, kin, i, folder / "lever.dxf", lang))
        run.jobs.append(lambda: _sheets(run, cycle, plans, lv, at))
    return body, names


def _sheets(run: Any, cycle: Any, plans: Any, lv: Any, at: Where) -> None:
    """The drawing sheets of the course project (:mod:`linkwork.io.dxf_sheet`), ``figures/sheet_1.dxf`` (the
    kinematics at the plans' position), ``sheet_2.dxf`` (the kinetostatics at ``at``), ``sheet_3.dxf`` (the
    dynamics of a file with a machine, as the dynamics section found them), more on A3 and A4, and
    ``figures/sheets.pdf``, the same sheets."""
    from linkwork.errors import LinkworkError
    from linkwork.io.sheet_drawings import SheetAnalyses, sheet_options, write_sheets

    fmt, block = sheet_options(run.mech, run.sheets)
    folder = run.folder / "figures"
    twelve, first, named = cycle.twelve, cycle.drawn[0], at.name(run)
    dynamics = None
    if run.mech.motor_gear is not None:
        try:
            dynamics = run.study.dynamics  # found once, by the dynamics section
        except LinkworkError:
            dynamics = None  # the dynamics section says why
    analyses = SheetAnalyses(twelve, first, cycle.kin, plans, lv, at.index, named, dynamics)
    write_sheets(analyses, folder, run.lang, fmt, block)


def _kinematic_plans(run: Any, at: Where, where: str) -> list[str]:
    """The velocity and acceleration plans at ``at``, a position between the twelve."""
    from linkwork import figures

    kin, lang = at.forces.kinematics, run.lang
    return [
        run.figure(
            f"{kind}_plan_forces",
            functools.partial(getattr(figures, f"{kind}_plan"), kin, at.index, position=at.name(run), lang=lang),
            run.t(f"caption.{kind}_plan") + where,
        )
        for kind in ("velocity", "acceleration")
    ]


def _forces_on(run: Any, g: GroupPlan, i: int) -> list[str]:
    lang = run.lang
    rows: list[list[Any]] = []
    for f in g.polygon:
        if f.kind in ("weight", "inertia", "load", "known"):
            v = f.vector[0, i]
            rows.append(
                [
                    f.name(lang),
                    run.t(f"force.{f.kind}") + (f" ({f.about})" if f.kind == "load" else ""),
                    _n(float(np.hypot(*v))),
                    _angle(v),
                ]
            )
    for c in g.couples:
        rows.append([c.name(lang), run.t("kgraph.couple"), _n(float(c.moment[0, i])), ""])
    head = [
        run.t("kgraph.head.force"),
        run.t("kgraph.head.what"),
        run.t("kgraph.head.value"),
        run.t("kgraph.head.direction"),
    ]
    return [_table(head, rows)] if rows else []


def _equation(run: Any, e: MomentEquation, i: int) -> str:
    lang = run.lang
    terms = []
    for f, moment in e.terms:
        m = float(moment[0, i])
        if f.kind == "couple" or not np.any(f.vector[0, i]):
            terms.append(f"{f.name(lang)} ({_n(m)} {run.t('unit.Nm')})")
        else:
            size = float(np.hypot(*f.vector[0, i]))
            arm = m / size if size > 0 else math.nan
            h = _n(arm * 1000 + 0.0, 4)
            h = f"({h})" if h.startswith("-") else h
            terms.append(
                f"{f.name(lang)}·h ({_n(size)} {run.t('unit.N')}·{h} {run.t('unit.mm')} = {_n(m)} {run.t('unit.Nm')})"
            )
    u = e.unknown
    link = f"{e.link}"
    if math.isfinite(float(e.arm[0, i])):
        length = float(e.arm[0, i])
        value = -sum(float(mm[0, i]) for _, mm in e.terms) / length
        return run.t(
            "kgraph.moment",
            about=e.about,
            link=link,
            terms=" + ".join(terms),
            unknown=u.name(lang),
            length=_n(length * 1000),
            value=_n(value),
        )
    return run.t(
        "kgraph.couple_eq",
        about=e.about,
        link=link,
        terms=" + ".join(terms),
        unknown=u.name(lang),
        value=_n(float(u.moment[0, i])),
    )


def _group(run: Any, g: GroupPlan, i: int) -> list[str]:
    lang = run.lang
    label = group_label(g.label, lang)
    links = ", ".join(str(k) for k in g.links)
    head = (
        run.t("kgraph.driving", group=label)
        if g.balancing is not None
        else run.t("kgraph.group", group=label, links=links)
    )
    out = [f"<h4>{_esc(head)}</h4>", f"<p>{_esc(run.t('kgraph.forces_on'))}</p>", *_forces_on(run, g, i)]
    if not g.solved:
        out.append(f"<p>{_esc(run.t('kgraph.not_solved'))}</p>")
    for n, e in enumerate(g.equations, 1):
        out.append(f"<p>{n}. {_esc(_equation(run, e, i))}</p>")
    scale = g.scale(i)
    plan = " + ".join(f.name(lang) for f in g.polygon) + " = 0"
    out.append(f"<p>{_esc(run.t('kgraph.plan', equation=plan, scale=f'{scale:g}'))}</p>")
    rows = [
        [
            f.name(lang),
            run.t(f"force.{f.kind}"),
            _n(float(np.hypot(*f.vector[0, i]))),
            _n(float(np.hypot(*f.vector[0, i])) / scale, 3),
            _angle(f.vector[0, i]),
        ]
        for f in g.polygon
    ]
    head = [
        run.t("kgraph.head.force"),
        run.t("kgraph.head.what"),
        run.t("kgraph.head.value"),
        run.t("kgraph.head.length"),
        run.t("kgraph.head.direction"),
    ]
    out.append(_table(head, rows))
    found = [f"{r.name(lang)} = {_n(float(np.hypot(*r.vector[0, i])))} {run.t('unit.N')}" for r in g.reactions]
    found += [
        f"M{r.index} = {_n(float(r.moment[0, i]))} {run.t('unit.Nm')}"
        for r in g.reactions
        if r.part == "" and np.any(r.moment[0, i]) and r.kind != "internal"
    ]
    out.append(f"<p>{_esc(run.t('kgraph.found', reactions='; '.join(found)))}</p>")
    if g.balancing is not None:
        out.append(f"<p>{_esc(run.t('kgraph.balancing', value=_n(float(g.balancing[0, i]), 6)))}</p>")
    return out


def _lever_table(
    run: Any, at12: Forces, balancing: np.ndarray, extra: tuple[Where, np.ndarray] | None = None
) -> list[str]:
    """The lever's balancing moment ``balancing`` beside the kinetostatic driving torque at the twelve positions,
    and at ``extra`` (a position between them: the force analysis's, with its lever's balancing moments) in a row of
    its own, marked ``*``."""
    from linkwork.kinetostatics.crosschecks import lever_gaps

    torque = np.asarray(at12.driving_torque)
    big = float(np.nanmax(np.abs(torque), initial=0.0))
    gaps = lever_gaps(at12, big, np.asarray(balancing))
    cases = [(str(k), 30.0 * k, float(balancing[k]), float(torque[k]), gaps[k]) for k in range(len(torque))]
    if extra is not None:
        there, moments = extra
        torque_there = float(np.asarray(there.forces.driving_torque)[there.index])
        gap = lever_gaps(there.forces, big, moments)[there.index]
        cases.append(("*", there.phi, float(moments[there.index]), torque_there, gap))
        cases.sort(key=lambda c: c[1])
    rows = []
    for name, phi, mb, md, diff in cases:
        rows.append([name, decimal(f"{phi:g}", run.lang), _n(mb, 7), _n(md, 7), f"{diff:.1e}"])
    head = [
        run.t("head.position"),
        run.t("head.phi"),
        run.t("kgraph.head.lever"),
        run.t("kgraph.head.kinetostatic"),
        run.t("kgraph.head.difference"),
    ]
    return [f"<p>{_esc(run.t('kgraph.lever'))}</p>", _table(head, rows)]
