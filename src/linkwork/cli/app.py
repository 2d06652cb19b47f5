"""``linkwork``: the command line.

Errors in files, options or geometry are printed to stderr, one line per
problem, and the command exits with code 2; so is a missing optional package
(with the pip command that installs it), checked before a command starts its
work.  ``--json`` output goes through one writer (:func:`linkwork.io.jsonout.dumps`),
tables through :func:`make_console`, :func:`make_table` and :func:`show`.
"""

from __future__ import annotations

import math
import sys
from typing import TYPE_CHECKING, Annotated, Any, NoReturn

import typer

from linkwork.errors import LinkworkError, MissingDependencyError
from linkwork.limits import TURN_STEPS
from linkwork.optional import require

app = typer.Typer(
    name="linkwork",
    help="Analysis of planar lever mechanisms: structure, kinematics, forces, dynamics, impact.",
    add_completion=False,
    no_args_is_help=True,
    pretty_exceptions_enable=False,
    rich_markup_mode=None,
)

if TYPE_CHECKING:
    from pathlib import Path

    from rich.console import Console
    from rich.table import Table

    from linkwork.motion.drive_range import DriveRange
    from linkwork.spec.values import ValueRead
    from linkwork.structure.model import Mechanism


@app.callback()
def _every_command() -> None:
    """Analysis of planar lever mechanisms: structure, kinematics, forces, dynamics, impact."""
    import warnings

    from linkwork.cli.terminal import install
    from linkwork.errors import FrictionWarning

    install()  # whatever calls the application (the script, a test's runner): its output escaped
    # where friction has no solution the commands say so in their own words (forces, the report, dynamics)
    warnings.filterwarnings("ignore", category=FrictionWarning)


FileOrExample = Annotated[str, typer.Argument(help="a mechanism file (.yaml) or the name of a bundled example")]

#: ``--steps`` of the commands that take either it or ``--angles``.
Steps = Annotated[
    int | None, typer.Option(help=f"equal steps over one turn of the crank (default {TURN_STEPS})", show_default=False)
]

#: ``--angles``: the crank angles in degrees.
Angles = Annotated[str | None, typer.Option(help="crank angles in degrees, e.g. 0,30,60")]

#: ``--speed``: the drive's uniform speed, in place of the file's (:func:`drive_speed` reads it).
Speed = Annotated[
    str | None, typer.Option(help='uniform drive speed with a unit, e.g. "30 rpm" (default: the file\'s drive speed)')
]


def fail(exc: Exception) -> NoReturn:
    """Print a linkwork error to stderr and exit with code 2."""
    sys.stderr.write(f"error: {exc}\n" if "\n" not in str(exc) else f"error:\n{exc}\n")
    raise typer.Exit(2)


def drive_speed(mech: Mechanism, text: str | None) -> float | None:
    """The drive speed of ``--speed`` (:data:`Speed`) in SI, in the file's direction of the drive; None
    where it is not given (the file's speed).  Exit code 2 with one line for a speed without its unit,
    of the wrong kind, or below 0."""
    from linkwork.limits import MAX_MAGNITUDE, quote
    from linkwork.structure.model import PairType
    from linkwork.units import KINDS

    if text is None:
        return None
    revolute = mech.pair_type[mech.drive_pair[0]] == PairType.REVOLUTE
    kind, example = ("angular_speed", "30 rpm") if revolute else ("speed", "0.2 m/s")
    value = quantity_option(text, kind, "--speed", example)
    if value < 0:
        fail(LinkworkError(f'--speed: the direction comes from the file; give a speed from 0 up, got "{text}"'))
    if value > MAX_MAGNITUDE:
        size = f"{KINDS[kind][0]} of a machine's size (at most 1e9 in SI)"
        fail(LinkworkError(f"--speed: expected {size}, got {quote(text)}"))
    sign = -1.0 if mech.drive_speed[0] < 0 else 1.0
    return sign * value


def quantity_option(text: str, kind: str, option: str, example: str) -> float:
    """The value (SI) of the ``option`` that needs its unit (a quantity of ``kind``, as ``example``); exit code 2
    with one line for a bare number or a text that is not such a quantity."""
    from linkwork.errors import UnitParseError
    from linkwork.units import parse_quantity

    try:
        float(text)
    except ValueError:
        pass
    else:
        fail(LinkworkError(f'{option}: give the unit, e.g. "{example}", got "{text}"'))
    try:
        return parse_quantity(text, kind)
    except UnitParseError as exc:
        fail(LinkworkError(f"{option}: {exc}"))


