"""``linkwork synthesize``: a mechanism file from requirements (stroke or swing, time ratio, angle bounds)."""

from __future__ import annotations

import inspect
import math
from typing import Annotated, Any

import typer

from linkwork.cli.app import app, echo_json, fail
from linkwork.errors import LinkworkError
from linkwork.limits import QUOTE_PATH, excerpt
from linkwork.requirements import EXAMPLES, RECORDS, needs, options, required

Quantity = Annotated[str | None, typer.Option()]


def _read(options: dict[str, tuple[str | None, str]]) -> dict[str, Any]:
    """The given options (name -> (text, kind)) in SI; one line per option that does not read, or that is a
    quantity given without its unit (refused: a bare 160 read as metres would build a press of 160 m)."""
    from linkwork.units import parse_quantity

    out: dict[str, Any] = {}
    problems = []
    for name, (text, kind) in options.items():
        if text is None:
            continue
        option = f"--{name.replace('_', '-')}"
        if kind != "ratio" and _bare(text):  # a bare length is no length: 160 is not 160 m to a press designer
            shown = excerpt(text.strip(), QUOTE_PATH)
            problems.append(f'{option} "{shown}": give the unit, e.g. "{shown} {EXAMPLES[kind].split()[1]}"')
            continue
        try:
            out[name] = _number(text) if kind == "ratio" else parse_quantity(text, kind)
        except (ValueError, LinkworkError) as exc:
            problems.append(f"{option}: {exc}")
    if problems:
        fail(LinkworkError("\n".join(problems)))
    return out


def _bare(text: str) -> bool:
    """Whether ``text`` is a number without a unit."""
    try:
        float(text)
    except ValueError:
        return False
    return True


def _number(text: str) -> float:
    try:
        return float(text)
    except ValueError:
        raise ValueError(f'expected a number, got "{excerpt(text, QUOTE_PATH)}"') from None


def _section(text: str | None) -> dict[str, Any]:
    if text is None:
        return {}
    from linkwork.units import parse_quantity

    parts = text.lower().split("x")
    try:
        if len(parts) != 2:
            raise ValueError("expected WIDTHxHEIGHT")
        return {"section": tuple(parse_quantity(p.strip(), "length") for p in parts)}
    except (ValueError, LinkworkError) as exc:
        fail(LinkworkError(f'--section "{excerpt(text, QUOTE_PATH)}": {exc}, e.g. "40mm x 20mm"'))


#: The requirement options of ``linkwork synthesize`` (each a text: a quantity with its unit, a ratio or a word): name
#: -> (kind of quantity, help), generated from the kinds' records, in the order of its help (:func:`_signature`).
OPTIONS = options()


def synthesize(
    kind: Annotated[
        str, typer.Argument(help="slider-crank, crank-rocker, slotted-lever, toggle-press or double-cut-shears")
    ],
    out: Annotated[str, typer.Option("--out", help="the mechanism file to write (.yaml)")],
    speed: Annotated[
        str | None, typer.Option("--speed", help="the crank's speed written in the file (60 rpm; the shears' own)")
    ] = None,
    section: Annotated[
        str | None, typer.Option("--section", help='the steel bars\' section, "40mm x 20mm" by default')
    ] = None,
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON object")] = False,
    lang: Annotated[str, typer.Option(help="language of the printed summary: en or ru")] = "en",
    **given: str | None,
) -> None:
    """Write a mechanism file that meets the requirements, verified by the kinematic analysis of that file.

    slider-crank: --stroke, --time-ratio, and --rod-ratio or --offset (else the member picked by --criterion: pressure,
    the least largest pressure angle, or torque, the least peak driving torque under --force over the last --working of
    the stroke, within --max-pressure-angle); --max-pressure-angle a bound.  crank-rocker: --swing, --time-ratio,
    --rocker or --frame; --min-transmission-angle a bound.  slotted-lever: --stroke, --time-ratio; --frame or --crank
    (else the greatest frame), --rod (else the shortest rod meeting --max-pressure-angle, 10 deg by default).
    toggle-press: --stroke, --force at --before the bottom dead centre, --torque (the crank's limit, N m);
    --swing and --time-ratio of its four-bar.  double-cut-shears (the bundled file's structure): --upper-stroke,
    --lower-stroke, --time-ratio (closing over opening), --overlap or --opening; --crank fixes the crank, else
    --criterion picks it.  Every kind keeps the design rule: the least transmission angle of every dyad over the
    turn at least 40 deg (--min-transmission-angle lowers it).  Requirements that cannot be met: exit 2, no file."""
    from linkwork.lang import check_lang
    from linkwork.synthesis import synthesize as run

    try:
        check_lang(lang)
    except LinkworkError as exc:
        fail(exc)
    if kind not in RECORDS:
        fail(LinkworkError(f"unknown kind {kind!r}: expected one of {', '.join(RECORDS)}"))
    if not out.endswith((".yaml", ".yml")):
        fail(LinkworkError(f'--out "{excerpt(out, QUOTE_PATH)}": expected a .yaml file'))
    known = needs(kind)
    texts = {name: given.get(name) for name in OPTIONS}
    wrong = [name for name, text in texts.items() if text is not None and name not in known]
    if wrong:
        fail(LinkworkError(f"{kind}: --{', --'.join(w.replace('_', '-') for w in wrong)}: not a requirement of {kind}"))
    texts = {name: text for name, text in texts.items() if name in known}
    missing = [n for n in required(kind) if texts[n] is None]
    if missing:
        fail(LinkworkError(f"{kind}: missing --{', --'.join(m.replace('_', '-') for m in missing)}"))
    words = {
        name: texts.pop(name) for name in list(texts) if known[name].quantity == "word" and texts[name] is not None
    }
    requirements = _read({name: (text, known[name].quantity) for name, text in texts.items()})
    extra = {"speed": speed} if speed is not None else {}
    try:
        result = run(kind, **requirements, **words, **extra, **_section(section))
        result.write(out)
    except (LinkworkError, OSError) as exc:
        fail(exc)
    _show(result, out, as_json, lang)


