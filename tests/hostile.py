"""Hostile input for the command line: mechanism files mutated from the bundled examples, options at
and past their bounds, and a runner that holds each case to a time and a memory bound.

A case is a command line (``["check", FILE, "--json"]``) and, for a mutated file, its text.  Each must
end in exit code 0, or 2 with a message of short lines on stderr (no traceback), within its time; a
``--json`` output that exits 0 must parse with a strict parser (no NaN or infinities, valid Unicode).

The mutations, each drawn from a seeded random generator so that a case is the same on every run:
types (a value replaced by a list, a mapping, a string, a truth value, nothing), missing and extra keys,
renamed names, huge, tiny and non-finite numbers, one-element and empty lists, unicode (Cyrillic, control
characters, a lone surrogate, right-to-left marks), sizes (many links, long names and values, deep
nesting, long lines, large files), and YAML itself (alias bombs, self-referencing aliases, merge keys,
tags, several documents, tabs, a byte-order mark, bytes that are not UTF-8); unit expressions that explode
(``m^9^9^9``), fields of loads, the machine, the impact and the drives left empty or given absurd magnitudes,
names and descriptions with control characters (no output may print one raw).  Beside the mutated files:
files whose read fails and digits of other scripts among the options, merge-key bombs, hostile surroundings
(standard output on ``/dev/full``, ``MPLBACKEND=bogus``), files whose links share an anchor to be written back
(:func:`shared`) and sweep parts that are no files (:func:`make_odd`).
"""

from __future__ import annotations

import contextlib
import copy
import functools
import json
import math
import os
import random
import re
import resource
import signal
import subprocess
import sys
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ruamel.yaml import YAML
from typer.testing import CliRunner

import linkwork
from hostile_synthesis import synthesis_argvs
from linkwork.examples import names, text
from linkwork.limits import MAX_ANGLES, MAX_BLOWS, MAX_FILE_BYTES, MAX_NAME, MAX_NODES, MAX_SEED, MAX_VARIANTS

#: Seconds a case may take (a generous bound for a loaded machine, and for the first run of the compiled
#: kernels, which compiles them; most cases take 0.1 s).
TIME_LIMIT = 120.0

#: Bytes of address space a case run in a subprocess may take.
MEMORY_LIMIT = 3 << 30

#: Characters of a line of a message (the messages quote at most a short excerpt of what they were given).
LINE_LIMIT = 600


@dataclass(frozen=True)
class Case:
    """One command line; ``files`` are written to the case's folder first, and ``{dir}`` in ``argv`` is
    that folder."""

    name: str
    argv: tuple[str, ...]
    files: dict[str, str | bytes] = field(default_factory=dict)
    env: tuple[tuple[str, str], ...] = ()  # set for the command (a case with them runs in its own process)
    full: bool = False  # standard output is /dev/full, where no write succeeds

    def args(self, folder: Path) -> list[str]:
        return [a.replace("{dir}", str(folder)) for a in self.argv]

    def write(self, folder: Path) -> None:
        for name, content in self.files.items():
            path = folder / name
            if isinstance(content, bytes):
                path.write_bytes(content)
            else:
                path.write_text(content, encoding="utf-8", errors="surrogatepass")


@dataclass(frozen=True)
class Outcome:
    code: int | None
    stdout: str
    stderr: str
    seconds: float
    crash: str | None = None  # a traceback, a time or memory bound passed


# ---------------------------------------------------------------- mutated files


def _base(name: str) -> dict[str, Any]:
    """The bundled example ``name`` as plain data, a copy of its own to mutate."""
    return copy.deepcopy(_read(name))


@functools.cache
def _read(name: str) -> dict[str, Any]:
    return YAML(typ="safe").load(text(name))


_INF = "__LINKWORK_INF__"


def to_yaml(data: Any) -> str:
    """``data`` as YAML text (JSON with YAML's spelling of infinities and NaN; ``\\u`` escapes for
    everything that is not ASCII, so a lone surrogate reaches the YAML reader as the escape a file
    would hold)."""

    def mark(x: Any) -> Any:
        if isinstance(x, float) and not math.isfinite(x):
            return f"{_INF}{'nan' if math.isnan(x) else ('-' if x < 0 else '+')}"
        if isinstance(x, dict):
            return {str(k): mark(v) for k, v in x.items()}
        if isinstance(x, list):
            return [mark(v) for v in x]
        return x

    out = json.dumps(mark(data), indent=1, ensure_ascii=True)
    return out.replace(f'"{_INF}nan"', ".nan").replace(f'"{_INF}+"', ".inf").replace(f'"{_INF}-"', "-.inf")


def _nodes(data: Any, path: tuple[Any, ...] = ()) -> Iterator[tuple[tuple[Any, ...], Any]]:
    """Every (path, value) of the tree, the root first."""
    yield path, data
    if isinstance(data, dict):
        for k, v in data.items():
            yield from _nodes(v, path + (k,))
    elif isinstance(data, list):
        for i, v in enumerate(data):
            yield from _nodes(v, path + (i,))


def _set(data: Any, path: tuple[Any, ...], value: Any) -> Any:
    if not path:
        return value
    parent = data
    for p in path[:-1]:
        parent = parent[p]
    parent[path[-1]] = value
    return data


