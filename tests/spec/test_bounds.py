"""What a mechanism file may ask of the reader: nested aliases, a large file, many points and long numbers
are refused at a bound, or read in near-linear time, with messages that quote a short excerpt."""

from __future__ import annotations

import itertools
import math
import random
import time
from pathlib import Path

import pytest
from ruamel.yaml import YAML

import linkwork as lw
from hostile import Case, problems, run_in_subprocess, within
from linkwork.errors import SpecError, UnitParseError
from linkwork.examples import text
from linkwork.spec.reader import validate
from linkwork.spec.yamlsource import Source, read_yaml
from linkwork.units import parse_quantity


def _laughs(levels: int, width: int) -> str:
    """``levels`` lists of ``width`` aliases of the list before: ``width ** levels`` values once expanded."""
    lines = ["name: bomb", f"a0: &a0 [{', '.join(['lol'] * width)}]"]
    lines += [f"a{i}: &a{i} [{', '.join([f'*a{i - 1}'] * width)}]" for i in range(1, levels)]
    return "\n".join(lines) + "\n"


@pytest.mark.parametrize(
    "yaml_text",
    [
        _laughs(9, 9),  # 387 million values from 500 bytes
        _laughs(40, 2),  # a trillion
        "a0: &a0 {k: 1}\n" + "".join(f"a{i}: &a{i} {{<<: [{', '.join([f'*a{i - 1}'] * 8)}]}}\n" for i in range(1, 9)),
    ],
    ids=["9x9", "40x2", "merge-keys"],
)
def test_nested_aliases_stop_at_the_bound_on_values(yaml_text, tmp_path):
    """Each was expanded without a limit (minutes and gigabytes): here in a process of its own, under a
    bound on its memory."""
    case = Case("check", ("check", "{dir}/bomb.yaml"), {"bomb.yaml": yaml_text})
    outcome = run_in_subprocess(case, tmp_path, limit=30)
    assert outcome.code == 2 and problems(case, outcome) == [], outcome.stderr
    assert "more than 100,000 values" in outcome.stderr


def _merges(keys: int, width: int, levels: int) -> str:
    """A mapping of ``keys`` keys, then ``levels - 1`` mappings that each merge the one before ``width`` times:
    ``keys * width ** (levels - 1)`` merged keys from a few kilobytes."""
    lines = ["a0: &a0 {" + ", ".join(f"k{i}: {i}" for i in range(keys)) + "}"]
    lines += [f"a{i}: &a{i} {{<<: [{', '.join([f'*a{i - 1}'] * width)}]}}" for i in range(1, levels)]
    return "\n".join(lines) + "\n"


@pytest.mark.parametrize("keys, width, levels", [(5000, 2000, 3), (0, 60, 6), (200, 50, 8)])
def test_merged_keys_count_against_the_bound_on_values(keys, width, levels):
    """A merge that a list of aliases repeats was gathered without a bound (33 s for the first, hours for the
    second: merges of empty mappings that add no key); each merged key and each merged mapping counts now."""
    with within(10), pytest.raises(SpecError, match="more than 100,000 values"):
        lw.loads(_merges(keys, width, levels), file="merge.yaml")


def test_merge_keys_mean_what_yaml_says_nested_and_in_order():
    """The values built (with each one's line) equal those of ruamel's own safe loader: a merge's own merges
    resolved, an earlier mapping of a list overriding a later one, the mapping's own keys overriding both."""
    body = "a0: &a0 {k: 1, j: 1}\na1: &a1 {<<: *a0, j: 2}\na2: {<<: [*a1, {k: 3, n: 5}], m: 4, k: 6}\n"
    src = read_yaml(body)
    assert src.problems == [] and src.data == YAML(typ="safe").load(body)
    assert src.data["a2"] == {"k": 6, "j": 2, "n": 5, "m": 4}


