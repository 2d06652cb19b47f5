"""One self-contained page: the viewer with its script, style and the whole cycle inlined.

The page needs no server and no network: it opens from a file URL, and its
Content-Security-Policy forbids every fetch, so the page cannot reach out
even by mistake.  The file is written atomically.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import TYPE_CHECKING, Any

from linkwork.atomic import write_atomic
from linkwork.web.force_plans import exported_samples
from linkwork.web.session import SCRIPTS, Viewer, page_html, static_text

if TYPE_CHECKING:
    from linkwork.spec.schema import Spec
    from linkwork.structure.model import Mechanism

_CSP = (
    "default-src 'none'; script-src 'unsafe-inline'; style-src 'unsafe-inline'; img-src data:; "
    "base-uri 'none'; form-action 'none'"
)


def render_page(payload: dict[str, Any]) -> str:
    """The viewer's page with ``payload`` (from :func:`~linkwork.web.payload.cycle_payload`) embedded."""
    page = page_html(payload.get("lang", "en"))
    css = static_text("viewer.css")
    scripts = {name: static_text(name) for name in SCRIPTS}
    if "</" in css or any("</script" in js.lower() for js in scripts.values()):
        raise ValueError("the viewer's files cannot be inlined")  # a packaging error, not a user's
    data = json.dumps(payload, allow_nan=False, separators=(",", ":"))
    data = data.replace("<", "\\u003c").replace(">", "\\u003e").replace("&", "\\u0026")
    replace = {
        '<link rel="stylesheet" href="static/viewer.css">': f'<meta http-equiv="Content-Security-Policy" '
        f'content="{_CSP}">\n<style>\n{css}</style>',
        "<!--linkwork-data-->": f'<script type="application/json" id="linkwork-data">{data}</script>',
    }
    for name, js in scripts.items():
        replace[f'<script src="static/{name}"></script>'] = f"<script>\n{js}</script>"
    for old, new in replace.items():
        if page.count(old) != 1:
            raise ValueError(f"the viewer's page lacks {old!r}")
        page = page.replace(old, new)
    return page


def export_page(
    spec_or_mech: Spec | Mechanism | str | Path, path: str | Path, steps: int = 360, lang: str = "en"
) -> Path:
    """Write the viewer of a spec, a compiled mechanism, or a file or example name to one HTML file.

    Parameters
    ----------
    spec_or_mech : Spec, Mechanism or str
        The mechanism: a description, a compiled mechanism, a file's path or an example's name.
    path : str or Path
        The page to write (replaced atomically).
    steps : int
        Crank angles of the precomputed cycle.
    lang : str
        The language of the page (``en`` or ``ru``, :data:`linkwork.lang.LANGUAGES`).

    Returns
    -------
    Path
        ``path``.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from linkwork.web import export_page
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     page = export_page("four-bar", pathlib.Path(tmp) / "four-bar.html", steps=36)
    ...     page.name, page.stat().st_size > 10_000
    ('four-bar.html', True)
    """
    viewer = Viewer(spec_or_mech, steps, placed=None, lang=lang)  # the labels placed at every sample
    payload = dict(viewer.cycle())
    payload["editable"] = False
    # the force plans and the lever at some samples (the live page asks its server for the sample shown)
    payload["force_plans"] = viewer.force_plans_at(exported_samples(viewer.steps))
    text = render_page(payload)
    return write_atomic(path, lambda tmp: tmp.write_text(text, encoding="utf-8"))
