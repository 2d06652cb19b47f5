"""When the compiled kernels run (linkwork.jit): nobody waits for a compile they did not ask for.

A first run with an empty cache answers with the NumPy kernels (the same numbers) and starts the compile in a
process of its own, once; a cache that cannot be written leaves the NumPy kernels, said once; a ready cache
is used for long batches; ``linkwork warm`` compiles every kernel the analyses call.
"""

from __future__ import annotations

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
    monkeypatch.setattr(jit, "_preferred", [])
    forget()
    yield spawned
    forget()


@pytest.mark.skipif(not jit.installed(), reason="numba is not installed")
def test_the_lock_keeps_a_second_compile_from_starting_until_it_is_stale(cache, tmp_path):
    """A held lock: no second compile; one older than :data:`jit.STALE` (its holder died): taken over; a
    compile that failed: not started again."""
    lock = tmp_path / f"compiling-{jit.key()}"
    lock.write_text("1 0\n")
    assert jit.start_compiling() and cache == []
    jit.start_compiling.cache_clear()
    old = time.time() - jit.STALE - 10
    os.utime(lock, (old, old))
    assert jit.start_compiling() and cache == [lock] and lock.read_text().split()[0] == str(os.getpid())
    jit.start_compiling.cache_clear()
    jit.release(failed=True)
    assert not lock.exists() and not jit.start_compiling() and cache == [lock]


@pytest.mark.skipif(not jit.installed(), reason="numba is not installed")
def test_a_ready_cache_serves_long_batches_only(cache, monkeypatch):
    """Ready: a batch of :data:`jit.LONG` samples loads the compiled kernels, a short one does not (the NumPy
    kernels answer before numba would have loaded); not ready: neither, and the compile starts."""
    monkeypatch.setattr(jit, "_loaded", [])
    assert not jit.use(jit.LONG) and len(cache) == 1
    jit.mark_ready()
    assert jit.ready()
    assert not jit.use(jit.LONG - 1) and not jit.loaded()
    assert jit.use(jit.LONG) and jit.loaded() and jit.use(1)
    monkeypatch.setenv("LINKWORK_NUMBA", "0")
    assert not jit.use(jit.LONG)


@pytest.mark.skipif(not jit.installed(), reason="numba is not installed")
def test_a_process_that_prefers_the_kernels_switches_when_the_compile_is_done(cache, monkeypatch):
    """The viewer asks for the kernels (:func:`jit.prefer`) while the cache is empty: the NumPy kernels answer
    and reading points never loads numba; once the compile in the background marks the cache ready, its next
    batch, however short, loads them."""
    monkeypatch.setattr(jit, "_loaded", [])
    assert not jit.prefer() and len(cache) == 1
    assert not jit.use(1) and not jit.active() and not jit.loaded()
    jit.mark_ready()
    assert not jit.active()  # a reading of points does not load them
    assert jit.use(1) and jit.loaded() and jit.active()


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


@pytest.mark.skipif(not jit.installed(), reason="numba is not installed")
def test_warm_compiles_every_kernel_the_analyses_call():
    """After ``linkwork warm`` (:func:`linkwork.api.compile_kernels`) the analyses of every example (a cycle,
    angles given, design variants, points, forces, dynamics, a sweep) call no kernel with arrays it was not
    compiled for: a later process loads them all from the cache and compiles nothing."""
    from numba.core.registry import CPUDispatcher

    from linkwork.api import compile_kernels
    from linkwork.kinetostatics import reactions_numba
    from linkwork.motion import kernels_numba

    compile_kernels()
    twins = (kernels_numba, reactions_numba)
    dispatchers = [f for m in twins for f in vars(m).values() if isinstance(f, CPUDispatcher)]
    before = {d: len(d.signatures) for d in dispatchers}
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
    assert {d: len(d.signatures) for d in dispatchers} == before
