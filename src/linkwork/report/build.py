"""The main job: every analysis a mechanism supports, its tables, figures, animation and a report.

:func:`analyze` writes into a fresh folder beside the output folder and puts
it in place only when everything is written, so an interrupted run never
leaves a half-written report where a good one was; it replaces only a folder
that holds a report and nothing else (:mod:`linkwork.report.folder`).
"""

from __future__ import annotations

import base64
import html
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from linkwork.io.jsonout import dumps
from linkwork.structure.model import PairType


@dataclass
class Section:
    """One section of the report: a title, paragraphs and tables (HTML), figures (names)."""

    key: str
    title: str
    body: list[str] = field(default_factory=list)
    figures: list[str] = field(default_factory=list)


def _table(head: list[str], rows: list[list[Any]]) -> str:
    def cell(x: Any) -> str:
        if isinstance(x, float):
            return "-" if not math.isfinite(x) else f"{x:.6g}"
        return html.escape(str(x))

    out = ["<table><thead><tr>" + "".join(f"<th>{html.escape(h)}</th>" for h in head) + "</tr></thead><tbody>"]
    out += ["<tr>" + "".join(f"<td>{cell(x)}</td>" for x in row) + "</tr>" for row in rows]
    return "".join(out) + "</tbody></table>"


def _p(text: str) -> str:
    return f"<p>{html.escape(text)}</p>"


class _Run:
    def __init__(self, mech: Any, folder: Path, progress: Callable[[str], None]) -> None:
        self.mech = mech
        self.folder = folder
        self.progress = progress
        self.sections: list[Section] = []
        self.figures: dict[str, Any] = {}
        (folder / "figures").mkdir(parents=True)

    def figure(self, name: str, fig: Any) -> str:
        fig.savefig(self.folder / "figures" / f"{name}.svg")
        fig.savefig(self.folder / "figures" / f"{name}.png", dpi=90)
        self.figures[name] = fig
        return name


def analyze(
    mech: Any,
    out: str | Path,
    *,
    steps: int = 360,
    position: int | str | None = None,
    pdf: bool = False,
    animation: bool = True,
    dxf: bool = False,
    progress: Callable[[str], None] | None = None,
) -> Path:
    """Run every analysis ``mech`` supports and write tables, figures, an animation and
    ``report.html`` (and ``report.pdf``) into the folder ``out``; returns the report's path.

    ``position``: which of the 12 positions (numbered from the working slider's or rocker's high
    end, as ``linkwork positions`` does) gets the scheme and the velocity and acceleration plans;
    ``"all"`` adds sheets of the plans of all twelve; default the file's ``drawing.positions``, else
    where the working point moves fastest (:func:`linkwork.scene.positions.plan_positions`).  ``dxf``:
    also the drawings for CAD, ``figures/*.dxf`` (needs ezdxf).  Needs matplotlib and xarray
    (:func:`require_packages`).

    Raises
    ------
    LinkworkError
        ``out`` is something other than a report folder, an empty folder or a new name: a folder of
        other files, a file, a symbolic link, a device (see :func:`linkwork.report.folder.problem`).
    """
    from linkwork.report.folder import replacing

    require_packages()
    with replacing(out) as work:
        run = _Run(mech, work, progress or (lambda _: None))
        _build(run, steps, position, animation, dxf)
        _write_html(run, work / "report.html")
        if pdf:
            _write_pdf(run, work / "report.pdf")
    return Path(out) / "report.html"


def require_packages() -> None:
    """Raise :class:`~linkwork.errors.MissingDependencyError` unless the optional packages of the
    report are installed: matplotlib (the figures) and xarray (``kinematics.nc``)."""
    from linkwork.optional import require

    require("matplotlib", "xarray", purpose="the report (linkwork analyze)")


