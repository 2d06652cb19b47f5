"""Load and validate mechanism descriptions: one pass, every problem reported."""

from __future__ import annotations

import math
import re
import types
import typing
from pathlib import Path
from typing import Any

from pydantic import BaseModel, ValidationError
from pydantic_core import ErrorDetails

from linkwork.did_you_mean import suggest
from linkwork.errors import Problem, SpecError, UnitParseError
from linkwork.limits import echo, quote
from linkwork.spec.checks import check
from linkwork.spec.part_checks import part_checks
from linkwork.spec.schema import UNION_TAGS, Spec
from linkwork.spec.yamlsource import Source, dotted, read_file, read_yaml
from linkwork.units import DECLARABLE, DEFAULT_UNITS, KINDS, SI_UNITS, check_unit, parse_quantity


def load(path: str | Path) -> Spec:
    """Read and validate a mechanism file.

    Raises
    ------
    SpecError
        Listing every problem with ``file:line``, the element and what was expected; or the one reason
        the file cannot be read (:func:`~linkwork.spec.yamlsource.read_file`: not a regular file, too large,
        not UTF-8).
    """
    return loads(read_file(path), file=str(Path(path)))


def loads(text: str, file: str | None = None) -> Spec:
    """Validate a mechanism given as YAML text (``linkwork.loads``).

    Parameters
    ----------
    text : str
        The mechanism file's text.
    file : str, optional
        The name that messages give the text (``file:line``); default none.

    Returns
    -------
    Spec
        The description, validated, in SI units.

    Raises
    ------
    SpecError
        Every problem of the text at once, each with its line, the element and what was expected.

    Examples
    --------
    >>> import linkwork as lw
    >>> from linkwork import examples
    >>> lw.loads(examples.text("four-bar")).name
    'four-bar'
    """
    return validate(read_yaml(text, file))


def from_dict(data: dict[str, Any], file: str | None = None) -> Spec:
    """Validate a mechanism given as plain data, the file's keys as a dict (``linkwork.from_dict``; the
    builder's route).

    Parameters
    ----------
    data : dict
        The mapping a mechanism file holds (``name``, ``units``, ``links``, ``joints``, ``drives``, ...).
    file : str, optional
        The name that messages give the data; default none.

    Returns
    -------
    Spec
        The description, validated, in SI units.

    Raises
    ------
    SpecError
        Every problem of the data at once, each with the element and what was expected.

    Examples
    --------
    >>> import yaml
    >>> import linkwork as lw
    >>> from linkwork import examples
    >>> data = yaml.safe_load(examples.text("four-bar"))
    >>> lw.from_dict(data) == lw.load("four-bar")
    True
    """
    return validate(Source(data, {}, file, []))


def description(spec: Spec) -> Source:
    """The plain record of ``spec`` a compiled mechanism keeps (``Mechanism.description``):
    the document it was read from (its data and the line of each element), or, for a description made otherwise
    (changed in code, or by ``Spec.model_validate``), its values in SI (:func:`si_data`).  The record reads back
    (:func:`described`) as ``spec`` itself while it is one of the last few read."""
    if spec.source is None:
        return Source(si_data(spec))
    _remember(spec)
    return spec.source


def si_data(spec: Spec) -> dict[str, Any]:
    """The values of ``spec`` as the plain data of a file that declares SI units: read again (:func:`validate`),
    they give the same description but for its ``units:``."""
    data = plain(spec.model_dump(mode="python", exclude_none=True))
    data["units"] = dict(SI_UNITS)
    return data


def plain(x: Any) -> Any:
    """``x`` with its tuples as lists: YAML's data."""
    if isinstance(x, dict):
        return {k: plain(v) for k, v in x.items()}
    if isinstance(x, list | tuple):
        return [plain(v) for v in x]
    return x


#: The descriptions read back lately (:func:`described`), by the identity of their record: the record and its Spec.
_READ_BACK: dict[int, tuple[Source, Spec]] = {}


def described(source: Source | None) -> Spec | None:
    """The description of the record ``source`` a compiled mechanism keeps (its ``description``; None for none): the
    document validated again, equal to the Spec it was compiled from (a description made in code: its values with
    SI units declared).  The last few are kept, so that the outputs that read one mechanism's file read it once."""
    if source is None:
        return None
    kept = _READ_BACK.get(id(source))
    if kept is not None and kept[0] is source:
        return kept[1]
    spec = validate(source)
    _remember(spec)
    return spec


