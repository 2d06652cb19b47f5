"""What the tests share: the reports they read, each built once for the whole run (both xdist workers), the
kernels they run, the lanes and the time budget of a test.

The lanes (markers in ``pyproject.toml``; the README's test command ``pytest`` runs the default lane, on both
cores through pytest-xdist, and ``.ci/run`` runs every lane after it):

- default: everything not marked below, on the NumPy kernels (``LINKWORK_NUMBA=0`` for this process and every
  command it runs), each test within :data:`BUDGET` seconds;
- ``slow``: the cases of a test beyond those the default lane keeps of it (:data:`SLOW`: every example, both
  languages, both turning directions, every file; most of the sample of hostile inputs), and tests that build
  whole reports of several examples: ``pytest -m slow --dist worksteal`` (a test to the next worker free);
- ``numba``: the compiled kernels, compared with the NumPy ones; each such test turns them on for itself
  (:func:`compiled_kernels`): ``linkwork warm && pytest -m numba``;
- ``browser``: Debian's chromium through Playwright: ``pytest -m browser``;
- ``dask``: Dask schedulers and worker processes: ``pytest -m dask``;
- ``hostile``: the full generated run of hostile inputs (hundreds of processes), only with ``pytest --hostile``.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

# The NumPy kernels in this process and in every command it runs, as a newcomer's first commands have them: a
# fresh clone's cache is empty, and compiling the numba kernels costs minutes of processor time.  The tests of
# the compiled kernels (marker ``numba``) turn them on for themselves (:func:`compiled_kernels`), and no command
# of the suite starts a compile in the background (tests/test_jit.py tests that route with a cache of its own).
os.environ.setdefault("LINKWORK_NUMBA", "0")

#: Seconds of processor time (this process's and its children's) the call of a test of the default lane may
#: take, and its setup (where a shared report is built by the first test that asks for it); and seconds of wall
#: time either may take (a test that waits for nothing should not wait that long, however loaded the machine).  A
#: test that needs more belongs to a lane of its own.  ``LINKWORK_NO_BUDGET=1`` lifts the budget (a debugger, a
#: profiler).  Processor time, not wall time: the budget is the same on a busy machine.
BUDGET, SETUP_BUDGET, WALL = 5.0, 30.0, 300.0


@dataclass(frozen=True)
class MainJob:
    """The README's Quick start: its two commands, and the report the first one wrote."""

    commands: list[str]
    args: list[str]
    returncode: int
    stderr: str
    folder: Path


def quick_start() -> list[str]:
    """The command lines of the README's Quick start."""
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    quick = readme.split("## Quick start", 1)[1].split("\n## ", 1)[0]
    blocks = re.findall(r"```(?:bash|sh)?\n(.*?)```", quick, flags=re.S)
    return [line for block in blocks for line in block.strip().splitlines()]


def shared_folder(factory: pytest.TempPathFactory, key: str, make: Callable[[Path], None]) -> Path:
    """The folder ``key`` of the whole run, made by ``make(folder)`` once whichever xdist worker asks first (the
    others wait for it under a file lock); a make that raised is made again by the next caller."""
    from filelock import FileLock

    root = factory.getbasetemp()
    if os.environ.get("PYTEST_XDIST_WORKER"):
        root = root.parent  # the workers' base folders are siblings
    folder = root / "shared" / re.sub(r"[^\w.=-]+", "_", key)
    folder.parent.mkdir(parents=True, exist_ok=True)
    with FileLock(str(folder) + ".lock"):
        if not (folder.parent / f"{folder.name}.done").exists():
            shutil.rmtree(folder, ignore_errors=True)
            folder.mkdir()
            make(folder)
            (folder.parent / f"{folder.name}.done").touch()
    return folder


@pytest.fixture(scope="session")
def main_job(tmp_path_factory: pytest.TempPathFactory) -> MainJob:
    """The README's main job (``linkwork analyze double-cut-shears --out report``) run once for the whole run,
    as written, in a fresh folder, with the NumPy kernels as a newcomer's first run has them; the tests of the
    command line and of the report read what it wrote."""
    commands = quick_start()
    args = commands[0].split("&&")[-1].strip().split()

    def run(cwd: Path) -> None:
        command = [sys.executable, "-m", "linkwork.cli", *args[1:]]
        proc = subprocess.run(command, capture_output=True, text=True, cwd=cwd, env=os.environ)
        (cwd.parent / f"{cwd.name}.json").write_text(json.dumps([proc.returncode, proc.stderr]), encoding="utf-8")

    cwd = shared_folder(tmp_path_factory, "main-job", run)
    code, stderr = json.loads((cwd.parent / f"{cwd.name}.json").read_text(encoding="utf-8"))
    folder = cwd / args[args.index("--out") + 1] if "--out" in args else cwd
    return MainJob(commands, args, code, stderr, folder)


