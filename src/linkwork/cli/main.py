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
from linkwork import jit
from linkwork.cli import terminal
from linkwork.cli.app import app

__all__ = ["app", "exit_before_native_teardown", "main", "run"]


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
    jit.one_shot()  # one command, then the exit: the compiled kernels only where they pay at once
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


def run() -> None:
    """Entry point of the ``linkwork`` script and of ``python -m linkwork.cli``: :func:`main`, then, where a
    command loaded Arrow, :func:`exit_before_native_teardown` (a caller of :func:`main` keeps its process)."""
    code: object = None
    try:
        main()
    except SystemExit as exc:
        code = exc.code
        if "pyarrow" not in sys.modules:
            raise
    if "pyarrow" in sys.modules:
        exit_before_native_teardown(code)


def exit_before_native_teardown(code: object) -> None:
    """End the process with ``code`` once the exit handlers of Python have run, without the teardown of the
    libraries' native parts.

    Arrow's thread pools (``pyarrow``, which writes and reads a sweep's tables) can still be tearing down when
    the interpreter's C++ destructors run: the process then aborts after its work is done ("terminate called
    without an active exception", exit -6; apache/arrow#34314), about one exit in a hundred and fifty on a
    busy machine.  The exit handlers (``atexit``: Dask's clusters, thread pools, the streams) still run; only
    what the operating system frees anyway is skipped.
    """
    if code is not None and not isinstance(code, int):
        print(code, file=sys.stderr)  # as the interpreter prints ``sys.exit("message")``
    atexit._run_exitfuncs()
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError, terminal.OutputError):
            pass
    os._exit(code if isinstance(code, int) else (0 if code is None else 1))
