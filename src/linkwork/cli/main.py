"""The ``linkwork`` command: the application with every command registered."""

from __future__ import annotations

import atexit
import gc
import io
import os
import sys

import linkwork.cli.analyze  # noqa: F401 - each command module registers its commands on ``app``
import linkwork.cli.design  # noqa: F401
import linkwork.cli.dynamics  # noqa: F401
import linkwork.cli.forces  # noqa: F401
import linkwork.cli.impact  # noqa: F401
import linkwork.cli.motion  # noqa: F401
import linkwork.cli.simulate  # noqa: F401
import linkwork.cli.size  # noqa: F401
import linkwork.cli.synthesize  # noqa: F401
import linkwork.cli.view  # noqa: F401
from linkwork.cli import terminal
from linkwork.cli.app import app

__all__ = ["app", "main"]


def main() -> None:
    """Entry point of the ``linkwork`` script.

    Whatever is printed goes through :mod:`linkwork.cli.terminal` (control characters escaped; output that
    cannot be written is one line on stderr and exit code 2).  Text that is not Unicode (a file name of bytes
    that are not UTF-8, given on the command line) is written escaped where the output's encoding would
    otherwise refuse it.  When the process exits, after
    every other exit handler, its objects are frozen out of the garbage collector's reach: the collections
    of the interpreter's shutdown would walk every object of NumPy, SciPy, numba and matplotlib (a third of
    a second after ``linkwork analyze``) only to free memory the operating system takes back anyway.  (A
    caller that runs ``main`` and goes on keeps its collector until it exits; files are closed where they
    are written, and the standard streams are flushed at exit all the same.)
    """
    atexit.register(gc.freeze)  # registered first, run last
    for stream in (sys.stdout, sys.stderr):
        if isinstance(stream, io.TextIOWrapper) and stream.errors == "strict":
            stream.reconfigure(errors="backslashreplace")
    terminal.install()
    os.environ["MPLBACKEND"] = "agg"  # the report draws on its own canvases, whatever the environment named
    try:
        try:
            app()
        finally:
            sys.stdout.flush()
    except terminal.OutputError as exc:
        terminal.give_up(exc)
        sys.exit(2)
