"""Pages of the reference generated when the site is built: the command line from the application itself,
the file format from the JSON Schema that ``linkwork schema`` prints, and one page of the Python API for
every public name of ``linkwork`` (``linkwork.__all__``), rendered from its docstring by mkdocstrings.

typer carries its own copy of click, whose commands mkdocs-click does not recognise; the command line is
read here through click's own interface instead (the same help texts and options ``--help`` prints).
"""

from __future__ import annotations

import functools
import inspect
import json
import re
from typing import Any

import mkdocs_gen_files


def _cell(text: Any) -> str:
    return " ".join(str(text).split()).replace("|", "\\|")


def cli_page() -> str:
    """Every command of ``linkwork``: its help, usage and options, as ``linkwork COMMAND --help`` gives them."""
    import typer
    from typer import _click as click  # typer's own copy of click: its commands are of these classes

    from linkwork.cli.main import app

    group = typer.main.get_command(app)
    root = click.Context(group, info_name="linkwork")
    out = [
        "# Command line",
        "",
        "Generated from the application when the manual is built: every command and",
        "every option, as `linkwork COMMAND --help` prints them.",
        "",
    ]
    out += ["| command | what it does |", "|---|---|"]
    for name, cmd in group.commands.items():
        summary = (cmd.help or "").strip().split("\n\n")[0]
        out.append(f"| [`{name}`](#linkwork-{name}) | {_cell(summary)} |")
    for name, cmd in group.commands.items():
        ctx = click.Context(cmd, info_name=name, parent=root)
        pieces = [re.sub(r"^\{(.*)\}$", lambda m: m.group(1).upper(), s) for s in cmd.collect_usage_pieces(ctx)]
        usage = " ".join(["linkwork", name, *pieces])
        out += ["", f"## linkwork {name}", "", "```", usage, "```", "", (cmd.help or "").strip(), ""]
        rows = [p.get_help_record(ctx) for p in cmd.get_params(ctx)]
        rows = [r for r in rows if r is not None]
        if rows:
            out += ["| argument or option | meaning |", "|---|---|"]
            out += [f"| `{_cell(opt)}` | {_cell(text)} |" for opt, text in rows]
    return "\n".join(out) + "\n"


def _type(schema: dict[str, Any]) -> str:
    """A property's type in words: references by the name of their definition, unions with "or"."""
    if "$ref" in schema:
        name = schema["$ref"].rsplit("/", 1)[-1]
        return f"[{name}](#{name.lower()})"
    if "anyOf" in schema:
        kinds = [_type(s) for s in schema["anyOf"] if s.get("type") != "null"]
        return " or ".join(dict.fromkeys(kinds))
    kind = schema.get("type", "any")
    if kind == "array":
        return f"list of {_type(schema.get('items', {}))}"
    if kind == "object" and "additionalProperties" in schema and isinstance(schema["additionalProperties"], dict):
        return f"mapping of name to {_type(schema['additionalProperties'])}"
    if "enum" in schema:
        return " or ".join(f"`{v}`" for v in schema["enum"])
    if "const" in schema:
        return f"`{schema['const']}`"
    return str(kind)


def _description(schema: dict[str, Any]) -> str:
    text = schema.get("description", "")
    if not text and "anyOf" in schema:
        text = next((s.get("description", "") for s in schema["anyOf"] if s.get("description")), "")
    return text


def _table(schema: dict[str, Any]) -> list[str]:
    required = set(schema.get("required", []))
    rows = ["| key | type | default | meaning |", "|---|---|---|---|"]
    for key, prop in schema.get("properties", {}).items():
        default = json.dumps(prop["default"]) if prop.get("default") is not None else ""
        default = "required" if key in required else default
        rows.append(f"| `{key}` | {_cell(_type(prop))} | {_cell(default)} | {_cell(_description(prop))} |")
    return rows


