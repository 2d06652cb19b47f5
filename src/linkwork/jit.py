"""When the compiled (numba) kernels run, where they are cached, and their compile in the background.

The kinematics and the reactions have twin kernels: NumPy (the reference, always there) and numba (the
same arithmetic compiled to machine code, 5 to 30 times faster).  Compiling the numba kernels takes one to
three minutes of processor time, once per install; loading them from the cache (importing numba, reading
the compiled code) costs a process 0.6 to 1.2 seconds of processor time (:func:`measured_cost`: measured on
the machine, :data:`LOAD_COST` until it is), more than a one-shot command spends in its batches.  So the
kernels are tiered, as a JIT runtime tiers its code:

- ``LINKWORK_NUMBA`` unset (or ``auto``): a process starts on the NumPy kernels and counts the processor time
  it spends in them (:func:`spent`).  Once the compiled kernels are in the cache (:func:`ready`, looked at
  once every :data:`RECHECK` seconds at most) and that time exceeds what their loading would cost the
  process (:func:`load_cost`: the loads measured on this machine, less what it has imported already), a
  thread of the process loads them in the background (:func:`load_in_background`: no caller waits for it,
  though the calls meanwhile share the interpreter with it) and the process switches to them: from then on
  every call, whatever its size, runs compiled.  A process that stops before has paid nothing for them; one
  that goes on pays for the load at most what it had spent already, and then runs 5 to 30 times faster.  Two
  shortcuts: a batch of at least :data:`LONG` samples (a sweep, a long cycle) pays for the load alone, and
  loads them in front; a process that asks for them (:func:`prefer`: the viewer) loads them in the background
  as soon as they are ready.
  A command of the command line (:func:`one_shot`) has only those two: it ends before a load would pay.
  A process that finds the cache empty starts the compile in a process of its own (:func:`start_compiling`:
  once, at the lowest priority, into :func:`cache_dir`), says so once on stderr, and goes on with the
  NumPy kernels (switching as above once the compile is done).  ``linkwork warm`` compiles them in front,
  for those who want them ready.
- ``LINKWORK_NUMBA=1``: the compiled kernels always, compiled when first used (benchmarks, and the tests
  that compare the twins).
- ``LINKWORK_NUMBA=0``: the NumPy kernels always; numba is not even imported.

A call decides once (:func:`deciding`): every batch of a call runs on the kernels in use as it started,
even where the switch happens while it runs; the one exception is a batch of :data:`LONG` samples, which
loads them in front and takes the rest of its call along.  Both give the same numbers (to rounding).

The cache is the user's (``$XDG_CACHE_HOME/linkwork/kernels``, ``~/Library/Caches/linkwork/kernels``,
``%LOCALAPPDATA%\\linkwork\\cache\\kernels``), or ``LINKWORK_CACHE_DIR`` (or numba's own
``NUMBA_CACHE_DIR``) when set, so a read-only install compiles into a folder it can write.  Where no folder
can be written, the NumPy kernels run (or, with ``LINKWORK_NUMBA=1``, the kernels compile without a cache),
and that is said once.

The modules of compiled kernels (:data:`KERNEL_MODULES`) wrap their functions with :func:`jit_in_place`
and ask :func:`use` or :func:`active` before they run; their NumPy twins report their time to :func:`spent`.
"""

from __future__ import annotations

import atexit
import contextvars
import dataclasses
import functools
import hashlib
import importlib
import importlib.util
import math
import os
import platform
import subprocess
import sys
import tempfile
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any, ParamSpec, TypeVar

#: The modules whose functions :func:`jit_in_place` compiles, relative to the package (their sources and
#: times are part of the key of the cache, as numba's own index keys each function's).
KERNEL_MODULES = ("motion/kernels_numba.py", "kinetostatics/reactions_numba.py")

