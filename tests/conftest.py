"""What the tests share: the report of the README's main job, built once, and the markers of the lanes.

Markers (``pyproject.toml``): ``slow`` (the cases of a test beyond those the fast lane keeps of it, listed in
:data:`SLOW`: every example, both languages, both turning directions, every file; two thirds of the sample of
hostile inputs), ``browser`` (Debian's chromium through Playwright), ``dask`` (worker processes and
schedulers).  ``pytest`` (the README's test command) leaves the slow lane out, ``pytest -m slow`` runs it, and
``.ci/run`` runs both; the fast lane is ``pytest -m "not slow and not browser and not dask"``.  The full
generated run of hostile inputs (marker ``hostile``, hundreds of processes) runs only when asked for:
``pytest --hostile``.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

# The compiled kernels always, compiled when first used (once, into the user's cache), in this process and in
# every command it runs: the tests compare them with the NumPy kernels, and no command of the suite starts a
# compile in the background (tests/test_jit.py tests that route with a cache of its own).
os.environ.setdefault("LINKWORK_NUMBA", "1")


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


@pytest.fixture(scope="session")
def main_job(tmp_path_factory: pytest.TempPathFactory) -> MainJob:
    """The README's main job (``linkwork analyze double-cut-shears --out report``) run once, as written, in
    a fresh folder; the tests of the command line and of the report read what it wrote."""
    commands = quick_start()
    args = commands[0].split("&&")[-1].strip().split()
    cwd = tmp_path_factory.mktemp("main-job")
    # with the NumPy kernels, as a newcomer's first run (the compiled kernels are compared with them elsewhere;
    # a child that compiled them again would cost a minute of the suite where the cache is cold)
    env = {**os.environ, "LINKWORK_NUMBA": "0"}
    command = [sys.executable, "-m", "linkwork.cli", *args[1:]]
    proc = subprocess.run(command, capture_output=True, text=True, cwd=cwd, env=env)
    folder = cwd / args[args.index("--out") + 1] if "--out" in args else cwd
    return MainJob(commands, args, proc.returncode, proc.stderr, folder)


#: Tests of the slow lane, by node id without the parameters (``path::name``), each with the parameter ids it
#: keeps in the fast lane: each checks every bundled example (or both languages, both turning directions, a
#: list of files) where the cases kept show the same code at work.  The Russian figures stand for the English
#: ones: their words are longer, so they are the first to cover one another.
SLOW = {
    "figures/test_figures.py::test_no_text_of_a_report_figure_covers_another_and_no_axes_cover_axes": (
        "double-cut-shears-ru",
    ),
    "figures/test_figures.py::test_every_figure_draws_every_example": ("double-cut-shears",),
    "scene/test_drawings.py::test_no_text_covers_another_in_any_drawing": ("double-cut-shears-ru",),
    # the percussion rocker's Russian report builds the impact section, the one section the README's main job
    # (the double-cut shears in English, the other test's case) has not
    "report/test_build.py::test_no_english_is_left_in_the_russian_report": ("percussion-rocker",),
    "report/test_build.py::test_analyze_writes_tables_figures_and_the_report": ("double-cut-shears",),
    "report/test_build.py::test_the_time_ratio_of_a_crank_shaper_is_one_number_in_every_output": ("ccw",),
    "report/test_crank_angles.py::test_every_bundled_example_writes_phi_from_position_0": ("four-bar",),
    # the README's main job's report in the browser; the other sections (impact) are read in their own tests
    "report/test_build.py::test_the_report_renders_in_a_headless_browser": ("double-cut-shears",),
    # the main job's example and the four-bar (a coupler point, the file's own dimensions in mm)
    "report/test_inputs.py::test_every_report_says_what_it_computed": ("double-cut-shears", "four-bar"),
    # names of any script in the C locale; plain English names run through the same writer
    "cli/test_names.py::test_the_report_carries_the_names_in_the_c_locale": ("scripts",),
    # the entry point on a file the YAML reader refuses and on one that cannot be assembled (every file of the
    # corpus runs through the application in the fast lane)
    "spec/test_bad_files.py::test_bad_file_through_the_real_command": ("yaml-syntax", "unassemblable"),
}


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
        if test in SLOW and case[:-1] not in SLOW[test]:
            item.add_marker(pytest.mark.slow)
