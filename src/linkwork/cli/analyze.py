"""``linkwork analyze``: the main job."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Annotated

import typer

from linkwork.cli.app import (
    FileOrExample,
    Speed,
    app,
    at_speed,
    check_options,
    compile_or_exit,
    fail,
    names_a_file,
    needs,
)
from linkwork.limits import MAX_ANGLES, TURN_STEPS, digits, quote, whole


@app.command()
def analyze(
    file_or_example: FileOrExample,
    out: Annotated[
        str,
        typer.Option(help="folder for the report, tables, figures and animation: new, empty, or an earlier report"),
    ] = "report",
    steps: Annotated[int, typer.Option(help="equal steps over one turn of the crank")] = TURN_STEPS,
    speed: Speed = None,
    position: Annotated[
        str | None,
        typer.Option(
            help="which of the 12 positions (0 to 11) gets the scheme, the velocity and acceleration plans and "
            "the force analysis, or all (also sheets of the twelve plans), or a crank angle phi from position 0 "
            "with its unit (87deg) for the force analysis; default: the plans at the file's drawing.positions, "
            "else where the working point moves fastest, the force analysis where the driving torque of the "
            "working stroke is largest"
        ),
    ] = None,
    pdf: Annotated[bool, typer.Option("--pdf", help="also write report.pdf")] = False,
    animation: Annotated[bool, typer.Option(help="write animation.gif (and .mp4 with imageio-ffmpeg)")] = True,
    dxf: Annotated[
        bool,
        typer.Option(
            "--dxf",
            help="also write the drawings for CAD, figures/*.dxf, and the drawing sheets to GOST, "
            "figures/sheet_*.dxf and figures/sheets.pdf (needs ezdxf)",
        ),
    ] = False,
    sheet: Annotated[
        str | None,
        typer.Option(help="format of the drawing sheets --dxf writes: A1, A2, A3 or A4 (default: the file's, else A1)"),
    ] = None,
    title_block: Annotated[
        list[str] | None,
        typer.Option(
            help="a field of the sheets' title block, KEY=VALUE, as the file's drawing.title_block has them "
            "(title, designation, organisation, developer, checker, norm_control, approved, date, litera); repeat it"
        ),
    ] = None,
    lang: Annotated[str, typer.Option(help="language of the report and its figures: en or ru")] = "en",
    sizing: Annotated[
        bool | None,
        typer.Option(help="a Sizing section (bearings, pins, links, bolts; default: where the file has sizing:)"),
    ] = None,
) -> None:
    """Every analysis the mechanism supports: tables, figures, animation and report.html."""
    from rich.progress import Progress, SpinnerColumn, TextColumn

    from linkwork.cli.terminal import console
    from linkwork.errors import LinkworkError, MissingDependencyError
    from linkwork.lang import check_lang
    from linkwork.report import analyze as run
    from linkwork.report import require_packages

    check_options(whole(steps, "--steps", 12, MAX_ANGLES, "number of steps over the turn"))
    asked = _position(position)
    try:
        check_lang(lang)
    except LinkworkError as exc:
        fail(exc)
    _check_out(out)
    try:
        require_packages()
    except MissingDependencyError as exc:
        fail(exc)
    if dxf:
        needs("ezdxf", purpose="the drawings for CAD (linkwork analyze --dxf)")
    mech = at_speed(compile_or_exit(file_or_example), speed)
    sheets = _sheets(sheet, title_block or [], dxf)
    # the spinner on stderr, and only in a terminal: piped or redirected, stdout holds the one line "wrote ..."
    shown = console(stderr=True)
    spinner = Progress(
        SpinnerColumn(), TextColumn("{task.description}"), console=shown, transient=True, disable=not shown.is_terminal
    )
    with spinner as bar:
        task = bar.add_task("analysing", total=None)
        try:
            path = run(
                mech,
                out,
                steps=steps,
                position=asked,
                pdf=pdf,
                animation=animation,
                dxf=dxf,
                lang=lang,
                sizing=sizing,
                sheets=sheets,
                progress=lambda what: bar.update(task, description=f"analysing: {what}"),
            )
        except LinkworkError as exc:
            fail(exc)
        except OSError as exc:
            fail(LinkworkError(f"--out {out}: cannot write ({exc.strerror or exc})"))
    typer.echo(f"wrote {path}")


def _check_out(out: str) -> None:
    """Exit code 2 with the reason where ``--out`` is no folder analyze can write its report into."""
    from linkwork.errors import LinkworkError
    from linkwork.report.folder import problem

    why = problem(out)
    if why is None and names_a_file(out):
        why = (
            f"names a {Path(out).suffix} file; analyze writes a folder (report.html, the tables, the figures): "
            f"give a folder, e.g. --out {Path(out).with_suffix('')}"
        )
    if why is not None:
        fail(LinkworkError(f"--out {out}: {why}"))


def _position(text: str | None) -> int | float | str | None:
    """``--position``: one of the 12 positions (int), ``all``, a crank angle φ from position 0 with its unit
    (``87deg``: rad, float, in [0, 2 pi)), or None; exits with one message (exit code 2) for anything else."""
    from linkwork.errors import LinkworkError
    from linkwork.units import parse_quantity

    if text is None or text == "all":
        return text
    if digits(text):
        if 0 <= int(text) < 12:
            return int(text)
    elif any(c.isalpha() for c in text):
        try:
            phi = parse_quantity(text, "angle")
        except (LinkworkError, ValueError):
            phi = math.nan
        if 0 <= phi < 2 * math.pi:
            return float(phi)
    fail(
        LinkworkError(
            f"--position: expected one of the 12 positions, 0 to 11, all, or a crank angle from position 0 "
            f"with its unit, 0 to 360 deg (e.g. 87deg), got {quote(text)}"
        )
    )


def _sheets(sheet: str | None, fields: list[str], dxf: bool) -> dict[str, str]:
    """The format (``sheet``) and the title block's fields given by ``--sheet`` and ``--title-block``, over the
    file's ``drawing:`` section (:func:`linkwork.io.sheet_drawings.sheet_options`); exits with a line for each wrong
    one (exit code 2)."""
    from linkwork.errors import LinkworkError
    from linkwork.spec.schema import TitleBlockSpec

    if sheet is None and not fields:
        return {}
    problems = []
    if not dxf:
        problems.append("--sheet and --title-block: the sheets are written with --dxf; add it")
    if sheet is not None and sheet.upper() not in ("A1", "A2", "A3", "A4"):
        problems.append(f"--sheet: expected A1, A2, A3 or A4, got {quote(sheet)}")
    known = tuple(TitleBlockSpec.model_fields)
    given: dict[str, str] = {}
    for item in fields:
        key, eq, value = item.partition("=")
        if not eq or key.strip() not in known:
            problems.append(f"--title-block: expected KEY=VALUE, KEY one of {', '.join(known)}; got {quote(item)}")
        else:
            given[key.strip()] = value.strip()
    if problems:
        fail(LinkworkError("\n".join(problems)))
    return {**given, **({"sheet": sheet.upper()} if sheet else {})}
