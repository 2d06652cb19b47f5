"""The velocity and acceleration plans worked out, as a course project writes them beside the plans.

For the position of the plans, group by group in the order the plans are built: each point's vector equation
(``v_B = v_A + v_BA = v_O3 + v_BO3``), each vector of the construction with its direction, its value and its
segment on the plan in mm at the plan's scale (``ab = 41.2 mm``), the angular velocity of the line it turns
about (``ω_BA = v_BA / l_BA``); on the acceleration plan the normal components ``aⁿ = ω² l`` (computed, drawn
first), the tangential ones measured off the plan with the angular accelerations ``ε = aτ / l`` they give, the
Coriolis component ``aᵏ = 2 ω v_r`` where a slider moves along a turning guide, the relative one along the
guide; then each point's absolute velocity and acceleration from its segment from the pole.  The values are
those of the analysis (:func:`linkwork.motion.plans.plan_series`), the segments their lengths at the plan's
scale (:func:`linkwork.scene.plans.plan_scale`, the scale the figures draw the plan at).
"""

from __future__ import annotations

import html
import math
from typing import TYPE_CHECKING, Any

import numpy as np

from linkwork.lang import group_label

if TYPE_CHECKING:
    from linkwork.motion.kinematic_analysis import Kinematics
    from linkwork.motion.plans import PlanEdge, PlanSeries


def _n(x: float) -> str:
    """``x`` to 4 significant digits; 0 below 1e-9."""
    if not math.isfinite(x):
        return "-"
    return "0" if abs(x) < 1e-9 else f"{float(f'{x:.4g}') + 0.0:.4g}"


def _point(series: PlanSeries, label: str, kin: Kinematics) -> str:
    """The point of the mechanism a plan point ``label`` stands for (``b`` -> ``B``, ``knife_upper.edge`` as it
    is); the label where none does."""
    names: dict[str, str] = {}
    for name in kin.mechanism.point_names:
        names.setdefault(name.lower(), name)
        names.setdefault(name.split(".", 1)[-1].lower(), name.split(".", 1)[-1])
    return names.get(label, label)


def _link(kin: Kinematics, point: str, about: str) -> str:
    """The number of the moving link that carries both ``point`` and ``about`` (``2`` for B and A on the rod),
    else ``""``."""
    mech = kin.mechanism
    names = set(mech.point_names)
    for k, link in enumerate(mech.link_names):
        if k and f"{link}.{point}" in names and f"{link}.{about}" in names:
            return str(k)
    return ""


def worked_plans(run: Any, kin: Kinematics, index: int, position: str) -> list[str]:
    """The HTML of the plans of sample ``index`` of ``kin`` worked out (``position``: its name for the heading),
    in the report's language (``run.t``, ``run.lang``)."""
    from linkwork.motion.plans import plan_series
    from linkwork.scene.plans import POLES, plan_scale

    out = [f"<h3>{html.escape(run.t('kplan.title', position=position))}</h3>"]
    for series in plan_series(kin):
        scale = plan_scale(series, [index])
        pole = POLES.get((series.kind, run.lang), "p")
        head = run.t(f"kplan.{series.kind}", scale=f"{scale:g}", pole=pole)
        out.append(f"<p><b>{html.escape(head)}</b></p>")
        lines: list[str] = []
        for group in dict.fromkeys(e.group for e in series.edges):
            edges = [(j, e) for j, e in enumerate(series.edges) if e.group == group]
            lines.append(f"<i>{html.escape(group_label(group, run.lang))}</i>")
            lines += _equations(run, series, kin, index, edges)
            lines += [_vector(run, series, kin, index, j, e, scale, pole) for j, e in edges]
        lines += _absolute(run, series, kin, index, scale, pole)
        out.append("<p>" + "<br>".join(lines) + "</p>")
    return out


def _symbol(kind: str, plan: str) -> str:
    """``v``; ``aⁿ``, ``aτ``, ``aᵏ`` (Coriolis), ``aʳ`` (relative, along a guide) or ``a``."""
    if plan == "velocity":
        return "v"
    return {"normal": "aⁿ", "tangential": "aτ", "coriolis": "aᵏ", "sliding": "aʳ"}.get(kind, "a")


