"""Write files so that a reader never sees a half-written one.

A file is written whole under a temporary name beside it and renamed over
the old one.  A symbolic link is written through: the file it points to is
replaced and the link kept.  A directory, a device, a fifo or a socket (or a
link to one, or a link to nothing) is refused before anything is written:
it cannot be replaced whole, and replacing it would lose it.
"""

from __future__ import annotations

import errno
import os
import secrets
import stat
from collections.abc import Callable
from pathlib import Path

_KINDS = {
    stat.S_IFDIR: "a directory",
    stat.S_IFCHR: "a character device",
    stat.S_IFBLK: "a block device",
    stat.S_IFIFO: "a fifo",
    stat.S_IFSOCK: "a socket",
    stat.S_IFLNK: "a symbolic link",
    stat.S_IFREG: "a file",
}


def kind(mode: int) -> str:
    """What an ``st_mode`` is, in words: ``"a file"``, ``"a directory"``, ``"a fifo"``..."""
    return _KINDS.get(stat.S_IFMT(mode), "not a regular file")


def target_problem(path: str | Path) -> str | None:
    """Why ``path`` cannot be replaced by a file written whole, or None (it is a file, a link to one, or new): not
    a regular file, a read-only file (its owner's choice is kept: it is not replaced), or a folder above it that is
    a file or cannot be written in.  Checked before any work, so that a bad destination is said at once."""
    path = Path(path)
    try:
        st = os.stat(path)
    except FileNotFoundError:
        if os.path.islink(path):
            return f"is a symbolic link to {os.readlink(path)}, which does not exist; not writing through it"
        return _folder_problem(path)
    except NotADirectoryError:
        return _folder_problem(path)
    except OSError:
        return None  # the write itself says what is wrong
    if stat.S_ISREG(st.st_mode):
        if not st.st_mode & 0o222:
            return f"is read-only (mode {stat.S_IMODE(st.st_mode):04o}); not replacing it (make it writable first)"
        return _folder_problem(Path(os.path.realpath(path)))
    via = " (through a symbolic link)" if os.path.islink(path) else ""
    return f"is {kind(st.st_mode)}{via}, not a regular file; linkwork writes only files, replacing them whole"


def _folder_problem(path: Path) -> str | None:
    """Why no file can be made at ``path`` (a new one, or one replaced through a file beside it), or None: the
    nearest folder above it that exists is a file, or cannot be written in."""
    folder = path.absolute().parent
    while not os.path.lexists(folder) and folder != folder.parent:
        folder = folder.parent
    if not os.path.isdir(folder):
        return f"cannot be made: {folder} is {kind(os.lstat(folder).st_mode)}, not a folder"
    if not os.access(folder, os.W_OK | os.X_OK):
        return f"cannot be made: the folder {folder} cannot be written in (permission denied)"
    return None


def write_atomic(path: str | Path, writer: Callable[[Path], object]) -> Path:
    """Call ``writer(tmp)`` on a temporary file beside ``path``, then move it into place.

    An interrupted or failed write leaves the old file (if any) untouched
    and no partial file behind.  Where ``path`` is a symbolic link, the file
    it points to is replaced (keeping its permissions) and the link stays.

    Raises
    ------
    OSError
        ``path`` is not a file nor a link to one (:func:`target_problem`), or the write failed.
    """
    path = Path(path)
    why = target_problem(path)
    if why is not None:
        raise OSError(errno.EEXIST, why, str(path))
    dest = Path(os.path.realpath(path)) if os.path.islink(path) else path
    dest.parent.mkdir(parents=True, exist_ok=True)
    try:
        mode: int | None = os.stat(dest).st_mode & 0o777
    except FileNotFoundError:
        mode = None
    while True:  # a fresh name; created as open() would (0666 less the umask), not private like mkstemp's
        tmp = dest.parent / f".{dest.name}.{secrets.token_hex(6)}.part"
        try:
            os.close(os.open(tmp, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o666))
            break
        except FileExistsError:  # pragma: no cover - 48 random bits
            continue
    try:
        writer(Path(tmp))
        if mode is not None:
            os.chmod(tmp, mode)
        os.replace(tmp, dest)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return path
