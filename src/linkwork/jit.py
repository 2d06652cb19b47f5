"""When the compiled (numba) kernels run, where they are cached, and their compile in the background.

The kinematics and the reactions have twin kernels: NumPy (the reference, always there) and numba (the
same arithmetic compiled to machine code, many times faster on long batches).  Compiling the numba kernels
takes one to three minutes of processor time, once per install; loading them from the cache takes
about half a second.  A report or a drag in the viewer solves a few hundred angles, which the NumPy kernels
do in milliseconds, so nobody waits for a compile they did not ask for:

- ``LINKWORK_NUMBA`` unset (or ``auto``): the compiled kernels run once they are in the cache
  (:func:`ready`), for a batch of at least :data:`LONG` samples (a sweep, a long cycle) or in a process
  that asked for them (:func:`prefer`: the viewer); shorter batches run on the NumPy kernels, which answer
  before numba would have loaded.  A process that finds the cache empty starts the compile in a process of
  its own (:func:`start_compiling`: once, at the lowest priority, into :func:`cache_dir`), says so once on
  stderr, and goes on with the NumPy kernels.  ``linkwork warm`` compiles them in front, for those who
  want them ready.
- ``LINKWORK_NUMBA=1``: the compiled kernels always, compiled when first used (benchmarks, and the tests
  that compare the twins).
- ``LINKWORK_NUMBA=0``: the NumPy kernels always.

Both give the same numbers (to rounding).  The cache is the user's (``$XDG_CACHE_HOME/linkwork/kernels``,
``~/Library/Caches/linkwork/kernels``, ``%LOCALAPPDATA%\\linkwork\\cache\\kernels``), or
``LINKWORK_CACHE_DIR`` (or numba's own ``NUMBA_CACHE_DIR``) when set, so a read-only install compiles into
a folder it can write.  Where no folder can be written, the NumPy kernels run (or, with
``LINKWORK_NUMBA=1``, the kernels compile without a cache), and that is said once.

The modules of compiled kernels (:data:`KERNEL_MODULES`) wrap their functions with :func:`jit_in_place`
and ask :func:`use` or :func:`loaded` before they run.
"""

from __future__ import annotations

import functools
import hashlib
import importlib.util
import os
import platform
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

#: The modules whose functions :func:`jit_in_place` compiles, relative to the package (their sources and
#: times are part of the key of the cache, as numba's own index keys each function's).
KERNEL_MODULES = ("motion/kernels_numba.py", "kinetostatics/reactions_numba.py")

#: Samples (variants times angles) of a batch from which loading the compiled kernels pays (about half a
#: second to import numba and load them; the NumPy reactions take about 35 us a sample of the double-cut
#: shears, the compiled ones about 2).
LONG = 20_000

#: How long a compile in the background may hold its lock before another process may start one again.
STALE = 30 * 60.0

#: Values of ``LINKWORK_NUMBA``.
OFF, ALWAYS, AUTO = "off", "always", "auto"

_loaded: list[bool] = []  # [True] once the compiled kernels are in use in this process
_preferred: list[bool] = []  # [True] once the process asked for them for every batch (:func:`prefer`)
_said: set[str] = set()  # the notes already written to stderr


def mode() -> str:
    """:data:`OFF`, :data:`ALWAYS` or :data:`AUTO`, from ``LINKWORK_NUMBA`` (``0``, ``1``, unset or ``auto``),
    :data:`OFF` where numba is not installed."""
    value = os.environ.get("LINKWORK_NUMBA", "auto").strip().lower()
    if value in ("0", "off", "no", "false") or not installed():
        return OFF
    return ALWAYS if value in ("1", "on", "yes", "true") else AUTO


@functools.cache
def installed() -> bool:
    """Whether numba can be imported (looked up, not imported)."""
    return importlib.util.find_spec("numba") is not None


def loaded() -> bool:
    """Whether the compiled kernels are in use in this process (then every kernel that has a compiled twin
    runs it)."""
    return bool(_loaded)


def active() -> bool:
    """Whether the pieces that follow a solve (reading points, the reactions) run their compiled twins: the
    kernels in use (or asked for always); this never loads them where they are not (a reading of points on
    the viewer's event loop must not wait for numba)."""
    current = mode()
    return current != OFF and (bool(_loaded) or (current == ALWAYS and _load()))