#: Values a scalar is replaced by.
HOSTILE_VALUES: list[Any] = [
    None,
    True,
    False,
    0,
    -1,
    1,
    0.0,
    -0.0,
    1e308,
    -1e308,
    1e-308,
    5e-324,
    10**400,
    -(10**30),
    math.inf,
    -math.inf,
    math.nan,
    "",
    " ",
    "0",
    "-0",
    "1e400 mm",
    "1e-400 mm",
    "nan mm",
    "inf m",
    "100 kg",
    "12 furlongs",
    "100 mm mm",
    "1/0 mm",
    "10**10**10 mm",
    "100mm",
    "0x10 mm",
    "1_000 mm",
    "30 rpm",
    "30 Hz",
    "-5 deg",
    "2 kg*m^2",
    "kg",
    "m" + " " * 300 + "!",
    "1" * 400 + "!",
    "кривошип",
    "O\u0301",
    "\u202eevil",
    "a\u200bb",
    "\x1b[31mred",
    "tab\there",
    "new\nline",
    "a\ud800b",
    "😀",
    "x" * (MAX_NAME + 1),
    "y" * 5000,
    [],
    [1],
    [1, 2, 3],
    [[1, 2]],
    {},
    {"x": 1},
    [None],
    ["a", "b"],
]


def _retype(rng: random.Random, data: Any) -> str:
    paths = [p for p, _ in _nodes(data) if p]
    path = rng.choice(paths)
    value = rng.choice(HOSTILE_VALUES)
    _set(data, path, copy.deepcopy(value))
    return f"{'.'.join(map(str, path))}={value!r:.30}"


def _drop(rng: random.Random, data: Any) -> str:
    maps = [(p, v) for p, v in _nodes(data) if isinstance(v, dict) and v]
    path, mapping = rng.choice(maps)
    key = rng.choice(list(mapping))
    del mapping[key]
    return f"drop {'.'.join(map(str, path + (key,)))}"


_KEYS = [
    "name",
    "links",
    "joints",
    "drives",
    "frame",
    "points",
    "ends",
    "length",
    "mass",
    "type",
    "angle",
    "speed",
    "loads",
    "machine",
    "impact",
    "hints",
    "units",
    "lenght",
    "Links",
    "",
    "0",
    "<<",
    "x" * 300,
]


def _extra(rng: random.Random, data: Any) -> str:
    maps = [(p, v) for p, v in _nodes(data) if isinstance(v, dict)]
    path, mapping = rng.choice(maps)
    key = rng.choice(_KEYS)
    mapping[key] = copy.deepcopy(rng.choice(HOSTILE_VALUES))
    return f"extra {'.'.join(map(str, path + (key,)))}"


def _one_element(rng: random.Random, data: Any) -> str:
    lists = [(p, v) for p, v in _nodes(data) if isinstance(v, list) and v]
    if not lists:
        return _retype(rng, data)
    path, items = rng.choice(lists)
    keep = items[:1] if rng.random() < 0.7 else []
    _set(data, path, keep)
    return f"{'.'.join(map(str, path))} -> {len(keep)} items"


def _numbers(rng: random.Random, data: Any) -> str:
    nums = [p for p, v in _nodes(data) if isinstance(v, int | float) and not isinstance(v, bool)]
    if not nums:
        return _retype(rng, data)
    path = rng.choice(nums)
    value = rng.choice([1e308, -1e308, 1e-300, -1e-300, 5e-324, math.inf, -math.inf, math.nan, 10**30, 0, -0.0])
    _set(data, path, value)
    return f"{'.'.join(map(str, path))}={value!r}"


def _rename(rng: random.Random, data: Any) -> str:
    maps = [(p, v) for p, v in _nodes(data) if isinstance(v, dict) and v and p and p[-1] in ("links", "joints")]
    if not maps:
        return _drop(rng, data)
    path, mapping = rng.choice(maps)
    old = rng.choice(list(mapping))
    new = rng.choice(["frame", "crank", old + "_", old.upper(), "кривошип", "a.b", "1st", "x" * 90, "a\ud800"])
    mapping[new] = mapping.pop(old)
    return f"rename {old} -> {new!r:.20}"


#: Names a string is replaced by: Cyrillic, right-to-left and zero-width marks, control characters, lone
#: surrogates, emoji, a byte-order mark.
UNICODE_NAMES = ["кривошип", "\u202e" + "O2", "O2\u200d", "\x00", "\x07bell", "a\ud800", "\udfff", "😀😀", "\ufeff"]


def _unicode(rng: random.Random, data: Any) -> str:
    strs = [p for p, v in _nodes(data) if isinstance(v, str)]
    if not strs:
        return _retype(rng, data)
    path = rng.choice(strs)
    value = rng.choice(UNICODE_NAMES)
    _set(data, path, value)
    return f"{'.'.join(map(str, path))}={value!r}"