def _signature() -> inspect.Signature:
    """The options typer reads off :func:`synthesize`: ``KIND`` and ``--out``, then one ``--NAME`` option of text per
    requirement of the kinds' records (:data:`OPTIONS`, generated from :mod:`linkwork.requirements`), then its own."""
    own = list(inspect.signature(synthesize, eval_str=True).parameters.values())[:-1]
    generated = [
        inspect.Parameter(
            name,
            inspect.Parameter.POSITIONAL_OR_KEYWORD,
            default=None,
            annotation=Annotated[str | None, typer.Option(f"--{name.replace('_', '-')}", help=text)],
        )
        for name, (_, text) in OPTIONS.items()
    ]
    return inspect.Signature([*own[:2], *generated, *own[2:]], return_annotation=None)


synthesize.__signature__ = _signature()  # type: ignore[attr-defined]
app.command()(synthesize)


def _show(result: Any, out: str, as_json: bool, lang: str = "en") -> None:
    if as_json:
        echo_json(
            {
                "kind": result.kind,
                "out": out,
                "requirements": result.requirements,
                "dimensions": result.dimensions,
                "predicted": result.predicted,
                "measured": result.measured,
                "tolerances": result.tolerances,
                "criterion": result.criterion,
            }
        )
        return
    from linkwork.lang import t

    mm = t("unit.mm", lang)
    typer.echo(f"{result.kind}: {result.criterion}")
    for name, value in result.dimensions.items():
        typer.echo(f"  {name:12s} {value * 1e3:12.1f} {mm}")  # as written: to 0.1 mm
    typer.echo(t("synth.measured", lang))
    from linkwork.synthesis.common import ALIASES

    for name, value in result.measured.items():
        label = name.replace("_", " ") if lang == "en" else t(f"synth.quantity.{name}", lang)
        tol = result.tolerances.get(ALIASES.get(name, name))
        within = f"  +- {_shown(name, tol, lang)}" if tol is not None else ""
        typer.echo(f"  {label:26s} {_shown(name, value, lang)}{within}")
    typer.echo(t("synth.written", lang, out=out))


#: The measured quantities that are lengths (the rest: ratios, torques, angles).
LENGTHS = ("stroke", "upper_stroke", "lower_stroke", "overlap", "opening")


def _shown(name: str, value: float, lang: str = "en") -> str:
    """A measured quantity as the summary prints it: lengths in mm, angles in degrees (in ``lang``'s units)."""
    from linkwork.lang import t

    if name in LENGTHS:
        return f"{value * 1e3:.9f} {t('unit.mm', lang)}"
    if name == "time_ratio":
        return f"{value:.12g}"
    if name in ("torque_at_nominal", "peak_torque"):
        return f"{value:.12g} {t('synth.unit.Nm', lang)}"
    return f"{math.degrees(value):.9f} {t('synth.unit.deg', lang)}"
