"""The report's folder: built beside its place, swapped in whole, and only ever replacing a report.

A report is built in a hidden folder ``.NAME.<12 hex>.part`` beside the
folder ``NAME`` it is for, marked by a file :data:`MARKER` that names every
file the report holds.  When the report is complete it takes the place of
``NAME`` in one step (Linux's ``renameat2`` exchange; elsewhere two renames,
the old report first moved to ``.NAME.<hex>.old``) and the old one is
removed.  Only a folder that does not exist, an empty folder, or a folder
whose marker lists everything in it is replaced: anything else (a folder
of other files, a file, a symbolic link, a device) is refused before any
work and left as it was.

A run that is killed leaves its hidden folders behind; the next run into the
same ``NAME`` removes them, and where ``NAME`` is missing (killed between
the two renames) first puts the newest complete report among them back.  A
folder in use is locked (``flock``) by its run, so a run never touches
another live run's folders.
"""

from __future__ import annotations

import ctypes
import errno
import functools
import json
import os
import re
import secrets
import shutil
import stat
import sys
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path, PurePosixPath
from typing import Any

try:
    import fcntl
except ImportError:  # pragma: no cover - not on POSIX: no locks, so no clean-up of other runs' folders
    fcntl = None  # type: ignore[assignment]

from linkwork.errors import LinkworkError

#: The file that marks a folder as a report linkwork wrote, and lists its files.
MARKER = ".linkwork-report"

#: Version of the marker's content.
FORMAT = 1

_NOTE = (
    "linkwork analyze wrote this folder; a later run with the same --out replaces it whole, "
    "as long as it holds no other files than these"
)


def entries(folder: Path) -> set[str]:
    """Every file and folder under ``folder`` (links not followed), as ``/``-separated relative paths."""

    def fail(exc: OSError) -> None:
        raise exc

    found: set[str] = set()
    for root, dirs, files in os.walk(folder, onerror=fail):
        rel = PurePosixPath(Path(root).relative_to(folder).as_posix())
        found.update(str(rel / n) for n in (*dirs, *files))
    return found


def read_marker(folder: Path) -> dict[str, Any] | None:
    """The marker of a folder linkwork wrote (``complete``, ``files``), or None: no marker, or not one of ours."""
    path = folder / MARKER
    try:
        if not stat.S_ISREG(os.lstat(path).st_mode):
            return None
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    if not isinstance(data, dict) or data.get("linkwork_report") != FORMAT:
        return None
    files = data.get("files")
    if not isinstance(files, list) or not all(isinstance(f, str) for f in files):
        return None
    return data


def _mark(folder: Path, complete: bool) -> None:
    """Write the marker: ``complete`` with the list of every file now in ``folder``."""
    from linkwork.atomic import write_atomic

    files = sorted(entries(folder) - {MARKER}) if complete else []
    text = json.dumps({"linkwork_report": FORMAT, "note": _NOTE, "complete": complete, "files": files}, indent=1)
    write_atomic(folder / MARKER, lambda tmp: tmp.write_text(text + "\n", encoding="utf-8"))


