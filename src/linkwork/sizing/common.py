"""What every part of the sizing shares: a result's table with units, and the catalogues read from CSV files.

A catalogue is a CSV file in ``linkwork/sizing/data/`` (or the user's, with the same columns): lines
starting with ``#`` are comments (the source of its values), the first other line names the columns,
each with its unit in brackets (``power [kW]``, ``inertia [kg m^2]``, ``[1]`` for a ratio); the values
are read into SI.  Every bundled catalogue declares its columns and their units (:data:`COLUMNS`) and is
checked against them when it is read.
"""

from __future__ import annotations

import csv
import io
import math
import re
from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np

from linkwork.errors import LinkworkError
from linkwork.limits import MAX_CATALOGUE_ROWS, MAX_PROBLEMS, QUOTE_PATH

#: A column heading: its name and, in brackets, its unit.
_HEADING = re.compile(r"^\s*([^\[\]]*?)\s*\[([^\[\]]*)\]\s*$")


@dataclass(frozen=True)
class Table:
    """A result as a person reads it: a title, the columns (each ``name [unit]``) and the rows (SI values
    converted to the columns' units where the heading says so).

    ``record()`` gives it as a list of objects keyed by the column names for the JSON record.
    """

    title: str
    columns: tuple[str, ...]
    rows: tuple[tuple[Any, ...], ...]
    key: str = ""  # which table of the sizing it is (``motor``, ``rolling``, ...): the report's title for it

    def record(self) -> list[dict[str, Any]]:
        """The rows as objects keyed by ``name_unit`` (``power_kW``): the JSON record's form."""
        keys = [_key(c) for c in self.columns]
        return [dict(zip(keys, row, strict=True)) for row in self.rows]

    def text(self) -> str:
        """The table as aligned plain text (numbers to 4 significant digits)."""
        cells = [list(self.columns)] + [[_cell(v) for v in row] for row in self.rows]
        widths = [max(len(r[i]) for r in cells) for i in range(len(self.columns))]
        lines = [self.title] + ["  " + "  ".join(c.rjust(w) for c, w in zip(r, widths, strict=True)) for r in cells]
        return "\n".join(lines)


def _key(column: str) -> str:
    """``power [kW]`` -> ``power_kW``; ``ratio [1]`` -> ``ratio``; spaces and signs as underscores."""
    match = _HEADING.match(column)
    name, unit = (match.group(1), match.group(2)) if match else (column, "")
    unit = "" if unit in ("", "1") else re.sub(r"[^A-Za-z0-9]+", "_", unit.replace("^2", "2").replace("^3", "3"))
    return re.sub(r"[^A-Za-z0-9]+", "_", name).strip("_") + (f"_{unit.strip('_')}" if unit else "")


def _cell(v: Any) -> str:
    if isinstance(v, float):
        return "-" if not math.isfinite(v) else f"{v + 0.0:.4g}"
    return str(v)


@dataclass(frozen=True)
class Catalogue:
    """A catalogue read from CSV: its ``source`` (path or bundled name), its comment lines, the row names
    (first column) and every other column in SI by its name (without the unit)."""

    source: str
    comments: tuple[str, ...]
    names: tuple[str, ...]
    columns: dict[str, np.ndarray]

    def __len__(self) -> int:
        return len(self.names)

    def row(self, i: int) -> dict[str, float]:
        return {k: float(v[i]) for k, v in self.columns.items()}


#: The columns every bundled catalogue declares, each with its SI unit (``"1"``: a ratio): its heading must name
#: each, in a unit of that kind (any of them; the values are read into SI), and every row give each a number.
COLUMNS: dict[str, dict[str, str]] = {
    "motors.csv": {
        "power": "W",
        "synchronous": "rad/s",
        "speed": "rad/s",
        "starting": "1",
        "breakdown": "1",
        "inertia": "kg*m^2",
        "mass": "kg",
    },
    "steels.csv": {"yield": "Pa", "tensile": "Pa", "endurance": "Pa"},
    "bushes.csv": {"p": "Pa", "v": "m/s", "pv": "Pa*m/s"},
    "bolt_classes.csv": {"yield": "Pa"},
    "threads.csv": {"diameter": "m", "pitch": "m", "stress area": "m^2"},
}


def bundled(name: str) -> Catalogue:
    """The catalogue ``name`` (one of :data:`COLUMNS`) bundled with linkwork, checked on load against the columns
    it declares.

    Raises
    ------
    LinkworkError
        No such catalogue; or, one line a problem, a declared column missing or in a unit of another kind, a value
        that is not a finite number.
    """
    if name not in COLUMNS:
        raise LinkworkError(f"no bundled catalogue {name!r}: one of {', '.join(COLUMNS)}")
    text = resources.files("linkwork.sizing").joinpath("data").joinpath(name).read_text(encoding="utf-8")
    return parse_catalogue(text, name, COLUMNS[name])


def read_catalogue(path: str | Path, need: dict[str, str]) -> Catalogue:
    """A user's catalogue at ``path`` with the columns ``need`` (name -> SI unit, ``"1"`` for a ratio).

    Raises
    ------
    LinkworkError
        The file cannot be read, a needed column is missing or has a unit of another kind, a value is
        not a finite number (each problem with its line).
    """
    return parse_catalogue(_catalogue_text(path), str(path), need)