#: The modules whose constants the compiled kernels take in as they are compiled (the group kinds' codes, the
#: program table's columns, the tolerances): numba's own index does not see them, so they key the cache too, and
#: each key compiles into a folder of its own (:func:`numba_dir`).
CONSTANT_MODULES = ("motion/compiled_program.py", "motion/groups.py", "motion/kernels.py", "motion/program_table.py")

#: Samples (variants times angles) of a batch that pays for loading the compiled kernels in front (about
#: :data:`LOAD_COST`; the NumPy reactions take about 35 us a sample of the double-cut shears, the compiled
#: ones about 2).
LONG = 20_000

#: Seconds of processor time loading the compiled kernels costs a process that has none of :data:`SUNK`, until a load
#: on this machine has been measured (:func:`measured_cost`; ``linkwork warm`` measures one as it ends), measured
#: in the thread that loads them (:func:`load_seconds`; 0.76 to 1.21 s on the 2-core virtual machine of the benchmarks
#: page): importing numba (0.23 to 0.34 s); its NumPy support (0.22 to 0.35 s, of which SciPy's linear algebra 0.14 to
#: 0.26 s: numba's ``np.arraymath`` imports ``scipy.linalg.cython_blas`` as it is loaded, whatever the kernels use,
#: and ours use no linear algebra of NumPy's); its compiler's first set-up and the reading of the nine compiled
#: signatures (0.31 to 0.53 s).  A load in the background costs the calls of the process about as much of their own
#: processor time (measured 68 to 105 % of it: importing holds the interpreter's lock, so the load and the calls take
#: turns, even on two cores), so that is the price of the switch: :func:`load_cost`.
LOAD_COST = 1.0

#: The parts of :data:`LOAD_COST` that a module imports, as fractions of it: a process that has imported the module
#: already (SciPy's linear algebra for a run in time or a user's own SciPy, numba for a user's own kernels) does not
#: pay that part again (:func:`load_cost`).
SUNK = {"numba": 0.3, "scipy.linalg": 0.2}

#: How many of the last loads measured on this machine :func:`measured_cost` takes the median of, and the range of
#: seconds it believes (a record outside it, from a file damaged or a machine swapped, is left out).
MEASURED, BELIEVED = 5, (0.05, 20.0)

#: Seconds between two looks at the cache (:func:`ready`) while the compiled kernels are not in use.
RECHECK = 5.0

#: How long a compile in the background may hold its lock before another process may start one again.
STALE = 30 * 60.0

#: Values of ``LINKWORK_NUMBA``.
OFF, ALWAYS, AUTO = "off", "always", "auto"

P = ParamSpec("P")
R = TypeVar("R")


@dataclasses.dataclass
class _State:
    """What this process knows of its kernels (one per process: :data:`_state`)."""

    loaded: bool = False  # the compiled kernels are in use
    preferred: bool = False  # the process asked for them (:func:`prefer`)
    one_shot: bool = False  # the process answers one command and ends (:func:`one_shot`)
    spent: float = 0.0  # seconds spent in the NumPy twins (:func:`spent`; a lost update between threads is harmless)
    looked: float = -math.inf  # when the cache was last looked at (:data:`_clock`)
    found: bool = False  # whether it was ready then
    loader: threading.Thread | None = None  # the thread that loads them in the background, once started
    stop: threading.Event = dataclasses.field(default_factory=threading.Event)  # the process ends: load no more
    took: float | None = None  # processor seconds the load took (:func:`load_seconds`)
    cost: float | None = None  # :func:`measured_cost`, read once


_state = _State()
_loading = threading.Lock()  # one import of numba at a time, in front or in the background
_starting = threading.Lock()  # one thread of :func:`load_in_background`
_call: contextvars.ContextVar[list[bool] | None] = contextvars.ContextVar("linkwork_kernels", default=None)
_said: set[str] = set()  # the notes already written to stderr
_clock = time.monotonic  # what :func:`_ready` reads the time from


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
    """Whether the compiled kernels are in use in this process (then every call that starts runs them)."""
    return _state.loaded


