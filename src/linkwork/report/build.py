"""The main job: every analysis a mechanism supports, its tables, figures, animation and a report.

:func:`analyze` writes into a fresh folder beside the output folder and puts
it in place only when everything is written, so an interrupted run never
leaves a half-written report where a good one was; it replaces only a folder
that holds a report and nothing else (:mod:`linkwork.report.folder`).

The report is written in English or Russian (``lang``, :mod:`linkwork.lang`): its
text, table headings and the labels of the diagrams.  Every angle of its tables
and diagrams is the crank angle φ turned from position 0 (0 to 360°,
:func:`linkwork.motion.analysis.from_position_0`); every table states its units.
"""

from __future__ import annotations

import base64
import functools
import html
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from linkwork.io.jsonout import dumps
from linkwork.lang import check_lang, group_kind, group_label, kind_named, link_named, t
from linkwork.limits import TURN_STEPS
from linkwork.optional import require
from linkwork.report.render import shown_width
from linkwork.report.sizing import asks_sizing
from linkwork.structure.model import PairType
from linkwork.units import turn_deg

if TYPE_CHECKING:
    from linkwork.kinetostatics.reaction_forces import Forces
    from linkwork.motion.kinematic_analysis import Kinematics
    from linkwork.structure.model import Mechanism


@dataclass
class Section:
    """One section of the report: a title, paragraphs and tables (HTML), figures (names)."""

    key: str
    title: str
    body: list[str] = field(default_factory=list)
    figures: list[str] = field(default_factory=list)


def _cell(x: Any) -> str:
    """A table's cell: a number to 4 significant digits, a tuple one line each (a point's x over its y)."""
    if isinstance(x, tuple):
        return "<br>".join(_cell(v) for v in x)
    if isinstance(x, float | np.floating):
        return "-" if not math.isfinite(x) else f"{x:.4g}"
    return html.escape(str(x))


def _fixed(values: Any, significant: int = 4) -> list[str]:
    """A column of numbers with one number of decimals: ``significant`` digits of its largest."""
    a = np.asarray(values, dtype=float)
    big = float(np.nanmax(np.abs(a))) if np.isfinite(a).any() else 0.0
    decimals = 0 if big == 0 else max(0, significant - 1 - math.floor(math.log10(big)))
    return ["-" if not math.isfinite(x) else f"{round(x, decimals) + 0.0:.{decimals}f}" for x in a]


def _ratio(x: float) -> str:
    return "-" if not math.isfinite(x) else f"{x:.6g}"


def _table(head: list[str], rows: list[list[Any]]) -> str:
    out = ["<table><thead><tr>" + "".join(f"<th>{html.escape(h)}</th>" for h in head) + "</tr></thead><tbody>"]
    out += ["<tr>" + "".join(f"<td>{_cell(x)}</td>" for x in row) + "</tr>" for row in rows]
    return "".join(out) + "</tbody></table>"


def _p(text: str) -> str:
    return f"<p>{html.escape(text)}</p>"


def _deg(x: float) -> str:
    return "-" if not math.isfinite(x) else f"{x:.1f}"


class _Run:
    """What a run of :func:`analyze` collects: its sections, the captions of its figures, its language, and
    the jobs that draw the figures (queued, then run beside the analyses or here: :class:`Beside`)."""

    def __init__(
        self, mech: Mechanism, folder: Path, progress: Callable[[str], None], lang: str, parallel: bool
    ) -> None:
        from linkwork.report.beside import Beside

        self.mech = mech
        self.folder = folder
        self.progress = progress
        self.lang = lang
        self.sizing: bool | None = None  # the "Sizing" section: asked, refused, or as the file says (None)
        self.sections: list[Section] = []
        self.figures: dict[str, Any] = {}  # those drawn in this process
        self.captions: dict[str, str] = {}
        self.jobs: list[Callable[[], object]] = []
        self.beside = Beside(parallel)
        (folder / "figures").mkdir(parents=True)

    def t(self, key: str, **values: Any) -> str:
        """The text ``key`` in the report's language."""
        return t(key, self.lang, **values)

    def figure(self, name: str, make: Callable[[], Any], caption: str) -> str:
        """Queue the figure ``make()`` draws, to be written as ``figures/NAME.svg`` and ``.png``; returns
        ``name`` for a section's figures."""
        self.captions[name] = self.t("caption", number=len(self.captions) + 1, text=caption)
        self.jobs.append(lambda: self._draw(name, make))
        return name

    def _draw(self, name: str, make: Callable[[], Any]) -> None:
        from linkwork.report.render import save

        fig = make()
        save(fig, self.folder / "figures" / name)
        self.figures[name] = fig

    def run_beside(self) -> None:
        """Start the jobs queued so far in the second process."""
        jobs, self.jobs = self.jobs, []
        self.beside.start(jobs)

    def run_here(self) -> None:
        """Run the jobs queued since, in this process, then those of the second process it has not started, and
        wait for it."""
        jobs, self.jobs = self.jobs, []
        for job in jobs:
            job()
        self.beside.wait()


