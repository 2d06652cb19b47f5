"""``linkwork size``: the motor from a catalogue with its gear and flywheel, bearings, pins and foundation bolts."""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import TYPE_CHECKING, Annotated, Any

import typer

from linkwork.cli.app import FileOrExample, app, check_options, compile_or_exit, echo_json, fail
from linkwork.errors import LinkworkError
from linkwork.limits import delta_problem

if TYPE_CHECKING:
    from linkwork.sizing import Sizing
    from linkwork.sizing.common import Catalogue


def _quantity(text: str | None, kind: str, option: str, example: str) -> float | None:
    """``text`` with its unit (``20000 h``, ``20000h``) in SI; exit code 2 with one line where it is not one: no
    unit, a unit that is not one (``20000 ч``) or of another kind, or not a positive value."""
    from linkwork.errors import UnitParseError
    from linkwork.limits import quote
    from linkwork.units import parse_quantity

    if text is None:
        return None
    match = re.match(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(.*?)\s*$", text)
    if match is None:
        fail(LinkworkError(f"{option}: expected a number and its unit, e.g. {quote(example)}, got {quote(text)}"))
    number, unit = match.groups()
    if not unit:
        fail(LinkworkError(f"{option}: give the unit, e.g. {quote(example)}, got {quote(text)}"))
    try:
        value = parse_quantity(f"{number} {unit}", kind)
    except UnitParseError:
        why = "is not a unit linkwork knows" if not _is_unit(unit) else "is a unit of another kind"
        fail(LinkworkError(f"{option}: {quote(unit)} {why}; expected e.g. {quote(example)}, got {quote(text)}"))
    if not value > 0:
        fail(LinkworkError(f"{option}: expected a positive value, got {quote(text)}"))
    return value


def _is_unit(unit: str) -> bool:
    """Whether pint reads ``unit`` as a unit (of any kind)."""
    from linkwork.units import registry

    try:
        registry().parse_units(unit.replace("^", "**"))
    except Exception:  # pint raises several types for what is not a unit
        return False
    return True


def _default(field: str) -> str:
    """`` (default: the file's sizing: FIELD, else VALUE)`` for an option's help, from the one home of the defaults
    (:class:`~linkwork.spec.schema.SizingSpec`)."""
    from linkwork.spec.schema import SizingSpec

    return f" (default: the file's sizing: {field}, else {SizingSpec.model_fields[field].default})"


def _before_work(catalogue: str | None, synchronous: float | None, write: str | None, motor: bool) -> Catalogue | None:
    """The motor catalogue read and the ``--write`` destination checked before any computing: the catalogue
    (None: the bundled one), or exit code 2 with the reason."""
    from linkwork.atomic import target_problem
    from linkwork.sizing.motor import motor_catalogue, synchronous_problem

    if write is not None:
        why = target_problem(write)
        if why is not None:
            fail(LinkworkError(f"--write {write}: {why}"))
    if not motor:
        return None
    try:
        cat = motor_catalogue(catalogue)
    except LinkworkError as exc:
        fail(exc)
    if synchronous is not None:
        why = synchronous_problem(cat, synchronous)
        if why is not None:
            fail(LinkworkError(f"--synchronous: {why}"))
    return cat


@app.command()
def size(
    file_or_example: FileOrExample,
    life: Annotated[
        str | None,
        typer.Option(
            help="basic rating life L10h of the rolling bearings, e.g. 20000h (default: the "
            "file's sizing: life, else 20000 h)"
        ),
    ] = None,
    kind: Annotated[str | None, typer.Option(help=f"rolling bearings: ball or roller{_default('bearings')}")] = None,
    delta: Annotated[
        float | None,
        typer.Option(help="coefficient of speed fluctuation for the flywheel (default: the file's, else 0.05)"),
    ] = None,
    reserve: Annotated[
        float | None,
        typer.Option(help=f"share of the breakdown torque the peak motor torque may reach{_default('reserve')}"),
    ] = None,
    catalogue: Annotated[
        str | None, typer.Option(help="a motor catalogue (CSV with the bundled one's columns)")
    ] = None,
    synchronous: Annotated[
        str | None, typer.Option(help='keep to motors of this synchronous speed, e.g. "1500 rpm"')
    ] = None,
    motor: Annotated[bool, typer.Option(help="choose the motor (--no-motor: bearings, pins and bolts only)")] = True,
    steel: Annotated[str | None, typer.Option(help=f"steel grade of the pins (steels.csv){_default('steel')}")] = None,
    bush: Annotated[str | None, typer.Option(help=f"plain bush (bushes.csv){_default('bush')}")] = None,
    width_ratio: Annotated[
        float | None, typer.Option(help=f"width / diameter of the pins sized{_default('width_ratio')}")
    ] = None,
    bolt_class: Annotated[
        str | None, typer.Option(help=f"property class of the foundation bolts{_default('bolt_class')}")
    ] = None,
    write: Annotated[
        str | None, typer.Option(help="write the mechanism file with the chosen motor, gear and flywheel (.yaml)")
    ] = None,
    masses: Annotated[
        str | None,
        typer.Option(
            help='"sized" (the default, unless the file\'s sizing: masses says "file"): from their sized steel '
            "sections (bars) and pins and guides (blocks), iterated with the loads to a fixed point (--write writes "
            'them too); "file": as the file gives them'
        ),
    ] = None,
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON object")] = False,
) -> None:
    """Size the machine from its loads: motor, gear and flywheel, rolling and plain bearings, pins, bolts."""
    from linkwork.study import SizingOptions, Study

    given = {"bearings": kind, "delta": delta, "reserve": reserve, "width_ratio": width_ratio, "masses": masses}
    problems = _option_problems(given, write, motor, catalogue=catalogue, synchronous=synchronous)
    check_options(*problems)
    life_s = _quantity(life, "time", "--life", "20000 h")
    sync = _quantity(synchronous, "angular_speed", "--synchronous", "1500 rpm")
    cat = _before_work(catalogue, sync, write, motor)
    mech = compile_or_exit(file_or_example)
    bar = _progress()
    given |= {"life": life_s, "synchronous": sync, "steel": steel, "bush": bush, "bolt_class": bolt_class}
    asked = SizingOptions(
        inputs={k: v for k, v in given.items() if v is not None},  # over the file's sizing: section
        motor=motor,
        catalogue=cat if catalogue is not None else None,  # the bundled one said as such
        progress=bar,
    )
    try:
        result = Study(mech, sizing=asked).sizing
        written = _write(mech, result, write) if write is not None else None
    except LinkworkError as exc:
        _cleared(bar)
        fail(exc)
    _cleared(bar)
    if as_json:
        echo_json({**result.record(), **({"written": written} if written else {})})
        return
    _print(result, written)


def _option_problems(
    given: dict[str, Any], write: str | None, motor: bool, *, catalogue: str | None, synchronous: str | None
) -> list[str | None]:
    """What is wrong with the options of ``linkwork size``: the inputs ``given`` (the record's fields, None where
    not given), the ``--write`` destination's name and the motor's options without the motor chosen."""
    from linkwork.sizing.bearings import width_ratio_problem

    kind, reserve, width_ratio, masses = (given[k] for k in ("bearings", "reserve", "width_ratio", "masses"))
    problems = [delta_problem(given["delta"], "--delta")]
    if kind is not None and kind not in ("ball", "roller"):
        problems.append(f'--kind: "ball" or "roller", got "{kind}"')
    if reserve is not None and not 0 < reserve <= 1:
        problems.append(f"--reserve: a share of the breakdown torque in (0, 1], got {reserve}")
    if width_ratio is not None:
        problems.append(width_ratio_problem(width_ratio, "--width-ratio"))
    if masses is not None and masses not in ("file", "sized"):
        problems.append(f'--masses: "file" or "sized", got "{masses}"')
    if write is not None and not write.endswith((".yaml", ".yml")):
        problems.append(f'--write "{write}": expected a .yaml file')
    if write is not None and not motor:
        problems.append("--write puts the chosen motor into the file: it needs the motor chosen (drop --no-motor)")
    if catalogue is not None and not motor:
        problems.append("--catalogue is the motors' catalogue: it needs the motor chosen (drop --no-motor)")
    if synchronous is not None and not motor:
        problems.append("--synchronous keeps to motors of that speed: it needs the motor chosen (drop --no-motor)")
    return problems


def _print(result: Sizing, written: str | None) -> None:
    """The sizing on the terminal: its inputs, its tables, the motors passed over, what was not sized, the file
    written."""
    typer.echo(f"{result.name}: sizing")
    shown = (f"{k} {v:g}" if isinstance(v, float) else f"{k} {v}" for k, v in result.inputs.items() if v is not None)
    typer.echo("  inputs (defaults included): " + ", ".join(shown))
    for table in result.tables():
        typer.echo(table.text())
    if result.motor is not None:
        for passed in result.motor.passed:
            typer.echo(f"  passed over: {passed.name}: {passed.why}")
    for part, why in result.missing.items():
        typer.echo(f"  not sized: {part}: {why}")
    for warning in result.warnings():
        typer.echo(f"  warning: does not fit: {warning}")
    if written:
        typer.echo(f"  wrote {written}")


def _progress() -> Callable[[int, int], None] | None:
    """Where standard error is a terminal: a line that counts the motors of the catalogue looked at (the choice of
    a large catalogue takes a while), rewritten in place; :func:`_cleared` clears it.  Else None."""
    import sys

    raw = getattr(sys.stderr, "unescaped", sys.stderr)  # the line's own carriage return and erase, as they are
    if not raw.isatty():
        return None

    def show(k: int, n: int) -> None:
        if n >= 20:
            raw.write(f"\r\033[K  motor {k + 1:,} of {n:,} looked at")
            raw.flush()

    return show


def _cleared(progress: Callable[[int, int], None] | None) -> None:
    """Clear the line of :func:`_progress` (where there is one)."""
    import sys

    if progress is not None:
        raw = getattr(sys.stderr, "unescaped", sys.stderr)
        raw.write("\r\033[K")
        raw.flush()


def _write(mech: object, result: object, out: str) -> str:
    """Write the file of ``mech`` with the chosen motor, gear and flywheel to ``out``, atomically; its path."""
    from pathlib import Path

    from linkwork.sizing import Sizing
    from linkwork.spec.edit import text_with_section, write_text
    from linkwork.spec.reader import described
    from linkwork.structure.model import Mechanism

    assert isinstance(result, Sizing) and isinstance(mech, Mechanism) and result.motor is not None
    spec = described(mech.description)
    if result.masses is not None and spec is not None:  # the masses it was sized with, written first
        from linkwork.spec.reader import loads
        from linkwork.structure.parameters import file_text

        sized = {f"links.{k}.mass": v for k, v in result.masses.masses.items()}
        spec = loads(file_text(mech, sized), spec.source.file if spec.source is not None else None)
    text = text_with_section(spec, "machine", result.motor.machine_section())
    try:
        path = write_text(text, out)
    except OSError as exc:
        raise LinkworkError(f"--write {out}: cannot write ({exc.strerror or exc})") from None
    return str(Path(path))
