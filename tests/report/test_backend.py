"""The report draws on its own Agg canvases whatever backend the environment names: ``MPLBACKEND=bogus``, which
matplotlib refuses at import, was a traceback."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import linkwork


def _env(**extra: str) -> dict[str, str]:
    source = str(Path(linkwork.__file__).resolve().parents[1])
    return {**os.environ, "PYTHONPATH": source, "LINKWORK_NUMBA": "0", **extra}


def test_analyze_writes_its_report_under_a_backend_matplotlib_does_not_know(tmp_path):
    r = subprocess.run(
        [
            sys.executable,
            "-m",
            "linkwork.cli",
            "analyze",
            "four-bar",
            "--out",
            str(tmp_path / "r"),
            "--steps",
            "36",
            "--no-animation",
        ],
        capture_output=True,
        text=True,
        env=_env(MPLBACKEND="bogus"),
        timeout=600,
    )
    assert r.returncode == 0 and "Traceback" not in r.stderr, r.stderr[-2000:]
    report = (tmp_path / "r" / "report.html").read_text(encoding="utf-8")
    assert "<img" in report and (tmp_path / "r" / "figures").is_dir()


def test_the_drawings_import_under_it_and_leave_the_environment_as_it_was():
    code = (
        "import os, linkwork as lw, linkwork.figures as f\n"
        "fig = f.draw_scheme(lw.kinematics('four-bar', steps=12))\n"
        "print(os.environ['MPLBACKEND'], type(fig).__name__)\n"
    )
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=_env(MPLBACKEND="bogus"))
    assert r.returncode == 0, r.stderr[-2000:]
    assert r.stdout.split() == ["bogus", "Figure"]
