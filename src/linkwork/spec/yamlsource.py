"""Read a YAML mechanism file into plain data, remembering where each value is.

The file is composed into a node tree (not constructed), so every key and
value keeps its line, duplicate keys are reported instead of silently
overwritten, and YAML syntax errors become one :class:`Problem` with a line.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from ruamel.yaml import YAML
from ruamel.yaml.error import MarkedYAMLError, YAMLError
from ruamel.yaml.nodes import MappingNode, Node, ScalarNode, SequenceNode

from linkwork.errors import Problem

Path = tuple[str | int, ...]


@dataclass
class Source:
    """Plain data of a YAML document with the line of every element.

    Attributes
    ----------
    data : Any
        The document as dicts, lists, str, int, float, bool and None.
    lines : dict
        One-based line of each element, keyed by its path tuple; the line of
        a mapping entry is the line of its key.
    file : str or None
        The file name for messages.
    problems : list of Problem
        Duplicate keys found while reading.
    """

    data: Any
    lines: dict[Path, int] = field(default_factory=dict)
    file: str | None = None
    problems: list[Problem] = field(default_factory=list)

    def line(self, path: Path) -> int | None:
        """The line of ``path``, or of its nearest ancestor that has one."""
        path = tuple(path)
        while path:
            if path in self.lines:
                return self.lines[path]
            path = path[:-1]
        return self.lines.get((), None)

    def problem(self, path: Path, message: str) -> Problem:
        """A :class:`Problem` at ``path`` with this source's file and line."""
        return Problem(dotted(path), message, self.file, self.line(path))


def dotted(path: Path) -> str:
    """``('links', 'rod', 'length')`` -> ``'links.rod.length'``; list items as ``[i]``."""
    out = ""
    for part in path:
        if isinstance(part, int):
            out += f"[{part}]"
        else:
            out += ("." if out else "") + str(part)
    return out


def read_yaml(text: str, file: str | None = None) -> Source:
    """Parse YAML ``text``; syntax errors come back as a single problem.

    Returns
    -------
    Source
        ``data`` is None and ``problems`` holds the syntax error when the
        text is not valid YAML.
    """
    yaml = YAML(typ="rt")
    try:
        node = yaml.compose(text)
    except RecursionError:
        return Source(None, {}, file, [Problem("", "YAML nesting too deep", file, None)])
    except MarkedYAMLError as exc:
        scanning = exc.context is not None and "scanning" in exc.context
        mark = (exc.context_mark if scanning else None) or exc.problem_mark or exc.context_mark
        line = mark.line + 1 if mark is not None else None
        what = exc.problem or "invalid YAML"
        if exc.context:
            what = f"{exc.context}, {what}"
        return Source(None, {}, file, [Problem("", f"YAML syntax error: {what}", file, line)])
    except YAMLError as exc:
        return Source(None, {}, file, [Problem("", f"YAML syntax error: {exc}", file, None)])
    src = Source(None, {}, file, [])
    if node is None or (getattr(node, "tag", None) and str(getattr(node.tag, "value", node.tag)).endswith("null")):
        return Source(
            None,
            {},
            file,
            [Problem("", "the file is empty: a mechanism file is a mapping with links, joints and drives", file, 1)],
        )
    try:
        src.data = _build(node, (), src, 0)
    except RecursionError:
        return Source(
            None, {}, file, [Problem("", "YAML nesting too deep, or an alias that contains itself", file, None)]
        )
    return src


_TAG = "tag:yaml.org,2002:"


def _build(node: Node, path: Path, src: Source, depth: int) -> Any:
    """The plain data of ``node``, each element's line recorded in ``src`` and each duplicate key reported."""
    if depth > 64:
        raise RecursionError
    src.lines.setdefault(path, node.start_mark.line + 1)
    if isinstance(node, MappingNode):
        out: dict[str, Any] = {}
        seen: dict[str, int] = {}
        pairs: list[tuple[Any, Any]] = []
        n_merged = 0
        for key_node, value_node in node.value:
            tag = str(getattr(key_node.tag, "value", key_node.tag))
            if tag.endswith(":merge"):  # <<: {...} or <<: [*a, *b]: merged keys, which the mapping's own override
                merged = value_node.value if isinstance(value_node, SequenceNode) else [value_node]
                for m in merged:
                    if isinstance(m, MappingNode):
                        pairs[:0] = list(m.value)
                        n_merged += len(m.value)
                continue
            pairs.append((key_node, value_node))
        for n, (key_node, value_node) in enumerate(pairs):
            key = _scalar(key_node) if isinstance(key_node, ScalarNode) else None
            line = key_node.start_mark.line + 1
            if not isinstance(key, str | int | float) or isinstance(key, bool):
                src.problems.append(Problem(dotted(path), "keys must be names", src.file, line))
                continue
            key = str(key)
            if key in seen and n >= n_merged and seen[key] >= 0:
                src.problems.append(
                    Problem(
                        dotted(path + (key,)),
                        f'duplicate name "{key}" (first defined at line {seen[key]})',
                        src.file,
                        line,
                    )
                )
                continue
            seen[key] = line if n >= n_merged else -1
            src.lines[path + (key,)] = line
            out[key] = _build(value_node, path + (key,), src, depth + 1)
        return out
    if isinstance(node, SequenceNode):
        return [_build(item, path + (i,), src, depth + 1) for i, item in enumerate(node.value)]
    return _scalar(node)


def _scalar(node: Any) -> Any:
    tag = node.tag
    tag = getattr(tag, "value", tag)
    value = node.value
    if tag == _TAG + "null":
        return None
    if tag == _TAG + "bool":
        return value.lower() in ("true", "yes", "on")
    if tag == _TAG + "int":
        try:
            return int(value.replace("_", ""), 0)
        except ValueError:
            return value
    if tag == _TAG + "float":
        low = value.lower().replace("_", "")
        if low in (".inf", "+.inf"):
            return math.inf
        if low == "-.inf":
            return -math.inf
        if low == ".nan":
            return math.nan
        try:
            return float(low)
        except ValueError:
            return value
    return value