def at_speed(mech: Mechanism, text: str | None) -> Mechanism:
    """``mech`` with its drive at the speed of ``--speed`` (:func:`drive_speed`), or as it is where none is
    given: for a command whose stages read the drive's speed from the mechanism (``analyze``)."""
    import dataclasses

    from linkwork.structure.model import frozen

    rate = drive_speed(mech, text)
    if rate is None:
        return mech
    return dataclasses.replace(mech, drive_speed=frozen([rate, *mech.drive_speed[1:]]))


def check_options(*problems: str | None) -> None:
    """Exit with code 2 and a line for each problem of the options (the messages of the checks of
    :mod:`linkwork.limits`; None where an option is right), before any work."""
    found = [p for p in problems if p is not None]
    if found:
        fail(LinkworkError("\n".join(found)))


def needs(*modules: str, purpose: str) -> None:
    """Exit with the one-line message of :func:`linkwork.optional.require` unless ``modules`` import."""
    try:
        require(*modules, purpose=purpose)
    except MissingDependencyError as exc:
        fail(exc)


def echo_json(data: Any, indent: int | None = None, why: dict[str, str] | None = None) -> None:
    """Print ``data`` as JSON by the command line's one writer (rounded numbers, no NaN), a record with
    its ``nulls`` explained (:func:`explain_nulls`, by ``why``)."""
    from linkwork.io.jsonout import dumps

    typer.echo(dumps(explain_nulls(data, why or {}) if isinstance(data, dict) else data, indent=indent))


#: Why a number has no value, where the record's command gives no reason of its own.
NO_VALUE = "no value: the computation gives none (not a finite number)"


def explain_nulls(data: dict[str, Any], why: dict[str, str]) -> dict[str, Any]:
    """``data`` (a ``--json`` record) with ``nulls``, an object that says why each null stands where a
    number would be, where it holds any: the one rule of the ``--json`` records.

    ``why`` maps a path in the record (``points.*``, ``events[].time_ratio``; ``*`` one key, ``[]`` the
    items of a list; a path covers what lies under it) to why its nulls have no value.  Every null or
    non-finite number under one of those paths is explained by the first that covers it (and listed
    under that path); every other non-finite number under its own path, as having :data:`NO_VALUE`.
    Other nulls mean what the record's documentation says (an order of a group of class I, a drive
    without a speed).
    """
    import re

    patterns = [(re.compile(re.escape(p).replace(r"\*", r"[^.\[]+") + r"(?=$|[.\[])"), p) for p in why]
    nulls: dict[str, str] = {}
    for path, finite_none in _no_values(data, ""):
        covering = next((p for regex, p in patterns if regex.match(path)), None)
        if covering is not None:
            nulls.setdefault(covering, why[covering])
        elif not finite_none:
            nulls.setdefault(path, NO_VALUE)
    return {**data, "nulls": nulls} if nulls else data


def _no_values(x: Any, path: str) -> Any:
    """``(path, is None)`` of each None and each non-finite number in ``x``, by the path of its key
    (``[]`` for the items of a list), once per path."""
    import numpy as np

    if x is None:
        yield path, True
    elif isinstance(x, float | np.floating) and not math.isfinite(x):
        yield path, False
    elif isinstance(x, np.ndarray) and x.dtype.kind == "f" and not np.isfinite(x).all():
        yield path + "[]", False
    elif isinstance(x, dict):
        for k, v in x.items():
            yield from _no_values(v, f"{path}.{k}" if path else str(k))
    elif isinstance(x, list | tuple) and _plain_records(x):
        return  # objects of plain values and short arrays of finite numbers: nothing to say
    elif isinstance(x, list | tuple):
        seen: set[tuple[str, bool]] = set()
        for v in x:
            if type(v) in (str, int, bool) or (type(v) is float and math.isfinite(v)):
                continue  # a plain value: nothing to say, and no generator for it
            for found in _no_values(v, path + "[]"):
                if found not in seen:
                    seen.add(found)
                    yield found


def names_a_file(out: str) -> bool:
    """Whether the path ``out`` of an ``--out`` names a file (:func:`out_files`): it ends in a file
    suffix and is not an existing folder."""
    import os
    import re
    from pathlib import Path

    return not os.path.isdir(out) and re.fullmatch(r"\.[A-Za-z][A-Za-z0-9]{0,4}", Path(out).suffix) is not None


