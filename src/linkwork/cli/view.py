"""``linkwork view``: the interactive viewer in the browser, or one exported page."""

from __future__ import annotations

from typing import Annotated

import typer

from linkwork.cli.app import FileOrExample, app, fail, needs
from linkwork.limits import QUOTE_PATH, excerpt


@app.command()
def view(
    file_or_example: FileOrExample,
    port: Annotated[int, typer.Option("--port", min=0, max=65535, help="port on 127.0.0.1; 0 picks a free one")] = 8765,
    no_browser: Annotated[bool, typer.Option("--no-browser", help="do not open a browser; just print the URL")] = False,
    export: Annotated[
        str | None, typer.Option("--export", metavar="PAGE.html", help="write one self-contained page and exit")
    ] = None,
    steps: Annotated[int, typer.Option("--steps", min=12, max=1440, help="crank angles of the cycle")] = 360,
    lang: Annotated[str, typer.Option(help="language of the page: en or ru")] = "en",
) -> None:
    """Show the mechanism in the browser: crank slider, plans, charts, structure, edits.

    The server listens on 127.0.0.1 only; stop it with Ctrl-C.  With --export the whole cycle is
    precomputed into one HTML file that works offline, without a server.
    """
    from linkwork.errors import LinkworkError
    from linkwork.examples import resolve
    from linkwork.lang import check_lang

    try:
        check_lang(lang)
    except LinkworkError as exc:
        fail(exc)
    if export is None:
        needs("fastapi", "uvicorn", purpose="the viewer's server (linkwork view)")
    try:
        spec = resolve(file_or_example)
        if export is not None:
            from pathlib import Path

            from linkwork.web.export import export_page

            if not export.strip():
                fail(LinkworkError("--export: give the name of the page to write, e.g. --export shears.html"))
            shown = excerpt(export, QUOTE_PATH)
            try:
                if Path(export).is_dir():
                    fail(LinkworkError(f"--export {shown}: is a directory; give the name of the page to write"))
                written = export_page(spec, export, steps=steps, lang=lang)
            except OSError as exc:
                fail(LinkworkError(f"--export {shown}: cannot write ({exc.strerror or exc})"))
            typer.echo(f"wrote {written}")
            return
        from linkwork.web.server import create_app, serve

        app_ = create_app(spec, steps=steps, lang=lang)
    except LinkworkError as exc:
        fail(exc)

    def ready(url: str) -> None:
        typer.echo(f"linkwork viewer at {url}  (Ctrl-C stops it)")
        if not no_browser:
            import webbrowser

            webbrowser.open(url)

    try:
        serve(app_, port, ready)
    except LinkworkError as exc:
        fail(exc)
    except KeyboardInterrupt:
        pass
