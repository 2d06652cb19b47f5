"""Hostile input: whatever a file or an option holds, a command ends in exit code 0, or 2 with a
message of short lines, within a bounded time and memory, and its ``--json`` is strict JSON.

The cases come from :mod:`hostile` (mutated bundled examples, of the first campaign's kinds and of the
fresh ones, attacks on the YAML reader, options at and past their bounds, hostile surroundings, each of
those in a process of its own).  A sample runs with the suite, each case in this process under a time bound (every
sixth case of each kind in the default lane, the others in the slow one); the full run
(``pytest --hostile tests/cli/test_hostile.py``) runs many more, each in its own process under a memory
bound too.  Then the defects found by such runs, one test each.
"""

from __future__ import annotations

import resource
import subprocess
import sys
from collections import Counter
from pathlib import Path
from typing import Any

import pytest

import hostile
from hostile import Case, option_cases, problems, run_in_process, run_in_subprocess

#: Mutated files in the sample of the normal suite, and in the full run.
SAMPLE, FULL = 60, 300

#: Of each kind of case in the sample, one in this many runs in the fast lane.
FAST_EVERY = 6

#: Growth of this process's largest memory in use that a case of the sample may cause.
MEMORY_GROWTH = 1.5 * (1 << 30)


def _folder(tmp_path: Path) -> Path:
    for name, content in hostile.OPTION_FILES.items():
        (tmp_path / name).write_text(content) if isinstance(content, str) else (tmp_path / name).write_bytes(content)
    return tmp_path


def _case(kind: str, key: str | int) -> Case:
    """A case by its kind and key (cases are built when a test runs, so that collecting them is quick)."""
    if kind in ("file", "fresh"):
        return hostile.file_case(int(key), fresh=kind == "fresh")
    if kind == "yaml":
        return hostile.yaml_case(str(key))
    if kind == "env":
        return hostile.environment_cases()[int(key)]
    return option_cases()[int(key)]


