"""Editing a mechanism file: values written into its text, its comments, layout and units kept.

The one writer of mechanism files, for edited, sized and synthesised ones alike.  What a named parameter is (its
path, kind and range) is :mod:`linkwork.structure.parameters`'s, which checks the values and calls here; this
module knows the file format only.
"""

from __future__ import annotations

import copy
import io
import re
from pathlib import Path
from typing import Any

from linkwork.atomic import write_atomic
from linkwork.errors import ParameterError
from linkwork.spec.reader import loads, plain, si_data, validate
from linkwork.spec.schema import Spec
from linkwork.spec.yamlsource import Source, read_yaml
from linkwork.units import DEFAULT_UNITS, si_factor, written

_NUMBER_AND_UNIT = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(\S.*)?$")


def set_values(data: Any, values: dict[str, float], declared: dict[str, str], kinds: dict[str, str]) -> None:
    """Write ``values`` (path -> SI) at their places in a mechanism file's data (a mapping as YAML
    loads it; a ruamel round-trip mapping keeps its comments and layout).

    Each value is written the way the file writes the one it replaces: a string with a unit in
    that unit (``"0.25 m"`` -> ``"0.3 m"``), a bare number as a bare number in the unit the file
    reads it in (its ``units:``).  A value the file leaves out (a moment of inertia left to its
    default) is written with its SI unit.  ``kinds``: path -> kind of quantity.

    Raises
    ------
    ParameterError
        Where the file has no place for a value (a point not given as ``[x, y]``).
    """
    for path, si in values.items():
        parts = path.split(".")
        kind = kinds[path]
        if parts[-1] in ("x", "y"):
            pair = _node(data, parts[:-1], path)
            if not isinstance(pair, list) or len(pair) != 2:
                raise ParameterError(f"{path}: the file does not give this point as [x, y]")
            c = 0 if parts[-1] == "x" else 1
            pair[c] = _written(pair[c], si, kind, declared)
        else:
            owner = _node(data, parts[:-1], path)
            owner[parts[-1]] = _written(owner.get(parts[-1]), si, kind, declared)


def _node(data: Any, keys: list[str], path: str) -> Any:
    node = data
    for key in keys:
        if not isinstance(node, dict) or key not in node:
            raise ParameterError(f"{path}: the file gives no such value")
        node = node[key]
    return node


def _written(old: Any, si: float, kind: str, declared: dict[str, str]) -> Any:
    """``si`` as the file would write it where it writes ``old``: in the unit of a string with a unit,
    else as :func:`linkwork.units.written` writes a value for the file (a bare number where the file
    reads one, else with its SI unit), 12 significant digits."""
    if isinstance(old, str):
        match = _NUMBER_AND_UNIT.match(old)
        if match is not None and match.group(2):
            unit = match.group(2).strip()
            return f"{si / si_factor(unit, kind):.12g} {unit}"
    return written(si, kind, declared, digits=12)


# --- an edited description ---------------------------------------------------------------------------


def with_values(spec: Spec, values: dict[str, float], kinds: dict[str, str]) -> Spec:
    """The description ``spec`` with ``values`` (path -> SI) written in, validated again: what a user gets who
    edits the file by hand.

    Parameters
    ----------
    spec : Spec
        The description as read (or built in code: then written in SI).
    values : dict
        Parameter path -> value in SI units.
    kinds : dict
        Parameter path -> kind of quantity (``"length"``, ``"mass"``...).

    Returns
    -------
    Spec
        The edited description.

    Raises
    ------
    ParameterError
        Where the file has no place for a value.
    SpecError
        The edited description fails validation (the file's message, with its line).
    """
    data, declared = _file_data(spec, round_trip=False)
    set_values(data, values, declared, kinds)
    src = spec.source
    return validate(Source(data, src.lines if src is not None else {}, src.file if src is not None else None, []))