def _grow(rng: random.Random, data: Any) -> str:
    """Many links, points or joints (still within the bounds of a file)."""
    links = data.get("links") if isinstance(data, dict) else None
    if not isinstance(links, dict) or not links:
        return _extra(rng, data)
    first = next(iter(links))
    n = rng.choice([50, 500, 3000])
    if rng.random() < 0.5:
        for i in range(n):
            links[f"{first}_{i}"] = copy.deepcopy(links[first])
        return f"{n} copies of {first}"
    link = links[first]
    if isinstance(link, dict):
        link["points"] = {f"P{i}": [i * 0.001, rng.choice([0, 1e-13, 1])] for i in range(n)}
    return f"{n} points on {first}"


#: Unit expressions that explode when evaluated (a power of a power), or give a number beyond any bound.
EXPLODING_UNITS = [
    "1 m^9^9^9",
    "1 mm**9**9",
    "2 kg*m^-9^9",
    "1 m ^ 9 ^ 9",
    "1e308 m^9",
    "1e300 km",
    "1 m" + "*m" * 40,
    "1 m^99",
    "3 kN*m^2^2",
    "1e-320 mm",
    "1 mm/s^9^9",
    "9" * 300 + " mm",
    "1 rpm^9^9",
    "1 kW**9**9**9",
]


def _explode(rng: random.Random, data: Any) -> str:
    """A quantity (a number, or a string with a unit) written as a unit expression that explodes."""
    spots = [p for p, v in _nodes(data) if p and (isinstance(v, int | float | str) and not isinstance(v, bool))]
    spots = [p for p in spots if not isinstance(p[-1], str) or p[-1] not in ("name", "description", "type")]
    if not spots:
        return _retype(rng, data)
    path = rng.choice(spots)
    value = rng.choice(EXPLODING_UNITS)
    _set(data, path, value)
    return f"{'.'.join(map(str, path))}={value!r:.30}"


#: The sections whose objects later stages read field by field.
_OBJECTS = ("loads", "machine", "impact", "drives", "drawing")

#: Values beyond what validation lets through: none at all, infinite, or out of all proportion.
ABSURD = [
    None,
    None,
    {},
    [],
    math.inf,
    -math.inf,
    math.nan,
    1e300,
    -1e300,
    1e10,
    1e-300,
    "1e300 rpm",
    "1e12 kN",
    "1e300 kW",
    "1e300 kg*m^2",
    "-1e300 N*m",
    10**400,
]


def _empty(rng: random.Random, data: Any) -> str:
    """A field of an object of :data:`_OBJECTS` (a process load's axis, a motor's breakdown, a gear's ratio,
    the impact's friction, a drive's speed) left empty or given an absurd magnitude."""
    spots = [p for p, _ in _nodes(data) if len(p) >= 2 and p[0] in _OBJECTS]
    if not spots:
        return _numbers(rng, data)
    path = rng.choice(spots)
    value = rng.choice(ABSURD)
    _set(data, path, copy.deepcopy(value))
    return f"{'.'.join(map(str, path))}={value!r:.30}"


#: Text a terminal would act on: retitle the window, ring, clear the screen, move the cursor, reset.
CONTROL_TEXTS = [
    "\x1b]0;owned\x07\x1b[2J",
    "\x1b[31mred\x1b[0m",
    "a\rb",
    "\x9b2J",
    "\x08\x08\x08x",
    "\x1bc",
    "\x7f",
    "\x1b]8;;http://x\x1b\\link\x1b]8;;\x1b\\",
    "\x1b[?1049h",
    "\x00",
]


def _controls(rng: random.Random, data: Any) -> str:
    """The mechanism's name, its description or a load's, or a unit, holding control characters."""
    spots = [p for p, v in _nodes(data) if p and isinstance(v, str)]
    named = [p for p in spots if p[-1] in ("name", "description")] or [("name",)]
    path = rng.choice(named if rng.random() < 0.7 else spots or named)
    value = rng.choice(CONTROL_TEXTS)
    if isinstance(data, dict):
        _set(data, path, value if rng.random() < 0.5 else f"{_get(data, path)}{value}")
    return f"{'.'.join(map(str, path))} += {value!r:.30}"


def _get(data: Any, path: tuple[Any, ...]) -> Any:
    for p in path:
        data = data[p] if isinstance(data, dict | list) and (isinstance(data, list) or p in data) else ""
    return data if isinstance(data, str) else ""


MUTATIONS: list[Callable[[random.Random, Any], str]] = [
    _retype,
    _retype,
    _retype,
    _drop,
    _drop,
    _extra,
    _one_element,
    _numbers,
    _numbers,
    _rename,
    _unicode,
    _grow,
]

#: The kinds found by the second campaign, drawn on their own (the seeds of :data:`MUTATIONS` stay as they were).
FRESH_MUTATIONS: list[Callable[[random.Random, Any], str]] = [_explode, _empty, _empty, _controls]


def mutated(seed: int, fresh: bool = False) -> tuple[str, str]:
    """A bundled example with one to three mutations (of :data:`FRESH_MUTATIONS` where ``fresh``):
    ``(description, YAML text)``."""
    rng = random.Random(seed)
    name = rng.choice(names())
    data = _base(name)
    kinds = FRESH_MUTATIONS if fresh else MUTATIONS
    what = [kinds[rng.randrange(len(kinds))](rng, data) for _ in range(rng.choice([1, 1, 2, 3]))]
    return f"{name}: {'; '.join(what)}", to_yaml(data)


