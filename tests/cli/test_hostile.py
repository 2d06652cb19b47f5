"""Hostile input: whatever a file or an option holds, a command ends in exit code 0, or 2 with a
message of short lines, within a bounded time and memory, and its ``--json`` is strict JSON.

The cases come from :mod:`hostile` (mutated bundled examples, attacks on the YAML reader, options at
and past their bounds).  A sample runs with the suite, each case in this process under a time bound (every
third case of each kind in the fast lane, the others in the slow one); the full run
(``pytest --hostile tests/cli/test_hostile.py``) runs many more, each in its own process under a memory
bound too.  Then the defects found by such runs, one test each.
"""

from __future__ import annotations

import resource
from collections import Counter
from pathlib import Path
from typing import Any

import pytest

import hostile
from hostile import Case, option_cases, problems, run_in_process, run_in_subprocess

#: Mutated files in the sample of the normal suite, and in the full run.
SAMPLE, FULL = 60, 300

#: Of each kind of case in the sample, one in this many runs in the fast lane.
FAST_EVERY = 3

#: Growth of this process's largest memory in use that a case of the sample may cause.
MEMORY_GROWTH = 1.5 * (1 << 30)


def _folder(tmp_path: Path) -> Path:
    for name, content in hostile.OPTION_FILES.items():
        (tmp_path / name).write_text(content) if isinstance(content, str) else (tmp_path / name).write_bytes(content)
    return tmp_path


def _case(kind: str, key: str | int) -> Case:
    """A case by its kind and key (cases are built when a test runs, so that collecting them is quick)."""
    if kind == "file":
        return hostile.file_case(int(key))
    if kind == "yaml":
        return hostile.yaml_case(str(key))
    return option_cases()[int(key)]


def _keys(files: int, slow: bool) -> list[tuple[str, str | int]]:
    n_options = len(option_cases())
    return (
        [("file", i) for i in range(files)]
        + [("yaml", name) for name in hostile.yaml_names(slow)]
        + [("option", i) for i in range(n_options)]
    )


def _sample() -> list[Any]:
    """The sample's cases; of each kind, every :data:`FAST_EVERY`-th runs in the fast lane, the others are slow."""
    seen: Counter[str] = Counter()
    out = []
    for kind, key in _keys(SAMPLE, slow=False):
        marks = () if seen[kind] % FAST_EVERY == 0 else (pytest.mark.slow,)
        seen[kind] += 1
        out.append(pytest.param(kind, key, marks=marks, id=f"{kind}-{str(key)[:40]}"))
    return out


@pytest.mark.parametrize(("kind", "key"), _sample())
def test_a_sample_of_hostile_cases_ends_cleanly(kind, key, tmp_path):
    case = _case(kind, key)
    before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
    outcome = run_in_process(case, _folder(tmp_path))
    assert problems(case, outcome) == [], (case.name, outcome.stderr[-1000:])
    grown = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024 - before
    assert grown < MEMORY_GROWTH, f"{case.name}: the process grew by {grown / 2**20:.0f} MiB"


@pytest.mark.hostile
@pytest.mark.parametrize(("kind", "key"), _keys(FULL, slow=True), ids=lambda k: str(k)[:40])
def test_every_hostile_case_ends_cleanly_in_its_own_process(kind, key, tmp_path):
    case = _case(kind, key)
    outcome = run_in_subprocess(case, _folder(tmp_path))
    assert problems(case, outcome) == [], (case.name, outcome.stderr[-1000:])


def test_the_generator_makes_what_it_says():
    """Mutations are reproducible, differ from the example, and cover the kinds the module lists."""
    assert hostile.mutated(7) == hostile.mutated(7)
    texts = {hostile.mutated(seed)[1] for seed in range(60)}
    assert len(texts) > 50
    kinds = " ".join(hostile.mutated(seed)[0] for seed in range(300))
    for word in ("drop", "extra", "rename", "items", "copies", "points", "nan", "inf", "1e+308", "\\ud800"):
        assert word in kinds, word
    assert len(option_cases()) > 150 and len(hostile.yaml_cases()) > 40


def test_the_checks_of_an_outcome_can_fail():
    case = Case("x", ("check", "f", "--json"))
    good = hostile.Outcome(0, '{"a": 1}', "", 0.1)
    assert problems(case, good) == []
    assert problems(case, hostile.Outcome(0, '{"a": NaN}', "", 0.1))
    assert problems(case, hostile.Outcome(0, '{"a": "\\ud800"}', "", 0.1))
    assert problems(case, hostile.Outcome(1, "", "Traceback (most recent call last):", 0.1))
    assert problems(case, hostile.Outcome(2, "", "error: " + "x" * 1000, 0.1))
    assert problems(case, hostile.Outcome(2, "", "", 0.1))
    assert problems(case, hostile.Outcome(None, "", "", 31.0, "more than 30 s"))