def _equations(
    run: Any, series: PlanSeries, kin: Kinematics, index: int, edges: list[tuple[int, PlanEdge]]
) -> list[str]:
    """Each point's vector equation of the group: the sums of the construction's vectors that reach it."""
    out = []
    ends = [e.end for _, e in edges if e.kind in ("rotation", "tangential", "sliding")]
    for label in dict.fromkeys(ends):
        point = _point(series, label, kin)
        sides = []
        for _, last in ((j, e) for j, e in edges if e.end == label):
            chain = [e for _, e in edges if e.end == last.start] + [last]  # a normal component before its tangential
            base = chain[0].start
            start = "" if base == "p" else f"{_symbol('absolute', series.kind)}_{_point(series, base, kin)} + "
            terms = " + ".join(f"{_symbol(e.kind, series.kind)}_{point}{_about(e, point)}" for e in chain)
            sides.append(start + terms)
        letter = "v" if series.kind == "velocity" else "a"
        out.append(html.escape(f"{letter}_{point} = " + " = ".join(sides)))
    return out


def _target(series: PlanSeries, e: PlanEdge) -> str:
    """The plan point of the mechanism's point a vector belongs to: its end, or for a component that ends at a
    construction point (``n_ba``, ``k'_e``) the end of the vector drawn from there."""
    label = e.end
    while label not in series.points:
        label = next((f.end for f in series.edges if f.start == label), series.points[0])
    return label


def _about(e: PlanEdge, point: str) -> str:
    """The second index of a relative vector of ``point`` X: the point it turns about (``v_BA``), X' for the
    motion relative to the guide's coincident point X' (``v_EE'``, ``aᵏ_EE'``), ``'`` for that point's own
    (``v_E'``)."""
    if e.kind in ("sliding", "coriolis"):
        return f"{point}'"
    return "'" if e.about == "frame" or e.kind == "transport" else e.about


def _vector(
    run: Any, series: PlanSeries, kin: Kinematics, index: int, j: int, e: PlanEdge, scale: float, pole: str
) -> str:
    """One vector of the construction: its value, its segment on the plan, and what it gives."""
    value = float(np.hypot(*series.vectors[0, index, j]))
    point = _point(series, _target(series, e), kin)
    mm = value / scale
    start = pole if e.start == "p" else e.start
    name = f"{_symbol(e.kind, series.kind)}_{point}{_about(e, point)}"
    unit = run.t("unit.m_s" if series.kind == "velocity" else "unit.m_s2")
    segment = f"{start}{e.end} = {_n(mm)} {run.t('unit.mm')}"
    length = math.nan
    if e.kind in ("rotation", "normal", "tangential") and e.about != "frame":
        try:
            length = float(np.hypot(*(kin.position(point)[index] - kin.position(e.about)[index])))
        except KeyError:  # a plan's point the solution does not name (a tool's): its vector alone
            length = math.nan
    if length > 0:  # a point turning about another one: its ω or ε (not a guide's coincident point, l = 0)
        k = _link(kin, point, e.about)
        key = {"rotation": "kplan.rotation", "normal": "kplan.normal", "tangential": "kplan.tangential"}[e.kind]
        omega = value / length if e.kind == "rotation" else math.sqrt(value / length)
        return html.escape(
            run.t(
                key,
                name=name,
                value=_n(value),
                unit=unit,
                segment=segment,
                l=_n(length),
                line=f"{point}{e.about}",
                point=point,
                about=e.about,
                omega=_n(omega),
                eps=_n(value / length),
                w=f"ω{k}" if k else f"ω_{point}{e.about}",
                e=f"ε{k}" if k else f"ε_{point}{e.about}",
                mm=_n(mm),
                scale=f"{scale:g}",
            )
        )
    key = f"kplan.{e.kind}" if e.kind in ("sliding", "coriolis", "transport") else "kplan.vector"
    return html.escape(run.t(key, name=name, value=_n(value), unit=unit, segment=segment))


def _absolute(run: Any, series: PlanSeries, kin: Kinematics, index: int, scale: float, pole: str) -> list[str]:
    """Each point's absolute vector from its segment from the pole."""
    unit = run.t("unit.m_s" if series.kind == "velocity" else "unit.m_s2")
    letter = "v" if series.kind == "velocity" else "a"
    out = []
    for j, label in enumerate(series.points):
        if label == "p" or "." in label:  # a tool's point moves as its slider's
            continue
        value = float(np.hypot(*series.values[0, index, j]))
        point = _point(series, label, kin)
        text = f"{letter}_{point} = {pole}{label} · μ = {_n(value / scale)} {run.t('unit.mm')} · {scale:g} = "
        out.append(html.escape(text + f"{_n(value)} {unit}"))
    return [f"<i>{html.escape(run.t('kplan.absolute'))}</i>", *out]