def _nested(depth: int) -> str:
    return "name: x\nlinks: " + "[" * depth + "]" * depth + "\n"


def merges(keys: int, width: int, levels: int) -> str:
    """A mapping of ``keys`` keys, then ``levels - 1`` mappings that each merge the one before ``width`` times
    (``<<: [*a, *a, ...]``): ``keys * width ** (levels - 1)`` merged keys from a few kilobytes."""
    lines = ["a0: &a0 {" + ", ".join(f"k{i}: {i}" for i in range(keys)) + "}"]
    lines += [f"a{i}: &a{i} {{<<: [{', '.join([f'*a{i - 1}'] * width)}]}}" for i in range(1, levels)]
    return "\n".join(lines) + "\n"


def _laughs(levels: int, width: int) -> str:
    lines = ["name: bomb", f"a0: &a0 [{', '.join(['lol'] * width)}]"]
    lines += [f"a{i}: &a{i} [{', '.join([f'*a{i - 1}'] * width)}]" for i in range(1, levels)]
    return "\n".join(lines) + "\n"


#: YAML attacks that take seconds each (many values composed before a bound stops them): the slow run only.
SLOW_YAML = {"many-nodes", "laughs-in-links", "markers-3000", "big-table", "merge-wide"}


@functools.cache
def yaml_cases() -> dict[str, str | bytes]:
    """Texts that attack the YAML reader itself, by name."""
    four = text("four-bar")
    big_table = four + "loads:\n  m: {type: moment, on: rocker, moment: [" + ", ".join(["1"] * 2000) + "],\n"
    big_table += "      angle: [" + ", ".join(f"{i * 0.1:.1f}" for i in range(2000)) + "]}\n"
    return {
        "laughs-9x9": _laughs(9, 9),
        "laughs-30x2": _laughs(30, 2),
        "laughs-in-links": four.replace(
            "links:",
            "bomb: &b0 [x, x, x, x, x, x, x, x]\n"
            + "\n".join(f"bomb{i}: &b{i} [{', '.join([f'*b{i - 1}'] * 8)}]" for i in range(1, 9))
            + "\nlinks:",
            1,
        ),
        "merge-bomb": "a0: &a0 {k: 1}\n"
        + "\n".join(f"a{i}: &a{i} {{<<: [{', '.join([f'*a{i - 1}'] * 8)}]}}" for i in range(1, 9))
        + "\n",
        "merge-wide": merges(5000, 2000, 3),
        "merge-empty": merges(0, 60, 6),
        "merge-in-links": four.replace("links:", merges(300, 300, 3) + "links:", 1),
        "merge-self": "a: &a {k: 1, <<: *a}\n",
        "self-alias": "a: &a [*a]\nb: &b {x: *b}\n",
        "undefined-alias": "a: *nothing\n",
        "deep-flow": _nested(10_000),
        "deep-block": "".join("  " * i + f"k{i}:\n" for i in range(200)) + "  " * 200 + "v\n",
        "long-line": "name: x\n# " + "c" * 2_000_000 + "\n",
        "long-comment-below-line-bound": "name: x\n# " + "c" * 99_000 + "\n" + four,
        "many-nodes": "name: x\nk:\n" + "- 1\n" * (MAX_NODES + 10),
        "large": "name: x\n" + "".join(f"k{i}: [1, 2, 3]\n" for i in range(110_000)),
        "just-over-size": "#" * (MAX_FILE_BYTES + 1),
        "many-documents": four + "---\n" + four,
        "tags": four.replace("name: four-bar", "name: !!python/object:os.system ls"),
        "binary-tag": four.replace("name: four-bar", "name: !!binary aGVsbG8="),
        "set-tag": four.replace("hints:", "hints: !!set {a, b}\nhints2:"),
        "tabs": four.replace("  ", "\t"),
        "bom": "\ufeff" + four,
        "crlf": four.replace("\n", "\r\n"),
        "nul": four.replace("name: four-bar", "name: four\x00bar"),
        "not-utf8": four.encode("utf-8").replace(b"four-bar", b"four\xff\xfebar"),
        "latin1": "name: caf\xe9\n".encode("latin-1"),
        "utf16": four.encode("utf-16"),
        "surrogate-key": four.replace("O2: [0, 0]", '"O\\ud800": [0, 0]'),
        "surrogate-name": four.replace("name: four-bar", 'name: "a\\udc80b"'),
        "shadow": "".join(f"user{i}:*:20228:0:99999:7:::\n" for i in range(40)),
        "passwd": "".join(f"user{i}:x:{i}:{i}:User {i}:/home/user{i}:/bin/sh\n" for i in range(40)),
        "scalar": "just a line of text\n",
        "list": "- a\n- b\n",
        "empty": "",
        "only-comments": "# nothing\n",
        "null": "~\n",
        "key-20k": "name: x\n" + "k" * 20_000 + ": 1\n",
        "value-20k": four.replace("length: 100", 'length: "' + "1" * 20_000 + '!"', 1),
        "unit-20k": four.replace("length: 100", 'length: "1 m' + " " * 20_000 + '!"', 1),
        "number-20k": four.replace("length: 100", "length: " + "9" * 20_000, 1),
        "float-20k": four.replace("length: 100", "length: 0." + "9" * 20_000, 1),
        "duplicate-keys": four.replace("links:", "links: {}\nlinks:", 1),
        "big-table": big_table,
        "markers-3000": four.replace(
            "points: {M: [175, 80]}",
            "points: {M: [175, 80], " + ", ".join(f"P{i}: [{i}, 1]" for i in range(3000)) + "}",
        ),
        "coincident-markers": four.replace(
            "points: {M: [175, 80]}", "points: {" + ", ".join(f"P{i}: [5, 5]" for i in range(2000)) + "}"
        ),
    }