@dataclass(frozen=True)
class ReportCycle:
    """The kinematics the report's tables and figures share.

    Attributes
    ----------
    kin : Kinematics
        ``steps`` equal steps of a turn from position 0 in the drive's direction.
    zero : float
        Drive angle of position 0, rad.
    sign : float
        +1 where the crank turns counter-clockwise, -1 clockwise.
    twelve : Kinematics
        The 12 positions, position 0 first.
    index : int
        The sample of ``kin`` at the position of the plans.
    drawn : tuple of int
        The positions the plans are drawn at (of the twelve).
    sheets : bool
        Whether the plans of all twelve positions are drawn too (``--position all``).
    dxf : bool
        Whether the drawings are written for CAD too.
    """

    kin: Kinematics
    zero: float
    sign: float
    twelve: Kinematics
    index: int
    drawn: tuple[int, ...] = (0,)
    sheets: bool = False
    dxf: bool = False

    def phi(self, angles: Any) -> np.ndarray:
        """Crank angles turned from position 0, degrees in [0, 360), of drive angles (rad), as the tables and
        JSON files write them (:func:`linkwork.motion.analysis.phi_deg`)."""
        from linkwork.motion.analysis import phi_deg

        return np.asarray(phi_deg(angles, self.zero, self.sign))


def analyze(
    mech: Mechanism,
    out: str | Path,
    *,
    steps: int = TURN_STEPS,
    position: int | str | None = None,
    pdf: bool = False,
    animation: bool = True,
    dxf: bool = False,
    lang: str = "en",
    progress: Callable[[str], None] | None = None,
    sizing: bool | None = None,
) -> Path:
    """Run every analysis ``mech`` supports and write tables, figures, an animation and
    ``report.html`` (and ``report.pdf``) into the folder ``out``; returns the report's path.

    ``position``: which of the 12 positions (numbered from position 0, the working member's high end,
    as ``linkwork positions`` does) gets the scheme and the velocity and acceleration plans; ``"all"``
    adds sheets of the plans of all twelve; default the file's ``drawing.positions``, else where the
    working point moves fastest (:func:`linkwork.scene.positions.plan_positions`).  ``dxf``: also the
    drawings for CAD, ``figures/*.dxf`` (needs ezdxf).  ``lang``: ``"en"`` or ``"ru"``.  ``sizing``: the
    "Sizing" section (:mod:`linkwork.report.sizing`, ``sizing.json``): True, False, or None where the file
    has a ``sizing:`` section.  Needs
    matplotlib and xarray (:func:`require_packages`).

    Parameters
    ----------
    mech : Mechanism
        A compiled mechanism (:func:`linkwork.compile`).
    out : str or Path
        The report's folder: a new name, an empty folder or an earlier report (replaced whole).
    steps : int
        Crank angles over the turn for the tables and diagrams; default 360.
    position : int or str, optional
        The position drawn (0 to 11), or ``"all"``.
    pdf : bool
        Also ``report.pdf``.
    animation : bool
        Write ``animation.gif``; default True.
    dxf : bool
        Also the drawings for CAD, ``figures/*.dxf``.
    lang : str
        ``"en"`` or ``"ru"``.
    progress : callable, optional
        ``progress(stage)`` as each stage begins.
    sizing : bool, optional
        The "Sizing" section: True, False, or None where the file has a ``sizing:`` section.

    Returns
    -------
    Path
        ``out/report.html``.

    Raises
    ------
    LinkworkError
        ``out`` is something other than a report folder, an empty folder or a new name: a folder of
        other files, a file, a symbolic link, a device (see :func:`linkwork.report.folder.problem`);
        or ``lang`` is not a language of the report.

    Examples
    --------
    >>> import linkwork as lw
    >>> from linkwork.report import analyze
    >>> analyze(lw.compile("four-bar"), "report", steps=72)  # doctest: +SKIP
    PosixPath('report/report.html')
    """
    from linkwork.report.folder import replacing

    check_lang(lang)
    require_packages()
    with replacing(out) as work:
        run = _Run(mech, work, progress or (lambda _: None), lang, parallel=PARALLEL and not pdf)
        run.sizing = sizing
        try:
            _build(run, steps, position, animation, dxf)
        finally:
            run.beside.stop()
        _write_html(run, work / "report.html")
        if pdf:
            _write_pdf(run, work / "report.pdf")
    return Path(out) / "report.html"


