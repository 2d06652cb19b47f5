"""Where the command line's text goes: standard output and error, with what no terminal should act on escaped,
and a write that fails said once.

:func:`install` puts every ``print``, ``typer.echo`` and warning through :func:`~linkwork.limits.printable` (a
name with an escape sequence is shown, not obeyed); :func:`console` is the rich console of the reports, whose
own styles and cursor moves go out as they are and whose text is escaped the same way.  A write that fails (a
full disk, ``> /dev/full``) raises :class:`OutputError`, which :func:`linkwork.cli.main.main` turns into one
line on stderr and exit code 2; a closed pipe stays the ``OSError`` (EPIPE) the command line already handles.
"""

from __future__ import annotations

import errno
import os
import sys
from collections.abc import Iterable
from typing import TYPE_CHECKING, Any, TextIO

from linkwork.limits import printable

if TYPE_CHECKING:
    from rich.console import Console
    from rich.segment import Segment


class OutputError(Exception):
    """Standard output or error cannot be written (not a closed pipe): ``str()`` says why."""


class _Stream:
    """A text stream that writes to ``raw``, escaped where ``escape``; a failed write raises OutputError.

    It holds no ``buffer``, so that click writes through it rather than around it."""

    def __init__(self, raw: TextIO, escape: bool):
        self.unescaped, self.escape = raw, escape

    def write(self, text: str) -> int:
        _guard(self.unescaped.write, printable(text) if self.escape else text)
        return len(text)

    def flush(self) -> None:
        _guard(self.unescaped.flush)

    def __getattr__(self, name: str) -> Any:
        if name == "buffer":
            raise AttributeError(name)
        return getattr(self.unescaped, name)


def _guard(call: Any, *args: Any) -> Any:
    try:
        return call(*args)
    except OSError as exc:
        if exc.errno == errno.EPIPE:
            raise
        raise OutputError(f"cannot write the output: {exc.strerror or exc}") from None


def install() -> None:
    """Put standard output and error through :class:`_Stream` (once)."""
    for name in ("stdout", "stderr"):
        stream = getattr(sys, name)
        if stream is not None and not isinstance(stream, _Stream):
            setattr(sys, name, _Stream(stream, escape=True))


def raw(stream: Any) -> Any:
    """The stream under :func:`install`'s (its ``unescaped``)."""
    return stream.unescaped if isinstance(stream, _Stream) else stream


def console(stderr: bool = False, **options: Any) -> Console:
    """A rich console of standard output (or error): its styles and cursor moves as rich writes them, its text
    escaped by :func:`~linkwork.limits.printable`."""
    from rich.console import Console
    from rich.segment import Segment

    class _Console(Console):
        def _render_buffer(self, buffer: Iterable[Segment]) -> str:
            shown = (s if s.control else Segment(printable(s.text), s.style, s.control) for s in buffer)
            return super()._render_buffer(shown)

    stream = raw(sys.stderr if stderr else sys.stdout)
    return _Console(file=_Stream(stream, escape=False), stderr=stderr, **options)  # type: ignore[arg-type]


def give_up(exc: OutputError) -> None:
    """Say ``exc`` on stderr (where it can be written) and point standard output at nothing, so that what is
    left in its buffer does not fail again when the interpreter exits."""
    try:
        raw(sys.stderr).write(f"error: {exc}\n")
        raw(sys.stderr).flush()
    except OSError:
        pass
    for stream in (sys.stdout, sys.stderr):
        try:
            null = os.open(os.devnull, os.O_WRONLY)
            os.dup2(null, raw(stream).fileno())
            os.close(null)
        except (OSError, ValueError, AttributeError):
            pass