def _remember(spec: Spec) -> None:
    """Keep ``spec`` (read from a document) as what its record reads back as."""
    if len(_READ_BACK) >= 16:
        _READ_BACK.pop(next(iter(_READ_BACK), 0), None)
    _READ_BACK[id(spec.source)] = (spec.source, spec)


def validate(src: Source) -> Spec:
    """Validate raw data with line numbers; raise one SpecError for all problems."""
    problems = list(src.problems)
    if src.data is None:
        raise SpecError(problems)
    if not isinstance(src.data, dict):
        problems.append(src.problem((), "a mechanism file is a mapping with links, joints and drives"))
        raise SpecError(problems)
    stranger = _not_a_mechanism(src)
    if stranger is not None:  # what is wrong with its keys and values is no help: one problem
        raise SpecError([stranger])
    declared = _declared_units(src, problems)
    empty = _nulls(src.data)
    problems += [src.problem(path, f"{quote(path[-1])} has no value: give one, or leave the key out") for path in empty]
    spec: Spec | None = None
    try:
        spec = Spec.model_validate(src.data, context={"units": declared})
    except ValidationError as exc:
        errors = [_untagged(e) for e in exc.errors(include_url=False)]
        problems += [_convert(src, e) for e in errors if not (e.get("input") is None and tuple(e["loc"]) in empty)]
    said = {dotted(p) for p in empty}
    problems += [p for p in check(src, declared) if not _restates(p, said)]
    if spec is not None:
        problems += _geometry_checks(spec, src) + _load_checks(spec, src) + _machine_checks(spec, src)
        problems += part_checks(spec, src)
    problems = _unique(problems)
    if problems or spec is None:
        raise SpecError(problems)
    spec = _finish(spec, declared)
    spec._source = src
    return spec


def _untagged(error: ErrorDetails) -> ErrorDetails:
    """A problem placed without the tags of the union it was found in (the form of ``gravity:``)."""
    return {**error, "loc": tuple(x for x in error["loc"] if x not in UNION_TAGS)}


def _nulls(data: Any, path: tuple[Any, ...] = ()) -> list[tuple[Any, ...]]:
    """The paths of the keys written without a value (``axis:``, ``ratio: ~``): nothing in a mechanism file
    is given as nothing.  (An empty item of a list is the schema's to refuse: it says what the item is.)"""
    if isinstance(data, list):
        return [p for i, v in enumerate(data) for p in _nulls(v, path + (i,))]
    if not isinstance(data, dict):
        return []
    return [p for k, v in data.items() for p in ([path + (k,)] if v is None else _nulls(v, path + (k,)))]


def _restates(problem: Problem, empty: set[str]) -> bool:
    """Whether ``problem`` says that a field is missing that the file writes without a value (said already);
    ``empty``: the dotted paths of those."""
    missing = re.match(r'missing field "([^"]+)"', problem.message)
    if missing is None:
        return False
    return (f"{problem.path}.{missing.group(1)}" if problem.path else missing.group(1)) in empty


def _not_a_mechanism(src: Source) -> Problem | None:
    """One problem for a mapping none of whose keys is, or is close to, a field of a mechanism file (some
    other file: its keys are not listed one by one, which would quote it back whole)."""
    fields = list(Spec.model_fields)
    keys = src.keys or list(src.data)
    if not keys or any(k in fields or suggest(k, fields) for k in keys[:20]):
        return None
    return src.problem(
        (),
        f"not a mechanism file: none of its {len(keys):,} keys (the first {quote(keys[0])}) is a field of one "
        f"({', '.join(fields[:6])}, ...)",
    )


def _declared_units(src: Source, problems: list[Problem]) -> dict[str, str]:
    declared = dict(DEFAULT_UNITS)
    units = src.data.get("units")
    if not isinstance(units, dict):
        return declared
    for kind, unit in units.items():
        if kind not in DECLARABLE or not isinstance(unit, str):
            continue  # reported by the schema
        try:
            check_unit(unit, kind)
        except UnitParseError as exc:
            noun = KINDS[kind][0].split(" ", 1)[1]
            reason = f" ({exc.reason})" if exc.reason else ""
            problems.append(src.problem(("units", kind), f'expected a unit of {noun}, got "{unit}"{reason}'))
        else:
            declared[kind] = unit
    return declared


def _finish(spec: Spec, declared: dict[str, str]) -> Spec:
    """Convert the drive fields whose kind depends on the joint type to SI."""
    drives = []
    for drive in spec.drives:
        rot = spec.joints[drive.joint].type == "revolute"
        update: dict[str, Any] = {}
        if drive.speed is not None:
            update["speed"] = parse_quantity(drive.speed, "angular_speed" if rot else "speed", declared)
        if drive.law is not None:
            values = [parse_quantity(v, "angle" if rot else "length", declared) for v in drive.law.value]
            update["law"] = drive.law.model_copy(update={"value": values})
        drives.append(drive.model_copy(update=update))
    return spec.model_copy(update={"drives": drives})