def out_files(out: str, names: tuple[str, ...]) -> list[Path]:
    """The files a command's ``--out`` asks for, of the files ``names`` it writes (``forces.csv``,
    ``forces.json``): a path that ends in the suffix of one of them is that file alone; any other path
    is a folder that gets all of them.  The one rule of ``--out``: a path ending in a file suffix
    (``.txt``, ``.xlsx``: a dot, a letter and at most four more letters or digits) means a file, so a
    suffix the command does not write is refused here (exit code 2), before any work, rather than
    made into a folder of that name; an existing folder stays a folder whatever its name."""
    from pathlib import Path

    path = Path(out)
    suffixes = {Path(n).suffix: n for n in names}
    if not names_a_file(out):
        return [path / n for n in names]
    if path.suffix.lower() in suffixes:
        return [path]
    files = " and ".join(names)
    ours = " or ".join(suffixes)
    fail(
        LinkworkError(
            f"--out {out}: names a {path.suffix} file, which this command does not write; give a folder for "
            f"{files} (e.g. --out {path.with_suffix('')}), or a file ending in {ours} for that table alone"
        )
    )


def _plain_records(x: list[Any] | tuple[Any, ...]) -> bool:
    """Whether ``x`` is a list of objects whose values are ints, strings, finite floats or lists of finite
    floats (the rows of a table with a value in every cell), told at the cost of one pass."""
    import numpy as np

    if not x or type(x[0]) is not dict:
        return False
    kinds = {type(v) for r in x if type(r) is dict for v in r.values()}
    if len(kinds) != len(kinds & {int, str, float, list}) or not all(type(r) is dict for r in x):
        return False
    floats = [v for r in x for v in r.values() if type(v) is float]
    floats += [c for r in x for v in r.values() if type(v) is list for c in v]
    return all(type(c) is float for c in floats) and bool(np.isfinite(np.array(floats, dtype=float)).all())


def make_console() -> Console:
    """The console of the commands' reports: in a terminal, as wide as it is; piped or redirected,
    plain text whose lines are as long as they need."""
    from linkwork.cli.terminal import console

    out = console(highlight=False)
    if out.is_terminal:
        return out
    return console(highlight=False, width=_PIPED_WIDTH, no_color=True)


#: Width of the text of the reports when stdout is not a terminal: lines are not folded.
_PIPED_WIDTH = 1000


def make_table(title: str) -> Table:
    """A table of a report, to print with :func:`show`."""
    from rich.table import Table

    return Table(title=title, title_justify="left")


def show(out: Console, tab: Table, keep: int = 1) -> None:
    """Print a table: in a terminal with box lines, and where it is wider than the terminal, in parts
    of as many columns as fit, each with the first ``keep`` columns again; piped, as plain text, the
    title on its own line and the rows indented under it, with no box characters."""
    from rich.padding import Padding

    if out.is_terminal:
        for part in _parts(out, tab, keep):
            out.print(part)
        return
    lines = _plain_lines(tab)
    if lines is not None:  # what rich prints of it, without rich's cost a cell (100,000 rows in a second)
        typer.echo("\n".join(lines))
        return
    title, tab.title = tab.title, None
    tab.box, tab.pad_edge, tab.padding = None, False, (0, 2, 0, 0)
    with out.capture() as text:
        if title:
            out.print(title)
        out.print(Padding(tab, (0, 0, 0, 2)))
    typer.echo("\n".join(line.rstrip() for line in text.get().splitlines()))


def _plain_lines(tab: Table) -> list[str] | None:
    """The lines :func:`show` prints of ``tab`` piped (its title, then its header and rows indented by 2, each
    cell padded to its column's width and 2 more), written here; None where rich must lay it out (a cell that
    is not one line of text, a column with width rules of its own, a line wider than the piped width)."""
    from rich.cells import cell_len
    from rich.markup import render

    def plain(cell: Any) -> str | None:
        if not isinstance(cell, str) or "\n" in cell:
            return None
        return render(cell).plain if "[" in cell or "\\" in cell else cell

    columns = []
    for c in tab.columns:
        rules = (c.width, c.min_width, c.max_width, c.ratio)
        if c.justify not in ("left", "right") or any(v is not None for v in rules):
            return None
        cells = [plain(c.header), *(plain(x) for x in c.cells)]
        if any(x is None for x in cells):
            return None
        columns.append((c.justify, [str(x) for x in cells], max((cell_len(str(x)) for x in cells), default=0)))
    title = plain(tab.title or "")
    if title is None or not isinstance(title, str) or not tab.show_header or tab.show_footer or not columns:
        return None
    if cell_len(title) > _PIPED_WIDTH or 2 + sum(w + 2 for _, _, w in columns) > _PIPED_WIDTH:
        return None
    rows = []
    for row in zip(*(texts for _, texts, _ in columns), strict=True):
        parts = []
        for (justify, _, w), x in zip(columns, row, strict=True):
            pad = " " * (w - cell_len(x))
            parts.append((pad + x if justify == "right" else x + pad) + "  ")
        rows.append(("  " + "".join(parts)).rstrip())
    return ([title] if title else []) + rows