# ---------------------------------------------------------------- files that are not what they say

#: What a sweep's part may be in place of a file: a named pipe no program writes to, links to devices that never
#: end or hold nothing, a folder, a link to nowhere, a link to itself, a socket.
ODD_PARTS = ["fifo", "dev-zero", "dev-urandom", "dev-null", "folder", "dangling", "self-link", "socket"]


def make_odd(kind: str, path: Path) -> None:
    """Put a thing of ``kind`` (one of :data:`ODD_PARTS`) at ``path``, in place of what is there."""
    import socket

    if path.is_dir() and not path.is_symlink():
        path.rmdir()
    else:
        path.unlink(missing_ok=True)
    if kind == "fifo":
        os.mkfifo(path)
    elif kind.startswith("dev-"):
        path.symlink_to(f"/dev/{kind[4:]}")
    elif kind == "folder":
        path.mkdir()
    elif kind == "dangling":
        path.symlink_to(path.with_name("nowhere"))
    elif kind == "self-link":
        path.symlink_to(path.name)
    else:
        with socket.socket(socket.AF_UNIX) as sock:
            sock.bind(str(path))


def shared(seed: int) -> tuple[str, str, dict[str, float]]:
    """A bundled example whose links share through a YAML anchor, and overrides to write into it:
    ``(description, YAML text, overrides in SI)``.  One link's mapping is anchored and a later one merges it
    (``<<: *a``), leaving out its own mass or inertia, which it inherits now; the overrides change a mass of
    the anchored link, of the heir, or both."""
    rng = random.Random(seed)
    name = rng.choice(names())
    lines = text(name).split("\n")
    start = next(i for i, line in enumerate(lines) if line.startswith("links:"))
    heads = [i for i in range(start + 1, len(lines)) if re.match(r"^  [A-Za-z_]\w*:\s*(#.*)?$", lines[i])]
    heads = heads[
        : next((k for k, i in enumerate(heads) if any(re.match(r"^\S", ln) for ln in lines[start + 1 : i])), len(heads))
    ]
    if len(heads) < 2:
        return shared(seed + 1000)
    keys = {n: set(v) if isinstance(v, dict) else set() for n, v in _read(name)["links"].items()}
    named = [lines[i].split(":")[0].strip() for i in heads]
    own = {"mass", "inertia", "inertia_about", "description"}
    n = len(heads)
    pairs = [(a, h) for a in range(n) for h in range(a + 1, n) if keys[named[a]] - own <= keys[named[h]]]
    if not pairs:
        return shared(seed + 1000)
    first, second = rng.choice(pairs)
    anchor, heir = named[first], named[second]
    end = next((i for i in range(heads[second] + 1, len(lines)) if not lines[i].startswith("    ")), len(lines))
    block = lines[heads[second] + 1 : end]
    kept = [ln for ln in block if not (re.match(r"^    (mass|inertia|inertia_about):", ln) and rng.random() < 0.8)]
    lines[heads[second] + 1 : end] = [f"    <<: *{anchor}_", *kept]
    lines[heads[first]] = lines[heads[first]].replace(f"{anchor}:", f"{anchor}: &{anchor}_", 1)
    values = {f"links.{anchor}.mass": rng.choice([0.5, 2.0, 3.5])}
    if rng.random() < 0.5:
        values[f"links.{heir}.mass"] = rng.choice([0.7, 4.0])
    return f"{name}: {heir} merges {anchor}", "\n".join(lines), values


# ---------------------------------------------------------------- options at their bounds