def _build(run: _Run, steps: int, position: int | str | None, animation: bool, dxf: bool = False) -> None:
    from linkwork import figures
    from linkwork.io.motion_tables import write_csv, write_netcdf
    from linkwork.motion import kinematics
    from linkwork.motion.analysis import extremes, transmission_angles, zero_angle
    from linkwork.structure.model import one_crank, point_labels

    mech = run.mech
    s = mech.structure
    run.progress("structure")
    sec = Section("structure", "Structure")
    sec.body.append(
        _p(
            f"Moving links n = {s.n_links}, lower pairs p5 = {s.p5}, higher pairs p4 = {s.p4}: "
            f"W = 3n - 2p5 - p4 = {s.dof}; redundant constraints q = {s.redundant}, mobility {s.mobility}."
        )
    )
    sec.body.append(
        _table(
            ["#", "group", "kind", "links", "joints"],
            [
                [i, g.label.split(" ")[0], g.kind, ", ".join(g.link_names), ", ".join(g.joints)]
                for i, g in enumerate(s.groups, 1)
            ],
        )  # fmt: skip
    )
    sec.body.append(_p(f"Structural formula: {s.formula}"))
    run.sections.append(sec)

    if not one_crank(mech):
        run.sections.append(Section("kinematics", "Kinematics", [_p("Needs one crank (a revolute drive).")]))
        return
    run.progress("kinematics")
    kin = kinematics(mech, steps=steps)
    write_csv(kin, run.folder / "kinematics.csv")
    write_netcdf(kin, run.folder / "kinematics.nc")
    sec = Section("kinematics", "Kinematics")
    zero = zero_angle(mech)
    sign = 1.0 if mech.drive_speed[0] >= 0 else -1.0
    twelve = zero + sign * 2 * np.pi * np.arange(12) / 12
    kin12 = kinematics(mech, twelve)
    labels = point_labels(mech)
    rows = []
    for k in range(12):
        row: list[Any] = [k, f"{math.degrees(twelve[k]) % 360:.1f}"]
        for _, p in labels:
            x = kin12.position(mech.point_names[p])[k] * 1000
            row.append("-" if not np.isfinite(x).all() else f"{x[0]:.1f}, {x[1]:.1f}")
        rows.append(row)
    sec.body.append(_p("The 12 positions (coordinates in mm), position 0 at the working slider's high end:"))
    sec.body.append(_table(["pos", "crank, deg", *[label for label, _ in labels]], rows))
    ext = extremes(kin)
    if ext:
        sec.body.append(_table(["", "stroke", "from", "to", "time ratio K", "+ stroke / other"], _extreme_rows(ext)))
        sec.body.append(
            _p(
                "Sliders in mm along their guide's axis, rockers in degrees.  Time ratio K: the longer stroke's "
                "time over the shorter's at uniform crank speed; + stroke / other: the time of the stroke in the + "
                "direction of the guide's axis (the rocker turning counter-clockwise) over the other's."
            )
        )
    mu = [(lab, float(np.nanmin(v))) for lab, v in transmission_angles(kin).items() if np.isfinite(v).any()]
    if mu:
        sec.body.append(_table(["transmission angle", "least, deg"], [[lab, math.degrees(v)] for lab, v in mu]))
    for e in kin.events:
        sec.body.append(_p(f"{e.kind}: {e.message}"))
    sec.figures += _drawings(run, kin, kin12, position, dxf)
    sec.figures.append(run.figure("link_angles", figures.link_angles(kin)))
    moving = [p for _, p in labels if mech.point_link[p] != 0]
    if moving:
        sec.figures.append(run.figure("motion", figures.motion_diagram(kin, mech.point_names[moving[-1]])))
    run.sections.append(sec)
    if animation:
        run.progress("animation")
        figures.animate(kin, run.folder / "animation.gif")

    if not mech.structure.redundant:
        _forces(run, steps)
    if mech.machine is not None:
        _dynamics(run)
    if mech.blow is not None:
        _impact(run)


def _drawings(run: _Run, kin: Any, kin12: Any, position: int | str | None, dxf: bool) -> list[str]:
    """The scheme, the plan of positions and the plans at the positions drawn (the first one's named
    ``velocity_plan``, the others' ``velocity_plan_9``...), the sheets of all twelve plans for ``"all"``,
    and (``dxf``) the drawings for CAD."""
    from linkwork import figures
    from linkwork.scene.positions import plan_positions

    drawn = plan_positions(run.mech, kin12) if position in (None, "all") else [int(position)]
    first = drawn[0]
    names = [
        run.figure("scheme", figures.draw_scheme(kin12, first, position=first, cycle=kin)),
        run.figure("positions", figures.draw_positions(kin)),
    ]
    for k in drawn:
        tail = "" if k == first else f"_{k}"
        names.append(run.figure(f"velocity_plan{tail}", figures.velocity_plan(kin12, k, position=k)))
        names.append(run.figure(f"acceleration_plan{tail}", figures.acceleration_plan(kin12, k, position=k)))
    if position == "all":
        names += [run.figure(f"{kind}_plans", figures.plan_sheet(kin12, kind)) for kind in ("velocity", "acceleration")]
    if dxf:
        from linkwork.io.dxf import write_drawings

        write_drawings(kin12, first, run.folder / "figures", cycle=kin)
    return names


def _extreme_rows(ext: list[Any]) -> list[list[Any]]:
    """Rows of the strokes' table: sliders in mm, rockers in degrees."""
    rows = []
    for e in ext:
        scale, unit = (1000.0, "mm") if e.kind == "slider" else (180 / math.pi, "deg")
        cells = [f"{x * scale:.6g} {unit}" if math.isfinite(x) else "-" for x in (e.stroke, e.low, e.high)]
        rows.append([f"{e.kind} {e.name}", *cells, e.time_ratio, e.forward_time_ratio])
    return rows