def _parts(out: Console, tab: Table, keep: int) -> list[Table]:
    """``tab`` cut into tables of its first ``keep`` columns and as many of the others as fit ``out``."""
    from rich.table import Table

    def part(columns: list[Any], title: Any) -> Table:
        new = Table(title=title, title_justify=tab.title_justify)
        for c in columns:
            new.add_column(c.header, justify=c.justify)
        for row in zip(*(list(c.cells) for c in columns), strict=True):
            new.add_row(*row)
        return new

    def width(t: Table) -> int:  # as wide as its cells ask, not cut to the terminal
        return out.measure(t, options=out.options.update_width(1_000_000)).maximum

    head, rest = tab.columns[:keep], tab.columns[keep:]
    if width(tab) <= out.width or not rest:
        return [tab]
    parts: list[list[Any]] = [[]]
    for c in rest:
        if parts[-1] and width(part(head + parts[-1] + [c], None)) > out.width:
            parts.append([])
        parts[-1].append(c)
    return [part(head + cols, tab.title if i == 0 else None) for i, cols in enumerate(parts)]


def compile_or_exit(file_or_example: str) -> Mechanism:
    """The compiled mechanism of a file or a bundled example, for a command.

    Parameters
    ----------
    file_or_example : str
        A YAML file's path or a bundled example's name.

    Returns
    -------
    Mechanism
        The compiled mechanism.

    Raises
    ------
    typer.Exit
        With exit code 2 where the file cannot be read or compiled, its problems printed (:func:`fail`).
    """
    from linkwork.api import compile
    from linkwork.examples import resolve

    try:
        return compile(resolve(file_or_example))
    except LinkworkError as exc:
        fail(exc)


@app.command()
def check(
    file_or_example: FileOrExample,
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON object instead of the report")] = False,
    values: Annotated[
        bool, typer.Option("--values", help="list every value read from the file: its text, in SI, with its unit")
    ] = False,
) -> None:
    """Validate a mechanism and print its structure (DOF, redundant constraints, Assur groups) and the range
    of its drive over which it assembles (Grashof's class for a four-bar)."""
    from linkwork.api import compile
    from linkwork.examples import resolve
    from linkwork.motion.drive_range import drive_range
    from linkwork.spec.values import values_read

    try:
        spec = resolve(file_or_example)
        mech = compile(spec)
    except LinkworkError as exc:
        fail(exc)
    reach = drive_range(mech)
    warnings = [*mech.structure.warnings, *(reach.warnings() if reach is not None else [])]
    read = values_read(spec) if values else None
    if as_json:
        out = {"name": mech.name, **mech.structure.as_dict(), "drives": _drives(mech)}
        out["drive_range"] = None if reach is None else reach.as_dict()
        out["warnings"] = warnings
        if read is not None:
            out["values"] = [v.as_dict() for v in read]
        echo_json(out, indent=2)
        return
    _print_structure(mech, reach, warnings)
    if read is not None:
        _print_values(read)


def _drives(mech: Mechanism) -> list[dict[str, Any]]:
    """Each drive of ``mech``: its joint, its type, its speed and its value in the assembly pose, SI."""
    from linkwork.structure.model import PairType

    out = []
    for d, k in enumerate(mech.drive_pair):
        rot = mech.pair_type[k] == PairType.REVOLUTE
        out.append(
            {
                "joint": mech.pair_joint[k],
                "type": "revolute" if rot else "prismatic",
                "speed": None if math.isnan(mech.drive_speed[d]) else float(mech.drive_speed[d]),
                "speed_unit": "rad/s" if rot else "m/s",
                "start": float(mech.drive_start[d]),
                "start_unit": "rad" if rot else "m",
            }
        )
    return out