def load_seconds() -> float | None:
    """Seconds of processor time the load of the compiled kernels in the background took in this process
    (None before)."""
    return _state.took


def deciding(function: Callable[P, R]) -> Callable[P, R]:
    """``function`` as a call that decides its kernels once, as it starts (:func:`active`, :func:`use`): a
    switch to the compiled kernels while it runs is for the calls that start after it.  A call within
    another keeps the outer one's decision."""

    @functools.wraps(function)
    def call(*args: P.args, **kwargs: P.kwargs) -> R:
        if _call.get() is not None:
            return function(*args, **kwargs)
        token = _call.set([_now()])
        try:
            return function(*args, **kwargs)
        finally:
            _call.reset(token)

    return call


def _now() -> bool:
    """Whether a call that starts now runs the compiled kernels (loading them where they run always)."""
    current = mode()
    return current != OFF and (_state.loaded or (current == ALWAYS and _load()))


def active() -> bool:
    """Whether the pieces that follow a solve (reading points, the reactions) run their compiled twins: as
    the call decided (:func:`deciding`), else as the process runs now; this never loads them where they are
    not in use (a reading of points on the viewer's event loop must not wait for numba)."""
    decided = _call.get()
    return decided[0] if decided is not None else _now()


def use(samples: int) -> bool:
    """Whether a batch of ``samples`` samples is solved by the compiled kernels: as :func:`active`; else,
    with the kernels ready, a batch of :data:`LONG` samples loads them in front (and its call runs them
    from there on), and a process that :func:`prefer` them starts their load in the background; with the
    cache empty, their compile starts in the background."""
    decided = _call.get()
    if decided[0] if decided is not None else _now():
        return True
    if mode() != AUTO:
        return False
    if not _ready():
        start_compiling()
        return False
    if _state.preferred:
        load_in_background()
    if samples < LONG:
        return False
    _load()
    if decided is not None:
        decided[0] = True
    return True


def load_cost() -> float:
    """Seconds of processor time loading the compiled kernels would cost this process now: :func:`measured_cost`
    less the parts of :data:`SUNK` whose modules it has imported already."""
    return measured_cost() * (1.0 - _sunk())


def _sunk() -> float:
    """The fraction of a load that this process has paid already (:data:`SUNK`)."""
    return sum(part for name, part in SUNK.items() if name in sys.modules)