def _forces(run: _Run, steps: int) -> None:
    from linkwork import figures
    from linkwork.io.force_tables import groups, pair_labels, to_json, write_csv
    from linkwork.kinetostatics import forces

    mech = run.mech
    run.progress("forces")
    f = forces(mech, steps=steps)
    write_csv(f, run.folder / "forces.csv")
    (run.folder / "forces.json").write_text(dumps(to_json(f)), encoding="utf-8")
    sec = Section("forces", "Forces (kinetostatics)")
    phi = f.angles
    ok = np.isfinite(f.driving_torque)
    if ok.any():
        i = int(np.nanargmax(np.abs(f.driving_torque)))
        at = math.degrees(phi[i]) % 360
        sec.body.append(_p(f"Driving torque: peak {f.driving_torque[i]:.6g} N m at {at:.1f} deg."))
    rows = []
    for label, k in pair_labels(mech):
        size = np.hypot(*f.pair_force(k)[0].T)
        if np.isfinite(size).any():
            j = int(np.nanargmax(size))
            a, b = (mech.link_names[int(x)] for x in mech.pair_members[k])
            rows.append([label, f"{a} on {b}", float(size[j]), f"{math.degrees(phi[j]) % 360:.1f}"])
    sec.body.append(_table(["joint", "first on second", "largest force, N", "at, deg"], rows))
    b = f.bolts()
    sec.body.append(
        _table(
            ["foundation", "largest", "at, deg"],
            [
                ["horizontal force (bolt shear), N", b.shear, f"{math.degrees(b.shear_angle) % 360:.1f}"],
                ["pull on the bolts, N", b.pull, f"{math.degrees(b.pull_angle) % 360:.1f}"],
                ["push on the foundation, N", b.push, f"{math.degrees(b.push_angle) % 360:.1f}"],
                ["moment about the origin, N m", b.moment, f"{math.degrees(b.moment_angle) % 360:.1f}"],
            ],
        )  # fmt: skip
    )
    checks = [[k.replace("_", " "), v] for k, v in f.checks.items()]
    checks += [[f"free body {g['group']}", g["residual"]] for g in groups(f)]
    sec.body.append(_p("Cross-checks (relative discrepancy of the independent methods):"))
    sec.body.append(_table(["check", "discrepancy"], checks))
    sec.figures.append(run.figure("driving_torque", figures.torque_diagram(f)))
    sec.figures.append(run.figure("foundation", figures.foundation_diagram(f)))
    for k in range(mech.n_pairs):
        if mech.pair_links[k, 0] == 0 and mech.pair_type[k] == PairType.REVOLUTE:
            sec.figures.append(run.figure(f"hodograph_{mech.pair_joint[k]}", figures.hodograph(f, mech.pair_joint[k])))
    run.sections.append(sec)


def _dynamics(run: _Run) -> None:
    from linkwork import figures
    from linkwork.io.dynamics_tables import to_json
    from linkwork.machine import dynamics

    mech = run.mech
    run.progress("dynamics")
    result = dynamics(mech, steps=1440)
    data = to_json(mech, result)
    (run.folder / "dynamics.json").write_text(dumps(data), encoding="utf-8")
    rpm = 30 / math.pi
    last = result.motion.last
    sec = Section("dynamics", "Machine dynamics")
    rows = [
        ["mean crank speed, rpm", last.omega_mean * rpm],
        ["least and largest crank speed, rpm", f"{last.omega_min * rpm:.4g} to {last.omega_max * rpm:.4g}"],
        ["coefficient of speed fluctuation", last.delta],
        ["mean power of the drive on the crank, W", result.drive_power],
        ["mean power of the motor at its shaft, W", result.mean_power],
        ["start-up time, s", result.startup_time],
        ["flywheel, kg m^2 (on the " + result.drive.flywheel_on + " shaft)", result.drive.flywheel],
    ]
    sec.body.append(_table(["quantity", "value"], rows))
    sec.figures.append(run.figure("dynamics", figures.dynamics_diagrams(result)))
    run.sections.append(sec)