def _print_structure(mech: Mechanism, reach: DriveRange | None, warnings: list[str]) -> None:
    """The report of ``linkwork check``: the structure, the drives, the Assur groups, the drive's range."""
    from rich.markup import escape

    s = mech.structure
    console = make_console()
    console.print(f"[bold]{escape(mech.name)}[/bold]" + (f"  ({escape(mech.source)})" if mech.source else ""))
    tail = f" - {s.p4}" if s.p4 else ""
    console.print(f"  moving links n = {s.n_links}, lower pairs p5 = {s.p5}, higher pairs p4 = {s.p4}")
    console.print(f"  W = 3n - 2p5 - p4 = 3*{s.n_links} - 2*{s.p5}{tail} = {s.dof}   (Chebyshev)")
    console.print(f"  redundant constraints q = {s.redundant}, mobility W + q = {s.mobility}")
    for drive in _drives(mech):
        if drive["speed"] is None:
            speed = "motion law"
        elif drive["type"] == "revolute":
            speed = f"{abs(drive['speed']) * 30 / math.pi:.6g} rpm {'ccw' if drive['speed'] >= 0 else 'cw'}"
        else:
            speed = f"{drive['speed']:.6g} m/s"
        console.print(f"  drive: joint {escape(drive['joint'])} ({drive['type']}), {speed}")
    table = make_table("Assur groups in solving order")
    for col in ("#", "group", "class", "order", "kind", "links", "joints"):
        table.add_column(col)
    for i, g in enumerate(s.groups, 1):
        links = ", ".join(f"{n} {name}" for n, name in zip(g.links, g.link_names, strict=True))
        table.add_row(
            *(
                escape(c)
                for c in (
                    str(i),
                    g.label.split(" ")[0],
                    str(g.klass),
                    "-" if g.order is None else str(g.order),
                    g.kind,
                    links,
                    ", ".join(g.joints),
                )
            ),
        )
    show(console, table)
    console.print(f"  structural formula: {s.formula}")
    for i, line in enumerate(reach.describe() if reach is not None else []):
        console.print(f"  {'drive range:' if i == 0 else ' ' * 12} {escape(line)}")
    if reach is not None and reach.grashof is not None:
        console.print(f"  Grashof: {escape(reach.grashof.describe())}")
    for w in warnings:
        console.print(f"  [yellow]warning:[/yellow] {escape(w)}")


def _print_values(read: list[ValueRead]) -> None:
    """The table of every value read from the file (``linkwork check --values``)."""
    from rich.markup import escape

    table = make_table("Values read from the file, in SI")
    for col in ("line", "path", "in the file", "SI", "unit"):
        table.add_column(col, justify="right" if col in ("line", "SI") else "left")
    for v in read:
        line = "" if v.line is None else str(v.line)
        table.add_row(*(escape(c) for c in (line, v.path, str(v.text), f"{v.value:.10g}", v.unit or "-")))
    show(make_console(), table)


@app.command()
def schema() -> None:
    """Print the JSON Schema of the mechanism file format (for editors)."""
    from linkwork.spec.schema import Spec

    echo_json(Spec.model_json_schema(), indent=2)


@app.command()
def warm(
    quiet: Annotated[bool, typer.Option("--quiet", help="print nothing")] = False,
    background: Annotated[bool, typer.Option("--background", hidden=True)] = False,
) -> None:
    """Compile the fast (numba) kernels into their cache now, once: later runs load them where they pay.

    Without this, the first run that finds the cache empty starts the same compile in the background and
    answers with the NumPy kernels meanwhile.
    """
    import os

    from linkwork import jit
    from linkwork.api import compile_kernels

    if not jit.installed():
        fail(LinkworkError("numba is not installed: the NumPy kernels run (pip install numba)"))
    if background and hasattr(os, "nice"):
        os.nice(19)
    say = (lambda text: None) if quiet else typer.echo
    if jit.ready():
        say(f"the fast kernels are ready in {jit.cache_dir()}")
        return
    say(f"compiling the fast kernels into {jit.cache_dir() or 'memory (no writable cache)'} (a few minutes, once)")
    try:
        compile_kernels()
    except BaseException:
        if background:
            jit.release(failed=True)
        raise
    if background:
        jit.release()
    say("done: later runs load them where they pay")


@app.command()
def examples() -> None:
    """List the bundled example mechanisms."""
    from linkwork.examples import load_example, names

    for name in names():
        spec = load_example(name)
        first = (spec.description or "").strip().split(". ")[0].split("\n")[0]
        typer.echo(f"{name:22s} {first}")


@app.command()
def example(name: Annotated[str, typer.Argument(help="name of a bundled example")]) -> None:
    """Print a bundled example as YAML (a starting point for your own file)."""
    from linkwork.examples import text

    try:
        typer.echo(text(name), nl=False)
    except LinkworkError as exc:
        fail(exc)