def _keys(files: int, slow: bool) -> list[tuple[str, str | int]]:
    n_options = len(option_cases())
    return (
        [("file", i) for i in range(files)]
        + [("fresh", i) for i in range(files // 2)]
        + [("yaml", name) for name in hostile.yaml_names(slow)]
        + [("option", i) for i in range(n_options)]
        + [("env", i) for i in range(len(hostile.environment_cases()))]
    )


def _sample() -> list[Any]:
    """The sample's cases; of each kind, every :data:`FAST_EVERY`-th runs in the fast lane, the others are slow."""
    seen: Counter[str] = Counter()
    out = []
    for kind, key in _keys(SAMPLE, slow=False):
        # a whole report (analyze of a file the checks accept) is over the default lane's budget; every other
        # one is the full run's alone (each is 8-16 s of processor time, the same report of another example)
        whole = kind == "option" and option_cases()[int(key)].argv[0] == "analyze"
        seen["whole"] += whole
        if whole and seen["whole"] % 2 == 0:
            continue
        marks = () if seen[kind] % FAST_EVERY == 0 and not whole else (pytest.mark.slow,)
        seen[kind] += 1
        out.append(pytest.param(kind, key, marks=marks, id=f"{kind}-{str(key)[:40]}"))
    return out


@pytest.mark.parametrize(("kind", "key"), _sample())
def test_a_sample_of_hostile_cases_ends_cleanly(kind, key, tmp_path):
    case = _case(kind, key)
    before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
    run = run_in_subprocess if kind == "env" else run_in_process  # its own surroundings: its own process
    outcome = run(case, _folder(tmp_path))
    assert problems(case, outcome) == [], (case.name, outcome.stderr[-1000:])
    grown = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024 - before
    assert grown < MEMORY_GROWTH, f"{case.name}: the process grew by {grown / 2**20:.0f} MiB"


@pytest.mark.hostile
@pytest.mark.parametrize(("kind", "key"), _keys(FULL, slow=True), ids=lambda k: str(k)[:40])
def test_every_hostile_case_ends_cleanly_in_its_own_process(kind, key, tmp_path):
    case = _case(kind, key)
    outcome = run_in_subprocess(case, _folder(tmp_path))
    assert problems(case, outcome) == [], (case.name, outcome.stderr[-1000:])


def _collected(*options: str) -> str:
    """What ``pytest --collect-only`` lists of this file's full run, and its summary line."""
    here = Path(__file__)
    command = [sys.executable, "-m", "pytest", str(here), "--collect-only", "-q", "-n", "0", "-p", "no:cacheprovider"]
    command += options
    proc = subprocess.run(command, capture_output=True, text=True, cwd=here.parents[2], timeout=120)
    return proc.stdout


def test_the_full_run_is_not_collected_unless_asked_for():
    """Without ``--hostile`` the full run's cases are deselected, not shown as skips; with it they are all there."""
    plain, asked = _collected(), _collected("--hostile")
    name = "test_every_hostile_case_ends_cleanly_in_its_own_process"
    full = len(_keys(FULL, slow=True))
    assert plain.count(name) == 0 and "deselected" in plain.splitlines()[-1]
    assert asked.count(name) == full > 500


#: Files with links that share through an anchor, in the sample (in the fast lane, every sixth).
SHARED = 12


@pytest.mark.parametrize(
    "seed", [pytest.param(i, marks=() if i % FAST_EVERY == 0 else (pytest.mark.slow,)) for i in range(SHARED)]
)
def test_a_file_written_where_links_share_an_anchor_solves_as_the_variant_written(seed, tmp_path):
    """The written file, read back and solved, gives the driving torque of the variant solved, to 1e-12; each
    value it was not asked to change, as before (the inertias left to their default follow their masses)."""
    import numpy as np

    import linkwork as lw
    from linkwork.spec.edit import write_text
    from linkwork.structure.parameters import file_text

    what, body, values = hostile.shared(seed)
    (tmp_path / "m.yaml").write_text(body, encoding="utf-8")
    mech = lw.compile(tmp_path / "m.yaml")
    before = lw.parameters(mech)
    out = write_text(file_text(mech, values), tmp_path / "x.yaml")
    again = lw.parameters(out)
    for name, value in before.items():
        if not name.endswith("inertia"):
            assert again[name] == pytest.approx(values.get(name, value), rel=1e-12, abs=1e-15), (what, name)
    variant = lw.forces(mech, steps=36, variants={k: [v] for k, v in values.items()}).driving_torque[0]
    np.testing.assert_allclose(lw.forces(out, steps=36).driving_torque, variant, rtol=1e-12, atol=1e-9, err_msg=what)


@pytest.mark.parametrize("seed", [0, pytest.param(1, marks=pytest.mark.slow)])
def test_a_resumed_sweep_computes_again_the_parts_that_are_no_files(seed, tmp_path):
    """Every part of a sweep replaced by a thing of :data:`hostile.ODD_PARTS` (two kinds per seed, all kinds over
    the seeds): the resume ends within its time bound and its table equals an uninterrupted run's."""
    import random
    import warnings

    pq = pytest.importorskip("pyarrow.parquet")
    import linkwork as lw

    vary, metrics, options = ["links.crank.length=80:110:6"], ["swing"], {"chunk_size": 2, "steps": 24}
    lw.sweep("four-bar", vary, metrics, out=tmp_path / "w.parquet", **options)
    out = tmp_path / "s.parquet"
    lw.sweep("four-bar", vary, metrics, out=out, keep_parts=True, **options)
    out.unlink()
    kinds = hostile.ODD_PARTS[4 * seed : 4 * seed + 4]
    parts = sorted((tmp_path / "s.parquet.parts").glob("chunk-*.parquet"))
    for part, kind in zip(parts, random.Random(seed).sample(kinds, len(parts)), strict=False):
        hostile.make_odd(kind, part)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with hostile.within(60):
            lw.sweep("four-bar", vary, metrics, out=out, resume=True, **options)
    assert pq.read_table(out).equals(pq.read_table(tmp_path / "w.parquet"), check_metadata=True), kinds


def test_the_generator_makes_what_it_says():
    """Mutations are reproducible, differ from the example, and cover the kinds the module lists."""
    assert hostile.mutated(7) == hostile.mutated(7)
    texts = {hostile.mutated(seed)[1] for seed in range(60)}
    assert len(texts) > 50
    kinds = " ".join(hostile.mutated(seed)[0] for seed in range(300))
    fresh = " ".join(hostile.mutated(seed, fresh=True)[0] for seed in range(300))
    for word in ("drop", "extra", "rename", "items", "copies", "points", "nan", "inf", "1e+308", "\\ud800"):
        assert word in kinds, word
    for word in ("^9^9", "**9**9", "=None", "1e300 rpm", "\\x1b]0;owned", "description += "):  # the fresh kinds
        assert word in fresh, word
    assert len(option_cases()) > 150 and len(hostile.yaml_cases()) > 40
    assert len(hostile.environment_cases()) > 10 and all(hostile.shared(i)[1] for i in range(3))


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
