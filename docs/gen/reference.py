"""Pages of the reference generated when the site is built: the command line from the application itself,
the file format from the JSON Schema that ``linkwork schema`` prints, and one page of the Python API for
every public name of ``linkwork`` (``linkwork.__all__``), rendered from its docstring by mkdocstrings.

typer carries its own copy of click, whose commands mkdocs-click does not recognise; the command line is
read here through click's own interface instead (the same help texts and options ``--help`` prints).
"""

from __future__ import annotations

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


def api_pages() -> dict[str, str]:
    """One page per public name of ``linkwork`` (``lw.NAME``), from the docstring of the object it names."""
    import linkwork

    pages: dict[str, str] = {}
    index = [
        "# Python API",
        "",
        "Every public name of `linkwork` (`import linkwork as lw`), each on a page of its",
        "own generated from its docstring.  The names are loaded when first used, so `import linkwork`",
        "costs nothing.",
        "",
        "| name | defined in |",
        "|---|---|",
    ]
    for name in linkwork.__all__:
        if name == "__version__":
            continue
        obj = getattr(linkwork, name)
        target = inspect.unwrap(obj)  # lw.kinematics and the other analyses wrap their stage's function
        path = f"{target.__module__}.{target.__qualname__}"
        index.append(f"| [`lw.{name}`]({name}.md) | `{path}` |")
        note = ""
        if target is not obj:
            note = (
                f"`lw.{name}` takes its mechanism as a file's path, a bundled example's name, a `Spec` or a "
                f"compiled `Mechanism` (see [Use linkwork from Python](../../how-to/python.md)), and passes it "
                f"on to `{path}`:\n\n"
            )
        options = "    options:\n      show_root_heading: false\n"
        pages[f"reference/api/{name}.md"] = f"# lw.{name}\n\n{note}::: {path}\n{options}"
    index += [
        "",
        f"`lw.__version__` is `{linkwork.__version__}`.",
        "",
        "The figures (matplotlib) are functions of the results in [`linkwork.figures`](figures.md).",
    ]
    pages["reference/api/index.md"] = "\n".join(index) + "\n"
    pages["reference/api/figures.md"] = "# linkwork.figures\n\n::: linkwork.figures\n"
    return pages


with mkdocs_gen_files.open("reference/cli.md", "w") as f:
    f.write(cli_page())
with mkdocs_gen_files.open("reference/schema.md", "w") as f:
    f.write(schema_page())
for path, text in api_pages().items():
    with mkdocs_gen_files.open(path, "w") as f:
        f.write(text)