@pytest.fixture(scope="session")
def report(tmp_path_factory: pytest.TempPathFactory) -> Callable[..., Path]:
    """``report(name, **options)``: the folder of a bundled example's (or a file's) report written by
    :func:`linkwork.report.analyze` with these options (default 36 steps and no animation, the least that
    draws every section), built once for the whole run; tests that read a report only read it."""

    def get(name: str, **options: object) -> Path:
        options = {"steps": 36, "animation": False, **options}
        key = "report-" + Path(name).name + "-" + "-".join(f"{k}={v}" for k, v in sorted(options.items()))

        def make(folder: Path) -> None:
            import linkwork as lw
            from linkwork import report as build

            build.analyze(lw.compile(lw.load(name)), folder / "r", **options)  # type: ignore[arg-type]

        return shared_folder(tmp_path_factory, key, make) / "r"

    return get


def _png(width: int, height: int) -> bytes:
    """A blank PNG of ``width`` x ``height`` pixels (grey, 8 bits)."""
    import struct
    import zlib

    def chunk(kind: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    rows = b"".join(b"\0" + b"\xff" * width for _ in range(height))
    head = struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", head) + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b"")


@pytest.fixture
def sketched_figures(monkeypatch: pytest.MonkeyPatch) -> None:
    """A report's figures written as blank pictures, not drawn (in this process, no second one): for the tests of
    what a report's folder, tables and page hold, whose figures other tests draw and read."""
    from linkwork.report import build
    from linkwork.report.run import ReportRun

    png = _png(20, 10)

    def sketch(self: object, name: str, make: Callable[[], object]) -> None:
        stem = self.folder / "figures" / name  # type: ignore[attr-defined]
        stem.with_suffix(".png").write_bytes(png)
        stem.with_suffix(".svg").write_text("<svg xmlns='http://www.w3.org/2000/svg'/>", encoding="utf-8")

    monkeypatch.setattr(ReportRun, "_draw", sketch)
    monkeypatch.setattr(build, "PARALLEL", False)


@pytest.fixture(autouse=True)
def compiled_kernels(request: pytest.FixtureRequest, monkeypatch: pytest.MonkeyPatch) -> Iterator[None]:
    """A test marked ``numba`` runs with the compiled kernels (``LINKWORK_NUMBA=1``, compiled into the cache when
    first used; ``linkwork warm`` compiles them before the lane), and fails where they do not load where numba
    is installed: a comparison of the twins never compares the NumPy kernels with themselves."""
    if request.node.get_closest_marker("numba") is None:
        yield
        return
    from linkwork import jit

    if not jit.installed():
        pytest.skip("numba is not installed on this platform (the NumPy kernels are the only ones)")
    monkeypatch.setenv("LINKWORK_NUMBA", "1")
    assert jit.mode() == jit.ALWAYS  # each kernel with a compiled twin runs it (compiled or read from the cache)
    yield


def processor_seconds() -> float:
    """Seconds of processor time of this process and of its children that have ended (where the platform counts
    them): what a test costs whatever else the machine is doing."""
    try:
        import resource
    except ImportError:  # Windows: this process only
        return time.process_time()
    own, children = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime


_SPENT = pytest.StashKey[dict[str, float]]()


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_setup(item: pytest.Item) -> Iterator[None]:
    start = processor_seconds()
    yield
    item.stash.setdefault(_SPENT, {})["setup"] = processor_seconds() - start


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_call(item: pytest.Item) -> Iterator[None]:
    start = processor_seconds()
    yield
    item.stash.setdefault(_SPENT, {})["call"] = processor_seconds() - start


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item: pytest.Item, call: pytest.CallInfo[None]) -> Iterator[None]:
    """Fail a test of the default lane whose call took more than :data:`BUDGET` seconds of processor time, or
    whose setup took more than :data:`SETUP_BUDGET` (a shared report it was the first to ask for included), or
    either more than :data:`WALL` seconds of wall time: the lane's time is a budget, and a test over it goes to a
    lane of its own (``slow``, ``browser``, ``dask``, ``numba``)."""
    outcome = yield
    rep = outcome.get_result()
    limit = {"call": BUDGET, "setup": SETUP_BUDGET}.get(call.when)
    lanes = ("slow", "browser", "dask", "numba", "hostile")
    if limit is None or not rep.passed or any(item.get_closest_marker(m) for m in lanes):
        return
    if os.environ.get("LINKWORK_NO_BUDGET"):
        return
    spent = item.stash.get(_SPENT, {}).get(call.when, 0.0)
    if spent > limit or call.duration > WALL:
        rep.outcome = "failed"
        rep.longrepr = (
            f"{item.nodeid}: its {call.when} took {spent:.1f} s of processor time and {call.duration:.1f} s of wall "
            f"time, over the default lane's budget of {limit:.0f} s and {WALL:.0f} s (tests/conftest.py: BUDGET); "
            "make it cheaper, or put it in the slow lane (tests/slow-tests.txt)"
        )


