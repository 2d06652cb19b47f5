"""``linkwork`` run through the command's application in the test's own process.

For the tests of what a command prints, writes and exits with: the same application ``python -m linkwork.cli``
runs, without a second of interpreter start and imports each time.  What only a process of its own shows (a
kill, a terminal, a memory bound, the modules a fresh start imports) is tested with one.  The hostile cases
run through the application likewise, under a time bound (:func:`hostile.run_in_process`).
"""

from __future__ import annotations

import contextlib
import subprocess
import traceback
from pathlib import Path

from typer.testing import CliRunner


def linkwork(*args: str, cwd: str | Path | None = None) -> subprocess.CompletedProcess[str]:
    """``linkwork ARGS`` in the folder ``cwd`` (the current one by default): its exit code, stdout and stderr,
    as :func:`subprocess.run` gives them.  An exception that escapes the command exits 1 with its traceback
    on stderr, as the interpreter would print it."""
    from linkwork.cli.main import app

    with contextlib.chdir(cwd or "."):
        result = CliRunner().invoke(app, list(args))
    stderr = result.stderr
    if result.exception is not None and not isinstance(result.exception, SystemExit):
        stderr += "".join(traceback.format_exception(result.exception))
    return subprocess.CompletedProcess(["linkwork", *args], result.exit_code, result.stdout, stderr)