#: Whether a report draws the figures of its kinematics (and writes its animation and NetCDF table) in a
#: second process while this one solves the forces and dynamics and draws theirs (on Linux; not with
#: ``pdf``, whose pages need every figure here).
PARALLEL = True


def require_packages() -> None:
    """Raise :class:`~linkwork.errors.MissingDependencyError` unless the optional packages of the
    report are installed: matplotlib (the figures) and xarray (``kinematics.nc``).

    They are found, not imported: ``kinematics.nc``, the file xarray reads, is written through SciPy
    (:func:`linkwork.io.motion_tables.write_netcdf`), without importing xarray, pandas or Dask."""
    from importlib.util import find_spec

    from linkwork.optional import require

    missing = [name for name in ("matplotlib", "xarray") if find_spec(name) is None]
    if missing:
        require(*missing, purpose="the report (linkwork analyze)")  # raises, naming them and the pip command


def _build(run: _Run, steps: int, position: int | str | None, animation: bool, dxf: bool = False) -> None:
    from linkwork.report.inputs import input_section
    from linkwork.structure.model import one_crank

    _requirements(run)
    run.sections.append(Section("input", run.t("section.input"), input_section(run.mech, steps, run.t)))
    _structure(run)
    if not one_crank(run.mech):
        run.sections.append(Section("kinematics", run.t("section.kinematics"), [_p(run.t("kin.needs_crank"))]))
        return
    cycle = _kinematics(run, steps, position, dxf)
    if animation:
        from linkwork import figures

        # first: the longest job, not left for last to one process while the other has nothing to draw
        run.jobs.insert(0, lambda: figures.animate(cycle.kin, run.folder / "animation.gif", lang=run.lang))
    _import_drawing()
    run.run_beside()
    if not run.mech.structure.redundant:
        _forces(run, cycle)
    if run.mech.motor_gear is not None:
        _dynamics(run, cycle)
    if run.mech.blow is not None:
        _impact(run)
    if asks_sizing(run.mech, run.sizing):
        _sizing(run)
    if run.mech.spec is not None and run.mech.spec.simulate is not None:
        _time_run(run)
    run.progress("figures")
    run.run_here()


def _requirements(run: _Run) -> None:
    """The section a file that carries requirements (a synthesised one) opens with: each requirement, what the
    mechanism achieves as the analysis measures it, and the limit positions with theta drawn."""
    from linkwork.structure.model import one_crank
    from linkwork.synthesis.achieved import requirement_rows

    if not one_crank(run.mech):
        return
    from linkwork import figures
    from linkwork.motion import kinematics
    from linkwork.scene.limits import limits_scene

    kin = kinematics(run.mech, steps=360)
    found = requirement_rows(kin)
    if found is None:
        return
    kind, rows = found
    sec = Section("requirements", run.t("section.requirements"), [_p(run.t("requirements.intro", kind=kind))])
    head = [run.t(f"requirements.head.{k}") for k in ("name", "asked", "achieved", "met")]
    sec.body.append(_table(head, [_requirement_row(run, row) for row in rows]))
    limits = limits_scene(kin)
    if limits is not None:
        theta = math.degrees(limits.theta)
        k = (180.0 + theta) / (180.0 - theta)
        sec.body.append(_p(run.t("requirements.theta", theta=f"{theta:.3f}", k=f"{k:.6g}", member=limits.member)))
        lang = run.lang
        sec.figures.append(
            run.figure(
                "limits", lambda: figures.draw_limits(kin, lang=lang), run.t("caption.limits", member=limits.member)
            )
        )
    run.sections.append(sec)


def _requirement_row(run: _Run, row: Any) -> list[str]:
    """A requirement's name, the value asked (with its sense), what the mechanism achieves, whether it is met."""
    scale, unit = {"length": (1e3, "unit.mm"), "angle": (180 / math.pi, "unit.deg")}.get(row.kind, (1.0, ""))

    def shown(x: float) -> str:
        text = f"{x * scale:.10g}"
        return f"{text}{run.t(unit)}" if unit == "unit.deg" else f"{text} {run.t(unit)}" if unit else text

    sense = "" if row.sense in ("equal", "given") else run.t(f"requirements.sense.{row.sense.replace(' ', '_')}") + " "
    achieved = run.t("requirements.as_given") if row.achieved is None else shown(row.achieved)
    met = "" if row.met is None else run.t("requirements.yes" if row.met else "requirements.no")
    return [run.t(f"requirement.{row.name}"), sense + shown(row.asked), achieved, met]


def _import_drawing() -> None:
    """Import matplotlib's figure and Agg canvas (a third of a second) once, before the second process forks:
    both processes draw."""
    require("matplotlib.figure", "matplotlib.backends.backend_agg", purpose="the report's figures")