def problem(out: str | Path) -> str | None:
    """Why the folder ``out`` may not be written or replaced by a report, or None.

    It may be: a path that does not exist, an empty folder, or a report folder whose marker
    lists everything in it.  Not: anything else, nor a folder that holds the current one.
    """
    from linkwork.atomic import kind

    out = Path(os.path.abspath(out))
    try:
        st = os.lstat(out)
    except FileNotFoundError:
        return None
    except OSError as exc:
        return f"cannot be used ({exc.strerror or exc})"
    if stat.S_ISLNK(st.st_mode):
        return (
            f"is a symbolic link (to {os.readlink(out)}); linkwork neither replaces it nor writes where it "
            "points: give the folder itself, or another --out"
        )
    if not stat.S_ISDIR(st.st_mode):
        return f"is {kind(st.st_mode)}, not a report folder; refusing to replace it: choose another --out"
    cwd = os.path.realpath(os.getcwd())
    real = os.path.realpath(out)
    if cwd == real or cwd.startswith(real.rstrip(os.sep) + os.sep):
        return "is the current folder or holds it; refusing to replace it: choose another --out"
    try:
        with os.scandir(out) as it:
            if next(it, None) is None:
                return None
        marker = read_marker(out)
        if marker is None or not marker.get("complete"):
            return (
                f"is a folder linkwork did not write (it holds no {MARKER}); refusing to replace it: "
                "choose a new or empty folder"
            )
        extra = sorted(entries(out) - set(marker["files"]) - {MARKER})
    except OSError as exc:
        return f"cannot be read ({exc.strerror or exc}); refusing to replace it"
    if extra:
        shown = ", ".join(extra[:3]) + (f" and {len(extra) - 3} more" if len(extra) > 3 else "")
        return (
            f"holds files linkwork did not write ({shown}); refusing to replace it: "
            "move them out of it, or choose another --out"
        )
    return None


def check(out: str | Path) -> None:
    """Raise :class:`~linkwork.errors.LinkworkError` (``"OUT: why"``) where :func:`problem` finds one."""
    why = problem(out)
    if why is not None:
        raise LinkworkError(f"{out}: {why}")


@contextmanager
def replacing(out: str | Path) -> Iterator[Path]:
    """A fresh folder to build a report in, put in the place of ``out`` when the block ends without error.

    Raises
    ------
    LinkworkError
        ``out`` is not a folder a report may replace (:func:`problem`), checked before the block
        and again before the swap.
    OSError
        A folder cannot be created, locked or renamed.
    """
    given = out
    out = Path(os.path.abspath(out))
    out.parent.mkdir(parents=True, exist_ok=True)
    _recover(out)
    check(given)
    build, lock = _new_build(out)
    try:
        yield build
        _mark(build, complete=True)
        check(given)
        _swap(build, out)
    except BaseException:
        _remove(build)
        raise
    finally:
        _unlock(lock)


def _hidden(out: Path, token: str, suffix: str) -> Path:
    return out.with_name(f".{out.name}.{token}.{suffix}")


def _new_build(out: Path) -> tuple[Path, int | None]:
    """A new marked build folder beside ``out`` (mode as the umask gives), and the lock held on it."""
    while True:
        build = _hidden(out, secrets.token_hex(6), "part")
        try:
            os.mkdir(build)
        except FileExistsError:  # pragma: no cover - 48 random bits
            continue
        lock = _lock(build)
        if lock is not None and _same(build, lock):
            break
        _unlock(lock)  # another run's clean-up took the empty folder before the lock: take another name
    try:
        _mark(build, complete=False)
    except BaseException:
        _unlock(lock)
        _remove(build)
        raise
    return build, lock


def _swap(build: Path, out: Path) -> None:
    """Put the complete report ``build`` at ``out``; the old report (if any) is removed once it is out of place."""
    if not os.path.lexists(out):
        _rename(build, out)
        return
    held = _lock(out, wait=10.0)
    if held is None:
        raise LinkworkError(f"{out}: another linkwork run is replacing it right now; run again")
    try:
        if _exchange(build, out):
            _remove(build)  # the old report, now under the build's name
        else:
            old = _hidden(out, build.name.split(".")[-2], "old")
            _rename(out, old)
            try:
                _rename(build, out)
            except BaseException:
                _rename(old, out)  # put the old one back where it was
                raise
            _remove(old)
    finally:
        _unlock(held)