def _unique(problems: list[Problem]) -> list[Problem]:
    seen: set[tuple[str, str]] = set()
    out = []
    for p in problems:
        if (p.path, p.message) not in seen:
            seen.add((p.path, p.message))
            out.append(p)
    return sorted(out, key=lambda p: p.line if p.line is not None else 0)


def _convert(src: Source, err: Any) -> Problem:
    loc = tuple(err["loc"])
    kind = err["type"]
    value = err.get("input")
    if kind == "extra_forbidden":
        if loc[:-1] == ("units",) and loc[-1] == "torque":
            return src.problem(loc, 'unknown key "torque" (the unit of moments and torques is "moment")')
        allowed = _fields_at(loc[:-1])
        return src.problem(loc, f"unknown key {quote(loc[-1])}{suggest(loc[-1], allowed)}")
    if kind == "missing":
        return src.problem(loc[:-1], f'missing field "{loc[-1]}"')
    if kind == "literal_error":
        expected = err.get("ctx", {}).get("expected", "")
        options = [o.strip().strip("'") for o in expected.replace(" or ", ", ").split(",")]
        return src.problem(
            loc, f"expected one of {', '.join(options)}, got {echo(value)}{suggest(str(value), options)}"
        )
    if kind == "linkwork":
        return src.problem(loc, err["msg"])
    if kind in ("dict_type", "model_type", "model_attributes_type"):
        return src.problem(loc, f"expected a mapping, got {echo(value)}")
    if kind == "list_type":
        return src.problem(loc, f"expected a list, got {echo(value)}")
    if kind == "string_type":
        return src.problem(loc, f"expected a name or text, got {echo(value)}")
    if kind == "finite_number":
        return src.problem(loc, f"expected a finite number, got {echo(value)}")
    if kind in ("float_type", "float_parsing"):
        return src.problem(loc, f"expected a number, got {echo(value)}")
    bounds = {"greater_than": "greater than", "greater_than_equal": "at least", "less_than": "less than"}
    bounds["less_than_equal"] = "at most"
    if kind in bounds:
        limit = next(iter(err.get("ctx", {}).values()), "")
        limit = f"{limit:g}" if isinstance(limit, int | float) else limit
        return src.problem(loc, f"expected a number {bounds[kind]} {limit}, got {echo(value)}")
    return src.problem(loc, err["msg"])


def _fields_at(loc: tuple[Any, ...]) -> list[str]:
    """Field names allowed at ``loc`` in the schema (for "did you mean")."""
    current: Any = Spec
    for part in loc:
        current = _step(current, part)
        if current is None:
            return []
    model = _model_of(current)
    return list(model.model_fields) if model else []


def _model_of(tp: Any) -> type[BaseModel] | None:
    if isinstance(tp, type) and issubclass(tp, BaseModel):
        return tp
    for arg in typing.get_args(tp):
        found = _model_of(arg)
        if found:
            return found
    return None


def _step(tp: Any, part: Any) -> Any:
    model = _model_of(tp) if not _is_container(tp) else None
    if model is not None and isinstance(part, str) and part in model.model_fields:
        return model.model_fields[part].annotation
    for candidate in (tp, *typing.get_args(tp)):
        origin = typing.get_origin(candidate)
        if origin in (dict,) and isinstance(part, str):
            return typing.get_args(candidate)[1]
        if origin in (list,) and isinstance(part, int):
            return typing.get_args(candidate)[0]
    return None


def _is_container(tp: Any) -> bool:
    if typing.get_origin(tp) in (dict, list):
        return True
    if typing.get_origin(tp) in (typing.Union, types.UnionType):
        return any(_is_container(a) for a in typing.get_args(tp))
    return False


