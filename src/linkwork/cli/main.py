"""The ``linkwork`` command: the application with every command registered."""

from __future__ import annotations

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
    """Entry point of the ``linkwork`` script."""
    app()