def use(samples: int) -> bool:
    """Whether a batch of ``samples`` samples is solved by the compiled kernels (loading them, or starting
    their compile in the background, as the module's rules say): in a process that :func:`prefer` them, as
    soon as the compile in the background has put them in the cache."""
    current = mode()
    if current == OFF:
        return False
    if _loaded or current == ALWAYS:
        return _load()
    if not ready():
        start_compiling()
        return False
    return (samples >= LONG or bool(_preferred)) and _load()


def prefer() -> bool:
    """Use the compiled kernels for every batch of this process once they are ready, loading them now where
    they are (else starting their compile): for a process that runs many batches (the viewer, which thus
    switches to them when the compile it started is done); whether they are in use."""
    _preferred.append(True)
    return use(LONG)


def force() -> None:
    """Use the compiled kernels in this process whatever ``LINKWORK_NUMBA`` says (compiling them as they are
    first used): what ``linkwork warm`` does."""
    os.environ["LINKWORK_NUMBA"] = "1"
    _load()


def _load() -> bool:
    if not _loaded:
        folder = cache_dir()
        if folder is not None:  # read by numba as it is imported (and kept if it reloads its settings)
            os.environ["NUMBA_CACHE_DIR"] = str(folder)
        import numba

        if folder is not None:
            numba.config.CACHE_DIR = str(folder)  # type: ignore[attr-defined]
        else:
            note("no-cache", f"the compiled kernels compile without a cache: {_unwritable()}")
        _loaded.append(True)
    return True


def jit_in_place(space: dict[str, object], inline: tuple[str, ...], called: tuple[str, ...]) -> bool:
    """Replace the functions named ``inline`` and ``called`` in the module namespace ``space`` by numba's
    ``njit`` of them (the first inlined into their callers; no reference counting: the kernels allocate
    nothing); False where numba cannot be imported.  Each module of :data:`KERNEL_MODULES` calls this once,
    from its cached ``compiled()``, when its kernels first run."""
    try:
        from numba import njit
    except ImportError:  # pragma: no cover
        return False
    opts: dict[str, Any] = {"cache": cache_dir() is not None, "error_model": "numpy", "nogil": True, "_nrt": False}
    for name in inline:
        space[name] = njit(inline="always", **opts)(space[name])
    for name in called:
        space[name] = njit(**opts)(space[name])
    return True


@functools.cache
def cache_dir() -> Path | None:
    """The folder of the compiled kernels (made where it was not), or None where it cannot be written."""
    try:
        folder = _cache_folder()
        folder.mkdir(parents=True, exist_ok=True)
        with tempfile.TemporaryFile(dir=folder):
            pass
    except (OSError, RuntimeError):  # RuntimeError: no home folder to be found
        return None
    return folder


def _cache_folder() -> Path:
    for name in ("LINKWORK_CACHE_DIR", "NUMBA_CACHE_DIR"):
        if os.environ.get(name):
            return Path(os.environ[name]).expanduser()
    if sys.platform == "win32":
        return (
            Path(os.environ.get("LOCALAPPDATA") or Path.home() / "AppData" / "Local") / "linkwork" / "cache" / "kernels"
        )
    if sys.platform == "darwin":
        return Path.home() / "Library" / "Caches" / "linkwork" / "kernels"
    return Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "linkwork" / "kernels"


def _unwritable() -> str:
    try:
        folder = str(_cache_folder())
    except RuntimeError:
        folder = "(no home folder)"
    return f"{folder} cannot be written (set LINKWORK_CACHE_DIR to a folder that can)"


@functools.cache
def key() -> str:
    """What the compiled kernels in the cache were compiled from: the versions of Python, numba and
    linkwork, the machine, and each kernel module's path, size and time (numba's own index checks the
    last two of each function's source)."""
    from importlib.metadata import version

    import linkwork

    here = Path(__file__).resolve().parent
    parts = [sys.version, sys.platform, platform.machine(), version("numba"), linkwork.__version__]
    for name in KERNEL_MODULES:
        path = here / name
        stat = path.stat()
        parts += [str(path), str(stat.st_size), str(stat.st_mtime_ns)]
    return hashlib.sha256("\0".join(parts).encode()).hexdigest()[:20]