@functools.cache
def option_cases() -> list[Case]:
    """Command lines whose options are at, or past, their bounds (one past each bound is refused)."""
    big, huge = str(MAX_ANGLES + 1), "1" + "0" * 30
    out: list[tuple[str, ...]] = []
    for cmd in ("kinematics", "forces"):
        out += [(cmd, "four-bar", "--steps", s) for s in ("0", "-1", "1", "2", big, huge, "1e9", "x")]
        angles = ("1e308", "-1e308", "nan", "inf", "1e12", "36000", "36001", ",", "", "1,,2", "1;2", "0x10", "1" * 400)
        out += [(cmd, "four-bar", "--angles", a) for a in angles]
        out += [(cmd, "four-bar", "--angles", ",".join(["1"] * (MAX_ANGLES + 1)))]
        out += [(cmd, "four-bar", "--steps", "12", "--angles", "0")]
    out += [("forces", "four-bar", "--speed", s) for s in ("1e308 rpm", "-1 rpm", "30", "nan rpm", "30 kg", "")]
    out += [("forces", "shears-slider-crank", "--pull", p) for p in ("1e308 N", "-1 N", "0 N", "inf N", "x")]
    out += [("positions", "four-bar", "--count", c) for c in ("0", "-1", "1", big, huge)]
    out += [("positions", "four-bar", "--zero", z) for z in ("1e308", "-1e308", "nan", "inf", "36000", "36001")]
    out += [("balance", "four-bar", "--links", "crank", "--steps", s) for s in ("0", "7", "8", big)]
    out += [("balance", "four-bar", "--links", "crank", "--radius", r) for r in ("1e308 m", "0 m", "-1 m", "1 kg")]
    out += [("balance", "four-bar", "--links", ln) for ln in ("", ",", "frame", "x" * 5000, "crank," * 100)]
    out += [("dynamics", "double-cut-shears", "--delta", d) for d in ("1e-300", "0", "-0.1", "1", "nan", "inf")]
    out += [("dynamics", "double-cut-shears", "--steps", s) for s in ("0", "15", big, huge)]
    out += [("impact", "percussion-rocker", "--cycle", "--blows", b) for b in ("0", "2", str(MAX_BLOWS + 1), huge)]
    out += [("analyze", "four-bar", "--out", "{dir}/r", "--steps", s) for s in ("11", big, huge)]
    out += [("analyze", "four-bar", "--out", "{dir}/r", "--position", p) for p in ("12", "-1", "x" * 5000)]
    out += [("analyze", "four-bar", "--out", "{dir}/" + "r" * 300)]
    out += [("analyze", "four-bar", "--out", "{dir}/r", "--lang", lang) for lang in ("xx", "x" * 5000)]
    sweep = ("sweep", "four-bar", "--metric", "swing", "--quiet", "--out")
    grid = ("--vary", "links.crank.length=90mm:110mm:3")
    out += [
        (*sweep, "{dir}/s.parquet", "--vary", f"links.crank.length=90mm:110mm:{c}")
        for c in ("0", "-1", str(MAX_VARIANTS + 1), huge, "1e9", "x")
    ]
    out += [
        (
            *sweep,
            "{dir}/s.parquet",
            "--vary",
            "links.crank.length=90mm:110mm:4000",
            "--vary",
            "links.rocker.length=200mm:300mm:4000",
        )
    ]
    lhs = ("--vary", "links.crank.length=90mm:110mm", "--sample", "lhs")
    out += [(*sweep, "{dir}/s.parquet", *lhs, "--samples", n) for n in ("0", "-1", str(MAX_VARIANTS + 1), huge)]
    out += [(*sweep, "{dir}/s.parquet", *lhs, "--samples", "3", "--seed", s) for s in ("-1", str(MAX_SEED + 1), huge)]
    out += [(*sweep, "{dir}/s.parquet", *grid, "--steps", s) for s in ("0", "2", big, huge)]
    out += [(*sweep, "{dir}/s.parquet", *grid, "--chunk-size", c) for c in ("0", "-1", "100000", huge)]
    out += [(*sweep, "{dir}/s.parquet", *grid, "--workers", w) for w in ("-1", "100000", huge)]
    out += [
        (*sweep, "{dir}/s.parquet", *grid, "--scheduler", s)
        for s in ("{dir}/sched.json", "{dir}/notjson", "nowhere", "x" * 5000)
    ]
    out += [
        (*sweep, "{dir}/s.parquet", *grid, "--scheduler", "tcp://127.0.0.1:1", "--connect-timeout", t)
        for t in ("inf", "1e308", "0", "-1", "nan")
    ]
    out += [(*sweep, "{dir}/" + "s" * 300 + ".parquet", *grid)]
    varies = ("x" * 5000, "links.crank.length=" + "9" * 5000, "links.crank.length=1e308m:1e308m:2", "=", "")
    out += [(*sweep, "{dir}/s.parquet", "--vary", v) for v in varies]
    opt = ("optimize", "four-bar", "--vary", "links.crank.length=90mm:110mm", "--objective", "swing")
    out += [(*opt, "--popsize", p) for p in ("0", "-1", "1000000000", huge)]
    out += [(*opt, "--seed", s) for s in ("-1", str(MAX_SEED + 1))]
    out += [(*opt, "--maxiter", m) for m in ("-1", "100000000")]
    out += [(*opt, "--steps", s) for s in ("2", big)]
    out += [(*opt, "--constraint", c) for c in ("swing>=1" + " " * 20000 + "x", "x" * 5000, "swing>=1e400deg")]
    out += [(*opt, "--out", o) for o in ("{dir}/" + "o" * 300 + ".yaml", "{dir}/o.txt")]
    out += [("view", "four-bar", "--export", e) for e in ("{dir}/" + "p" * 300 + ".html", "{dir}", "", " ")]
    out += [("view", "four-bar", "--export", "{dir}/p.html", "--steps", s) for s in ("11", "1441")]
    out += [
        ("check", f)
        for f in (
            "/dev/zero",
            "/dev/null",
            "{dir}",
            "{dir}/" + "f" * 300 + ".yaml",
            "/nonexistent",
            "x" * 5000,
            "{dir}/\udcff.yaml",
        )
    ]
    out += [("example", "x" * 5000), ("check", "four-bar", "--values", "--json")]
    out += [("check", f) for f in UNREADABLE if os.path.exists(f)]
    for digits in UNICODE_DIGITS:  # str.isdigit passes them, int refuses some and reads others
        out += [
            ("analyze", "four-bar", "--out", "{dir}/r", "--position", digits),
            ("kinematics", "four-bar", "--steps", digits),
            ("positions", "four-bar", "--count", digits),
        ]
    out += synthesis_argvs()  # every synthesize option of every kind at and past its bounds
    # simulate's options and requirements in files; sizing's options, parts, springs and catalogues (each module
    # imports Case from here)
    import hostile_simulate
    import hostile_sizing

    return [Case(f"option {i}", argv) for i, argv in enumerate(out)] + hostile_simulate.cases() + hostile_sizing.cases()


