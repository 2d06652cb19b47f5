"""``python -m linkwork.cli``: the ``linkwork`` command."""

from linkwork.cli.main import run

run()
