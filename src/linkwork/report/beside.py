"""Work done beside the report's main line, in a second process, so that two processor cores draw at once.

The second process is forked (on Linux): it shares the results computed so far without copying or
pickling them, takes the jobs it was given one at a time, in order (figures, the animation, a table: each
writes its own files into the report's folder), and exits when none is left.  When this process has done
its own work, :meth:`Beside.wait` has it take the jobs the other has not started, then joins it and raises
the first exception a job raised there, so a report is never put in place without its files and neither
process waits while the other has figures to draw.  The jobs are handed out as tickets, their numbers read
from one pipe by both processes (a read of a pipe is atomic: each job is taken once).  Where the platform
does not fork safely (macOS, Windows) the jobs run in this process when they are given.
"""

from __future__ import annotations

import os
import pickle
import signal
import sys
from collections.abc import Callable

#: Whether jobs may run in a forked process (Linux).
FORKS = sys.platform.startswith("linux") and hasattr(os, "fork")

#: The most jobs handed out at once (their tickets fill 4 KiB, the least a pipe holds).
MOST_JOBS = 2048


class Beside:
    """At most one forked process sharing a list of jobs with this one; ``wait`` takes what is left of them
    and joins it (and is called on every way out)."""

    def __init__(self, parallel: bool = True) -> None:
        self.parallel = parallel and FORKS
        self.pid: int | None = None
        self.pipe: int | None = None
        self.jobs: list[Callable[[], object]] = []
        self.tickets: int | None = None  # read end of the pipe of the jobs' numbers

    def start(self, jobs: list[Callable[[], object]]) -> None:
        """Have a forked process take ``jobs`` in order (or run them here, at once, where there is none)."""
        if not self.parallel or not jobs:
            for job in jobs:
                job()
            return
        self.jobs, self.tickets = jobs, _tickets(len(jobs))
        read, write = os.pipe()
        pid = os.fork()
        if pid == 0:  # the child: run the jobs, say how it went, exit without running the parent's exit code
            os.close(read)
            _die_with_parent()
            code = 0
            try:
                self._take_all()
            except BaseException as exc:  # noqa: BLE001 - every failure goes back to the parent
                code = 1
                data = memoryview(_pickled(exc))
                while data:
                    data = data[os.write(write, data) :]
            finally:
                os.close(write)
                os._exit(code)
        os.close(write)
        self.pid, self.pipe = pid, read

    def _take_all(self) -> None:
        """Run the jobs whose tickets this process draws, until none is left."""
        while self.tickets is not None and (ticket := os.read(self.tickets, 2)):
            self.jobs[int.from_bytes(ticket, "little")]()

    def wait(self) -> None:
        """Run here the jobs the forked process has not started, wait for it, and raise the exception its
        jobs raised, if one did."""
        try:
            self._take_all()
        finally:
            self._join()

    def _join(self) -> None:
        if self.tickets is not None:
            os.close(self.tickets)
            self.tickets = None
        if self.pid is None or self.pipe is None:
            return
        pid, pipe = self.pid, self.pipe
        self.pid = self.pipe = None
        chunks = []
        while chunk := os.read(pipe, 1 << 16):
            chunks.append(chunk)
        os.close(pipe)
        _, status = os.waitpid(pid, 0)
        if chunks:
            raise _unpickled(b"".join(chunks))
        if status != 0:
            raise RuntimeError(f"the process drawing the figures ended with status {status}")

    def stop(self) -> None:
        """End the forked process, if it runs, and reap it (on the way out after an error)."""
        if self.pid is not None:
            try:
                os.kill(self.pid, signal.SIGKILL)
            except ProcessLookupError:  # pragma: no cover - it ended by itself
                pass
        try:
            self._join()
        except BaseException:  # noqa: BLE001 - the error that stopped the parent is the one to report
            pass


def _tickets(count: int) -> int:
    """The read end of a pipe holding the numbers ``0 .. count - 1``, two bytes each, its write end closed
    (written whole before anyone reads: at most :data:`MOST_JOBS`, which a pipe's buffer always holds)."""
    if count > MOST_JOBS:
        raise ValueError(f"{count} jobs: at most {MOST_JOBS} can be handed out")
    read, write = os.pipe()
    data = memoryview(b"".join(i.to_bytes(2, "little") for i in range(count)))
    while data:
        data = data[os.write(write, data) :]
    os.close(write)
    return read


def _die_with_parent() -> None:
    """Have the kernel end this process when its parent ends (Linux ``PR_SET_PDEATHSIG``), so that a killed
    ``analyze`` leaves nothing writing into its folder."""
    try:
        import ctypes

        ctypes.CDLL(None, use_errno=True).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG = 1
    except (OSError, AttributeError):  # pragma: no cover - not Linux's C library
        pass


def _pickled(exc: BaseException) -> bytes:
    try:
        return pickle.dumps(exc)
    except Exception:  # noqa: BLE001 - an exception that does not pickle goes back as its text
        return pickle.dumps(RuntimeError(f"{type(exc).__name__}: {exc}"))


def _unpickled(data: bytes) -> BaseException:
    try:
        exc = pickle.loads(data)
    except Exception:  # noqa: BLE001
        return RuntimeError("the process drawing the figures failed")
    return exc if isinstance(exc, BaseException) else RuntimeError(str(exc))