#: Tests of the slow lane, by node id without the parameters (``path::name``), each with the parameter ids it
#: keeps in the fast lane: each checks every bundled example (or both languages, both turning directions, a
#: list of files) where the cases kept show the same code at work.  The Russian figures stand for the English
#: ones: their words are longer, so they are the first to cover one another.
SLOW = {
    # a whole Russian report drawn in this process (17 s of processor time): the slow lane's; the default lane
    # reads the Russian drawings' texts in scene/test_drawings.py
    "figures/test_figures.py::test_no_text_of_a_report_figure_covers_another_and_no_axes_cover_axes": (),
    "figures/test_figures.py::test_every_figure_draws_every_example": ("four-bar",),
    "scene/test_drawings.py::test_no_text_covers_another_in_any_drawing": ("double-cut-shears-ru",),
    # the sheets of every format but A1 in Russian (each 2-3 s of processor time, written and read back) in the slow
    # lane; the other formats place the same drawings by the same rule
    "scene/test_sheets.py::test_no_text_is_under_2_5_mm_nor_covers_another_on_any_sheet": ("A1-ru",),
    # a whole Russian report with the plans of all twelve positions (28 s of processor time): the slow lane's
    "report/test_build.py::test_no_english_is_left_in_the_russian_report": (),
    "report/test_build.py::test_analyze_writes_tables_figures_and_the_report": ("double-cut-shears",),
    "report/test_build.py::test_the_time_ratio_of_a_crank_shaper_is_one_number_in_every_output": ("ccw",),
    "report/test_crank_angles.py::test_every_bundled_example_writes_phi_from_position_0": ("four-bar",),
    # the README's main job's report in the browser; the other sections (impact) are read in their own tests
    "report/test_build.py::test_the_report_renders_in_a_headless_browser": ("double-cut-shears",),
    # the four-bar (a coupler point, the file's own dimensions in mm); the main job's example in the slow lane
    "report/test_inputs.py::test_every_report_says_what_it_computed": ("four-bar",),
    # names of any script in the C locale; plain English names run through the same writer
    # (a report in a process of its own in the C locale: 18 s of processor time, the slow lane's)
    "cli/test_names.py::test_the_report_carries_the_names_in_the_c_locale": (),
    # the entry point on a file the YAML reader refuses and on one that cannot be assembled (every file of the
    # corpus runs through the application in the fast lane)
    "spec/test_bad_files.py::test_bad_file_through_the_real_command": ("yaml-syntax", "unassemblable"),
}


#: Tests over the default lane's budget, by node id (``tests/slow-tests.txt``): the slow lane runs them.
SLOW_TESTS = frozenset(
    line.strip()
    for line in (ROOT / "tests" / "slow-tests.txt").read_text(encoding="utf-8").splitlines()
    if line.strip() and not line.startswith("#")
)


def pytest_addoption(parser: pytest.Parser) -> None:
    parser.addoption("--hostile", action="store_true", help="also run the full generated run of hostile inputs")


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    """Leave out the full generated run of hostile inputs unless ``--hostile`` asks for it (deselected, so that the
    summary's skips are real ones), and mark the cases of :data:`SLOW` beyond those the fast lane keeps."""
    if not config.getoption("--hostile"):
        left = [item for item in items if item.get_closest_marker("hostile") is not None]
        if left:
            config.hook.pytest_deselected(items=left)
            items[:] = [item for item in items if item.get_closest_marker("hostile") is None]
    for item in items:
        test, _, case = item.nodeid.replace("\\", "/").split("tests/", 1)[-1].partition("[")
        if (test in SLOW and case[:-1] not in SLOW[test]) or item.nodeid in SLOW_TESTS:
            item.add_marker(pytest.mark.slow)
