"""The main job: every analysis a mechanism supports, its tables, figures, animation and a report.

The analyses are read from one :class:`linkwork.study.Study`; each section of the page is written by a module of
its own (:mod:`linkwork.report.requirements`, ``structure``, ``kinematics``, ``forces``, ``dynamics``, ``impact``,
``sizing``), the page by :mod:`linkwork.report.page`.

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

from collections.abc import Callable, Mapping
from pathlib import Path
from typing import TYPE_CHECKING

from linkwork.lang import check_lang
from linkwork.limits import TURN_STEPS
from linkwork.optional import require
from linkwork.report.dynamics import dynamics_section, simulate_section
from linkwork.report.forces import forces_section
from linkwork.report.html import Section, paragraph
from linkwork.report.impact import impact_section
from linkwork.report.inputs import input_section
from linkwork.report.kinematics import kinematics_section
from linkwork.report.page import write_html, write_pdf
from linkwork.report.requirements import requirements_section
from linkwork.report.run import ReportRun
from linkwork.report.sizing import asks_sizing, sizing_section
from linkwork.report.structure import structure_section
from linkwork.structure.model import one_crank
from linkwork.study import Study

if TYPE_CHECKING:
    from linkwork.structure.model import Mechanism


def analyze(
    mech: Mechanism,
    out: str | Path,
    *,
    steps: int = TURN_STEPS,
    position: int | float | str | None = None,
    pdf: bool = False,
    animation: bool = True,
    dxf: bool = False,
    lang: str = "en",
    progress: Callable[[str], None] | None = None,
    sizing: bool | None = None,
    sheets: Mapping[str, str] | None = None,
) -> Path:
    """Run every analysis ``mech`` supports and write tables, figures, an animation and
    ``report.html`` (and ``report.pdf``) into the folder ``out``; returns the report's path.

    ``position``: which of the 12 positions (numbered from position 0, the working member's high end,
    as ``linkwork positions`` does) gets the scheme, the velocity and acceleration plans and the force
    analysis; ``"all"`` adds sheets of the plans of all twelve; a float: φ (rad from position 0) of the force
    analysis (its plans drawn there too); default the file's ``drawing.positions``, else where the
    working point moves fastest (:func:`linkwork.scene.positions.plan_positions`), and the force analysis
    where the driving torque of the working stroke is largest (:mod:`linkwork.report.kinetostatic`).  ``dxf``: also the
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
    sheets : mapping, optional
        The sheets' format (``"sheet": "A3"``) and title block fields (``"developer": "..."``) given over the
        file's ``drawing:`` section (:func:`linkwork.io.sheet_drawings.sheet_options`); with ``dxf``.

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
        study = Study(mech, steps)
        run = ReportRun(study, work, progress or (lambda _: None), lang, parallel=PARALLEL and not pdf)
        run.sizing = sizing
        run.sheets = dict(sheets or {})
        try:
            _build(run, position, animation, dxf)
        finally:
            run.beside.stop()
        write_html(run, work / "report.html")
        if pdf:
            write_pdf(run, work / "report.pdf")
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


def _build(run: ReportRun, position: int | float | str | None, animation: bool, dxf: bool = False) -> None:
    """The sections in the page's order, the figures queued as each is written (those of the kinematics drawn
    in the second process while this one goes on)."""
    requirements_section(run)
    run.sections.append(Section("input", run.t("section.input"), input_section(run.mech, run.study.steps, run.t)))
    structure_section(run)
    if not one_crank(run.mech):
        run.sections.append(Section("kinematics", run.t("section.kinematics"), [paragraph(run.t("kin.needs_crank"))]))
        return
    cycle = kinematics_section(run, position, dxf)
    if animation:
        from linkwork import figures

        # first: the longest job, not left for last to one process while the other has nothing to draw
        run.jobs.insert(0, lambda: figures.animate(cycle.kin, run.folder / "animation.gif", lang=run.lang))
    _import_drawing()
    run.run_beside()
    if not run.mech.structure.redundant:
        forces_section(run, cycle)
    if run.mech.motor_gear is not None:
        dynamics_section(run, cycle)
    if run.mech.blow is not None:
        impact_section(run)
    if asks_sizing(run.mech, run.sizing):
        sizing_section(run)
    if run.study.file is not None and run.study.file.simulate is not None:
        simulate_section(run)
    run.progress("figures")
    run.run_here()


def _import_drawing() -> None:
    """Import matplotlib's figure and Agg canvas (a third of a second) once, before the second process forks:
    both processes draw."""
    require("matplotlib.figure", "matplotlib.backends.backend_agg", purpose="the report's figures")
