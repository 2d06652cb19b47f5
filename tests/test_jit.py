"""When the compiled kernels run (linkwork.jit): nobody waits for a compile they did not ask for.

A first run with an empty cache answers with the NumPy kernels (the same numbers) and starts the compile in a
process of its own, once; a cache that cannot be written leaves the NumPy kernels, said once; a ready cache
is used for long batches; ``linkwork warm`` compiles every kernel the analyses call.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import linkwork as lw
from linkwork import jit

NOTE = "compiling the fast kernels in the background"


def _run(args: list[str], cache: Path | str, mode: str | None = None) -> subprocess.CompletedProcess[str]:
    env = {k: v for k, v in os.environ.items() if k not in ("LINKWORK_NUMBA", "NUMBA_CACHE_DIR")}
    env["LINKWORK_CACHE_DIR"] = str(cache)
    if mode is not None:
        env["LINKWORK_NUMBA"] = mode
    return subprocess.run(
        [sys.executable, "-m", "linkwork.cli", *args], capture_output=True, text=True, env=env, timeout=120
    )


def _stop(lock: Path) -> None:
    """Stop the compile that holds ``lock`` (the test needs no kernels from it), once it is seen running."""
    pid = int(lock.read_text().split()[0])
    command = Path(f"/proc/{pid}/cmdline").read_bytes().replace(b"\0", b" ").decode()
    assert "linkwork.cli warm --quiet --background" in command
    os.kill(pid, signal.SIGKILL)


@pytest.mark.skipif(not jit.installed() or not Path("/proc/self").exists(), reason="numba is not installed")
def test_a_first_run_answers_with_numpy_and_compiles_once_in_the_background(tmp_path):
    """An empty cache: the command's output is that of the NumPy kernels, one line on stderr says the kernels
    compile in the background, and a process of its own does so under a lock; a second command while it runs
    starts no second compile."""
    args = ["kinematics", "double-cut-shears", "--json"]
    numpy = _run(args, tmp_path / "unused", mode="0")
    first = _run(args, tmp_path)
    try:
        assert first.returncode == 0, first.stderr
        assert first.stdout == numpy.stdout
        assert first.stderr.count(NOTE) == 1 and first.stderr.count("\n") == 1
        (lock,) = tmp_path.glob("compiling-*")
        second = _run(args, tmp_path)
        assert second.stdout == numpy.stdout and second.stderr.count(NOTE) == 1
        assert list(tmp_path.glob("compiling-*")) == [lock]
    finally:
        for lock in tmp_path.glob("compiling-*"):
            _stop(lock)
    assert not list(tmp_path.glob("ready-*"))


@pytest.mark.skipif(not jit.installed() or not Path("/proc/self").exists(), reason="numba is not installed")
def test_the_viewer_with_an_empty_cache_answers_edits_without_compiling(tmp_path):
    """The viewer (many solves) asks for the compiled kernels at its start: with an empty cache it starts their
    compile in the background and answers its first cycle and its edits with the NumPy kernels, numba not
    even imported (the first drag froze the page for minutes while numba compiled on the event loop)."""
    script = (
        "import sys; from linkwork.web.server import create_app; app = create_app('double-cut-shears'); "
        "viewer = app.state.viewer; answer = viewer.edit({'links.crank.length': 0.21}); "
        "print(len(answer) > 0, 'numba' in sys.modules)"
    )
    env = {k: v for k, v in os.environ.items() if k not in ("LINKWORK_NUMBA", "NUMBA_CACHE_DIR")}
    env["LINKWORK_CACHE_DIR"] = str(tmp_path)
    try:
        out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, env=env, timeout=120)
        assert out.stdout.split() == ["True", "False"], out.stderr
        assert out.stderr.count(NOTE) == 1
    finally:
        for lock in tmp_path.glob("compiling-*"):
            _stop(lock)


def test_a_cache_that_cannot_be_written_leaves_the_numpy_kernels_said_once(tmp_path):
    """A cache folder that cannot be made (under a file): the NumPy kernels' numbers, one line that says why
    and what to set, no compile started."""
    blocker = tmp_path / "file"
    blocker.write_text("")
    args = ["kinematics", "four-bar", "--json"]
    numpy = _run(args, tmp_path / "unused", mode="0")
    out = _run(args, blocker / "cache")
    assert out.returncode == 0 and out.stdout == numpy.stdout
    assert out.stderr.count("\n") == 1 and "cannot be written" in out.stderr and "LINKWORK_CACHE_DIR" in out.stderr


@pytest.fixture
def cache(tmp_path, monkeypatch):
    """An empty cache folder of this process's own, and :mod:`linkwork.jit`'s memory of it forgotten before
    and after; spawning recorded, not done."""
    spawned: list[Path] = []

    def forget():
        for f in (jit.cache_dir, jit.key, jit.start_compiling):
            f.cache_clear()

    monkeypatch.setenv("LINKWORK_CACHE_DIR", str(tmp_path))
    monkeypatch.setenv("LINKWORK_NUMBA", "auto")
    monkeypatch.setattr(jit, "_spawn", spawned.append)
    monkeypatch.setattr(jit, "_said", set())
    monkeypatch.setattr(jit, "_state", jit._State())
    forget()
    yield spawned
    forget()


class Clock:
    """A clock that moves only when told (for :func:`linkwork.jit._ready`)."""

    def __init__(self) -> None:
        self.now = 1000.0

    def __call__(self) -> float:
        return self.now


@pytest.fixture
def fake(cache, monkeypatch):
    """:func:`cache`, with a clock of the test's and loads that import nothing: a load in front records
    itself, a load in the background records itself and switches (``loads``, the clock, the spawns)."""
    clock = Clock()
    loads: list[str] = []

    def fetch():
        loads.append("background")
        jit._state.loaded = True

    monkeypatch.setattr(jit, "_clock", clock)
    monkeypatch.setattr(jit, "_import_numba", lambda: loads.append("front"))
    monkeypatch.setattr(jit, "_fetch", fetch)
    monkeypatch.setattr(jit, "installed", lambda: True)
    return clock, loads, cache


def _joined() -> bool:
    """Whether a load in the background was started (waited for here)."""
    loader = jit._state.loader
    if loader is not None:
        loader.join(timeout=10)
    return loader is not None


def test_a_ready_cache_loads_in_front_for_a_long_batch_only(fake):
    """Not ready: no batch loads them, and the compile starts; ready: a batch of :data:`jit.LONG` samples loads
    them in front, a shorter one does not; then every batch runs them.  ``LINKWORK_NUMBA=0``: none does."""
    clock, loads, spawned = fake
    assert not jit.use(jit.LONG) and len(spawned) == 1
    jit.mark_ready()
    clock.now += jit.RECHECK
    assert not jit.use(jit.LONG - 1) and not jit.loaded() and loads == []
    assert jit.use(jit.LONG) and jit.loaded() and loads == ["front"] and jit.use(1)
    os.environ["LINKWORK_NUMBA"] = "0"
    assert not jit.use(jit.LONG)


def test_the_switch_comes_once_the_numpy_kernels_took_what_the_load_costs(fake):
    """With the cache ready, the kernels load in the background once the time reported from the NumPy kernels
    reaches :func:`jit.load_cost`, not before; then every call, however short, runs them."""
    clock, loads, _ = fake
    jit.mark_ready()
    jit.spent(0.45 * jit.load_cost())
    jit.spent(0.45 * jit.load_cost())
    assert not jit.use(1) and not jit.active() and jit._state.loader is None
    jit.spent(0.11 * jit.load_cost())
    assert _joined() and loads == ["background"]
    assert jit.use(1) and jit.active()


def test_an_empty_cache_keeps_the_numpy_kernels_whatever_they_took(fake):
    """The compile in the background not done: however long the NumPy kernels took, nothing loads (the cache
    looked at again after :data:`jit.RECHECK` seconds); once it is done, the next look loads them."""
    clock, loads, spawned = fake
    assert not jit.use(1) and len(spawned) == 1
    jit.spent(10 * jit.LOAD_COST)
    jit.mark_ready()  # the compile ends, and is not looked for until RECHECK has passed
    jit.spent(1.0)
    assert jit._state.loader is None and not jit.use(1)
    clock.now += jit.RECHECK
    jit.spent(1e-6)
    assert _joined() and jit.use(1)


def test_the_cache_is_looked_at_once_every_few_seconds(fake, monkeypatch):
    """However many batches a process runs, the cache's file is looked at once every :data:`jit.RECHECK`
    seconds at most, and the compile started once."""
    clock, _, spawned = fake
    looks: list[float] = []
    monkeypatch.setattr(jit, "ready", lambda: looks.append(clock.now) is not None and False)
    for _ in range(1000):
        jit.use(360)
        jit.spent(0.01)
    assert len(looks) == 1
    clock.now += 0.99 * jit.RECHECK
    jit.use(360)
    assert len(looks) == 1
    clock.now += 0.02 * jit.RECHECK
    jit.use(360)
    assert len(looks) == 2 and len(spawned) == 1


def test_a_process_that_prefers_the_kernels_switches_when_the_compile_is_done(fake):
    """The viewer asks for the kernels (:func:`jit.prefer`) while the cache is empty: the NumPy kernels answer
    and reading points never loads numba; once the compile in the background marks the cache ready, its next
    look loads them in the background (never in front), and the calls after run them."""
    clock, loads, spawned = fake
    assert not jit.prefer() and len(spawned) == 1
    assert not jit.use(1) and not jit.active() and not jit.loaded()
    jit.mark_ready()
    clock.now += jit.RECHECK
    assert not jit.active()  # a reading of points does not load them
    assert not jit.use(1)  # the load starts behind this batch, which runs on NumPy
    assert _joined() and loads == ["background"] and jit.use(1) and jit.active()


def test_a_call_decides_its_kernels_once(fake):
    """The switch while a call runs is for the calls that start after it: the call (and any call within it)
    keeps the NumPy kernels, however short or long its batches; a batch of :data:`jit.LONG` samples, with the
    cache ready, loads them in front and takes the rest of its call along."""

    @jit.deciding
    def inner():
        return jit.active(), jit.use(1)

    @jit.deciding
    def outer(switch):
        before = jit.active(), jit.use(1)
        switch()
        return before, (jit.active(), jit.use(1)), inner()

    def done():
        jit._state.loaded = True

    assert outer(done) == ((False, False), (False, False), (False, False))
    assert outer(lambda: None) == ((True, True), (True, True), (True, True))
    jit._state.loaded = False
    clock, loads, _ = fake
    jit.mark_ready()
    clock.now += jit.RECHECK
    assert outer(lambda: jit.use(jit.LONG)) == ((False, False), (True, True), (True, True))


@pytest.mark.skipif(not jit.installed(), reason="numba is not installed")
def test_a_call_in_flight_keeps_the_numpy_kernels_when_the_switch_comes(cache, monkeypatch):
    """``lw.forces`` on the NumPy kernels: the load finishes as its kinematics are solved (the first time the
    NumPy kernels report to :func:`jit.spent`); its reactions still run on NumPy, and the next call runs the
    compiled kernels (stand-ins that say so: nothing is compiled)."""
    from linkwork.kinetostatics import reactions_numba
    from linkwork.motion import kernels_numba

    class Compiled(Exception):
        pass

    def compiled(*args):
        raise Compiled

    for module in (reactions_numba, kernels_numba):
        monkeypatch.setattr(module, "compiled", lambda: True)
        monkeypatch.setattr(module, "run", compiled)
    monkeypatch.setattr(jit, "spent", lambda seconds: setattr(jit._state, "loaded", True))
    mech = lw.compile("double-cut-shears")
    forces = lw.forces(mech, steps=12)
    assert jit.loaded() and np.isfinite(forces.driving_torque).all()
    with pytest.raises(Compiled):
        lw.forces(mech, steps=12)


def test_the_numpy_kernels_report_their_time(fake, monkeypatch):
    """Calls of ``lw.forces`` on the NumPy kernels (their processor time taken here, around each call) start the
    load in the background once they have taken :func:`jit.load_cost` (here at most 0.05 s), not before (the
    kernels take part of each call's time) and not much after (they take most of it: the kinematics and the
    reactions)."""
    clock = fake[0]
    mech = lw.compile("double-cut-shears")
    lw.forces(mech, steps=36)  # imports and caches warmed, the cache not ready yet: nothing loads
    monkeypatch.setattr(jit, "LOAD_COST", 0.05)
    started: list[float] = []
    monkeypatch.setattr(jit, "_fetch", lambda: started.append(jit._state.spent))
    jit.mark_ready()
    clock.now += jit.RECHECK
    jit._state.spent = 0.0
    took, before = 0.0, 0.0  # seconds of the calls before the one that started the load
    while not started and before < 10 * jit.load_cost():
        t = time.thread_time()
        lw.forces(mech, steps=360)
        took = time.thread_time() - t
        if not _joined():
            before += took
    assert started and started[0] >= jit.load_cost()
    assert before + took >= jit.load_cost() and before < 2 * jit.load_cost()


@pytest.mark.skipif(not jit.installed(), reason="numba is not installed")
def test_the_numpy_kernels_alone_never_import_numba(tmp_path):
    """``LINKWORK_NUMBA=0``: a process that spends far more than :data:`jit.LOAD_COST` in the kernels, with the
    cache ready, never imports numba; the same process on the default settings loads it (in the background:
    nothing is compiled, the cache holds no kernel)."""
    script = (
        "import sys; import linkwork as lw; from linkwork import jit; jit.mark_ready(); jit.LOAD_COST = 0.0; "
        "m = lw.compile('double-cut-shears'); [lw.forces(m, steps=36).driving_torque for _ in range(3)]; "
        "jit._state.loader and jit._state.loader.join(); print('numba' in sys.modules, jit.loaded())"
    )
    env = {k: v for k, v in os.environ.items() if k not in ("LINKWORK_NUMBA", "NUMBA_CACHE_DIR")}
    env["LINKWORK_CACHE_DIR"] = str(tmp_path)
    out = {}
    for mode in ("0", "auto"):
        run = subprocess.run(
            [sys.executable, "-c", script], capture_output=True, text=True, env={**env, "LINKWORK_NUMBA": mode}
        )
        out[mode] = run.stdout.split()
        assert run.returncode == 0, run.stderr
    assert out == {"0": ["False", "False"], "auto": ["True", "True"]}


def test_a_command_loads_nothing_for_its_time_but_the_viewer_does(fake):
    """A process of the command line (:func:`jit.one_shot`) keeps the NumPy kernels however long they took (it
    ends before a load would pay); the viewer, which prefers them, loads them in the background all the same."""
    clock, loads, _ = fake
    jit.mark_ready()
    jit.one_shot()
    jit.spent(10 * jit.LOAD_COST)
    assert jit._state.loader is None and not jit.use(1)
    jit.prefer()
    assert _joined() and loads == ["background"] and jit.use(1)


@pytest.mark.skipif(not jit.installed(), reason="numba is not installed")
def test_the_command_line_answers_with_numpy_with_the_cache_ready(tmp_path):
    """``linkwork forces`` with the cache ready and no cost to pay for a load: numba is not imported (the
    exit would wait for a load the command has no time left to use)."""
    script = (
        "import sys, atexit; from linkwork import jit; jit.mark_ready(); jit.LOAD_COST = 0.0; "
        "atexit.register(lambda: print('numba' in sys.modules, file=sys.stderr)); "
        "from linkwork.cli.main import main; sys.argv = ['linkwork', 'forces', 'four-bar']; main()"
    )
    env = {k: v for k, v in os.environ.items() if k not in ("LINKWORK_NUMBA", "NUMBA_CACHE_DIR")}
    env["LINKWORK_CACHE_DIR"] = str(tmp_path)
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, env=env)
    assert run.returncode == 0 and run.stderr.split() == ["False"], run.stderr


@pytest.mark.skipif(not hasattr(os, "fork"), reason="no fork")
def test_a_fork_waits_for_the_load_under_way(fake, monkeypatch):
    """A process forked while the kernels load in the background (the report's second process) is forked once
    the load is done: a thread caught mid-import would leave the child an import lock it never gets."""
    done: list[bool] = []
    monkeypatch.setattr(jit, "_fetch", lambda: time.sleep(0.3) or done.append(True))
    jit.load_in_background()
    pid = os.fork()
    if pid == 0:  # the child: was the load done before the fork?
        os._exit(0 if done else 1)
    _, status = os.waitpid(pid, 0)
    assert os.waitstatus_to_exitcode(status) == 0


#: A process on the default settings that loads the compiled kernels after its first calls (no cost to pay:
#: ``LOAD_COST`` 0), then solves with them: what it read from the cache, what it compiled, and its numbers.
LONG_LIVED = """
import json, time
import numpy as np
import linkwork as lw
from linkwork import jit
from numba.core.registry import CPUDispatcher
from linkwork.kinetostatics import reactions_numba
from linkwork.motion import kernels_numba
jit._state.cost = 0.0  # a load that costs nothing: the switch comes at once
m = lw.compile("double-cut-shears")
numpy = lw.forces(m, steps=360).driving_torque
calls = 1
while not jit.loaded() and calls < 1000:
    lw.forces(m, steps=360)
    calls += 1
    time.sleep(0.01)
kernels = [f for mod in (kernels_numba, reactions_numba) for f in vars(mod).values() if isinstance(f, CPUDispatcher)]
before = sum(len(f.signatures) for f in kernels)
compiled = lw.forces(m, steps=360).driving_torque
lw.kinematics(m, steps=360).position("B")
print(json.dumps({
    "loaded": jit.loaded(), "took": jit.load_seconds(), "before": before,
    "read": sum(sum(f.stats.cache_hits.values()) for f in kernels),
    "compiled": sum(sum(f.stats.cache_misses.values()) for f in kernels),
    "error": float(np.max(np.abs(compiled - numpy)) / np.max(np.abs(numpy))),
}))
"""


@pytest.mark.numba
@pytest.mark.skipif(not jit.installed(), reason="numba is not installed")
def test_a_long_lived_process_switches_to_the_kernels_read_from_the_cache(tmp_path):
    """A cache filled by calls of ``lw.forces`` and ``lw.kinematics`` with ``LINKWORK_NUMBA=1``: a process on the
    default settings loads its kernels in the background, every one read from the cache before a call needs it
    (none compiled, none read in front of a call), and its later calls run them, with the NumPy kernels'
    numbers to rounding.  The cache is a copy of this run's (which ``linkwork warm`` filled before the lane: the
    calls then read what they need, where they would compile it for minutes), so that the test owns its copy."""
    import shutil

    env = {k: v for k, v in os.environ.items() if k not in ("LINKWORK_NUMBA", "NUMBA_CACHE_DIR")}
    env["LINKWORK_CACHE_DIR"] = str(tmp_path / "kernels")
    warmed = jit.cache_dir()
    if warmed is not None:
        shutil.copytree(warmed, tmp_path / "kernels", ignore=shutil.ignore_patterns("compiling-*", "*.log"))
    fill = (
        "import linkwork as lw; from linkwork import jit; m = lw.compile('double-cut-shears'); "
        "lw.forces(m, steps=360); lw.kinematics(m, steps=360).position('B'); jit.mark_ready()"
    )
    done = subprocess.run([sys.executable, "-c", fill], env={**env, "LINKWORK_NUMBA": "1"}, capture_output=True)
    assert done.returncode == 0, done.stderr
    run = subprocess.run([sys.executable, "-c", LONG_LIVED], env=env, capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    found = json.loads(run.stdout)
    assert found["loaded"] and found["took"] > 0
    record = (tmp_path / "kernels").glob("loads-*")
    assert float(next(record).read_text().split()[-1]) >= found["took"]  # counted whole: SciPy's part added back
    assert found["before"] == found["read"] >= 3 and found["compiled"] == 0  # read before any call needed them
    assert found["error"] < 1e-12


@pytest.mark.numba
def test_without_a_cache_the_kernels_compile_in_memory(monkeypatch):
    """No folder to write: numba's dispatchers get no cache (they would fail with "cannot cache function")."""
    pytest.importorskip("numba")
    monkeypatch.setattr(jit, "cache_dir", lambda: None)
    space: dict[str, object] = {"twice": lambda x: 2 * x}
    assert jit.jit_in_place(space, (), ("twice",))
    assert type(space["twice"]._cache).__name__ == "NullCache"  # type: ignore[attr-defined]
    assert space["twice"](21) == 42  # type: ignore[operator]