#: Files whose read fails after they open (EIO, EINVAL), or that are no file.
UNREADABLE = [
    "/proc/self/mem",
    "/proc/self/pagemap",
    "/proc/self/task",
    "/proc/self/clear_refs",
    "/dev/full",
    "/proc/self/fd/0",
    "/sys/kernel/security",
]

#: Digits of other scripts and forms: superscript two, Arabic-Indic three, full-width one two, N'Ko one, a
#: digit with a combining accent, mathematical bold one two.
UNICODE_DIGITS = ["\u00b2", "\u0663", "\uff11\uff12", "\u07c1", "1\u0301", "\U0001d7cf\U0001d7d0"]


#: Files some option cases read: a scheduler file that is none, and one that is not JSON.
OPTION_FILES: dict[str, str | bytes] = {"sched.json": '{"address": 5}', "notjson": "address: tcp://x:1\n"}


@functools.cache
def environment_cases() -> list[Case]:
    """Commands whose surroundings are hostile: standard output on a full disk (``> /dev/full``), a matplotlib
    backend that does not exist, an ASCII locale with a Cyrillic name, a terminal of no width."""
    printing = [
        ("check", "four-bar"),
        ("check", "four-bar", "--json"),
        ("kinematics", "four-bar", "--steps", "12"),
        ("forces", "four-bar", "--steps", "12", "--json"),
        ("parameters", "four-bar"),
        ("examples",),
        ("example", "four-bar"),
        ("positions", "four-bar", "--count", "3"),
        ("dynamics", "double-cut-shears"),
        ("impact", "percussion-rocker"),
        ("balance", "four-bar", "--links", "crank"),
    ]
    out = [Case(f"full {' '.join(argv)}", argv, full=True) for argv in printing]
    cyrillic = {"m.yaml": text("four-bar").replace("name: four-bar", "name: Ножницы")}
    report = ("analyze", "four-bar", "--out", "{dir}/r", "--steps", "24", "--no-animation")
    out += [
        Case("MPLBACKEND=bogus analyze", report, env=(("MPLBACKEND", "bogus"),)),
        Case("MPLBACKEND=bogus check", ("check", "four-bar"), env=(("MPLBACKEND", "bogus"),)),
        Case("LANG=C check", ("check", "{dir}/m.yaml"), cyrillic, env=(("LANG", "C"), ("LC_ALL", "C"))),
        Case("COLUMNS=0 forces", ("forces", "four-bar", "--steps", "12"), env=(("COLUMNS", "0"),)),
    ]
    return out


def file_case(i: int, fresh: bool = False) -> Case:
    """The mutated file of seed ``i`` (``fresh``: of the fresh kinds): checked, or solved (every fourth by
    kinematics, every fourth by forces)."""
    what, body = mutated(i, fresh)
    argv: tuple[str, ...] = ("check", "{dir}/m.yaml", "--json")
    if i % 4 == 1:
        argv = ("kinematics", "{dir}/m.yaml", "--steps", "24", "--json")
    elif i % 4 == 3:
        argv = ("forces", "{dir}/m.yaml", "--steps", "24", "--json")
    return Case(f"{'fresh' if fresh else 'file'} {i}: {what}", argv, {"m.yaml": body})


def yaml_names(slow: bool = False) -> list[str]:
    """The names of the YAML attacks (with ``slow``, also those of :data:`SLOW_YAML`)."""
    return [name for name in yaml_cases() if slow or name not in SLOW_YAML]


def yaml_case(name: str) -> Case:
    """The YAML attack ``name``, checked."""
    return Case(f"yaml {name}", ("check", "{dir}/m.yaml", "--json"), {"m.yaml": yaml_cases()[name]})


# ---------------------------------------------------------------- running a case


class _Timeout(BaseException):
    pass


def _alarm(signum: int, frame: Any) -> None:
    raise _Timeout


def run_in_process(case: Case, folder: Path, limit: float = TIME_LIMIT) -> Outcome:
    """Run ``case`` through the command's application in this process, stopped after ``limit`` s."""
    from linkwork.cli.main import app

    case.write(folder)
    old = signal.signal(signal.SIGALRM, _alarm)
    signal.setitimer(signal.ITIMER_REAL, limit)
    start = time.perf_counter()
    try:
        result = CliRunner().invoke(app, case.args(folder))
    except _Timeout:
        return Outcome(None, "", "", time.perf_counter() - start, f"more than {limit:g} s")
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old)
    seconds = time.perf_counter() - start
    crash = None
    if isinstance(result.exception, _Timeout):
        crash = f"more than {limit:g} s"
    elif result.exception is not None and not isinstance(result.exception, SystemExit):
        crash = f"{type(result.exception).__name__}: {result.exception!s:.300}"
    return Outcome(result.exit_code, result.stdout, result.stderr, seconds, crash)