def schema_page() -> str:
    """The file format: the top level and every definition of the JSON Schema, a table of keys each."""
    from linkwork.spec.schema import Spec

    schema = Spec.model_json_schema()
    out = [
        "# File format (JSON Schema)",
        "",
        "Generated from the JSON Schema that `linkwork schema` prints (for your editor: save it and point",
        "the YAML language server at it).  [The mechanism file](file-format.md) says the same in prose,",
        "with an example.",
        "",
        "## The file",
        "",
        _cell(schema.get("description", "")),
        "",
        *_table(schema),
    ]
    for name, sub in schema.get("$defs", {}).items():
        out += ["", f"## {name}", "", sub.get("description", "").strip(), ""]
        if "properties" in sub:
            out += _table(sub)
        else:
            out.append(f"Type: {_cell(_type(sub))}.")
    return "\n".join(out) + "\n"


#: The Python reference by task: (title, what the group is for, its entries).  An entry is a public name of
#: ``linkwork`` (``lw.NAME``, a page of its own) or the dotted path of another public object (``linkwork.web.serve``),
#: or ``(label, page)`` for an entry that points to another group's page.
GROUPS: list[tuple[str, str, list[str | tuple[str, str]]]] = [
    (
        "Load and build",
        "Read a mechanism from a file, a bundled example or Python, and compile it.",
        [
            "load",
            "loads",
            "from_dict",
            "example",
            "Spec",
            "MechanismBuilder",
            "compile",
            "Mechanism",
            "Structure",
            "AssurGroup",
            "parameters",
        ],
    ),
    (
        "Analyse",
        "Kinematics, forces, machine dynamics and impact of a compiled mechanism.",
        [
            "kinematics",
            "Kinematics",
            "forces",
            "forces_of",
            "Forces",
            "bolt_speed",
            "balance",
            "reduced",
            "dynamics",
            "simulate",
            "rocker_impact",
            "impact",
            "simulate_blows",
        ],
    ),
    (
        "Design and synthesise",
        "Find dimensions from requirements, sweep variants, optimise.",
        ["synthesize", "sweep", "optimize"],
    ),
    ("Size", "Sections, pins, bearings, motor and flywheel from the forces.", ["size"]),
    (
        "Draw and report",
        "Figures of the results (matplotlib) and the whole report folder.",
        ["linkwork.report.analyze", "linkwork.figures"],
    ),
    (
        "Viewer",
        "The interactive page in a browser: served live, or written to one file.",
        ["linkwork.web.export_page", "linkwork.web.create_app", "linkwork.web.serve"],
    ),
    (
        "Design on Dask",
        "A sweep's chunks on a local or a running Dask cluster: the `workers` and `scheduler` of "
        "[`lw.sweep`](sweep.md); [Sweeps on a Dask cluster](../../how-to/dask.md) shows them at work.",
        [("lw.sweep(..., workers=N)", "sweep.md"), ("lw.sweep(..., scheduler=ADDRESS)", "sweep.md")],
    ),
]


#: Where the objects that a package loads when first used (its ``__getattr__``, which the pages' reader cannot
#: follow) are defined.
DEFINED = {
    "linkwork.web.export_page": "linkwork.web.export.export_page",
    "linkwork.web.create_app": "linkwork.web.server.create_app",
    "linkwork.web.serve": "linkwork.web.server.serve",
}


#: What a page says before its docstring.
NOTES = {
    "Spec": "Its parameters are the keys of a mechanism file ([the file format](../schema.md) gives every key "
    "of the sections below it); [`lw.load`](load.md) reads one from a file, [`lw.MechanismBuilder`]"
    "(MechanismBuilder-class.md) builds one in Python.\n\n",
}


def _page_name(entry: str) -> str:
    """The page of an entry: ``forces.md`` for ``lw.forces``, ``Forces-class.md`` for the class ``lw.Forces``
    (``Forces.md`` and ``forces.md`` are one file on the file systems of macOS and Windows), ``analyze.md`` for
    ``linkwork.report.analyze``, ``figures.md`` for the module ``linkwork.figures``."""
    name = entry.rsplit(".", 1)[-1]
    return f"{name}-class.md" if name[:1].isupper() else f"{name}.md"