def measured_cost() -> float:
    """Seconds of processor time a whole load costs on this machine: the median of the last :data:`MEASURED` loads
    measured here (:func:`load_seconds`, each counted whole: what a process had imported already added back), read
    from the cache once per process; :data:`LOAD_COST` until one is."""
    state = _state
    if state.cost is None:
        record = _record()
        try:
            seen = [float(v) for v in record.read_text(encoding="utf-8").split()] if record is not None else []
        except (OSError, ValueError):
            seen = []
        seen = [v for v in seen[-MEASURED:] if BELIEVED[0] <= v <= BELIEVED[1]]
        state.cost = float(sorted(seen)[len(seen) // 2]) if seen else LOAD_COST
    return state.cost


def _record() -> Path | None:
    """The file of the loads measured on this machine, beside the kernels of :func:`key`."""
    folder = cache_dir()
    return None if folder is None else folder / f"loads-{key()}"


def _remember(seconds: float) -> None:
    """Add a load of ``seconds`` (whole) to :func:`_record` (written whole, then renamed into place)."""
    record = _record()
    if record is None:
        return
    try:
        seen = record.read_text(encoding="utf-8").split() if record.is_file() else []
        part = record.with_suffix(f".{os.getpid()}.part")
        part.write_text("\n".join([*seen[-(MEASURED - 1) :], f"{seconds:.4f}"]) + "\n", encoding="utf-8")
        part.replace(record)
    except OSError:  # a cache that went read-only: the next process measures again
        pass


def measure_load() -> float | None:
    """Load the compiled kernels from the cache in a fresh process that has run an analysis, as a process on the
    default settings does, and record its cost (:func:`measured_cost`); the seconds it took, None where it could
    not."""
    env = {k: v for k, v in os.environ.items() if k not in ("LINKWORK_NUMBA", "NUMBA_CACHE_DIR")}
    folder = cache_dir()
    if folder is None:
        return None
    env["LINKWORK_CACHE_DIR"] = str(folder)
    code = (  # a process that has run an analysis (numpy and the analyses' modules imported) loads them
        "import linkwork as lw; from linkwork import jit; lw.forces(lw.compile('four-bar'), steps=12); "
        "jit.load_in_background(); jit._settle(); print(jit.load_seconds())"
    )
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=300)
    try:
        return float(out.stdout)
    except ValueError:
        return None


def spent(seconds: float) -> None:
    """Count ``seconds`` of processor time spent in a NumPy twin of a compiled kernel; once past :func:`load_cost`,
    with the compiled kernels ready, load them in the background.

    Both sides are processor time of this process: what the NumPy kernels took, and what the load will take from
    its calls (they wait for the interpreter's lock while it imports).  On a loaded machine the wall time of both
    grows alike, so the switch comes after the same number of calls; waiting until the kernels have taken what the
    switch costs before paying for it keeps a process's total within twice the least it could have taken, whether
    it stops early or goes on (the ski-rental rule)."""
    state = _state
    state.spent += seconds
    if state.loaded or state.loader is not None or state.one_shot or state.spent < load_cost():
        return
    if mode() == AUTO and _ready():
        load_in_background()


def prefer() -> bool:
    """Use the compiled kernels for every call of this process as soon as they are ready, loading them in
    the background where they are (else starting their compile): for a process that runs many batches (the
    viewer, which thus switches to them when the compile it started is done); whether they are in use."""
    _state.preferred = True
    return use(0)


def one_shot() -> None:
    """Say that this process answers one command and ends (the command line): it loads no compiled kernels
    for the time it spent in the NumPy ones, as its exit would wait for a load it had no time left to use
    (a batch of :data:`LONG` samples still loads them in front, and a process that :func:`prefer` them, the
    viewer, in the background)."""
    _state.one_shot = True


def force() -> None:
    """Use the compiled kernels in this process whatever ``LINKWORK_NUMBA`` says (compiling them as they are
    first used): what ``linkwork warm`` does."""
    os.environ["LINKWORK_NUMBA"] = "1"
    _load()


def _ready() -> bool:
    """:func:`ready`, looked at once every :data:`RECHECK` seconds at most (the answer kept between)."""
    state = _state
    now = _clock()
    if now - state.looked >= RECHECK:
        state.found, state.looked = ready(), now
    return state.found


def load_in_background() -> None:
    """Load the compiled kernels in a thread of their own (once per process), then switch to them."""
    if _state.loaded or _state.loader is not None:  # the usual answer, without waiting for a lock
        return
    with _starting:
        if _state.loaded or _state.loader is not None:
            return
        _state.loader = threading.Thread(target=_fetch, name="linkwork-kernels", daemon=True)
        _state.loader.start()


def _fetch() -> None:
    """Import numba, wrap every kernel and read every one the cache holds, then switch (what the thread of
    :func:`load_in_background` does)."""
    start, sunk = time.thread_time(), _sunk()
    try:
        with _loading:
            if _state.loaded:  # loaded in front meanwhile (a long batch)
                return
            _import_numba()
            for name in KERNEL_MODULES:
                module = importlib.import_module("linkwork." + name.removesuffix(".py").replace("/", "."))
                if _state.stop.is_set() or not module.compiled() or not _read_cache(vars(module)):
                    return
    except Exception as exc:  # pragma: no cover - a broken numba: the NumPy kernels go on
        note("load", f"the NumPy kernels run: the compiled kernels could not be loaded ({exc})")
        return
    _state.took = time.thread_time() - start
    _state.loaded = True
    _remember(_state.took / (1.0 - sunk))


def _read_cache(space: dict[str, Any]) -> bool:
    """Load into each numba dispatcher of the module namespace ``space`` every signature the cache holds
    compiled from these sources (numba's cache index, read as its dispatchers read it), so that no call
    waits for a read (where numba's internals differ, each kernel is read on its first call instead);
    False where the process ends meanwhile."""
    from numba.core.registry import CPUDispatcher

    dispatchers: list[Any] = [f for f in list(space.values()) if isinstance(f, CPUDispatcher)]
    for function in dispatchers:
        try:
            cache = function._cache
            codegen = function.targetctx.codegen()
            keys = list(cache._cache_file._load_index())
        except AttributeError:  # pragma: no cover - another numba
            return True
        for key in keys:
            if _state.stop.is_set():
                return False
            if cache._index_key(key[0], codegen) == key:  # these sources, this machine
                function.compile(key[0])
    return True


def _settle() -> None:
    """Wait for a load in the background to end (before a fork: a thread caught mid-import would leave the
    child process an import lock it can never take)."""
    loader = _state.loader
    if loader is not None and loader is not threading.current_thread():
        loader.join()


def _end() -> None:
    """At the process's exit: stop a load in the background at its next step, and wait for it (numba's
    native parts must not be torn down under it)."""
    _state.stop.set()
    _settle()


if hasattr(os, "register_at_fork"):
    os.register_at_fork(before=_settle)
atexit.register(_end)


def _load() -> bool:
    """Switch to the compiled kernels now (a load in the background under way is waited for); True."""
    _settle()
    if not _state.loaded:
        with _loading:
            _import_numba()
            _state.loaded = True
    return True


def numba_dir() -> Path | None:
    """The folder numba caches the kernels of :func:`key` in, within :func:`cache_dir` (None where there is none):
    one a key, so that a kernel compiled with other constants is never read back (:data:`CONSTANT_MODULES`)."""
    folder = cache_dir()
    return None if folder is None else folder / f"numba-{key()}"


def _import_numba() -> None:
    """Import numba with the cache folder of :func:`numba_dir` (said once where there is none)."""
    folder = numba_dir()
    if folder is not None:  # read by numba as it is imported (and kept if it reloads its settings)
        os.environ["NUMBA_CACHE_DIR"] = str(folder)
    import numba

    if folder is not None:
        numba.config.CACHE_DIR = str(folder)  # type: ignore[attr-defined]
    else:
        note("no-cache", f"the compiled kernels compile without a cache: {_unwritable()}")


def read_only(array: Any) -> Any:
    """``array`` as a read-only view, as the compiled kernels take every array they only read: numba compiles a
    kernel once for each set of argument types, and types a read-only array apart from a writable one, so
    that a kernel called with the file's geometry (kept read-only) and then with a design variant's (made
    writable) would compile twice (the kinematics kernel takes about two minutes of processor time each)."""
    view = array.view()
    view.flags.writeable = False
    return view


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
    linkwork, the machine, and the path, size and time of each kernel module and of each module whose constants
    they take in (:data:`CONSTANT_MODULES`; numba's own index checks the last two of each function's source
    only)."""
    from importlib.metadata import version

    import linkwork

    here = Path(__file__).resolve().parent
    parts = [sys.version, sys.platform, platform.machine(), version("numba"), linkwork.__version__]
    for name in (*KERNEL_MODULES, *CONSTANT_MODULES):
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
    """Say that every kernel is in the cache now (written whole, then renamed into place), and remove the kernels
    of other keys (compiled from other sources: no process of these reads them)."""
    import shutil

    path, mine = stamp(), numba_dir()
    if path is not None and mine is not None:
        part = path.with_suffix(".part")
        part.write_text(f"{time.time()}\n", encoding="utf-8")
        part.replace(path)
        for old in path.parent.glob("numba-*"):
            if old != mine:
                shutil.rmtree(old, ignore_errors=True)


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