def text_with_values(spec: Spec, values: dict[str, float], kinds: dict[str, str]) -> str:
    """The text of the file of ``spec`` with ``values`` (path -> SI; ``kinds``: path -> kind) written in: the text
    the description was read from (never the file on disk again, which may be another or have changed), its
    comments and layout kept, each value in the unit the file writes it in (:func:`set_values`).  A value
    in a mapping or list that the file shares through an anchor is written to this place alone.  The text
    is read back and must give the description with ``values`` written in (as :func:`with_values`); where
    the layout cannot say it, the file is written out plainly, anchors resolved.  A description built in
    code is written in SI.

    Raises
    ------
    ParameterError
        Where the file has no place for a value.
    """
    flat, declared = _file_data(spec, round_trip=False)
    set_values(flat, values, declared, kinds)
    data, _ = _file_data(spec, round_trip=True)
    if data is not flat:
        _unshare(data, values)
        set_values(data, values, declared, kinds)
        text = yaml_text(data)
        if read_yaml(text).data == flat:
            return text
    return yaml_text(flat)


def text_with_section(spec: Spec | None, key: str, values: dict[str, Any]) -> str:
    """The text of the file of ``spec`` with its top-level section ``key`` set to ``values``:
    where the file has the section, each value is written in its place (a mapping into a mapping, key by key, so
    the comments and layout of what stays are kept; a value None removes its key), else the section is added.
    The text is read back and must validate.

    Raises
    ------
    ParameterError
        A mechanism without its description (``spec`` None).
    SpecError
        The text written does not validate (the message of the file's check).
    """
    if spec is None:
        raise ParameterError(NO_FILE)
    data, _ = _file_data(spec, round_trip=True)
    _merge(data, key, values)
    text = yaml_text(data)
    original = spec.source.text if spec.source is not None else None
    spliced = _spliced(original, text, key) if original is not None else None
    text = spliced if spliced is not None and _reads_as(spliced, text) else text
    loads(text, spec.source.file if spec.source is not None else None)
    return text


def _spliced(original: str, written: str, key: str) -> str | None:
    """``original`` with its top-level section ``key`` replaced by (or, where it has none, followed by) that
    section as ``written`` has it: every byte outside the section as the file had it (the YAML writer moves a
    comment after an alias onto a line of its own); None where either is not a block mapping at the top."""
    spans = [_sections(t) for t in (original, written)]
    if spans[0] is None or spans[1] is None or key not in spans[1]:
        return None
    lines, new = original.splitlines(keepends=True), written.splitlines(keepends=True)
    a, b = spans[1][key]
    section = "".join(new[a:b])
    section += "" if section.endswith("\n") else "\n"
    if key in spans[0]:
        start, end = spans[0][key]
        return "".join(lines[:start]) + section + "".join(lines[end:])
    head = "".join(lines)
    return head + ("" if head.endswith("\n") or not head else "\n") + section


def _sections(text: str) -> dict[str, tuple[int, int]] | None:
    """The lines ``[start, end)`` of each top-level key's section of ``text`` (to the next key's line), or None
    where the top is not a block mapping whose keys start their lines."""
    data = round_trip_yaml().load(text)
    lc, fa = getattr(data, "lc", None), getattr(data, "fa", None)
    if not isinstance(data, dict) or lc is None or fa is None or fa.flow_style():
        return None
    starts = sorted((lc.key(k)[0], str(k)) for k in data)
    if any(lc.key(k)[1] != 0 for k in data):
        return None
    n = len(text.splitlines())
    return {k: (line, starts[i + 1][0] if i + 1 < len(starts) else n) for i, (line, k) in enumerate(starts)}


def _reads_as(text: str, written: str) -> bool:
    """Whether ``text`` holds the same data as ``written`` (a splice that changed nothing but comments)."""
    yaml = round_trip_yaml()
    return bool(plain(yaml.load(text)) == plain(yaml.load(written)))


#: Why a mechanism assembled in code has no file to edit.
NO_FILE = "this mechanism was assembled in code without a description: it has no file to edit"


def _merge(node: Any, key: str, value: Any) -> None:
    """Set ``node[key]`` to ``value``, a mapping into an existing mapping key by key; None removes the key."""
    if value is None:
        if key in node:
            del node[key]
        return
    old = node.get(key)
    if isinstance(value, dict) and isinstance(old, dict):
        for k, v in value.items():
            _merge(old, k, v)
        return
    node[key] = _pruned(value)