def _geometry_checks(spec: Spec, src: Source) -> list[Problem]:
    """Problems that need the values in SI: coincident points of a link, impossible inertia."""
    out = []
    for name, link in spec.links.items():
        local: dict[str, tuple[float, float]] = {}
        if link.ends is not None and len(link.ends) == 2 and link.length is not None:
            local = {link.ends[0]: (0.0, 0.0), link.ends[1]: (link.length, 0.0)}
        local.update(link.points)
        for a, b in coincident(local):
            out.append(src.problem(("links", name, "points"), f"points {a} and {b} coincide"))
        if link.inertia is not None and link.inertia_about in local and link.mass is not None and local:
            com = link.com if link.com is not None else None
            if isinstance(com, str):
                com = local.get(com)
            if com is None:
                com = (sum(p[0] for p in local.values()) / len(local), sum(p[1] for p in local.values()) / len(local))
            about = local[link.inertia_about]
            d2 = (about[0] - com[0]) ** 2 + (about[1] - com[1]) ** 2
            if link.inertia < link.mass * d2 * (1 - 1e-12):
                out.append(
                    src.problem(
                        ("links", name, "inertia"),
                        f"an inertia of {link.inertia:.6g} kg m^2 about {link.inertia_about} is less than "
                        f"m d^2 = {link.mass * d2:.6g} kg m^2 of the centre of mass alone: impossible",
                    )
                )
    return out


#: Points of a link closer than this (m) coincide.
COINCIDE = 1e-12


def coincident(points: dict[str, tuple[float, float]]) -> list[tuple[str, str]]:
    """Each point of ``points`` (name -> (x, y), m) that lies within :data:`COINCIDE` of an earlier one,
    as ``(earlier, later)``, in the order of the later.

    Near-linear: the points go into square cells of that size, and each is compared with the points of
    its own and the eight neighbouring cells only, until the first that it coincides with.
    """

    def cell(v: float) -> float:
        c = v / COINCIDE
        return math.floor(c) if math.isfinite(c) else v  # beyond 1e296 m a point coincides only with itself

    cells: dict[tuple[float, float], list[str]] = {}
    out = []
    for name, (x, y) in points.items():
        cx, cy = cell(x), cell(y)
        near = (p for dx in (-1, 0, 1) for dy in (-1, 0, 1) for p in cells.get((cx + dx, cy + dy), ()))
        first = next((p for p in near if math.hypot(points[p][0] - x, points[p][1] - y) < COINCIDE), None)
        if first is not None:
            out.append((first, name))
        cells.setdefault((cx, cy), []).append(name)
    return out


def _machine_checks(spec: Spec, src: Source) -> list[Problem]:
    """An induction motor's speeds and breakdown ratio, in SI."""
    motor = spec.machine.motor if spec.machine is not None else None
    if motor is None or motor.type != "induction":
        return []
    speed, synchronous, breakdown = motor.speed, motor.synchronous, motor.breakdown
    if speed is None or synchronous is None or breakdown is None:
        return []
    out = []
    path = ("machine", "motor")
    if not speed < synchronous:
        out.append(src.problem(path + ("speed",), "the rated speed must be below the synchronous speed"))
    if not breakdown > 1:
        out.append(src.problem(path + ("breakdown",), f"the breakdown torque ratio must exceed 1, got {breakdown}"))
    return out


def _load_checks(spec: Spec, src: Source) -> list[Problem]:
    """Values of the external loads in SI: tables that increase, a workpiece of positive height."""
    out = []
    first = spec.joints.get(spec.drives[0].joint) if spec.drives else None
    for name, load in spec.loads.items():
        path = ("loads", name)
        if load.angle is not None:
            if first is not None and first.type != "revolute":
                out.append(
                    src.problem(path + ("angle",), "a table against the crank angle needs a revolute first drive")
                )
            a = load.angle
            if any(y <= x for x, y in zip(a, a[1:], strict=False)):
                out.append(src.problem(path + ("angle",), "the crank angles of a table must increase"))
            elif a and a[-1] - a[0] > 2 * math.pi * (1 + 1e-12):
                span = math.degrees(a[-1] - a[0])
                out.append(src.problem(path + ("angle",), f"a table spans at most one turn, got {span:.6g} deg"))
        if load.type == "friction":
            for key in ("moment", "magnitude"):
                value = getattr(load, key)
                if isinstance(value, float) and value < 0:
                    out.append(src.problem(path + (key,), "a friction is given by its size, from 0 up"))
            continue
        if load.type != "process":
            continue
        if load.workpiece is not None and len(load.workpiece) == 2 and not load.workpiece[1] > load.workpiece[0]:
            out.append(src.problem(path + ("workpiece",), "expected [low, high] with high above low"))
        pen = load.penetration or []
        if any(not math.isfinite(x) or x < 0 for x in pen):
            out.append(src.problem(path + ("penetration",), "relative penetrations are numbers from 0 up"))
        elif any(y <= x for x, y in zip(pen, pen[1:], strict=False)):
            out.append(src.problem(path + ("penetration",), "the penetrations of a table must increase"))
    return out