def stamp() -> Path | None:
    """The file whose presence says the compiled kernels of :func:`key` are all in the cache."""
    folder = cache_dir()
    return None if folder is None else folder / f"ready-{key()}"


def ready() -> bool:
    """Whether every compiled kernel is in the cache, compiled from these sources (:func:`key`)."""
    path = stamp()
    return path is not None and path.is_file()


def mark_ready() -> None:
    """Say that every kernel is in the cache now (written whole, then renamed into place)."""
    path = stamp()
    if path is not None:
        part = path.with_suffix(".part")
        part.write_text(f"{time.time()}\n", encoding="utf-8")
        part.replace(path)


def _lock() -> Path | None:
    folder = cache_dir()
    return None if folder is None else folder / f"compiling-{key()}"


def compiling() -> bool:
    """Whether a compile of these kernels is under way (its lock held, and not older than :data:`STALE`)."""
    lock = _lock()
    try:
        return lock is not None and time.time() - lock.stat().st_mtime < STALE
    except OSError:
        return False


@functools.cache
def start_compiling() -> bool:
    """Start ``linkwork warm --quiet`` in a process of its own at the lowest priority (once per process, and
    not while another compile holds the lock), saying so once on stderr; whether one is under way."""
    lock = _lock()
    if lock is None:
        note("no-cache", f"the NumPy kernels run: the compiled kernels' cache {_unwritable()}")
        return False
    if _failed().is_file():  # compile.log says why; ``linkwork warm`` tries again in front
        return False
    try:
        if _take(lock):
            child = _spawn(lock)
            if child is not None:  # the lock names the process that holds it
                lock.write_text(f"{child} {time.time()}\n", encoding="utf-8")
        elif not compiling():
            return False
    except OSError:
        return False
    note(
        "compiling",
        f"compiling the fast kernels in the background, once (into {lock.parent}); the NumPy kernels answer meanwhile",
    )
    return True


def _take(lock: Path) -> bool:
    """Make the lock file (not there, or left stale by a compile that died); False where another holds it."""
    for _ in range(2):
        try:
            fd = os.open(lock, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o644)
        except FileExistsError:
            if compiling():
                return False
            lock.unlink(missing_ok=True)
            continue
        with os.fdopen(fd, "w", encoding="utf-8") as out:
            out.write(f"{os.getpid()} {time.time()}\n")
        return True
    return False


def _spawn(lock: Path) -> int | None:
    """Start the compile (its output into ``compile.log`` beside the lock); its process id."""
    env = {**os.environ, "LINKWORK_NUMBA": "1", "LINKWORK_CACHE_DIR": str(lock.parent)}
    log = open(lock.parent / "compile.log", "wb")  # noqa: SIM115 - the child holds it
    with log:
        options: dict[str, Any] = {"start_new_session": True}
        if sys.platform == "win32":  # pragma: no cover
            options = {"creationflags": subprocess.IDLE_PRIORITY_CLASS | subprocess.CREATE_NEW_PROCESS_GROUP}
        child = subprocess.Popen(
            [sys.executable, "-m", "linkwork.cli", "warm", "--quiet", "--background"],
            stdin=subprocess.DEVNULL,
            stdout=log,
            stderr=log,
            cwd=lock.parent,
            env=env,
            close_fds=True,
            **options,
        )
    return child.pid


def release(failed: bool = False) -> None:
    """Give up the lock of the compile (at the end of ``linkwork warm --background``); ``failed``: leave a
    mark that keeps later processes from starting the same failing compile again."""
    lock = _lock()
    if lock is not None:
        if failed:
            _failed().write_text(f"{time.time()}\n", encoding="utf-8")
        lock.unlink(missing_ok=True)


def _failed() -> Path:
    lock = _lock()
    assert lock is not None
    return lock.with_name(f"failed-{key()}")


def note(kind: str, text: str) -> None:
    """Write ``linkwork: text`` on stderr, once per process for each ``kind``."""
    if kind not in _said:
        _said.add(kind)
        print(f"linkwork: {text}", file=sys.stderr)