def _limit_memory() -> None:
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_LIMIT, MEMORY_LIMIT))


#: Linux's bound on one argument of a program (MAX_ARG_STRLEN, 32 pages of 4 KiB).
ARG_LIMIT = 131072


def run_in_subprocess(
    case: Case, folder: Path, limit: float = TIME_LIMIT, env: dict[str, str] | None = None
) -> Outcome:
    if case.full:
        with open(os.devnull if not os.path.exists("/dev/full") else "/dev/full", "w") as full:
            return _run_in_subprocess(case, folder, limit, env, full)
    return _run_in_subprocess(case, folder, limit, env, subprocess.PIPE)


def _run_in_subprocess(case: Case, folder: Path, limit: float, env: dict[str, str] | None, stdout: Any) -> Outcome:
    """Run ``case`` as ``python -m linkwork.cli`` with at most :data:`MEMORY_LIMIT` of memory and ``limit`` s.
    A case with an argument longer than the system passes to a program (:data:`ARG_LIMIT`: no shell could
    give it either) runs in this process instead."""
    case.write(folder)
    argv = [os.fsencode(a) for a in case.args(folder)]
    if any(len(a) >= ARG_LIMIT for a in argv):
        return run_in_process(case, folder, limit)
    source = Path(linkwork.__file__).resolve().parents[1]  # the linkwork this process imported
    environ = {**os.environ, "PYTHONPATH": str(source), **(env or {}), **dict(case.env)}
    start = time.perf_counter()
    try:
        proc = subprocess.run(
            [sys.executable, "-m", "linkwork.cli", *argv],
            stdout=stdout,
            stderr=subprocess.PIPE,
            timeout=limit,
            env=environ,
            preexec_fn=_limit_memory,
            stdin=subprocess.DEVNULL,
        )
    except subprocess.TimeoutExpired:
        return Outcome(None, "", "", time.perf_counter() - start, f"more than {limit:g} s")
    stderr = proc.stderr.decode("utf-8", "backslashreplace")
    crash = "Traceback" if "Traceback" in stderr or proc.returncode not in (0, 2) else None
    out = (proc.stdout or b"").decode("utf-8", "backslashreplace")
    return Outcome(proc.returncode, out, stderr, time.perf_counter() - start, crash)


#: What a command says whose standard output is a full disk.
FULL_DISK = "error: cannot write the output: No space left on device\n"

#: A control character a terminal acts on (tab and newline are text).
_CONTROL = re.compile("[\x00-\x08\x0b-\x1f\x7f-\x9f]")


def _strict_json(text: str) -> Any:
    def refuse(constant: str) -> Any:
        raise ValueError(f"not JSON: {constant}")

    data = json.loads(text, parse_constant=refuse)
    json.dumps(data, ensure_ascii=False).encode("utf-8")  # a lone surrogate in a string fails here
    return data


def problems(case: Case, outcome: Outcome) -> list[str]:
    """What is wrong with the outcome of a case (empty where it ended as it should)."""
    if outcome.crash is not None:
        return [f"{outcome.crash}\n{outcome.stderr[-2000:]}"]
    found = []
    if outcome.code not in (0, 2):
        found.append(f"exit code {outcome.code}")
    if "Traceback" in outcome.stdout + outcome.stderr:
        found.append("a traceback")
    if outcome.code == 2:
        lines = outcome.stderr.splitlines()
        if not lines or not lines[0].startswith("error:") and not lines[0].startswith("Usage:"):
            found.append(f"exit code 2 without a message: {outcome.stderr[:300]!r}")
        long = [line for line in lines if len(line) > LINE_LIMIT]
        if long:
            found.append(f"a message line of {len(long[0])} characters: {long[0][:200]!r}...")
    raw = sorted({f"{ord(c):#04x}" for c in outcome.stdout + outcome.stderr if _CONTROL.match(c)})
    if raw:
        found.append(f"control characters printed raw, which a terminal would act on: {', '.join(raw[:5])}")
    if case.full and (outcome.code, outcome.stderr) != (2, FULL_DISK):
        found.append(f"output to a full disk: not the one line that says so, exit 2: {outcome.stderr[-300:]!r}")
    if outcome.code == 0 and "--json" in case.argv:
        try:
            _strict_json(outcome.stdout)
        except ValueError as exc:  # UnicodeEncodeError is one
            found.append(f"--json output is not strict JSON: {exc!s:.200}")
    return found


class TooLong(AssertionError):
    pass


@contextlib.contextmanager
def within(seconds: float) -> Iterator[None]:
    """Fail the test where its block takes more than ``seconds`` (it is stopped then, not waited for)."""

    def stop(signum: int, frame: object) -> None:
        raise TooLong(f"took more than {seconds:g} s")

    old = signal.signal(signal.SIGALRM, stop)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old)
