"""Work done beside the report's main line, in a second process, so that two processor cores draw at once.

The second process is forked (on Linux): it shares the results computed so far without copying or
pickling them, runs its jobs (figures, the animation, a table: each writes its own files into the report's
folder) and exits; :meth:`Beside.wait` raises the first exception a job raised there, so a report is never
put in place without its files.  Where the platform does not fork safely (macOS, Windows) the jobs run in
this process when they are given.
"""

from __future__ import annotations

import os
import pickle
import signal
import sys
from collections.abc import Callable

#: Whether jobs may run in a forked process (Linux).
FORKS = sys.platform.startswith("linux") and hasattr(os, "fork")


class Beside:
    """At most one forked process running jobs; ``wait`` joins it (and is called on every way out)."""

    def __init__(self, parallel: bool = True) -> None:
        self.parallel = parallel and FORKS
        self.pid: int | None = None
        self.pipe: int | None = None

    def start(self, jobs: list[Callable[[], object]]) -> None:
        """Run ``jobs`` in order, in a forked process (or here, at once, where there is none)."""
        if not self.parallel or not jobs:
            for job in jobs:
                job()
            return
        read, write = os.pipe()
        pid = os.fork()
        if pid == 0:  # the child: run the jobs, say how it went, exit without running the parent's exit code
            os.close(read)
            _die_with_parent()
            code = 0
            try:
                for job in jobs:
                    job()
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

    def wait(self) -> None:
        """Wait for the forked process; raise the exception its jobs raised, if one did."""
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
                self.wait()
            except BaseException:  # noqa: BLE001 - the error that stopped the parent is the one to report
                pass


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