def test_every_module_of_kernels_is_in_the_key():
    """The modules that compile kernels are those whose sources key the cache (an edit of one is a new key)."""
    src = Path(jit.__file__).parent
    users = {p.relative_to(src).as_posix() for p in src.rglob("*.py") if "jit.jit_in_place(" in p.read_text()}
    assert users == set(jit.KERNEL_MODULES)


def test_every_module_whose_constants_the_kernels_take_in_is_in_the_key(cache):
    """The kernel modules import their codes, table columns and tolerances from other modules of the package; numba
    compiles those values in, and its own index does not see them: each such module keys the cache (an edit of one
    is a new key, and a new folder of numba's: :func:`jit.numba_dir`)."""
    import ast

    src = Path(jit.__file__).parent
    taken = set()
    for name in jit.KERNEL_MODULES:
        for node in ast.walk(ast.parse((src / name).read_text(encoding="utf-8"))):
            if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("linkwork."):
                module = node.module.removeprefix("linkwork.").replace(".", "/")
                if any(a.name.isupper() for a in node.names) and (src / f"{module}.py").is_file():
                    taken.add(f"{module}.py")
    assert taken <= set(jit.CONSTANT_MODULES) | set(jit.KERNEL_MODULES), taken
    assert "motion/groups.py" in taken
    before = jit.key()
    target = src / jit.CONSTANT_MODULES[0]
    stat = target.stat()
    try:
        os.utime(target, ns=(stat.st_atime_ns, stat.st_mtime_ns + 1_000_000))
        jit.key.cache_clear()
        assert jit.key() != before and jit.numba_dir() != jit.cache_dir() / f"numba-{before}"
    finally:
        os.utime(target, ns=(stat.st_atime_ns, stat.st_mtime_ns))
        jit.key.cache_clear()


