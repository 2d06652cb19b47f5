"""The ``linkwork`` command: the application with every command registered."""

from __future__ import annotations

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
    written escaped where the output's encoding would otherwise refuse it.
    """
    for stream in (sys.stdout, sys.stderr):
        if isinstance(stream, io.TextIOWrapper) and stream.errors == "strict":
            stream.reconfigure(errors="backslashreplace")
    app()