def _pruned(value: Any) -> Any:
    """``value`` with the keys whose value is None left out, at every depth."""
    if isinstance(value, dict):
        return {k: _pruned(v) for k, v in value.items() if v is not None}
    return value


def yaml_text(data: Any) -> str:
    """The text of a mechanism file's ``data`` (plain or a ruamel round-trip mapping, whose comments, order
    and flow style it keeps): the one YAML writer of mechanism files, for edited and synthesised ones alike."""
    buf = io.StringIO()
    round_trip_yaml().dump(data, buf)
    return buf.getvalue()


def _unshare(data: Any, values: dict[str, float]) -> None:
    """Make every mapping and list on the paths of ``values`` this place's own in a round-trip tree: an alias
    (the same node at another place) is replaced here by a copy, and a mapping that merges (``<<:``) a
    mapping written to keeps the value it inherits as its own."""
    uses: dict[int, int] = {}
    _count(data, uses)
    for path in values:
        parts = path.split(".")
        keys = parts[:-1] if parts[-1] in ("x", "y") else parts
        node = data
        for i, key in enumerate(keys):
            if not isinstance(node, dict) or key not in node:
                break
            child = node[key]
            shared = isinstance(child, dict | list) and uses.get(id(child), 0) > 1
            if shared or i == len(keys) - 1:
                _pin(node, key)
            if shared:
                child = copy.deepcopy(child)
                node[key] = child
            node = child


def _pin(node: Any, key: str) -> None:
    """Each mapping that merges ``node`` (``<<:``) and inherits its ``key`` holds a copy of it as its own."""
    for heir in getattr(node, "_ref", ()):
        if key in heir and key not in getattr(heir, "_ok", {key}):
            heir[key] = copy.deepcopy(heir[key])


def _count(node: Any, uses: dict[int, int]) -> None:
    """How many places of the tree hold each mapping and list (an anchored one, more than one)."""
    if not isinstance(node, dict | list):
        return
    uses[id(node)] = uses.get(id(node), 0) + 1
    if uses[id(node)] == 1:
        for child in node.values() if isinstance(node, dict) else node:
            _count(child, uses)


def write_text(text: str, out: str | Path) -> Path:
    """Write a mechanism file's ``text`` (:func:`text_with_values`, :func:`text_with_section`) to ``out``, atomically.

    Returns
    -------
    Path
        The path written.
    """
    return write_atomic(out, lambda tmp: tmp.write_text(text, encoding="utf-8"))


def _file_data(spec: Spec, round_trip: bool) -> tuple[Any, dict[str, str]]:
    """The description's data to write values into, and the units bare numbers are read in: the file
    as written (a ruamel round-trip tree for ``round_trip``, else a deep copy of the loaded data);
    for a description built in code, its values in SI."""
    text = spec.source.text if round_trip and spec.source is not None else None
    if text is not None:
        data = round_trip_yaml().load(text)
    elif spec.source is not None and isinstance(spec.source.data, dict):
        data = copy.deepcopy(spec.source.data)
    else:
        data = si_data(spec)
    units = data.get("units") if isinstance(data, dict) else None
    return data, {**DEFAULT_UNITS, **(dict(units) if isinstance(units, dict) else {})}


def round_trip_yaml() -> Any:
    """The YAML reader and writer of mechanism files that keeps comments, order and flow style (ruamel's round
    trip): quotes kept, long flow mappings not folded, mappings indented by 2 and sequences by 4.

    Returns
    -------
    ruamel.yaml.YAML
        A fresh reader and writer (``load(text)``, ``dump(data, stream)``).
    """
    from ruamel.yaml import YAML

    yaml = YAML()  # round trip: comments, order and flow style kept
    yaml.preserve_quotes = True
    yaml.width = 4096  # no folding of long flow mappings
    yaml.indent(mapping=2, sequence=4, offset=2)
    return yaml