def test_marking_the_cache_ready_removes_the_kernels_of_other_keys(cache):
    """The folder numba compiled other sources into is removed once these are all in; this key's stays."""
    folder = jit.cache_dir()
    assert folder is not None
    (folder / "numba-0123456789abcdef0123").mkdir()
    (folder / "numba-0123456789abcdef0123" / "kernels_numba._kernel-1.py311.nbi").write_bytes(b"old")
    mine = jit.numba_dir()
    assert mine is not None
    mine.mkdir()
    jit.mark_ready()
    assert sorted(p.name for p in folder.glob("numba-*")) == [mine.name] and jit.ready()


@pytest.mark.numba
@pytest.mark.skipif(not jit.installed(), reason="numba is not installed")
def test_warm_compiles_every_kernel_the_analyses_call():
    """After ``linkwork warm`` (:func:`linkwork.api.compile_kernels`) the analyses of every example (a cycle,
    angles given, design variants, points, forces, dynamics, a sweep) call no kernel with arrays it was not
    compiled for: a later process loads them all from the cache and compiles nothing.  And each kernel is
    compiled once, for one set of argument types: the file's geometry (read-only) and a design variant's
    (made anew) reach it alike (:func:`linkwork.jit.read_only`), as a second compile of the kinematics kernel
    costs as much as the first.  In a process of its own: the tests of the kernels themselves call them with
    arrays of other layouts, which an analysis never passes."""
    run = subprocess.run([sys.executable, "-c", _WARM_THEN_ANALYSES], capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr
    warmed, after = json.loads(run.stdout.strip().splitlines()[-1])
    assert {name: n for name, n in warmed.items() if n > 1} == {}
    assert after == warmed


#: :func:`test_warm_compiles_every_kernel_the_analyses_call`'s process: ``[signatures after warm, after the analyses]``
#: of each kernel, by name.
_WARM_THEN_ANALYSES = """
import json
import numpy as np
from numba.core.registry import CPUDispatcher
import linkwork as lw
from linkwork.api import compile_kernels
from linkwork.kinetostatics import reactions_numba
from linkwork.motion import kernels_numba

compile_kernels()
dispatchers = [f for m in (kernels_numba, reactions_numba) for f in vars(m).values() if isinstance(f, CPUDispatcher)]
counts = lambda: {d.__name__: len(d.signatures) for d in dispatchers}
warmed = counts()
for name in lw.examples.names():
    mech = lw.compile(name)
    for kin in (lw.kinematics(mech, steps=100), lw.kinematics(mech, np.linspace(0.1, 0.2, 7))):
        for point in mech.point_names:
            kin.position(point), kin.velocity(point), kin.acceleration(point)
        if mech.structure.redundant == 0:
            lw.forces(kin)
    if mech.motor_gear is not None:
        lw.dynamics(mech, steps=360)
    params = lw.parameters(mech)
    if params:
        path, value = next(iter(params.items()))
        lw.kinematics(mech, steps=90, variants={path: np.linspace(0.99, 1.01, 5) * value}).points()
print(json.dumps([warmed, counts()]))
"""


def test_the_price_of_the_switch_is_the_median_of_the_loads_measured_here(fake):
    """No load measured: :data:`jit.LOAD_COST`.  Loads recorded (each as a process measured it, whole): the median
    of the last :data:`jit.MEASURED`, read once per process; values out of :data:`jit.BELIEVED` and a damaged
    file left out.  And the switch comes once the NumPy kernels took that, not :data:`jit.LOAD_COST`."""
    clock, loads, _ = fake
    assert jit.measured_cost() == jit.LOAD_COST
    for seconds in (9.0, 0.9, 0.3, 0.5, 0.7, 0.4):  # the first falls out of the last five
        jit._remember(seconds)
    jit._state.cost = None
    assert jit.measured_cost() == pytest.approx(0.5)  # median of 0.9, 0.3, 0.5, 0.7, 0.4
    record = jit._record()
    assert record is not None and record.read_text().split() == ["0.9000", "0.3000", "0.5000", "0.7000", "0.4000"]
    record.write_text("0.6\n1000\n0.01\n", encoding="utf-8")
    jit._state.cost = None
    assert jit.measured_cost() == pytest.approx(0.6)
    record.write_text("damaged", encoding="utf-8")
    jit._state.cost = None
    assert jit.measured_cost() == jit.LOAD_COST
    record.write_text("0.2\n", encoding="utf-8")
    jit._state.cost = None
    jit.mark_ready()
    jit.spent(0.95 * jit.load_cost())
    assert jit._state.loader is None and jit.load_cost() < 0.2 + 1e-12
    jit.spent(0.06 * jit.load_cost())
    assert _joined() and loads == ["background"]


def test_what_a_process_has_imported_already_costs_its_load_nothing(cache, monkeypatch):
    """The price of the switch is the load's processor time less the parts a process has paid already: with SciPy's
    linear algebra imported (a run in time, a user's SciPy) it is :data:`jit.SUNK` of it less, with numba too less
    again; the parts add up to less than the whole (the compiler's set-up and the reads are always to pay)."""
    import sys as system

    present = dict(system.modules)
    for name in jit.SUNK:
        monkeypatch.delitem(system.modules, name, raising=False)
    assert jit.load_cost() == pytest.approx(jit.LOAD_COST)
    monkeypatch.setitem(system.modules, "scipy.linalg", present.get("scipy.linalg", object()))
    assert jit.load_cost() == pytest.approx(jit.LOAD_COST * (1 - jit.SUNK["scipy.linalg"]))
    monkeypatch.setitem(system.modules, "numba", present.get("numba", object()))
    assert jit.load_cost() == pytest.approx(jit.LOAD_COST * (1 - jit.SUNK["scipy.linalg"] - jit.SUNK["numba"]))
    assert 0 < jit.load_cost() < jit.LOAD_COST
