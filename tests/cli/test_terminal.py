"""What the command line prints: control characters from a file or an option are shown escaped, never obeyed by
the terminal, and output that cannot be written is one line on stderr and exit code 2."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

import linkwork
from linkwork.examples import text

#: A name that would retitle the terminal's window, ring its bell and clear its screen.
HOSTILE_NAME = "\x1b]0;owned\x07\x1b[2J\x9b"


def _run(*argv: str, stdout: object = subprocess.PIPE, **env: str) -> subprocess.CompletedProcess[bytes]:
    source = str(Path(linkwork.__file__).resolve().parents[1])
    environ = {**os.environ, "PYTHONPATH": source, "LINKWORK_NUMBA": "0", **env}
    return subprocess.run(
        [sys.executable, "-m", "linkwork.cli", *argv], stdout=stdout, stderr=subprocess.PIPE, env=environ, timeout=120
    )


def _controls(out: bytes) -> set[str]:
    """The control characters in ``out`` but newline and tab, and the escape sequences that are not a colour
    or a style (``ESC [ ... m``), which rich writes for a terminal."""
    import re

    text = re.sub(r"\x1b\[[0-9;]*m", "", out.decode("utf-8", "replace"))
    return {c for c in text if (ord(c) < 32 and c not in "\n\t") or 0x7F <= ord(c) <= 0x9F}


@pytest.mark.parametrize("terminal", [False, True], ids=["piped", "terminal"])
@pytest.mark.parametrize("argv", [("check",), ("kinematics", "--steps", "12"), ("forces", "--steps", "12")])
def test_a_name_with_escape_sequences_is_printed_escaped(tmp_path, argv, terminal):
    path = tmp_path / "m.yaml"
    name = HOSTILE_NAME.encode("unicode_escape").decode("ascii")
    path.write_text(text("four-bar").replace("name: four-bar", f'name: "{name}"'), encoding="utf-8")
    r = _run(argv[0], str(path), *argv[1:], **({"FORCE_COLOR": "1"} if terminal else {}))
    assert r.returncode == 0, r.stderr
    assert _controls(r.stdout + r.stderr) == set()
    assert "\\x1b]0;owned" in r.stdout.decode()  # the name is there, shown (click drops a colour or a move when piped)


def test_an_option_with_escape_sequences_is_quoted_escaped():
    r = _run("check", "\x1b[2J\x1b]0;owned\x07.yaml")
    assert r.returncode == 2 and _controls(r.stderr) == set(), r.stderr
    assert "\\x1b]0;owned" in r.stderr.decode()


@pytest.mark.skipif(not os.path.exists("/dev/full"), reason="needs /dev/full")
@pytest.mark.parametrize(
    "argv",
    [
        ("check", "four-bar"),
        ("check", "four-bar", "--json"),
        ("kinematics", "four-bar", "--json"),
        ("forces", "four-bar", "--steps", "36"),
        ("parameters", "four-bar"),
        ("example", "four-bar"),
        ("examples",),
    ],
)
def test_output_that_cannot_be_written_is_one_line_and_exit_code_2(argv):
    with open("/dev/full", "w") as full:
        r = _run(*argv, stdout=full)
    assert r.returncode == 2
    assert r.stderr.decode() == "error: cannot write the output: No space left on device\n"


def test_a_closed_pipe_ends_quietly():
    proc = subprocess.Popen(
        [sys.executable, "-m", "linkwork.cli", "kinematics", "four-bar", "--json"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        env={**os.environ, "PYTHONPATH": str(Path(linkwork.__file__).resolve().parents[1]), "LINKWORK_NUMBA": "0"},
    )
    assert proc.stdout is not None and proc.stdout.read(10)
    proc.stdout.close()
    _, err = proc.communicate(timeout=120)
    assert b"Traceback" not in err and proc.returncode in (0, 1, 2)