def _catalogue_text(path: str | Path) -> str:
    """The text of the catalogue file ``path``: a regular file (a device, a fifo or a folder is refused before it is
    opened: it could be endless or block for ever) of at most :data:`~linkwork.limits.MAX_CATALOGUE_BYTES`, UTF-8."""
    import os
    import stat

    from linkwork.atomic import kind
    from linkwork.limits import MAX_CATALOGUE_BYTES, excerpt

    shown = excerpt(os.fspath(path), QUOTE_PATH)
    try:
        info = os.stat(path)
        if not stat.S_ISREG(info.st_mode):
            raise LinkworkError(f"catalogue {shown}: it is {kind(info.st_mode)}, not a regular file (a CSV file)")
        if info.st_size > MAX_CATALOGUE_BYTES:
            raise LinkworkError(
                f"catalogue {shown}: {info.st_size:,} bytes; a catalogue is at most {MAX_CATALOGUE_BYTES:,} bytes"
            )
        with open(path, "rb") as stream:  # a regular file, read no further than the bound
            data = stream.read(MAX_CATALOGUE_BYTES + 1)
        if len(data) > MAX_CATALOGUE_BYTES:
            raise LinkworkError(f"catalogue {shown}: larger than {MAX_CATALOGUE_BYTES:,} bytes, the most it may be")
        return data.decode("utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise LinkworkError(f"catalogue {shown}: cannot read it ({getattr(exc, 'strerror', None) or exc})") from None


def parse_catalogue(text: str, source: str, need: dict[str, str]) -> Catalogue:
    """The catalogue in ``text`` (see the module), its values in SI; ``need``: the columns it must have
    (name -> SI unit).  Every problem is collected into one :class:`LinkworkError`."""
    lines = text.splitlines()
    comments = tuple(line.lstrip("#").strip() for line in lines if line.lstrip().startswith("#"))
    body = [(n + 1, line) for n, line in enumerate(lines) if line.strip() and not line.lstrip().startswith("#")]
    if not body:
        raise LinkworkError(f"catalogue {source}: no heading line (name,power [kW],...)")
    heading_line, heading = body[0]
    head = next(csv.reader(io.StringIO(heading)))
    problems: list[str] = []
    units: dict[str, tuple[int, str]] = {}
    for c, cell in enumerate(head[1:], start=1):
        match = _HEADING.match(cell)
        if match is None:
            problems.append(f"{source}:{heading_line}: column {cell.strip()!r} has no unit in brackets, e.g. [kW]")
            continue
        units[match.group(1)] = (c, match.group(2).strip())
    for name, si in need.items():
        if name not in units:
            problems.append(f"{source}:{heading_line}: no column {name!r} [{si}]")
    factors = {}
    for name, (_, unit) in units.items():
        try:
            factors[name] = _factor(unit, need.get(name))
        except LinkworkError as exc:
            problems.append(f"{source}:{heading_line}: column {name!r}: {exc}")
    names, values = [], []
    rows = len(body) - 1
    if rows > MAX_CATALOGUE_ROWS:
        problems.append(
            f"{source}: {rows:,} rows; a catalogue has at most {MAX_CATALOGUE_ROWS:,} (each is screened "
            "against the machine, and a run of the machine takes seconds): keep the motors that may serve"
        )
        body = body[:1]
    for n, line in body[1:]:
        cells = next(csv.reader(io.StringIO(line)))
        row = []
        for name, (c, _) in units.items():
            try:
                v = float(cells[c])
            except (IndexError, ValueError):
                v = math.nan
            if not math.isfinite(v):
                problems.append(f"{source}:{n}: column {name!r}: expected a number")
            row.append(v * factors.get(name, 1.0))
        names.append(cells[0].strip())
        values.append(row)
    if not rows:
        problems.append(f"{source}: no rows under the heading")
    if problems:
        more = len(problems) - MAX_PROBLEMS
        shown = problems[:MAX_PROBLEMS] + ([f"... and {more:,} more problems"] if more > 0 else [])
        raise LinkworkError("\n".join(shown))
    table = np.array(values, dtype=float).reshape(len(names), len(units))
    return Catalogue(source, comments, tuple(names), {k: table[:, i] for i, k in enumerate(units)})


def _factor(unit: str, si: str | None) -> float:
    """SI value of one ``unit`` (pint), checked against the ``si`` unit's dimension where given."""
    if unit in ("", "1", "-"):
        if si not in (None, "1"):
            raise LinkworkError(f"expected a unit of {si}, got a ratio")
        return 1.0
    from linkwork.units import registry

    ureg = registry()
    try:
        q = ureg.Quantity(1.0, ureg.parse_units(unit.replace("^", "**")))
        if si is None:
            return float(q.to_base_units().magnitude)
        return float(q.to(si.replace("^", "**")).magnitude)
    except Exception as exc:  # pint raises several types for unknown or mismatched units
        raise LinkworkError(f"unit [{unit}]" + (f" is not a unit of {si}" if si else " is unknown")) from exc


def worst(values: np.ndarray) -> int:
    """The index of the largest finite value (0 where there is none)."""
    v = np.where(np.isfinite(values), values, -np.inf)
    return int(np.argmax(v))
