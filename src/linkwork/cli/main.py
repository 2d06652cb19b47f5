"""The ``linkwork`` command: the application with every command registered."""

from __future__ import annotations

import gc
import io
import sys

import linkwork.cli.analyze  # noqa: F401 - each command module registers its commands on ``app``
import linkwork.cli.design  # noqa: F401
import linkwork.cli.dynamics  # noqa: F401
import linkwork.cli.forces  # noqa: F401
import linkwork.cli.impact  # noqa: F401
import linkwork.cli.motion  # noqa: F401
import linkwork.cli.view  # noqa: F401
from linkwork.cli.app import app

__all__ = ["app", "main"]


def main() -> None:
    """Entry point of the ``linkwork`` script.

    Text that is not Unicode (a file name of bytes that are not UTF-8, given on the command line) is
    written escaped where the output's encoding would otherwise refuse it.  When the command is done, the
    objects made so far are frozen out of the garbage collector's reach: the process ends there, and the
    collections of its shutdown would walk every object of NumPy, SciPy, numba and matplotlib (a third of
    a second after ``linkwork analyze``) only to free memory the operating system takes back anyway.
    Files are closed where they are written, and exit handlers still run.
    """
    for stream in (sys.stdout, sys.stderr):
        if isinstance(stream, io.TextIOWrapper) and stream.errors == "strict":
            stream.reconfigure(errors="backslashreplace")
    try:
        app()
    finally:
        gc.freeze()