def _recover(out: Path) -> None:
    """Clear what killed runs into ``out`` left beside it; where ``out`` is missing, first put back the newest
    complete report among those folders."""
    if fcntl is None:  # pragma: no cover - without locks a live run's folder cannot be told from a dead one's
        return
    pattern = re.compile(rf"\.{re.escape(out.name)}\.[0-9a-f]{{12}}\.(?:part|old)")
    stale: list[tuple[Path, int, dict[str, Any] | None]] = []
    try:
        with os.scandir(out.parent) as it:
            found = [Path(e.path) for e in it if pattern.fullmatch(e.name) and e.is_dir(follow_symlinks=False)]
        for path in found:
            lock = _lock(path)
            if lock is None:
                continue  # a live run's
            marker = read_marker(path)
            if marker is None and _nonempty(path):
                _unlock(lock)  # not ours: leave it
                continue
            stale.append((path, lock, marker))
        if not os.path.lexists(out):
            complete = [s for s in stale if s[2] is not None and s[2].get("complete")]
            if complete:
                newest = max(complete, key=lambda s: (os.lstat(s[0] / MARKER).st_mtime_ns, s[0].suffix == ".part"))
                _rename(newest[0], out)
                stale.remove(newest)
                _unlock(newest[1])
        for path, _, _ in stale:
            _remove(path)
    except OSError:
        pass  # a clean-up that cannot be done now is tried again by the next run
    finally:
        for _, lock, _ in stale:
            _unlock(lock)


# ---------------------------------------------------------------- the steps, one function each


def _rename(src: Path, dst: Path) -> None:
    os.rename(src, dst)


def _remove(folder: Path) -> None:
    """Remove a folder of ours, its marker last, so that a removal cut short is still recognised as ours."""
    try:
        with os.scandir(folder) as it:
            items = [Path(e.path) for e in it if e.name != MARKER]
        for p in items:
            if p.is_dir() and not p.is_symlink():
                shutil.rmtree(p)
            else:
                p.unlink()
        (folder / MARKER).unlink(missing_ok=True)
        folder.rmdir()
    except OSError:
        pass  # left for the next run


@functools.cache
def _renameat2() -> Any:
    if not sys.platform.startswith("linux"):
        return None
    try:
        fn = ctypes.CDLL(None, use_errno=True).renameat2
    except (OSError, AttributeError):
        return None
    fn.argtypes = [ctypes.c_int, ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p, ctypes.c_uint]
    fn.restype = ctypes.c_int
    return fn


def _exchange(a: Path, b: Path) -> bool:
    """Swap ``a`` and ``b`` in one step (Linux's ``renameat2`` with ``RENAME_EXCHANGE``); False where the
    system or the file system cannot."""
    fn = _renameat2()
    if fn is None:
        return False
    at_fdcwd, rename_exchange = -100, 2
    if fn(at_fdcwd, os.fsencode(a), at_fdcwd, os.fsencode(b), rename_exchange) == 0:
        return True
    err = ctypes.get_errno()
    if err in (errno.ENOSYS, errno.EINVAL, errno.EOPNOTSUPP):
        return False
    raise OSError(err, os.strerror(err), str(b))


def _lock(folder: Path, wait: float = 0.0) -> int | None:
    """An open descriptor of ``folder`` holding its exclusive lock; None while another process holds it
    (after ``wait`` seconds) or where ``folder`` is gone.  Without ``flock`` the descriptor holds no lock."""
    try:
        fd = os.open(folder, os.O_RDONLY | getattr(os, "O_DIRECTORY", 0))
    except FileNotFoundError:
        return None
    if fcntl is None:  # pragma: no cover
        return fd
    deadline = time.monotonic() + wait
    while True:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            return fd
        except BlockingIOError:
            if time.monotonic() >= deadline:
                os.close(fd)
                return None
            time.sleep(0.05)


def _nonempty(folder: Path) -> bool:
    with os.scandir(folder) as it:
        return next(it, None) is not None


def _unlock(fd: int | None) -> None:
    if fd is not None:
        os.close(fd)


def _same(path: Path, fd: int) -> bool:
    """Whether ``path`` is still the folder open as ``fd``."""
    try:
        a, b = os.stat(path, follow_symlinks=False), os.fstat(fd)
    except OSError:
        return False
    return (a.st_dev, a.st_ino) == (b.st_dev, b.st_ino)