def _impact(run: _Run) -> None:
    from linkwork.impulse import impact

    mech = run.mech
    blow = mech.blow
    run.progress("impact")
    r = impact(mech)
    sec = Section("impact", "Impact")
    rows = [[f"impulse on {blow.at}", f"({r.impulse[0]:.6g}, {r.impulse[1]:.6g}) N s"]]
    rows += [[f"joint {j}", f"({v[0]:.6g}, {v[1]:.6g}) N s"] for j, v in r.joints.items()]
    rows += [["energy lost, J", r.energy_loss]]
    if r.ideal_com is not None:
        rows.append(["ideal centre of mass", f"({r.ideal_com[0]:.6g}, {r.ideal_com[1]:.6g}) m"])
    sec.body.append(_table(["", "value"], rows))
    if mech.machine is not None and blow.tool is not None:
        _impact_cycle(sec, mech)
    run.sections.append(sec)


def _impact_cycle(sec: Section, mech: Any) -> None:
    """The working cycle with the file's drive and tool: the steady cycle's blow and phases."""
    from linkwork.errors import LinkworkError
    from linkwork.impulse import simulate_blows

    try:
        c = simulate_blows(mech)
    except LinkworkError as exc:
        sec.body.append(_p(f"Working cycle: {exc}"))
        return
    b = c.last
    sec.body.append(_p(f"Working cycle with the drive and the tool: {c.blows_per_minute:.6g} blows per minute."))
    rows = [
        ["impact speed of the striker, m/s", b.impact_speed],
        ["crank speed before / after, rad/s", f"{b.crank_speed_before:.6g} / {b.crank_speed_after:.6g}"],
        ["energy lost in the blow / given to the tool, J", f"{b.energy_lost:.6g} / {b.energy_to_tool:.6g}"],
        [f"impulse on {mech.blow.at}", f"({b.impulse[0]:.6g}, {b.impulse[1]:.6g}) N s"],
    ]
    rows += [[f"joint {j}", f"({v[0]:.6g}, {v[1]:.6g}) N s"] for j, v in b.joints.items()]
    rows += [["work on the work per cycle, J", b.work_on_work], ["mean motor power, W", c.mean_power]]
    sec.body.append(_table(["blow of the steady cycle", "value"], rows))
    phases = [[p.kind, p.freedom, 1000 * (p.start - b.time), 1000 * p.duration] for p in c.cycle_phases()]
    sec.body.append(_table(["phase", "W", "from the blow, ms", "lasts, ms"], phases))


STYLE = """
body{font-family:system-ui,sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;color:#222}
table{border-collapse:collapse;margin:0.6em 0;font-size:90%}
td,th{border:1px solid #ccc;padding:2px 8px;text-align:right}th{background:#f3f3f3}
img{max-width:100%;border:1px solid #eee;margin:0.4em 0}
pre{background:#f8f8f8;padding:0.6em;overflow:auto}nav a{margin-right:1em}
"""


def _write_html(run: _Run, path: Path) -> None:
    mech = run.mech
    title = f"{html.escape(mech.name)}: linkwork report"
    parts = [f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>{title}</title>"]
    parts.append(f"<style>{STYLE}</style></head><body><h1>{html.escape(mech.name)}</h1>")
    parts.append("<nav>" + "".join(f"<a href='#{s.key}'>{html.escape(s.title)}</a>" for s in run.sections) + "</nav>")
    if mech.source and Path(mech.source).exists():
        text = Path(mech.source).read_text(encoding="utf-8")
        parts.append(f"<section id='input'><h2>Input</h2><pre>{html.escape(text)}</pre></section>")
    for s in run.sections:
        parts.append(f"<section id='{s.key}'><h2>{html.escape(s.title)}</h2>")
        parts += s.body
        for name in s.figures:
            data = base64.b64encode((run.folder / "figures" / f"{name}.png").read_bytes()).decode()
            parts.append(f"<figure><img alt='{html.escape(name)}' src='data:image/png;base64,{data}'></figure>")
        parts.append("</section>")
    if (run.folder / "animation.gif").exists():
        data = base64.b64encode((run.folder / "animation.gif").read_bytes()).decode()
        img = f"<img alt='animation' src='data:image/gif;base64,{data}'>"
        parts.append(f"<section id='animation'><h2>Animation</h2>{img}</section>")
    if mech.structure.warnings:
        warnings = "".join(_p(w) for w in mech.structure.warnings)
        parts.append(f"<section id='warnings'><h2>Warnings</h2>{warnings}</section>")
    parts.append("</body></html>")
    path.write_text("".join(parts), encoding="utf-8")


def _write_pdf(run: _Run, path: Path) -> None:
    from matplotlib.backends.backend_pdf import PdfPages
    from matplotlib.figure import Figure

    with PdfPages(path) as pdf:
        title = Figure(figsize=(8.27, 11.69))
        title.text(0.1, 0.9, f"{run.mech.name}: linkwork report", fontsize=18)
        title.text(0.1, 0.85, f"structural formula {run.mech.structure.formula}", fontsize=11)
        pdf.savefig(title)
        for fig in run.figures.values():
            pdf.savefig(fig)