def test_an_alias_that_holds_itself_is_one_problem():
    with within(20), pytest.raises(SpecError) as err:
        lw.loads("name: x\nlinks: &a [*a]\n", file="self.yaml")
    assert "nesting too deep" in str(err.value)


@pytest.mark.parametrize(
    ("argv", "says"),
    [
        (("check", "{dir}/large.yaml"), "larger than 1 MiB"),  # 2.4 MB of small values: read for a minute
        (("check", "/dev/zero"), "character device"),  # read until memory ran out
        (("check", "/proc/self/mem"), "cannot read the file: Input/output error"),  # its read fails: EIO
        (("check", "/proc/self/pagemap"), "cannot read the file: Invalid argument"),  # EINVAL
    ],
    ids=["large", "device", "eio", "einval"],
)
def test_a_file_too_large_or_a_device_is_refused_unread(argv, says, tmp_path):
    if argv[1].startswith("/proc") and not Path(argv[1]).exists():
        pytest.skip("needs Linux's /proc")
    case = Case("check", argv, {"large.yaml": "name: x\nk:\n" + "- 1\n" * 600_000})
    outcome = run_in_subprocess(case, tmp_path, limit=30)
    assert outcome.code == 2 and problems(case, outcome) == [], outcome.stderr
    assert says in outcome.stderr


def _with_markers(n: int, spacing: float = 1.0) -> dict:
    data = YAML(typ="safe").load(text("four-bar"))
    data["links"]["coupler"]["points"] = {f"P{i}": [i * spacing, 1.0] for i in range(n)}
    return data


def test_twenty_thousand_points_on_a_link_are_checked_in_near_linear_time():
    """Every pair of the points was compared: 2e8 pairs took minutes."""
    with within(20):
        spec = validate(Source(_with_markers(20_000), {}, "many.yaml", []))
    assert len(spec.links["coupler"].points) == 20_000


def _brute(points: dict[str, tuple[float, float]], tol: float) -> set[str]:
    """The points that coincide with some point before them (every pair compared)."""
    names = list(points)
    return {
        b
        for i, b in enumerate(names)
        for a in names[:i]
        if math.hypot(points[a][0] - points[b][0], points[a][1] - points[b][1]) < tol
    }


def test_coincident_points_are_those_every_pair_compared_finds():
    from linkwork.spec.reader import COINCIDE, coincident

    rng = random.Random(5)
    base = [(rng.uniform(-1, 1), rng.uniform(-1, 1)) for _ in range(60)]
    # copies, and points a fraction of the tolerance away, either side of a cell's edge
    near = [(x + f * COINCIDE, y - f * COINCIDE) for (x, y), f in zip(base[:30], itertools.cycle((0.0, 0.4, 0.7, 2.0)))]
    edge = [(0.0, 0.0), (-0.3 * COINCIDE, 0.2 * COINCIDE), (5 * COINCIDE, 0.0), (math.inf, 1.0), (math.inf, 1.0)]
    pts = base + near + edge
    rng.shuffle(pts)
    points = {f"P{i}": p for i, p in enumerate(pts)}
    found = coincident(points)
    assert {b for _, b in found} == _brute(points, COINCIDE)
    assert all(
        math.hypot(points[a][0] - points[b][0], points[a][1] - points[b][1]) < COINCIDE
        for a, b in found
        if math.isfinite(points[a][0])
    )


@pytest.mark.parametrize(
    "value",
    ["1 m" + " " * 20_000 + "!", "1" * 20_000 + "!", "1 " + "m " * 10_000 + "!", "1 " + "m*" * 10_000 + "!"],
    ids=["spaces", "digits", "names", "products"],
)
def test_a_long_quantity_is_refused_in_linear_time_with_a_short_excerpt(value):
    """The unit patterns backtracked: 20 kB took 12 to 38 s, and the message quoted all of it."""
    start = time.perf_counter()
    with within(10), pytest.raises(UnitParseError) as err:
        parse_quantity(value, "length")
    assert time.perf_counter() - start < 1.0
    assert len(str(err.value)) < 300
