"""The defects hostile input found on the command line, one test each: a bound or a check, one clear line and
exit code 2 instead of a traceback, a hang or memory without end; ``--json`` records that say why a value
is null.

A case that could take memory or time without end on a defect runs in its own process under the bounds of
:func:`hostile.run_in_subprocess`; the others run in this process under a time bound.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from hostile import Case, problems, run_in_process, run_in_subprocess
from linkwork.examples import text

#: Seconds a refused option may take (the refusal comes before any work; a run takes about 1 s).
REFUSED_WITHIN = 20.0

#: Shared by the cases of a sweep and an optimisation.
SWEEP = ("sweep", "four-bar", "--metric", "swing", "--quiet", "--out", "{dir}/s.parquet")
LHS = ("--vary", "links.crank.length=90mm:110mm", "--sample", "lhs")
GRID = ("--vary", "links.crank.length=90mm:110mm:3")
OPTIMIZE = ("optimize", "four-bar", "--vary", "links.crank.length=90mm:110mm", "--objective", "swing")

#: (command line, what the one line of the message says, in its own process): each of them gave a traceback,
#: ran out of memory or did not end.
REFUSED = [
    (("kinematics", "four-bar", "--steps", "1000000000"), "--steps: expected a positive number, at most", True),
    (("forces", "four-bar", "--angles", "1e308"), "--angles: expected crank angles within 100 turns", False),
    (("positions", "four-bar", "--count", "1000000000"), "--count: expected a positive number of positions", True),
    (("positions", "four-bar", "--zero", "1e308"), "--zero: expected crank angles within 100 turns", False),
    (("dynamics", "double-cut-shears", "--delta", "1e-300"), "--delta: expected a coefficient of speed", False),
    (("dynamics", "{dir}/tiny-delta.yaml"), "machine.delta", False),
    ((*SWEEP, "--vary", "links.crank.length=90mm:110mm:1000000000"), "the grid has 1,000,000,000 variants", True),
    ((*SWEEP, *LHS, "--samples", "1000000000"), "--samples: expected at most 10,000,000 variants", True),
    ((*SWEEP, *LHS, "--samples", "3", "--seed", "-1"), "seed: expected a whole number, at least 0", False),
    ((*SWEEP, *GRID, "--scheduler", "{dir}/sched.json"), "not a Dask scheduler file", False),
    ((*SWEEP, *GRID, "--scheduler", "tcp://127.0.0.1:1", "--connect-timeout", "inf"), "at most 3600, got inf", False),
    ((*SWEEP, *GRID, "--scheduler", "tcp://127.0.0.1:1", "--connect-timeout", "1e308"), "at most 3600", True),
    ((*OPTIMIZE, "--popsize", "1000000000"), "--popsize: expected a positive number, at most", True),
    ((*OPTIMIZE, "--seed", "-1"), "--seed: expected a whole number, at least 0", False),
    (("view", "four-bar", "--export", "{dir}/" + "p" * 300 + ".html"), "File name too long", False),
    (("check", "{dir}/surrogate.yaml"), 'not Unicode text: "a\\ud800b" holds the lone surrogate', False),
    (("forces", "four-bar", "--speed", "1e300 rpm"), "--speed: expected an angular speed of a machine's size", False),
    (("analyze", "four-bar", "--out", "{dir}/r", "--position", "\u00b2"), "--position: expected one of the 12", False),
    (("analyze", "four-bar", "--out", "{dir}/r", "--position", "\u0663"), "--position: expected one of the 12", False),
]


def _files(folder: Path) -> Path:
    """The files the cases read: a delta too small to size a flywheel for, a scheduler file without an
    address, a name that holds a lone surrogate."""
    shears = text("double-cut-shears")
    assert "delta: 0.05" in shears
    (folder / "tiny-delta.yaml").write_text(shears.replace("delta: 0.05", "delta: 1e-300"))
    (folder / "sched.json").write_text('{"address": 5}')
    (folder / "surrogate.yaml").write_text(text("four-bar").replace("name: four-bar", 'name: "a\\ud800b"'))
    return folder


def _id(value: object) -> str | None:
    return " ".join(value)[:50] if isinstance(value, tuple) else None


@pytest.mark.parametrize(("argv", "says", "own_process"), REFUSED, ids=_id)
def test_an_option_or_a_value_past_its_bound_is_refused_in_one_line(argv, says, own_process, tmp_path):
    case = Case(argv[0], argv)
    run = run_in_subprocess if own_process else run_in_process
    outcome = run(case, _files(tmp_path), limit=REFUSED_WITHIN)
    assert problems(case, outcome) == [], outcome.stderr[-2000:]
    assert outcome.code == 2
    lines = [line for line in outcome.stderr.splitlines() if line.strip()]
    assert says in outcome.stderr and len(lines) <= 2, outcome.stderr  # "error:" and the problem, or both in one
    assert not (tmp_path / "s.parquet").exists()


def test_a_message_quotes_a_short_excerpt_of_a_file_that_is_no_mechanism(tmp_path):
    """A file of 40 lines none of whose keys is a field (a password file): one problem, not each line
    quoted back."""
    secret = "$6$saltsalt$" + "h" * 86
    body = "".join(f"user{i}:{secret}:20228:0:99999:7:::\n" for i in range(40))
    case = Case("check", ("check", "{dir}/shadow"), {"shadow": body})
    outcome = run_in_process(case, tmp_path)
    assert outcome.code == 2 and problems(case, outcome) == []
    assert len(outcome.stderr) < 600 and secret not in outcome.stderr, outcome.stderr


def _strict(stdout: str) -> dict:
    def refuse(constant: str) -> None:
        raise ValueError(constant)

    return json.loads(stdout, parse_constant=refuse)


@pytest.mark.parametrize(
    ("argv", "null_at"),
    [
        # one angle is no turn: no stroke, extreme positions or time ratio
        (("kinematics", "four-bar", "--steps", "1", "--json"), "events"),
        # a crank of 260 mm does not turn fully in a four-bar of 300, 350 and 250 mm (260 + 350 > 300 + 250)
        (("kinematics", "{dir}/no-turn.yaml", "--steps", "36", "--json"), "points"),
        (("forces", "{dir}/no-turn.yaml", "--steps", "36", "--json"), "driving_torque"),
    ],
)
def test_a_json_record_with_nulls_says_why(argv, null_at, tmp_path):
    four = text("four-bar")
    assert "    length: 100\n" in four
    (tmp_path / "no-turn.yaml").write_text(four.replace("    length: 100\n", "    length: 260\n", 1))
    case = Case(argv[0], argv)
    outcome = run_in_process(case, tmp_path)
    assert problems(case, outcome) == [] and outcome.code == 0, outcome.stderr
    data = _strict(outcome.stdout)
    nulls = data.get("nulls", {})
    assert null_at in nulls and len(nulls[null_at]) > 20, nulls
    assert _has_null(data[null_at])


def _has_null(x: object) -> bool:
    if x is None:
        return True
    if isinstance(x, dict):
        return any(_has_null(v) for v in x.values())
    if isinstance(x, list):
        return any(_has_null(v) for v in x)
    return False


def test_balance_with_a_counterweight_at_1e308_m_prints_strict_json_with_its_reasons():
    case = Case("balance", ("balance", "four-bar", "--links", "crank", "--radius", "1e308 m", "--json"))
    outcome = run_in_process(case, Path("."))
    assert problems(case, outcome) == [] and outcome.code == 0, outcome.stderr
    data = _strict(outcome.stdout)
    assert _has_null(data["after"]) and "after" in data["nulls"]