def _entry_page(entry: str) -> tuple[str, str, str]:
    """(label, dotted path of the documented object, page text) of one entry."""

    import linkwork

    if "." not in entry:
        obj = getattr(linkwork, entry)
        target = inspect.unwrap(obj)  # lw.kinematics and the other analyses wrap their stage's function
        path = f"{target.__module__}.{target.__qualname__}"
        note = NOTES.get(entry, "")
        if target is not obj:
            note = (
                f"`lw.{entry}` takes its mechanism as a file's path, a bundled example's name, a `Spec` or a "
                f"compiled `Mechanism` (see [Use linkwork from Python](../../how-to/python.md)) in place of the "
                f"compiled mechanism of the signature below, and passes it on to `{path}`.\n\n"
            )
        return f"lw.{entry}", path, f"# lw.{entry}\n\n{note}::: {path}\n"
    if entry == "linkwork.figures":  # a module: its functions, each with its signature
        body = f"::: {entry}\n    options:\n      show_root_heading: false\n      members_order: alphabetical\n"
        return entry, entry, f"# {entry}\n\n{body}"
    path = DEFINED.get(entry, entry)
    return entry, path, f"# {entry}\n\n::: {path}\n"


@functools.cache
def _package() -> Any:
    """The package as griffe reads it from the source, as the pages are (the viewer's server needs no FastAPI to
    be listed); loaded once for the whole index (each load parses every module: 6 s)."""
    import griffe

    return griffe.load("linkwork", search_paths=["src"], resolve_aliases=True)


def _summary(path: str) -> str:
    """The first sentence of the docstring of the object at ``path``, read from the source (:func:`_package`)."""
    obj = _package()[path.removeprefix("linkwork.")]
    text = " ".join((obj.docstring.value if obj.docstring else "").split("\n\n")[0].split())
    first = re.split(r"(?<=[.:;])\s", text, maxsplit=1)[0].rstrip(":;")
    first = first if first.endswith(".") else first + "."
    return _cell(re.sub(r":\w+:`~?([^`]+)`", r"`\1`", first))


def api_pages() -> dict[str, str]:
    """The Python reference: an index by task and a page per entry of :data:`GROUPS`, rendered from the
    docstring of the object it names (with its signature), and its navigation (``reference/api/SUMMARY.md``)."""
    import linkwork

    pages: dict[str, str] = {}
    index = [
        "# Python API",
        "",
        "Every public function and class of `linkwork` (`import linkwork as lw`), by task; each on a page",
        "of its own, generated from its docstring: signature, parameters with their units, what it returns",
        "and raises, and an example (the examples run with the tests).  The names are loaded when first",
        "used, so `import linkwork` costs nothing.",
        "",
    ]
    nav = ["* [Python API](index.md)"]
    for title, about, entries in GROUPS:
        index += [f"## {title}", "", about, "", "| name | what it does |", "|---|---|"]
        if any(isinstance(entry, str) for entry in entries):  # a section of pages in the navigation
            nav.append(f"* {title}")
        for entry in entries:
            if isinstance(entry, tuple):
                label, page = entry
                index.append(f"| [`{label}`]({page}) | see [`lw.sweep`]({page}) |")
                continue
            label, path, text = _entry_page(entry)
            page = _page_name(entry)
            pages[f"reference/api/{page}"] = text
            index.append(f"| [`{label}`]({page}) | {_summary(path)} |")
            nav.append(f"    * [{label}]({page})")
        index.append("")
    index.append(f"`lw.__version__` is `{linkwork.__version__}`.")
    pages["reference/api/index.md"] = "\n".join(index) + "\n"
    pages["reference/api/SUMMARY.md"] = "\n".join(nav) + "\n"
    return pages


with mkdocs_gen_files.open("reference/cli.md", "w") as f:
    f.write(cli_page())
with mkdocs_gen_files.open("reference/schema.md", "w") as f:
    f.write(schema_page())
for path, text in api_pages().items():
    with mkdocs_gen_files.open(path, "w") as f:
        f.write(text)
