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
from typing import TYPE_CHECKING, Any

import numpy as np

from linkwork.lang import group_label

if TYPE_CHECKING:
    from linkwork.kinetostatics.force_polygons import GroupPlan, MomentEquation
    from linkwork.kinetostatics.reaction_forces import Forces


def _n(x: float, digits: int = 4) -> str:
    return "-" if not math.isfinite(x) else f"{float(f'{x:.{digits}g}') + 0.0:.{digits}g}"  # no "-0"


def _esc(text: str) -> str:
    return html.escape(text)


def _table(head: list[str], rows: list[list[Any]]) -> str:
    out = ["<table><thead><tr>" + "".join(f"<th>{_esc(h)}</th>" for h in head) + "</tr></thead><tbody>"]
    out += ["<tr>" + "".join(f"<td>{_esc(str(x))}</td>" for x in row) + "</tr>" for row in rows]
    return "".join(out) + "</tbody></table>"


def _angle(v: np.ndarray) -> str:
    return f"{math.degrees(math.atan2(float(v[1]), float(v[0]))) % 360:.1f}"


def sections(
    run: Any, at12: Forces, position: int, sheets: bool = False, dxf: bool = False
) -> tuple[list[str], list[str]]:
    """The body (HTML) and the figures' names of the graphical kinetostatics at ``position`` (of ``at12``, the
    forces at the twelve positions) for the report ``run`` (:class:`linkwork.report.build._Run`); with
    ``sheets``, each group's force plans and the levers of all twelve positions on sheets too; with ``dxf``,
    ``figures/force_plans.dxf`` and ``figures/lever.dxf``."""
    from linkwork.figures import force_plans as figures
    from linkwork.kinetostatics.force_polygons import force_plans
    from linkwork.kinetostatics.zhukovsky import lever

    plans, lv = force_plans(at12), lever(at12)
    lang = run.lang
    body = [f"<h3>{_esc(run.t('kgraph.title', position=position))}</h3>", f"<p>{_esc(run.t('kgraph.intro'))}</p>"]
    for g in plans.groups:
        body += _group(run, g, position)
    body += _lever_table(run, at12, lv.balancing[0])
    make_plans = functools.partial(figures.force_plans_figure, plans, position, position, lang)
    make_lever = functools.partial(figures.lever_figure, lv, at12.kinematics, position, position, lang)
    where = run.t("at_position", position=position)
    names = [
        run.figure("force_plans", make_plans, run.t("caption.force_plans") + where),
        run.figure("lever", make_lever, run.t("caption.lever") + where),
    ]
    if sheets:
        for j, g in enumerate(plans.groups):
            caption = run.t("caption.force_plan_sheet", group=group_label(g.label, lang))
            name = f"force_plans_{'_'.join(str(k) for k in g.links)}"
            names.append(run.figure(name, functools.partial(figures.force_plan_sheet, plans, j, lang), caption))
        names.append(
            run.figure(
                "levers", functools.partial(figures.lever_sheet, lv, at12.kinematics, lang), run.t("caption.levers")
            )
        )
    if dxf:
        from linkwork.io.dxf_forces import write_force_plans, write_lever

        folder = run.folder / "figures"
        run.jobs.append(lambda: write_force_plans(plans, position, folder / "force_plans.dxf", lang))
        run.jobs.append(lambda: write_lever(lv, at12.kinematics, position, folder / "lever.dxf", lang))
    return body, names


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


def _lever_table(run: Any, at12: Forces, balancing: np.ndarray) -> list[str]:
    torque = np.asarray(at12.driving_torque)
    big = float(np.nanmax(np.abs(torque), initial=0.0))
    rows = []
    for k in range(len(torque)):
        diff = abs(float(balancing[k]) - float(torque[k])) / big if big > 0 else math.nan
        rows.append([k, f"{30 * k}", _n(float(balancing[k]), 7), _n(float(torque[k]), 7), f"{diff:.1e}"])
    head = [
        run.t("head.position"),
        run.t("head.phi"),
        run.t("kgraph.head.lever"),
        run.t("kgraph.head.kinetostatic"),
        run.t("kgraph.head.difference"),
    ]
    return [f"<p>{_esc(run.t('kgraph.lever'))}</p>", _table(head, rows)]
