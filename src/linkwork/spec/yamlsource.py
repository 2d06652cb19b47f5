"""Read a YAML mechanism file into plain data, remembering where each value is.

The file is composed into a node tree (not constructed), so every key and
value keeps its line, duplicate keys are reported instead of silently
overwritten, and YAML syntax errors become one :class:`Problem` with a line.

What a file may hold is bounded (:mod:`linkwork.limits`): its size, the
number of values it expands to (aliases counted each time they are used, so
that a file of nested aliases cannot grow without end), their nesting and
the length of a name; a text that is not Unicode (a lone surrogate) is
refused where it is.
"""

from __future__ import annotations

import math
import os
import re
import stat
from dataclasses import dataclass, field
from typing import Any

from ruamel.yaml import YAML
from ruamel.yaml.composer import Composer
from ruamel.yaml.error import MarkedYAMLError, YAMLError
from ruamel.yaml.nodes import MappingNode, Node, ScalarNode, SequenceNode

from linkwork.errors import Problem, SpecError
from linkwork.limits import MAX_DEPTH, MAX_FILE_BYTES, MAX_LINE, MAX_NAME, MAX_NODES, QUOTE, quote

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
    keys : list of str
        The keys of the document's mapping as written, those refused (a name too long) included.
    text : str or None
        The YAML text the data was read from (None for data given as such): what a file written back
        from this description edits, whatever the file on disk holds now.
    """

    data: Any
    lines: dict[Path, int] = field(default_factory=dict)
    file: str | None = None
    problems: list[Problem] = field(default_factory=list)
    keys: list[str] = field(default_factory=list)
    text: str | None = None

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


def read_file(path: str | os.PathLike[str]) -> str:
    """The text of the mechanism file ``path``: a regular file (or a pipe) of at most
    :data:`~linkwork.limits.MAX_FILE_BYTES`, in UTF-8.

    A device, a folder or a socket is refused without reading it, a file too large as soon as that is
    known, and a named pipe that no program writes to reads as empty (it does not wait for one).

    Raises
    ------
    SpecError
        One problem that says why the file cannot be read.
    """
    name = os.fspath(path)
    try:
        fd = os.open(name, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0))
    except OSError as exc:
        raise SpecError([Problem("", f"cannot read the file: {exc.strerror or exc}", name)]) from None
    try:
        data = _read_bounded(fd, name)
    except OSError as exc:  # EIO of /proc/self/mem, EINVAL of /proc/self/pagemap, a failing disk
        raise SpecError([Problem("", f"cannot read the file: {exc.strerror or exc}", name)]) from None
    finally:
        os.close(fd)
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        why = f"it is not UTF-8 text (byte 0x{data[exc.start]:02x} at offset {exc.start:,})"
        raise SpecError([Problem("", f"cannot read the file: {why}", name, line)]) from None


def _read_bounded(fd: int, name: str) -> bytes:
    """At most :data:`~linkwork.limits.MAX_FILE_BYTES` bytes of the open file ``fd``; SpecError beyond,
    or where it is not a regular file or a pipe."""
    info = os.fstat(fd)
    kinds = {stat.S_ISDIR: "a folder", stat.S_ISCHR: "a character device", stat.S_ISBLK: "a block device"}
    kinds[stat.S_ISSOCK] = "a socket"
    what = next((text for test, text in kinds.items() if test(info.st_mode)), None)
    if what is not None or not (stat.S_ISREG(info.st_mode) or stat.S_ISFIFO(info.st_mode)):
        raise SpecError([Problem("", f"cannot read the file: it is {what or 'not a regular file'}", name)])
    if stat.S_ISFIFO(info.st_mode):
        os.set_blocking(fd, True)  # opened without waiting for a writer; now read what one writes
    why = f"the file is larger than {_mib(MAX_FILE_BYTES)}, the most a mechanism file may be"
    too_large = SpecError([Problem("", why, name)])
    if info.st_size > MAX_FILE_BYTES:
        raise too_large
    chunks: list[bytes] = []
    size = 0
    while size <= MAX_FILE_BYTES:
        chunk = os.read(fd, MAX_FILE_BYTES + 1 - size)
        if not chunk:
            return b"".join(chunks)
        chunks.append(chunk)
        size += len(chunk)
    raise too_large


def _mib(n: int) -> str:
    return f"{n / (1 << 20):g} MiB ({n:,} bytes)"


class _Composer(Composer):
    """ruamel's composer, counting the values it composes (aliases included) and their nesting, within
    the bounds of :mod:`linkwork.limits`."""

    count = 0

    def compose_node(self, parent: Any, index: Any) -> Any:
        self.count += 1
        if self.count > MAX_NODES or self.depth >= MAX_DEPTH:
            raise _Bound(self.parser.peek_event().start_mark.line + 1, self.count > MAX_NODES)
        return super().compose_node(parent, index)


class _Bound(Exception):
    """A bound of the file passed at ``line``: the number of values (``many``) or their nesting."""

    def __init__(self, line: int | None, many: bool):
        super().__init__(line, many)
        self.line, self.many = line, many

    def problem(self, file: str | None) -> Problem:
        if self.many:
            why = (
                f"the file holds more than {MAX_NODES:,} values (keys, list items and numbers, aliases counted "
                "each time they are used): more than any mechanism needs"
            )
        else:
            why = f"YAML nesting too deep (more than {MAX_DEPTH} levels), or an alias that contains itself"
        return Problem("", why, file, self.line)


def read_yaml(text: str, file: str | None = None) -> Source:
    """Parse YAML ``text``; syntax errors and bounds passed come back as a single problem.

    Returns
    -------
    Source
        ``data`` is None and ``problems`` holds the syntax error when the
        text is not valid YAML, is larger than :data:`~linkwork.limits.MAX_FILE_BYTES`,
        has a line longer than :data:`~linkwork.limits.MAX_LINE` or holds more than
        :data:`~linkwork.limits.MAX_NODES` values.
    """
    if len(text) > MAX_FILE_BYTES:
        why = f"the text is longer than {MAX_FILE_BYTES:,} characters, the most a mechanism file may be"
        return Source(None, {}, file, [Problem("", why, file, None)])
    long = next((n for n, line in enumerate(text.split("\n"), 1) if len(line) > MAX_LINE), None)
    if long is not None:  # the YAML scanner takes time that grows faster than the length of a long comment
        why = f"a line longer than {MAX_LINE:,} characters: write a long list over several lines"
        return Source(None, {}, file, [Problem("", why, file, long)])
    node, problem = _compose(text, file)
    if problem is not None:
        return Source(None, {}, file, [problem])
    src = Source(None, {}, file, [], text=text)
    if node is None or (getattr(node, "tag", None) and str(getattr(node.tag, "value", node.tag)).endswith("null")):
        return Source(
            None,
            {},
            file,
            [Problem("", "the file is empty: a mechanism file is a mapping with links, joints and drives", file, 1)],
        )
    try:
        src.data = _build(node, (), src, 0, [0])
    except _Bound as exc:
        return Source(None, {}, file, [exc.problem(file)])
    return src


def _compose(text: str, file: str | None) -> tuple[Node | None, Problem | None]:
    """The node tree of ``text``, or the one problem that keeps it from being composed."""
    yaml = YAML(typ="rt")
    yaml.Composer = _Composer
    try:
        return yaml.compose(text), None
    except _Bound as exc:
        return None, exc.problem(file)
    except RecursionError:
        return None, Problem("", "YAML nesting too deep", file, None)
    except MarkedYAMLError as exc:
        scanning = exc.context is not None and "scanning" in exc.context
        mark = (exc.context_mark if scanning else None) or exc.problem_mark or exc.context_mark
        line = mark.line + 1 if mark is not None else None
        what = exc.problem or "invalid YAML"
        if exc.context:
            what = f"{exc.context}, {what}"
        return None, Problem("", f"YAML syntax error: {_cut(what)}", file, line)
    except YAMLError as exc:
        return None, Problem("", f"YAML syntax error: {_cut(str(exc))}", file, None)


def _cut(text: str) -> str:
    """A parser's message, which may quote the file, cut to a few excerpts' length."""
    return text if len(text) <= 3 * QUOTE else text[: 3 * QUOTE] + "..."


_TAG = "tag:yaml.org,2002:"

#: A code point of UTF-16's surrogates, which is no character: a YAML escape like "\ud800" can make one.
_SURROGATE = re.compile("[\ud800-\udfff]")


def _build(node: Node, path: Path, src: Source, depth: int, count: list[int]) -> Any:
    """The plain data of ``node``, each element's line recorded in ``src`` and each duplicate key reported;
    ``count`` holds the number of values built so far (an alias's each time it is used)."""
    count[0] += 1
    if depth > MAX_DEPTH or count[0] > MAX_NODES:
        raise _Bound(node.start_mark.line + 1, count[0] > MAX_NODES)
    src.lines.setdefault(path, node.start_mark.line + 1)
    if isinstance(node, MappingNode):
        out: dict[str, Any] = {}
        seen: dict[str, int] = {}
        merged, own = _pairs(node, count, depth)
        n_merged = len(merged)
        for n, (key_node, value_node) in enumerate(merged + own):
            key = _scalar(key_node, src) if isinstance(key_node, ScalarNode) else None
            line = key_node.start_mark.line + 1
            if not isinstance(key, str | int | float) or isinstance(key, bool):
                src.problems.append(Problem(dotted(path), "keys must be names", src.file, line))
                continue
            key = str(key)
            if not path:
                src.keys.append(key)
            if len(key) > MAX_NAME:
                why = f"a name of {len(key):,} characters, {quote(key)}: names are at most {MAX_NAME} characters"
                src.problems.append(Problem(dotted(path), why, src.file, line))
                continue
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
            out[key] = _build(value_node, path + (key,), src, depth + 1, count)
        return out
    if isinstance(node, SequenceNode):
        return [_build(item, path + (i,), src, depth + 1, count) for i, item in enumerate(node.value)]
    return _scalar(node, src)


def _pairs(node: MappingNode, count: list[int], depth: int) -> tuple[list[Any], list[Any]]:
    """The (key, value) nodes of a mapping: those it merges (``<<: *a`` or ``<<: [*a, *b]``, the merged mappings'
    own merges resolved too; an earlier one overriding a later), and its own (overriding both).  Each merged
    mapping and each merged key counts as a value against :data:`~linkwork.limits.MAX_NODES`, as each use of
    an alias does, and merges nest at most :data:`~linkwork.limits.MAX_DEPTH` deep."""
    own, sources = [], []
    for key_node, value_node in node.value:
        if str(getattr(key_node.tag, "value", key_node.tag)).endswith(":merge"):
            found = value_node.value if isinstance(value_node, SequenceNode) else [value_node]
            sources += [m for m in found if isinstance(m, MappingNode)]
        else:
            own.append((key_node, value_node))
    merged: list[Any] = []
    for m in reversed(sources):
        if depth >= MAX_DEPTH:
            raise _Bound(m.start_mark.line + 1, False)
        inner, inner_own = _pairs(m, count, depth + 1)
        count[0] += 1 + len(inner_own)
        if count[0] > MAX_NODES:
            raise _Bound(m.start_mark.line + 1, True)
        merged += inner + inner_own
    return merged, own


def _scalar(node: Any, src: Source) -> Any:
    """The value of a scalar node: None, a bool, an int, a float or a string (one with a surrogate
    reported in ``src`` and its surrogates replaced by U+FFFD)."""
    tag = node.tag
    tag = getattr(tag, "value", tag)
    value = node.value
    found = _SURROGATE.search(value) if isinstance(value, str) else None
    if found is not None:
        why = f"not Unicode text: {quote(value)} holds the lone surrogate {found.group()!a}, which is no character"
        src.problems.append(Problem("", why, src.file, node.start_mark.line + 1))
        return _SURROGATE.sub("\ufffd", value)
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
