"""The page assembler: the report's sections and figures written as ``report.html`` (and ``report.pdf``)."""

from __future__ import annotations

import base64
import html
from pathlib import Path

from linkwork.lang import russian_html
from linkwork.report.html import paragraph
from linkwork.report.render import shown_width
from linkwork.report.run import ReportRun

STYLE = """
body{font-family:system-ui,sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;color:#222}
table{border-collapse:collapse;margin:0.6em 0;font-size:90%;display:block;overflow-x:auto;max-width:100%}
td,th{border:1px solid #ccc;padding:2px 8px;text-align:right}th{background:#f3f3f3;min-width:2.5em}
td{white-space:nowrap}td:first-child,th:first-child{text-align:left}
figure{margin:1em 0}img{max-width:100%;border:1px solid #eee}figcaption{font-size:90%;color:#444}
pre{background:#f8f8f8;padding:0.6em;overflow:auto}nav a{margin-right:1em}
"""


def write_html(run: ReportRun, path: Path) -> None:
    mech = run.mech
    title = html.escape(run.t("report.title", name=mech.name))
    parts = [f"<!DOCTYPE html><html lang='{run.lang}'><head><meta charset='utf-8'><title>{title}</title>"]
    parts.append(f"<style>{STYLE}</style></head><body><h1>{html.escape(mech.name)}</h1>")
    parts.append("<nav>" + "".join(f"<a href='#{s.key}'>{html.escape(s.title)}</a>" for s in run.sections) + "</nav>")
    for s in run.sections:
        parts.append(f"<section id='{s.key}'><h2>{html.escape(s.title)}</h2>")
        parts += s.body
        parts += [figure_html(run, name) for name in s.figures]
        parts.append("</section>")
    if (run.folder / "animation.gif").exists():
        data = base64.b64encode((run.folder / "animation.gif").read_bytes()).decode()
        img = f"<img alt='{html.escape(run.t('section.animation'))}' src='data:image/gif;base64,{data}'>"
        parts.append(f"<section id='animation'><h2>{html.escape(run.t('section.animation'))}</h2>{img}</section>")
    if mech.structure.warnings:
        warnings = "".join(paragraph(run.t(key, **dict(fields))) for key, fields in mech.structure.said)
        parts.append(f"<section id='warnings'><h2>{html.escape(run.t('section.warnings'))}</h2>{warnings}</section>")
    parts.append("</body></html>")
    page = "".join(parts)  # in Russian its numbers with decimal commas and powers of ten (lang.russian_html)
    path.write_text(russian_html(page) if run.lang == "ru" else page, encoding="utf-8")


def figure_html(run: ReportRun, name: str) -> str:
    png = (run.folder / "figures" / f"{name}.png").read_bytes()
    data = base64.b64encode(png).decode()
    caption = html.escape(run.captions[name])
    return (
        f"<figure id='{html.escape(name)}'><img alt='{caption}' width='{shown_width(png)}' "
        f"src='data:image/png;base64,{data}'>"
        f"<figcaption>{caption}</figcaption></figure>"
    )


def write_pdf(run: ReportRun, path: Path) -> None:
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
            body = [russian_html("".join(s.body))] if run.lang == "ru" else s.body  # as the HTML page writes it
            for kind, part in parts(body):
                pages.table(part) if kind == "table" else pages.paragraph(part)
        for page in pages.pages:
            pdf.savefig(page)
        for fig in run.figures.values():
            pdf.savefig(fig)