def _structure(run: _Run) -> None:
    run.progress("structure")
    s = run.mech.structure
    sec = Section("structure", run.t("section.structure"))
    sec.body.append(
        _p(run.t("structure.counts", n=s.n_links, p5=s.p5, p4=s.p4, w=s.dof, q=s.redundant, mobility=s.mobility))
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
    sec.body.append(_table(head, rows))
    sec.body.append(_p(run.t("structure.formula", formula=s.formula)))
    run.sections.append(sec)


def _kinematics(run: _Run, steps: int, position: int | str | None, dxf: bool) -> ReportCycle:
    from linkwork import figures
    from linkwork.io.motion_tables import write_csv, write_netcdf
    from linkwork.motion import kinematics
    from linkwork.motion.analysis import position_angles, zero_angle
    from linkwork.motion.kinematic_analysis import direction
    from linkwork.scene.positions import plan_positions

    mech = run.mech
    run.progress("kinematics")
    zero = zero_angle(mech)
    kin = kinematics(mech, position_angles(mech, steps, zero))
    twelve = kinematics(mech, position_angles(mech, 12, zero))
    sign = direction(mech)
    drawn = plan_positions(mech, twelve) if position in (None, "all") else [int(position) % 12]
    phi = np.degrees(np.arange(steps) * 2 * np.pi / steps)
    index = int(np.argmin(np.abs((phi - 30.0 * drawn[0] + 180.0) % 360.0 - 180.0)))
    cycle = ReportCycle(kin, zero, sign, twelve, index, tuple(drawn), position == "all", dxf)
    run.jobs.append(lambda: write_csv(kin, run.folder / "kinematics.csv"))
    run.jobs.append(lambda: write_netcdf(kin, run.folder / "kinematics.nc"))
    sec = Section("kinematics", run.t("section.kinematics"))
    sec.body.append(_p(_position_0(run, cycle)))
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
    sec.body += [_p(_event(run, cycle, e)) for e in kin.events]
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


def _plans(run: _Run, twelve: Kinematics, drawn: list[int], sheets: bool) -> list[str]:
    """The velocity and acceleration plans at the positions ``drawn`` (the first one's named
    ``velocity_plan``, the others' ``velocity_plan_9``...) and, with ``sheets``, those of all twelve."""
    from linkwork import figures

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


def _position_0(run: _Run, cycle: ReportCycle) -> str:
    """What φ and position 0 are, in words."""
    from linkwork.figures.diagrams import member_label
    from linkwork.motion.analysis import working

    members = working(run.mech)
    crank = _deg(turn_deg(cycle.zero))
    if not members:
        return run.t("kin.phi.assembly", crank=crank)
    kind = "slider" if members[0].kind == "slider" else "rocker"
    member = member_label(run.mech, members[0], run.lang)
    if kind == "rocker":  # "the output rocker", not "the output rocker rocker"
        member = kind_named(run.t("kin.rocker_word"), member)
    return run.t(f"kin.phi.{kind}", member=member, crank=crank)


def _positions_table(run: _Run, cycle: ReportCycle) -> list[str]:
    from linkwork.structure.model import point_labels

    mech, kin12 = run.mech, cycle.twelve
    labels = point_labels(mech)
    rows = []
    for k in range(12):
        row: list[Any] = [k, f"{30 * k}", _deg(turn_deg(kin12.angles[k]))]
        for _, p in labels:
            x = kin12.position(mech.point_names[p])[k] * 1000
            row.append("-" if not np.isfinite(x).all() else tuple(f"{round(c, 1) + 0.0:.1f}" for c in x))
        rows.append(row)
    head = [run.t("head.position"), run.t("head.phi"), run.t("head.crank_to_x"), *[label for label, _ in labels]]
    return [_p(run.t("kin.positions")), _table(head, rows)]


def _extremes_tables(run: _Run, cycle: ReportCycle) -> list[str]:
    """Strokes of the sliders (mm) and swings of the rockers (°), with the φ of their extreme positions."""
    from linkwork.motion.analysis import extremes

    mech = run.mech
    out: list[str] = []
    found = extremes(cycle.kin)
    for kind, scale in (("slider", 1000.0), ("rocker", 180.0 / math.pi)):
        ext = [e for e in found if e.kind == kind]
        values = [_fixed([getattr(e, k) * scale for e in ext], 5) for k in ("stroke", "low", "high")]
        rows = []
        for i, e in enumerate(ext):
            slider = link_named(mech.link_names[_slider_link(mech, e.name)], run.t) if kind == "slider" else ""
            name = e.name if kind == "rocker" else f"{slider} ({e.name})"
            at_low, at_high = cycle.phi([e.at_low, e.at_high])
            rows.append(
                [
                    name,
                    *(v[i] for v in values),
                    _deg(at_low),
                    _deg(at_high),
                    _ratio(e.time_ratio),
                    _ratio(e.forward_time_ratio),
                ]
            )
        if rows:
            head = [run.t(f"extremes.head.{kind}.{k}") for k in ("name", "stroke", "low", "high")]
            head += [run.t(f"extremes.head.{k}") for k in ("phi_low", "phi_high", "k", "forward")]
            out += [_p(run.t(f"extremes.{kind}")), _table(head, rows)]
    if out:
        out.append(_p(run.t("extremes.note")))
    return out


def _slider_link(mech: Mechanism, joint: str) -> int:
    k = list(mech.pair_joint).index(joint)
    return int(mech.pair_links[k, 1])


def _working_table(run: _Run, cycle: ReportCycle) -> list[str]:
    """Displacement, velocity and acceleration of the working members at the 12 positions."""
    from linkwork.figures.diagrams import member_label
    from linkwork.motion.analysis import coordinate, working

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
    shown = [_fixed(c) for c in columns]
    rows = [[k, f"{30 * k}", *(c[k] for c in shown)] for k in range(12)]
    return [_p(run.t("working.title")), _table(head, rows)]


def _transmission_table(run: _Run, cycle: ReportCycle) -> list[str]:
    from linkwork.motion.analysis import transmission_angles

    rows = []
    for label, mu in transmission_angles(cycle.kin).items():
        if np.isfinite(mu).any():
            i = int(np.nanargmin(mu))
            phi = _deg(float(cycle.phi(cycle.kin.angles[i])))
            rows.append([group_label(label, run.lang), f"{math.degrees(float(mu[i])):.1f}", phi])
    if not rows:
        return []
    return [_table([run.t("transmission.head.group"), run.t("transmission.head.least"), run.t("head.at_phi")], rows)]


def _event(run: _Run, cycle: ReportCycle, event: Any) -> str:
    start, end = cycle.phi([event.start, event.end])
    return run.t(f"event.{event.kind}", group=group_label(event.group, run.lang), start=_deg(start), end=_deg(end))


def _forces(run: _Run, cycle: ReportCycle) -> None:
    from linkwork import figures
    from linkwork.io.force_tables import to_json, write_csv
    from linkwork.kinetostatics import forces
    from linkwork.structure.model import one_crank

    mech = run.mech
    run.progress("forces")
    f = forces(cycle.kin)
    write_csv(f, run.folder / "forces.csv")
    (run.folder / "forces.json").write_text(dumps(to_json(f)), encoding="utf-8")
    at12 = forces(cycle.twelve)
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
    if one_crank(mech):  # the graphical method: force plans and Zhukovsky's lever at the plans' position
        from linkwork.report.kinetostatic import sections

        body, names = sections(run, at12, cycle.drawn[0], cycle.sheets, cycle.dxf)
        sec.body += body
        sec.figures += names
    run.sections.append(sec)


def _efficiency_text(run: _Run, f: Forces) -> list[str]:
    """With friction in the pairs: where it has no solution, the efficiency of the cycle and the instantaneous
    one, and a table of the work lost in each joint (:mod:`linkwork.kinetostatics.efficiency`)."""
    from linkwork.io.force_tables import has_losses

    if not has_losses(f):
        return []
    out = []
    for problem in f.friction.problems if f.friction is not None else ():
        at = ", ".join(f"{x:.0f}" for x in problem.angles[:8]) + (" …" if len(problem.angles) > 8 else "")
        out.append(_p(run.t(f"friction.{problem.kind}", at=at)))
    e = f.efficiency
    drive, cycle, eta = float(e.work(e.drive)), float(e.cycle), e.instantaneous
    if math.isfinite(cycle) and np.isfinite(eta).any():
        useful = float(e.work(e.useful))
        low, high = (round(float(x), 3) + 0.0 for x in (np.nanmin(eta), np.nanmax(eta)))  # no "-0.000"
        out.append(
            _p(
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
        out.append(_p(run.t("efficiency.none")))
    works = e.work(e.losses)
    peaks = [
        float(np.nanmax(e.losses[:, j])) if np.isfinite(e.losses[:, j]).any() else math.nan
        for j in range(len(e.joints))
    ]
    share = works / drive * 100 if drive > 0 else np.full(len(works), np.nan)
    rows = [list(r) for r in zip(e.joints, _fixed(works), _fixed(share), _fixed(peaks), strict=True)]
    head = [
        run.t("efficiency.head.joint"),
        run.t("efficiency.head.work"),
        run.t("efficiency.head.share"),
        run.t("efficiency.head.peak"),
    ]
    return out + [_table(head, rows)]


def _force_unit(f: Forces) -> tuple[float, str]:
    """kN where the largest joint force is 10 kN or more, else N: (factor from N, unit key)."""
    big = np.nanmax(np.abs(f.multipliers)) if np.isfinite(f.multipliers).any() else 0.0
    return (1e-3, "unit.kN") if big >= 1e4 else (1.0, "unit.N")


def _torque_text(run: _Run, cycle: ReportCycle, f: Forces) -> list[str]:
    from linkwork.kinetostatics.peaks import torque_peak

    torque = np.asarray(f.driving_torque)
    if not np.isfinite(torque).any():
        return []
    peak = torque_peak(f)  # refined between the samples, as every route gives it
    top, at = float(peak.value[0]), float(peak.at[0])
    factor, unit = (1e-3, "unit.kNm") if abs(top) >= 1e4 else (1.0, "unit.Nm")
    return [
        _p(
            run.t(
                "forces.torque",
                peak=f"{top * factor:.4g}",
                mean=f"{np.nanmean(torque) * factor:.4g}",
                unit=run.t(unit),
                at=_deg(float(cycle.phi(at))),
            )
        )
    ]


def _joint_table(run: _Run, cycle: ReportCycle, f: Forces, unit: tuple[float, str]) -> list[str]:
    from linkwork.kinetostatics.peaks import pair_force_peaks
    from linkwork.kinetostatics.tables import pair_labels

    mech = run.mech
    rows: list[list[Any]] = []
    members = mech.pair_links if mech.pair_members is None else mech.pair_members  # in the file's order
    labels = pair_labels(mech)
    peaks = pair_force_peaks(f, [k for _, k in labels])  # refined between the samples, as every route gives them
    for (label, k), size, at in zip(labels, peaks.value, peaks.at, strict=True):
        if not np.isnan(size):  # infinite where it grows without bound towards a singular position
            a, b = (link_named(mech.link_names[int(x)], run.t) for x in members[k])
            rows.append([label, f"{a} \u2192 {b}", float(size) * unit[0], _deg(float(cycle.phi(at)))])
    sizes = np.array([row[2] for row in rows], dtype=float)
    for row, text, endless in zip(rows, _fixed(np.where(np.isinf(sizes), np.nan, sizes)), np.isinf(sizes), strict=True):
        row[2] = run.t("joints.unbounded") if endless else text
    head = [
        run.t("joints.head.joint"),
        run.t("joints.head.links"),
        run.t("joints.head.largest", unit=run.t(unit[1])),
        run.t("head.at_phi"),
    ]
    return [_table(head, rows)] + ([_p(run.t("joints.unbounded.note"))] if np.isinf(sizes).any() else [])


def _forces_at_positions(run: _Run, f: Forces, unit: tuple[float, str]) -> list[str]:
    """The driving torque and the forces in the frame's joints at the 12 positions."""
    mech = run.mech
    supports = [str(mech.pair_joint[k]) for k in range(mech.n_pairs) if mech.pair_links[k, 0] == 0]
    supports = list(dict.fromkeys(supports))
    torque = np.asarray(f.driving_torque)
    tf, tunit = (1e-3, "unit.kNm") if np.nanmax(np.abs(torque), initial=0.0) >= 1e4 else (1.0, "unit.Nm")
    columns = [_fixed(torque * tf)] + [_fixed(np.hypot(*np.asarray(f.reaction(j)).T) * unit[0]) for j in supports]
    rows = [[k, f"{30 * k}", *(c[k] for c in columns)] for k in range(12)]
    head = [run.t("head.position"), run.t("head.phi"), run.t("positions.head.torque", unit=run.t(tunit))]
    head += [run.t("positions.head.support", joint=j, unit=run.t(unit[1])) for j in supports]
    return [_p(run.t("positions.forces")), _table(head, rows)]


def _foundation_table(run: _Run, cycle: ReportCycle, f: Forces, unit: tuple[float, str]) -> list[str]:
    b = f.bolts()
    factor, funit = unit
    mfactor, munit = (1e-3, "unit.kNm") if abs(b.moment) >= 1e4 else (1.0, "unit.Nm")
    rows = [
        [run.t(f"foundation.{name}", unit=run.t(u)), value * k, _deg(float(cycle.phi(angle)))]
        for name, value, angle, k, u in (
            ("shear", b.shear, b.shear_angle, factor, funit),
            ("pull", b.pull, b.pull_angle, factor, funit),
            ("push", b.push, b.push_angle, factor, funit),
            ("moment", b.moment, b.moment_angle, mfactor, munit),
        )
    ]
    head = [run.t("foundation.head"), run.t("foundation.head.largest"), run.t("head.at_phi")]
    return [_table(head, rows)]


def _checks_table(run: _Run, f: Forces) -> list[str]:
    from linkwork.io.force_tables import groups

    checks: list[list[Any]] = [[run.t(f"check.{k}"), f"{v:.2g}"] for k, v in f.checks.items()]
    checks += [
        [run.t("check.free_body", group=group_label(g["group"], run.lang)), f"{g['residual']:.2g}"] for g in groups(f)
    ]
    return [_p(run.t("checks.title")), _table([run.t("checks.head.check"), run.t("checks.head.value")], checks)]


def _dynamics(run: _Run, cycle: ReportCycle) -> None:
    from linkwork import figures
    from linkwork.io.dynamics_tables import to_json
    from linkwork.machine import dynamics

    mech = run.mech
    run.progress("dynamics")
    result = dynamics(mech)  # as lw.dynamics and linkwork dynamics run it
    data = to_json(mech, result, zero=cycle.zero)
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
    sec.body.append(_table([run.t("dynamics.head.quantity"), run.t("dynamics.head.value")], rows))
    if fly is not None:
        sec.body.append(
            _p(
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


def _sizing(run: _Run) -> None:
    from linkwork.report.sizing import sizing_section

    run.progress("sizing")
    body, result = sizing_section(run.mech, run.t)
    if result is not None:
        (run.folder / "sizing.json").write_text(dumps(result.record()), encoding="utf-8")
    run.sections.append(Section("sizing", run.t("section.sizing"), body))


def _time_run(run: _Run) -> None:
    """The run in time the file asks for (``simulate:``), as ``linkwork simulate`` runs it: a table of its
    start, end and stops, ``simulate.json`` and ``simulate.csv`` beside the report, and its diagram."""
    from linkwork import figures
    from linkwork.errors import LinkworkError
    from linkwork.io.run_tables import csv_text, to_json
    from linkwork.machine.timerun import simulate
    from linkwork.units import turn_deg

    mech = run.mech
    asked = mech.spec.simulate if mech.spec is not None else None
    assert asked is not None  # _build calls this only for a file with a run
    run.progress("simulate")
    sec = Section("simulate", run.t("section.simulate"))
    try:
        result = simulate(mech, asked.until, angle=asked.angle, speed=asked.speed or 0.0, motor=asked.motor)
    except LinkworkError as exc:
        sec.body.append(_p(str(exc)))
        run.sections.append(sec)
        return
    (run.folder / "simulate.json").write_text(dumps(to_json(result)), encoding="utf-8")
    (run.folder / "simulate.csv").write_text(csv_text(result), encoding="utf-8")
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
    sec.body.append(_table([run.t("dynamics.head.quantity"), run.t("dynamics.head.value")], rows))
    lang = run.lang
    sec.figures.append(run.figure("simulate", lambda: figures.run_diagram(result, lang), run.t("caption.simulate")))
    run.sections.append(sec)


def _impact(run: _Run) -> None:
    from linkwork.impulse import impact

    mech = run.mech
    blow = mech.blow
    assert blow is not None  # _build calls this only for a mechanism with a blow
    run.progress("impact")
    r = impact(mech)
    sec = Section("impact", run.t("section.impact"))
    rows: list[list[Any]] = [[run.t("impact.impulse_on", at=blow.at), _vector(r.impulse, run.t("unit.Ns"))]]
    rows += [[run.t("impact.joint", joint=j), _vector(v, run.t("unit.Ns"))] for j, v in r.joints.items()]
    rows += [[run.t("impact.energy_lost"), r.energy_loss]]
    if r.ideal_com is not None:
        rows.append([run.t("impact.ideal_com"), _vector(np.asarray(r.ideal_com) * 1000, run.t("unit.mm"))])
    sec.body.append(_table([run.t("impact.head.blow"), run.t("dynamics.head.value")], rows))
    if mech.motor_gear is not None and blow.tool is not None:
        _impact_cycle(run, sec)
    run.sections.append(sec)


def _vector(v: Any, unit: str) -> str:
    return f"({v[0]:.4g}, {v[1]:.4g}) {unit}"


def _impact_cycle(run: _Run, sec: Section) -> None:
    """The working cycle with the file's drive and tool: the steady cycle's blow and phases."""
    from linkwork.errors import LinkworkError
    from linkwork.impulse import simulate_blows

    mech = run.mech
    assert mech.blow is not None  # _impact calls this only for a mechanism with a blow
    try:
        c = simulate_blows(mech)
    except LinkworkError as exc:
        sec.body.append(_p(run.t("impact.cycle_failed", reason=str(exc))))
        return
    b = c.last
    sec.body.append(_p(run.t("impact.cycle", blows=f"{c.blows_per_minute:.4g}")))
    ns = run.t("unit.Ns")
    rows: list[list[Any]] = [
        [run.t("impact.speed"), b.impact_speed],
        [run.t("impact.crank_speeds"), f"{b.crank_speed_before:.4g} / {b.crank_speed_after:.4g}"],
        [run.t("impact.energies"), f"{b.energy_lost:.4g} / {b.energy_to_tool:.4g}"],
        [run.t("impact.impulse_on", at=mech.blow.at), _vector(b.impulse, ns)],
    ]
    rows += [[run.t("impact.joint", joint=j), _vector(v, ns)] for j, v in b.joints.items()]
    rows += [[run.t("impact.work"), b.work_on_work], [run.t("impact.motor_power"), c.mean_power]]
    sec.body.append(_table([run.t("impact.head.steady"), run.t("dynamics.head.value")], rows))
    phases = [
        [run.t(f"phase.{p.kind}"), p.freedom, 1000 * (p.start - b.time), 1000 * p.duration] for p in c.cycle_phases()
    ]
    head = [run.t(f"phases.head.{k}") for k in ("phase", "freedom", "from", "lasts")]
    sec.body.append(_table(head, phases))


STYLE = """
body{font-family:system-ui,sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;color:#222}
table{border-collapse:collapse;margin:0.6em 0;font-size:90%;display:block;overflow-x:auto;max-width:100%}
td,th{border:1px solid #ccc;padding:2px 8px;text-align:right}th{background:#f3f3f3;min-width:2.5em}
td{white-space:nowrap}td:first-child,th:first-child{text-align:left}
figure{margin:1em 0}img{max-width:100%;border:1px solid #eee}figcaption{font-size:90%;color:#444}
pre{background:#f8f8f8;padding:0.6em;overflow:auto}nav a{margin-right:1em}
"""


def _write_html(run: _Run, path: Path) -> None:
    mech = run.mech
    title = html.escape(run.t("report.title", name=mech.name))
    parts = [f"<!DOCTYPE html><html lang='{run.lang}'><head><meta charset='utf-8'><title>{title}</title>"]
    parts.append(f"<style>{STYLE}</style></head><body><h1>{html.escape(mech.name)}</h1>")
    parts.append("<nav>" + "".join(f"<a href='#{s.key}'>{html.escape(s.title)}</a>" for s in run.sections) + "</nav>")
    for s in run.sections:
        parts.append(f"<section id='{s.key}'><h2>{html.escape(s.title)}</h2>")
        parts += s.body
        parts += [_figure_html(run, name) for name in s.figures]
        parts.append("</section>")
    if (run.folder / "animation.gif").exists():
        data = base64.b64encode((run.folder / "animation.gif").read_bytes()).decode()
        img = f"<img alt='{html.escape(run.t('section.animation'))}' src='data:image/gif;base64,{data}'>"
        parts.append(f"<section id='animation'><h2>{html.escape(run.t('section.animation'))}</h2>{img}</section>")
    if mech.structure.warnings:
        warnings = "".join(_p(w) for w in mech.structure.warnings)
        parts.append(f"<section id='warnings'><h2>{html.escape(run.t('section.warnings'))}</h2>{warnings}</section>")
    parts.append("</body></html>")
    path.write_text("".join(parts), encoding="utf-8")


def _figure_html(run: _Run, name: str) -> str:
    png = (run.folder / "figures" / f"{name}.png").read_bytes()
    data = base64.b64encode(png).decode()
    caption = html.escape(run.captions[name])
    return (
        f"<figure id='{html.escape(name)}'><img alt='{caption}' width='{shown_width(png)}' "
        f"src='data:image/png;base64,{data}'>"
        f"<figcaption>{caption}</figcaption></figure>"
    )


def _write_pdf(run: _Run, path: Path) -> None:
    from matplotlib.backends.backend_pdf import PdfPages
    from matplotlib.figure import Figure

    from linkwork.report.pdf import Pages, parts

    with PdfPages(path) as pdf:
        title = Figure(figsize=(8.27, 11.69))
        title.text(0.1, 0.9, run.t("report.title", name=run.mech.name), fontsize=18)
        title.text(0.1, 0.85, run.t("structure.formula", formula=run.mech.structure.formula), fontsize=11)
        pdf.savefig(title)
        pages = Pages()
        for s in run.sections:
            pages.heading(s.title)
            for kind, part in parts(s.body):
                pages.table(part) if kind == "table" else pages.paragraph(part)
        for page in pages.pages:
            pdf.savefig(page)
        for fig in run.figures.values():
            pdf.savefig(fig)
