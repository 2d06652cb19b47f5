"""``linkwork analyze``: the main job."""

from __future__ import annotations

from typing import Annotated

import typer

from linkwork.cli.app import FileOrExample, _compile, app, fail


@app.command()
def analyze(
    file_or_example: FileOrExample,
    out: Annotated[
        str,
        typer.Option(help="folder for the report, tables, figures and animation: new, empty, or an earlier report"),
    ] = "report",
    steps: Annotated[int, typer.Option(help="equal steps over one turn of the crank")] = 360,
    position: Annotated[
        int, typer.Option(help="which of the 12 positions (0 to 11) gets the velocity and acceleration plans")
    ] = 0,
    pdf: Annotated[bool, typer.Option("--pdf", help="also write report.pdf")] = False,
    animation: Annotated[bool, typer.Option(help="write animation.gif (and .mp4 with ffmpeg)")] = True,
    lang: Annotated[str, typer.Option(help="language of the report and its figures: en or ru")] = "en",
) -> None:
    """Every analysis the mechanism supports: tables, figures, animation and report.html."""
    from rich.progress import Progress, SpinnerColumn, TextColumn

    from linkwork.errors import LinkworkError, MissingDependencyError
    from linkwork.lang import check_lang
    from linkwork.report import analyze as run
    from linkwork.report import require_packages

    if steps < 12:
        fail(LinkworkError(f"--steps: expected at least 12 steps over the turn, got {steps}"))
    if not 0 <= position < 12:
        fail(LinkworkError(f"--position: expected one of the 12 positions, 0 to 11, got {position}"))
    try:
        check_lang(lang)
    except LinkworkError as exc:
        fail(exc)
    from linkwork.report.folder import problem

    why = problem(out)
    if why is not None:
        fail(LinkworkError(f"--out {out}: {why}"))
    try:
        require_packages()
    except MissingDependencyError as exc:
        fail(exc)
    mech = _compile(file_or_example)
    with Progress(SpinnerColumn(), TextColumn("{task.description}"), transient=True) as bar:
        task = bar.add_task("analysing", total=None)
        try:
            path = run(
                mech, out, steps=steps, position=position, pdf=pdf, animation=animation, lang=lang,
                progress=lambda what: bar.update(task, description=f"analysing: {what}"),
            )  # fmt: skip
        except LinkworkError as exc:
            fail(exc)
        except OSError as exc:
            fail(LinkworkError(f"--out {out}: cannot write ({exc.strerror or exc})"))
    typer.echo(f"wrote {path}")
