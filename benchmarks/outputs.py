"""The outputs of every bundled example, written to a folder, and two such folders compared.

A refactoring must not move a number.  Run ``write`` on the tree before the change and on the tree after it
(each with its own ``PYTHONPATH``), then ``compare``::

    PYTHONPATH=/old/src LINKWORK_NUMBA=0 python benchmarks/outputs.py write /tmp/before [EXAMPLE ...]
    PYTHONPATH=src LINKWORK_NUMBA=0 python benchmarks/outputs.py write /tmp/after
    python benchmarks/outputs.py compare /tmp/before /tmp/after

``write`` keeps, for each bundled example: the ``--json`` output of ``kinematics``, ``forces``, ``dynamics``,
``size`` (of a file with
``sizing:``), ``impact``, ``balance`` and a ``simulate`` run (or the command's message and exit code where it
refuses), the viewer's payload of the cycle, and the folder ``linkwork analyze --no-animation`` writes (its
JSON and CSV tables, and ``report.html`` without its pictures).  ``compare`` holds numbers to a relative
1e-12 (or an absolute 1e-9 of the largest magnitude of their array, for numbers that cancel to zero) and text
to equality; it prints each difference and exits 1 where there is one.
"""

from __future__ import annotations

import csv
import io
import json
import math
import re
import sys
from pathlib import Path
from typing import Any

RTOL = 1e-12
COMMANDS = {
    "kinematics": ["--steps", "72"],
    "forces": ["--steps", "72"],
    "dynamics": [],
    "size": [],
    "impact": [],
    "balance": [],
    "simulate": ["--until", "50 ms", "--speed", "30 rpm", "--samples", "41"],
}


def write(out: Path, only: list[str] | None = None) -> None:
    """Every example's outputs (or those of the examples ``only``) into ``out``."""
    import os

    os.environ.setdefault("LINKWORK_NUMBA", "0")
    from typer.testing import CliRunner

    import linkwork.cli.main  # noqa: F401 - registers the commands
    from linkwork.cli.app import app
    from linkwork.examples import names, text

    runner = CliRunner()
    for name in only or names():
        folder = out / name
        folder.mkdir(parents=True, exist_ok=True)
        for command, options in COMMANDS.items():
            if command == "size" and "\nsizing:" not in text(name):
                continue  # without a sizing: section it takes minutes
            res = runner.invoke(app, [command, name, "--json", *options])
            said = res.stdout if res.exit_code == 0 else f"exit {res.exit_code}\n{res.output}"
            (folder / f"{command}.txt").write_text(said, encoding="utf-8")
        _viewer(name, folder)
        report = folder / "report"
        res = runner.invoke(app, ["analyze", name, "--out", str(report), "--no-animation"])
        (folder / "analyze.txt").write_text(f"exit {res.exit_code}\n", encoding="utf-8")
        if (report / "report.html").exists():
            page = (report / "report.html").read_text(encoding="utf-8")
            page = re.sub(r"base64,[A-Za-z0-9+/=]+", "base64,", page)
            page = re.sub(r"width='\d+'", "width=''", page)
            (report / "report.html").write_text(page, encoding="utf-8")
        for kept in ("figures", "kinematics.nc"):
            path = report / kept
            if path.is_dir():
                import shutil

                shutil.rmtree(path)
            elif path.exists():
                path.unlink()
        print(name, flush=True)


def _viewer(name: str, folder: Path) -> None:
    import linkwork as lw
    from linkwork.io.jsonout import dumps
    from linkwork.web.payload import cycle_payload

    try:
        payload = cycle_payload(lw.compile(lw.load(name)), steps=72)
    except Exception as exc:  # a mechanism the viewer does not turn: its message is the output
        (folder / "viewer.txt").write_text(f"{type(exc).__name__}: {exc}", encoding="utf-8")
        return
    (folder / "viewer.txt").write_text(dumps(payload), encoding="utf-8")


def compare(before: Path, after: Path) -> list[str]:
    """The differences between two folders written by :func:`write`."""
    problems: list[str] = []
    names = {p.relative_to(before) for p in before.rglob("*") if p.is_file()}
    names |= {p.relative_to(after) for p in after.rglob("*") if p.is_file()}
    for rel in sorted(names):
        a, b = before / rel, after / rel
        if not a.exists() or not b.exists():
            problems.append(f"{rel}: only {'after' if b.exists() else 'before'}")
            continue
        ta, tb = a.read_text(encoding="utf-8"), b.read_text(encoding="utf-8")
        if ta == tb:
            continue
        where = str(rel)
        if rel.suffix in (".json", ".txt") and _json(ta) is not None and _json(tb) is not None:
            _same(_json(ta), _json(tb), where, problems)
        elif rel.suffix == ".csv":
            _same(_csv(ta), _csv(tb), where, problems)
        else:
            problems.append(f"{where}: the text differs")
    return problems


def _json(text: str) -> Any:
    try:
        return json.loads(text)
    except ValueError:
        return None


def _csv(text: str) -> list[list[Any]]:
    return [[_number(c) for c in row] for row in csv.reader(io.StringIO(text))]


def _number(cell: str) -> Any:
    try:
        return float(cell)
    except ValueError:
        return cell


def _scale(x: Any) -> float:
    """The largest magnitude of the numbers in ``x``."""
    if isinstance(x, bool):
        return 0.0
    if isinstance(x, int | float):
        return abs(x) if math.isfinite(x) else 0.0
    if isinstance(x, list):
        return max((_scale(v) for v in x), default=0.0)
    return 0.0


def _same(a: Any, b: Any, where: str, problems: list[str], scale: float = 0.0) -> None:
    if len(problems) > 200:
        return
    if isinstance(a, dict) and isinstance(b, dict):
        if a.keys() != b.keys():
            problems.append(f"{where}: keys {sorted(set(a) ^ set(b))}")
        for k in a.keys() & b.keys():
            _same(a[k], b[k], f"{where}.{k}", problems)
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            problems.append(f"{where}: {len(a)} items before, {len(b)} after")
            return
        scale = max(scale, _scale(a))
        for i, (x, y) in enumerate(zip(a, b, strict=True)):
            _same(x, y, f"{where}[{i}]", problems, scale)
    elif isinstance(a, int | float) and isinstance(b, int | float) and not isinstance(a, bool):
        if a == b or (isinstance(a, float) and math.isnan(a) and isinstance(b, float) and math.isnan(b)):
            return
        if not math.isclose(a, b, rel_tol=RTOL, abs_tol=1e-9 * scale):
            problems.append(f"{where}: {a!r} before, {b!r} after")
    elif a != b:
        problems.append(f"{where}: {a!r} before, {b!r} after")


def main(argv: list[str]) -> int:
    if len(argv) >= 2 and argv[0] == "write":
        write(Path(argv[1]), argv[2:])
        return 0
    if len(argv) == 3 and argv[0] == "compare":
        problems = compare(Path(argv[1]), Path(argv[2]))
        print("\n".join(problems) if problems else "the same numbers")
        return 1 if problems else 0
    print(__doc__)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
